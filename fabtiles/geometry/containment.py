"""Which small convex quadrilaterals lie inside a polygon: in numpy, for thousands at once.

An interlaced relief asks this of every sliver beside a crossing (12,700 tested
on a 600 x 400 mm sheet) against a region with 75,000 boundary edges. A convex
quad lies in the interior of a polygon exactly when no edge of the polygon's
boundary meets it (closed) and one of its points is inside. The first half is a
join of the boundary edges and the quads on a uniform grid of about a quad's
size, then a separating-axis test per candidate pair (in floating point: only a
touch closer than about 1e-12 mm could be judged otherwise than GEOS judges it);
the second is GEOS's point in polygon (:func:`shapely.contains_xy`) for one point
of each quad no edge meets. Quicker than probing the quads' four corners with GEOS
and every boundary vertex against them, and than GEOS's containment test of each quad
(``docs/speed.md``).
"""

from __future__ import annotations

import numpy as np
import shapely

MAX_CELLS = 4_000_000
"""At most this many grid cells (a few quads spread over a huge area get larger cells)."""


def quads_inside(region, quads, *, centre_inside=None) -> np.ndarray:
    """Which convex quadrilaterals ``(k, 4, 2)`` lie in the interior of ``region``.

    A quad touching the boundary is not inside (as
    :func:`shapely.contains_properly`). Either orientation. ``centre_inside``
    (optional, a mask) marks the quads whose centroid the caller knows lies in
    ``region``: they skip the point in polygon test.

    >>> from shapely.geometry import box
    >>> square = box(0, 0, 10, 10).difference(box(4, 4, 6, 6))
    >>> q = np.array([[[1, 1], [2, 1], [2, 2], [1, 2]],  # inside
    ...               [[3, 3], [5, 3], [5, 5], [3, 5]],  # over the hole's corner
    ...               [[4.5, 4.5], [5.5, 4.5], [5.5, 5.5], [4.5, 5.5]],  # in the hole
    ...               [[0, 1], [1, 1], [1, 2], [0, 2]]], float)  # on the edge
    >>> quads_inside(square, q).tolist()
    [True, False, False, False]
    """
    quads = np.asarray(quads, float).reshape(-1, 4, 2)
    inside = np.zeros(len(quads), bool)
    if not len(quads) or region.is_empty:
        return inside
    a, b = boundary_edges(region)
    free = ~edges_meet_quads(a, b, quads)
    if centre_inside is not None:
        inside[free & centre_inside] = True
        free &= ~centre_inside
    if free.any():
        c = quads[free].mean(axis=1)  # a convex quad holds its centroid
        shapely.prepare(region)
        inside[free] = shapely.contains_xy(region, c[:, 0], c[:, 1])
    return inside


def boundary_edges(geom):
    """The edges ``(a, b)`` (two ``(m, 2)`` arrays) of every ring of a (Multi)Polygon."""
    rings = shapely.get_rings(shapely.get_parts(geom))
    pts, ring = shapely.get_coordinates(rings, return_index=True)
    same = ring[1:] == ring[:-1]
    return pts[:-1][same], pts[1:][same]


def edges_meet_quads(a, b, quads) -> np.ndarray:
    """For each convex quad ``(k, 4, 2)``, whether some segment ``a[i] -> b[i]`` meets it (closed).

    Edges and quads are joined on a grid of cells about a quad's size (an edge
    longer than a cell is cut into cell-long pieces first, so each piece touches
    at most four cells); each pair sharing a cell and overlapping boxes is
    tested exactly (:func:`_segment_meets_quad`).

    >>> sq = np.array([[[0, 0], [1, 0], [1, 1], [0, 1]]], float)
    >>> edges_meet_quads(np.array([[2, -1.0], [-1, 0.5]]), np.array([[2, 3.0], [0.5, 0.5]]), sq).tolist()
    [True]
    """
    k = len(quads)
    meets = np.zeros(k, bool)
    if not k or not len(a):
        return meets
    qlo, qhi = quads.min(axis=1), quads.max(axis=1)
    # only the edges near some quad
    lo_all, hi_all = qlo.min(axis=0), qhi.max(axis=0)
    near = np.all((np.minimum(a, b) <= hi_all) & (np.maximum(a, b) >= lo_all), axis=1)
    a, b = a[near], b[near]
    if not len(a):
        return meets
    span = np.maximum(hi_all - lo_all, 1e-9)
    # cells about a quad's size, at most MAX_CELLS of them (a dense grid: no sort of the pieces)
    cell = max(float(np.median(np.max(qhi - qlo, axis=1))), float(np.sqrt(span[0] * span[1] / MAX_CELLS)), 1e-9)
    # edges cut into pieces shorter than a cell: each in at most 2 x 2 cells
    n_cut = np.maximum(np.ceil(np.linalg.norm(b - a, axis=1) / (0.99 * cell)).astype(np.int64), 1)
    long = np.flatnonzero(n_cut > 1)  # most edges are shorter than a cell: kept whole
    if len(long):
        e = np.repeat(long, n_cut[long])
        t0 = (np.arange(len(e)) - np.repeat(np.cumsum(n_cut[long]) - n_cut[long], n_cut[long])) / n_cut[e]
        t1 = t0 + 1.0 / n_cut[e]
        short = n_cut == 1
        pa = np.concatenate([a[short], a[e] + t0[:, None] * (b[e] - a[e])])
        pb = np.concatenate([b[short], np.where((t1 >= 1.0)[:, None], b[e], a[e] + t1[:, None] * (b[e] - a[e]))])
    else:
        pa, pb = a, b
    plo, phi = np.minimum(pa, pb), np.maximum(pa, pb)
    # the quads listed cell by cell (cells -1 .. top on each axis, numbered from 0)
    top = np.floor(span / cell).astype(np.int64) + 1
    stride = int(top[1]) + 2
    q_key, q_id = _cells(qlo, qhi, lo_all, cell, top)
    order = np.argsort(q_key, kind="stable")
    q_id = q_id[order]
    in_cell = np.bincount(q_key, minlength=(int(top[0]) + 2) * stride)
    cell_start = np.cumsum(in_cell) - in_cell
    # each piece's (up to four) cells, those holding quads
    i0 = np.clip(np.floor((plo - lo_all) / cell), -1, top).astype(np.int64)
    i1 = np.clip(np.floor((phi - lo_all) / cell), -1, top).astype(np.int64)
    keys, ids = [], []
    for dx, dy in ((0, 0), (1, 0), (0, 1), (1, 1)):
        cx, cy = i0[:, 0] + dx, i0[:, 1] + dy
        key = (cx + 1) * stride + (cy + 1)
        ok = (cx <= i1[:, 0]) & (cy <= i1[:, 1])
        ok[ok] = in_cell[key[ok]] > 0
        keys.append(key[ok])
        ids.append(np.flatnonzero(ok))
    p_key, p_id = np.concatenate(keys), np.concatenate(ids)
    count = in_cell[p_key]
    piece = np.repeat(p_id, count)
    quad = q_id[
        np.repeat(cell_start[p_key], count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    ]
    # boxes overlapping, x then y (each test on fewer pairs)
    keep = (plo[piece, 0] <= qhi[quad, 0]) & (phi[piece, 0] >= qlo[quad, 0])
    piece, quad = piece[keep], quad[keep]
    keep = (plo[piece, 1] <= qhi[quad, 1]) & (phi[piece, 1] >= qlo[quad, 1])
    piece, quad = piece[keep], quad[keep]
    ccw = quads.copy()  # every quad counter-clockwise, its edge vectors: once
    cw = (
        np.sum(
            quads[:, :, 0] * np.roll(quads[:, :, 1], -1, axis=1) - np.roll(quads[:, :, 0], -1, axis=1) * quads[:, :, 1],
            axis=1,
        )
        < 0
    )
    ccw[cw] = quads[cw, ::-1]
    edge = np.roll(ccw, -1, axis=1) - ccw
    hit = _segment_meets_quad(pa[piece], pb[piece], ccw[quad], edge[quad])
    meets[quad[hit]] = True
    return meets


def _cells(lo, hi, origin, cell, top):
    """Keys of the grid cells each box ``lo``-``hi`` covers, and the box of each key.

    Cells are counted from ``origin``; indices below 0 or from ``top`` on (x, y)
    are clamped to -1 and ``top`` (no quad lies there).
    """
    i0 = np.clip(np.floor((lo - origin) / cell), -1, top).astype(np.int64)
    i1 = np.clip(np.floor((hi - origin) / cell), -1, top).astype(np.int64)
    nx, ny = i1[:, 0] - i0[:, 0] + 1, i1[:, 1] - i0[:, 1] + 1
    cnt = nx * ny
    box = np.repeat(np.arange(len(lo)), cnt)
    r = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    cx, cy = i0[box, 0] + r % nx[box], i0[box, 1] + r // nx[box]
    return (cx + 1) * (int(top[1]) + 2) + (cy + 1), box


def _segment_meets_quad(a, b, q, edge) -> np.ndarray:
    """Whether segment ``a -> b`` meets the counter-clockwise convex quad ``q`` (closed), pair
    by pair (``edge``: the quad's edge vectors, ``q[i + 1] - q[i]``).

    Separating axes: the segment misses the quad exactly when it lies wholly
    outside one of the quad's edges, or the quad wholly on one side of the
    segment's line.
    """
    d = b - a
    rel = q - a[:, None, :]
    o = d[:, None, 0] * rel[:, :, 1] - d[:, None, 1] * rel[:, :, 0]
    meets = ~(np.all(o > 0, axis=1) | np.all(o < 0, axis=1))  # the quad across the segment's line
    k = np.flatnonzero(meets)  # then only those: the segment wholly outside one of the quad's edges?
    q, e = q[k], edge[k]
    ra, rb = a[k, None, :] - q, b[k, None, :] - q
    out_a = e[:, :, 0] * ra[:, :, 1] - e[:, :, 1] * ra[:, :, 0] < 0
    out_b = e[:, :, 0] * rb[:, :, 1] - e[:, :, 1] * rb[:, :, 0] < 0
    meets[k] = ~np.any(out_a & out_b, axis=1)
    return meets
