"""Stars and rosettes drawn from n points on S concentric circles (paper sections 3-4)."""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import KW_ONLY, dataclass

import numpy as np

from ..core.errors import ParameterError, did_you_mean
from ..core.schema import register_check
from ..core.validate import check_float, check_float_seq, check_int
from .presets import PRESETS

MAX_N = 120
"""Largest number of points per circle; more gives strokes thinner than any laser or nozzle."""

MAX_CIRCLES = 24
"""Largest number of concentric circles S."""


@dataclass(frozen=True, slots=True, repr=False)
class Star:
    """A star or rosette: ``n`` points on each of ``len(radii)`` concentric circles.

    Circle ``w`` (1-based) holds points at angles
    ``rotation + (w - 1) * 180 / n + (i - 1) * 360 / n`` for ``i = 1..n``. Adjacent
    circles are joined point to point; when ``special`` names circle ``w + 1``, two
    special points at radius ``r(w+1) - spr`` and angles ``+-alpha`` around each
    point of that circle turn the star into a rosette (see ``docs/construction.md``).

    Parameters
    ----------
    n : int
        Points on each circle, 3 to 120.
    radii : sequence of float
        Radius of each circle (2 to 24 of them, each > 0, in any order).
    alpha : float, keyword-only
        Angular offset of the two special points, degrees.
    spr : float, keyword-only
        The special points lie at radius ``r(special) - spr`` (may be negative).
    special : int or None, keyword-only
        1-based index 2..S of the special circle, or None for a plain star.
    rotation : float, keyword-only
        Degrees added to every angle.

    Examples
    --------
    >>> star = Star(n=8, radii=(51, 70, 172))
    >>> star.segments().shape
    (32, 2, 2)
    >>> round(star.extent, 6)
    172.0
    >>> Star(n=9, radii=(93, 225), alpha=48, spr=-68, special=2).segments().shape
    (36, 2, 2)

    A Star is a frozen value (equal stars share their cached segments): change it with
    :meth:`replace`.

    >>> star.n = 9
    Traceback (most recent call last):
    ...
    dataclasses.FrozenInstanceError: cannot assign to field 'n'
    """

    n: int
    """Points on each circle."""
    radii: Sequence[float]
    """Radius of each circle (a tuple)."""
    _: KW_ONLY
    alpha: float = 0.0
    """Angular offset of the special points, degrees."""
    spr: float = 0.0
    """The special points lie at r(special) - spr."""
    special: int | None = None
    """1-based special circle, or None."""
    rotation: float = 0.0
    """Degrees added to every angle."""

    def __post_init__(self) -> None:
        # Each field checked and normalised (radii to a tuple of floats) before the Star is used.
        init = object.__setattr__  # the frozen dataclass's own way to set a field in __post_init__
        init(self, "n", check_int("n", self.n, low=3, high=MAX_N))
        radii = check_float_seq("radii", self.radii, min_len=2, max_len=MAX_CIRCLES, low=0, low_open=True)
        init(self, "radii", radii)
        init(self, "alpha", check_float("alpha", self.alpha))
        init(self, "spr", check_float("spr", self.spr))
        special = self.special
        init(self, "special", None if special is None else check_int("special", special, low=2, high=len(radii)))
        init(self, "rotation", check_float("rotation", self.rotation))

    # -- construction -------------------------------------------------------
    @classmethod
    def preset(cls, name: str, *, rotation: float = 0.0) -> Star:
        """The motif of one row of the paper's tables.

        Parameters
        ----------
        name : str
            A preset's name (:meth:`presets`; ``fabtiles presets`` lists them with their values).
        rotation : float, keyword-only
            Added to every angle, degrees.

        Returns
        -------
        Star
            The row's motif, its radii in the paper's units (a packing scales it to its circles).

        Raises
        ------
        ParameterError
            An unknown name; the message suggests the nearest and lists them all.

        Examples
        --------
        >>> Star.preset("table1-part1").n
        8
        >>> Star.preset("table3-33")
        Traceback (most recent call last):
        ...
        fabtiles.core.errors.ParameterError: preset 'table3-33' is unknown; did you mean 'table3-3'? (presets: table1-part1, table1-part2, table2-left, table2-right, table3-1, table3-2, table3-3; `fabtiles presets` lists them)
        """  # noqa: E501 - a doctest's lines are as Python prints them
        if not isinstance(name, str) or name not in PRESETS:
            hint = did_you_mean(name, PRESETS)
            raise ParameterError(
                f"preset {name!r} is unknown{'; ' + hint if hint else ''} (presets: {', '.join(PRESETS)}; "
                "`fabtiles presets` lists them)",
                param="preset",
            )
        return cls(**PRESETS[name], rotation=rotation)

    @staticmethod
    def presets() -> tuple[str, ...]:
        """Names of the presets, in the paper's order.

        >>> Star.presets()[0]
        'table1-part1'
        """
        return tuple(PRESETS)

    def params(self) -> dict:
        """The constructor arguments, so ``Star(**star.params())`` rebuilds the motif."""
        return dict(
            n=self.n,
            radii=self.radii,
            alpha=self.alpha,
            spr=self.spr,
            special=self.special,
            rotation=self.rotation,
        )

    def replace(self, **changes) -> Star:
        """A copy with some parameters changed (validated again).

        >>> Star(n=8, radii=(1, 2)).replace(rotation=22.5).rotation
        22.5
        """
        return Star(**{**self.params(), **changes})

    def __repr__(self) -> str:
        extra = ""
        if self.special is not None:
            extra = f", alpha={self.alpha:g}, spr={self.spr:g}, special={self.special}"
        if self.rotation:
            extra += f", rotation={self.rotation:g}"
        radii = ", ".join(f"{r:g}" for r in self.radii)
        return f"Star(n={self.n}, radii=({radii}){extra})"

    # -- geometry -----------------------------------------------------------
    def points(self) -> np.ndarray:
        """The marked points ``P(w, i)``: array of shape ``(S, n, 2)``.

        >>> Star(n=4, radii=(1, 2)).points()[1, 0].round(6).tolist()
        [1.414214, 1.414214]
        """
        s = len(self.radii)
        w = np.arange(s)[:, None]
        i = np.arange(self.n)[None, :]
        theta = np.radians(self.rotation + w * 180.0 / self.n + i * 360.0 / self.n)
        r = np.asarray(self.radii)[:, None]
        return np.stack([r * np.cos(theta), r * np.sin(theta)], axis=-1)

    def segments(self) -> np.ndarray:
        """Centre-lines of the motif, float array ``(k, 2, 2)``, centred at (0, 0).

        ``k = n * (2 * (S - 1) + 2 * [special given])`` unless segments degenerate
        (zero length) or repeat, which are dropped or merged. The returned array is
        a fresh copy.
        """
        return self._segments.copy()

    @property
    def _segments(self) -> np.ndarray:
        """The cached segments (read-only): never handed out, a copy is."""
        return _segments_of(self)

    @property
    def extent(self) -> float:
        """Largest distance from the centre of any segment endpoint."""
        seg = self.segments()
        return float(np.sqrt((seg**2).sum(axis=-1)).max())

    def _raw_segments(self) -> np.ndarray:
        n = self.n
        pts = self.points()
        nxt = np.roll(np.arange(n), -1)  # j = i mod n + 1, 0-based
        out = []
        for w in range(len(self.radii) - 1):  # 0-based: circle w -> w + 1
            a, b, t = pts[w], pts[w][nxt], pts[w + 1]
            if self.special is not None and w + 2 == self.special:
                theta = np.radians(self.rotation + (w + 1) * 180.0 / n + np.arange(n) * 360.0 / n)
                rs = self.radii[w + 1] - self.spr
                da = np.radians(self.alpha)
                left = rs * np.stack([np.cos(theta - da), np.sin(theta - da)], axis=-1)
                right = rs * np.stack([np.cos(theta + da), np.sin(theta + da)], axis=-1)
                out += [np.stack(p, axis=1) for p in ((a, left), (b, right), (left, t), (right, t))]
            else:
                out += [np.stack((a, t), axis=1), np.stack((b, t), axis=1)]
        # Interleave so the segments of one point i stay together (stable, readable output).
        return np.stack(out, axis=1).reshape(-1, 2, 2)


@functools.lru_cache(maxsize=64)
def _segments_of(star: Star) -> np.ndarray:
    """A star's segments, computed once per distinct star (stars are values: equal ones share them)."""
    seg = _dedupe(star._raw_segments())
    seg.flags.writeable = False
    return seg


def _dedupe(seg: np.ndarray) -> np.ndarray:
    """Drop zero-length segments and merge exact duplicates (either direction)."""
    scale = max(1.0, float(np.abs(seg).max()))
    tol = 1e-9 * scale
    length = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1)
    seg = seg[length > tol]
    # Canonical direction: lexicographically smaller endpoint first.
    a, b = seg[:, 0], seg[:, 1]
    swap = (a[:, 0] > b[:, 0] + tol) | ((np.abs(a[:, 0] - b[:, 0]) <= tol) & (a[:, 1] > b[:, 1]))
    canon = np.where(swap[:, None, None], seg[:, ::-1], seg)
    key = np.round(canon.reshape(len(canon), 4) / (tol * 100)).astype(np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    return np.ascontiguousarray(seg[np.sort(first)], dtype=float)


# The schema names no module above it: the values and checks of its keys are registered from here.
register_check(Star, "motif.n", "motif.radii", "motif.alpha", "motif.spr", "motif.special", "motif.rotation")
