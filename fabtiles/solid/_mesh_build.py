"""Fast, exact 2.5D meshing of tiles: stacked prisms over a planar coverage.

Every 3D part fabtiles makes is a "stack": a set of polygons covering part of the
plane, each raised to its own level above a common bottom (relief: the pattern at
``b + h`` and the rest of the outline at ``b``; pierced: the pattern at ``t``;
deboss: the rest at ``b`` and the grooves at ``b - d``). This module meshes such a
stack directly, without mesh booleans:

1. Snap every coordinate to a grid of ``QUANTUM`` = 2**-10 mm. Grid points are
   exact in float32 up to 16 m, so a binary STL stores the very vertices the mesh
   was checked with: no two vertices collapse and no face turns degenerate when a
   slicer reads the file back.
2. Cut the plane into square cells along grid lines. Triangulating one polygon
   with thousands of holes is quadratic in the number of holes (half a minute for
   a sheet); cells of a few hundred vertices keep it linear. The lines
   keep clear of every vertex (:func:`_off_vertices`), and rings are first noded
   at them (crossing points inserted, snapped), so the pieces of neighbouring
   cells share their seam vertices exactly.
3. Triangulate each piece (:mod:`fabtiles.solid._triangulate`: fans, earcut
   checked exactly, else manifold3d's triangulator), put its top at its level,
   its bottom at the common bottom (an outline alone is triangulated on its own),
   and raise a wall on every piece edge whose
   neighbour across it is lower (no neighbour: the bottom). Walls are split at
   every level so vertical edges always pair up.

The result is watertight by construction whenever the pieces form a proper
coverage; the caller checks it anyway (see :mod:`fabtiles.solid.parts`) and falls
back to manifold3d booleans if it is not.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.errors import FabricationError, ParameterError
from ..core.native import import_uninterrupted
from ..geometry.stack import MAX_HEIGHT_MM, QUANTUM, Stack, resolve_stack  # noqa: F401  (the writers' names)
from ._triangulate import bottom_triangles, cdt, ear_clip, flat, flip_degenerate, recessed_bottom

CELL_VERTICES = 1500
"""Target number of region vertices per meshing cell."""


def check_shapes(region, outline):
    """Check the material region and the outline; return them as shapely geometry.

    Raises :class:`~fabtiles.ParameterError` for anything that is not a valid,
    non-empty, finite (Multi)Polygon.
    """
    import shapely
    from shapely.geometry import MultiPolygon, Polygon

    for name, geom, kinds in (
        ("region", region, (Polygon, MultiPolygon)),
        ("outline", outline, (Polygon, MultiPolygon)),
    ):
        if not isinstance(geom, kinds):
            raise ParameterError(f"{name} must be a shapely Polygon or MultiPolygon, got {type(geom).__name__}")
        if geom.is_empty or geom.area <= 0:
            raise ParameterError(f"{name} must have an area > 0, got an empty {geom.geom_type}")
        coords = shapely.get_coordinates(geom)
        if not np.isfinite(coords).all():
            raise ParameterError(f"{name} must have finite coordinates, got NaN or infinite values")
        if np.abs(coords).max() > 16000:
            raise ParameterError(
                f"{name} must lie within 16 m of the origin (coordinates in mm), got {np.abs(coords).max():g}"
            )
        if not geom.is_valid:
            raise ParameterError(f"{name} is not a valid polygon ({shapely.is_valid_reason(geom)})")
    return region, outline


# --------------------------------------------------------------------------- grid


def snap(geom):
    """``geom`` with every vertex on the ``QUANTUM`` grid, still valid.

    Rounds the coordinates (fast); only if that breaks validity (features finer
    than the grid) does it fall back to GEOS snap rounding.
    """
    import shapely

    parts = shapely.get_parts(geom)
    parts = parts[~shapely.is_empty(parts)]
    if len(parts):
        _, coords, (ring_off, poly_off) = shapely.to_ragged_array(parts)
        ring_off, poly_off = np.asarray(ring_off), np.asarray(poly_off)
        pts = np.round(np.asarray(coords) / QUANTUM) * QUANTUM
        ring_of = np.repeat(np.arange(len(ring_off) - 1), np.diff(ring_off))
        keep = np.ones(len(pts), bool)
        keep[1:] = np.any(pts[1:] != pts[:-1], axis=1) | (ring_of[1:] != ring_of[:-1])
        pts, ring_of = pts[keep], ring_of[keep]
        n_ring = np.bincount(ring_of, minlength=len(ring_off) - 1)
        alive = n_ring >= 4  # a closed ring needs 3 distinct points
        is_shell = np.zeros(len(alive), bool)
        is_shell[poly_off[:-1]] = True
        if np.all(alive[is_shell]):
            # drop collapsed holes (slivers thinner than the grid)
            sel = alive[ring_of]
            pts, ring_of = pts[sel], ring_of[sel]
            new_index = np.cumsum(alive) - 1
            ring_off2 = np.concatenate([[0], np.cumsum(n_ring[alive])])
            poly_off2 = np.concatenate([[0], np.cumsum(np.add.reduceat(alive, poly_off[:-1]))])
            del new_index
            polys = shapely.from_ragged_array(shapely.GeometryType.POLYGON, pts, (ring_off2, poly_off2))
            rounded = polys[0] if len(polys) == 1 else shapely.multipolygons(polys)
            if shapely.is_valid(rounded):
                return rounded
    return shapely.set_precision(geom, QUANTUM)


GRID_SHIFT_MM = 41 * QUANTUM
"""How far the cell lines move on each retry of a mesh whose defect lies on a cell line."""


def _grid_lines(lo: float, hi: float, size: float, shift: int = 0) -> np.ndarray:
    """Interior cell lines between lo and hi, on the quantum grid, off round numbers.

    ``shift`` moves every line by ``shift * GRID_SHIFT_MM``: a retry for the rare
    ring that, noded at a line and snapped, lands on a neighbouring ring's edge.
    """
    n = max(1, math.ceil((hi - lo) / size))
    step = (hi - lo) / n
    # 0.3125 + 0.0390625 mm offsets keep lines off the round values designs use
    lines = lo + step * np.arange(1, n) + 0.3515625 + shift * GRID_SHIFT_MM
    return np.round(lines / QUANTUM) * QUANTUM


def _node_rings(coords: np.ndarray, ring_off: np.ndarray, xs: np.ndarray, ys: np.ndarray):
    """Insert the (snapped) points where closed rings cross the grid lines.

    ``coords`` holds the rings one after another, each closed (last point = first),
    ``ring_off`` their start offsets (with the end). Returns the new pair.
    """
    n = len(coords)
    ring_of = np.repeat(np.arange(len(ring_off) - 1), np.diff(ring_off))
    # segment i runs from point i to i + 1 unless i is the closing point of its ring
    is_seg = np.ones(n, bool)
    is_seg[ring_off[1:] - 1] = False
    seg_ids = np.flatnonzero(is_seg)
    p = coords[seg_ids]
    q = coords[seg_ids + 1]
    cut_seg, cut_t, cut_pts = [], [], []
    for axis, lines in ((0, xs), (1, ys)):
        if len(lines) == 0:
            continue
        a = np.minimum(p[:, axis], q[:, axis])
        b = np.maximum(p[:, axis], q[:, axis])
        lo = np.searchsorted(lines, a, side="right")
        hi = np.searchsorted(lines, b, side="left")
        cnt = np.maximum(hi - lo, 0)
        total = int(cnt.sum())
        if not total:
            continue
        seg = np.repeat(np.arange(len(p)), cnt)
        k = np.arange(total) - np.repeat(np.cumsum(cnt) - cnt, cnt) + np.repeat(lo, cnt)
        value = lines[k]
        t = (value - p[seg, axis]) / (q[seg, axis] - p[seg, axis])
        # the point from the segment's lower end, whichever way the ring runs: a ring and
        # the same ring reversed (a dip and the hole it leaves) get the same points
        swap = (p[seg, 0] > q[seg, 0]) | ((p[seg, 0] == q[seg, 0]) & (p[seg, 1] > q[seg, 1]))
        lo_pt = np.where(swap[:, None], q[seg], p[seg])
        hi_pt = np.where(swap[:, None], p[seg], q[seg])
        s = (value - lo_pt[:, axis]) / (hi_pt[:, axis] - lo_pt[:, axis])
        pts = lo_pt + s[:, None] * (hi_pt - lo_pt)
        pts[:, axis] = value
        cut_seg.append(seg_ids[seg])
        cut_t.append(t)
        cut_pts.append(pts)
    if not cut_seg:
        return coords, ring_off
    seg = np.concatenate(cut_seg)
    t = np.concatenate(cut_t)
    pts = np.round(np.concatenate(cut_pts) / QUANTUM) * QUANTUM
    # original point i sorts as (i, -1), the cuts of segment i as (i, t)
    all_pos = np.concatenate([np.arange(n), seg])
    all_t = np.concatenate([np.full(n, -1.0), t])
    order = np.lexsort((all_t, all_pos))
    out = np.concatenate([coords, pts])[order]
    out_ring = np.concatenate([ring_of, ring_of[seg]])[order]
    keep = np.ones(len(out), bool)
    keep[1:] = np.any(out[1:] != out[:-1], axis=1) | (out_ring[1:] != out_ring[:-1])
    out, out_ring = out[keep], out_ring[keep]
    new_off = np.searchsorted(out_ring, np.arange(len(ring_off)))
    return out, new_off


def node_polygons(geom, xs, ys):
    """``geom`` (on the grid) with its rings noded at the cell lines."""
    import shapely

    parts = shapely.get_parts(geom)
    parts = parts[~shapely.is_empty(parts)]
    if len(parts) == 0:
        return shapely.Polygon()
    _, coords, (ring_off, poly_off) = shapely.to_ragged_array(parts)
    coords, ring_off = _node_rings(np.asarray(coords, float), np.asarray(ring_off), xs, ys)
    polys = shapely.from_ragged_array(shapely.GeometryType.POLYGON, coords, (ring_off, np.asarray(poly_off)))
    return polys[0] if len(polys) == 1 else shapely.MultiPolygon(list(polys))


def cells_for(geoms, cell_vertices: int = CELL_VERTICES, shift: int = 0, avoid=()):
    """Cell lines (xs, ys) for geometries with about ``cell_vertices`` vertices a cell.

    ``shift`` moves the lines (see :func:`_grid_lines`). No line passes through a
    vertex of ``geoms`` or of ``avoid`` (geometries cut with the same lines, not
    counted in the size; see :func:`_off_vertices`).
    """
    import shapely

    bounds = np.array([g.bounds for g in geoms])
    x0, y0 = bounds[:, 0].min(), bounds[:, 1].min()
    x1, y1 = bounds[:, 2].max(), bounds[:, 3].max()
    nverts = sum(int(shapely.get_num_coordinates(g)) for g in geoms)
    area = max((x1 - x0) * (y1 - y0), 1e-9)
    size = math.sqrt(area * cell_vertices / max(nverts, 1))
    size = max(size, 2.0)
    xs, ys = _grid_lines(x0, x1, size, shift), _grid_lines(y0, y1, size, shift)
    if len(xs) or len(ys):
        pts = shapely.get_coordinates(np.array([*geoms, *avoid], dtype=object))
        xs, ys = _off_vertices(xs, pts[:, 0]), _off_vertices(ys, pts[:, 1])
    return xs, ys, (x0, y0, x1, y1)


LINE_SEARCH = 40
"""Grid steps a cell line may move forward to keep clear of vertices (less than a retry's move,
:data:`GRID_SHIFT_MM`, so that a retry tries other lines)."""

LINE_CLEARANCE = 16
"""Grid steps of clearance from every vertex that a cell line looks for."""


def _off_vertices(lines: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Cell lines (on the grid) moved forward by up to :data:`LINE_SEARCH` steps, clear of ``values``.

    Each line goes to the first place of its window farthest from every value there
    (up to :data:`LINE_CLEARANCE` steps). A ring that only touches a cell line at a
    vertex is not noded there, and clipped at the line it becomes a ring touching
    itself (two lobes joined at that vertex): invalid, and GEOS's triangulator stops
    on it. A line just beside a sharp tip is no better: the tip's two edges cross it
    at points that round to one, and the ring folds back on itself. Clear of the
    vertices, a line is crossed by every ring that reaches it, at distinct points
    (:func:`_node_rings` inserts them).

    >>> q = QUANTUM
    >>> _off_vertices(np.array([1.0]), np.array([1.0, 1.0 + 3 * q, 5.0])).tolist() == [1.0 + 19 * q]
    True
    """
    if not len(lines):
        return lines
    k = np.round(lines / QUANTUM).astype(np.int64)
    v = np.round(np.asarray(values) / QUANTUM).astype(np.int64)
    lo, hi = k - LINE_CLEARANCE, k + LINE_SEARCH + LINE_CLEARANCE
    # the values near each line (its window with the clearance either side; the windows do not overlap)
    at = np.searchsorted(lo, v, side="right") - 1
    near = (at >= 0) & (v <= hi[np.maximum(at, 0)])
    v, at = v[near], at[near]
    out = k.copy()
    cand = np.arange(LINE_SEARCH + 1)
    for i in np.unique(at).tolist():
        taken = np.unique(v[at == i])
        c = k[i] + cand
        j = np.searchsorted(taken, c)
        below = np.where(j > 0, c - taken[np.maximum(j - 1, 0)], LINE_CLEARANCE)
        above = np.where(j < len(taken), taken[np.minimum(j, len(taken) - 1)] - c, LINE_CLEARANCE)
        clear = np.minimum(np.minimum(below, above), LINE_CLEARANCE)
        out[i] = c[int(np.argmax(clear))]
    return out * QUANTUM


def split_cells(geom, xs, ys, box):
    """Clip ``geom`` into the cells of the grid; yield ``(i, j, piece)`` for non-empty pieces.

    Bisects along grid lines (cost n log n), always down to single cells so that
    neighbouring pieces share exactly the same seam vertices.
    """
    import shapely

    ex = np.concatenate([[box[0] - 1.0], xs, [box[2] + 1.0]])
    ey = np.concatenate([[box[1] - 1.0], ys, [box[3] + 1.0]])
    out = []
    stack = [(geom, 0, len(ex) - 1, 0, len(ey) - 1)]
    while stack:
        g, i0, i1, j0, j1 = stack.pop()
        if g.is_empty:
            continue
        if i1 - i0 == 1 and j1 - j0 == 1:
            out.append((i0, j0, g))
            continue
        if i1 - i0 >= j1 - j0:
            m = (i0 + i1) // 2
            halves = ((i0, m, j0, j1), (m, i1, j0, j1))
        else:
            m = (j0 + j1) // 2
            halves = ((i0, i1, j0, m), (i0, i1, m, j1))
        for a0, a1, b0, b1 in halves:
            part = shapely.clip_by_rect(g, ex[a0], ey[b0], ex[a1], ey[b1])
            if not part.is_empty:
                stack.append((part, a0, a1, b0, b1))
    return out, ex, ey


def polygons_of(geom):
    """The non-empty polygons in a geometry (dropping lines and points)."""
    import shapely
    from shapely.geometry import Polygon

    if geom.is_empty:
        return []
    if isinstance(geom, Polygon):
        return [geom]
    parts = shapely.get_parts(geom)
    nested = shapely.get_type_id(parts) >= 4  # multi-part geometries and collections
    while nested.any():
        parts = np.concatenate([parts[~nested], shapely.get_parts(parts[nested])])
        nested = shapely.get_type_id(parts) >= 4
    return list(parts[(shapely.get_type_id(parts) == 3) & (shapely.area(parts) > 0)])


# --------------------------------------------------------------------------- coverage


@dataclass
class Coverage:
    """Pieces of a planar coverage on the quantum grid, each with a level index."""

    pieces: list  # list of (shapely MultiPolygon, level index)
    levels: np.ndarray  # z of each level index; index 0 is the bottom
    xs: np.ndarray | None = None  # the cell lines
    ys: np.ndarray | None = None


def coverage(layers, *, bottom: float, cell_vertices: int = CELL_VERTICES, shift: int = 0, cells=None) -> Coverage:
    """Cut a stack into small pieces for meshing.

    Parameters
    ----------
    layers : list of (geometry, z)
        Disjoint (Multi)Polygons, already on the quantum grid, and the height of
        the top of each.
    bottom : float
        Height of the common bottom.
    cell_vertices : int
        About this many region vertices per cell.
    shift : int
        Moves the cell lines (see :func:`_grid_lines`).
    cells : tuple, optional
        The cell lines and box ``(xs, ys, box)`` to use, as :func:`cells_for` gives
        them (then ``cell_vertices`` and ``shift`` are not used).
    """
    geoms = [g for g, _ in layers if not g.is_empty]
    xs, ys, box = cells if cells is not None else cells_for(geoms, cell_vertices, shift)
    levels = np.array(sorted({bottom, *[z for _, z in layers]}))
    pieces: list = []
    for geom, z in layers:
        if geom.is_empty:
            continue
        lvl = int(np.searchsorted(levels, z))
        noded = node_polygons(geom, xs, ys)
        cells, _, _ = split_cells(noded, xs, ys, box)
        pieces.extend((piece, lvl) for _, _, piece in cells)
    return coverage_from_cells(pieces, levels, xs, ys)


def coverage_from_cells(cell_layers, levels, xs=None, ys=None) -> Coverage:
    """Coverage from pieces already cut per cell: ``[(geometry, level index), ...]``."""
    import shapely

    pieces = []
    for geom, lvl in cell_layers:
        polys = polygons_of(geom)
        if polys:
            pieces.append((shapely.orient_polygons(shapely.multipolygons(polys)), lvl))
    return Coverage(pieces, np.asarray(levels, float), xs, ys)


@dataclass
class Topology:
    """The planar structure of a coverage: shared vertices, piece rings, neighbours.

    Ring point ``i`` (all rings of all pieces, one after another, without closing
    points) is vertex ``vid[i]`` at ``xy[vid[i]]``; its edge runs to point
    ``nxt[i]``. ``level[i]`` is the level of the piece on the edge's left,
    ``out_level[i]`` that on its right (0, the bottom, where there is none).
    """

    xy: np.ndarray
    vid: np.ndarray
    nxt: np.ndarray
    level: np.ndarray
    out_level: np.ndarray
    twin: np.ndarray  # ring point of the reverse edge, -1 where there is none
    ring_start: np.ndarray  # start of each ring, with the end
    piece_rings: np.ndarray  # first ring of each piece, with the end
    piece_level: np.ndarray
    tris: np.ndarray | None  # (m, 3) ring point indices of each piece's triangles
    tri_level: np.ndarray | None


def topology(cov: Coverage, *, triangulate: bool = True, exact: bool = False) -> Topology:
    """Number the vertices of a coverage, pair its edges and (optionally) triangulate its pieces.

    Vertices are the same when they round to the same grid point, or with
    ``exact``, when their coordinates are equal (pieces of one exact overlay
    share their vertices bit for bit; the STEP writer's B-rep keeps them so).

    Raises :class:`~fabtiles.FabricationError` if two pieces claim the same
    directed edge (they overlap), which a proper coverage never does.
    """
    import shapely

    if not cov.pieces:
        raise FabricationError("nothing to mesh: the material region is empty")
    polys = np.array([p for p, _ in cov.pieces], dtype=object)
    plevel = np.array([lvl for _, lvl in cov.pieces])
    _, coords, (ring_off, part_off, multi_off) = shapely.to_ragged_array(polys)
    ring_off = np.asarray(ring_off)
    part_off = np.asarray(part_off)  # rings of each polygon
    multi_off = np.asarray(multi_off)  # polygons of each piece
    poly_off = part_off[multi_off]  # rings of each piece
    # drop each ring's closing point
    keep = np.ones(len(coords), bool)
    keep[ring_off[1:] - 1] = False
    pts = np.asarray(coords, float)[keep]
    ring_len = np.diff(ring_off) - 1
    starts = np.concatenate([[0], np.cumsum(ring_len)])
    ring_level = np.repeat(plevel, np.diff(poly_off))
    idx = np.arange(len(pts))
    nxt = idx + 1
    nxt[starts[1:] - 1] = starts[:-1]
    edge_lvl = np.repeat(ring_level, ring_len)
    tri_idx, tri_lvl = [], []
    if triangulate:
        grid = np.round(pts / QUANTUM).astype(np.int64)
        for k in range(len(polys)):
            r0, r1 = poly_off[k], poly_off[k + 1]
            rings = (starts, ring_len[r0:r1], part_off[multi_off[k] : multi_off[k + 1] + 1], nxt)
            found = _piece_triangles(polys[k], pts, grid, r0, r1, rings)
            if found is None:
                continue
            base, tris = found
            tri_idx.append(base[tris])
            tri_lvl.append(np.full(len(tris), plevel[k]))
        if not tri_idx:
            raise FabricationError("nothing to mesh: the material region is empty")
    xy, inv, n2 = _vertex_ids(pts, exact)
    u, v = inv, inv[nxt]
    a, b = _edge_twins(u, v, n2)
    out_lvl = np.zeros(len(u), dtype=edge_lvl.dtype)
    out_lvl[a] = edge_lvl[b]
    out_lvl[b] = edge_lvl[a]
    degenerate = u == v
    out_lvl[degenerate] = edge_lvl[degenerate]  # no wall on a zero-length edge
    twin = np.full(len(u), -1)
    twin[a] = b
    twin[b] = a
    return Topology(
        xy=xy,
        vid=inv,
        nxt=nxt,
        level=edge_lvl,
        out_level=out_lvl,
        twin=twin,
        ring_start=starts,
        piece_rings=poly_off,
        piece_level=plevel,
        tris=np.concatenate(tri_idx) if tri_idx else None,
        tri_level=np.concatenate(tri_lvl) if tri_lvl else None,
    )


def _piece_triangles(poly, pts, grid, r0: int, r1: int, rings):
    """``(ring points, triangles)`` of one piece (rings r0..r1), or None when it has no ring to fill.

    Ear clipping on the grid first (:func:`ear_clip`), manifold3d's triangulator where it
    gives up, then the degenerate triangles flipped away and, if some stay flat, a
    constrained Delaunay triangulation (:func:`cdt`). ``rings``: ``(starts, ring lengths,
    the piece's polygons' ring offsets, next point)`` of the coverage's ring points.
    """
    m3 = import_uninterrupted("manifold3d")

    starts, ring_len, part_off, nxt = rings
    tris = None
    if ring_len.min() >= 3:
        base = np.arange(starts[r0], starts[r1])
        ij = grid[base]
        tris = ear_clip(ij, starts, part_off, nxt[base] - starts[r0])
    if tris is None:
        full = [r for r in range(r0, r1) if ring_len[r - r0] >= 3]
        if not full:
            return None
        tris = np.asarray(m3.triangulate([pts[starts[r] : starts[r + 1]] for r in full]), dtype=np.int64).reshape(-1, 3)
        # the triangulator numbers the points of the rings it was given, in order
        base = np.concatenate([np.arange(starts[r], starts[r + 1]) for r in full])
        ij = grid[base]
    tris = flip_degenerate(tris, ij)
    if flat(tris, ij).any():
        tris = cdt(poly, ij)
    return base, tris


def _vertex_ids(pts, exact: bool):
    """``(xy, vid, n)``: the distinct vertices of the ring points ``pts``, each point's vertex, how many.

    Points are one vertex when they round to one grid point (the vertex there), or with
    ``exact`` when their coordinates are equal.
    """
    if exact:
        xy, inv = np.unique(pts, axis=0, return_inverse=True)
        return xy, inv.ravel(), len(xy)
    ij = np.round(pts / QUANTUM).astype(np.int64)
    keys = (ij[:, 0] + (1 << 30)) * (1 << 31) + (ij[:, 1] + (1 << 30))
    uniq, inv = np.unique(keys, return_inverse=True)
    inv = inv.ravel()
    xy = np.zeros((len(uniq), 2))
    xy[inv] = pts
    return np.round(xy / QUANTUM) * QUANTUM, inv, len(uniq)


def _edge_twins(u, v, n: int):
    """``(a, b)``: the ring points of each directed edge ``u -> v`` and of its reverse, paired by one sort.

    Raises :class:`~fabtiles.FabricationError` where an edge has more than two pieces or
    two pieces run it the same way (they overlap).
    """
    ok = np.flatnonzero(u != v)
    ukey = np.minimum(u[ok], v[ok]) * n + np.maximum(u[ok], v[ok])
    order = np.argsort(ukey, kind="stable")
    sk = ukey[order]
    same_next = sk[1:] == sk[:-1]
    if np.any(same_next[1:] & same_next[:-1]):
        raise FabricationError("cannot mesh the region: an edge is shared by more than two pieces")
    a, b = ok[order[:-1][same_next]], ok[order[1:][same_next]]
    if np.any(u[a] == u[b]):
        raise FabricationError("cannot mesh the region: two pieces overlap (the region is not a clean coverage)")
    return a, b


def mesh_coverage(cov: Coverage, recess=None):
    """Mesh a coverage as one stack: returns ``(vertices (n, 3) float64, faces (m, 3) int64)``.

    ``recess`` (a :class:`~fabtiles.geometry.stack.Recess`, on the grid, strictly inside
    the bottom and shallower than the lowest level over it) is sunk into the bottom
    (:func:`_recess_faces`).
    """
    topo = topology(cov)
    assert topo.tris is not None and topo.tri_level is not None  # topology() triangulates by default
    nl = len(cov.levels)
    tris = topo.vid[topo.tris]
    top = tris * nl + topo.tri_level[:, None]
    u, v = topo.vid, topo.vid[topo.nxt]
    cup = None
    if recess is None:
        own = bottom_triangles(u, v, topo.out_level, topo.xy)
        bottom = ((tris if own is None else own) * nl)[:, ::-1]
    else:
        bottom, cup = _recess_faces(u, v, topo, nl, recess)
    walls = []
    if nl >= 4:
        walls = [_ladder_walls(u, v, topo.out_level, topo.level, nl, len(topo.xy))]
    else:
        for lo in range(nl - 1):
            sel = (topo.out_level <= lo) & (topo.level > lo)
            uu, vv = u[sel], v[sel]
            a, b = uu * nl + lo, vv * nl + lo
            c, d = vv * nl + lo + 1, uu * nl + lo + 1
            walls.append(np.stack([a, b, c], axis=1))
            walls.append(np.stack([a, c, d], axis=1))
    faces = np.concatenate([top, bottom] + walls + ([cup[0]] if cup is not None else []))
    # number the used (vertex, level) ids in order: a mark and a cumulative sum, no sort
    n_ids = len(topo.xy) * nl
    mark = np.zeros(n_ids + (len(cup[1]) if cup is not None else 0), bool)
    mark[faces.ravel()] = True
    used = np.flatnonzero(mark)
    new_id = np.cumsum(mark) - 1
    faces = new_id[faces]
    verts = np.empty((len(used), 3))
    grid = used[used < n_ids]
    verts[: len(grid), :2] = topo.xy[grid // nl]
    verts[: len(grid), 2] = cov.levels[grid % nl]
    if cup is not None:  # the recess's points, numbered after the coverage's
        verts[len(grid) :] = cup[1][used[len(grid) :] - n_ids]
    return verts, faces


def _recess_faces(u, v, topo, nl: int, recess):
    """``(bottom, (cup, points))``: the faces of a bottom with ``recess`` sunk into it.

    The bottom is its outline less the recess, triangulated on its own
    (:func:`~fabtiles.solid._triangulate.recessed_bottom`); the recess is a cup: its
    walls from the bottom up to ``recess.depth`` and its roof there, facing down. Its
    points are ids ``len(xy) * nl + k``: each recess ring point at z = 0, then again at
    the depth. Nothing else changes: the walls and tops above do not reach the recess.
    """
    import shapely

    rings = []
    for poly in shapely.get_parts(shapely.orient_polygons(recess.region)):
        for ring in (poly.exterior, *poly.interiors):
            rings.append(np.asarray(ring.coords, float)[:-1])
    found = recessed_bottom(u, v, topo.out_level, topo.xy, rings)
    if found is None:
        raise FabricationError("the bottom with its recess (the piece's number) could not be triangulated")
    own, roof = found
    n_ids, m = len(topo.xy) * nl, sum(len(r) for r in rings)
    # the bottom's outline vertices at level 0; the recess's points at z = 0 (ids n_ids + k)
    bottom = np.where(own < len(topo.xy), own * nl, n_ids + own - len(topo.xy))[:, ::-1]
    starts = np.concatenate([[0], np.cumsum([len(r) for r in rings])])
    a = np.arange(m)
    b = a + 1
    b[starts[1:] - 1] = starts[:-1]  # each ring's last point to its first
    low, high = n_ids + a, n_ids + m + a
    low_b, high_b = n_ids + b, n_ids + m + b
    # the recess lies on each ring edge's left: its walls face it (the edge run backwards)
    walls = np.concatenate([np.stack([low_b, low, high], axis=1), np.stack([low_b, high, high_b], axis=1)])
    pts = np.concatenate(rings)
    points = np.concatenate([np.c_[pts, np.zeros(m)], np.c_[pts, np.full(m, recess.depth)]])
    cup = np.concatenate([walls, (n_ids + m + roof)[:, ::-1]])
    return bottom, (cup, points)


def _ladder_walls(u, v, out_level, level, nl: int, n_vertices: int) -> np.ndarray:
    """Wall triangles of the edges ``u -> v`` rising from ``out_level`` to ``level``, each
    split only at the levels its end vertices need (``(m, 3)`` ids ``vertex * nl + level``).

    With three or more levels over the bottom (an interlaced relief: plate, dips,
    full height) splitting every wall at every level crossed doubles the walls of
    every band edge that no dip touches (+400,000 triangles on the 600 x 400 mm
    sheet). Here a wall's side at a vertex breaks only at the levels where some
    wall at that vertex starts or ends, so the vertical edges still pair up; each
    wall is a ladder between its two sides, one triangle per break.

    >>> _ladder_walls(np.array([0]), np.array([1]), np.array([0]), np.array([2]), 4, 2).tolist()
    [[0, 4, 6], [0, 6, 2]]
    """
    sel = out_level < level
    u, v, lo, hi = u[sel], v[sel], out_level[sel].astype(np.int64), level[sel].astype(np.int64)
    bits = (np.int64(1) << lo) | (np.int64(1) << hi)
    mask = np.zeros(n_vertices, np.int64)
    np.bitwise_or.at(mask, u, bits)
    np.bitwise_or.at(mask, v, bits)
    mu, mv = mask[u], mask[v]

    def step(m, cur):
        """The next break above ``cur`` on a side (``hi`` at the latest)."""
        nxt = hi.copy()
        for k in range(nl - 1, 0, -1):
            here = (k > cur) & (k < hi) & (((m >> k) & 1) == 1)
            nxt[here] = k
        return nxt

    a, b = lo.copy(), lo.copy()  # current level on u's side and on v's side
    out = []
    while True:
        live = (a < hi) | (b < hi)
        if not live.any():
            break
        na, nb = step(mu, a), step(mv, b)
        right = live & (b < hi) & ((nb <= na) | (a >= hi))
        left = live & ~right
        out.append(np.stack([u[right] * nl + a[right], v[right] * nl + b[right], v[right] * nl + nb[right]], axis=1))
        out.append(np.stack([u[left] * nl + a[left], v[left] * nl + b[left], u[left] * nl + na[left]], axis=1))
        b = np.where(right, nb, b)
        a = np.where(left, na, a)
    return np.concatenate(out) if out else np.empty((0, 3), np.int64)


def coverage_pair(
    region,
    outline,
    *,
    region_z: float,
    rest_z: float,
    bottom: float,
    cell_vertices: int = CELL_VERTICES,
    shift: int = 0,
    cells=None,
) -> Coverage:
    """Cut an outline into the region (top at ``region_z``) and the rest (``rest_z``).

    Both inputs must be on the quantum grid. Cells fully inside the outline are
    split by a plain overlay (which keeps every input vertex); cells on the
    outline's edge use one snap-rounded overlay for both parts, so the two parts
    share their vertices exactly there too. ``shift`` moves the cell lines;
    ``cells`` gives them instead (as :func:`coverage`).
    """
    import shapely

    xs, ys, box = cells if cells is not None else cells_for([region, outline], cell_vertices, shift)
    levels = np.array(sorted({bottom, region_z, rest_z}))
    lr = int(np.searchsorted(levels, region_z))
    lo = int(np.searchsorted(levels, rest_z))
    r_cells, ex, ey = split_cells(node_polygons(region, xs, ys), xs, ys, box)
    o_cells, _, _ = split_cells(node_polygons(outline, xs, ys), xs, ys, box)
    r_by_cell = {(i, j): g for i, j, g in r_cells}
    shapely.prepare(outline)
    pieces = []
    for i, j, o_c in o_cells:
        r_c = r_by_cell.get((i, j))
        cell = shapely.box(ex[i], ey[j], ex[i + 1], ey[j + 1])
        if r_c is None or r_c.is_empty:
            pieces.append((o_c, lo))
            continue
        if shapely.contains_properly(outline, cell) or shapely.covered_by(r_c, o_c):
            rest = shapely.difference(o_c, r_c)
        else:
            rest = shapely.difference(o_c, r_c, grid_size=QUANTUM)
            r_c = shapely.intersection(r_c, o_c, grid_size=QUANTUM)
        pieces.append((r_c, lr))
        pieces.append((rest, lo))
    return coverage_from_cells(pieces, levels, xs, ys)
