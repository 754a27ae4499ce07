"""The 11 Archimedean and the two-uniform tilings as translational unit cells, and their gap circles
(``docs/tile-operation.md``, ``docs/tilings.md``).

Pure numpy. Each tiling is given by two lattice vectors and the regular polygons
of one cell (centre, number of sides, direction of one edge midpoint), all for
edge length 1. Everything else is derived here and checked by the tests: the
tiling's vertices (polygon corners, one per lattice class) and, around each
vertex, the gap circle -- the largest circle in the gap the incircles leave
there. That circle touches at least three incircles (a largest empty circle
among circles sits on a vertex of their additively weighted Voronoi diagram), so
it is found exactly by solving Apollonius' problem (a circle externally tangent
to three given circles) for every triple of incircles around the vertex and
keeping the largest solution that overlaps none of them. For three mutually
tangent incircles this is the inner Soddy circle of Descartes' theorem.

>>> cell = unit_cell("4.8.8")
>>> sorted(set(cell.sides.tolist())), len(cell.vertices), len(cell.gap_radii)
([4, 8], 4, 4)
>>> canonical("3^4.6"), canonical("4.6.4.3")
('3.3.3.3.6', '3.4.6.4')
>>> canonical("3.3.3.3.3.3; 3.3.6.3.3 #2"), len(ALL_TILINGS)
('[3^6; 3^4.6]#2', 31)
"""

from __future__ import annotations

import functools
import itertools
import math
import re
from dataclasses import dataclass

import numpy as np

from ..core.errors import ParameterError, did_you_mean
from ..core.schema import register_check, register_choices
from .two_uniform import TWO_UNIFORM, TWO_UNIFORM_NAMES, two_uniform_cells

S3 = math.sqrt(3.0)

TILINGS = (
    "3.3.3.3.3.3",
    "4.4.4.4",
    "6.6.6",
    "3.6.3.6",
    "3.12.12",
    "4.6.12",
    "4.8.8",
    "3.3.3.3.6",
    "3.3.3.4.4",
    "3.3.4.3.4",
    "3.4.6.4",
)
"""The 11 Archimedean tilings by vertex configuration (the regular ones first)."""

NAMES = {
    "3.3.3.3.3.3": "triangular",
    "4.4.4.4": "square",
    "6.6.6": "hexagonal",
    "3.6.3.6": "trihexagonal",
    "3.12.12": "truncated hexagonal",
    "4.6.12": "truncated trihexagonal",
    "4.8.8": "truncated square",
    "3.3.3.3.6": "snub hexagonal",
    "3.3.3.4.4": "elongated triangular",
    "3.3.4.3.4": "snub square",
    "3.4.6.4": "rhombitrihexagonal",
}
"""Vertex configuration -> common name of the tiling."""

ALL_TILINGS = TILINGS + TWO_UNIFORM
"""The 11 Archimedean tilings, then the two-uniform ones (:data:`~fabtiles.pattern.two_uniform.TWO_UNIFORM`)."""

NAMES = {**NAMES, **TWO_UNIFORM_NAMES}


def inradius(p: int, edge: float = 1.0) -> float:
    """Incircle radius ``edge / (2 tan(pi/p))`` of a regular p-gon.

    >>> round(inradius(6, 2 / math.sqrt(3)), 12)
    1.0
    """
    return edge / (2.0 * math.tan(math.pi / p))


def circumradius(p: int, edge: float = 1.0) -> float:
    """Circumcircle radius ``edge / (2 sin(pi/p))`` of a regular p-gon."""
    return edge / (2.0 * math.sin(math.pi / p))


def _expand(name: str) -> tuple[int, ...]:
    """``"3^4.6"`` -> ``(3, 3, 3, 3, 6)``; raises ValueError when it is not of that form."""
    out = []
    for part in name.replace(" ", "").split("."):
        base, _, power = part.partition("^")
        out += [int(base)] * (int(power) if power else 1)
    return tuple(out)


def _cyclic_forms(seq: tuple[int, ...]) -> set[tuple[int, ...]]:
    rots = [seq[k:] + seq[:k] for k in range(len(seq))]
    return set(rots) | {r[::-1] for r in rots}


_FORMS = {form: name for name in TILINGS for form in _cyclic_forms(_expand(name))}

_PAIR = re.compile(r"\[?\s*([0-9^.\s]+?)\s*[;,]\s*([0-9^.\s]+?)\s*\]?\s*(?:(?:#|\s)\s*([0-9]+))?")


def _config(text: str) -> tuple[int, ...]:
    """A vertex configuration's one spelling: the least of its rotations and reflections."""
    return min(_cyclic_forms(_expand(text)))


def _pair_key(text: str):
    """``(frozenset of the two configurations, number or None)`` of a two-uniform name, or None."""
    match = _PAIR.fullmatch(text.strip())
    if match is None:
        return None
    try:
        return frozenset((_config(match[1]), _config(match[2]))), match[3] and int(match[3])
    except ValueError:
        return None


_PAIRS = {_pair_key(name): name for name in TWO_UNIFORM}
_PAIRS |= {(types, None): name for (types, number), name in list(_PAIRS.items()) if number is None}


def _pair_hint(tiling) -> str:
    """``did you mean '...#1' or '...#2'?`` for a two-uniform name without the number its pair needs."""
    key = _pair_key(tiling) if isinstance(tiling, str) else None
    both = [name for (types, number), name in _PAIRS.items() if key and number and types == key[0]]
    return f"did you mean {both[0]!r} or {both[1]!r}?" if key and key[1] is None and len(both) == 2 else ""


def canonical(tiling) -> str:
    """The tiling's name in :data:`ALL_TILINGS` form.

    Accepts exponent forms (``"3^6"``, ``"3^4.6"``, ``"4.8^2"``) and any rotation or
    reflection of the vertex configuration (``"8.4.8"``); a two-uniform tiling by its two
    configurations in either order, separated by ``;`` or ``,``, brackets optional, and
    ``#1``/``#2`` (or `` 1``/`` 2``) where two tilings share their vertex types.

    >>> canonical("3^6"), canonical("4.8^2"), canonical("12.3.12")
    ('3.3.3.3.3.3', '4.8.8', '3.12.12')
    >>> canonical("3.3.4.3.4, 3.3.3.3.3.3"), canonical("[3^6; 3^3.4^2] 2")
    ('[3^6; 3^2.4.3.4]', '[3^6; 3^3.4^2]#2')
    >>> canonical("5.5.5")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: tiling '5.5.5' is unknown (tilings: 3.3.3.3.3.3, 4.4.4.4, ..., [3^6; 3^3.4^2]#2; exponent forms such as 3^4.6 also work)
    """  # noqa: E501 - a doctest's lines are as Python prints them
    name = None
    if isinstance(tiling, str):
        try:
            name = _FORMS.get(_expand(tiling))
        except ValueError:
            name = _PAIRS.get(_pair_key(tiling))
    if name is None:
        hint = _pair_hint(tiling) or did_you_mean(tiling, ALL_TILINGS)
        raise ParameterError(
            f"tiling {tiling!r} is unknown{'; ' + hint if hint else ''} (tilings: "
            f"{', '.join(ALL_TILINGS)}; exponent forms such as 3^4.6 also work)",
            param="tiling",
        )
    return name


@dataclass(frozen=True, eq=False)
class UnitCell:
    """One translational cell of a tiling with edge 1 (arrays are read-only).

    Attributes
    ----------
    name : str
        The tiling's name: its vertex configuration, or a two-uniform tiling's two.
    lattice : ndarray (2, 2)
        Rows are the two lattice vectors.
    centres, sides, angles : ndarray (k, 2), (k,), (k,)
        The cell's polygons: centre, number of sides, direction (radians) from the
        centre to one edge midpoint (a tangency point of its incircle).
    vertices : ndarray (v, 2)
        One representative of each lattice class of tiling vertices.
    gap_centres, gap_radii, gap_angles : ndarray (v, 2), (v,), (v,)
        The gap circle of each vertex, in the order of ``vertices``, and the
        direction (radians) from its centre to the incircle it touches that has
        the most sides (the first listed of those), where its motif points.
    """

    name: str
    lattice: np.ndarray
    centres: np.ndarray
    sides: np.ndarray
    angles: np.ndarray
    vertices: np.ndarray
    gap_centres: np.ndarray
    gap_radii: np.ndarray
    gap_angles: np.ndarray

    @property
    def area(self) -> float:
        """Area of the cell (edge 1)."""
        return float(abs(np.linalg.det(self.lattice)))

    def radii(self) -> np.ndarray:
        """Incircle radius of each polygon of the cell."""
        return np.array([inradius(int(p)) for p in self.sides])


def _cells() -> dict:
    """name -> (lattice rows, [(x, y, sides, edge-midpoint angle in degrees), ...]), edge 1."""
    d12, d6 = 2 + S3, 3 + S3  # dodecagon spacing in 3.12.12 and in 4.6.12
    d4 = 1 + S3  # hexagon spacing in 3.4.6.4
    s8 = 1 + math.sqrt(2)  # octagon spacing in 4.8.8
    ls = (1 + S3) / math.sqrt(2)  # snub square period
    ts = inradius(3) + inradius(4)  # square centre to triangle centre, edge-adjacent
    tri = lambda d: (d, d * S3)  # noqa: E731 - triangular lattice second vector
    cells = {
        # A triangle centred on the origin; up and down triangles.
        "3.3.3.3.3.3": ([(1, 0), (0.5, S3 / 2)], [(0, 0, 3, -90), (0.5, S3 / 6, 3, 90)]),
        # As SquarePacking: a square on the origin, neighbours along x.
        "4.4.4.4": ([(1, 0), (0, 1)], [(0, 0, 4, 0)]),
        # As HexPacking: a pointy-top hexagon on the origin, neighbours along x.
        "6.6.6": ([(S3, 0), (S3 / 2, 1.5)], [(0, 0, 6, 0)]),
        # Hexagons meeting corner to corner along x, triangles between them.
        "3.6.3.6": ([(2, 0), tri(1)], [(0, 0, 6, 30), (1, S3 / 3, 3, 90), (0, 2 * S3 / 3, 3, -90)]),
        "3.12.12": (
            [(d12, 0), tri(d12 / 2)],
            [(0, 0, 12, 0), (d12 / 2, d12 * S3 / 6, 3, 90), (d12 / 2, -d12 * S3 / 6, 3, -90)],
        ),
        "4.6.12": (
            [(d6, 0), tri(d6 / 2)],
            [
                (0, 0, 12, 0),
                (d6 / 2, 0, 4, 0),
                (d6 / 4, d6 * S3 / 4, 4, 60),
                (-d6 / 4, d6 * S3 / 4, 4, 120),
                (d6 / 2, d6 * S3 / 6, 6, 30),
                (d6 / 2, -d6 * S3 / 6, 6, 30),
            ],
        ),
        "4.8.8": ([(s8, 0), (0, s8)], [(0, 0, 8, 0), (s8 / 2, s8 / 2, 4, 45)]),
        "3.3.3.4.4": (
            [(1, 0), (0.5, 1 + S3 / 2)],
            [(0, 0, 4, 0), (0, 0.5 + S3 / 6, 3, -90), (0.5, 0.5 + S3 / 3, 3, 90)],
        ),
        # Squares turned by +-15 degrees, each edge shared with a triangle.
        "3.3.4.3.4": (
            [(ls, 0), (0, ls)],
            [(0, 0, 4, 15), (ls / 2, ls / 2, 4, 75)]
            + [
                (ts * math.cos(math.radians(a)), ts * math.sin(math.radians(a)), 3, a + 180)
                for a in (15, 105, 195, 285)
            ],
        ),
        "3.4.6.4": (
            [(d4, 0), tri(d4 / 2)],
            [
                (0, 0, 6, 0),
                (d4 / 2, 0, 4, 0),
                (d4 / 4, d4 * S3 / 4, 4, 60),
                (-d4 / 4, d4 * S3 / 4, 4, 120),
                (d4 / 2, d4 * S3 / 6, 3, 30),
                (d4 / 2, -d4 * S3 / 6, 3, 90),
            ],
        ),
    }
    cells["3.3.3.3.6"] = _snub_hexagonal()
    return cells


@functools.cache
def _all_cells() -> dict:
    """The cells of :data:`ALL_TILINGS`, in :func:`_cells`' form."""
    archimedean = _cells()
    return {**archimedean, **two_uniform_cells(archimedean)}


def _snub_hexagonal():
    """3.3.3.3.6 from the triangular tiling: the six triangles around every point of the
    index-7 sublattice ``a + b w`` with ``a = 2b (mod 7)`` (w = e^(i pi/3)) merge into a
    hexagon; the other eight triangles of each cell stay. Turned so the lattice vector
    ``2 + w`` lies along x."""
    w = np.array([0.5, S3 / 2])
    lattice = np.array([[2.5, S3 / 2], [-1 + 1.5, 3 * S3 / 2]])  # 2 + w, 3w - 1
    turn = -math.atan2(lattice[0, 1], lattice[0, 0])
    polys = [(0.0, 0.0, 6, 30.0)]
    for k in range(7):  # the coset representatives a + 0 w, a = 0..6
        a, b = k, 0
        v = np.array([a, 0.0]) + b * w
        for centroid, corners, ang in (
            (v + [0.5, S3 / 6], [(0, 0), (1, 0), (0, 1)], -90.0),
            (v + [1.0, S3 / 3], [(1, 0), (0, 1), (1, 1)], 90.0),
        ):
            in_hexagon = any((a + i - 2 * (b + j)) % 7 == 0 for i, j in corners)
            if not in_hexagon:
                polys.append((*centroid, 3, ang))
    c, s = math.cos(turn), math.sin(turn)
    rot = np.array([[c, -s], [s, c]])
    lattice = lattice @ rot.T
    polys = [(*(rot @ np.array([x, y])), p, ang + math.degrees(turn)) for x, y, p, ang in polys]
    return [tuple(v) for v in lattice], polys


@functools.cache
def unit_cell(tiling) -> UnitCell:
    """The :class:`UnitCell` of a tiling (any form :func:`canonical` accepts), edge 1."""
    name = canonical(tiling)
    lattice, polys = _all_cells()[name]
    lattice = np.array(lattice, dtype=float)
    centres = np.array([(x, y) for x, y, _, _ in polys], dtype=float)
    sides = np.array([p for _, _, p, _ in polys], dtype=int)
    angles = np.radians(np.array([a for _, _, _, a in polys], dtype=float))
    vertices = _vertices(lattice, centres, sides, angles)
    gap_c, gap_r, gap_a = _gap_circles(lattice, centres, sides, vertices)
    arrays = [lattice, centres, sides, angles, vertices, gap_c, gap_r, gap_a]
    for a in arrays:
        a.setflags(write=False)
    return UnitCell(name, *arrays)


def _reduce(points, lattice):
    """Points moved into the cell spanned by ``lattice`` (fractional coordinates in [0, 1))."""
    frac = points @ np.linalg.inv(lattice)
    frac = frac - np.floor(np.round(frac, 9))
    return frac @ lattice


def _corners(centres, sides, angles):
    out = []
    for c, p, a in zip(centres, sides, angles, strict=True):
        t = a + math.pi / p + 2 * math.pi * np.arange(p) / p
        out.append(c + circumradius(int(p)) * np.stack([np.cos(t), np.sin(t)], axis=1))
    return np.concatenate(out)


def _vertices(lattice, centres, sides, angles):
    pts = _reduce(_corners(centres, sides, angles), lattice)
    key = np.round(pts, 6)
    _, first = np.unique(key, axis=0, return_index=True)
    pts = pts[np.sort(first)]
    # Corners on the cell's far edges are the same class as those on the near ones.
    frac = np.round(pts @ np.linalg.inv(lattice), 6) % 1.0
    _, first = np.unique(np.round(frac, 6) % 1.0, axis=0, return_index=True)
    return pts[np.sort(first)]


def _around(vertex, lattice, centres, sides):
    """Centres and incircle radii of the polygons having ``vertex`` as a corner."""
    shifts = np.array(list(itertools.product(range(-2, 3), repeat=2)), dtype=float) @ lattice
    allc = (centres[None] + shifts[:, None]).reshape(-1, 2)
    alls = np.tile(sides, len(shifts))
    circ = np.array([circumradius(int(p)) for p in alls])
    hit = np.abs(np.hypot(*(allc - vertex).T) - circ) < 1e-7
    index = np.tile(np.arange(len(sides)), len(shifts))[hit]
    order = np.argsort(np.arctan2(*(allc[hit] - vertex).T[::-1]))
    return allc[hit][order], np.array([inradius(int(p)) for p in alls[hit]])[order], index[order]


def apollonius_outer(c, r):
    """Circles externally tangent to three circles: ``(centres (m, 2), radii (m,))``, radius > 0.

    Subtracting the tangency equations ``|x - c_i| = r + r_i`` pairwise leaves
    ``x`` linear in ``r``; the first equation is then a quadratic in ``r``.

    >>> c = np.array([[0.0, 0.0], [2.0, 0.0], [1.0, math.sqrt(3)]])
    >>> centre, rad = apollonius_outer(c, np.ones(3))
    >>> round(float(rad[0]), 6), centre[0].round(6).tolist()  # Soddy: 2/sqrt(3) - 1
    (0.154701, [1.0, 0.57735])
    """
    r1 = r[0]
    a = 2 * (c[1:] - c[0])  # rows: equations i = 2, 3
    if abs(np.linalg.det(a)) < 1e-12:
        return np.empty((0, 2)), np.empty(0)
    # a @ x = k + m * rad
    k = (c[1:] ** 2).sum(1) - (c[0] ** 2).sum() - (r[1:] ** 2 - r1**2)
    m = -2 * (r[1:] - r1)
    inv = np.linalg.inv(a)
    p0, p1 = inv @ k, inv @ m  # x = p0 + p1 * rad
    d0 = p0 - c[0]
    qa = p1 @ p1 - 1
    qb = 2 * (d0 @ p1) - 2 * r1
    qc = d0 @ d0 - r1**2
    if abs(qa) < 1e-12:
        roots = [-qc / qb] if abs(qb) > 1e-12 else []
    else:
        disc = qb * qb - 4 * qa * qc
        if disc < 0:
            return np.empty((0, 2)), np.empty(0)
        sq = math.sqrt(disc)
        roots = [(-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)]
    roots = np.array([t for t in roots if t > 1e-12])
    return p0 + roots[:, None] * p1, roots


def _gap_circles(lattice, centres, sides, vertices):
    out_c, out_r, out_a = [], [], []
    for v in vertices:
        cc, rr, index = _around(v, lattice, centres, sides)
        # The gap lies inside the polygon of the surrounding centres (the dual tile).
        edges = np.roll(cc, -1, axis=0) - cc
        best = None
        for tri in itertools.combinations(range(len(cc)), 3):
            idx = list(tri)
            cand_c, cand_r = apollonius_outer(cc[idx], rr[idx])
            for x, rad in zip(cand_c, cand_r, strict=True):
                gaps = np.hypot(*(cc - x).T) - rr - rad
                d = x - cc
                inside = (edges[:, 0] * d[:, 1] - edges[:, 1] * d[:, 0]).min() > 0
                if gaps.min() < -1e-9 or not inside:
                    continue
                # Ties (mirror images) go to the circle touching the polygons listed first.
                key = (-round(rad, 9), sorted(index[gaps < 1e-9].tolist()))
                if best is None or key < best[0]:
                    best = (key, x, rad, gaps)
        assert best is not None, "every vertex of a tiling has a gap circle"
        _, x, rad, gaps = best
        touching = np.flatnonzero(gaps < 1e-9)
        first = min(touching, key=lambda t: (-sides[index[t]], index[t]))
        out_c.append(x)
        out_r.append(rad)
        out_a.append(math.atan2(*(cc[first] - x)[::-1]))
    return np.array(out_c), np.array(out_r), np.array(out_a)


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(ALL_TILINGS, "packing.tiling")
register_check(unit_cell, "packing.tiling")
