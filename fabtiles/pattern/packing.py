"""Circle packings filled with motifs: the paper's tile operation (see ``docs/tile-operation.md``).

Pure numpy. A packing knows where its circles are and which motif fills each;
it hands out circle centres/radii and the centre-line segments of every motif
placed in a window. Stroking, clipping and files belong to later layers.

Two packings share one base class and differ only in their lattice:

* :class:`HexPacking` -- big circles of radius ``R`` at ``i*(2R, 0) + j*(R, sqrt(3) R)``,
  a surrounded circle of radius ``R (2/sqrt(3) - 1)`` at the centroid of every up
  and every down triangle (``p + (R, +-R/sqrt(3))`` for each lattice point ``p``).
* :class:`SquarePacking` -- big circles at ``i*(2R, 0) + j*(0, 2R)``, a gap circle of
  radius ``(sqrt(2) - 1) R`` at every cell centre ``p + (R, R)``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import KW_ONLY, dataclass
from typing import ClassVar, cast

import numpy as np

from ..core.errors import LimitError, ParameterError
from ..core.schema import GAP_MOTIF, register_check
from ..core.validate import check_float
from .star import Star

MAX_CIRCLES_IN_WINDOW = 2_000_000
"""Refuse windows holding more circles than this (a unit slip such as metres for mm)."""


def default_gap_motif() -> Star:
    """The default motif of the gap circles: ``Star(n=6, radii=(0.5, 1.0))`` (paper section 6).

    >>> default_gap_motif()
    Star(n=6, radii=(0.5, 1))
    """
    return Star(**GAP_MOTIF)  # the schema's default of [packing] gap_motif


def chord_count(radius: float, *, tolerance: float = 0.005, multiple: int = 24) -> int:
    """Chords on a circle of ``radius`` for sagitta <= ``tolerance``, rounded up to a multiple of ``multiple``.

    >>> chord_count(15.0), chord_count(1.0)
    (144, 48)
    """
    ratio = min(1.0, tolerance / radius)
    k = max(multiple, math.ceil(math.pi / math.acos(1.0 - ratio)))
    return multiple * math.ceil(k / multiple)


def circle_segments(centres, radii, *, tolerance: float = 0.005, multiple: int = 24) -> np.ndarray:
    """Circles flattened to chords, ``(k, 2, 2)``, with sagitta <= ``tolerance``.

    Each circle gets the same number of chords per size (:func:`chord_count`),
    a multiple of ``multiple`` starting at angle 0, so the tangency points of
    the hex and square packings (multiples of 30 and 45 degrees) are vertices.
    The chords of one circle are consecutive, counter-clockwise.

    >>> seg = circle_segments([[0.0, 0.0]], [10.0])
    >>> seg.shape[0] % 24, round(float(np.hypot(*seg[:, 0].T).max()), 9)
    (0, 10.0)
    """
    centres = np.asarray(centres, dtype=float).reshape(-1, 2)
    radii = np.broadcast_to(np.asarray(radii, dtype=float), (len(centres),))
    out = []
    for r in np.unique(radii):
        sel = centres[radii == r]
        k = chord_count(r, tolerance=tolerance, multiple=multiple)
        t = np.linspace(0.0, 2.0 * math.pi, k + 1)
        ring = r * np.stack([np.cos(t), np.sin(t)], axis=-1)
        one = np.stack([ring[:-1], ring[1:]], axis=1)  # (k, 2, 2)
        out.append((one[None] + sel[:, None, None, :]).reshape(-1, 2, 2))
    return np.concatenate(out) if out else np.empty((0, 2, 2))


@dataclass(frozen=True, slots=True, repr=False)
class Packing:
    """Shared machinery of the packings; a subclass only defines its lattice.

    Subclasses set ``kind``, ``gap_ratio`` (gap circle radius / R) and implement
    :meth:`_basis` (two lattice vectors in units of R) and :meth:`_gap_offsets`
    (gap circle centres relative to each lattice point, units of R). A packing is a
    frozen value: change it with :meth:`replace`.
    """

    kind: ClassVar[str] = ""
    gap_ratio: ClassVar[float] = 0.0

    radius: float
    """Radius R of the big circles, mm."""
    motif: Star
    """Motif of the big circles."""
    gap_motif: Star | None = None
    """Motif of the gap circles (None given: :func:`default_gap_motif`, set when the packing is made)."""
    _: KW_ONLY
    outline_circles: bool = False
    """Whether the circles are stroked."""
    fill: float = 1.0
    """Motif extent / circle radius."""

    def __post_init__(self) -> None:
        init = object.__setattr__  # the frozen dataclass's own way to set a field in __post_init__
        init(self, "radius", check_float("radius", self.radius, low=0, low_open=True))
        if not isinstance(self.motif, Star):
            raise ParameterError(f"motif must be a Star, got {self.motif!r}", param="motif")
        if self.gap_motif is None:
            init(self, "gap_motif", default_gap_motif())
        if not isinstance(self.gap_motif, Star):
            raise ParameterError(
                f"gap_motif must be a Star or None (the default), got {self.gap_motif!r}", param="gap_motif"
            )
        if not isinstance(self.outline_circles, bool):
            raise ParameterError(
                f"outline_circles must be true or false, got {self.outline_circles!r}", param="outline_circles"
            )
        init(self, "fill", check_float("fill", self.fill, low=0, high=1, low_open=True))

    # -- lattice ------------------------------------------------------------
    def _basis(self) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def _gap_offsets(self) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def gap_radius(self) -> float:
        """Radius of the gap (surrounded) circles, mm."""
        return self.gap_ratio * self.radius

    @property
    def period(self) -> tuple[float, float]:
        """Smallest rectangular period ``(px, py)`` of the packing, mm."""
        raise NotImplementedError  # pragma: no cover - abstract

    def lattice_points(self, window) -> np.ndarray:
        """Lattice points (big circle centres) whose circle may meet ``window``.

        A circle is kept when its bounding box overlaps
        the window: a superset of the circles that meet it, never fewer.

        ``window`` is ``(xmin, ymin, xmax, ymax)`` in the packing's own frame
        (lattice point (0, 0) at the origin). Returns an ``(m, 2)`` array.
        """
        return self._points(window, np.zeros((1, 2)), self.radius)

    def gap_centres(self, window) -> np.ndarray:
        """Centres of the gap circles that may meet ``window``, ``(m, 2)`` (as :meth:`lattice_points`)."""
        return self._points(window, self._gap_offsets() * self.radius, self.gap_radius)

    def circles(self, window) -> tuple[np.ndarray, np.ndarray]:
        """Centres ``(m, 2)`` and radii ``(m,)`` of every circle that may meet ``window``.

        Big circles first, then gap circles.

        >>> p = HexPacking(radius=10, motif=Star(n=8, radii=(1, 2)))
        >>> c, r = p.circles((0, 0, 12, 8))
        >>> c.round(2).tolist(), r.round(2).tolist()
        ([[0.0, 0.0], [20.0, 0.0], [-10.0, 17.32], [10.0, 17.32], [10.0, 5.77]], [10.0, 10.0, 10.0, 10.0, 1.55])
        """
        big = self.lattice_points(window)
        gap = self.gap_centres(window)
        radii = np.concatenate([np.full(len(big), self.radius), np.full(len(gap), self.gap_radius)])
        return np.concatenate([big, gap]), radii

    def _points(self, window, offsets, reach) -> np.ndarray:
        x0, y0, x1, y1 = check_window(window)
        m = reach * max(self.fill, 1.0) * (1 + 1e-9)
        x0, y0, x1, y1 = x0 - m, y0 - m, x1 + m, y1 + m
        basis = self._basis() * self.radius  # rows are lattice vectors
        inv = np.linalg.inv(basis.T)
        corners = np.array([[x0, y0], [x1, y0], [x0, y1], [x1, y1]])
        lo = np.full(2, np.inf)
        hi = np.full(2, -np.inf)
        for off in offsets:
            ij = (corners - off) @ inv.T
            lo = np.minimum(lo, np.floor(ij.min(axis=0)))
            hi = np.maximum(hi, np.ceil(ij.max(axis=0)))
        count = float(np.prod(hi - lo + 1)) * len(offsets)
        if count > MAX_CIRCLES_IN_WINDOW:
            raise LimitError(
                f"the window holds about {count:.3g} circles, more than the limit of "
                f"{MAX_CIRCLES_IN_WINDOW}; use a larger radius (got {self.radius:g} mm) or a smaller tile"
            )
        i = np.arange(lo[0], hi[0] + 1)
        j = np.arange(lo[1], hi[1] + 1)
        jj, ii = np.meshgrid(j, i, indexing="ij")
        lattice = ii.reshape(-1, 1) * basis[0] + jj.reshape(-1, 1) * basis[1]
        pts = (lattice[None, :, :] + offsets[:, None, :]).reshape(-1, 2)
        keep = (pts[:, 0] >= x0) & (pts[:, 0] <= x1) & (pts[:, 1] >= y0) & (pts[:, 1] <= y1)
        pts = pts[keep]
        # Deterministic order: rows bottom to top, left to right.
        order = np.lexsort((np.round(pts[:, 0], 9), np.round(pts[:, 1], 9)))
        return pts[order]

    # -- motifs ---------------------------------------------------------------
    def placed_motif(self, which: str = "big") -> np.ndarray:
        """One motif scaled for its circle and centred at (0, 0), ``(k, 2, 2)`` in mm.

        ``which`` is ``"big"`` or ``"gap"``. The motif in a circle of radius ``c`` is
        scaled by ``c * fill / extent``, so its extent is ``c * fill``.

        >>> p = HexPacking(radius=12.5, motif=Star.preset("table3-3"))
        >>> round(float(np.hypot(*p.placed_motif().reshape(-1, 2).T).max()), 9)
        12.5
        """
        if which not in ("big", "gap"):
            raise ParameterError(f"{which!r} is not a valid motif, must be one of: big, gap", param="which")
        return _placed_motif(self, which).copy()  # the cache is never handed out (a copy is)

    def segments(self, window) -> np.ndarray:
        """Centre-lines of every motif whose circle meets ``window``, ``(k, 2, 2)`` mm.

        Each motif's segments are computed once per circle size and translated to
        every centre by broadcasting. With ``outline_circles`` the circles are
        added as chords (sagitta <= 0.005 mm, see :func:`circle_segments`), after
        the motifs.

        >>> p = HexPacking(radius=10, motif=Star(n=8, radii=(1, 2)))
        >>> p.segments((0, 0, 12, 8)).shape  # 4 big motifs (16 each) + 1 gap motif (12)
        (76, 2, 2)
        """
        parts = [self.motif_segments(window)]
        if self.outline_circles:
            parts.append(circle_segments(*self.circles(window)))
        return np.concatenate(parts)

    def motif_segments(self, window) -> np.ndarray:
        """The motifs' centre-lines alone (without the outline circles), ``(k, 2, 2)`` mm.

        >>> p = HexPacking(radius=10, motif=Star(n=8, radii=(1, 2)), outline_circles=True)
        >>> len(p.motif_segments((0, 0, 12, 8)))
        76
        """
        parts = []
        for which, centres in (("big", self.lattice_points(window)), ("gap", self.gap_centres(window))):
            unit = self.placed_motif(which)
            parts.append((unit[None] + centres[:, None, None, :]).reshape(-1, 2, 2))
        return np.concatenate(parts)

    def params(self) -> dict:
        """The constructor arguments."""
        return dict(
            radius=self.radius,
            motif=self.motif,
            gap_motif=self.gap_motif,
            outline_circles=self.outline_circles,
            fill=self.fill,
        )

    def replace(self, **changes):
        """A copy with some parameters changed (validated again).

        >>> HexPacking(radius=10, motif=Star(n=8, radii=(1, 2))).replace(radius=5).radius
        5.0
        """
        return type(self)(**{**self.params(), **changes})

    def __repr__(self) -> str:
        extra = ", outline_circles=True" if self.outline_circles else ""
        extra += f", fill={self.fill:g}" if self.fill != 1.0 else ""
        return (
            f"{type(self).__name__}(radius={self.radius:g}, motif={self.motif!r}, gap_motif={self.gap_motif!r}{extra})"
        )


@dataclass(frozen=True, slots=True, repr=False)
class HexPacking(Packing):
    """Hexagonal packing of tangent circles with a motif in each (paper section 5).

    Parameters
    ----------
    radius : float
        Radius ``R`` of the big circles, mm (> 0).
    motif : Star
        Motif of the big circles.
    gap_motif : Star or None
        Motif of the surrounded circles (radius ``R (2/sqrt(3) - 1)``); None gives
        the default ``Star(n=6, radii=(0.5, 1.0))``.
    outline_circles : bool, keyword-only
        Also stroke the packing circles themselves.
    fill : float, keyword-only
        Motif extent as a fraction of its circle's radius, in (0, 1].

    Examples
    --------
    >>> p = HexPacking(radius=12.5, motif=Star.preset("table3-3"))
    >>> round(p.gap_radius, 4), tuple(round(v, 4) for v in p.period)
    (1.9338, (25.0, 43.3013))
    """

    kind = "hex"
    gap_ratio = 2.0 / math.sqrt(3.0) - 1.0

    def _basis(self):
        return np.array([[2.0, 0.0], [1.0, math.sqrt(3.0)]])

    def _gap_offsets(self):
        return np.array([[1.0, 1.0 / math.sqrt(3.0)], [1.0, -1.0 / math.sqrt(3.0)]])

    @property
    def period(self):
        return (2.0 * self.radius, 2.0 * math.sqrt(3.0) * self.radius)


@dataclass(frozen=True, slots=True, repr=False)
class SquarePacking(Packing):
    """Square packing of tangent circles, a gap circle in each cell (same parameters as
    :class:`HexPacking`; gap circle radius ``(sqrt(2) - 1) R``).

    Parameters
    ----------
    radius, motif, gap_motif, outline_circles, fill
        As for :class:`HexPacking`; the gap motif fills the circle in the middle of each
        square of four big circles.

    Examples
    --------
    >>> p = SquarePacking(radius=10, motif=Star.preset("table1-part1"))
    >>> round(p.gap_radius, 4), p.period
    (4.1421, (20.0, 20.0))
    """

    kind = "square"
    gap_ratio = math.sqrt(2.0) - 1.0

    def _basis(self):
        return np.array([[2.0, 0.0], [0.0, 2.0]])

    def _gap_offsets(self):
        return np.array([[1.0, 1.0]])

    @property
    def period(self):
        return (2.0 * self.radius, 2.0 * self.radius)


PACKINGS = {"hex": HexPacking, "square": SquarePacking}
"""Packing kind name -> class."""


@functools.lru_cache(maxsize=64)
def _placed_motif(packing: Packing, which: str) -> np.ndarray:
    """One motif of a packing placed for its circle (read-only), once per distinct packing."""
    if which == "big":
        star, c = packing.motif, packing.radius
    else:
        star, c = cast(Star, packing.gap_motif), packing.gap_radius  # never None once the packing is made
    unit = star.segments() * (c * packing.fill / star.extent)
    unit.flags.writeable = False
    return unit


def check_window(window) -> tuple[float, float, float, float]:
    """``window`` as four floats ``(xmin, ymin, xmax, ymax)``, finite with min <= max; else a
    :class:`~fabtiles.ParameterError` naming it (every packing's window is checked here).

    >>> check_window((0, 0, 10, 5))
    (0.0, 0.0, 10.0, 5.0)
    """
    try:
        x0, y0, x1, y1 = (float(v) for v in window)
    except (TypeError, ValueError):
        raise ParameterError(f"window must be (xmin, ymin, xmax, ymax), got {window!r}", param="window") from None
    if not all(math.isfinite(v) for v in (x0, y0, x1, y1)) or x1 < x0 or y1 < y0:
        raise ParameterError(
            f"window must be finite (xmin, ymin, xmax, ymax) with min <= max, got {window!r}", param="window"
        )
    return x0, y0, x1, y1


# The schema names no module above it: the values and checks of its keys are registered from here.
register_check(Packing, "packing.radius", "packing.fill")
