"""Laser contours: kerf offset, clean rings, cut order (shared by the DXF and laser SVG writers).

A laser cuts along the boundary of the material. :func:`laser_contours` turns the
material region into the closed rings to cut, once, for every laser writer:

* **Kerf.** The material is grown by ``kerf/2`` (mitre joins with a limit, so the
  sharp tips of a star stay sharp): the outer contour moves outward, every hole
  inward, and the part comes off the bed at its nominal size. Holes narrower
  than the kerf close up and disappear. Every outer ring is grown and every hole
  shrunk on its own (vectorised, several times faster than buffering the whole
  region); pieces are joined only where they meet: parts closer than the kerf
  are united, islands lying in a hole are cut out of the shrunk hole.
* **Clean rings.** Coordinates are rounded to 1e-6 mm; repeated points (hence
  zero-length edges) and degenerate rings (area below ``tolerance_mm**2``) are
  dropped. The first point is not repeated at the end (the writers close the
  polylines). Outer rings run counter-clockwise, holes clockwise (material on the
  left of the head).
* **Order.** Inner contours come first, outer contours last. "Outer" is the outer
  ring of each top-level part (what frees a part from the sheet); everything
  inside it -- holes, and the rings of any part lying in a hole -- is "inner" and
  is cut deepest first, so nothing is cut on a piece that has already dropped.
  Inside one depth, and among outer contours, rings follow a Hilbert curve over
  their centres, so the head sweeps the sheet instead of zig-zagging. On a sheet
  of several tiles this cuts every hole of every tile first and every outline
  last (the usual "inside first, outside last" order).

>>> from shapely.geometry import box
>>> plate = box(0, 0, 10, 10).difference(box(4, 4, 6, 6))
>>> inner, outer = laser_contours(plate, box(0, 0, 10, 10), kerf_mm=0.2, tolerance_mm=0.01)
>>> len(inner), len(outer)
(1, 1)
>>> float(outer[0][:, 0].min()), float(inner[0][:, 0].min())
(-0.1, 4.1)
"""

from __future__ import annotations

import numpy as np
import shapely

from ..core.errors import ParameterError

MITRE_LIMIT = 5.0
"""Mitre limit of the kerf offset (a corner sharper than about 23 degrees is bevelled)."""

ROUND_DECIMALS = 6
"""Contours are rounded to this many decimals of a millimetre."""


def polygon_parts(region, name: str = "region") -> np.ndarray:
    """The non-empty polygons of ``region`` as an array, checking it is valid polygonal geometry.

    >>> from shapely.geometry import box
    >>> len(polygon_parts(box(0, 0, 1, 1).union(box(2, 0, 3, 1))))
    2
    """
    if not isinstance(region, shapely.Geometry):
        raise ParameterError(
            f"{name} must be a shapely Polygon or MultiPolygon, got {type(region).__name__}", param=name
        )
    parts = shapely.get_parts(region)
    if len(parts) == 0 or region.is_empty:
        raise ParameterError(f"{name} is empty: there is nothing to cut", param=name)
    kinds = set(shapely.get_type_id(parts).tolist())
    if not kinds <= {3}:
        raise ParameterError(f"{name} must be a shapely Polygon or MultiPolygon, got {region.geom_type}", param=name)
    if not shapely.is_valid(region):
        raise ParameterError(f"{name} is not a valid polygon: {shapely.is_valid_reason(region)}", param=name)
    parts = parts[~shapely.is_empty(parts)]
    return parts


def hilbert_order(points: np.ndarray, order: int = 16) -> np.ndarray:
    """Indices that sort ``points`` (n, 2) along a Hilbert curve over their bounding box.

    >>> pts = np.array([[0, 0], [10, 10], [0, 10], [10, 0]], dtype=float)
    >>> hilbert_order(pts).tolist()
    [0, 2, 1, 3]
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(pts) < 2:
        return np.arange(len(pts))
    n = 1 << order
    lo = pts.min(axis=0)
    span = float((pts.max(axis=0) - lo).max()) or 1.0
    xy = np.clip(((pts - lo) / span * (n - 1)).round(), 0, n - 1).astype(np.int64)
    x, y = xy[:, 0].copy(), xy[:, 1].copy()
    d = np.zeros(len(pts), dtype=np.int64)
    s = n >> 1
    while s > 0:
        rx = ((x & s) > 0).astype(np.int64)
        ry = ((y & s) > 0).astype(np.int64)
        d += s * s * ((3 * rx) ^ ry)
        flip = (ry == 0) & (rx == 1)
        x = np.where(flip, n - 1 - x, x)
        y = np.where(flip, n - 1 - y, y)
        swap = ry == 0
        x, y = np.where(swap, y, x), np.where(swap, x, y)
        s >>= 1
    return np.argsort(d, kind="stable")


def _buffer(geoms, d):
    return shapely.buffer(geoms, d, join_style="mitre", mitre_limit=MITRE_LIMIT) if d else geoms


def _kerf_polygons(parts: np.ndarray, d: float):
    """Polygons whose rings are the cuts of ``parts`` grown by ``d``, with the depth of their outer rings.

    Exact and local: every outer ring is grown and every hole shrunk on its own;
    only where grown pieces meet are they joined -- top-level parts closer than
    the kerf are united, and the pieces lying in a hole (islands) are subtracted
    from that shrunk hole. The depth of a polygon's outer ring is 0 for a top-level
    part; its interior rings are one deeper.
    """
    n = len(parts)
    filled = shapely.polygons(shapely.get_exterior_ring(parts))
    a, b = shapely.STRtree(filled).query(filled, predicate="within")
    a, b = a[a != b], b[a != b]
    level = np.bincount(a, minlength=n)  # how many parts enclose each part
    container = np.full(n, -1)
    order = np.argsort(level[b], kind="stable")
    container[a[order]] = b[order]  # the innermost enclosing part wins
    nholes = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(n), nholes)
    hole_idx = np.concatenate([np.arange(k) for k in nholes]) if n else np.empty(0, int)
    holes = shapely.polygons(shapely.get_interior_ring(parts[owner], hole_idx))
    hole_of = np.full(n, -1)
    nested = np.flatnonzero(container >= 0)
    if len(nested):
        pa, hb = shapely.STRtree(holes).query(shapely.point_on_surface(parts[nested]), predicate="within")
        ok = owner[hb] == container[nested[pa]]
        hole_of[nested[pa[ok]]] = hb[ok]
    grown = _buffer(filled, d)
    # a hole narrower than the kerf closes: its bounding box tells most of them cheaply
    shrunk = np.full(len(holes), shapely.Polygon(), dtype=object)
    bb = shapely.bounds(holes)
    keep = np.minimum(bb[:, 2] - bb[:, 0], bb[:, 3] - bb[:, 1]) > 2 * d
    shrunk[keep] = _buffer(holes[keep], -d)
    polys, depth = [], []
    # top-level parts; those whose grown rings meet are united
    top = np.flatnonzero(container < 0)
    tops = grown[top]
    if d and len(top) > 1:
        ta, tb = shapely.STRtree(tops).query(tops, predicate="intersects")
        meet = np.zeros(len(top), dtype=bool)
        meet[ta[ta != tb]] = True
        if meet.any():
            tops = np.concatenate([tops[~meet], shapely.get_parts(shapely.union_all(tops[meet]))])
    polys.append(tops)
    depth.append(np.zeros(len(tops), dtype=int))
    # holes: islands inside a hole are cut out of it
    with_islands = np.unique(hole_of[hole_of >= 0])
    free = shrunk.copy()
    for k in with_islands.tolist():
        free[k] = shapely.difference(shrunk[k], shapely.union_all(grown[hole_of == k]))
    free, idx = shapely.get_parts(free, return_index=True)
    polys.append(free)
    depth.append(2 * level[owner[idx]] + 1)
    return np.concatenate(polys), np.concatenate(depth)


def _rings_of(polys: np.ndarray):
    """All rings of the (non-empty) ``polys``: (ring geometries, part index, is_exterior)."""
    rings, part = shapely.get_rings(polys, return_index=True)
    nint = shapely.get_num_interior_rings(polys)
    first = np.zeros(len(rings), dtype=bool)
    starts = np.concatenate([[0], np.cumsum(nint + 1)[:-1]]) if len(polys) else np.empty(0, int)
    first[starts] = True
    return rings, part, first


def clean_rings(rings, *, min_area: float = 0.0, ccw=None):
    """Coordinates of closed ``rings`` as a list of (m, 2) arrays, cleaned.

    Rounded to :data:`ROUND_DECIMALS`, closing point dropped, consecutive repeated
    points removed, rings with fewer than 3 points or area <= ``min_area`` dropped.
    ``ccw`` (bool array, one per ring) orients each ring counter-clockwise where
    True and clockwise where False. Returns (list of arrays, indices kept).

    >>> from shapely.geometry import LinearRing
    >>> out, kept = clean_rings([LinearRing([(0, 0), (0, 0), (1, 0), (1, 1)])], ccw=np.array([True]))
    >>> out[0].tolist()
    [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]
    """
    rings = np.asarray(rings, dtype=object)
    if len(rings) == 0:
        return [], np.empty(0, dtype=int)
    coords, idx = shapely.get_coordinates(rings, return_index=True)
    coords = np.round(coords, ROUND_DECIMALS) + 0.0  # + 0.0 turns -0.0 into 0.0
    n = len(coords)
    # drop the closing point of each ring, then repeats of the previous point in the same ring
    last = np.ones(n, dtype=bool)
    last[:-1] = idx[1:] != idx[:-1]
    same = np.zeros(n, dtype=bool)
    same[1:] = (idx[1:] == idx[:-1]) & np.all(coords[1:] == coords[:-1], axis=1)
    keep = ~(last | same)
    coords, idx = coords[keep], idx[keep]
    # wrap-around repeat: last kept point equal to the first of its ring
    if len(idx):
        starts = np.flatnonzero(np.r_[True, idx[1:] != idx[:-1]])
        ends = np.r_[starts[1:], len(idx)] - 1
        dup = np.all(coords[ends] == coords[starts], axis=1) & (ends > starts)
        mask = np.ones(len(idx), dtype=bool)
        mask[ends[dup]] = False
        coords, idx = coords[mask], idx[mask]
    if not len(idx):
        return [], np.empty(0, dtype=int)
    starts = np.flatnonzero(np.r_[True, idx[1:] != idx[:-1]])
    counts = np.diff(np.r_[starts, len(idx)])
    x, y = coords[:, 0], coords[:, 1]
    nxt = np.arange(len(idx)) + 1
    ends = starts + counts
    nxt[ends - 1] = starts
    area2 = np.add.reduceat(x * y[nxt] - x[nxt] * y, starts)
    ring_ids = idx[starts]
    ok = (counts >= 3) & (np.abs(area2) / 2 > min_area)
    out = []
    for s, c, a, r, good in zip(
        starts.tolist(), counts.tolist(), area2.tolist(), ring_ids.tolist(), ok.tolist(), strict=True
    ):
        if not good:
            continue
        ring = coords[s : s + c]
        if ccw is not None and (a > 0) != bool(ccw[r]):
            ring = ring[::-1]
        out.append(ring)
    return out, ring_ids[ok]


def _order(rings: list, depth: np.ndarray | None = None) -> list:
    if not rings:
        return []
    flat = np.concatenate(rings)
    starts = np.cumsum([0] + [len(r) for r in rings[:-1]])
    centres = (np.minimum.reduceat(flat, starts) + np.maximum.reduceat(flat, starts)) / 2
    order = hilbert_order(centres)
    if depth is not None:
        order = order[np.argsort(-depth[order], kind="stable")]
    return [rings[i] for i in order]


def _anisotropic(kerf_mm: float, kerf_y_mm):
    """``(y scale, kerf)`` that turn an offset by an ellipse into a round one (1.0: round already).

    A laser whose spot is wider along Y than along X cuts a kerf ``kerf_y`` across
    horizontal edges and ``kerf_x`` across vertical ones: the cut edge is the material
    grown by the ellipse of semi-axes ``kerf_x / 2``, ``kerf_y / 2`` (its support
    distance along each edge's normal). Scaling y by ``kerf_x / kerf_y`` makes that
    ellipse a circle of radius ``kerf_x / 2``; the round (mitred) offset there, scaled
    back, is the elliptical one, corners and all, since an affine map keeps lines and
    mitres. Tested against GEOS's buffer of the scaled geometry and against the
    ellipse's support distance on every edge.
    """
    if kerf_y_mm is None or abs(float(kerf_y_mm) - float(kerf_mm)) < 1e-12:
        return 1.0, float(kerf_mm)
    kx, ky = float(kerf_mm), float(kerf_y_mm)
    if kx < 1e-9 or ky < 1e-9:
        raise ParameterError(
            f"kerf_x_mm and kerf_y_mm must both be > 0 or both equal, got {kx:g} and {ky:g}", param="kerf_y_mm"
        )
    return kx / ky, kx


def _scaled(geoms, sy: float):
    return geoms if sy == 1.0 else shapely.transform(geoms, lambda c: c * [1.0, sy])


def laser_contours(
    region,
    outline=None,
    *,
    kerf_mm: float,
    kerf_y_mm: float | None = None,
    tolerance_mm: float = 0.01,
    validate: bool = True,
):
    """Kerf-offset closed contours of ``region`` in cut order: ``(inner, outer)``.

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The material, in file coordinates (mm).
    outline : shapely geometry, optional
        The tile outline (unused in the pierced mode; accepted for a uniform call).
    kerf_mm : float
        Width of the cut, >= 0; contours move ``kerf_mm / 2`` away from the material.
    kerf_y_mm : float, optional
        The kerf along Y when it differs from ``kerf_mm`` (then the kerf along X): the
        contours move by the ellipse of those widths (see :func:`_anisotropic`).
    tolerance_mm : float
        Rings with area below ``tolerance_mm ** 2`` are numerical noise and dropped.
    validate : bool
        Check ``region`` is valid polygonal geometry (skip when the caller already did).

    Returns
    -------
    inner, outer : list of ndarray (m, 2)
        Closed rings without the repeated first point, in the order to cut them.

    >>> from shapely.geometry import box
    >>> inner, outer = laser_contours(box(0, 0, 2, 1), kerf_mm=0, tolerance_mm=0.01)
    >>> inner, outer[0].tolist()
    ([], [[2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [0.0, 0.0]])
    """
    parts = polygon_parts(region) if validate else shapely.get_parts(region)
    sy, kerf = _anisotropic(kerf_mm, kerf_y_mm)
    parts = _scaled(parts, sy)
    d = kerf / 2
    polys, poly_depth = _kerf_polygons(parts, d if d >= 1e-9 else 0.0)  # below a nanometre is no kerf
    polys, poly_depth = polys[~shapely.is_empty(polys)], poly_depth[~shapely.is_empty(polys)]
    rings, part, first = _rings_of(polys)
    depth = poly_depth[part] + (~first)
    # outer rings counter-clockwise, hole rings clockwise: even depths are material's outer rings
    first = depth % 2 == 0
    min_area = float(tolerance_mm) ** 2
    cleaned, kept = clean_rings(_scaled(rings, 1.0 / sy), min_area=min_area, ccw=first)
    depth = depth[kept]
    is_outer = depth == 0
    inner = _order([r for r, o in zip(cleaned, is_outer, strict=True) if not o], depth[~is_outer])
    outer = _order([r for r, o in zip(cleaned, is_outer, strict=True) if o])
    return inner, outer


def outline_contours(outline, *, kerf_mm: float, kerf_y_mm: float | None = None, tolerance_mm: float = 0.01) -> list:
    """The outer rings of ``outline`` grown by ``kerf_mm / 2``: the cut of the score mode.

    >>> from shapely.geometry import box
    >>> outline_contours(box(0, 0, 1, 1), kerf_mm=0.2)[0].min(axis=0).tolist()
    [-0.1, -0.1]
    """
    parts = polygon_parts(outline, "outline")
    sy, kerf = _anisotropic(kerf_mm, kerf_y_mm)
    filled = _scaled(shapely.polygons(shapely.get_exterior_ring(parts)), sy)
    grown = shapely.get_parts(shapely.buffer(filled, kerf / 2, join_style="mitre", mitre_limit=MITRE_LIMIT))
    rings = _scaled(shapely.get_exterior_ring(grown), 1.0 / sy)
    cleaned, _ = clean_rings(rings, min_area=float(tolerance_mm) ** 2, ccw=np.ones(len(rings), bool))
    return _order(cleaned)


def unique_segments(segments) -> np.ndarray:
    """Segments ``(k, 2, 2)`` rounded to :data:`ROUND_DECIMALS`, each run from its lower end (by x, then y),
    zero-length ones and repeats dropped, sorted: what is cut or drawn once.

    >>> unique_segments([[[1, 0], [0, 0]], [[0, 0], [1, 0]], [[2, 2], [2, 2]]]).tolist()
    [[[0.0, 0.0], [1.0, 0.0]]]
    """
    seg = np.round(np.asarray(segments, float).reshape(-1, 2, 2), ROUND_DECIMALS) + 0.0
    seg = seg[np.any(seg[:, 0] != seg[:, 1], axis=1)]
    flip = (seg[:, 0, 0] > seg[:, 1, 0]) | ((seg[:, 0, 0] == seg[:, 1, 0]) & (seg[:, 0, 1] > seg[:, 1, 1]))
    seg[flip] = seg[flip][:, ::-1]
    return np.unique(seg.reshape(-1, 4), axis=0).reshape(-1, 2, 2)


def score_paths(centrelines, outline, *, tolerance_mm: float = 0.01) -> list:
    """Centre-lines clipped to ``outline`` and joined into open paths (the score layer).

    Segments are rounded to 1e-6 mm, zero-length and repeated segments dropped, collinear ones
    that overlap joined (:func:`dissolve_overlaps`: a line shared by two motifs is scored once),
    and chains through vertices where exactly two segments meet merged into one path, so the
    file holds a few long paths instead of thousands of 2-point lines. Lines that cross are
    not split where they cross: the laser scores each straight through, one path each, not
    a path between every two crossings (a dense star's lines cross every few hundredths of a
    millimetre).

    >>> from shapely.geometry import box
    >>> seg = np.array([[[0, 0], [1, 0]], [[1, 0], [2, 1]], [[5, 5], [20, 5]]], dtype=float)
    >>> [p.tolist() for p in score_paths(seg, box(0, 0, 10, 10))]
    [[[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]], [[5.0, 5.0], [10.0, 5.0]]]
    """
    seg = np.asarray(centrelines, dtype=float)
    if seg.ndim != 3 or seg.shape[1:] != (2, 2):
        raise ParameterError(
            f"centrelines must be an array of shape (k, 2, 2), got shape {seg.shape}", param="centrelines"
        )
    if not np.all(np.isfinite(seg)):
        raise ParameterError("centrelines must be finite numbers, got NaN or infinite values", param="centrelines")
    seg = dissolve_overlaps(unique_segments(seg))
    if not len(seg):
        return []
    polygon_parts(outline, "outline")
    clip = shapely.get_parts(shapely.intersection(shapely.linestrings(seg), outline))  # each on its own
    clip = clip[(shapely.get_type_id(clip) == 1) & (shapely.length(clip) > 0)]
    if not len(clip):
        return []
    lines = shapely.get_parts(shapely.line_merge(shapely.multilinestrings(clip)))
    lines = lines[shapely.get_type_id(lines) == 1]
    lines = lines[shapely.length(lines) > tolerance_mm / 10]
    paths = []
    for coords in (shapely.get_coordinates(g) for g in lines):
        coords = np.round(coords, ROUND_DECIMALS) + 0.0
        keep = np.r_[True, np.any(coords[1:] != coords[:-1], axis=1)]
        coords = coords[keep]
        if len(coords) >= 2:
            paths.append(coords)
    return _order(paths)


def dissolve_overlaps(segments, *, tolerance_mm: float = 1e-5) -> np.ndarray:
    """Segments ``(k, 2, 2)`` with the collinear ones that overlap or meet end to end joined into one.

    Two segments within ``tolerance_mm`` of each other are collinear when the shorter one's ends lie
    within ``tolerance_mm`` of the longer one's line; every set of segments joined so is laid along its
    longest one's direction, and each run of them that overlaps becomes the segment from the
    first's start to the farthest end, both original points.

    >>> dissolve_overlaps([[[0, 0], [2, 0]], [[1, 0], [3, 0]], [[0, 1], [1, 2]]]).tolist()
    [[[0.0, 1.0], [1.0, 2.0]], [[0.0, 0.0], [3.0, 0.0]]]
    """
    from ..core.graph import components

    seg = np.asarray(segments, float).reshape(-1, 2, 2)
    if len(seg) < 2:
        return seg.copy()
    lines = shapely.linestrings(seg)
    i, j = shapely.STRtree(lines).query(lines, predicate="dwithin", distance=tolerance_mm)
    i, j = i[i < j], j[i < j]
    d = seg[:, 1] - seg[:, 0]
    length = np.linalg.norm(d, axis=1)

    def off(p, q):  # the larger distance of q's two ends from p's line
        r = seg[q] - seg[p][:, :1]
        return np.abs(d[p][:, None, 0] * r[..., 1] - d[p][:, None, 1] * r[..., 0]).max(axis=1) / length[p]

    long_, short = np.where(length[i] >= length[j], i, j), np.where(length[i] >= length[j], j, i)
    collinear = off(long_, short) <= tolerance_mm  # a short segment's direction is the less sure
    if not collinear.any():
        return seg.copy()
    group = components(len(seg), i[collinear], j[collinear])
    shared = np.bincount(group, minlength=len(seg))[group] > 1
    # each group along its longest segment: the place of every end on that line
    longest = np.zeros(len(seg), np.int64)
    members = np.flatnonzero(shared)
    by_length = members[np.lexsort((length[members], group[members]))]
    longest[group[by_length]] = by_length  # the last of each group, its longest, stays
    u = d[longest[group]] / length[longest[group]][:, None]
    t = np.einsum("kij,kj->ki", seg - seg[longest[group]][:, :1], u)
    lo_end = np.argmin(t, axis=1)
    out = [seg[~shared]]
    runs: list[list] = []  # (start point, farthest t, its point) of each run of overlapping segments in a group
    previous = -1
    along = np.lexsort((t.min(axis=1), group))  # group by group, each from its lowest end
    for k in along[shared[along]].tolist():
        a, b = seg[k, lo_end[k]], seg[k, 1 - lo_end[k]]
        ta, tb = t[k].min(), t[k].max()
        if group[k] != previous or ta > runs[-1][1] + tolerance_mm:
            runs.append([a, tb, b])
        elif tb > runs[-1][1]:
            runs[-1][1:] = [tb, b]
        previous = group[k]
    out.append(np.array([[a, b] for a, _, b in runs]))
    return np.concatenate(out)
