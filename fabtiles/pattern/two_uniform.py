"""The two-uniform tilings as translational unit cells (``docs/tilings.md``).

Pure numpy. A two-uniform tiling is an edge-to-edge tiling by regular polygons whose vertices
fall in two orbits under its symmetries (Grunbaum and Shephard, *Tilings and Patterns*, 2.2).
Each cell is built here from a simpler tiling by an operation that says where it comes from,
all for edge 1, then given a short basis turned so the first lattice vector lies along x (as the
11 Archimedean cells are):

- hexagons cut out of the triangular tiling: the six triangles around every point of a
  sublattice merge into a hexagon (the ``[3^6; 3^4.6]`` pair, ``[3^6; 3^2.6^2]``, ...);
- a tiling's hexagons split into six triangles, or its dodecagons dissected into a hexagon,
  six squares and six triangles (the squares on one set of alternate edges or the other);
- in a 2 x 2 block of 3.4.6.4 cells, one hexagon with its six squares and six triangles merged
  into a dodecagon;
- rows of squares and rows of triangles, or rows of hexagons and bowties between rows of
  squares, stacked;
- dodecagons sharing edges on a square lattice, a square in each hole;
- the two of squares and triangles with vertices 3^3.4^2 and 3^2.4.3.4, polygon by polygon
  across edges from one square (found by a search of small lattices).

The tests check every cell from its polygons alone: regular polygons covering the plane once,
360 degrees around every vertex, and exactly the two vertex types the name gives.

>>> lattice, polys = two_uniform_cells({})["[3^6; 3^4.6]#1"]
>>> sorted({p for _, _, p, _ in polys}), round(abs(lattice[0][0] * lattice[1][1] - lattice[0][1] * lattice[1][0]), 4)
([3, 6], 7.7942)
"""

from __future__ import annotations

import math

import numpy as np

S3 = math.sqrt(3.0)
_E1, _E2 = np.array([1.0, 0.0]), np.array([0.5, S3 / 2])

TWO_UNIFORM = (
    "[3^6; 3^2.4.3.4]",
    "[3.4.6.4; 3^2.4.3.4]",
    "[3.4.6.4; 3^3.4^2]",
    "[3.4.6.4; 3.4^2.6]",
    "[4.6.12; 3.4.6.4]",
    "[3^6; 3^2.4.12]",
    "[3.12^2; 3.4.3.12]",
    "[3^6; 3^2.6^2]",
    "[3^6; 3^4.6]#1",
    "[3^6; 3^4.6]#2",
    "[3^2.6^2; 3^4.6]",
    "[3.6.3.6; 3^2.6^2]",
    "[3.4^2.6; 3.6.3.6]#1",
    "[3.4^2.6; 3.6.3.6]#2",
    "[3^3.4^2; 3^2.4.3.4]#1",
    "[3^3.4^2; 3^2.4.3.4]#2",
    "[3^3.4^2; 4^4]#1",
    "[3^3.4^2; 4^4]#2",
    "[3^6; 3^3.4^2]#1",
    "[3^6; 3^3.4^2]#2",
)
"""The two-uniform tilings fabtiles draws, by their two vertex types (``#1``/``#2``: the
smaller cell first)."""

TWO_UNIFORM_NAMES = {
    "[3^6; 3^2.4.3.4]": "3.4.6.4, hexagons split",
    "[3.4.6.4; 3^2.4.3.4]": "3.12.12, dodecagons dissected",
    "[3.4.6.4; 3^3.4^2]": "3.12.12, dodecagons dissected, turned",
    "[3.4.6.4; 3.4^2.6]": "4.6.12, dodecagons dissected",
    "[4.6.12; 3.4.6.4]": "3.4.6.4, a rosette in four merged",
    "[3^6; 3^2.4.12]": "4.6.12, hexagons split",
    "[3.12^2; 3.4.3.12]": "dodecagons on a square lattice",
    "[3^6; 3^2.6^2]": "6.6.6, a hexagon in three split",
    "[3^6; 3^4.6]#1": "triangles, hexagons 3 apart",
    "[3^6; 3^4.6]#2": "triangles, hexagons sqrt 13 apart",
    "[3^2.6^2; 3^4.6]": "triangles, rows of hexagons sharing edges",
    "[3.6.3.6; 3^2.6^2]": "bowties, rows of hexagons sharing edges",
    "[3.4^2.6; 3.6.3.6]#1": "3.6.3.6 rows and squares, staggered",
    "[3.4^2.6; 3.6.3.6]#2": "3.6.3.6 rows and squares, aligned",
    "[3^3.4^2; 3^2.4.3.4]#1": "pairs of squares in zigzag rows",
    "[3^3.4^2; 3^2.4.3.4]#2": "pairs of squares round single squares",
    "[3^3.4^2; 4^4]#1": "two rows of squares, one of triangles",
    "[3^3.4^2; 4^4]#2": "three rows of squares, one of triangles",
    "[3^6; 3^3.4^2]#1": "two rows of triangles, one of squares",
    "[3^6; 3^3.4^2]#2": "three rows of triangles, one of squares",
}
"""Name -> how the tiling is made, for menus and listings."""


def _inradius(p: int) -> float:
    return 1.0 / (2.0 * math.tan(math.pi / p))


def _carved(basis, hexagons) -> tuple:
    """The triangular tiling with a hexagon on each point of ``hexagons`` modulo the sublattice
    ``basis`` (rows, in the triangular lattice's coordinates); the triangles those leave."""
    b = np.array(basis, dtype=float)
    inv = np.linalg.inv(b)

    def reduced(ij) -> tuple:
        f = np.asarray(ij, dtype=float) @ inv
        return tuple(int(v) for v in np.round((f - np.floor(np.round(f, 9))) @ b))

    count = round(abs(np.linalg.det(b)))
    span = range(-2 * count, 2 * count + 1)
    points = sorted({reduced((i, j)) for i in span for j in span})
    holes = {reduced(h) for h in hexagons}
    polys = [(*(i * _E1 + j * _E2), 6, 30.0) for i, j in sorted(holes)]
    for i, j in points:
        corner = i * _E1 + j * _E2
        if not holes & {reduced(q) for q in ((i, j), (i + 1, j), (i, j + 1))}:
            polys.append((*(corner + (0.5, S3 / 6)), 3, -90.0))
        if not holes & {reduced(q) for q in ((i + 1, j), (i, j + 1), (i + 1, j + 1))}:
            polys.append((*(corner + (1.0, S3 / 3)), 3, 90.0))
    return (b[:, :1] * _E1 + b[:, 1:] * _E2).tolist(), polys


def _hexagons_split(cell) -> tuple:
    """Every hexagon of ``cell`` as its six triangles."""
    lattice, polys = cell
    out = []
    for x, y, p, a in polys:
        if p != 6:
            out.append((x, y, p, a))
            continue
        for k in range(6):
            t = math.radians(a + 60 * k)
            out.append((x + S3 / 3 * math.cos(t), y + S3 / 3 * math.sin(t), 3, a + 60 * k))
    return lattice, out


def _dodecagons_dissected(cell, squares_first: bool) -> tuple:
    """Every dodecagon of ``cell`` as a hexagon, six squares and six triangles: the squares on
    the edges at 0, 60, ... degrees from its edge-midpoint direction (``squares_first``) or on
    those at 30, 90, ..."""
    lattice, polys = cell
    out = []
    r12 = _inradius(12)
    for x, y, p, a in polys:
        if p != 12:
            out.append((x, y, p, a))
            continue
        s = 0 if squares_first else 1
        out.append((x, y, 6, a + 30 * s))
        for k in range(12):
            t = a + 30 * k
            r, sides = (r12 - 0.5, 4) if k % 2 == s else (r12 - _inradius(3), 3)
            out.append((x + r * math.cos(math.radians(t)), y + r * math.sin(math.radians(t)), sides, t))
    return lattice, out


def _rosette_merged(cell) -> tuple:
    """3.4.6.4 on twice its lattice, the hexagon on the origin with its six squares and six
    triangles merged into one dodecagon."""
    lattice, polys = cell
    lat = 2 * np.asarray(lattice, dtype=float)
    out = [(0.0, 0.0, 12, 0.0)]
    for i in (0, 1):
        for j in (0, 1):
            shift = i * np.asarray(lattice[0]) + j * np.asarray(lattice[1])
            for x, y, p, a in polys:
                c = np.array([x, y]) + shift
                near = (c[None] - (np.array([(u, v) for u in (-1, 0, 1) for v in (-1, 0, 1)]) @ lat)).tolist()
                if min(math.hypot(*q) for q in near) > _inradius(12) - 0.01:
                    out.append((*c, p, a))
    return lat.tolist(), out


def _rows(rows: str) -> tuple:
    """Rows of squares (``S``) and of triangles (``T``) along x, bottom to top; a row of triangles
    moves the next row's corners half an edge along."""
    h = S3 / 2
    y = offset = 0.0
    polys: list = []
    for row in rows:
        if row == "S":
            polys.append((offset + 0.5, y + 0.5, 4, 0.0))
            y += 1.0
        else:
            polys += [(offset + 0.5, y + h / 3, 3, -90.0), (offset + 1.0, y + 2 * h / 3, 3, 90.0)]
            y += h
            offset += 0.5
    return [[1.0, 0.0], [offset % 1.0, y]], polys


def _hexagon_rows(shift: float) -> tuple:
    """A row of hexagons and bowties (a strip of 3.6.3.6) below a row of squares; the next row's
    hexagons sit over this row's bowties (``shift`` 1) or its hexagons (0)."""
    polys = [(0.0, 0.0, 6, 30.0), (1.0, S3 / 3, 3, 90.0), (1.0, -S3 / 3, 3, -90.0)]
    polys += [(0.0, S3 / 2 + 0.5, 4, 0.0), (1.0, S3 / 2 + 0.5, 4, 0.0)]
    return [[2.0, 0.0], [shift, S3 + 1]], polys


def _dodecagon_squares() -> tuple:
    """Dodecagons sharing edges on a square lattice, a square in each hole (corners to the four
    dodecagons), a triangle on each other edge (shared by two neighbouring dodecagons)."""
    d = 2 + S3
    r = _inradius(12) + _inradius(3)
    polys = [(0.0, 0.0, 12, 0.0), (d / 2, d / 2, 4, 0.0)]
    for k in (1, 2, 4, 5, 7, 8, 10, 11):  # each twice (from both dodecagons): _normal keeps one
        t = math.radians(30 * k)
        polys.append((r * math.cos(t), r * math.sin(t), 3, 30 * k + 180.0))
    return [[d, 0.0], [0.0, d]], polys


def _attached(lattice, steps) -> tuple:
    """A square on the origin, then each polygon of ``steps`` across an edge of one already
    placed: ``(index of that polygon, its edge k, sides)``, edge k the one whose midpoint lies
    ``360 (k + 1) / p`` degrees round from the polygon's edge-midpoint direction."""
    polys = [(0.0, 0.0, 4, 0.0)]
    for parent, k, sides in steps:
        x, y, p, a = polys[parent]
        phi = a + 360.0 * (k + 1) / p
        r = _inradius(p) + _inradius(sides)
        polys.append((x + r * math.cos(math.radians(phi)), y + r * math.sin(math.radians(phi)), sides, phi + 180.0))
    return lattice, polys


def _gauss(lattice) -> np.ndarray:
    """A shortest basis of the lattice (Lagrange-Gauss reduction)."""
    u, v = (np.array(r, dtype=float) for r in lattice)
    while True:
        if u @ u > v @ v:
            u, v = v, u
        m = round(float(u @ v) / float(u @ u))
        if m == 0:
            return np.array([u, v])
        v = v - m * u


def _normal(cell) -> tuple:
    """The cell with a short basis turned so its first vector lies along x (the second above
    it), each polygon moved into the cell once."""
    lat = _gauss(cell[0])
    turn = -math.atan2(lat[0, 1], lat[0, 0])
    c, s = math.cos(turn), math.sin(turn)
    rot = np.array([[c, -s], [s, c]])
    lat = lat @ rot.T
    if lat[1, 1] < 0:
        lat[1] = -lat[1]
    inv = np.linalg.inv(lat)
    polys: dict[tuple, tuple] = {}
    for x, y, p, a in cell[1]:
        f = (rot @ np.array([x, y])) @ inv
        f = f - np.floor(np.round(f, 9))
        f[np.round(f, 9) >= 1.0] = 0.0
        key = tuple(np.round(f, 6).tolist())
        polys.setdefault(key, (*(f @ lat).tolist(), int(p), (a + math.degrees(turn)) % 360.0))
    return [tuple(r) for r in lat.tolist()], list(polys.values())


def two_uniform_cells(archimedean: dict) -> dict:
    """Name -> ``(lattice rows, [(x, y, sides, edge-midpoint angle in degrees), ...])``, edge 1.

    ``archimedean``: the Archimedean cells, in the same form (3.4.6.4, 3.12.12 and 4.6.12 are
    used; the others may be missing).
    """
    cells = {
        "[3^6; 3^2.6^2]": lambda: _carved([(3, 0), (0, 3)], [(0, 0), (1, 1)]),
        "[3^6; 3^4.6]#1": lambda: _carved([(3, 0), (0, 3)], [(0, 0)]),
        "[3^6; 3^4.6]#2": lambda: _carved([(13, 0), (3, 1)], [(0, 0)]),
        "[3^2.6^2; 3^4.6]": lambda: _carved([(5, 0), (1, 1)], [(0, 0)]),
        "[3.6.3.6; 3^2.6^2]": lambda: _carved([(2, 0), (1, 2)], [(0, 0)]),
        "[3.4^2.6; 3.6.3.6]#1": lambda: _hexagon_rows(1.0),
        "[3.4^2.6; 3.6.3.6]#2": lambda: _hexagon_rows(0.0),
        "[3^3.4^2; 4^4]#1": lambda: _rows("SST"),
        "[3^3.4^2; 4^4]#2": lambda: _rows("SSST"),
        "[3^6; 3^3.4^2]#1": lambda: _rows("TTS"),
        "[3^6; 3^3.4^2]#2": lambda: _rows("TTTS"),
        "[3.12^2; 3.4.3.12]": _dodecagon_squares,
        # squares and triangles found by a search of the square-triangle tilings of these two vertex
        # types on small lattices (a cell filled vertex by vertex), kept as the steps that build them
        "[3^3.4^2; 3^2.4.3.4]#1": lambda: _attached(
            [(-(1 + S3 / 2), 0.5), (-1.0, -(2 + S3))],
            [(0, 0, 4), (0, 1, 3), (0, 2, 3), (0, 3, 3), (1, 0, 3), (1, 1, 3)]
            + [(1, 2, 3), (2, 1, 4), (3, 0, 3), (5, 1, 4), (6, 0, 3)],
        ),
        "[3^3.4^2; 3^2.4.3.4]#2": lambda: _attached(
            [(-S3 / 2, -(1.5 + S3)), (-(1.5 + S3), S3 / 2)],
            [(0, 0, 3), (0, 1, 3), (0, 2, 3), (0, 3, 3), (1, 0, 4), (1, 1, 3), (2, 0, 4), (2, 1, 3), (3, 0, 4)]
            + [(3, 1, 3), (4, 0, 4), (4, 1, 3), (5, 1, 3), (6, 0, 3), (7, 1, 3), (8, 0, 3), (13, 0, 4)],
        ),
    }
    if archimedean:
        cells |= {
            "[3^6; 3^2.4.3.4]": lambda: _hexagons_split(archimedean["3.4.6.4"]),
            "[3.4.6.4; 3^2.4.3.4]": lambda: _dodecagons_dissected(archimedean["3.12.12"], False),
            "[3.4.6.4; 3^3.4^2]": lambda: _dodecagons_dissected(archimedean["3.12.12"], True),
            "[3.4.6.4; 3.4^2.6]": lambda: _dodecagons_dissected(archimedean["4.6.12"], True),
            "[4.6.12; 3.4.6.4]": lambda: _rosette_merged(archimedean["3.4.6.4"]),
            "[3^6; 3^2.4.12]": lambda: _hexagons_split(archimedean["4.6.12"]),
        }
    return {name: _normal(cells[name]()) for name in TWO_UNIFORM if name in cells}
