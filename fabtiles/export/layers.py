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


def split_region(r, dips):
    """``(full, dips)``: the region cut into its full-height part and its dips, on the grid.

    ``dips`` lie strictly inside ``r`` (see :data:`fabtiles.geometry.interlace.INSET_MM`),
    so the full part is ``r`` with the dips as holes, vertex for vertex; dip parts
    thinner than :data:`THIN_MM` are left at full height. ``dips`` may be None or empty.
    """
    import shapely

    from ..geometry.interlace import polygonal
    from ._mesh_build import snap

    if dips is None or dips.is_empty:
        return r, shapely.Polygon()
    d = polygonal(shapely.intersection(snap(dips), r))
    parts = shapely.get_parts(d)
    parts = parts[~_thin(parts)] if len(parts) else parts
    if not len(parts):
        return r, shapely.Polygon()
    d = snap(shapely.MultiPolygon(list(parts)))
    return polygonal(shapely.difference(r, d)), d


THIN_MM = 3 * 2.0**-10
"""A part of a level no point of which is farther than this from its edge is thin."""


def _thin(parts):
    import shapely

    if not len(parts):
        return np.zeros(0, bool)
    return shapely.is_empty(shapely.buffer(parts, -THIN_MM, quad_segs=1, join_style="mitre"))




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


def dips_volume(r, dips, stack) -> float:
    """Volume a relief loses to its dips (mm^3): their area times the depth below full height."""
    if dips is None or dips.is_empty:
        return 0.0
    _, dip = split_region(r, dips)
    return dip.area * (stack.base + stack.relief - dip_z(stack))
