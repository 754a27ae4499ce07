"""The levels of a printed body: which area stands at which height (one place for every 3D writer).

A body is a stack of disjoint (polygons, top z) layers over a common bottom (see
:mod:`fabtiles.export._mesh_build`). An interlaced relief has a third level: where
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


def dip_level(dips):
    """The dips as the meshes and the STEP file build them: on the grid, parts thinner
    than :data:`THIN_MM` dropped (those stay at full height). A MultiPolygon, or an
    empty Polygon.

    >>> from shapely.geometry import box
    >>> dip_level(box(0, 0, 1, 2 ** -12)).is_empty, round(dip_level(box(0, 0, 1, 0.5)).area, 3)
    (True, 0.5)
    """
    import shapely

    from ._mesh_build import snap

    if dips is None or dips.is_empty:
        return shapely.Polygon()
    parts = shapely.get_parts(snap(dips))
    parts = parts[~_thin(parts)] if len(parts) else parts
    return shapely.multipolygons(parts) if len(parts) else shapely.Polygon()


def split_region(r, dips, *, holes: bool = True, leveled: bool = False):
    """``(full, dips)``: the region cut into its full-height part and its dips, on the grid.

    ``dips`` must lie strictly inside ``r``, as :func:`fabtiles.geometry.interlace.dips`
    makes them (20 grid steps inside, so snapping keeps them there). The full part
    is then ``r`` with the dips as holes, vertex for vertex: each dip is added as a
    hole of the part of ``r`` holding it, no overlay of the whole region. Dip parts
    thinner than :data:`THIN_MM` stay at full height. ``dips`` may be None or empty;
    ``holes=False`` returns ``r`` itself as the full part; ``leveled`` says ``dips``
    already is :func:`dip_level`'s.
    """
    import shapely

    d = dips if leveled else dip_level(dips)
    if d is None or d.is_empty:
        return r, shapely.Polygon()
    parts = shapely.get_parts(d)
    if not holes:
        return r, d
    owners = shapely.get_parts(r)
    corner = shapely.get_coordinates(shapely.get_point(shapely.get_exterior_ring(parts), 0))
    owner_of = np.full(len(parts), -1)
    hit, cand = shapely.STRtree(owners).query(shapely.points(corner))
    for k in np.unique(cand):  # point in polygon, part by part (prepared: the sheet is one part)
        sel = hit[cand == k]
        shapely.prepare(owners[k])
        inside = shapely.contains_xy(owners[k], corner[sel, 0], corner[sel, 1])
        owner_of[sel[inside]] = k
    if (owner_of < 0).any():  # not inside the region after all: no dip there (never seen)
        parts, owner_of = parts[owner_of >= 0], owner_of[owner_of >= 0]
        d = shapely.multipolygons(parts) if len(parts) else shapely.Polygon()
        if not len(parts):
            return r, d
    # every ring of r, then each dip's exterior as a hole of its owner: one ragged array, no
    # shapely object a ring (0.18 s for the sheet's 20,000 rings built one by one, now 0.02 s)
    _, coords, (ring_off, part_off) = shapely.to_ragged_array(owners)
    ring_off, part_off = np.asarray(ring_off), np.asarray(part_off)
    d_coords, d_ring = shapely.get_coordinates(shapely.get_exterior_ring(parts), return_index=True)
    src = np.concatenate([np.asarray(coords, float), d_coords])
    length = np.concatenate([np.diff(ring_off), np.bincount(d_ring, minlength=len(parts))])
    start = np.cumsum(length) - length  # each ring's first point in src
    owner = np.concatenate([np.repeat(np.arange(len(owners)), np.diff(part_off)), owner_of])
    order = np.argsort(owner, kind="stable")  # each owner's own rings first, then its dips
    length, start = length[order], start[order]
    gather = np.repeat(start - np.concatenate([[0], np.cumsum(length)[:-1]]), length) + np.arange(length.sum())
    new_rings = np.concatenate([[0], np.cumsum(length)])
    new_parts = np.concatenate([[0], np.cumsum(np.bincount(owner, minlength=len(owners)))])
    full = shapely.from_ragged_array(shapely.GeometryType.POLYGON, src[gather], (new_rings, new_parts))
    return shapely.multipolygons(full), d


THIN_MM = 3 * 2.0**-10
"""A part of a level no point of which is farther than this from its edge is thin."""


def _thin(parts):
    """Parts no point of which is farther than :data:`THIN_MM` from their edge (at most).

    Twice the area over the perimeter bounds the largest inscribed disc's radius
    from above, so a part below :data:`THIN_MM` by it is thin (no buffer: 0.15 s
    for the 10,287 dips of the 600 x 400 mm sheet).
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
    >>> from fabtiles.export._mesh_build import Stack
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

    The body without dips is cut into cells as usual (the relief by
    ``coverage_pair``, no overlay of the whole sheet); the dips, strictly inside the
    region, are cut at the same cell lines and taken out of the region's piece of
    their cell as holes. No overlay of a whole sheet: ``coverage`` of the three
    layers took 12 s on the 600 x 400 mm sheet, this 0.5 s (0.2 s without dips).
    ``leveled`` says ``dips`` already is :func:`dip_level`'s.

    >>> from shapely.geometry import box
    >>> from fabtiles.export._mesh_build import Stack
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
        coverage_pair,
        node_polygons,
        split_cells,
    )

    b, h = stack.base, stack.relief
    full, dip = split_region(r, dips, holes=False, leveled=leveled)
    if kind == "relief":
        cov = coverage_pair(r, o, region_z=b + h, rest_z=b, bottom=0.0, shift=shift)
        xs, ys, box = cells_for([r, o], CELL_VERTICES, shift)
    elif kind == "pattern":
        cov = coverage([(r, b + h)], bottom=b, shift=shift)
        xs, ys, box = cells_for([r], CELL_VERTICES, shift)
    else:
        raise ValueError(f"{kind!r} has no dips, must be one of: relief, pattern")
    if dip.is_empty:
        return cov
    d_cells, ex, ey = split_cells(node_polygons(dip, xs, ys), xs, ys, box)
    by_cell = {(i, j): g for i, j, g in d_cells}
    levels = np.array(sorted({*cov.levels.tolist(), dip_z(stack)}))
    remap = np.searchsorted(levels, cov.levels)
    top, low = int(np.searchsorted(levels, b + h)), int(np.searchsorted(levels, dip_z(stack)))
    pieces, cut = [], []
    for piece, lvl in cov.pieces:
        lvl = int(remap[lvl])
        if lvl == top:
            x0, y0, x1, y1 = piece.bounds
            cell = (int(np.searchsorted(ex, (x0 + x1) / 2)) - 1, int(np.searchsorted(ey, (y0 + y1) / 2)) - 1)
            d = by_cell.get(cell)
            if d is not None:
                # the dips lie inside the piece (off its edges but for the cell lines): exact
                cut.append((shapely.difference(piece, d), top))
                cut.append((d, low))
                continue
        pieces.append((piece, lvl))  # already oriented, as coverage_from_cells left it
    from ._mesh_build import coverage_from_cells

    return Coverage(pieces + coverage_from_cells(cut, levels).pieces, levels, cov.xs, cov.ys)
