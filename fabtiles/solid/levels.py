"""The levels of a printed body: which area stands at which height (one place for every 3D writer).

A body is a stack of disjoint (polygons, top z) layers over a common bottom (see
:mod:`fabtiles.solid._mesh_build`). An interlaced relief has a third level: where
an under strand passes under another it dips to ``DIP_FRACTION`` of the relief
height, across the over band's clearance (see :mod:`fabtiles.geometry.interlace`).
The STL/3MF meshers and the STEP writer all take their layers from
:func:`body_layers`, so the three formats describe the same solid.
"""

from __future__ import annotations

import numpy as np

DIP_FRACTION = 0.5
"""Height of an under strand's dip above the plate, as a fraction of the relief height."""

KINDS = ("relief", "base", "pattern", "pierced", "plate")
"""Body kinds: a relief's plate and pattern fused, the plate alone, the pattern alone
(3MF part, bottom at the plate's top), a pierced part, a debossed plate."""


def dip_z(stack) -> float:
    """Height of the dips' top: the plate plus ``DIP_FRACTION`` of the relief."""
    return stack.base + DIP_FRACTION * stack.relief


def dip_level(dips, region=None):
    """The dips as the meshes and the STEP file build them: on the grid, parts thinner
    than :data:`THIN_MM` dropped (those stay at full height), no holes, none touching
    another (:func:`_apart_dips`). A MultiPolygon, or an empty Polygon.

    A part with a hole is filled where the hole is an island of the ``region`` (all
    material); a part ringing an opening of the ``region`` (an outline circle inside
    a crossing) is dropped and stays at full height: filled, it would lay plastic over
    the opening.

    >>> from shapely.geometry import box
    >>> dip_level(box(0, 0, 1, 2 ** -12)).is_empty, round(dip_level(box(0, 0, 1, 0.5)).area, 3)
    (True, 0.5)
    >>> ring = box(0, 0, 3, 3).difference(box(1, 1, 2, 2))
    >>> dip_level(ring, region=box(0, 0, 3, 3)).area, dip_level(ring, region=ring).is_empty
    (9.0, True)
    """
    import shapely

    from ._mesh_build import QUANTUM, snap

    if dips is None or dips.is_empty:
        return shapely.Polygon()
    # :func:`fabtiles.geometry.interlace.dips` makes them on the grid already (no snapping
    # again, nor its validity check)
    coords = shapely.get_coordinates(dips)
    on_grid = np.array_equal(np.round(coords / QUANTUM) * QUANTUM, coords)
    parts = shapely.get_parts(dips if on_grid else snap(dips))
    parts = parts[~_thin(parts)] if len(parts) else parts
    holed = shapely.get_num_interior_rings(parts) > 0
    if holed.any() and region is not None:
        for i in np.flatnonzero(holed).tolist():
            holes = shapely.polygons(
                shapely.get_interior_ring(parts[i], range(shapely.get_num_interior_rings(parts[i])))
            )
            if not shapely.covers(region, holes).all():  # an opening of the region in the hole
                holed[i] = False  # it rings an opening: no dip here
                parts[i] = None
        parts = parts[~shapely.is_missing(parts)] if shapely.is_missing(parts).any() else parts
        holed = shapely.get_num_interior_rings(parts) > 0
    if holed.any():  # an island ringed by overlapping slivers: far too small to stand up, it dips too
        parts[holed] = shapely.polygons(shapely.get_exterior_ring(parts[holed]))
    parts = _apart_dips(parts)
    return shapely.multipolygons(parts) if len(parts) else shapely.Polygon()


APART_MM = 8 * 2.0**-10
"""How far around the point where two dips touch :func:`_apart_dips` first cuts them back."""

APART_ROUNDS = 6
"""Rounds of :func:`_apart_dips`, each cutting twice as far around the points still in contact."""


def _apart_dips(parts):
    """Dips ``parts`` (on the grid) cut back :data:`APART_MM` around the points where two touch.

    Two dips meeting at a point (the under strands' ends of two crossings) would share
    the vertical edge there with the full height's walls: four walls on one edge. Cut
    back, the full height fills the speck between them. Two dips within a grid step
    of each other count as touching: the STEP writer nodes the levels on the grid,
    which joins them. Two dips leaving their point at a small angle are still within
    a grid step of each other where the cut ends (snapped, they touch there again):
    they are cut again around that point, twice as far, a few rounds
    (:data:`APART_ROUNDS`).

    >>> from shapely.geometry import box
    >>> out = _apart_dips(np.array([box(0, 0, 1, 1), box(1, 1, 2, 2), box(3, 3, 4, 4)]))
    >>> sorted(round((1 - p.area) / APART_MM ** 2, 6) for p in out)  # a quarter of a diamond off each of two
    [0.0, 0.5, 0.5]
    """
    import shapely

    from ._mesh_build import QUANTUM, polygons_of

    if len(parts) < 2:
        return parts
    test, radius = np.arange(len(parts)), APART_MM
    for _ in range(APART_ROUNDS):
        # the parts cut last round (all of them at first) against all: pairs within a grid step
        q, other = shapely.STRtree(parts).query(parts[test], predicate="dwithin", distance=QUANTUM)
        pairs = np.unique(np.sort(np.stack([test[q], other], axis=1), axis=1), axis=0)
        a, b = pairs[:, 0], pairs[:, 1]
        # overlapping dips are no contact (dip_level makes none)
        contact = (a != b) & (~shapely.intersects(parts[a], parts[b]) | shapely.touches(parts[a], parts[b]))
        a, b = a[contact], b[contact]
        if not len(a):
            break
        # every point where two touch, and the nearest points of two apart
        points = np.concatenate(
            [
                shapely.get_coordinates(shapely.intersection(parts[a], parts[b])),
                shapely.get_coordinates(shapely.shortest_line(parts[a], parts[b])),
            ]
        )
        cut = shapely.union_all(shapely.buffer(shapely.points(points), radius, quad_segs=1))
        hit = np.unique(np.concatenate([a, b]))
        cut_parts = [q for p in parts[hit] for q in polygons_of(shapely.difference(p, cut, grid_size=QUANTUM))]
        keep = np.ones(len(parts), bool)
        keep[hit] = False
        parts = np.concatenate([parts[keep], np.asarray(cut_parts, dtype=object)])
        test, radius = np.arange(len(parts) - len(cut_parts), len(parts)), 2 * radius
    return parts


def split_region(r, dips, *, holes: bool = True, leveled: bool = False):
    """``(full, dips)``: the region cut into its full-height part and its dips, on the grid.

    ``dips`` must lie strictly inside ``r``, as :func:`fabtiles.geometry.interlace.dips`
    makes them (20 grid steps inside, so snapping keeps them there). The full part
    is then ``r`` with the dips as holes, vertex for vertex: each dip is added as a
    hole of the part of ``r`` holding it, no overlay of the whole region. Dip parts
    thinner than :data:`THIN_MM`, and dips ringing a face of the region
    (:func:`_ringing_faces`), stay at full height. ``dips`` may be None or empty;
    ``holes=False`` returns ``r`` itself as the full part; ``leveled`` says ``dips``
    already is :func:`dip_level`'s.
    """
    import shapely

    d = dips if leveled else dip_level(dips, r)
    if d is None or d.is_empty:
        return r, shapely.Polygon()
    parts = shapely.get_parts(d)
    ringing = _ringing_faces(r, parts)
    if ringing.any():
        parts = parts[~ringing]
        d = shapely.multipolygons(parts) if len(parts) else shapely.Polygon()
        if not len(parts):
            return r, d
    if not holes:
        return r, d
    owners = shapely.get_parts(r)
    owner_of = _owner_of(owners, shapely.get_coordinates(shapely.get_point(shapely.get_exterior_ring(parts), 0)))
    if (owner_of < 0).any():  # not inside the region after all: no dip there (never seen)
        parts, owner_of = parts[owner_of >= 0], owner_of[owner_of >= 0]
        d = shapely.multipolygons(parts) if len(parts) else shapely.Polygon()
        if not len(parts):
            return r, d
    full = add_holes(owners, owner_of, *_ragged_rings(shapely.get_exterior_ring(parts)))
    return shapely.multipolygons(full), d


def _ringing_faces(r, parts) -> np.ndarray:
    """Which dips of ``parts`` (:func:`dip_level`'s) ring a hole of the region ``r``.

    The under strands around a small face can dip all the way round it: the dip is a
    ring whose hole is that face, and :func:`dip_level` fills it (the hole it is made
    for is an island of material too small to stand). Filled, the dip would cover the
    face, and as a hole of the region it would hold the face's own hole: no valid
    polygon. Those dips stay at full height.

    >>> import shapely
    >>> r = shapely.box(0, 0, 10, 10).difference(shapely.box(4, 4, 6, 6))
    >>> _ringing_faces(r, np.array([shapely.box(3, 3, 7, 7), shapely.box(1, 1, 2, 2)])).tolist()
    [True, False]
    """
    import shapely

    out = np.zeros(len(parts), bool)
    polys = shapely.get_parts(r)
    counts = shapely.get_num_interior_rings(polys)
    if not len(parts) or not counts.sum():
        return out
    holes = shapely.get_interior_ring(np.repeat(polys, counts), np.concatenate([np.arange(c) for c in counts]))
    _, ringing = shapely.STRtree(parts).query(shapely.get_point(holes, 0), predicate="within")
    out[ringing] = True
    return out


def _owner_of(polys, points) -> np.ndarray:
    """Index of the polygon of ``polys`` holding each point strictly inside (-1: none), for
    points each known to lie inside one of them (a dip's corner, inside the region).

    A point in the box of one polygon alone lies in that one (most of the 600 x 400 mm
    sheet's 10,000 dips: a cell's part of the region is mostly one polygon); the others
    are tested, polygon by polygon, each prepared once.
    """
    import shapely

    owner = np.full(len(points), -1)
    if not len(points) or not len(polys):
        return owner
    pt, poly = shapely.STRtree(polys).query(shapely.points(points))
    alone = np.bincount(pt, minlength=len(points))[pt] == 1
    owner[pt[alone]] = poly[alone]
    pt, poly = pt[~alone], poly[~alone]
    for k in np.unique(poly).tolist():
        sel = pt[poly == k]
        shapely.prepare(polys[k])
        owner[sel[shapely.contains_xy(polys[k], points[sel, 0], points[sel, 1])]] = k
    return owner


def _ragged_rings(rings):
    """``(coords, lengths)``: the points of closed rings one after another, and each ring's count."""
    import shapely

    coords, ring = shapely.get_coordinates(rings, return_index=True)
    return coords, np.bincount(ring, minlength=len(rings))


def add_holes(polys, owner, coords, lengths):
    """Polygons ``polys`` with rings added as holes, ring ``k`` to ``polys[owner[k]]``.

    ``coords`` holds the closed rings one after another, ``lengths`` their point
    counts; they are added as given (a caller orienting its polygons passes them
    clockwise). The holes must lie strictly inside their owners, apart from each
    other and the owners' own holes: nothing is checked or overlaid. Built as one
    ragged array, no shapely object per ring (a sheet has tens of thousands).

    >>> import shapely
    >>> ring = np.array([[1, 1], [1, 2], [2, 2], [2, 1], [1, 1]], float)
    >>> [p.area for p in add_holes(np.array([shapely.box(0, 0, 4, 4)]), np.array([0]), ring, np.array([5]))]
    [15.0]
    """
    import shapely

    _, src, (ring_off, part_off) = shapely.to_ragged_array(polys)
    ring_off, part_off = np.asarray(ring_off), np.asarray(part_off)
    src = np.concatenate([np.asarray(src, float), np.asarray(coords, float).reshape(-1, 2)])
    length = np.concatenate([np.diff(ring_off), lengths]).astype(np.int64)
    start = np.cumsum(length) - length  # each ring's first point in src
    own = np.concatenate([np.repeat(np.arange(len(polys)), np.diff(part_off)), owner])
    order = np.argsort(own, kind="stable")  # each polygon's own rings first, then its new holes
    length, start = length[order], start[order]
    gather = np.repeat(start - np.concatenate([[0], np.cumsum(length)[:-1]]), length) + np.arange(length.sum())
    new_rings = np.concatenate([[0], np.cumsum(length)])
    new_parts = np.concatenate([[0], np.cumsum(np.bincount(own, minlength=len(polys)))])
    return shapely.from_ragged_array(shapely.GeometryType.POLYGON, src[gather], (new_rings, new_parts))


THIN_MM = 3 * 2.0**-10
"""A part of a level no point of which is farther than this from its edge is thin."""


def _thin(parts):
    """Parts no point of which is farther than :data:`THIN_MM` from their edge (at most).

    Twice the area over the perimeter bounds the largest inscribed disc's radius
    from above, so a part below :data:`THIN_MM` by it is thin (no buffer of each of a
    sheet's thousands of dips).
    """
    import shapely

    if not len(parts):
        return np.zeros(0, bool)
    return 2 * shapely.area(parts) < THIN_MM * shapely.length(parts)


def body_layers(kind: str, r, o, stack, dips=None):
    """The layers of one body: ``([(geometry, top z), ...], bottom z)``.

    Parameters
    ----------
    kind : {"relief", "base", "pattern", "pierced", "plate"}
    r, o : shapely geometry
        The material region and the outline, on the 2**-10 mm grid, ``r`` within ``o``.
    stack : Stack
        Style and heights (``base``, ``relief``, ``pierced``, ``deboss``).
    dips : shapely geometry, optional
        Where the relief's under strands dip (relief and pattern kinds only),
        strictly inside ``r`` (as :func:`fabtiles.geometry.interlace.dips` makes them).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> from fabtiles.solid._mesh_build import Stack
    >>> stack = Stack("relief", base=2.0, relief=1.0, pierced=3.0, deboss=0.5)
    >>> dips = box(1.5, 1.5, 2, 2.5)  # strictly inside the region
    >>> layers, bottom = body_layers("relief", box(1, 1, 3, 3), box(0, 0, 4, 4), stack, dips=dips)
    >>> [(round(g.area, 3), z) for g, z in layers], bottom
    ([(0.5, 2.5), (3.5, 3.0), (12.0, 2.0)], 0.0)
    """
    import shapely

    from ..geometry.interlace import polygonal
    from ._mesh_build import QUANTUM

    b, h, t, d = stack.base, stack.relief, stack.pierced, stack.deboss
    if kind in ("relief", "pattern"):
        full, dip = split_region(r, dips)
        top = [(dip, dip_z(stack))] if not dip.is_empty else []
        top.append((full, b + h))
        if kind == "pattern":
            return top, b
        return top + [(polygonal(shapely.difference(o, r, grid_size=QUANTUM)), b)], 0.0
    if kind == "base":
        return [(o, b)], 0.0
    if kind == "pierced":
        return [(r, t)], 0.0
    if kind == "plate":
        return [(r, b - d), (polygonal(shapely.difference(o, r, grid_size=QUANTUM)), b)], 0.0
    raise ValueError(f"{kind!r} is not a valid body kind, must be one of: {', '.join(KINDS)}")


def dips_volume(r, dips, stack, *, leveled: bool = False) -> float:
    """Volume a relief loses to its dips (mm^3): their area times the depth below full height."""
    if dips is None or dips.is_empty:
        return 0.0
    _, dip = split_region(r, dips, holes=False, leveled=leveled)
    return dip.area * (stack.base + stack.relief - dip_z(stack))


def body_coverage(kind: str, r, o, stack, dips, *, shift: int = 0, leveled: bool = False):
    """The meshing coverage of an interlaced ``relief`` or ``pattern`` body: the layers of
    :func:`body_layers`, built the fast way.

    The body is cut into cells as without dips (the relief by ``coverage_pair``, no
    overlay of the whole sheet), with the few dips that a cell line crosses (496 of
    the 600 x 400 mm sheet's 10,287) already holes of the region: they are cut at
    the cell lines with it, and their own pieces noded there the same way. Every
    other dip lies inside one cell, strictly inside the region's piece there, and
    is added to that piece as a hole, as arrays (:func:`add_holes`): no overlay at
    all, quicker than one overlay a cell and far quicker than ``coverage`` of the three
    layers (``docs/speed.md``). ``leveled`` says ``dips``
    already is :func:`dip_level`'s.

    >>> from shapely.geometry import box
    >>> from fabtiles.solid._mesh_build import Stack
    >>> stack = Stack("relief", base=2.0, relief=1.0, pierced=3.0, deboss=0.5)
    >>> cov = body_coverage("relief", box(1, 1, 3, 3), box(0, 0, 4, 4), stack, box(1.5, 1.5, 2, 2.5))
    >>> cov.levels.tolist(), sorted(round(p.area, 3) for p, _ in cov.pieces)
    ([0.0, 2.0, 2.5, 3.0], [0.5, 3.5, 12.0])
    """
    import shapely

    from ._mesh_build import (
        CELL_VERTICES,
        Coverage,
        cells_for,
        coverage,
        coverage_from_cells,
        coverage_pair,
        node_polygons,
        split_cells,
    )

    if kind not in ("relief", "pattern"):
        raise ValueError(f"{kind!r} has no dips, must be one of: relief, pattern")
    b, h = stack.base, stack.relief
    _, dip = split_region(r, dips, holes=False, leveled=leveled)
    cells = cells_for([r, o] if kind == "relief" else [r], CELL_VERTICES, shift, avoid=[dip])
    xs, ys, box = cells
    parts, coords, ring_off, inner = _dips_in_cells(dip, xs, ys)
    crossed = parts[~inner]
    rr = split_region(r, shapely.multipolygons(crossed), leveled=True)[0] if len(crossed) else r
    if kind == "relief":
        cov = coverage_pair(rr, o, region_z=b + h, rest_z=b, bottom=0.0, cells=cells)
    else:
        cov = coverage([(rr, b + h)], bottom=b, cells=cells)
    if not len(parts):
        return cov
    levels = np.array(sorted({*cov.levels.tolist(), dip_z(stack)}))
    remap = np.searchsorted(levels, cov.levels)
    top, low = int(np.searchsorted(levels, b + h)), int(np.searchsorted(levels, dip_z(stack)))
    pieces = [(p, int(remap[lvl])) for p, lvl in cov.pieces]
    extra = []
    if len(crossed) and kind == "relief":
        # the rest of a cell (outline minus the region with these holes) holds their pieces
        pieces = _relevel_crossed(pieces, remap[int(np.searchsorted(cov.levels, b))], low, crossed)
    elif len(crossed):
        cut, _, _ = split_cells(node_polygons(shapely.multipolygons(crossed), xs, ys), xs, ys, box)
        extra = coverage_from_cells([(g, low) for _, _, g in cut], levels).pieces
    if inner.any():
        lengths = np.diff(ring_off)
        ring = np.repeat(inner, lengths)
        pieces = _inner_dips(pieces, top, low, coords[ring], lengths[inner])
    return Coverage(pieces + extra, levels, cov.xs, cov.ys)


def _dips_in_cells(dip, xs, ys):
    """``(parts, coords, ring offsets, inner)``: the dips, their rings' points as arrays (dip_level
    leaves them no holes), and which lie inside one cell (no cell line ``xs``, ``ys`` between their
    bounds; cell i lies between xs[i - 1] and xs[i])."""
    import shapely

    parts = shapely.get_parts(dip) if not dip.is_empty else np.empty(0, object)
    coords, which = shapely.get_coordinates(parts, return_index=True)
    ring_off = np.concatenate([[0], np.cumsum(np.bincount(which, minlength=len(parts)))])
    lo = np.minimum.reduceat(coords, ring_off[:-1]) if len(parts) else np.empty((0, 2))
    hi = np.maximum.reduceat(coords, ring_off[:-1]) if len(parts) else np.empty((0, 2))
    ci, cj = np.searchsorted(xs, lo[:, 0], "left"), np.searchsorted(ys, lo[:, 1], "left")
    inner = (ci == np.searchsorted(xs, hi[:, 0], "right")) & (cj == np.searchsorted(ys, hi[:, 1], "right"))
    return parts, coords, ring_off, inner


def _reversed(coords, lengths, flip):
    """Closed rings one after another (``lengths`` points each), those where ``flip`` reversed.

    >>> _reversed(np.arange(7.0), np.array([3, 4]), np.array([False, True])).tolist()
    [0.0, 1.0, 2.0, 6.0, 5.0, 4.0, 3.0]
    """
    start = np.repeat(np.cumsum(lengths) - lengths, lengths)
    local = np.arange(len(coords)) - start
    idx = np.where(np.repeat(flip, lengths), start + np.repeat(lengths, lengths) - 1 - local, start + local)
    return coords[idx]


def _relevel_crossed(pieces, rest, low, dips):
    """``pieces`` with the polygons of level ``rest`` that meet ``dips`` moved to level ``low``.

    Outline minus a region whose holes are ``dips`` leaves the dips' pieces among
    the rest; all the rest's other polygons lie outside the region, 20 grid steps
    from any dip (:data:`fabtiles.geometry.interlace.INSET_MM`), so meeting a dip
    is exact where lying in one is not (the points noded at a cell line are
    rounded to the grid, maybe just outside the dip's edge).
    """
    import shapely

    at = [k for k, (_, lvl) in enumerate(pieces) if lvl == rest]
    polys, piece = shapely.get_parts([pieces[k][0] for k in at], return_index=True)
    hit = np.zeros(len(polys), bool)
    hit[shapely.STRtree(polys).query(dips, predicate="intersects")[1]] = True  # few dips, many polygons
    out = [pc for k, pc in enumerate(pieces) if pieces[k][1] != rest]
    for sel, lvl in ((~hit, rest), (hit, low)):
        if sel.any():  # a piece a cell still (indices sorted: get_parts keeps the order)
            # the pieces' numbers made consecutive: a piece with no polygon selected has none
            index = np.unique(piece[sel], return_inverse=True)[1].ravel()
            out += [(g, lvl) for g in shapely.multipolygons(polys[sel], indices=index) if not g.is_empty]
    return out


def _inner_dips(pieces, top, low, coords, lengths):
    """``pieces`` with every dip that lies inside one cell made a hole of the ``top``
    polygon holding it, and the dips themselves added at level ``low``, one piece.

    The dips are closed rings, ``coords`` one after another, ``lengths`` points
    each. Pieces are oriented (exteriors counter-clockwise), so the holes are added
    clockwise and the dips counter-clockwise.
    """
    import shapely

    is_top = np.array([lvl == top for _, lvl in pieces])
    top_idx = np.flatnonzero(is_top)
    polys, piece_of = shapely.get_parts([pieces[k][0] for k in top_idx.tolist()], return_index=True)
    start = np.cumsum(lengths) - lengths
    owner = _owner_of(polys, coords[start])
    ok = owner >= 0  # always (a dip lies strictly inside the region's piece of its cell)
    if not ok.all():
        keep = np.repeat(ok, lengths)
        coords, lengths, owner = coords[keep], lengths[ok], owner[ok]
        start = np.cumsum(lengths) - lengths
    if not len(lengths):
        return pieces
    x, y = coords[:, 0], coords[:, 1]
    twice = x[:-1] * y[1:] - x[1:] * y[:-1]
    twice = np.append(twice, 0.0)
    twice[start[1:] - 1] = 0.0  # no term from one ring's last point to the next ring's first
    ccw = np.add.reduceat(twice, start) > 0
    holed = add_holes(polys, owner, _reversed(coords, lengths, ccw), lengths)  # holes clockwise
    out = [p for k, p in enumerate(pieces) if not is_top[k]]
    out += [(g, top) for g in shapely.multipolygons(holed, indices=piece_of)]
    # the dips themselves, all one piece: the piece's polygons are meshed one by one anyway
    # (fanned, these quads), and one piece is less bookkeeping than one a cell
    dip_polys = shapely.from_ragged_array(
        shapely.GeometryType.POLYGON,
        _reversed(coords, lengths, ~ccw),
        (np.concatenate([[0], np.cumsum(lengths)]), np.arange(len(lengths) + 1)),
    )
    out.append((shapely.multipolygons(dip_polys), low))
    return out
