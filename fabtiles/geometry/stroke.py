"""Stroking centre-lines into material: bands with clean joins, unioned in one batch.

Why this is hand-written instead of ``shapely.MultiLineString(...).buffer(...)`` or
one ``shapely.union_all`` of the stroked bands: a 600 x 400 mm sheet with R = 15 mm
has tens of thousands of segments, and one GEOS union of all stroked bands takes
seconds (``benchmarks/bench_region.py``, ``docs/speed.md``). Here every
segment becomes a plain quad, every vertex where segments meet gets a small join
polygon (miter, bevel or round) filling the outer corners only, and everything is
unioned in one batch by Clipper2 (through ``manifold3d.CrossSection``, positive fill
rule), which measured several times faster for the same result.

Joins
    At each vertex the incident edges are sorted by angle. For each pair of
    consecutive edges whose angular gap exceeds 180 degrees (an outer corner)
    a join polygon is added: the miter point where the two offset edges meet;
    when that point lies farther than ``miter_limit * stroke / 2`` from the
    vertex the miter is cut square at that distance (as GEOS and Clipper do),
    so star tips stay sharp up to the limit; ``bevel`` joins the two offset
    corners straight; ``round`` adds an arc. Gaps under 180 degrees need no join:
    the two bands overlap there.
Caps (free ends, vertices of degree 1)
    ``butt`` for the miter and bevel joins (the band ends square at the
    endpoint), ``round`` for the round join. Ends at the tile's edge are cut by
    the outline clip anyway.
Vertices
    Endpoints closer than about 1e-6 mm are merged, so motifs that touch
    (tips meeting at a tangency point) share a vertex and get one clean join.
"""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from ..core.native import import_uninterrupted
from ..core.schema import key

JOINS: tuple[str, ...] = key("tile.join").choice_values()
"""Valid join styles."""

_MERGE = 1e-6  # mm: endpoints closer than about this are one vertex

MIN_HOLE_AREA = 1e-10
"""Holes smaller than this (mm^2) in a stroked union are rounding noise and dropped."""


def _cs():
    manifold3d = import_uninterrupted("manifold3d")

    return manifold3d


def segment_graph(segments: np.ndarray, *, return_ids: bool = False):
    """Merged vertices ``(v, 2)`` and unique undirected edges ``(e, 2)`` of the segments.

    With ``return_ids``, also the vertex ids ``(k, 2)`` of every input segment.
    """
    pts = segments.reshape(-1, 2)
    key = np.round(pts / _MERGE).astype(np.int64)
    first, inverse = _unique_rows(key)
    verts = pts[first]
    seg_ids = inverse.reshape(-1, 2)
    ids = seg_ids[seg_ids[:, 0] != seg_ids[:, 1]]
    ids = np.sort(ids, axis=1)
    ids = ids[_unique_rows(ids)[0]]
    return (verts, ids, seg_ids) if return_ids else (verts, ids)


def _unique_rows(key: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(first, inverse)`` of ``np.unique(key, axis=0, return_index=True, return_inverse=True)``
    for integer pairs ``key`` ``(n, 2)``: the unique rows in the same (lexicographic) order.

    ``np.unique`` with ``axis=0`` sorts the rows as records, several times slower than sorting
    one integer per row, which the pair is whenever its range allows (else two sort keys).
    """
    if not len(key):
        return np.empty(0, np.int64), np.empty(0, np.int64)
    lo = key.min(axis=0)
    span = key.max(axis=0) - lo + 1
    if float(span[0]) * float(span[1]) < 2.0**62:
        order = np.argsort((key[:, 0] - lo[0]) * span[1] + (key[:, 1] - lo[1]), kind="stable")
    else:
        order = np.lexsort((key[:, 1], key[:, 0]))
    ordered = key[order]
    new = np.r_[True, (ordered[1:] != ordered[:-1]).any(axis=1)]
    inverse = np.empty(len(key), np.int64)
    inverse[order] = np.cumsum(new) - 1
    return order[new], inverse


def clip_segments(seg: np.ndarray, outline) -> np.ndarray:
    """Segments ``(k, 2, 2)`` clipped to a convex ``outline``, merged where they meet (:meth:`Tile.centrelines`)."""
    lines = shapely.linestrings(seg)
    shapely.prepare(outline)
    # a segment strictly inside is its own clip: only the others go through GEOS's overlay, an
    # overlay a segment costing far more than the prepared outline's containment test
    clipped = lines.copy()
    cross = ~shapely.contains_properly(outline, lines)
    clipped[cross] = shapely.intersection(lines[cross], outline)
    keep = shapely.get_type_id(clipped) == 1  # LineString
    coords, idx = shapely.get_coordinates(clipped[keep], return_index=True)
    if not len(coords):
        return np.empty((0, 2, 2))
    first = np.r_[0, np.flatnonzero(np.diff(idx)) + 1]
    last = np.r_[first[1:] - 1, len(idx) - 1]
    out = np.stack([coords[first], coords[last]], axis=1)
    verts, edges = segment_graph(out)
    return verts[edges]


def band_polygons(verts: np.ndarray, edges: np.ndarray, half: float) -> np.ndarray:
    """One counter-clockwise quad ``(e, 4, 2)`` of half-width ``half`` per edge."""
    a, b = verts[edges[:, 0]], verts[edges[:, 1]]
    d = b - a
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    n = np.stack([-d[:, 1], d[:, 0]], axis=1) * half
    return np.stack([a - n, b - n, b + n, a + n], axis=1)


def join_polygons(verts, edges, half, *, join="miter", miter_limit=4.0, tolerance=0.005, at=None):
    """Join (and round cap) polygons at every outer corner, as a list of ``(k, m, 2)`` arrays.

    ``at`` (bool per vertex), if given, limits them to those vertices.
    """
    v = np.concatenate([edges[:, 0], edges[:, 1]])
    other = np.concatenate([edges[:, 1], edges[:, 0]])
    d = verts[other] - verts[v]
    ang = np.arctan2(d[:, 1], d[:, 0])
    order = np.lexsort((ang, v))
    v, ang = v[order], ang[order]
    starts = np.flatnonzero(np.r_[True, v[1:] != v[:-1]])
    counts = np.diff(np.r_[starts, len(v)])
    group_start = np.repeat(starts, counts)
    group_end = np.repeat(starts + counts, counts)
    idx = np.arange(len(v))
    nxt = np.where(idx + 1 < group_end, idx + 1, group_start)
    gap = ang[nxt] - ang
    gap = np.where(nxt <= idx, gap + 2.0 * math.pi, gap)  # wrap-around (and degree 1: 2 pi)
    degree = np.repeat(counts, counts)
    outer = gap > math.pi + 1e-12
    if join != "round":
        outer &= degree >= 2  # butt caps
    if at is not None:
        outer &= at[v]
    sel = np.flatnonzero(outer)
    if len(sel) == 0:
        return []
    c = verts[v[sel]]
    a0 = ang[sel]
    phi = gap[sel]
    out = []
    if join == "round":
        # arc from a0 + 90 deg to a0 + phi - 90 deg (sweep phi - 180 deg <= 180 deg), each
        # with as many chords as its own sweep needs (a slight bend needs one, a cap 12 at
        # the default tolerance), grouped by count so each group is one array
        step = 2.0 * math.acos(max(-1.0, 1.0 - tolerance / half)) if tolerance < half else math.pi / 2
        sweep = phi - math.pi
        count = np.maximum(1, np.ceil(sweep / step - 1e-9)).astype(np.int64)
        anchor = _anchor(c, a0, phi, half)
        for k in np.unique(count).tolist():
            g = count == k
            t = np.linspace(0.0, 1.0, k + 1)
            th = (a0[g] + math.pi / 2)[:, None] + sweep[g][:, None] * t[None, :]
            arc = c[g][:, None, :] + half * np.stack([np.cos(th), np.sin(th)], axis=-1)
            out.append(np.concatenate([anchor[g][:, None, :], arc], axis=1))
        return out
    da = np.stack([np.cos(a0), np.sin(a0)], axis=1)
    db = np.stack([np.cos(a0 + phi), np.sin(a0 + phi)], axis=1)
    pa = c + half * np.stack([-da[:, 1], da[:, 0]], axis=1)  # left of edge a
    pb = c + half * np.stack([db[:, 1], -db[:, 0]], axis=1)  # right of edge b
    anchor = _anchor(c, a0, phi, half)
    if join == "bevel":
        out.append(np.stack([anchor, pa, pb], axis=1))
        return out
    s = np.sin(phi / 2.0)
    dist = half / s
    u = np.stack([np.cos(a0 + phi / 2.0), np.sin(a0 + phi / 2.0)], axis=1)
    limit = miter_limit * half
    full = dist <= limit
    tip = c + dist[:, None] * u
    # Square cut at distance `limit` along the bisector: walk back along each offset edge.
    back = np.maximum(-np.cos(phi / 2.0), 1e-300)
    t_cut = (limit - half * s) / back
    qa = np.where(full[:, None], tip, pa - t_cut[:, None] * da)
    qb = np.where(full[:, None], tip, pb - t_cut[:, None] * db)
    out.append(np.stack([anchor, pa, qa, qb, pb], axis=1))
    return out


def _anchor(c, a0, phi, half):
    """The join polygon's inner corner: the vertex moved half a half-width into the bands.

    A join polygon that only shares the bands' butt-end edges (through the vertex) meets
    them along a line that floating-point rounding may open into a hairline gap; Clipper2
    then returns the join as a separate, loose piece (seen on table3-3 sheets: hundreds of
    specks). Moving its inner corner back along the bisector, into the wedge where both
    bands overlap, makes join and bands overlap by area, so the union is always one piece.
    The point stays inside both bands (its distance from each centre-line is below
    ``half``), so the material's outline does not change.
    """
    back = a0 + phi / 2.0 + math.pi
    return c + 0.5 * half * np.stack([np.cos(back), np.sin(back)], axis=1)


def stroke_cross_section(segments, width, *, join="miter", miter_limit=4.0, tolerance=0.005, circles=None):
    """Union of the stroked ``segments`` as a ``manifold3d.CrossSection``.

    Parameters
    ----------
    segments : array_like, shape (k, 2, 2)
        Centre-lines, mm.
    width : float
        Stroke width, mm (> 0).
    join : {"miter", "round", "bevel"}
    miter_limit : float
        Largest miter distance from the vertex, in half-widths (>= 1).
    tolerance : float
        Largest chord error of round joins, mm.
    circles : tuple of arrays (centres (m, 2), radii (m,)), optional
        Circles stroked too, as the chords of
        :func:`~fabtiles.pattern.packing.circle_segments` (what a packing's
        ``outline_circles`` adds to its segments; leave them out of ``segments``).
        Each chord polygon is stroked as one exact annulus: its miter offsets,
        the same angles at radius ``r +- half / cos(pi / k)``. That is the union its
        chords' miter-joined bands would give (round and bevel joins differ from it
        by at most ``2 * 0.005 * half / r`` mm, under the chords' own 0.005 mm
        flattening), at a fraction of the cost: one ring pair per circle instead of
        a band and a join per chord (the same holes, the boundaries within 2e-3 mm,
        in about half the time). Joins where ``segments`` meet a circle are
        computed with the chords, so motif tips on a circle keep their shape.
    """
    m3d = _cs()
    seg = np.asarray(segments, dtype=float).reshape(-1, 2, 2)
    chords = np.empty((0, 2, 2))
    if circles is not None:
        from ..pattern.packing import circle_segments

        chords = circle_segments(*circles)
    if len(seg) + len(chords) == 0:
        return m3d.CrossSection()
    half = width / 2.0
    verts, edges, seg_ids = segment_graph(np.concatenate([seg, chords]), return_ids=True)
    if len(edges) == 0:
        return m3d.CrossSection()
    rings = []
    at = None
    band_edges = edges
    if len(chords):
        # bands for the motif edges only; joins only where a motif edge ends
        n = len(verts)
        ids = np.sort(seg_ids, axis=1)
        chord_key = np.unique(ids[len(seg) :, 0] * n + ids[len(seg) :, 1])
        band_edges = edges[~np.isin(edges[:, 0] * n + edges[:, 1], chord_key)]
        at = np.zeros(n, bool)
        at[band_edges.ravel()] = True
        rings = _annulus_rings(circles[0], circles[1], half)
    polys = [band_polygons(verts, band_edges, half)] if len(band_edges) else []
    polys += join_polygons(verts, edges, half, join=join, miter_limit=miter_limit, tolerance=tolerance, at=at)
    contours = [p for block in polys for p in block]
    band_area = 2.0 * half * float(np.linalg.norm(verts[edges[:, 1]] - verts[edges[:, 0]], axis=1).sum())
    span = verts.max(axis=0) - verts.min(axis=0) + 2.0 * half
    if contours and band_area > _DENSE * float(span[0] * span[1]):
        bands = _bucketed_union(contours)
        return (
            m3d.CrossSection.batch_boolean([bands, m3d.CrossSection(rings, m3d.FillRule.Positive)], m3d.OpType.Add)
            if rings
            else bands
        )
    # An annulus's hole (clockwise) is nested in its own shell, so the positive fill
    # rule unions shells, holes and bands correctly in one batch.
    return m3d.CrossSection(contours + rings, m3d.FillRule.Positive)


def _annulus_rings(centres, radii, half) -> list:
    """The rings of the stroked chord polygon of every circle: shells CCW, holes CW.

    A circle of radius ``r`` with ``k`` chords (vertices at angles ``2 pi j / k``)
    stroked to half-width ``half`` with miter joins is the annulus between the
    regular ``k``-gons of radius ``r +- half / cos(pi / k)`` at the same angles;
    when ``r cos(pi / k) <= half`` the bands cover the middle and it is a disk.
    """
    from ..pattern.packing import chord_count

    centres = np.asarray(centres, dtype=float).reshape(-1, 2)
    radii = np.broadcast_to(np.asarray(radii, dtype=float), (len(centres),))
    rings = []
    for r in np.unique(radii):
        k = chord_count(r)
        t = np.linspace(0.0, 2.0 * math.pi, k + 1)[:-1]
        unit = np.stack([np.cos(t), np.sin(t)], axis=-1)
        d = half / math.cos(math.pi / k)
        for c in centres[radii == r]:
            rings.append(c + (r + d) * unit)
            if r - d > 0:
                rings.append(c + (r - d) * unit[::-1])
    return rings


# Bands covering their bounding box this many times over count as dense.
_DENSE = 2.0


def _bucketed_union(contours, per_bucket: int = 128):
    """Union in two levels: small spatial buckets first, then the buckets' results.

    When strokes are as wide as the pattern's features, every band overlaps dozens of
    others and one Clipper2 batch spends its time on edge intersections, several times
    longer than in buckets. Each bucket's union drops the interior edges before the final
    union. On sparse patterns (a sheet) one batch is faster, hence the density test in
    :func:`stroke_cross_section` (``docs/speed.md`` has both figures).
    """
    m3d = _cs()
    # each contour's mean point, all at once: a mean a contour costs more than the unions on dense patterns
    sizes = np.fromiter(map(len, contours), np.int64, len(contours))
    starts = np.r_[0, np.cumsum(sizes)[:-1]]
    centres = np.add.reduceat(np.concatenate(contours), starts, axis=0) / sizes[:, None]
    lo = centres.min(axis=0)
    cells = max(1, int(math.sqrt(len(contours) / per_bucket)))
    size = float((centres.max(axis=0) - lo).max()) / cells + 1e-9
    cell = np.floor((centres - lo) / size).astype(np.int64)
    key = cell[:, 0] * (cells + 1) + cell[:, 1]
    order = np.argsort(key, kind="stable")
    sorted_keys = key[order]
    cuts = np.flatnonzero(np.r_[True, sorted_keys[1:] != sorted_keys[:-1], True])
    parts = [m3d.CrossSection([contours[i] for i in order[a:b]], m3d.FillRule.Positive) for a, b in pairwise(cuts)]
    return m3d.CrossSection.batch_boolean(parts, m3d.OpType.Add)


def to_cross_section(geom):
    """A shapely Polygon/MultiPolygon as a ``manifold3d.CrossSection`` (holes kept)."""
    m3d = _cs()
    contours = []
    for poly in getattr(geom, "geoms", [geom]):
        if poly.is_empty:
            continue
        poly = shapely.geometry.polygon.orient(poly, 1.0)
        contours.append(np.asarray(poly.exterior.coords)[:-1])
        contours += [np.asarray(r.coords)[:-1] for r in poly.interiors]
    return m3d.CrossSection(contours, m3d.FillRule.Positive) if contours else m3d.CrossSection()


def to_shapely(cs) -> Polygon | MultiPolygon:
    """A ``manifold3d.CrossSection`` as a valid shapely Polygon or MultiPolygon.

    Clipper's contours are the answer's rings: the counter-clockwise ones shells, the
    clockwise ones holes, each hole in the smallest shell around it
    (:func:`_assign_holes`; asking Clipper for its components instead costs the square
    of a region's holes). Clipper may return a contour that touches itself at a
    vertex, which shapely calls invalid; such contours are split at the repeated
    vertex first (cheap), and ``shapely.make_valid`` is only a last resort for a
    polygon still invalid.
    """
    # Clipper's union of the contours again (a tenth of the cost of asking it for components) gives
    # each ring from the vertex and in the order the components would, so files stay as they were
    m3d = _cs()
    again = m3d.CrossSection(cs.to_polygons(), m3d.FillRule.Positive).to_polygons()
    rings = [np.asarray(r, dtype=float) for r in again if len(r) >= 3]
    if not rings:
        return Polygon()
    _split_pinched_rings(rings)
    lens = np.array([len(r) for r in rings])
    lr = shapely.linearrings(np.concatenate(rings), indices=np.repeat(np.arange(len(rings)), lens))
    ccw = shapely.is_ccw(lr)
    # Holes of no size: where many band edges cross at one point, Clipper2 can leave a
    # speck of ~1e-15 mm^2 (seen on table3-3 tiles); it is rounding noise, not a hole.
    speck = ~ccw & (shapely.area(shapely.polygons(lr)) < MIN_HOLE_AREA)
    if speck.any():
        lr, ccw = lr[~speck], ccw[~speck]
    fixed = _made_valid(_assign_holes(lr[ccw], lr[~ccw]))
    if not fixed:
        return Polygon()
    if len(fixed) > 1:
        geom = MultiPolygon(fixed)
        if not geom.is_valid:
            # Rarely, after rounding to Clipper's integer grid, two components share
            # a boundary segment: merge just the parts that touch along a line.
            fixed = _merge_line_touching(fixed)
    fixed.sort(key=lambda p: (round(p.bounds[1], 6), round(p.bounds[0], 6), -p.area))
    return fixed[0] if len(fixed) == 1 else MultiPolygon(fixed)


def _split_pinched_rings(rings: list) -> None:
    """Split, in place, the rings that visit a vertex twice (:func:`_split_pinched`).
    All rings are searched at once: sorting beats a per-ring unique."""
    lens = np.array([len(r) for r in rings])
    coords = np.concatenate(rings)
    rid = np.repeat(np.arange(len(rings)), lens)
    order = np.lexsort((coords[:, 1], coords[:, 0], rid))
    c, r = coords[order], rid[order]
    dup = (r[1:] == r[:-1]) & (c[1:] == c[:-1]).all(axis=1)
    for k in sorted(set(r[1:][dup].tolist()), reverse=True):
        rings[k : k + 1] = _split_pinched(rings[k])


def _made_valid(polys: list) -> list:
    """``polys``, each invalid one replaced by the polygons of ``shapely.make_valid`` (a last resort)."""
    fixed = []
    for p in polys:
        if p.is_valid:
            fixed.append(p)
        else:  # pragma: no cover - Clipper output that splitting did not repair
            fixed += [g for g in _polygons_of(shapely.make_valid(p)) if g.area > 0]
    return fixed


def _merge_line_touching(polys: list[Polygon]) -> list[Polygon]:
    tree = shapely.STRtree(polys)
    a, b = tree.query(polys, predicate="intersects")
    parent = list(range(len(polys)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, j in zip(a.tolist(), b.tolist(), strict=True):
        if i < j and shapely.get_dimensions(polys[i].intersection(polys[j])) >= 1:
            parent[find(i)] = find(j)
    groups: dict[int, list[Polygon]] = {}
    for i, p in enumerate(polys):
        groups.setdefault(find(i), []).append(p)
    out = []
    for members in groups.values():
        geom = members[0] if len(members) == 1 else shapely.union_all(members)
        out += [g for g in _polygons_of(geom) if g.area > 0]
    return out


def _assign_holes(shells, holes) -> list[Polygon]:
    """Polygons of the rings ``shells`` (counter-clockwise) and ``holes`` (clockwise): each hole goes
    to the smallest shell that covers it (a shell in another's hole is an island, and the holes
    inside the island are its own). A hole no shell covers is dropped."""
    if len(shells) == 1:
        return [shapely.Polygon(shells[0], holes)]
    shell_polys = shapely.polygons(shells)
    owner: list[list] = [[] for _ in shells]
    if len(holes) and len(shells):
        hole_of, shell_of = shapely.STRtree(shell_polys).query(shapely.polygons(holes), predicate="covered_by")
        # per hole the smallest shell covering it, the holes in their order
        order = np.lexsort((shapely.area(shell_polys)[shell_of], hole_of))
        hole_of, shell_of = hole_of[order], shell_of[order]
        first = np.r_[True, hole_of[1:] != hole_of[:-1]]
        for h, k in zip(hole_of[first].tolist(), shell_of[first].tolist(), strict=True):
            owner[k].append(holes[h])
    return [shapely.Polygon(s, h) for s, h in zip(shells, owner, strict=True)]


def _polygons_of(geom):
    if isinstance(geom, Polygon):
        return [geom]
    return [g for g in getattr(geom, "geoms", []) for g in _polygons_of(g)]


def _split_pinched(ring: np.ndarray) -> list[np.ndarray]:
    """Split a closed ring (without the repeated first point) at vertices it visits twice.

    One pass with a stack: when the walk comes back to a vertex already on the
    current path, the loop since then is cut off as a ring of its own.

    >>> sq = [(0, 0), (1, 0), (1, 1), (0, 0), (-1, 0), (-1, -1)]  # two triangles
    >>> [len(r) for r in _split_pinched(np.array(sq, dtype=float))]
    [3, 3]
    """
    out = []
    path: list[tuple[float, float]] = []
    where: dict[tuple[float, float], int] = {}
    for p in map(tuple, ring.tolist()):
        i = where.get(p)
        if i is not None:
            loop = path[i:]
            if len(loop) >= 3:
                out.append(np.array(loop))
            for q in path[i + 1 :]:
                del where[q]
            del path[i + 1 :]
        else:
            where[p] = len(path)
            path.append(p)
    if len(path) >= 3:
        out.append(np.array(path))
    return out
