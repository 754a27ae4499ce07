"""Girih tiles: the five Lu-Steinhardt tiles, their strapwork and periodic patterns of them (``docs/girih.md``).

Pure numpy. The five tiles (P. J. Lu and P. J. Steinhardt, "Decagonal and quasi-crystalline
tilings in medieval Islamic architecture", Science 315, 1106, 2007, Fig. 1A) have equal edges
and every angle a multiple of 36 degrees: the regular decagon and pentagon, the elongated
hexagon (72, 144, 144, 72, 144, 144), the bowtie (72, 72, 216, 72, 72, 216) and the rhombus
(72, 108). Each edge's midpoint is crossed by two decoration lines at 54 degrees to the edge
(72 degrees to each other), so the lines of two tiles sharing an edge continue each other.

Inside a tile every line runs on until it meets another, and two lines that meet each other
first are a pair: a tile's lines are paired in order of the distance they run, shortest first.
That gives the figures of Lu and Steinhardt's Fig. 1A: on the decagon and the pentagon the lines
of two edges beside a corner meet on its bisector (a 10- and a 5-pointed star, their points at
the midpoints); beside a 72-degree corner the two lines are one straight line from midpoint to
midpoint; in the bowtie the lines leaning to a 216-degree corner meet the lines of the far edge
of their own half first, so each half holds its own closed figure.

A pattern is a lattice and the tiles of one cell (:data:`PATTERNS`), so a tile of it repeats
seamlessly and the pipeline takes its strapwork like any packing's centre-lines.

>>> seg = strapwork(tile_corners("decagon"))
>>> seg.shape, round(float(np.hypot(*(seg[0, 1] - seg[0, 0]))), 4)
((20, 2, 2), 0.5878)
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import KW_ONLY, dataclass
from types import MappingProxyType

import numpy as np

from ..core.errors import LimitError, ParameterError, did_you_mean
from ..core.schema import register_check, register_choices
from ..core.validate import check_float
from .packing import MAX_CIRCLES_IN_WINDOW, check_window

TILES: Mapping[str, tuple[int, ...]] = MappingProxyType(
    {
        "decagon": (144,) * 10,
        "pentagon": (108,) * 5,
        "hexagon": (72, 144, 144, 72, 144, 144),
        "bowtie": (72, 72, 216, 72, 72, 216),
        "rhombus": (72, 108, 72, 108),
    }
)
"""Tile name -> its interior angles in degrees, corner by corner counter-clockwise (edge 1 each)."""

CONTACT_ANGLE = 54.0
"""The decoration lines' angle to the edge whose midpoint they cross, degrees."""

_EPS = 1e-9


def tile_corners(kind: str, *, edge: float = 1.0, start=(0.0, 0.0), heading: float = 0.0) -> np.ndarray:
    """The corners ``(k, 2)`` of a girih tile, counter-clockwise: corner 0 at ``start``, its first
    edge leaving at ``heading`` degrees, each edge ``edge`` long.

    >>> tile_corners("rhombus", heading=-36).round(4).tolist()
    [[0.0, 0.0], [0.809, -0.5878], [1.618, 0.0], [0.809, 0.5878]]
    """
    angles = TILES[check_tile(kind)]
    points = [np.asarray(start, dtype=float)]
    h = math.radians(heading)
    for i in range(len(angles) - 1):
        points.append(points[-1] + edge * np.array([math.cos(h), math.sin(h)]))
        h += math.radians(180 - angles[i + 1])  # turn left by the exterior angle (right at a reflex corner)
    return np.array(points)


def check_tile(kind) -> str:
    """``kind`` checked against the five tiles, with a "did you mean".

    >>> check_tile("bowtie")
    'bowtie'
    >>> check_tile("bow-tie")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: 'bow-tie' is not a girih tile (did you mean 'bowtie'?), must be one of: decagon, pentagon, hexagon, bowtie, rhombus
    """  # noqa: E501 - a doctest's lines are as Python prints them
    if kind not in TILES:
        hint = did_you_mean(kind, TILES)
        raise ParameterError(
            f"{kind!r} is not a girih tile{f' ({hint})' if hint else ''}, must be one of: {', '.join(TILES)}",
            param="tile",
        )
    return kind


def _rays(corners: np.ndarray):
    """Each edge's two decoration lines: ``(starts, directions)``, ``(2k, 2)`` each; row ``2i`` leans
    to edge i's first corner, row ``2i + 1`` to its second."""
    nxt = np.roll(corners, -1, axis=0)
    along = nxt - corners
    along /= np.hypot(*along.T)[:, None]
    inward = np.stack([-along[:, 1], along[:, 0]], axis=1)  # left of a counter-clockwise edge
    c, s = math.cos(math.radians(CONTACT_ANGLE)), math.sin(math.radians(CONTACT_ANGLE))
    mids = (corners + nxt) / 2
    starts = np.repeat(mids, 2, axis=0)
    directions = np.empty_like(starts)
    directions[0::2] = -c * along + s * inward
    directions[1::2] = c * along + s * inward
    return starts, directions


def _meetings(starts: np.ndarray, directions: np.ndarray) -> list:
    """Every two lines of different edges that meet ahead of both: ``(distance run, i, j, point)``;
    two lines on one straight line facing each other meet half way."""
    out = []
    n = len(starts)
    for i in range(n):
        for j in range(i + 1, n):
            if i // 2 == j // 2:
                continue
            d = starts[j] - starts[i]
            det = directions[i, 0] * -directions[j, 1] + directions[j, 0] * directions[i, 1]
            if abs(det) < _EPS:
                on_line = abs(directions[i, 0] * d[1] - directions[i, 1] * d[0]) < _EPS
                if on_line and d @ directions[i] > 0 and d @ directions[j] < 0:
                    out.append((float(np.hypot(*d)) / 2, i, j, (starts[i] + starts[j]) / 2))
                continue
            ti = (d[0] * -directions[j, 1] + directions[j, 0] * d[1]) / det
            tj = (directions[i, 0] * d[1] - directions[i, 1] * d[0]) / det
            if ti > _EPS and tj > _EPS:
                out.append((float(max(ti, tj)), i, j, starts[i] + ti * directions[i]))
    return out


def strapwork(corners) -> np.ndarray:
    """The decoration lines of one tile, ``(m, 2, 2)``: each from an edge's midpoint to where it meets
    its partner (two lines on one straight line: one segment from midpoint to midpoint).

    The lines are paired in order of the distance they run before meeting, shortest first, so
    each line stops at the first line that stops it too.

    >>> strapwork(tile_corners("rhombus", heading=-36)).round(4).shape
    (6, 2, 2)
    """
    corners = np.asarray(corners, dtype=float)
    starts, directions = _rays(corners)
    used: set[int] = set()
    segments = []
    for _, i, j, point in sorted(_meetings(starts, directions), key=lambda m: (round(m[0], 9), m[1], m[2])):
        if i in used or j in used:
            continue
        used |= {i, j}
        if np.allclose(point, (starts[i] + starts[j]) / 2) and abs(_cross(directions[i], directions[j])) < _EPS:
            segments.append([starts[i], starts[j]])
        else:
            segments += [[starts[i], point], [starts[j], point]]
    assert len(used) == len(starts), "every girih line meets a partner"
    return np.array(segments, dtype=float)


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


# -- periodic patterns ------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class GirihCell:
    """One cell of a periodic girih pattern, edge 1: the lattice (rows) and its tiles' names and corners."""

    lattice: np.ndarray
    kinds: tuple[str, ...]
    corners: tuple[np.ndarray, ...]

    @property
    def period(self) -> tuple[float, float]:
        """The rectangular period ``(px, py)``: every cell is laid so that ``v1 + v2`` lies along x and
        ``v1 - v2`` along y (their lattices are centred rectangular)."""
        v1, v2 = self.lattice
        return float(abs((v1 + v2)[0])), float(abs((v1 - v2)[1]))


def _decagon_bowtie() -> GirihCell:
    """Decagons sharing edges with four neighbours on a rhombic lattice (sides two inradii, 72 degrees
    apart); the gap between four decagons is one bowtie."""
    r = 1 / (2 * math.tan(math.pi / 10))
    big = 1 / (2 * math.sin(math.pi / 10))
    turn = np.radians(18 + 36 * np.arange(10))
    decagon = big * np.stack([np.cos(turn), np.sin(turn)], axis=1)
    lattice = (
        2
        * r
        * np.array([[math.cos(-math.pi / 5), math.sin(-math.pi / 5)], [math.cos(math.pi / 5), math.sin(math.pi / 5)]])
    )
    bowtie = tile_corners("bowtie", start=decagon[0], heading=-90)
    return GirihCell(lattice=lattice, kinds=("decagon", "bowtie"), corners=(decagon, bowtie))


def _hexagons() -> GirihCell:
    """Elongated hexagons by translation: the hexagon is centrally symmetric, so two sums of its
    successive edges are a lattice it tiles."""
    hexagon = tile_corners("hexagon", heading=-36)
    e = np.diff(hexagon, axis=0)
    hexagon = hexagon - hexagon.mean(axis=0)
    return GirihCell(lattice=np.array([e[0] + e[1], e[1] + e[2]]), kinds=("hexagon",), corners=(hexagon,))


def _rhombi() -> GirihCell:
    """72-degree rhombi by translation along their two edges."""
    rhombus = tile_corners("rhombus", heading=-36)
    lattice = np.array([rhombus[1] - rhombus[0], rhombus[3] - rhombus[0]])
    return GirihCell(lattice=lattice, kinds=("rhombus",), corners=(rhombus - rhombus.mean(axis=0),))


_CELLS = {"decagon-bowtie": _decagon_bowtie, "hexagons": _hexagons, "rhombi": _rhombi}

PATTERNS: tuple[str, ...] = tuple(_CELLS)
"""The girih patterns of ``GirihPacking(pattern=...)`` (``[packing] girih_pattern``)."""


def check_pattern(pattern) -> str:
    """``pattern`` checked against :data:`PATTERNS`, with a "did you mean".

    >>> check_pattern("decagon-bowties")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: pattern = 'decagon-bowties' is not a girih pattern (did you mean 'decagon-bowtie'?), must be one of: decagon-bowtie, hexagons, rhombi
    """  # noqa: E501 - a doctest's lines are as Python prints them
    if pattern not in PATTERNS:
        hint = did_you_mean(pattern, PATTERNS)
        raise ParameterError(
            f"pattern = {pattern!r} is not a girih pattern{f' ({hint})' if hint else ''}, "
            f"must be one of: {', '.join(PATTERNS)}",
            param="pattern",
        )
    return pattern


@functools.cache
def girih_cell(pattern: str) -> GirihCell:
    """The cell of a periodic pattern, edge 1 (made once)."""
    return _CELLS[check_pattern(pattern)]()


@functools.cache
def _cell_strapwork(pattern: str) -> tuple[np.ndarray, ...]:
    """Each cell tile's strapwork, edge 1, read-only (made once)."""
    out = []
    for corners in girih_cell(pattern).corners:
        seg = strapwork(corners)
        seg.setflags(write=False)
        out.append(seg)
    return tuple(out)


@dataclass(frozen=True, slots=True, repr=False)
class GirihPacking:
    """A periodic pattern of girih tiles and its strapwork (immutable).

    Parameters
    ----------
    pattern : str
        One of :data:`PATTERNS`.
    edge : float
        The tiles' edge length, mm (> 0).

    Examples
    --------
    >>> p = GirihPacking("decagon-bowtie", edge=10)
    >>> [round(v, 3) for v in p.period], len(p.polygons((-1, -1, 1, 1)))
    ([49.798, 36.18], 1)
    >>> GirihPacking("rhombus", edge=10)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: pattern = 'rhombus' is not a girih pattern (did you mean 'rhombi'?), must be one of: decagon-bowtie, hexagons, rhombi
    """  # noqa: E501 - a doctest's lines are as Python prints them

    pattern: str
    """One of :data:`PATTERNS`."""
    edge: float = 20.0
    """The tiles' edge, mm."""
    _: KW_ONLY

    def __post_init__(self) -> None:
        object.__setattr__(self, "pattern", check_pattern(self.pattern))
        object.__setattr__(self, "edge", check_float("edge", self.edge, low=0, low_open=True))

    @property
    def outline_circles(self) -> bool:
        """A girih pattern strokes no circles."""
        return False

    @property
    def radius(self) -> float:
        """The largest stroke a tile of this pattern takes, mm: a sixth of the edge, so the smallest face
        of the strapwork (the rhombus's, a third of the edge across) stays open."""
        return self.edge / 6

    @property
    def lattice(self) -> np.ndarray:
        """The two lattice vectors (rows), mm."""
        return girih_cell(self.pattern).lattice * self.edge

    @property
    def period(self) -> tuple[float, float]:
        """The smallest rectangular period ``(px, py)``, mm."""
        px, py = girih_cell(self.pattern).period
        return (px * self.edge, py * self.edge)

    def params(self) -> dict:
        """The constructor arguments."""
        return dict(pattern=self.pattern, edge=self.edge)

    def replace(self, **changes) -> GirihPacking:
        """A copy with some parameters changed (validated again)."""
        return type(self)(**{**self.params(), **changes})

    def __repr__(self) -> str:
        return f"GirihPacking({self.pattern!r}, edge={self.edge:g})"

    # -- tiles ----------------------------------------------------------------------------------------------------
    def _placed(self, window) -> tuple[np.ndarray, np.ndarray]:
        """``(shifts, tile index)`` of every cell tile whose bounding box meets ``window``, mm."""
        x0, y0, x1, y1 = check_window(window)
        cell, a = girih_cell(self.pattern), self.edge
        basis = cell.lattice * a
        inv = np.linalg.inv(basis.T)
        shifts, index = [], []
        for e, corners in enumerate(cell.corners):
            lo_c, hi_c = corners.min(axis=0) * a, corners.max(axis=0) * a
            box = np.array([[x0 - hi_c[0], y0 - hi_c[1]], [x1 - lo_c[0], y1 - lo_c[1]]])
            ij = np.array([[box[i, 0], box[j, 1]] for i in (0, 1) for j in (0, 1)]) @ inv.T
            lo, hi = np.floor(ij.min(axis=0)), np.ceil(ij.max(axis=0))
            if float(np.prod(hi - lo + 1)) * len(cell.corners) > MAX_CIRCLES_IN_WINDOW:
                raise LimitError(
                    f"the window holds about {float(np.prod(hi - lo + 1)):.3g} girih tiles, more than the limit of "
                    f"{MAX_CIRCLES_IN_WINDOW}; use a larger edge (got {self.edge:g} mm) or a smaller tile",
                    param="edge",
                )
            jj, ii = np.meshgrid(np.arange(lo[1], hi[1] + 1), np.arange(lo[0], hi[0] + 1), indexing="ij")
            s = ii.reshape(-1, 1) * basis[0] + jj.reshape(-1, 1) * basis[1]
            keep = (
                (s[:, 0] + hi_c[0] >= x0)
                & (s[:, 0] + lo_c[0] <= x1)
                & (s[:, 1] + hi_c[1] >= y0)
                & (s[:, 1] + lo_c[1] <= y1)
            )
            shifts.append(s[keep])
            index.append(np.full(int(keep.sum()), e))
        return np.concatenate(shifts), np.concatenate(index)

    def tiles(self, window) -> list[tuple[str, np.ndarray]]:
        """Every tile whose bounding box meets ``window``: its name and corners ``(k, 2)``, mm,
        counter-clockwise.

        >>> [name for name, _ in GirihPacking("hexagons", edge=10).tiles((-1, -1, 1, 1))]
        ['hexagon']
        """
        cell, a = girih_cell(self.pattern), self.edge
        shifts, index = self._placed(window)
        return [(cell.kinds[e], cell.corners[e] * a + s) for s, e in zip(shifts, index.tolist(), strict=True)]

    def polygons(self, window) -> list[np.ndarray]:
        """Every tile of the pattern whose bounding box meets ``window`` ``(xmin, ymin, xmax, ymax)``, mm:
        its corners ``(k, 2)``, mm, counter-clockwise.

        >>> [len(c) for c in GirihPacking("decagon-bowtie", edge=10).polygons((-1, -1, 1, 1))]
        [10]
        """
        return [corners for _, corners in self.tiles(window)]

    def segments(self, window) -> np.ndarray:
        """The strapwork's centre-lines of every tile whose bounding box meets ``window``, ``(k, 2, 2)`` mm.

        >>> GirihPacking("decagon-bowtie", edge=10).segments((-1, -1, 1, 1)).shape
        (20, 2, 2)
        """
        units = _cell_strapwork(self.pattern)
        shifts, index = self._placed(window)
        parts = [np.empty((0, 2, 2))]
        for e in np.unique(index):
            placed = units[e][None] * self.edge + shifts[index == e][:, None, None, :]
            parts.append(placed.reshape(-1, 2, 2))
        return np.concatenate(parts)

    def circles(self, window) -> tuple[np.ndarray, np.ndarray]:
        """No circles: centres ``(0, 2)`` and radii ``(0,)`` (a girih pattern is drawn from its tiles)."""
        check_window(window)
        return np.empty((0, 2)), np.empty(0)

    def motif_segments(self, window) -> np.ndarray:
        """The same as :meth:`segments` (a girih pattern has no circles to leave out)."""
        return self.segments(window)

    def segment_count(self, window) -> int:
        """Centre-line segments :meth:`segments` returns for ``window``, counted without placing them."""
        per = np.array([len(u) for u in _cell_strapwork(self.pattern)])
        return int(per[self._placed(window)[1]].sum())


# The schema names no module above it: the values and checks of its keys are registered from here.
def _check_design_pattern(value) -> str:
    """A design's ``[packing] girih_pattern``: :func:`check_pattern`, the key named as the design names it."""
    try:
        return check_pattern(value)
    except ParameterError as exc:
        raise ParameterError(f"girih_{exc}", param="girih_pattern") from None


register_choices(PATTERNS, "packing.girih_pattern")
register_check(_check_design_pattern, "packing.girih_pattern")
