"""Girih tiles: the five Lu-Steinhardt tiles, their strapwork, periodic patterns of them and their subdivision
(``docs/girih.md``).

Pure numpy. The five tiles (P. J. Lu and P. J. Steinhardt, "Decagonal and quasi-crystalline
tilings in medieval Islamic architecture", Science 315, 1106, 2007, Fig. 1F) have equal edges
and every angle a multiple of 36 degrees: the regular decagon and pentagon, the elongated
hexagon (72, 144, 144, 72, 144, 144), the bowtie (72, 72, 216, 72, 72, 216) and the rhombus
(72, 108). Each edge's midpoint is crossed by two decoration lines at 54 degrees to the edge
(72 degrees to each other), so the lines of two tiles sharing an edge continue each other.

Inside a tile every line runs on until it meets another, and two lines that meet each other
first are a pair: a tile's lines are paired in order of the distance they run, shortest first.
That gives the figures of Lu and Steinhardt's Fig. 1F: on the decagon and the pentagon the lines
of two edges beside a corner meet on its bisector (a 10- and a 5-pointed star, their points at
the midpoints); beside a 72-degree corner the two lines are one straight line from midpoint to
midpoint; in the bowtie the lines leaning to a 216-degree corner meet the lines of the far edge
of their own half first, so each half holds its own closed figure.

A pattern is a lattice and the tiles of one cell (:data:`PATTERNS`), so a tile of it repeats
seamlessly and the pipeline takes its strapwork like any packing's centre-lines.

The subdivision (:func:`subdivide`) replaces each decagon, hexagon and bowtie by girih tiles ``TAU2`` times
smaller: every large edge is the long diagonal of a small hexagon, half in each tile sharing it, and
:func:`subdivision_rule` fills the rest. A pattern subdivided ``level`` times is again a lattice and one cell.

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


# -- subdivision -------------------------------------------------------------------------------------------------------
TAU2 = (3 + math.sqrt(5)) / 2
"""The subdivision's scale, the golden ratio squared: a large tile's edge over its small tiles' edge. It is
also the elongated hexagon's length from tip to tip (``1 + 2 cos 36``), so a small hexagon spans a large edge."""

SUBDIVIDED: tuple[str, ...] = ("decagon", "hexagon", "bowtie")
"""The tiles the subdivision rule replaces (the tiles it makes are these three too)."""

MAX_SUBDIVISION_SEGMENTS = 500_000
"""The most strapwork segments one repeat of a subdivided pattern may hold (they are all made, once)."""

_PLURAL = {
    "decagon": "decagons",
    "pentagon": "pentagons",
    "hexagon": "hexagons",
    "bowtie": "bowties",
    "rhombus": "rhombi",
}
_SEGMENTS_PER_TILE = {"decagon": 20, "hexagon": 10, "bowtie": 8}

# Each large tile's small tiles, not counting the hexagons on its edges: (kind, a corner of the large tile
# tile_corners(kind, edge=TAU2), a walk of unit steps from it (degrees) to the small tile's corner 0, the heading of
# the small tile's first edge). The decagon's are made in _decagon_rule.
_WALKED_RULES: Mapping[str, tuple[tuple[str, int, tuple[int, ...], int], ...]] = MappingProxyType(
    {
        # a small bowtie in each half, its end edges on the half-hexagons of the large bowtie's ends
        "bowtie": (("bowtie", 0, (36,), 0), ("bowtie", 0, (36, 72, 108), 0)),
        # two hexagons and three bowties: the filling with a mirror line (none keeps both of the tile's)
        "hexagon": (
            ("hexagon", 4, (), 252),
            ("bowtie", 1, (36, 72), 0),
            ("bowtie", 4, (252,), 216),
            ("bowtie", 1, (), 72),
            ("hexagon", 1, (72,), 108),
        ),
    }
)
_COUNTS = np.array(
    # small tiles (rows: decagon, hexagon, bowtie) a large tile (columns) becomes, each edge's hexagon counted
    # half (it is shared with the neighbour)
    [[1, 0, 0], [10 + 10 / 2, 2 + 6 / 2, 0 + 6 / 2], [10, 3, 2]]
)


def _unit(degrees: float) -> np.ndarray:
    return np.array([math.cos(math.radians(degrees)), math.sin(math.radians(degrees))])


def edge_hexagon(a, b) -> np.ndarray:
    """The small hexagon ``(6, 2)`` whose tips are the ends of a large edge ``a -> b``: its edge is ``|ab| / TAU2``,
    half of it lies on each side of the edge, so the two tiles sharing the edge make the same one.

    >>> np.round(edge_hexagon((0, 0), (TAU2, 0)), 4).tolist()
    [[0.0, 0.0], [0.809, -0.5878], [1.809, -0.5878], [2.618, 0.0], [1.809, 0.5878], [0.809, 0.5878]]
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    d = b - a
    return tile_corners(
        "hexagon", edge=float(np.hypot(*d)) / TAU2, start=a, heading=math.degrees(math.atan2(d[1], d[0])) - 36
    )


def _decagon_rule() -> list[tuple[str, np.ndarray]]:
    """The large decagon's small tiles: a decagon at its centre turned as it is, a bowtie standing on each of that
    decagon's edges and a hexagon on each of its corners, pointing out (the hexagon's far tip is a large corner)."""
    big = tile_corners("decagon", edge=TAU2)
    centre = big.mean(axis=0)
    small = tile_corners("decagon")
    small += centre - small.mean(axis=0)
    out = [("decagon", small)]
    for k in range(10):
        # corner k points out at 36k - 108 degrees; the hexagon's axis is 36 degrees left of its first edge
        out.append(("hexagon", tile_corners("hexagon", start=small[k], heading=36 * k - 144)))
        # the bowtie's end edge (its first) runs back along the decagon's edge k, so the bowtie lies outside
        out.append(("bowtie", tile_corners("bowtie", start=small[(k + 1) % 10], heading=36 * k + 180)))
    return out


@functools.cache
def subdivision_rule(kind: str) -> tuple[tuple[str, np.ndarray], ...]:
    """The small tiles (edge 1) that replace the large tile ``tile_corners(kind, edge=TAU2)``, besides the hexagons on
    its edges (:func:`edge_hexagon`), each counter-clockwise from the corner :data:`TILES` starts at.

    >>> [k for k, _ in subdivision_rule("bowtie")]
    ['bowtie', 'bowtie']
    """
    if check_tile(kind) not in SUBDIVIDED:
        raise ParameterError(
            f"tile = {kind!r} has no subdivision rule, must be one of: {', '.join(SUBDIVIDED)}", param="tile"
        )
    if kind == "decagon":
        rule = _decagon_rule()
    else:
        big = tile_corners(kind, edge=TAU2)
        rule = [
            (k, tile_corners(k, start=big[corner] + sum((_unit(d) for d in walk), np.zeros(2)), heading=h))
            for k, corner, walk, h in _WALKED_RULES[kind]
        ]
    for _, corners in rule:
        corners.setflags(write=False)
    return tuple(rule)


def _start(kind: str, corners: np.ndarray) -> int:
    """The first corner from which ``corners`` has the angles of :data:`TILES` (a tile's own frame)."""
    prev, nxt = np.roll(corners, 1, axis=0) - corners, np.roll(corners, -1, axis=0) - corners
    turn = np.degrees(np.arctan2(nxt[:, 0] * prev[:, 1] - nxt[:, 1] * prev[:, 0], (nxt * prev).sum(axis=1)))
    angles = tuple(round(float(t)) % 360 for t in turn)
    seq = TILES[kind]
    return next(k for k in range(len(seq)) if angles[k:] + angles[:k] == seq)


def _frame(kind: str, corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(origin, matrix)`` taking ``tile_corners(kind)`` (edge 1) onto ``corners``, corner 0 onto :func:`_start`."""
    k = _start(kind, corners)
    d = corners[(k + 1) % len(corners)] - corners[k]
    return corners[k], np.array([[d[0], -d[1]], [d[1], d[0]]])


def _edge_key(midpoint: np.ndarray, lattice: np.ndarray | None) -> tuple[float, ...]:
    """An edge's midpoint as a key, taken modulo ``lattice`` when there is one (edges a lattice step apart are one)."""
    if lattice is None:
        return tuple(np.round(midpoint, 6).tolist())
    f = np.linalg.solve(lattice.T, midpoint)
    return tuple((np.round(f, 6) % 1.0).round(6).tolist())


def subdivide(tiles, *, lattice=None) -> list[tuple[str, np.ndarray]]:
    """One step of the subdivision: every tile ``(kind, corners)`` of an edge-to-edge tiling of decagons, hexagons
    and bowties replaced by its :func:`subdivision_rule` tiles, ``TAU2`` times smaller, and every edge by the one
    :func:`edge_hexagon` the two tiles sharing it make. ``lattice`` (rows): the tiles are one cell of a periodic
    tiling, and edges a lattice step apart are one.

    >>> one = subdivide([("decagon", tile_corners("decagon", edge=TAU2))])
    >>> sorted({k: sum(1 for n, _ in one if n == k) for k in SUBDIVIDED}.items())
    [('bowtie', 10), ('decagon', 1), ('hexagon', 20)]
    """
    out: list[tuple[str, np.ndarray]] = []
    edges: dict[tuple[float, ...], tuple[np.ndarray, np.ndarray]] = {}
    for kind, corners in tiles:
        corners = np.asarray(corners, dtype=float)
        origin, matrix = _frame(kind, corners)
        for small, unit in subdivision_rule(kind):
            out.append((small, unit @ matrix.T / TAU2 + origin))
        for a, b in zip(corners, np.roll(corners, -1, axis=0), strict=True):
            edges.setdefault(_edge_key((a + b) / 2, lattice), (a, b))
    return out + [("hexagon", edge_hexagon(a, b)) for a, b in edges.values()]


def check_level(pattern, level) -> int:
    """``level`` checked for ``pattern``: a whole number from 0 (the pattern's own tiles), above 0 only for a pattern
    of the tiles the rule replaces, and no deeper than :data:`MAX_SUBDIVISION_SEGMENTS` allows.

    >>> check_level("decagon-bowtie", 2)
    2
    >>> check_level("decagon-bowtie", 5)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.LimitError: level = 5 would make 692,918 strapwork segments in one repeat of the girih pattern decagon-bowtie, more than the limit of 500,000; the deepest level it takes is 4
    """  # noqa: E501 - a doctest's lines are as Python prints them
    pattern = check_pattern(pattern)
    if isinstance(level, bool) or not isinstance(level, (int, np.integer)) or level < 0:
        raise ParameterError(f"level must be an integer >= 0, got {level!r}", param="level")
    level = int(level)
    if level == 0:
        return level
    other = [k for k in TILES if k in _CELLS[pattern]().kinds and k not in SUBDIVIDED]
    if other:
        raise ParameterError(
            f"level = {level} subdivides decagons, hexagons and bowties; the girih pattern {pattern} has "
            f"{' and '.join(_PLURAL[k] for k in other)}, which the rule does not replace: use 0, or a pattern "
            f"of those tiles ({', '.join(subdividable_patterns())})",
            param="level",
        )
    count = subdivided_segments(pattern, level)
    if count > MAX_SUBDIVISION_SEGMENTS:
        deepest = max(n for n in range(level) if subdivided_segments(pattern, n) <= MAX_SUBDIVISION_SEGMENTS)
        raise LimitError(
            f"level = {level} would make {count:,} strapwork segments in one repeat of the girih pattern {pattern}, "
            f"more than the limit of {MAX_SUBDIVISION_SEGMENTS:,}; the deepest level it takes is {deepest}",
            param="level",
        )
    return level


def subdividable_patterns() -> tuple[str, ...]:
    """The patterns of :data:`PATTERNS` made of the tiles the subdivision rule replaces (``level`` above 0)."""
    return tuple(p for p in PATTERNS if set(_CELLS[p]().kinds) <= set(SUBDIVIDED))


def subdivided_segments(pattern: str, level: int) -> int:
    """The strapwork segments of one cell of ``pattern`` subdivided ``level`` times, counted without making it: the
    tiles of each kind grow by the rule's counts, each edge's hexagon counted half in each of its two tiles.

    >>> [subdivided_segments("decagon-bowtie", n) for n in range(3)]
    [28, 296, 2134]
    """
    kinds = girih_cell(pattern).kinds
    counts = np.array([sum(k == kind for k in kinds) for kind in SUBDIVIDED], dtype=float)
    for _ in range(level):
        counts = _COUNTS @ counts
    per = np.array([_SEGMENTS_PER_TILE[k] for k in SUBDIVIDED])
    return round(float(per @ counts))


@functools.cache
def girih_cell(pattern: str, level: int = 0) -> GirihCell:
    """The cell of a periodic pattern, edge 1 (made once): at ``level`` above 0 the pattern's cell ``TAU2 ** level``
    times larger, subdivided ``level`` times, so its tiles have edge 1 again."""
    seed = _CELLS[check_pattern(pattern)]()
    level = check_level(pattern, level)
    scale = TAU2**level
    lattice = seed.lattice * scale
    tiles = [(k, c * scale) for k, c in zip(seed.kinds, seed.corners, strict=True)]
    for _ in range(level):
        tiles = subdivide(tiles, lattice=lattice)
    return GirihCell(lattice=lattice, kinds=tuple(k for k, _ in tiles), corners=tuple(c for _, c in tiles))


@functools.cache
def _unit_strapwork(kind: str) -> np.ndarray:
    """The strapwork of ``tile_corners(kind)``, read-only (made once)."""
    seg = strapwork(tile_corners(kind))
    seg.setflags(write=False)
    return seg


def tile_strapwork(kind: str, corners) -> np.ndarray:
    """The strapwork of a tile given by its name and corners: the unit tile's, moved onto it (the same lines as
    :func:`strapwork` of the corners, made without pairing them again).

    >>> c = tile_corners("bowtie", edge=3, start=(1, 2), heading=40)
    >>> bool(np.allclose(tile_strapwork("bowtie", c), strapwork(c)))
    True
    """
    origin, matrix = _frame(kind, np.asarray(corners, dtype=float))
    return _unit_strapwork(kind) @ matrix.T + origin


@functools.cache
def _cell_strapwork(pattern: str, level: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Every cell tile's strapwork, edge 1, as one read-only array ``(m, 2, 2)`` and where each tile's segments
    start in it (``n + 1`` offsets), made once."""
    cell = girih_cell(pattern, level)
    parts = [tile_strapwork(k, c) for k, c in zip(cell.kinds, cell.corners, strict=True)]
    seg = np.concatenate(parts)
    starts = np.concatenate([[0], np.cumsum([len(p) for p in parts])])
    seg.setflags(write=False)
    starts.setflags(write=False)
    return seg, starts


@dataclass(frozen=True, slots=True, repr=False)
class GirihPacking:
    """A periodic pattern of girih tiles and its strapwork (immutable).

    Parameters
    ----------
    pattern : str
        One of :data:`PATTERNS`.
    edge : float
        The tiles' edge length, mm (> 0).
    level : int
        How many times the pattern is subdivided (:func:`subdivide`; 0, the default: its own tiles). At level n the
        pattern is laid ``TAU2 ** n`` times larger and subdivided n times, so its tiles have ``edge`` again.

    Examples
    --------
    >>> p = GirihPacking("decagon-bowtie", edge=10)
    >>> [round(v, 3) for v in p.period], len(p.polygons((-1, -1, 1, 1)))
    ([49.798, 36.18], 1)
    >>> [round(v, 3) for v in GirihPacking("decagon-bowtie", edge=10, level=1).period]
    [130.373, 94.721]
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
    level: int = 0
    """Times the pattern is subdivided (0: its own tiles)."""

    def __post_init__(self) -> None:
        object.__setattr__(self, "pattern", check_pattern(self.pattern))
        object.__setattr__(self, "edge", check_float("edge", self.edge, low=0, low_open=True))
        object.__setattr__(self, "level", check_level(self.pattern, self.level))

    @property
    def _cell(self) -> GirihCell:
        return girih_cell(self.pattern, self.level)

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
        return self._cell.lattice * self.edge

    @property
    def period(self) -> tuple[float, float]:
        """The smallest rectangular period ``(px, py)``, mm."""
        px, py = self._cell.period
        return (px * self.edge, py * self.edge)

    def params(self) -> dict:
        """The constructor arguments."""
        return dict(pattern=self.pattern, edge=self.edge, level=self.level)

    def replace(self, **changes) -> GirihPacking:
        """A copy with some parameters changed (validated again)."""
        return type(self)(**{**self.params(), **changes})

    def __repr__(self) -> str:
        level = f", level={self.level}" if self.level else ""
        return f"GirihPacking({self.pattern!r}, edge={self.edge:g}{level})"

    # -- tiles ----------------------------------------------------------------------------------------------------
    def _placed(self, window) -> tuple[np.ndarray, np.ndarray]:
        """``(shifts, tile index)`` of every cell tile whose bounding box meets ``window``, mm."""
        x0, y0, x1, y1 = check_window(window)
        cell, a = self._cell, self.edge
        basis = cell.lattice * a
        inv = np.linalg.inv(basis.T)
        lo_c = np.array([c.min(axis=0) for c in cell.corners]) * a
        hi_c = np.array([c.max(axis=0) for c in cell.corners]) * a
        # the lattice steps that can bring any cell tile's box into the window
        box = np.array([[x0 - hi_c[:, 0].max(), y0 - hi_c[:, 1].max()], [x1 - lo_c[:, 0].min(), y1 - lo_c[:, 1].min()]])
        ij = np.array([[box[i, 0], box[j, 1]] for i in (0, 1) for j in (0, 1)]) @ inv.T
        lo, hi = np.floor(ij.min(axis=0)), np.ceil(ij.max(axis=0))
        steps = float(np.prod(hi - lo + 1))
        if steps * len(cell.corners) > MAX_CIRCLES_IN_WINDOW:
            raise LimitError(
                f"the window holds about {steps * len(cell.corners):.3g} girih tiles, more than the limit of "
                f"{MAX_CIRCLES_IN_WINDOW}; use a larger edge (got {self.edge:g} mm) or a smaller tile",
                param="edge",
            )
        jj, ii = np.meshgrid(np.arange(lo[1], hi[1] + 1), np.arange(lo[0], hi[0] + 1), indexing="ij")
        s = ii.reshape(-1, 1) * basis[0] + jj.reshape(-1, 1) * basis[1]
        keep = (
            (s[None, :, 0] + hi_c[:, None, 0] >= x0)
            & (s[None, :, 0] + lo_c[:, None, 0] <= x1)
            & (s[None, :, 1] + hi_c[:, None, 1] >= y0)
            & (s[None, :, 1] + lo_c[:, None, 1] <= y1)
        )
        tile, shift = np.nonzero(keep)  # tile by tile, as the cell lists them
        return s[shift], tile

    def tiles(self, window) -> list[tuple[str, np.ndarray]]:
        """Every tile whose bounding box meets ``window``: its name and corners ``(k, 2)``, mm,
        counter-clockwise.

        >>> [name for name, _ in GirihPacking("hexagons", edge=10).tiles((-1, -1, 1, 1))]
        ['hexagon']
        """
        cell, a = self._cell, self.edge
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
        units, starts = _cell_strapwork(self.pattern, self.level)
        shifts, index = self._placed(window)
        count = (starts[1:] - starts[:-1])[index]
        first = np.repeat(starts[index] - (np.cumsum(count) - count), count)
        rows = first + np.arange(int(count.sum()))
        return units[rows] * self.edge + np.repeat(shifts, count, axis=0)[:, None, :]

    def circles(self, window) -> tuple[np.ndarray, np.ndarray]:
        """No circles: centres ``(0, 2)`` and radii ``(0,)`` (a girih pattern is drawn from its tiles)."""
        check_window(window)
        return np.empty((0, 2)), np.empty(0)

    def motif_segments(self, window) -> np.ndarray:
        """The same as :meth:`segments` (a girih pattern has no circles to leave out)."""
        return self.segments(window)

    def segment_count(self, window) -> int:
        """Centre-line segments :meth:`segments` returns for ``window``, counted without placing them."""
        _, starts = _cell_strapwork(self.pattern, self.level)
        return int((starts[1:] - starts[:-1])[self._placed(window)[1]].sum())


# The schema names no module above it: the values and checks of its keys are registered from here.
def _check_design_pattern(value) -> str:
    """A design's ``[packing] girih_pattern``: :func:`check_pattern`, the key named as the design names it."""
    try:
        return check_pattern(value)
    except ParameterError as exc:
        raise ParameterError(f"girih_{exc}", param="girih_pattern") from None


register_choices(PATTERNS, "packing.girih_pattern")
register_check(_check_design_pattern, "packing.girih_pattern")
