"""Triangulating the meshing pieces: exactly, fast where it can, robust where it must.

A piece (a cell's part of one level, rings on the 2**-10 mm grid) is triangulated
polygon by polygon: a convex polygon without holes is fanned from its first
point; any other by mapbox's earcut, whose triangles are kept only when they tile
the piece exactly (:func:`tiles_exactly`), if need be once split where an edge runs
through collinear ring points (:func:`restore_collinear`), else by manifold3d's
triangulator (the caller's; no piece of the samples needs it). Earcut is several times faster here
than manifold3d's triangulator (``docs/speed.md``), interlaced too, where every dip is a hole.
Flat triangles (three collinear grid points) are flipped away
(:func:`flip_degenerate`), or the piece goes to GEOS's constrained Delaunay
triangulation (:func:`cdt`), which refuses a piece it cannot triangulate, naming
the place. A bottom that is an outline alone is triangulated on
its own (:func:`bottom_triangles`).
"""

from __future__ import annotations

import numpy as np

from ..core.errors import FabricationError
from ..core.native import import_uninterrupted
from ..geometry.stack import QUANTUM


def ear_clip(ij, starts, part_rings, nxt):
    """Ear-clipping triangles of one piece (mapbox_earcut, polygon by polygon), or None.

    ``ij`` are the piece's ring points on the grid (integers), ``starts`` the
    global ring starts, ``part_rings`` the ring index bounds of the piece's
    polygons, ``nxt`` each point's successor along its ring (piece numbering).
    The triangles are accepted only if they tile the piece (:func:`tiles_exactly`;
    earcut can run a triangle edge through a ring point where a ring touches a
    straight line at several points). Otherwise None: the caller uses manifold3d's
    triangulator.
    """
    import mapbox_earcut

    first = starts[part_rings[0]]
    n = len(ij)
    # polygons without holes whose every corner turns left: a fan from their first point
    # (an interlaced sheet's thousands of dips, with no earcut call each)
    ring_start = starts[part_rings[0] : part_rings[-1] + 1] - first
    prev = np.empty(n, np.int64)
    prev[nxt] = np.arange(n)
    turn = turns(ij[prev], ij, ij[nxt])
    bent = np.add.reduceat((turn <= 0).astype(np.int64), ring_start[:-1]) > 0
    head = part_rings[:-1] - part_rings[0]  # each polygon's first ring (its exterior)
    fan = (np.diff(part_rings) == 1) & ~bent[head]
    s, m = ring_start[head[fan]], np.diff(ring_start)[head[fan]]
    cnt = m - 2
    rep = np.repeat(s, cnt)
    k = np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt) + 1
    out = [np.stack([rep, rep + k, rep + k + 1], axis=1)]
    xy = ij.astype(np.float64)  # integers below 2**26: exact in earcut's arithmetic
    for p in np.flatnonzero(~fan).tolist():
        a, b = starts[part_rings[p]] - first, starts[part_rings[p + 1]] - first
        ends = (starts[part_rings[p] + 1 : part_rings[p + 1] + 1] - first - a).astype(np.uint32)
        t = mapbox_earcut.triangulate_float64(xy[a:b], ends)
        out.append(np.asarray(t, np.int64).reshape(-1, 3) + a)
    tris = np.concatenate(out)
    if tiles_exactly(ij, tris, nxt):
        return tris
    tris = restore_collinear(ij, tris, nxt)
    return tris if tris is not None and tiles_exactly(ij, tris, nxt) else None


def restore_collinear(ij, tris, nxt, *, rounds: int = 8):
    """Triangles split at the ring points lying inside their edges, or None.

    Earcut leaves a triangle edge running through points of the rings where they
    are collinear: a point it dropped between its neighbours, or holes whose edges
    lie on one straight line, the triangle edge running along them from hole to
    hole. There the edges do not pair up (a T-junction; a few pieces of a sheet,
    on the straight lines the cells cut, which manifold3d's triangulator would
    otherwise redo). Each such edge
    ``a -> b`` of a triangle ``(a, b, c)`` over points ``m1 ... mk`` (exact integer
    test) becomes the fan ``(a, m1, c), ..., (mk, b, c)``, a few rounds; the caller
    checks the result (:func:`tiles_exactly`). None when nothing was split.

    >>> ij = np.array([[0, 0], [2, 0], [2, 2], [0, 2], [1, 0]])  # point 4 on the edge 0 -> 1
    >>> restore_collinear(ij, np.array([[0, 1, 2], [0, 2, 3]]), np.array([4, 2, 3, 0, 1])).tolist()
    [[0, 2, 3], [0, 4, 2], [4, 1, 2]]
    """
    n = len(ij)
    ring_rev = nxt * n + np.arange(n)  # the ring edges reversed: each pairs a triangle edge
    split = False
    for _ in range(rounds):
        u, v = tris.ravel(), tris[:, [1, 2, 0]].ravel()
        have = np.sort(np.concatenate([u * n + v, ring_rev]))
        want = v * n + u  # each triangle edge's reverse: another triangle's, or a ring edge's
        at = np.minimum(np.searchsorted(have, want), len(have) - 1)
        bad = np.flatnonzero(have[at] != want).tolist()
        if not bad:
            break
        edges = np.stack([u, v], axis=1)
        drop: set = set()
        add: list = []
        for k in bad:
            t = k // 3
            if t in drop:
                continue
            a, b = edges[k]
            c = tris[t, (k % 3 + 2) % 3]
            d = ij[b] - ij[a]
            rel = ij - ij[a]
            along = rel @ d
            on = np.flatnonzero((rel[:, 0] * d[1] - rel[:, 1] * d[0] == 0) & (along > 0) & (along < d @ d))
            if not len(on):
                continue
            chain = [a, *on[np.argsort(along[on])].tolist(), b]
            drop.add(t)
            add.extend([chain[i], chain[i + 1], c] for i in range(len(chain) - 1))
        if not drop:
            break
        split = True
        keep = np.ones(len(tris), bool)
        keep[list(drop)] = False
        tris = np.concatenate([tris[keep], np.array(add, np.int64).reshape(-1, 3)])
    return tris if split else None


def tiles_exactly(ij, tris, nxt, *, flat_ok: bool = True) -> bool:
    """Whether triangles ``tris`` (indices into ``ij``) tile the polygon of rings ``nxt``.

    ``ij`` are integer grid points, ``nxt`` each point's successor along its ring
    (exteriors counter-clockwise, holes clockwise). The tiling is exact when no
    triangle is clockwise (nor flat, unless ``flat_ok``: flat ones are flipped
    away later), the triangles add up to the polygon's area in exact integer
    arithmetic, and their edges with the rings' edges reversed pair up: each ring
    edge is one triangle's, every other edge two triangles' in opposite directions.

    >>> square = np.array([[0, 0], [2, 0], [2, 2], [0, 2]])
    >>> nxt = np.array([1, 2, 3, 0])
    >>> tiles_exactly(square, np.array([[0, 1, 2], [0, 2, 3]]), nxt)
    True
    >>> tiles_exactly(square, np.array([[0, 1, 2], [1, 2, 3]]), nxt)  # overlapping, one corner bare
    False
    """
    if not len(tris):
        return False
    area = twice_areas(ij, tris)
    if (area < 0).any() or (not flat_ok and (area == 0).any()):
        return False
    if int(area.sum()) != int((ij[:, 0] * ij[nxt, 1] - ij[nxt, 0] * ij[:, 1]).sum()):
        return False
    n = len(ij)
    u = np.concatenate([tris.ravel(), nxt])
    v = np.concatenate([tris[:, [1, 2, 0]].ravel(), np.arange(n)])
    return edges_pair_up(u, v, n)


def edges_pair_up(u, v, n: int) -> bool:
    """Whether every directed edge ``u -> v`` (vertices below ``n``) occurs once and its reverse once.

    One sort: each edge is keyed by its two ends, smaller first, and a last bit
    for its direction; sorted, the keys must come in pairs of one edge, bit 0
    then bit 1, and no edge may come twice.

    >>> edges_pair_up(np.array([0, 1, 2, 1, 0, 2]), np.array([1, 2, 0, 0, 2, 1]), 3)
    True
    >>> edges_pair_up(np.array([0, 1, 2]), np.array([1, 2, 0]), 3)
    False
    """
    if len(u) % 2:
        return False
    key = np.sort((np.minimum(u, v) * n + np.maximum(u, v)) * 2 + (u > v))
    edge = key >> 1
    return bool(
        np.all(key[0::2] & 1 == 0)
        and np.all(key[1::2] & 1 == 1)
        and np.array_equal(edge[0::2], edge[1::2])
        and np.all(edge[2::2] != edge[1:-1:2])
    )


def twice_areas(ij, tris):
    """Twice the signed area of each triangle, exact (integer grid points)."""
    return turns(ij[tris[:, 0]], ij[tris[:, 1]], ij[tris[:, 2]])


def turns(a, b, c):
    """Twice the signed area of triangles ``a, b, c`` ((k, 2) integer points each)."""
    return (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])


def flat(tris, ij):
    """Which triangles are flat (three collinear grid points)."""
    return twice_areas(ij, tris) == 0


def cdt(piece, ij):
    """Constrained Delaunay triangulation of a piece (GEOS): never flat, slower.

    Returns triangles as indices into ``ij`` (the piece's ring points, on the grid).

    Raises
    ------
    FabricationError
        When GEOS cannot triangulate the piece (a ring touching itself, which a
        piece cut at a line through a vertex of its ring would be) or gives a point
        not of its rings; its ``points`` hold the place (x, y, mm) and the caller
        names the part.

    >>> import shapely
    >>> lobes = shapely.Polygon([(0, 0), (4, 0), (4, 2), (2, 0), (0, 2)])  # touching itself at (2, 0)
    >>> cdt(lobes, np.array([[0, 0], [4, 0], [4, 2], [2, 0], [0, 2]]) * 1024)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.FabricationError: cannot triangulate the region near (2, 0) mm: GEOS stops there (IllegalStateException: Unable to find a convex corner; its ring touches itself)
    """  # noqa: E501 - a doctest's lines are as Python prints them
    import shapely

    try:
        tri = shapely.get_parts(shapely.constrained_delaunay_triangles(piece))
    except shapely.errors.GEOSException as exc:
        reason = shapely.is_valid_reason(piece)
        where = _place(reason) if reason.startswith("Ring Self-intersection") else None
        if where is None:
            where = shapely.get_coordinates(shapely.point_on_surface(piece))[0]
            why = f"GEOS stops ({exc})"
        else:
            why = f"GEOS stops there ({exc}; its ring touches itself)"
        raise _failure(where, why) from None
    coords = shapely.get_coordinates(shapely.get_exterior_ring(tri)).reshape(len(tri), 4, 2)[:, :3]
    cij = np.round(coords / QUANTUM).astype(np.int64)
    lookup = {(int(x), int(y)): i for i, (x, y) in enumerate(ij.tolist())}
    missing = [(x, y) for x, y in cij.reshape(-1, 2).tolist() if (x, y) not in lookup]
    if missing:
        raise _failure(np.array(missing[0]) * QUANTUM, "GEOS gives a point not on its rings")
    out = np.array([[lookup[(x, y)] for x, y in t] for t in cij.tolist()], dtype=np.int64).reshape(-1, 3)
    # GEOS triangles may come either way round: make them counter-clockwise
    cw = twice_areas(ij, out) < 0
    out[cw] = out[cw][:, ::-1]
    return out


def _place(reason: str):
    """The point a GEOS validity reason names (``"Ring Self-intersection[2 0]"``), or None."""
    import re

    m = re.search(r"\[([-+\d.eE]+) ([-+\d.eE]+)\]", reason)
    return None if m is None else np.array([float(m.group(1)), float(m.group(2))])


def _failure(where, why: str) -> FabricationError:
    """The error of a piece that cannot be triangulated at ``where`` (x, y mm); see :func:`cdt`."""
    x, y = (float(v) for v in where)
    message = f"cannot triangulate the region near ({x:.6g}, {y:.6g}) mm: {why}"
    exc = FabricationError(message)
    exc.points = np.array([[x, y]])
    return exc


def _middle_point(t: list, ij: np.ndarray):
    """``(x, m, y)``: a flat triangle's corners turned so that m lies between x and y (within the
    bounding box of the other two), or None."""
    for r in range(3):
        x, m, y = t[r], t[(r + 1) % 3], t[(r + 2) % 3]
        px, pm, py = ij[x], ij[m], ij[y]
        if np.all(np.minimum(px, py) <= pm) and np.all(pm <= np.maximum(px, py)):
            return x, m, y
    return None


def flip_degenerate(tris: np.ndarray, ij: np.ndarray) -> np.ndarray:
    """Remove zero-area triangles (three collinear grid points) by edge flips.

    A flat triangle (x, m, y) with m between x and y is dropped and its neighbour
    across x-y, (x, y, d), split at m into (x, m, d) and (m, y, d): same edges
    outside, same area, no flat face. Exact: the points are integers.
    """
    flat = np.flatnonzero(twice_areas(ij, tris) == 0)
    if not len(flat):
        return tris
    tris = tris.copy()
    for _ in range(12):
        tris = _flip_round(tris, flat, ij)
        flat = np.flatnonzero(twice_areas(ij, tris) == 0)
        if not len(flat):
            break
    return tris


def _flip_round(tris: np.ndarray, flat: np.ndarray, ij: np.ndarray) -> np.ndarray:
    """One round of :func:`flip_degenerate`: each flat triangle ``flat`` and its neighbour across its long
    edge replaced by two, each triangle touched once (the others wait for the next round)."""
    owner = {}
    for k, (a, b, c) in enumerate(tris.tolist()):
        owner[(a, b)] = k
        owner[(b, c)] = k
        owner[(c, a)] = k
    alive = np.ones(len(tris), bool)
    extra = []
    touched: set = set()
    for k in flat.tolist():
        if k in touched:
            continue
        t = tris[k].tolist()
        mid = _middle_point(t, ij)
        if mid is None or len(set(t)) < 3:
            continue
        x, m, y = mid
        nb = owner.get((x, y))
        if nb is None or nb in touched:
            continue
        d = [v for v in tris[nb].tolist() if v not in (x, y)]
        if len(d) != 1:
            continue
        alive[k] = alive[nb] = False
        touched.update((k, nb))
        extra.append((x, m, d[0]))
        extra.append((m, y, d[0]))
    return np.concatenate([tris[alive], np.asarray(extra, dtype=np.int64).reshape(-1, 3)])


BOTTOM_RINGS = 64
BOTTOM_POINTS = 20_000
"""A bottom outlined by at most ``BOTTOM_RINGS`` rings of ``BOTTOM_POINTS`` points in all is
triangulated on its own (a seamless relief sheet's has a few hundred points); a bigger one (a
pierced tile's bottom is its whole pattern) takes the top's triangles, turned over."""


def _outline_rings(bu, bv, limit: int | None = BOTTOM_RINGS):
    """The edges ``bu -> bv`` (each vertex starting one) chained into rings of vertex ids, or None
    past ``limit`` rings (None: no limit)."""
    succ = dict(zip(bu.tolist(), bv.tolist(), strict=True))
    rings, seen = [], set()
    for start in bu.tolist():
        if start in seen:
            continue
        ring, k = [], start
        while k not in seen:
            seen.add(k)
            ring.append(k)
            k = succ[k]
        rings.append(ring)
        if limit is not None and len(rings) > limit:
            return None
    return rings


def bottom_triangles(u, v, out_level, xy):
    """Triangles (vertex ids, counter-clockwise seen from above) of the bottom on its own, or None.

    ``u -> v`` are a coverage's edges (vertex ids), ``out_level`` the level beside
    each (0: nothing, the bottom's outline), ``xy`` the vertices' positions.

    The bottom of a relief, a plate or a base is its outline: triangulated from
    the vertices on the outline's edges (every one, so that the walls meet it
    edge to edge), it takes a few hundred triangles where the top's, turned over,
    would be a third of a relief sheet's mesh.
    None when the outline has more than :data:`BOTTOM_RINGS` rings, a ring
    passes a vertex twice, or the triangles do not tile it exactly (then the
    caller turns the top's over).
    """
    m3 = import_uninterrupted("manifold3d")

    sel = (out_level == 0) & (u != v)  # edges with nothing beside them: the bottom's outline
    bu, bv = u[sel], v[sel]
    if not len(bu) or len(bu) > BOTTOM_POINTS:
        return None
    if len(np.unique(bu)) != len(bu) or not np.array_equal(np.sort(bu), np.sort(bv)):
        return None
    rings = _outline_rings(bu, bv)
    if rings is None:
        return None
    ids = np.concatenate([np.asarray(r, np.int64) for r in rings])
    ij = np.round(xy[ids] / QUANTUM).astype(np.int64)
    starts = np.concatenate([[0], np.cumsum([len(r) for r in rings])])
    tris = np.asarray(m3.triangulate([xy[np.asarray(r)] for r in rings]), dtype=np.int64).reshape(-1, 3)
    tris = flip_degenerate(tris, ij)
    nxt = np.arange(len(ids)) + 1
    nxt[starts[1:] - 1] = starts[:-1]
    return ids[tris] if tiles_exactly(ij, tris, nxt, flat_ok=False) else None


def _triangulated(rings) -> np.ndarray | None:
    """manifold3d's triangles of closed ``rings`` (points one after another, each ring's
    (k, 2) array, exteriors counter-clockwise, holes clockwise), flat ones flipped away, or
    None when they do not tile the rings exactly."""
    m3 = import_uninterrupted("manifold3d")

    pts = np.concatenate(rings)
    ij = np.round(pts / QUANTUM).astype(np.int64)
    lengths = np.array([len(r) for r in rings])
    starts = np.concatenate([[0], np.cumsum(lengths)])
    nxt = np.arange(len(pts)) + 1
    nxt[starts[1:] - 1] = starts[:-1]
    tris = np.asarray(m3.triangulate([np.asarray(r, float) for r in rings]), dtype=np.int64).reshape(-1, 3)
    tris = flip_degenerate(tris, ij)
    return tris if tiles_exactly(ij, tris, nxt, flat_ok=False) else None


def recessed_bottom(u, v, out_level, xy, recess_rings):
    """The triangles of a bottom with a recess: ``(bottom, roof)``, or None when either does not tile.

    ``u -> v`` are a coverage's edges, ``out_level`` the level beside each (0: nothing:
    the bottom's outline), ``xy`` the vertices; ``recess_rings`` the recess's rings
    (each a (k, 2) array, not closed, exteriors counter-clockwise, holes clockwise),
    strictly inside the bottom. The bottom is its outline less the recess, triangulated
    on its own (its rings' vertices are numbered ``xy``'s, then the recess's points
    ``len(xy) + k``, counter-clockwise seen from above); ``roof`` is the recess's own
    triangles (numbered by its points, counter-clockwise seen from above).
    """
    sel = (out_level == 0) & (u != v)
    bu, bv = u[sel], v[sel]
    if not len(bu) or len(np.unique(bu)) != len(bu) or not np.array_equal(np.sort(bu), np.sort(bv)):
        return None
    outline = [np.asarray(ring, np.int64) for ring in _outline_rings(bu, bv, limit=None) or ()]
    n_points = sum(len(r) for r in recess_rings)
    first = len(xy) + np.concatenate([[0], np.cumsum([len(r) for r in recess_rings])])
    # the recess is a hole of the bottom: its rings run the other way there
    holes = [np.arange(first[k], first[k + 1])[::-1] for k in range(len(recess_rings))]
    ids = np.concatenate(outline + holes)
    every = np.concatenate([xy, np.concatenate(recess_rings)]) if n_points else xy
    bottom = _triangulated([every[r] for r in outline + holes])
    roof = _triangulated(list(recess_rings))
    if bottom is None or roof is None:
        return None
    return ids[bottom], roof
