"""The boundary representation of a stacked part, as a CAD modeller would draw it.

A printed tile is a stack (see :mod:`fabtiles.solid._mesh_build`): polygons raised to
a few levels above a flat bottom. Its B-rep here has planar faces, vertical
cylinders and straight or circular edges, and one face per flat region:

- each connected region at a level is ONE horizontal face with all its holes, and
  the bottom of each solid is one face;
- a vertical wall face per straight run of the boundary: walls of neighbouring
  polygon sides that lie in the same vertical plane and share a vertical edge are
  one face (a straight side of the outline is one face, even where the top of the
  wall steps between levels);
- vertical edges wherever walls of two planes meet (the outline's corners among
  them), split only at the levels where a horizontal face meets them;
- with a ``tolerance_mm``, the walls over each arc of the boundary (arcs found by
  :func:`fabtiles.geometry.arcs.arc_runs`, see :func:`_wall_arcs`) are ONE cylinder
  face, its top and bottom circle edges shared with the flat faces; a whole circle is
  two halves.

Every edge is shared by exactly two faces, in opposite directions, by construction.
The result is plain numpy data (:class:`Brep`); :mod:`fabtiles.export.step_file`
writes it as STEP entities, :mod:`fabtiles.export.step` checks it with OCCT.

Example: a 10 x 10 mm plate 2 mm thick is 6 faces, 12 edges and 8 vertices.

>>> import shapely
>>> from fabtiles.solid._mesh_build import coverage
>>> b = planar_brep(coverage([(shapely.box(0, 0, 10, 10), 2.0)], bottom=0.0))
>>> len(b.faces), len(b.edges), len(b.points)
(6, 12, 8)
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import pairwise
from math import gcd
from typing import Any

import numpy as np

from ..core.errors import FabricationError
from ._mesh_build import QUANTUM, Coverage, Stack, coverage, topology
from .levels import body_layers, dip_z, split_region
from .parts import GRID_SHIFTS, checked_parts


@dataclass(frozen=True)
class Face:
    """A face: its surface and its loops of signed edge numbers.

    A plane (``radius == 0``): through ``origin``, outward ``normal``, ``ref`` a
    direction in it. ``loops[0]`` is the outer loop, counter-clockwise seen from
    outside; the others are holes. Edge ``i`` is ``edges[i]`` run forwards, ``~i``
    backwards.

    A vertical cylinder (``radius > 0``): its axis through ``origin`` along
    ``normal`` (0, 0, 1), ``ref`` the direction from the axis to where its angle
    starts (its seam); ``inward``: the face's outward normal points to the axis
    (the wall of a round hole). One loop: the arc at the bottom, the vertical edge
    up, the arc at the top back, the vertical edge down; a whole circle's loop runs
    up and down the same vertical edge, the seam.
    """

    origin: tuple  # a point of the plane, or of the cylinder's axis (mm)
    normal: tuple  # outward normal (direction ratios), or the cylinder's axis
    ref: tuple  # a direction in the plane (x axis of its placement), or to the cylinder's seam
    loops: tuple  # tuple of tuples of signed edge numbers
    radius: float = 0.0  # > 0: a cylinder of this radius
    inward: bool = False  # a cylinder whose material lies outside it


@dataclass(frozen=True)
class Brep:
    """Points, edges between them (straight or arcs of horizontal circles), faces, and the faces of each solid."""

    points: np.ndarray  # (n, 3) float
    edges: np.ndarray  # (m, 2) point indices, each edge runs from the first to the second
    faces: tuple  # of Face
    solids: tuple  # tuple of tuples of face indices, one closed shell each
    arcs: np.ndarray | None = None
    """(m, 5) per edge: ``(cx, cy, r, sweep, flat)``; ``r > 0``: the edge is an arc of the horizontal
    circle of centre (cx, cy) and radius r, counter-clockwise from its first point to its second
    through ``sweep`` radians (2 pi: a whole circle, both ends one point); ``flat``: the signed area
    between the chords the arc stands for and the straight line between its ends (what the mesh has
    there, for :func:`check_brep`). ``None`` or ``r == 0``: a straight edge."""

    def arc_rows(self) -> np.ndarray:
        """:attr:`arcs`, zeros where there are none."""
        return self.arcs if self.arcs is not None else np.zeros((len(self.edges), 5))


class _Edges:
    """Edges made on demand, keyed so that every face finds the same edge object."""

    def __init__(self):
        self.points = {}
        self.edges = {}
        self.list = []
        self.arcs = {}  # edge number -> (cx, cy, r, sweep, flat)
        self.arc_of = {}  # (low vid, high vid, level) of a chord an arc stands for -> (arc key, its ccw start vid)

    def arc(self, key, pa, pb, row):
        """The arc edge ``key`` from point pa to pb (counter-clockwise), made once."""
        e = self.edges.get(key)
        if e is None:
            e = self.edges[key] = len(self.list)
            self.list.append((pa, pb))
            self.arcs[e] = row
        return e

    def horizontal_or_arc(self, u, v, k):
        """Signed edge from ring vertex u to v at level k: the arc it is a chord of, if any
        (consecutive chords of one arc give the same signed arc: :func:`_collapse`)."""
        hit = self.arc_of.get((min(u, v), max(u, v), k))
        if hit is None:
            return self.horizontal(u, v, k)
        e = self.edges[hit[0]]
        return e if u == hit[1] else ~e

    def point(self, vid, k):
        key = (vid, k)
        p = self.points.get(key)
        if p is None:
            p = self.points[key] = len(self.points)
        return p

    def horizontal(self, u, v, k):
        """Signed edge from ring vertex u to v at level k."""
        key = ("h", min(u, v), max(u, v), k)
        e = self.edges.get(key)
        if e is None:
            e = self.edges[key] = len(self.list)
            self.list.append((self.point(min(u, v), k), self.point(max(u, v), k)))
        return e if u < v else ~e

    def vertical(self, p, ka, kb, corner=None):
        """Signed edge at ring vertex p from level ka to the adjacent split level kb (``corner``: the ring
        position of p it stands at, where two corners of the region meet at p: see :func:`_walls`)."""
        lo, hi = min(ka, kb), max(ka, kb)
        key = ("v", p, lo, hi) if corner is None else ("v", p, lo, hi, corner)
        e = self.edges.get(key)
        if e is None:
            e = self.edges[key] = len(self.list)
            self.list.append((self.point(p, lo), self.point(p, hi)))
        return e if ka < kb else ~e


def _ring_polygons(topo, k):
    """Rings of piece k grouped into polygons: [[outer ring, hole rings...], ...]."""
    polys: list = []
    for r in range(topo.piece_rings[k], topo.piece_rings[k + 1]):
        xy = topo.xy[topo.vid[topo.ring_start[r] : topo.ring_start[r + 1]]]
        area = 0.5 * np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1])
        if area > 0 or not polys:
            polys.append([r])
        else:
            polys[-1].append(r)
    return polys


def _chain(directed, what):
    """Chain directed edges ``[(start node, end node, signed edge), ...]`` into closed loops.

    At a node with several ways on (two loops touching at a point), the first
    unused one is taken: each loop still closes, which is all a face needs.
    """
    out: dict = {}
    for i, (a, _, _) in enumerate(directed):
        out.setdefault(a, []).append(i)
    used = np.zeros(len(directed), bool)
    loops = []
    for i0 in range(len(directed)):
        if used[i0]:
            continue
        loop, i = [], i0
        while not used[i]:
            used[i] = True
            loop.append(i)
            nxt = [j for j in out.get(directed[i][1], ()) if not used[j]]
            if not nxt:
                break
            i = nxt[0]
        if directed[loop[-1]][1] != directed[loop[0]][0]:
            raise FabricationError(f"the B-rep of the {what} has an open loop; nothing was written")
        loops.append(loop)
    return loops


def _loop_area(xy):
    return 0.5 * float(np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1]))


SIDE_TOLERANCE_MM = QUANTUM
"""A boundary point this close to a straight side of the outline lies on it (the grid's rounding)."""


def _onto_sides(xy, sides, outer):
    """Points of the outer boundary on a straight side of the outline, moved exactly onto it.

    On the 2**-10 mm grid a slanted side has no points between its corners: the
    points where the region meets it sit up to ``SIDE_TOLERANCE_MM`` off the
    line through its corners, which would split the side into faces at tiny
    angles. They are put on that line, so that the side is one plane. ``outer`` holds the outer boundary's edges
    ``(u, v)`` (material on the left); along each side a point that would fold
    back stays where it is. Returns the points and each point's side (-1: none).
    """
    out = np.array(xy, float)
    side_of = np.full(len(xy), -1)
    if sides is None or not len(sides) or not len(outer):
        return out, side_of
    sides = np.asarray(sides, float)
    succ = _runs_along_sides(out, sides, outer)
    for k in range(len(sides)):
        _onto_side(k, sides, succ, xy, out, side_of)
    return out, side_of


def _runs_along_sides(xy, sides, outer) -> dict:
    """``{(side, point): next point}``: the outer boundary's edges whose both ends are near the same side.

    A point near two sides (a corner) is in the runs of both.
    """
    import shapely

    tree = shapely.STRtree(shapely.linestrings(sides.reshape(-1, 2, 2)))
    ends = np.unique(np.asarray(outer).ravel())
    pi, si = tree.query(shapely.points(xy[ends]), predicate="dwithin", distance=SIDE_TOLERANCE_MM)
    near: dict = {}  # point -> sides it is near (corners: both of theirs)
    for p, k in zip(ends[pi].tolist(), si.tolist(), strict=True):
        near.setdefault(p, set()).add(k)
    succ: dict = {}
    for u, v in np.asarray(outer).tolist():
        if k_common := (near.get(u, set()) & near.get(v, set())):
            for k in k_common:
                succ.setdefault((k, u), v)
    return succ


def _run_starts(k: int, succ: dict) -> list:
    """The points where the runs along side k start: those with no predecessor along it (a closed run: any one)."""
    preds = {v for (kk, _), v in succ.items() if kk == k}
    return [u for (kk, u) in succ if kk == k and u not in preds] or [u for (kk, u) in succ if kk == k][:1]


def _onto_side(k: int, sides, succ: dict, xy, out, side_of) -> None:
    """Move the points of the runs along side k onto its line, in place (see :func:`_onto_sides`).

    Along a run, a point moves only if it lies past the last one moved (or corner
    passed) and strictly between the side's corners: one that would fold back stays
    where it is, and so does one whose foot on the line is a corner or past it (a
    point of the next side a quantum before the corner is within the tolerance of
    this side too; moved, it would sit on the corner, a wall of no width).
    """
    a, d = sides[k, :2], sides[k, 2:] - sides[k, :2]
    for u in _run_starts(k, succ):
        last, p, seen = -1.0, u, set()
        while p is not None and p not in seen:
            seen.add(p)
            t = float(np.dot(out[p] - a, d) / np.dot(d, d))
            corner = bool(np.all(xy[p] == sides[k, :2]) or np.all(xy[p] == sides[k, 2:]))
            if corner:
                last = max(last, t)
            elif side_of[p] < 0 and max(last, 0.0) < t < 1.0:
                out[p] = a + t * d
                side_of[p] = k
                last = t
            p = succ.get((k, p))


def _keep_pieces_valid(topo, vxy, side_of, outer_loops):
    """Move back the points whose move onto a side made a piece or a bottom loop invalid (in place).

    A sliver of a piece thinner than the move (a region edge within a micron of
    the side) would collapse; its points stay on the grid instead, as they were. So
    does a point moved onto another (a notch a quantum deep along the side: its
    moved end on the point where it meets the side), which GEOS does not call
    invalid (a repeated point) but which is a wall of no width.
    """

    ring_of_point = np.repeat(np.arange(len(topo.ring_start) - 1), np.diff(topo.ring_start))
    poly_of_ring = np.repeat(np.arange(len(topo.piece_rings) - 1), np.diff(topo.piece_rings))
    for _ in range(20):
        moved = side_of >= 0
        rings = np.unique(ring_of_point[moved[topo.vid]])
        if not len(rings):
            return
        bad_points = _points_of_invalid(topo, np.unique(poly_of_ring[rings]).tolist(), vxy, side_of, outer_loops)
        bad = [p for p in set(bad_points) | set(_coinciding(vxy, moved)) if side_of[p] >= 0]
        if not bad:
            return
        vxy[bad] = topo.xy[bad]
        side_of[bad] = -1


def _coinciding(vxy, moved) -> list:
    """The moved points that lie on another point (the points are distinct before the moves)."""
    # one complex key per point: a 1-D unique, much quicker than np.unique's rows
    _, inverse, counts = np.unique(vxy[:, 0] + 1j * vxy[:, 1], return_inverse=True, return_counts=True)
    return np.flatnonzero(moved & (counts[inverse] > 1)).tolist()


def _points_of_invalid(topo, pieces: list, vxy, side_of, outer_loops) -> list:
    """The points of the polygons of ``pieces``, and of the outer loops with a moved point, that are invalid."""
    import shapely

    bad_points = []
    for k in pieces:
        for poly in _piece_polygons(topo, k, vxy):
            if not shapely.is_valid(poly[0]):
                bad_points.extend(poly[1])
    for ids in outer_loops:
        if len(ids) >= 3 and (side_of[ids] >= 0).any() and not shapely.is_valid(shapely.Polygon(vxy[ids])):
            bad_points.extend(ids)
    return bad_points


def _piece_polygons(topo, k, xy):
    """Shapely polygons of piece k at points ``xy``, each with its point ids."""
    import shapely

    out = []
    for rings in _ring_polygons(topo, k):
        ids = [topo.vid[topo.ring_start[r] : topo.ring_start[r + 1]] for r in rings]
        shells = [xy[i] for i in ids]
        out.append((shapely.Polygon(shells[0], shells[1:]), np.concatenate(ids).tolist()))
    return out


def _side_of_wall(pa, pb, side_of, xy, sides, whole):
    """The side a wall from point pa to pb runs along (same direction), or -1.

    ``whole``: ``{(x0, y0, x1, y1): k}`` of the sides (a wall from corner to corner is one), made
    once: a loop over the sides for every wall was most of a circle tile's STEP (its outline
    has hundreds of sides).
    """
    ks = {int(side_of[pa]), int(side_of[pb])} - {-1}
    if len(ks) != 1:
        if ks or sides is None:
            return -1
        # both ends corners: a whole side from corner to corner
        return whole.get((*xy[pa].tolist(), *xy[pb].tolist()), -1)
    (k,) = ks
    a, b = np.asarray(sides[k][:2], float), np.asarray(sides[k][2:], float)
    for p in (pa, pb):  # the other end must be on the side too (or its corner)
        if side_of[p] != k and not ((xy[p] == a).all() or (xy[p] == b).all()):
            return -1
    return k if np.dot(xy[pb] - xy[pa], b - a) > 0 else -1  # xy: the moved points


def planar_brep(
    cov: Coverage,
    *,
    sides=None,
    what: str = "STEP solid",
    tolerance_mm: float = 0.0,
    radii=(),
    cells: bool = False,
    chords=frozenset(),
    recess=None,
) -> Brep:
    """The B-rep of a stack coverage (one closed shell per connected part).

    ``cov`` should hold one piece per level (a single meshing cell), so that each
    flat region is one face; pieces at the same level are merged first.
    ``sides`` (k, 4): the straight sides ``(x0, y0, x1, y1)`` of the outline,
    counter-clockwise; the walls along each are one face, whatever meets it.
    ``tolerance_mm > 0``: the arcs of the boundary within it (:func:`_wall_arcs`)
    become circle edges and their walls cylinders; 0: planar faces only. ``radii``: radii the
    boundary's curves are known to have (a round join's, half the stroke): two chords on one of
    them are an arc too (:func:`fabtiles.geometry.arcs.arc_runs_many`). ``cells``: each piece
    of the coverage (a cell of its grid) is a face of its own, and a one-level body's bottom too
    (see :data:`MAX_FACE_HOLES`); else the pieces at one level are merged first. ``chords``: the
    circles ``(cx, cy, r)`` (:func:`_circle_key`) whose arcs stay chords (see :func:`brep_of_part`).
    ``recess``: a :class:`~fabtiles.geometry.stack.Recess` sunk into the bottom (:func:`_recess_faces`).

    The faces are made in the order walls (arcs first), tops, bottoms: the edges are
    numbered as they are first met, so the order fixes the file written.
    """
    cov = Coverage(_unpinched(_level_pieces(cov, cells)), cov.levels)
    topo = topology(cov, triangulate=False, exact=True)
    z = np.asarray(cov.levels, float)
    ed = _Edges()
    walls = _walls(topo)
    vxy, side_of = _outline_points(topo, sides, what)

    arcs = _wall_arcs(topo, vxy, tolerance_mm, radii) if tolerance_mm > 0 else []
    if chords:
        arcs = [a for a in arcs if _circle_key(a[1], a[2]) not in chords]
    _ends_onto_circles(topo, vxy, arcs)
    faces, in_arc = _arc_faces(ed, topo, vxy, z, arcs, walls.splits, walls.pinched)
    if arcs:  # the other walls stay planar
        walls = walls.without(in_arc)
    wall_edges, keys = _plain_walls(ed, topo, walls, vxy, side_of, sides)
    faces += _wall_faces(ed, walls, wall_edges, keys, vxy, z, sides, what)
    faces += _top_faces(ed, topo, z, reverse=False)
    if recess is not None:
        # the recess's points are numbered after the ring points, its roof's level after the levels
        walls_and_roof, holes, points = _recess_faces(ed, len(vxy), len(z), recess)
        vxy, z = np.concatenate([vxy, points]), np.append(z, recess.depth)
        faces += _bottom_faces(ed, topo, vxy, z, what, recess_holes=holes)
        faces += walls_and_roof
    elif cells and len(cov.levels) == 2:  # one level: each top's bottom beneath it, its loops run backwards
        faces += _top_faces(ed, topo, z, reverse=True)
    else:
        faces += _bottom_faces(ed, topo, vxy, z, what)
    return _finish(ed, vxy, z, faces, what)


def _recess_faces(ed: _Edges, first: int, level: int, recess) -> tuple[list, list, np.ndarray]:
    """``(faces, holes, points)``: a recess sunk into the bottom, as faces on the edges of ``ed``.

    Its points are vertices ``first + k``, at level 0 and at ``level`` (its roof's). The
    faces are a plane wall over each edge of its rings, its roof (one face per polygon,
    facing down) and each island it rings (the hole of a digit's loop: bottom, at level
    0); ``holes`` are its outer rings as holes of the bottom, ``(loop, xy)`` as
    :func:`_holes_in_parts` takes them.
    """
    import shapely

    faces: list = []
    holes: list = []
    pts: list = []
    n = first

    def ring_ids(ring):
        nonlocal n
        xy = np.asarray(ring.coords, float)[:-1]
        pts.append(xy)
        ids = list(range(n, n + len(xy)))
        n += len(xy)
        return ids, xy

    for poly in shapely.get_parts(shapely.orient_polygons(recess.region)):
        rings = [ring_ids(r) for r in (poly.exterior, *poly.interiors)]
        roof = []
        for k, (ids, xy) in enumerate(rings):
            pairs = list(zip(ids, ids[1:] + ids[:1], strict=True))
            for (a, b), (pa, pb) in zip(pairs, zip(xy, np.roll(xy, -1, axis=0), strict=True), strict=True):
                # the recess lies left of a -> b: its wall faces it, run as a wall of the edge b -> a
                loop = (
                    ed.horizontal(b, a, 0),
                    ed.vertical(a, 0, level),
                    ed.horizontal(a, b, level),
                    ed.vertical(b, level, 0),
                )
                dx, dy = (pa - pb).tolist()
                faces.append(Face((float(pb[0]), float(pb[1]), 0.0), (dy, -dx, 0.0), (dx, dy, 0.0), (loop,)))
            roof.append(tuple(ed.horizontal(b, a, level) for a, b in reversed(pairs)))
            bottom = tuple(ed.horizontal(a, b, 0) for a, b in pairs)
            if k == 0:
                holes.append((bottom, xy))
            else:  # an island the recess rings: bottom
                faces.append(Face((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (bottom,)))
        faces.append(Face((0.0, 0.0, float(recess.depth)), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0), tuple(roof)))
    return faces, holes, np.concatenate(pts)


def _level_pieces(cov: Coverage, cells: bool) -> list:
    """The coverage's pieces as ``[(MultiPolygon, level), ...]``, by level, oriented.

    The pieces at one level are merged, so that a flat region is one face whatever
    the coverage's cells; with ``cells`` each cell keeps its own piece (a face each).
    """
    import shapely

    by_level: dict = {}
    for geom, lvl in cov.pieces:
        by_level.setdefault(int(lvl), []).append(geom)
    pieces = []
    for lvl, geoms in sorted(by_level.items()):
        for merged in geoms if cells else [geoms[0] if len(geoms) == 1 else shapely.coverage_union_all(geoms)]:
            if merged.geom_type == "Polygon":  # one polygon (a flush mosaic's whole top): as the others, a multi
                merged = shapely.MultiPolygon([merged])
            pieces.append((shapely.orient_polygons(merged), lvl))
    return pieces


@dataclass(frozen=True)
class _Walls:
    """The walls of a topology: one per ring edge whose neighbour across it is lower.

    ``at``: their ring positions; ``u``, ``v``: the vertices at their ends (material on
    the left); ``lo``, ``hi``: their bottom and top levels; ``splits``: per vertex, the
    levels where the walls meeting there start or stop (its vertical edges' ends);
    ``pinched``: the vertices where two corners of the region meet (two walls start there
    over common levels), whose vertical edges are one per corner.
    """

    at: np.ndarray
    u: list
    v: list
    lo: list
    hi: list
    splits: dict
    pinched: frozenset = frozenset()

    def corners(self, topo, k: int) -> tuple:
        """The corners (ring positions) of wall ``k``'s two ends where they are pinched vertices, else None."""
        at = int(self.at[k])
        a = at if self.u[k] in self.pinched else None
        b = int(topo.nxt[at]) if self.v[k] in self.pinched else None
        return a, b

    def without(self, dropped: np.ndarray) -> _Walls:
        """These walls less those at the ring positions marked in ``dropped`` (the arcs' walls)."""
        keep = np.flatnonzero(~dropped[self.at])
        return _Walls(
            self.at[keep],
            [self.u[i] for i in keep],
            [self.v[i] for i in keep],
            [self.lo[i] for i in keep],
            [self.hi[i] for i in keep],
            self.splits,
            self.pinched,
        )


def _walls(topo) -> _Walls:
    """The walls of ``topo`` and the levels at which each vertex's vertical edges are split."""
    u_all, v_all = topo.vid, topo.vid[topo.nxt]
    w = np.flatnonzero((topo.level > topo.out_level) & (u_all != v_all))
    wu, wv = u_all[w].tolist(), v_all[w].tolist()
    wlo, whi = topo.out_level[w].tolist(), topo.level[w].tolist()
    # split levels at each vertex: the bottoms and tops of the walls that meet there
    splits: dict = {}
    starts: dict = {}
    pinched = set()
    for a, b, lo, hi in zip(wu, wv, wlo, whi, strict=True):
        for p in (a, b):
            s = splits.setdefault(p, set())
            s.add(lo)
            s.add(hi)
        # a second wall starting at a over common levels: two corners of the region meet at a
        if any(lo < h and lo2 < hi for lo2, h in starts.get(a, ())):
            pinched.add(a)
        starts.setdefault(a, []).append((lo, hi))
    return _Walls(w, wu, wv, wlo, whi, {p: sorted(s) for p, s in splits.items()}, frozenset(pinched))


def _vertical_run(ed: _Edges, splits: dict, p, lo, hi, up: bool, corner=None) -> list:
    """Signed vertical edges at vertex p from level lo to hi (``up``) or from hi to lo.

    Each is ``(start node, end node, signed edge)``, one per pair of adjacent split
    levels of p, so that every face beside p meets the same edges (at a pinched vertex,
    every face of the same ``corner``).
    """
    ks = [k for k in splits[p] if lo <= k <= hi]
    pairs = list(pairwise(ks))
    if up:
        return [(ed.point(p, a), ed.point(p, b), ed.vertical(p, a, b, corner)) for a, b in pairs]
    return [(ed.point(p, b), ed.point(p, a), ed.vertical(p, b, a, corner)) for a, b in reversed(pairs)]


def _outline_points(topo, sides, what: str):
    """The ring points, those of the outer boundary on a straight side moved onto it: ``(xy, side_of)``.

    See :func:`_onto_sides`; the moves that would make a piece or a bottom loop
    invalid are undone (:func:`_keep_pieces_valid`).
    """
    u_all, v_all = topo.vid, topo.vid[topo.nxt]
    outer = np.flatnonzero((topo.out_level == 0) & (u_all != v_all))
    vxy, side_of = _onto_sides(topo.xy, sides, np.column_stack([u_all[outer], v_all[outer]]))
    outer_loops = [
        [int(u_all[outer[i]]) for i in lp] for lp in _chain([(int(u_all[e]), int(v_all[e]), e) for e in outer], what)
    ]
    _keep_pieces_valid(topo, vxy, side_of, outer_loops)
    return vxy, side_of


def _ends_onto_circles(topo, vxy, arcs) -> None:
    """Move the ends of the arcs marked ``onto`` (a whole circle's halves) onto their circle, in place."""
    u_all, v_all = topo.vid, topo.vid[topo.nxt]
    for at, centre, radius, _, onto in arcs:
        if onto:
            for p in (int(u_all[at[0]]), int(v_all[at[-1]])):
                d = vxy[p] - centre
                vxy[p] = centre + d * (radius / np.hypot(d[0], d[1]))


def _arc_faces(ed: _Edges, topo, vxy, z, arcs, splits, pinched=frozenset()) -> tuple[list, np.ndarray]:
    """One cylinder face per arc of walls, its circle edges shared with the flat faces.

    Returns the faces and, per ring position, whether its wall is in an arc (those
    walls are not planar faces). Each arc's chords at its two levels are recorded in
    ``ed.arc_of``, so that the flat faces take the arc for them.
    """
    u_all, v_all = topo.vid, topo.vid[topo.nxt]
    in_arc = np.zeros(len(u_all), bool)
    faces = []
    for j, (at, centre, radius, sweep, _) in enumerate(arcs):
        in_arc[at] = True
        lo, hi = int(topo.out_level[at[0]]), int(topo.level[at[0]])
        chain = u_all[at].tolist() + [int(v_all[at[-1]])]
        ccw = sweep > 0
        flat = _loop_area(vxy[chain])  # the chords and the line back from the last vertex to the first
        a_vid, b_vid = (chain[0], chain[-1]) if ccw else (chain[-1], chain[0])
        row = (float(centre[0]), float(centre[1]), float(radius), float(abs(sweep)), flat if ccw else -flat)
        signed = {}
        for lvl in (lo, hi):
            e = ed.arc(("a", j, lvl), ed.point(a_vid, lvl), ed.point(b_vid, lvl), row)
            signed[lvl] = e if ccw else ~e
            for x, y in pairwise(chain):
                ed.arc_of[(min(x, y), max(x, y), lvl)] = (("a", j, lvl), x if ccw else y)
        # the chain runs with the material on its left, as a wall's bottom edge does
        end = int(topo.nxt[at[-1]]) if chain[-1] in pinched else None  # corners, as _Walls.corners gives them
        start = int(at[0]) if chain[0] in pinched else None
        loop = [signed[lo]] + [e for _, _, e in _vertical_run(ed, splits, chain[-1], lo, hi, up=True, corner=end)]
        loop += [~signed[hi]] + [e for _, _, e in _vertical_run(ed, splits, chain[0], lo, hi, up=False, corner=start)]
        ref = seam_direction(vxy[a_vid] - centre, abs(sweep))
        faces.append(
            Face(
                (float(centre[0]), float(centre[1]), float(z[lo])),
                (0.0, 0.0, 1.0),
                (float(ref[0]), float(ref[1]), 0.0),
                (tuple(loop),),
                radius=float(radius),
                inward=not ccw,
            )
        )
    return faces, in_arc


def _plain_walls(ed: _Edges, topo, walls: _Walls, vxy, side_of, sides) -> tuple[list, list]:
    """Each planar wall's directed edges and the key of its vertical plane: ``(wall_edges, keys)``.

    A wall's edges are ``(start node, end node, signed edge)``: along its bottom, up
    its end, back along its top, down its start. Walls with equal keys lie in one
    plane: a straight side of the outline, or the line through two grid points (an
    exact integer key); any other wall is a plane of its own.
    """
    ij = np.round(topo.xy / QUANTUM).astype(np.int64)
    on_grid = np.all(ij * QUANTUM == topo.xy, axis=1)
    sides_arr: Any = None if sides is None else np.asarray(sides, float)  # read only where sides are given
    whole = None if sides is None else {tuple(row): k for k, row in enumerate(sides_arr.tolist())}
    wall_edges = []
    keys: list[tuple] = []
    for k, (a, b, lo, hi) in enumerate(zip(walls.u, walls.v, walls.lo, walls.hi, strict=True)):
        corner_a, corner_b = walls.corners(topo, k)
        loop = [(ed.point(a, lo), ed.point(b, lo), ed.horizontal(a, b, lo))]
        loop += _vertical_run(ed, walls.splits, b, lo, hi, up=True, corner=corner_b)
        loop.append((ed.point(b, hi), ed.point(a, hi), ed.horizontal(b, a, hi)))
        loop += _vertical_run(ed, walls.splits, a, lo, hi, up=False, corner=corner_a)
        wall_edges.append(loop)
        k = _side_of_wall(a, b, side_of, vxy, sides_arr, whole)
        if k >= 0:  # along a straight side of the outline: its plane
            x0, y0, x1, y1 = sides_arr[k]
            keys.append(("side", k, x1 - x0, y1 - y0))
        elif side_of[a] >= 0 or side_of[b] >= 0 or not (on_grid[a] and on_grid[b]):  # a plane of its own
            keys.append(("own", len(keys), *(vxy[b] - vxy[a]).tolist()))
        else:  # exact integer key of the line through two grid points
            dx, dy = (ij[b] - ij[a]).tolist()
            g = gcd(dx, dy)
            dx, dy = dx // g, dy // g
            keys.append((dx, dy, dy * int(ij[a, 0]) - dx * int(ij[a, 1])))
    return wall_edges, keys


def _wall_faces(ed: _Edges, walls: _Walls, wall_edges, keys, vxy, z, sides, what: str) -> list:
    """The planar wall faces: the walls in one plane that share a vertical edge are one face."""
    groups = _plane_groups(wall_edges, keys)
    pts = _node_xyz(ed, vxy, z)  # every wall node exists by now
    sides_arr: Any = None if sides is None else np.asarray(sides, float)
    faces = []
    for members in groups:
        key = keys[members[0]]
        dx, dy = key[-2:] if isinstance(key[0], str) else key[:2]
        a0 = walls.u[members[0]]
        origin = (float(vxy[a0, 0]), float(vxy[a0, 1]), float(z[walls.lo[members[0]]]))
        if key[0] == "side":
            origin = (float(sides_arr[key[1], 0]), float(sides_arr[key[1], 1]), origin[2])
        normal, ref = (float(dy), float(-dx), 0.0), (float(dx), float(dy), 0.0)
        if len(members) == 1:
            faces.append(Face(origin, normal, ref, (tuple(e for _, _, e in wall_edges[members[0]]),)))
            continue
        faces.append(Face(origin, normal, ref, _merged_wall_loops(members, wall_edges, pts, dx, dy, what)))
    return faces


def _plane_groups(wall_edges, keys) -> list:
    """The walls grouped into faces: two walls with equal plane keys that share a vertical edge are joined."""
    users: dict = {}
    for i, loop in enumerate(wall_edges):
        for _, _, e in loop:
            users.setdefault(e if e >= 0 else ~e, []).append(i)
    return _groups(
        len(wall_edges), (us for us in users.values() if len(us) == 2 and us[0] != us[1] and keys[us[0]] == keys[us[1]])
    )


def _merged_wall_loops(members, wall_edges, pts, dx, dy, what: str) -> tuple:
    """The loops of the face of several walls in one plane, the outer one first.

    The edges two of its walls share lie inside the face and are dropped; the rest
    are chained. The outer loop is the one of largest area in the plane's own
    (along, up) coordinates.
    """
    count: dict = {}
    for i in members:
        for _, _, e in wall_edges[i]:
            key = e if e >= 0 else ~e
            count[key] = count.get(key, 0) + 1
    directed = [d for i in members for d in wall_edges[i] if count[d[2] if d[2] >= 0 else ~d[2]] == 1]
    loops = _chain(directed, what)
    dirn = np.array([dx, dy], float) / np.hypot(dx, dy)

    def area(loop):
        p = pts[[directed[i][0] for i in loop]]
        return _loop_area(np.column_stack([p[:, :2] @ dirn, p[:, 2]]))

    loops.sort(key=area, reverse=True)
    return tuple(tuple(directed[i][2] for i in lp) for lp in loops)


def _top_faces(ed: _Edges, topo, z, *, reverse: bool) -> list:
    """A horizontal face per polygon of each piece: its top at the piece's level, or (``reverse``)
    its bottom at level 0, its loops run backwards."""
    faces = []
    for k in range(len(topo.piece_level)):
        lvl = 0 if reverse else int(topo.piece_level[k])
        for rings in _ring_polygons(topo, k):
            loops = []
            for r in rings:
                idx = np.arange(topo.ring_start[r], topo.ring_start[r + 1])
                if reverse:
                    idx = idx[::-1]
                uu, vv = topo.vid[idx].tolist(), topo.vid[topo.nxt[idx]].tolist()
                if reverse:
                    uu, vv = vv, uu
                loops.append(
                    _collapse([ed.horizontal_or_arc(a, b, lvl) for a, b in zip(uu, vv, strict=True) if a != b])
                )
            normal = (0.0, 0.0, -1.0) if reverse else (0.0, 0.0, 1.0)
            faces.append(Face((0.0, 0.0, float(z[lvl])), normal, (1.0, 0.0, 0.0), tuple(loops)))
    return faces


def _bottom_faces(ed: _Edges, topo, vxy, z, what: str, recess_holes=()) -> list:
    """The bottom faces: the ring edges with nothing beside them, run backwards, each hole in its part.

    The loops are sorted by their side seen from below: outer loops are faces, each
    hole goes to the smallest outer loop that covers it; so do ``recess_holes`` (a recess's,
    ``(loop of signed edges, xy)``).
    """
    u_all, v_all = topo.vid, topo.vid[topo.nxt]
    b = np.flatnonzero((topo.out_level == 0) & (u_all != v_all))
    # (an arc's chords give one edge: its ends from the edge itself)
    signed = dict.fromkeys(
        ed.horizontal_or_arc(vv, uu, 0) for uu, vv in zip(u_all[b].tolist(), v_all[b].tolist(), strict=True)
    )
    directed = [(*(ed.list[e] if e >= 0 else ed.list[~e][::-1]), e) for e in signed]
    loops = _chain(directed, what)
    pts = _node_xyz(ed, vxy, z)
    outers: list = []
    holes: list = []
    for lp in loops:
        xy = _loop_points([directed[i][2] for i in lp], ed.list, ed.arcs, pts)
        (outers if _loop_area(xy) < 0 else holes).append((lp, xy))  # seen from above, reversed
    bottom_loops = [[tuple(directed[i][2] for i in lp)] for lp, _ in outers]
    for j, lp in _holes_in_parts(outers, holes, what):
        bottom_loops[j].append(tuple(directed[i][2] for i in lp))
    for j, loop in _holes_in_parts(outers, list(recess_holes), what):
        bottom_loops[j].append(loop)
    return [Face((0.0, 0.0, float(z[0])), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0), tuple(loops_)) for loops_ in bottom_loops]


def _holes_in_parts(outers: list, holes: list, what: str) -> list:
    """``[(outer number, hole), ...]``: each bottom hole ``(loop, xy)`` with the smallest outer loop covering it."""
    import shapely

    if not holes:
        return []
    polys = [shapely.Polygon(xy) for _, xy in outers]
    tree = shapely.STRtree(polys)
    out = []
    for lp, xy in holes:
        probe = shapely.Point(xy[0])
        hits = [j for j in tree.query(probe) if polys[j].covers(probe)]
        if not hits:
            raise FabricationError(f"the B-rep of the {what} has a bottom hole outside every part; nothing was written")
        out.append((min(hits, key=lambda j: polys[j].area), lp))
    return out


def _unpinched(pieces: list) -> list:
    """``[(MultiPolygon, level), ...]`` with each pinched polygon split into valid ones where it touches itself.

    A meshing cell is clipped out of the region along its lines; where the region's
    boundary only touches a cell line at one of its vertices (a sharp corner of an
    interlace dip resting on the line), the clipped piece touches itself there: its
    ring runs along the line past that vertex and back to it. A mesh does not mind;
    a face must be valid. The piece is split there (GEOS :func:`shapely.make_valid`,
    which adds no point off the grid: the touching vertex is already one), and that
    vertex is put into the edges of the other pieces it lies on (the neighbour across
    the line), so that every edge still has its twin.
    """
    import shapely

    parts = [shapely.get_parts(g) for g, _ in pieces]
    flat = np.concatenate(parts) if parts else np.empty(0, object)
    bad = np.flatnonzero(~shapely.is_valid(flat))
    if not len(bad):
        return pieces
    owner = np.repeat(np.arange(len(pieces)), [len(p) for p in parts])
    fixed: dict[int, list] = {}
    added: list[tuple[float, ...]] = []
    for i in bad.tolist():
        split = _pinch_split(flat[i])
        if split is None:
            continue  # not a pinch on its own vertices: left for check_brep to refuse
        fixed[i], old = split
        added.extend(old)  # the touching vertices among them, to be put into the neighbours' edges
    if not fixed:
        return pieces
    pins = np.unique(np.asarray(added, dtype=np.float64), axis=0)
    out: list[list] = [[] for _ in pieces]
    for i, poly in enumerate(flat):
        for g in fixed.get(i, [poly]):
            out[owner[i]].append(_with_points_on_edges(g, pins))
    return [
        (shapely.orient_polygons(shapely.MultiPolygon(polys)), lvl) for polys, (_, lvl) in zip(out, pieces, strict=True)
    ]


def _pinch_split(poly):
    """``(polygons, poly's points)``: an invalid polygon split where it touches itself, or None when
    the split would add a point or change the area (not a pinch on its own vertices)."""
    import shapely

    split = shapely.make_valid(poly, method="structure", keep_collapsed=False)
    polys = [g for g in shapely.get_parts(split) if g.geom_type == "Polygon" and g.area > 0]
    if not polys:
        return None
    old = {tuple(c) for c in shapely.get_coordinates(poly).tolist()}
    new = {tuple(c) for c in shapely.get_coordinates(polys).tolist()}
    if not new <= old or abs(sum(g.area for g in polys) - poly.area) > 1e-9 * max(poly.area, 1.0):
        return None
    return polys, old


def _with_points_on_edges(poly, pins):
    """``poly`` with each of the grid points ``pins`` that lies inside one of its edges made a vertex there."""
    import shapely

    lo, hi = np.asarray(poly.bounds[:2]), np.asarray(poly.bounds[2:])
    pins = pins[np.all((pins >= lo) & (pins <= hi), axis=1)]
    if not len(pins):
        return poly
    grid = np.round(pins / QUANTUM).astype(np.int64)
    rings = []
    for ring in (poly.exterior, *poly.interiors):
        xy = np.asarray(ring.coords)[:-1]
        ij = np.round(xy / QUANTUM).astype(np.int64)
        out = []
        for k in range(len(xy)):
            a, b = ij[k], ij[(k + 1) % len(xy)]
            d, rel = b - a, grid - a
            # exactly on the segment (integer grid coordinates), strictly between its ends
            t = rel @ d
            on = (rel[:, 0] * d[1] - rel[:, 1] * d[0] == 0) & (t > 0) & (t < d @ d)
            out.append(xy[k : k + 1])
            if on.any():
                out.append(pins[on][np.argsort(t[on])])
        rings.append(np.concatenate(out))
    return shapely.Polygon(rings[0], rings[1:])


def _finish(ed: _Edges, vxy, z, faces: list, what: str) -> Brep:
    """The B-rep of ``faces`` on the edges and points ``ed`` made, compacted (:func:`_compact`)."""
    points = _node_xyz(ed, vxy, z)
    edges = np.array(ed.list, dtype=np.int64).reshape(-1, 2)
    arc_rows = None
    if ed.arcs:
        arc_rows = np.zeros((len(edges), 5))
        arc_rows[list(ed.arcs)] = list(ed.arcs.values())
    return _compact(Brep(points, edges, tuple(faces), _solids(faces, len(edges)), arc_rows), what)


def _compact(brep: Brep, what: str) -> Brep:
    """Drop the edges inside merged faces, and points no edge uses; renumber.

    Every edge left must be used once in each direction: a closed, manifold shell.
    """
    uses = np.zeros((len(brep.edges), 2), np.int64)
    for face in brep.faces:
        for loop in face.loops:
            for e in loop:
                uses[e if e >= 0 else ~e, int(e < 0)] += 1
    used = uses.any(axis=1)
    if np.any(uses[used] != 1):
        raise FabricationError(
            f"the B-rep of the {what} has an edge joining more than two faces "
            "(the region touches itself at a point); nothing was written"
        )
    new = np.cumsum(used) - 1
    faces = tuple(
        Face(
            f.origin,
            f.normal,
            f.ref,
            tuple(tuple(int(new[e]) if e >= 0 else ~int(new[~e]) for e in loop) for loop in f.loops),
            f.radius,
            f.inward,
        )
        for f in brep.faces
    )
    edges = brep.edges[used]
    keep = np.zeros(len(brep.points), bool)
    keep[edges.ravel()] = True
    renum = np.cumsum(keep) - 1
    arcs = None if brep.arcs is None else brep.arcs[used]
    return Brep(brep.points[keep], renum[edges], faces, brep.solids, arcs)


ARC_SAGITTA_MM = 0.001
"""Largest gap between an arc and the chords :func:`_loop_points` draws it with (for GEOS's checks)."""


def _loop_points(loop, edges, arcs, pts) -> np.ndarray:
    """The x, y of a loop of signed edges: each edge's start, and points along each arc.

    ``arcs``: a mapping (or array) of edge number -> ``(cx, cy, r, sweep, flat)`` (r = 0:
    straight). The arcs are drawn by chords within :data:`ARC_SAGITTA_MM`, for GEOS:
    the loop's side and the faces' validity.
    """
    loop = np.asarray(loop, np.int64)
    index = np.where(loop >= 0, loop, ~loop)
    is_arc = _are_arcs(index, arcs)
    if not is_arc.any():  # straight edges only (most loops): their starts
        ends = np.asarray(edges)[index] if not isinstance(edges, list) else np.array([edges[e] for e in index])
        return pts[np.where(loop >= 0, ends[:, 0], ends[:, 1]), :2]
    out = []
    for s in loop.tolist():
        e = s if s >= 0 else ~s
        a, b = edges[e]
        out.append(pts[a if s >= 0 else b, :2])
        row = arcs.get(e) if isinstance(arcs, dict) else arcs[e]
        if row is None or row[2] <= 0:
            continue
        inner = _arc_inner_points(row, pts[a])
        out.extend(inner if s >= 0 else inner[::-1])
    return np.asarray(out, float).reshape(-1, 2)


def _are_arcs(index, arcs) -> np.ndarray:
    """Whether each of the edges ``index`` is an arc, ``arcs`` a mapping or an array (see :func:`_loop_points`)."""
    if isinstance(arcs, dict):
        return np.fromiter((e in arcs for e in index.tolist()), bool, len(index))
    return np.asarray(arcs)[index, 2] > 0


def _arc_inner_points(row, start) -> np.ndarray:
    """The points inside an arc ``(cx, cy, r, sweep, ...)`` from ``start``, counter-clockwise, its
    chords within :data:`ARC_SAGITTA_MM` (at least four)."""
    cx, cy, r, sweep = (float(v) for v in row[:4])
    step = 2.0 * np.arccos(max(1.0 - ARC_SAGITTA_MM / r, -1.0))
    n = max(4, int(np.ceil(sweep / step)))
    t0 = np.arctan2(start[1] - cy, start[0] - cx)
    t = t0 + sweep * np.arange(1, n) / n
    return np.column_stack([cx + r * np.cos(t), cy + r * np.sin(t)])


def seam_direction(start, sweep: float) -> np.ndarray:
    """The direction, from a circle's centre, opposite the middle of its arc from ``start`` (counter-clockwise,
    ``sweep`` radians): where a circle's or a cylinder's angle starts, away from the arc's ends.

    With the angle starting at an end, OCCT's STEP reader may put that end at 2 pi
    instead of 0, and the face or edge is invalid (measured: every cylinder face
    invalid that way).

    >>> np.round(seam_direction(np.array([2.0, 0.0]), np.pi), 12).tolist() == [0.0, -1.0]
    True
    """
    t = np.arctan2(start[1], start[0]) + sweep / 2 + np.pi
    return np.array([np.cos(t), np.sin(t)])


def _collapse(loop) -> tuple:
    """A loop's signed edges with the repeats of one arc (its chords, in a row) made one, cyclically.

    >>> _collapse([5, 7, 7, 7, 2, 5])
    (5, 7, 2)
    """
    out = [e for i, e in enumerate(loop) if i == 0 or e != loop[i - 1]]
    while len(out) > 1 and out[0] == out[-1]:
        out.pop()
    return tuple(out)


ON_LINE_MM = 2 * QUANTUM
"""A vertex this close to the line between its neighbours, and between them, is left out of the arc search
(see :func:`_wall_arcs`)."""


def _wall_arcs(topo, xy, tolerance_mm: float, radii=()) -> list:
    """The arcs of the walls: ``[(ring positions, centre, radius, sweep, onto), ...]``.

    A ring's edges with a wall beside them (the piece on their left higher than the one on
    their right) are cut where the wall's bottom level changes, where it stops, and at the
    vertices where more than two edges of the boundary meet (a vertical edge of another
    face stands there); each stretch is then searched for arcs within ``tolerance_mm``
    (:func:`fabtiles.geometry.arcs.arc_runs`, each arc through its end vertices). A whole
    ring without a cut is searched as a closed ring: a round hole. ``sweep`` is signed
    along the ring (positive: counter-clockwise). The points within :data:`ON_LINE_MM` of
    the lines between the others (Douglas-Peucker, GEOS) are left out of the search: a
    circle outline's chords hold such points wherever the region's noding met them, up
    to the chords' sagitta off the circle, and each would cut the circle there
    (measured: the 100 mm circle outline in 28 arcs of radii 49.68 to 50.13 mm instead
    of one circle); the arc found passes by them within that sagitta. All the stretches
    are searched in one pass (:func:`~fabtiles.geometry.arcs.arc_runs_many`).

    A whole circle is two arcs, each from one of two opposite vertices to the other,
    and ``onto`` is True: those vertices are to be moved onto the circle (by at most
    :func:`~fabtiles.geometry.arcs.fit_distance`, 2 micrometres at 0.02 mm), which is
    fitted to all its vertices. Two halves and not one closed circle: a closed edge
    on a cylinder is a seam, which OCCT's STEP reader makes only from a ``SEAM_CURVE``
    with a curve of the surface's parameters for each side; the halves need none
    (measured: one closed circle and its seam written as a plain line read back as an
    invalid face).
    """
    from ..geometry.arcs import GRID_LINK_SLACK, arc_runs_many

    jobs = _arc_search_jobs(topo)
    if not jobs:
        return []
    searched = _searched_vertices(jobs, xy)
    out: list = []
    for closed in (True, False):
        ks = [k for k, job in enumerate(jobs) if job[2] == closed and len(searched[k]) >= 4]
        found = arc_runs_many(
            [xy[jobs[k][1][searched[k]]] for k in ks],
            tolerance_mm=tolerance_mm,
            closed=closed,
            link_slack=GRID_LINK_SLACK,
            radii=radii,
        )
        for k, runs in zip(ks, found, strict=True):
            if len(runs.first):
                out.extend(_found_arcs(xy, jobs[k][0], jobs[k][1], searched[k], runs))
    return out


def _arc_search_jobs(topo) -> list:
    """The stretches of walled ring edges to search for arcs: ``[(ring positions, their vertices, closed), ...]``.

    A ring is cut where its wall's bottom level changes, where the wall stops, and at
    the vertices where more than two boundary edges meet; a ring with no cut is one
    closed stretch (see :func:`_wall_arcs`).
    """
    u, v = topo.vid, topo.vid[topo.nxt]
    n_points = len(topo.xy)
    real = u != v
    # each boundary edge once, as one int64 key (np.unique of rows sorts them lexically, more slowly)
    lo_v, hi_v = np.minimum(u, v)[real].astype(np.int64), np.maximum(u, v)[real].astype(np.int64)
    edge_keys = np.unique(lo_v * n_points + hi_v)
    degree = np.bincount(np.r_[edge_keys // n_points, edge_keys % n_points], minlength=n_points)
    walled = real & (topo.level > topo.out_level)
    jobs = []
    for r in range(len(topo.ring_start) - 1):
        idx = np.arange(topo.ring_start[r], topo.ring_start[r + 1])
        idx = idx[real[idx]]
        if len(idx) < 4 or not walled[idx].any():
            continue
        before = idx[np.arange(-1, len(idx) - 1)]
        cut = (degree[u[idx]] != 2) | ~walled[idx] | ~walled[before] | (topo.out_level[idx] != topo.out_level[before])
        if not cut.any():
            jobs.append((idx, u[idx], True))
            continue
        starts = np.flatnonzero(cut)
        for s0, s1 in zip(starts.tolist(), np.roll(starts, -1).tolist(), strict=True):
            seg = idx[(s0 + np.arange((s1 - s0) % len(idx) or len(idx))) % len(idx)]
            if walled[seg[0]] and len(seg) >= 3:
                jobs.append((seg, np.append(u[seg], v[seg[-1]]), False))
    return jobs


def _searched_vertices(jobs: list, xy) -> list:
    """Per job, the positions of its vertices searched for arcs: those Douglas-Peucker keeps within
    :data:`ON_LINE_MM` (all rings in one GEOS call), and an open stretch's ends."""
    import shapely

    lines = np.array(
        [shapely.linearrings(xy[verts]) if closed else shapely.linestrings(xy[verts]) for _, verts, closed in jobs],
        dtype=object,
    )
    kept_xy, kept_of = shapely.get_coordinates(shapely.simplify(lines, ON_LINE_MM), return_index=True)
    # a vertex is kept when its job and point are among the kept ones: one exact key each (grid points,
    # each job's x shifted by a whole multiple of the extent)
    lengths = np.array([len(verts) for _, verts, _ in jobs])
    verts_all = np.concatenate([verts for _, verts, _ in jobs])
    job_of = np.repeat(np.arange(len(jobs)), lengths)
    x0, shift = xy[:, 0].min(), np.ceil(np.ptp(xy[:, 0]) + 1.0)
    keys = (xy[verts_all, 0] - x0 + shift * job_of) + 1j * xy[verts_all, 1]
    keep_all = np.isin(keys, (kept_xy[:, 0] - x0 + shift * kept_of) + 1j * kept_xy[:, 1])
    offsets = np.concatenate([[0], np.cumsum(lengths)])
    searched = []
    for k, (_, _verts, closed) in enumerate(jobs):
        keep = keep_all[offsets[k] : offsets[k + 1]]
        if not closed:
            keep[[0, -1]] = True
        searched.append(np.flatnonzero(keep))
    return searched


def _found_arcs(xy, positions, verts, at, runs) -> list:
    """The arcs ``runs`` found among the vertices ``at`` of ``verts`` (the ends of ``positions``),
    as :func:`_wall_arcs` returns them; a whole circle as two halves (see there)."""
    n = len(positions)
    if runs.full:
        return _circle_halves(xy, positions, verts, at, runs)
    out = []
    for first, last, c, rad, sw in zip(
        runs.first.tolist(), runs.last.tolist(), runs.centre, runs.radius.tolist(), runs.sweep.tolist(), strict=True
    ):
        a, b = at[first], at[last]
        if b <= a:
            b += n
        out.append((positions[np.arange(a, b) % n], c, rad, sw, False))
    return out


def _circle_halves(xy, positions, verts, at, runs) -> list:
    """A whole circle's two halves, its sense the ring's, between the vertices nearest the circle, one
    in each half of the ring; none when those are farther than :data:`ON_LINE_MM` from it (moved onto
    the circle they would change the faces: the ring stays planar)."""
    n = len(positions)
    turn = np.copysign(1.0, _loop_area(xy[verts[at]]))
    d = xy[verts[at]] - runs.centre[0]
    off = np.abs(np.hypot(d[:, 0], d[:, 1]) - runs.radius[0])
    m = len(at) // 2
    i = int(np.argmin(off[:m]))
    lo = i + m // 2  # at least a quarter of the ring away on either side
    j = lo + int(np.argmin(off[lo : min(i + m + m // 2 + 1, len(at) - m // 2 + i + 1, len(at))]))
    if max(off[i], off[j]) > ON_LINE_MM:
        return []
    out = []
    for a, b in ((at[i], at[j]), (at[j], at[i] + n)):
        part = positions[np.arange(a, b) % n]
        ends = xy[[verts[a % n], verts[b % n]]] - runs.centre[0]
        t = np.arctan2(ends[:, 1], ends[:, 0])
        sweep = ((t[1] - t[0]) * turn) % (2 * np.pi)
        out.append((part, runs.centre[0], float(runs.radius[0]), float(turn * sweep), True))
    return out


def _node_xyz(ed: _Edges, xy, z):
    keys = np.array(list(ed.points.keys()), dtype=np.int64).reshape(-1, 2)
    idx = np.array(list(ed.points.values()), dtype=np.int64)
    out = np.empty((len(idx), 3))
    out[idx, :2] = xy[keys[:, 0]]
    out[idx, 2] = z[keys[:, 1]]
    return out


def _groups(n, pairs):
    """The numbers 0..n-1 grouped by the pairs that join them, each group in order, the groups in
    the order of their smallest member (:func:`fabtiles.core.graph.components`; importing networkx's
    union-find would slow every STEP export).

    >>> _groups(5, [(3, 1), (4, 2)])
    [[0], [1, 3], [2, 4]]
    """
    from ..core.graph import components

    pairs = np.asarray(list(pairs), np.int64).reshape(-1, 2)
    label = components(n, pairs[:, 0], pairs[:, 1])
    groups: dict = {}
    for i, g in enumerate(label.tolist()):
        groups.setdefault(g, []).append(i)
    return list(groups.values())


def _solids(faces, n_edges):
    """Faces grouped into closed shells: faces are joined through the edges they share."""
    owner = np.full(n_edges, -1)
    pairs = []
    for f, face in enumerate(faces):
        for loop in face.loops:
            for e in loop:
                e = e if e >= 0 else ~e
                if owner[e] < 0:
                    owner[e] = f
                else:
                    pairs.append((int(owner[e]), f))
    return tuple(tuple(g) for g in _groups(len(faces), pairs))


# --------------------------------------------------------------------------- a printed tile

SINGLE_CELL = 1 << 40
"""``cell_vertices`` that keeps a coverage in one cell: one face per flat region."""

MAX_FACE_HOLES = 300
"""A flat face holds at most about this many holes; a region with more is cut into cells of a
grid, a face each (and a pierced tile's bottom likewise). OCCT's STEP reader heals each wire
of a face against the whole face (``ShapeFix_IntersectionTool::FixSelfIntersectWire`` applies
its context to the face once per wire), so its time grows as the holes times the face's edges:
cells make a 200 mm pierced tile's import several times quicker (``docs/speed.md``). The seams
show on the face in a CAD program, so a tile of up to about 100 mm (a few hundred holes) keeps
its one face."""


def _cells_for_faces(layers) -> int:
    """``cell_vertices`` for the B-rep's coverage: :data:`SINGLE_CELL` unless a flat region holds
    more than :data:`MAX_FACE_HOLES` holes, else a size that gives each cell about that many."""
    import shapely

    polys = [p for g, _ in layers for p in shapely.get_parts(g)]
    holes = shapely.get_num_interior_rings(polys) if polys else np.zeros(0, int)
    if not len(holes) or holes.max() <= MAX_FACE_HOLES:
        return SINGLE_CELL
    vertices = int(shapely.get_num_coordinates(polys).sum())
    # cells_for sizes a cell to hold cell_vertices of the region's vertices: as many as MAX_FACE_HOLES / 2
    # holes would bring (a cell's holes are cut by its lines, and the region is not uniform)
    return max(int(vertices * MAX_FACE_HOLES / 2 / int(holes.sum())), 64)


# --------------------------------------------------------------------------- building


def _layers(kind, r, o, stack, dips):
    """The body's layers: region, dips and the rest of the outline from ONE snap-rounded noding.

    The meshes cut them with separate overlays (:func:`body_layers`), which may
    leave cracks and pinholes a quantum wide where the region meets a slanted side:
    harmless in a mesh, an invalid face in a B-rep. Here the boundaries of all of
    them are noded together on the 2**-10 mm grid and polygonized: the faces share
    every vertex, and slivers under a quantum wide collapse.
    """
    import shapely

    if kind not in ("relief", "plate", "mosaic"):
        return body_layers(kind, r, o, stack)
    d = split_region(r, dips, holes=False)[1] if kind == "relief" else shapely.Polygon()
    lines = shapely.union_all([shapely.boundary(g) for g in (r, o, d) if not g.is_empty], grid_size=QUANTUM)
    faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(lines)))
    faces = _merge_slivers(faces[shapely.area(faces) > 0])
    probe = shapely.point_on_surface(faces)
    in_o, in_r = shapely.contains(o, probe), shapely.contains(r, probe)
    in_d = shapely.contains(d, probe) if not d.is_empty else np.zeros(len(faces), bool)
    top = stack.base + stack.relief if kind in ("relief", "mosaic") else stack.base - stack.deboss
    rest = top - stack.inset if kind == "mosaic" else stack.base  # a mosaic: its faces, to the top less the inset
    layers = [(faces[in_o & in_r & ~in_d], top), (faces[in_o & ~in_r], rest), (faces[in_o & in_d], dip_z(stack))]
    return [(shapely.MultiPolygon(list(g)), z) for g, z in layers if len(g)], 0.0


def _noded_levels(levels) -> list:
    """A mosaic part's levels ``((geometry, z), ...)`` from ONE snap-rounded noding, as :func:`_layers` makes a
    body's: each polygon of the noding takes the height of the first level holding it; none: not the part's."""
    import shapely

    geoms = [g for g, _ in levels if not g.is_empty]
    lines = shapely.union_all([shapely.boundary(g) for g in geoms], grid_size=QUANTUM)
    faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(lines)))
    faces = _merge_slivers(faces[shapely.area(faces) > 0])
    probe = shapely.point_on_surface(faces)
    height = np.full(len(faces), np.nan)
    for g, z in levels:
        if not g.is_empty:
            height[np.isnan(height) & shapely.contains(g, probe)] = z
    return [
        (shapely.MultiPolygon(list(faces[height == z])), z)
        for z in dict.fromkeys(z for _, z in levels)
        if (height == z).any()
    ]


def _merge_slivers(faces):
    """``faces`` with every sliver under a quantum wide merged into the neighbour it shares most edge with.

    Where a filled region's boundary runs within a quantum of a slanted side of the
    outline, the noding leaves triangles 0.0004 mm wide between them (measured on
    the seamless hexagon sample): each a face of its own that the B-rep's grid then
    flattens to three collinear points, a face of no area. Merged into their
    neighbour they change the volume by under 0.001 mm^3.
    """
    import shapely

    faces = np.asarray(faces, dtype=object)
    width = 2 * shapely.area(faces) / shapely.length(faces)  # the mean width of each face, in one pass
    thin = np.flatnonzero(width < QUANTUM).tolist()
    if not thin:
        return faces
    faces = list(faces)
    tree = shapely.STRtree(faces)
    gone = set()
    for i in thin:
        best, shared = None, 0.0
        for j in tree.query(faces[i]).tolist():
            if j == i or j in gone or width[j] < QUANTUM:
                continue
            length = shapely.intersection(faces[i].boundary, faces[j].boundary, grid_size=QUANTUM).length
            if length > shared:
                best, shared = j, length
        if best is not None:
            # on the grid the union may leave a tail of the sliver as a line beside the polygon: dropped
            merged = shapely.get_parts(shapely.union(faces[best], faces[i], grid_size=QUANTUM))
            merged = merged[(shapely.get_type_id(merged) == 3) & (shapely.area(merged) > 0)]
            if len(merged) == 1:
                faces[best] = merged[0]
                gone.add(i)
    return np.asarray([f for k, f in enumerate(faces) if k not in gone], dtype=object)


def _sides(outline):
    """The straight sides of the outline's exterior rings, counter-clockwise: (k, 4)."""
    import shapely

    rows = []
    for poly in shapely.get_parts(shapely.orient_polygons(outline)):
        ring = shapely.get_coordinates(poly.exterior)
        rows.append(np.hstack([ring[:-1], ring[1:]]))
    return np.vstack(rows) if rows else np.empty((0, 4))


def build_brep(*, region, outline, stack: Stack, dips=None, tolerance_mm: float = 0.0, radii=()):
    """The B-rep of a printed tile, beside its checked mesh.

    Returns ``(brep, mesh_volume, n_solids)``. The mesh goes first: it is
    checked, bridges point contacts of the region (the B-rep is built from the
    region it used) and gives the volume the solid must have (with the arcs'
    chords, see :func:`check_brep`). A pierced tile in several pieces is one solid
    per piece. ``tolerance_mm > 0``: arcs within it are circles and cylinders; ``radii``: radii
    the region's curves are known to have (:func:`planar_brep`).
    """
    (part,) = checked_parts(region, outline, stack, single=True, dips=dips).values()
    return brep_of_part(part, stack, dips, tolerance_mm=tolerance_mm, radii=radii)


def brep_of_part(part, stack: Stack, dips=None, *, tolerance_mm: float = 0.0, radii=()):
    """The B-rep of a checked fused body (see :func:`build_brep`), or of a mosaic's part from the
    levels it was meshed from (:attr:`~fabtiles.solid.parts.CheckedPart.layers`):
    ``(brep, mesh_volume, n_solids)``."""
    if part.layers:
        layers, bottom = _noded_levels(part.layers), part.bottom_mm
        recess = stack.recess if bottom == 0 else None  # a recess is sunk into the part on the bed
    else:
        kind = {"relief": "relief", "pierced": "pierced", "deboss": "plate", "mosaic": "mosaic"}[stack.style]
        layers, bottom = _layers(kind, part.region, part.outline, stack, dips if stack.style == "relief" else None)
        recess = stack.recess
    # a recess's holes go into the bottom's one face: not a bottom of cells
    cells_at = _cells_for_faces(layers) if recess is None else SINGLE_CELL
    cov, cells = _face_coverage(layers, bottom, cells_at)
    sides, chords = _sides(part.outline), frozenset[tuple]()
    for _ in range(CHORD_ROUNDS):
        brep = planar_brep(
            cov, sides=sides, tolerance_mm=tolerance_mm, radii=radii, cells=cells, chords=chords, recess=recess
        )
        crossing = _crossing_arcs(brep)
        if not crossing:
            break
        chords |= crossing
    return brep, part.mesh_volume_mm3, len(brep.solids)


CHORD_ROUNDS = 4
"""How many times a B-rep is made again with the arcs that crossed another loop left as chords."""


def _circle_key(centre, radius) -> tuple:
    """A circle found by :func:`_wall_arcs`, as a key that the same search finds again."""
    return (round(float(centre[0]), 9), round(float(centre[1]), 9), round(float(radius), 9))


def _crossing_arcs(brep: Brep) -> frozenset:
    """The circles of the arcs that cross or touch another edge of their flat face.

    An arc stands for its chords within the tolerance, so it bulges up to that far
    past them: where two loops of a face come closer (a wall thinner than the
    tolerance), the arc crosses the other loop. Such an arc stays chords, as the mesh
    has it. Only faces GEOS finds invalid are searched.
    """
    import shapely

    if brep.arcs is None:
        return frozenset()
    out: set = set()
    for face in brep.faces:
        if face.radius > 0 or abs(face.normal[0]) + abs(face.normal[1]) > 0:
            continue
        index = [e if e >= 0 else ~e for loop in face.loops for e in loop]
        if not (brep.arcs[index, 2] > 0).any():
            continue
        rings = [_loop_points(list(loop), brep.edges, brep.arcs, brep.points) for loop in face.loops]
        if shapely.is_valid(shapely.Polygon(rings[0], rings[1:])):
            continue
        out |= _face_crossing_circles(face, index, brep.edges, brep.arcs, brep.points)
    return frozenset(out)


def _face_crossing_circles(face, index: list, edges, arcs, pts) -> set:
    """The circles of the arcs of a flat face that cross or touch an edge of it other than their neighbours,
    and of the arcs they cross. ``index``: the face's edges, loop by loop."""
    import shapely

    lines, where = [], []  # each edge as drawn, and (loop, position, loop length)
    for li, loop in enumerate(face.loops):
        for k, e in enumerate(loop):
            a = edges[e if e >= 0 else ~e]
            end = pts[a[1] if e >= 0 else a[0], :2]
            lines.append(shapely.LineString(np.vstack([_loop_points([e], edges, arcs, pts), end])))
            where.append((li, k, len(loop)))
    tree = shapely.STRtree(lines)
    out = set()
    for i, e in enumerate(index):
        if arcs[e, 2] <= 0:
            continue
        li, k, n = where[i]
        near = {(li, k), (li, (k - 1) % n), (li, (k + 1) % n)}  # itself and the edges it joins
        hits = [j for j in tree.query(lines[i], predicate="intersects").tolist() if where[j][:2] not in near]
        for j in hits + ([i] if hits else []):
            if arcs[index[j], 2] > 0:
                out.add(_circle_key(arcs[index[j], :2], arcs[index[j], 2]))
    return out


def _face_coverage(layers, bottom: float, cell_vertices: int):
    """``(coverage, in cells)``: the coverage whose pieces are the flat faces, and whether they are cells.

    A ring noded at a cell line has the point where it crosses the line rounded to the
    grid, which may put it across a neighbouring edge: GEOS cannot clip it. As the
    mesh does (:data:`~fabtiles.solid.parts.GRID_SHIFTS` tries), the cut was unlucky,
    not the region: the lines are moved and the cells cut again; when every try
    fails, each flat region stays one face (slower for a CAD program to read, as
    valid).
    """
    import shapely

    if cell_vertices != SINGLE_CELL:
        for shift in range(GRID_SHIFTS):
            try:
                return coverage(layers, bottom=bottom, cell_vertices=cell_vertices, shift=shift), True
            except shapely.errors.GEOSException:
                continue
    return coverage(layers, bottom=bottom, cell_vertices=SINGLE_CELL), False


def brep_volume(brep: Brep) -> float:
    """The volume of a B-rep's solids, its arcs as arcs: what OCCT and CAD programs report of the STEP.

    By the divergence theorem with the field (0, 0, z), only the horizontal faces
    count: each its height times its signed area, an arc adding the segment between
    it and its chord, ``r**2 / 2 * (sweep - sin(sweep))``. The checked mesh's volume
    differs by those segments (:func:`check_brep`).

    >>> import shapely
    >>> from fabtiles.solid._mesh_build import coverage
    >>> disc = shapely.Point(0, 0).buffer(10.0, quad_segs=16)
    >>> b = planar_brep(coverage([(disc, 2.0)], bottom=0.0, cell_vertices=SINGLE_CELL), tolerance_mm=0.02)
    >>> round(brep_volume(b) / (np.pi * 100 * 2.0), 6), round(disc.area * 2.0 / brep_volume(b), 4)
    (1.0, 0.9984)
    """
    pts, edges, arcs = np.asarray(brep.points, float), np.asarray(brep.edges, np.int64), brep.arc_rows()
    total = 0.0
    for face in brep.faces:
        if face.radius > 0 or face.normal[0] or face.normal[1]:
            continue
        loop = np.concatenate([np.asarray(lp, np.int64) for lp in face.loops])
        e = np.where(loop >= 0, loop, ~loop)
        a = pts[np.where(loop >= 0, edges[e, 0], edges[e, 1])]
        b = pts[np.where(loop >= 0, edges[e, 1], edges[e, 0])]
        row = arcs[e]
        area = 0.5 * float(np.sum(a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]))
        area += float(np.sum(np.where(loop >= 0, 1.0, -1.0) * row[:, 2] ** 2 / 2 * (row[:, 3] - np.sin(row[:, 3]))))
        total += face.origin[2] * area
    return total


BREP_VOLUME_TOLERANCE = 0.0005
"""Largest relative difference between a B-rep's volume and its checked mesh's (0.05 %)."""


def check_brep(brep: Brep, *, volume: float, parts: int, what: str = "STEP solid") -> float:
    """Check a B-rep in memory before it is written: closed, oriented, valid faces, the mesh's volume.

    What OCCT's reading back of the written file checked, in a fraction of its time
    (the read-back and its checks were most of an export's time):

    - every edge bounds exactly two faces, run once each way (a closed shell,
      consistently oriented), and the faces fall into ``parts`` shells;
    - each horizontal face, its loops in the plane, is a valid polygon by GEOS (no
      loop crossing or touching another, every hole inside its outer loop); every
      face's points lie on its plane;
    - the volume, by the divergence theorem over the faces' vector areas, is
      positive and within :data:`BREP_VOLUME_TOLERANCE` of ``volume``.

    ``fabtiles check --deep`` and the tests still read the written file back with OCCT
    (:func:`fabtiles.export.step.check_step_file`). Returns the volume; raises
    :class:`~fabtiles.FabricationError`.

    >>> import shapely
    >>> from fabtiles.solid._mesh_build import coverage
    >>> b = planar_brep(coverage([(shapely.box(0, 0, 10, 10), 2.0)], bottom=0.0))
    >>> check_brep(b, volume=200.0, parts=1)
    200.0
    >>> check_brep(b, volume=100.0, parts=1)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.FabricationError: the STEP solid has a volume of 200 mm^3, not the mesh's 100 mm^3 (0.05% allowed); nothing was written
    """  # noqa: E501 - a doctest's lines are as Python prints them

    def fail(why):
        raise FabricationError(f"the {what} {why}; nothing was written")

    pts, edges = np.asarray(brep.points, float), np.asarray(brep.edges, np.int64)
    signed, face_of = [], []
    for f, face in enumerate(brep.faces):
        for loop in face.loops:
            signed.extend(loop)
            face_of.extend([f] * len(loop))
    signed, face_of = np.asarray(signed, np.int64), np.asarray(face_of, np.int64)
    index = np.where(signed >= 0, signed, ~signed)
    forward = np.bincount(index[signed >= 0], minlength=len(edges))
    backward = np.bincount(index[signed < 0], minlength=len(edges))
    if np.any(forward != 1) or np.any(backward != 1):
        fail("has an open shell or an edge joining more than two faces")
    if len(brep.solids) != parts:
        fail(f"holds {len(brep.solids)} solids, not {parts}")
    # each signed edge from its start to its end, as the loop runs it
    a = np.where(signed >= 0, edges[index, 0], edges[index, 1])
    b = np.where(signed >= 0, edges[index, 1], edges[index, 0])
    arcs = brep.arc_rows()
    surfaces = _face_surfaces(brep)
    off_plane, off_curve = _off_surfaces(surfaces, pts, edges, arcs, a, face_of)
    if off_plane > 1e-6:
        fail(f"has a face with a point {off_plane:.3g} mm off its plane")
    if off_curve > 1e-6:
        fail(f"has a point {off_curve:.3g} mm off its cylinder or circle")
    wound, total, chords = _winding_and_volume(brep, surfaces, pts, edges, arcs, signed, face_of, a, b)
    if np.any(wound <= 0):
        fail("has a face wound against its normal (inside out)")
    if not total > 0:
        fail(f"has a volume of {total:.6g} mm^3: inside out")
    if abs(chords - volume) > BREP_VOLUME_TOLERANCE * abs(volume):
        fail(
            f"has a volume of {chords:.6g} mm^3, not the mesh's {volume:.6g} mm^3 ({BREP_VOLUME_TOLERANCE:.2%} allowed)"
        )
    if not _flat_faces_valid(brep, pts, edges, arcs):
        fail("has an invalid horizontal face (loops crossing or touching)")
    return total


def _face_surfaces(brep: Brep) -> tuple:
    """``(radius, unit normal, origin)`` of each face, as arrays."""
    radius = np.asarray([f.radius for f in brep.faces], float)
    normals = np.asarray([f.normal for f in brep.faces], float)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    origins = np.asarray([f.origin for f in brep.faces], float)
    return radius, normals, origins


def _off_surfaces(surfaces, pts, edges, arcs, a, face_of) -> tuple[float, float]:
    """How far the B-rep's points lie off their faces: ``(off a plane, off a cylinder or circle)`` in mm.

    ``surfaces``: per face, its radius, unit normal and origin; ``a``: the start point of
    each signed edge of the faces' loops, ``face_of`` its face.
    """
    radius, normals, origins = surfaces
    on_plane = ~(radius > 0)[face_of]
    off = np.abs(np.einsum("ij,ij->i", pts[a] - origins[face_of], normals[face_of]))[on_plane]
    off_plane = float(off.max()) if off.size else 0.0
    d = pts[a[~on_plane], :2] - origins[face_of[~on_plane], :2]
    off = np.abs(np.hypot(d[:, 0], d[:, 1]) - radius[face_of[~on_plane]])
    is_arc = arcs[:, 2] > 0
    d = pts[edges[is_arc]][:, :, :2] - arcs[is_arc, None, :2]
    off = np.concatenate([off, np.abs(np.hypot(d[..., 0], d[..., 1]) - arcs[is_arc, 2:3]).ravel()])
    return off_plane, float(off.max()) if off.size else 0.0


def _winding_and_volume(brep: Brep, surfaces, pts, edges, arcs, signed, face_of, a, b):
    """``(wound, volume, chords' volume)``: per face, its vector area along its outward normal (positive:
    wound as its normal says), and the volume with the arcs as arcs and as the mesh's chords.

    The volume is the divergence theorem's with the field (0, 0, z): only the
    horizontal faces count, an arc adding what lies between it and its chord.
    """
    index = np.where(signed >= 0, signed, ~signed)
    radius, normals, origins = surfaces
    cyl = radius > 0
    cross = np.cross(pts[a], pts[b])
    area_vec = np.zeros((len(brep.faces), 3))
    np.add.at(area_vec, face_of, cross / 2)
    # an arc adds to its face's area what lies between it and its chord: exactly, and as the mesh's chords did
    run = np.where(signed >= 0, 1.0, -1.0)
    row = arcs[index]
    exact, flat = np.zeros(len(brep.faces)), np.zeros(len(brep.faces))
    np.add.at(exact, face_of, run * row[:, 2] ** 2 / 2 * (row[:, 3] - np.sin(row[:, 3])))
    np.add.at(flat, face_of, run * row[:, 4])
    flat_faces = ~cyl & (np.abs(normals[:, 2]) == 1.0)  # the horizontal faces: they alone hold the volume
    wound = np.einsum("ij,ij->i", area_vec, normals) + np.where(flat_faces, exact * normals[:, 2], 0.0)
    wound[cyl] = 1.0
    for f in np.flatnonzero(cyl).tolist():
        wound[f] = _cylinder_winding(brep.faces[f], pts, edges, arcs, area_vec[f])
    z_of = origins[:, 2] * flat_faces
    return wound, float(z_of @ (area_vec[:, 2] + exact)), float(z_of @ (area_vec[:, 2] + flat))


def _cylinder_winding(face, pts, edges, arcs, area_vec) -> float:
    """A cylinder patch's vector area along the direction it faces at its middle, out from its axis
    (or into it, ``inward``); a whole circle's, whose vector area is nought, 1."""
    e = face.loops[0][0]  # the arc at its bottom
    row_e = arcs[e if e >= 0 else ~e]
    if row_e[3] >= 2 * np.pi - 1e-9:
        return 1.0
    start = pts[edges[e if e >= 0 else ~e, 0], :2] - row_e[:2]
    mid = np.arctan2(start[1], start[0]) + row_e[3] / 2
    out = np.array([np.cos(mid), np.sin(mid)]) * (-1.0 if face.inward else 1.0)
    return float(area_vec[:2] @ out)


def _flat_faces_valid(brep: Brep, pts, edges, arcs) -> bool:
    """Whether each horizontal face, its loops in x, y (arcs drawn by chords), is a valid polygon by GEOS."""
    import shapely

    is_arc = arcs[:, 2] > 0
    polys = []
    for face in brep.faces:
        if face.radius > 0 or abs(face.normal[0]) + abs(face.normal[1]) > 0:
            continue
        rings = []
        for loop in face.loops:
            loop = np.asarray(loop, np.int64)
            e = np.where(loop >= 0, loop, ~loop)
            if is_arc[e].any():
                rings.append(_loop_points(loop.tolist(), edges, arcs, pts))
                continue
            start = np.where(loop >= 0, edges[e, 0], edges[e, 1])
            rings.append(pts[start, :2])
        polys.append(shapely.Polygon(rings[0], rings[1:]))
    return bool(np.all(shapely.is_valid(np.asarray(polys, dtype=object)))) if polys else True
