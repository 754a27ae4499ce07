"""Face classes: the faces of a tile's pattern grouped by shape, for colouring.

A **face** is a part of the outline left open by the material: a hole of the region, or
with a frame of 0 a part open to the tile's edge. :func:`face_classes` groups the faces
of a tile by shape, congruent under translation, rotation and reflection, and letters
the classes A, B, C... by decreasing total area in the tile.

A face cut by the tile's edge or by the frame keeps the class of the **whole face** it
is a piece of: for a packing the whole faces are those of the same pattern stroked over
one rectangular period and a margin, not clipped to any outline, and each tile face
takes the class of the whole face holding its representative point (moved into that
period by the packing's translations). So most of the sheet's ~10,000 faces cost a
point look-up, and only the few dozen distinct whole faces are compared shape by shape.
A tile face with no whole face (the ring between a single motif and the frame, a face
larger than the margin) is a class of its own shape.

Congruence is decided with a tolerance, never by rounding alone: faces are sorted by
cheap invariants (the vertex count after dropping collinear vertices, the number of
islands, the area), split where two neighbours differ by more than the tolerance, and
each face is then matched vertex to vertex against the first face of each class of its
run, after the best rotation or reflection.

>>> from fabtiles.pattern.packing import SquarePacking
>>> from fabtiles.pattern.star import Star
>>> from fabtiles.geometry.tile import TileGeometry
>>> tile = TileGeometry("square", 40, SquarePacking(10, Star(n=8, radii=(0.5, 1))), frame=2, stroke=0.6)
>>> fc = face_classes(tile)
>>> [(c.letter, c.count, c.description) for c in fc.classes]
[('A', 4, ''), ('B', 9, '8-point star'), ('C', 12, 'rhombus'), ('D', 4, '6-point star')]
>>> round(fc.of("B").area, 1), round(fc.classes[1].area_mm2, 1)
(342.4, 342.4)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from ..core.errors import ParameterError
from ..core.validate import check_choice
from ..pattern.star import Star
from .contours import polygon_parts

BY = ("shape", "none")
"""The ways faces are grouped: by congruent shape, or all in one class ("none": the two colours)."""

TOLERANCE_MM = 1e-3
"""Largest distance between matched vertices of two faces called congruent (mm), and the
least change along a ring that counts as a vertex (a tenth of it). Measured: the uncut faces of
a class in the table3-3, 3.12.12 and seamless hexagon samples match their first within 4e-7 mm
(areas within 8e-7 relative), so 1 micron leaves a margin of 2,500 and still parts shapes a
laser could tell. The vertex threshold (1e-4 mm off the chord of its neighbours) sits between
that noise and the least real vertex of the samples' faces (4.6e-4 mm off, 13 samples)."""

AREA_TOLERANCE = 1e-5
"""Relative difference of area beyond which two faces are not compared (the run split);
13 times the largest spread of a class's areas measured (8e-7, the seamless hexagon)."""

SLIVER_MM = 1e-6
"""Half the width of the slivers cut off the faces open to the tile's edge (see ``_faces``)."""

MIN_FACE_AREA_MM2 = 1e-9
"""Faces smaller than this are overlay slivers along the outline, not faces (none in the samples)."""

MAX_SIDES = 24
"""Faces of more sides (not stars) are described as "": no polygon a reader would count."""

_NAMES = {
    3: "triangle",
    4: "quadrilateral",
    5: "pentagon",
    6: "hexagon",
    7: "heptagon",
    8: "octagon",
    9: "nonagon",
    10: "decagon",
    12: "dodecagon",
}


@dataclass(frozen=True)
class FaceClass:
    """One class of congruent faces: its letter, how many faces, what they are, their total area."""

    letter: str
    """"A", "B", ... "Z", "AA", "AB", ...: A has the largest total area."""
    count: int
    """Faces of the tile in this class (pieces cut by the edge count as faces)."""
    description: str
    """What the faces are where it is plain ("12-point star", "regular hexagon", "kite"), else ""."""
    area_mm2: float
    """Total area of the class's faces in the tile, mm^2."""


@dataclass(frozen=True)
class FaceClasses:
    """Every face of a tile and its class (see :func:`face_classes`)."""

    faces: np.ndarray
    """Shapely Polygons in file coordinates: the outline minus the region, split into parts."""
    labels: np.ndarray
    """Index into :attr:`classes` of each face."""
    classes: tuple[FaceClass, ...]
    """Sorted by decreasing total area: index 0 is "A"."""

    def of(self, letter: str):
        """The faces of class ``letter`` as one shapely MultiPolygon (file coordinates).

        Raises :class:`~fabtiles.ParameterError` for a letter no class has.
        """
        letters = [c.letter for c in self.classes]
        if letter not in letters:
            raise ParameterError(
                f"face class {letter!r} is not one of this tile's classes ({', '.join(letters) or 'none'}); "
                f"use a letter of face_classes(...).classes",
                param="letter",
            )
        return shapely.multipolygons(self.faces[self.labels == letters.index(letter)])

    def stats(self) -> list[dict]:
        """The classes for a report: ``[{"letter", "count", "description", "area_mm2"}, ...]``.

        >>> FaceClasses(np.empty(0, object), np.empty(0, int), (FaceClass("A", 2, "kite", 1.23456),)).stats()
        [{'letter': 'A', 'count': 2, 'description': 'kite', 'area_mm2': 1.235}]
        """
        return [
            {"letter": c.letter, "count": c.count, "description": c.description, "area_mm2": round(c.area_mm2, 3)}
            for c in self.classes
        ]


def letter(index: int) -> str:
    """The letter of class ``index``: 0 -> "A", 25 -> "Z", 26 -> "AA", 27 -> "AB".

    >>> [letter(i) for i in (0, 25, 26, 27, 701, 702)]
    ['A', 'Z', 'AA', 'AB', 'ZZ', 'AAA']
    """
    out = ""
    index += 1
    while index:
        index, rest = divmod(index - 1, 26)
        out = chr(ord("A") + rest) + out
    return out


def face_classes(tile, *, by: str = "shape", region=None) -> FaceClasses:
    """The faces of ``tile`` and their classes; see the module text.

    Parameters
    ----------
    tile : TileGeometry
        The tile; its outline bounds the faces.
    by : {"shape", "none"}
        ``"shape"``: classes of congruent faces (a piece cut by the edge keeps its whole
        face's class); ``"none"``: one class "A" holding every face.
    region : shapely Polygon or MultiPolygon, optional
        The material, if not ``tile.region()`` (e.g. with its small holes filled).

    Returns
    -------
    FaceClasses

    Raises
    ------
    ParameterError
        ``by`` is not one of the valid values, ``tile`` is not a tile, or ``region`` is
        not valid polygonal geometry.

    Examples
    --------
    >>> from fabtiles.pattern.star import Star
    >>> from fabtiles.geometry.tile import TileGeometry
    >>> tile = TileGeometry("circle", 50, Star(n=6, radii=(0.5, 1)), frame=2, stroke=0.8)
    >>> [(c.letter, c.description) for c in face_classes(tile).classes]
    [('A', ''), ('B', '6-point star')]
    >>> face_classes(tile, by="none").classes[0].description
    'faces'
    """
    from .tile import TileGeometry

    check_choice("by", by, BY)
    if not isinstance(tile, TileGeometry):
        raise ParameterError(
            f"tile must be a TileGeometry (e.g. design.build_tile()), got {type(tile).__name__}", param="tile"
        )
    outline = tile.outline_shape()
    # a region passed in is checked; the tile's own is valid by construction (GEOS's is_valid
    # would be half the work on a sheet)
    faces = _faces(tile.region(), outline) if region is None else _faces(polygon_parts(region), outline)
    areas = shapely.area(faces)
    if not len(faces):
        return FaceClasses(faces, np.empty(0, int), ())
    if by == "none":
        return FaceClasses(faces, np.zeros(len(faces), int), (FaceClass("A", len(faces), "faces", float(areas.sum())),))

    wholes, index, unbounded = _whole_faces(tile, faces)
    own = np.flatnonzero(index < 0)  # tile faces with no whole face: classified by their own shape
    shapes = np.concatenate([wholes, faces[own]])
    free = np.concatenate([unbounded, np.zeros(len(own), bool)])
    item_of = index.copy()
    item_of[own] = len(wholes) + np.arange(len(own))
    used, item_of = np.unique(item_of, return_inverse=True)  # the shapes some tile face needs
    shapes, free = shapes[used], free[used]
    rings = [_ring(p) for p in shapes]
    group = np.empty(len(shapes), int)
    bounded = np.flatnonzero(~free)
    group[bounded] = _congruence_groups(shapes[bounded], [rings[i] for i in bounded]) if len(bounded) else []
    # an unbounded face (the background of stars that never close it) is a class of its own
    group[free] = len(set(group[bounded].tolist())) + np.arange(int(free.sum()))
    label = group[item_of]

    # one entry per group: its first shape describes it; letters by decreasing total area
    ngroups = int(group.max()) + 1
    first = np.array([np.flatnonzero(group == g)[0] for g in range(ngroups)])
    total = np.bincount(label, weights=areas, minlength=ngroups)
    count = np.bincount(label, minlength=ngroups)
    desc = ["" if free[i] else _describe(rings[i], len(shapes[i].interiors)) for i in first]
    # ties (equal total areas within 1e-9 relative) broken by description, then the shape's
    # own area and vertex count, then its vertices: the same design always gets the same letters
    order = sorted(
        range(ngroups),
        key=lambda g: (
            -_rounded(float(total[g])),
            desc[g],
            -_rounded(shapes[first[g]].area),
            len(rings[first[g]]),
            _vertex_key(rings[first[g]]),
        ),
    )
    rank = np.empty(ngroups, int)
    rank[order] = np.arange(ngroups)
    classes = tuple(FaceClass(letter(k), int(count[g]), desc[g], float(total[g])) for k, g in enumerate(order))
    return FaceClasses(faces, rank[label], classes)


def _rounded(x: float) -> float:
    """``x`` to 9 significant digits: float noise in a total does not reorder letters."""
    return float(f"{x:.9g}")


# -- the faces ------------------------------------------------------------------
def _faces(region, outline) -> np.ndarray:
    """``outline - region`` as an array of Polygons: the region's holes (less the material
    lying in them) and the parts of the outline outside every piece of material.
    ``region``: a valid Polygon or MultiPolygon, or its parts (an array of Polygons).

    Read from the region's rings rather than by one GEOS difference, which is several
    times slower on a sheet's thousands of faces.
    """
    parts = region if isinstance(region, np.ndarray) else shapely.get_parts(region)
    parts = parts[~shapely.is_empty(parts)]
    nholes = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), nholes)
    index = np.arange(int(nholes.sum())) - np.repeat(np.cumsum(nholes) - nholes, nholes)  # its number in its part
    holes = shapely.polygons(shapely.get_interior_ring(parts[owner], index))
    shells = shapely.polygons(shapely.get_exterior_ring(parts))
    # a piece of material inside a hole (an island) is taken out of it: its shell, so the
    # island's own holes stay faces of their own
    island = np.zeros(len(parts), bool)
    if len(holes) and len(parts) > 1:
        a, b = shapely.STRtree(holes).query(shapely.point_on_surface(parts), predicate="within")
        island[a] = True
        for k in np.unique(b).tolist():
            holes[k] = shapely.difference(holes[k], shapely.union_all(shells[a[b == k]]))
    faces = [shapely.get_parts(holes)] if len(holes) else []
    top = shells[~island]
    if outline.area - shapely.area(top).sum() > MIN_FACE_AREA_MM2:  # open faces (frame 0)
        open_ = shapely.get_parts(shapely.difference(outline, shapely.union_all(top)))
        # Where a band's edge runs along the outline (the seamless hexagon sample's slanted
        # sides) the two differ by a rounding, and the difference joined up to nine pieces of
        # faces along the edge by slivers 2e-9 mm wide into one "face" of 76 mm^2. An opening
        # by SLIVER_MM cuts the slivers and moves no other edge (mitred corners stay put).
        opened = shapely.buffer(
            shapely.buffer(open_, -SLIVER_MM, join_style="mitre", mitre_limit=1e6),
            SLIVER_MM,
            join_style="mitre",
            mitre_limit=1e6,
        )
        faces.append(shapely.get_parts(opened))
    if not faces:
        return np.empty(0, object)
    faces = np.concatenate(faces)
    faces = faces[(shapely.get_type_id(faces) == 3) & (shapely.area(faces) > MIN_FACE_AREA_MM2)]
    return shapely.orient_polygons(faces)


def _whole_faces(tile, faces):
    """The whole faces the tile's faces are pieces of: ``(wholes, index, unbounded)``,
    ``index[i]`` the whole face of tile face ``i`` (moved by a period of the packing) or -1
    when it has none, ``unbounded[k]`` whether whole face ``k`` runs on without end.

    For a single motif every face is whole already (the motif lies inside its circle) but
    the ring round it, which has no whole face: all -1, each classified by its own shape.
    """
    none = np.full(len(faces), -1)
    pattern = tile.pattern
    if isinstance(pattern, Star):
        return np.empty(0, object), none, np.zeros(0, bool)
    px, py = pattern.period
    cx, cy = tile.centre
    areas = shapely.area(faces)
    # the representative point of each face, moved into the period [-px/2, px/2] x [-py/2, py/2]
    inner = _inner_points(faces)
    pts = inner - (cx, cy)
    pts = pts - np.round(pts / (px, py)) * (px, py)
    moves = np.array([(px, 0.0), (-px, 0.0), (0.0, py), (0.0, -py)])
    # A margin of half a period holds every whole face of the samples (the hex packing's
    # largest face spans 1.8 R). A face reaching the window's edge grows it once to two periods
    # unless the face holds its own point moved by a period: then it runs on without end (the
    # background of stars whose tips never meet), and no window would hold it.
    margin = max(px, py) / 2
    while True:
        window = tile.replace(
            outline="rectangle",
            size=(px + 2 * margin, py + 2 * margin),
            frame=0.0,
            corner_radius=0.0,
            interlace=False,
            border_mm=0.0,
        )
        wholes = _faces(window.region(), window.outline_shape())
        wx, wy = window.centre
        b = shapely.bounds(wholes)
        eps = 1e-6 * (wx + wy)
        open_ = (b[:, 0] < eps) | (b[:, 1] < eps) | (b[:, 2] > 2 * wx - eps) | (b[:, 3] > 2 * wy - eps)
        tree = shapely.STRtree(wholes)
        i, k = tree.query(shapely.points(pts + (wx, wy)), predicate="within")
        reached = np.unique(k[open_[k]])
        if not len(reached) or margin >= 2 * max(px, py):
            break
        own = _inner_points(wholes[reached])
        a, c = tree.query(shapely.points((own[:, None, :] + moves[None]).reshape(-1, 2)), predicate="within")
        if (np.bincount(a[reached[a // len(moves)] == c] // len(moves), minlength=len(reached)) > 0).all():
            break
        margin *= 4
    # the open faces the tile's faces reach, joined where a lattice move takes one into another:
    # pieces of one background (split by the window into two faces in a hex packing of 20-gons
    # that never touch) are one class
    root = np.arange(len(wholes))
    reached = np.unique(k[open_[k]])
    if len(reached):
        lat = _lattice(pattern)
        steps = np.concatenate([moves, lat, -lat, [lat[0] - lat[1], lat[1] - lat[0]]])[:, None, :]
        own = _inner_points(wholes[reached])
        a, c = tree.query(shapely.points((own[None, :, :] + steps).reshape(-1, 2)), predicate="within")
        a = reached[a % len(reached)]
        for x, y in sorted(zip(a[open_[c]].tolist(), c[open_[c]].tolist(), strict=True)):
            rx, ry = _find(root, x), _find(root, y)
            root[max(rx, ry)] = min(rx, ry)
        k = np.array([_find(root, j) for j in k.tolist()], dtype=int)
    index = none.copy()
    # a bounded whole face is no smaller than its piece in the tile (a region passed in may
    # merge faces the pattern keeps apart: then the tile's face is classified by its own shape)
    ok = open_[k] | (areas[i] <= shapely.area(wholes[k]) * (1 + AREA_TOLERANCE))
    if tile.border_mm > 0:  # the border's frieze is no piece of the packing: its faces go by their own shape
        ok &= shapely.contains_xy(tile.field_shape(), *inner[i].T)
    index[i[ok]] = k[ok]
    return wholes, index, open_


def _lattice(pattern) -> np.ndarray:
    """The two lattice vectors of a packing (rows, mm)."""
    lattice = getattr(pattern, "lattice", None)
    return np.asarray(lattice if lattice is not None else pattern._basis() * pattern.radius, dtype=float)


def _find(root: np.ndarray, x: int) -> int:
    """The root of ``x`` in the union-find array ``root``."""
    while root[x] != x:
        root[x] = root[root[x]]
        x = int(root[x])
    return x


def _inner_points(faces) -> np.ndarray:
    """A point well inside each face ``(n, 2)``: GEOS's point on the surface, or for the faces
    where it lies within ``10 x`` :data:`TOLERANCE_MM` of the edge, the centre of the largest disc.

    The point on the surface is the middle of the widest run across the face at its middle
    height; for a face of the seamless hexagon sample with a sliver 2e-9 mm wide along the tile's
    edge (a band's edge and the outline's, a rounding apart) that run was the sliver, and the
    point missed its whole face. The largest disc (about 20 us a face) is kept for those few.
    """
    pts = shapely.point_on_surface(faces)
    near = np.flatnonzero(shapely.distance(pts, shapely.boundary(faces)) < 10 * TOLERANCE_MM)
    if len(near):
        lines = shapely.maximum_inscribed_circle(faces[near], TOLERANCE_MM / 10)
        pts[near] = shapely.get_point(lines, 0)
    return shapely.get_coordinates(pts)


# -- congruence -----------------------------------------------------------------
def _ring(poly) -> np.ndarray:
    """The outer ring's vertices ``(n, 2)``, counter-clockwise, without the closing vertex,
    repeated vertices or vertices that turn the ring by less than :data:`TOLERANCE_MM`."""
    pts = shapely.get_coordinates(poly.exterior)[:-1]
    while len(pts) > 3:
        prev, nxt = np.roll(pts, 1, axis=0), np.roll(pts, -1, axis=0)
        chord = nxt - prev
        length = np.hypot(chord[:, 0], chord[:, 1])
        # the distance of each vertex from the chord joining its neighbours
        rel = pts - prev
        off = np.abs(chord[:, 0] * rel[:, 1] - chord[:, 1] * rel[:, 0]) / np.where(length > 0, length, 1.0)
        off = np.where(length > 0, off, np.hypot(*(pts - prev).T))
        flat = off < TOLERANCE_MM / 10
        if not flat.any():
            break
        # drop every other flat vertex of a run, so a gentle arc loses no more than one chord's worth
        k = np.flatnonzero(flat)
        drop = k[np.r_[True, np.diff(k) > 1]] if len(k) > 1 else k
        pts = np.delete(pts, drop, axis=0)
    return pts


def _edges_turns(pts: np.ndarray):
    """Edge lengths (from each vertex to the next) and turning angles at each vertex."""
    e = np.roll(pts, -1, axis=0) - pts
    length = np.hypot(e[:, 0], e[:, 1])
    heading = np.arctan2(e[:, 1], e[:, 0])
    turn = (heading - np.roll(heading, 1) + math.pi) % (2 * math.pi) - math.pi
    return length, turn


def _congruent(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether rings ``a`` and ``b`` are congruent: some rotation or reflection and a
    translation put every vertex of ``a`` within :data:`TOLERANCE_MM` of one of ``b``'s
    in the same cyclic order.

    Candidate correspondences come from the edge-length and turn sequences (within the
    tolerance), each is then checked on the points by the best rigid fit.
    """
    n = len(a)
    if len(b) != n:
        return False
    la, ta = _edges_turns(a)
    size = max(float(np.ptp(a, axis=0).max()), 1.0)
    idx = (np.arange(n)[:, None] + np.arange(n)[None, :]) % n  # row s: the sequence shifted by s
    for mirrored in (False, True):
        # b mirrored in x and read backwards: still counter-clockwise
        bb = b[::-1] * (-1.0, 1.0) if mirrored else b
        lb, tb = _edges_turns(bb)
        fits = (np.abs(lb[idx] - la).max(axis=1) <= 2 * TOLERANCE_MM) & (
            np.abs(tb[idx] - ta).max(axis=1) <= 4 * TOLERANCE_MM / max(la.min(), TOLERANCE_MM)
        )
        for s in np.flatnonzero(fits):
            q = bb[idx[s]]
            if _fit_distance(a, q) <= TOLERANCE_MM * max(1.0, size / 1000):
                return True
    return False


def _fit_distance(p: np.ndarray, q: np.ndarray) -> float:
    """Largest distance between matched points after the best rotation and translation of ``p`` onto ``q``."""
    pc, qc = p - p.mean(axis=0), q - q.mean(axis=0)
    u, _, vt = np.linalg.svd(pc.T @ qc)
    r = u @ vt
    if np.linalg.det(r) < 0:  # a rotation only: reflections were tried by mirroring q
        u[:, -1] *= -1
        r = u @ vt
    return float(np.hypot(*(pc @ r - qc).T).max())


def _congruence_groups(shapes: np.ndarray, rings: list) -> np.ndarray:
    """A group number for each shape, congruent shapes sharing one; groups numbered by first shape.

    Shapes are sorted by (vertex count, islands, area) and cut into runs where the area
    jumps by more than :data:`AREA_TOLERANCE`: two congruent shapes, whose areas differ by
    far less, always share a run, whatever rounding would do. Within a run each shape is
    matched against the first shape of each group so far.
    """
    n = len(shapes)
    verts = np.array([len(r) for r in rings])
    nisl = shapely.get_num_interior_rings(shapes)
    area = shapely.area(shapes)
    hole_area = area - shapely.area(shapely.polygons(shapely.get_exterior_ring(shapes)))
    order = np.lexsort((area, nisl, verts))
    group = np.full(n, -1)
    reps: list[int] = []  # the first shape of each group, by group number
    start = 0
    while start < n:
        end = _run_end(order, start, verts, nisl, area)
        run_reps: list[int] = []
        for i in order[start:end].tolist():
            for g in run_reps:
                r = reps[g]
                if abs(hole_area[i] - hole_area[r]) <= AREA_TOLERANCE * area[r] and _congruent(rings[r], rings[i]):
                    group[i] = g
                    break
            else:
                group[i] = len(reps)
                run_reps.append(len(reps))
                reps.append(i)
        start = end
    # number the groups by their first shape, so the result does not depend on the sort
    firsts = np.array([np.flatnonzero(group == g).min() for g in range(len(reps))])
    renum = np.empty(len(reps), int)
    renum[np.argsort(firsts)] = np.arange(len(reps))
    return renum[group]


def _run_end(order, start: int, verts, nisl, area) -> int:
    """The end of the run of sorted shapes from ``start``: the same vertex count and islands, no area jump
    over :data:`AREA_TOLERANCE` (see :func:`_congruence_groups`)."""
    n = len(order)
    end = start + 1
    while (
        end < n
        and verts[order[end]] == verts[order[start]]
        and nisl[order[end]] == nisl[order[start]]
        and area[order[end]] - area[order[end - 1]] <= AREA_TOLERANCE * area[order[end]]
    ):
        end += 1
    return end


def _vertex_key(ring: np.ndarray) -> tuple:
    """A last tie-break between classes: the edge lengths sorted, to a micron."""
    length, _ = _edges_turns(ring)
    return tuple(np.round(np.sort(length), 3).tolist())


# -- descriptions ----------------------------------------------------------------
def _describe_convex(length: np.ndarray, turn: np.ndarray, same_len: bool) -> str:
    """The name of a convex face from its edges' lengths and its turns at the vertices (see :func:`_describe`)."""
    n = len(length)
    size = float(length.max())
    interior = math.pi - turn  # interior angle at each vertex
    same_angle = bool(np.ptp(interior) <= 1e-4)
    if same_len and same_angle and n <= MAX_SIDES:
        return {3: "equilateral triangle", 4: "square"}.get(n, f"regular {_NAMES.get(n, f'{n}-gon')}")
    if n == 3:
        return "triangle"
    if n == 4:
        return _describe_quadrilateral(length, size, same_len, same_angle)
    return _NAMES.get(n, f"{n}-gon") if n <= MAX_SIDES else ""


def _describe_quadrilateral(length: np.ndarray, size: float, same_len: bool, same_angle: bool) -> str:
    """A convex quadrilateral's name: rhombus, rectangle, kite (two pairs of adjacent equal edges; edge i
    runs from vertex i to i + 1) or quadrilateral."""
    if same_len:
        return "rhombus"
    if same_angle:
        return "rectangle"

    def near(x, y):
        return abs(x - y) <= 1e-4 * size + TOLERANCE_MM

    if any(near(length[k], length[(k + 1) % 4]) and near(length[(k + 2) % 4], length[(k + 3) % 4]) for k in range(2)):
        return "kite"
    return "quadrilateral"


def _alternates(convex: np.ndarray) -> bool:
    """Whether the vertices turn out and in by turns (a star's points and notches)."""
    return bool((convex[::2].all() and not convex[1::2].any()) or (convex[1::2].all() and not convex[::2].any()))


def _describe(ring: np.ndarray, islands: int = 0) -> str:
    """What a face with outer ring ``ring`` (counter-clockwise) is, where it is plain, else "".

    >>> _describe(np.array([[0, 0], [2, 0], [2, 1], [0, 1]]))
    'rectangle'
    >>> _describe(np.array([[0, 0], [1, -1], [3, 0], [1, 1]]))
    'kite'
    >>> _describe(np.array([[0, 0], [3, -1], [1, 0], [3, 1]]))
    'dart'
    >>> _describe(np.array([[0, 0], [6, 0], [6, 6], [3, 2], [0, 6]]))
    'concave pentagon'
    """
    n = len(ring)
    if islands or n < 3:
        return ""
    length, turn = _edges_turns(ring)
    size = float(length.max())
    same_len = bool(np.ptp(length) <= 1e-4 * size + TOLERANCE_MM)
    convex = turn > 0
    if convex.all():
        return _describe_convex(length, turn, same_len)
    if n >= 6 and n % 2 == 0 and same_len and _alternates(convex):
        return f"{n // 2}-point star"
    if n == 4:
        return "dart"  # the kite's concave partner, as Penrose named it
    # beyond 24 sides a face is no polygon a reader would count (the ring round a motif, an arc's chords)
    return f"concave {_NAMES.get(n, f'{n}-gon')}" if n <= MAX_SIDES else ""
