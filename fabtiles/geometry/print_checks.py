"""3D-printing checks from the printer profile, reported like the laser checks.

:func:`check_print` adds these findings to a :class:`~fabtiles._report.Report`:

``thin_wall``
    Material narrower than the profile's ``min_wall_mm`` (about two line widths of
    the nozzle): the slicer drops such walls or prints them as a single line. With
    the stroke known it is compared directly; without it, two boundaries of the
    same piece closer than the minimum are looked for (as the laser's thin bridges).
``thin_layer``
    A height thinner than two layers (``2 * layer_height_mm``): the relief or the
    plate (relief), the tile (pierced), the groove or the floor under it (deboss).
``bed_size``
    The tile does not fit the profile's bed either way round (a finding, not an
    error: the file may be meant for another printer).
``loose_part``
    Pierced style only: pieces of material not joined to the largest one.

>>> from shapely.geometry import box
>>> plate = box(0, 0, 300, 20)
>>> r = check_print(plate, plate, "fdm-0.4mm", stroke=0.5, relief_mm=0.3)
>>> [f.code for f in r.findings]
['thin_wall', 'thin_layer', 'bed_size']
"""

from __future__ import annotations

import numpy as np
import shapely

from .._profiles import load_profile
from .._report import Report

MAX_LOCATIONS = 20
"""At most this many locations are listed per finding."""


def _locations(points, limit=MAX_LOCATIONS):
    pts = shapely.get_coordinates(np.asarray(points, dtype=object)[:limit])
    return [tuple(np.round(p, 3)) for p in pts]


def _segments_of(rings: np.ndarray, max_points: int = 64):
    """Rings with many points cut into 2-point segments (for a spatial index), with their ring index."""
    npts = shapely.get_num_coordinates(rings)
    big = np.flatnonzero(npts > max_points)
    small = np.flatnonzero(npts <= max_points)
    if not len(big):
        return rings, np.arange(len(rings))
    coords, idx = shapely.get_coordinates(rings[big], return_index=True)
    same = idx[1:] == idx[:-1]
    segs = shapely.linestrings(np.stack([coords[:-1][same], coords[1:][same]], axis=1))
    return np.concatenate([rings[small], segs]), np.concatenate([small, big[idx[:-1][same]]])


def thin_walls(region, width: float):
    """Places where two boundaries of the same piece of ``region`` are closer than ``width``.

    Returns ``(count, narrowest, midpoints)``. Thin dead-end spikes (star tips)
    belong to one boundary and are not reported.

    >>> from shapely.geometry import box
    >>> thin_walls(box(0, 0, 10, 10).difference(box(1, 1, 9.5, 9)), 0.8)[:2]
    (1, 0.5)
    """
    parts = shapely.get_parts(region)
    parts = parts[shapely.area(parts) > 0]
    if not len(parts):
        return 0, float("inf"), []
    n_int = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), n_int)
    idx = np.concatenate([np.arange(k) for k in n_int]) if len(owner) else np.zeros(0, int)
    holes = shapely.get_interior_ring(parts[owner], idx) if len(owner) else np.zeros(0, object)
    rings = np.concatenate([shapely.get_exterior_ring(parts), holes])
    part_of = np.concatenate([np.arange(len(parts)), owner])
    items, ring_of = _segments_of(rings)
    grow = np.array([-width / 2, -width / 2, width / 2, width / 2])
    env = shapely.box(*(shapely.bounds(items) + grow).T)
    a, b = shapely.STRtree(env).query(env)
    ra, rb = ring_of[a], ring_of[b]
    sel = (ra < rb) & (part_of[ra] == part_of[rb])
    a, b = a[sel], b[sel]
    near = shapely.dwithin(items[a], items[b], width * (1 - 1e-9))
    a, b = a[near], b[near]
    if not len(a):
        return 0, float("inf"), []
    _, first = np.unique(ring_of[a] * len(rings) + ring_of[b], return_index=True)
    a, b = a[first], b[first]
    narrowest = float(shapely.distance(items[a], items[b]).min())
    lines = shapely.shortest_line(items[a[:MAX_LOCATIONS]], items[b[:MAX_LOCATIONS]])
    mids = shapely.line_interpolate_point(lines, 0.5, normalized=True)
    return len(a), narrowest, mids


def check_print(region, outline, profile, *, stroke=None, style=None, base_mm=None, relief_mm=None,
                pierced_mm=None, deboss_mm=None, report: Report | None = None) -> Report:
    """Run the printability checks; findings go into ``report`` (see the module text).

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The material, in file coordinates (mm).
    outline : shapely Polygon or MultiPolygon
        The tile outline.
    profile : str, Path or PrinterProfile
    stroke : float, optional
        Stroke width; when given, walls are judged by it instead of by geometry.
    style, base_mm, relief_mm, pierced_mm, deboss_mm : optional
        The part's style and heights; the profile's when not given.
    report : Report, optional
        Added to and returned; a new one (path ``""``) otherwise.
    """
    from ..export._mesh_build import resolve_stack

    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, base_mm, relief_mm, pierced_mm, deboss_mm)
    report = report if report is not None else Report(path="", format="print")
    wall = profile.min_wall_mm

    if stroke is not None:
        if stroke < wall * (1 - 1e-9):
            report.add("thin_wall",
                       f"the stroke is {stroke:g} mm, narrower than min_wall_mm = {wall:g} mm "
                       f"(about two line widths of the {profile.nozzle_mm:g} mm nozzle): walls print thin or not at all")
    else:
        count, narrowest, mids = thin_walls(region, wall)
        if count:
            report.add("thin_wall",
                       f"{count} wall{'s' if count > 1 else ''} narrower than min_wall_mm = {wall:g} mm "
                       f"(narrowest {narrowest:.3g} mm): they print thin or not at all",
                       count=count, locations=_locations(mids))

    layers = 2 * profile.layer_height_mm
    heights = {
        "relief": (("base_mm", stack.base, "the plate"), ("relief_mm", stack.relief, "the relief")),
        "pierced": (("pierced_mm", stack.pierced, "the tile"),),
        "deboss": (("deboss_mm", stack.deboss, "the groove depth"),
                   ("base_mm - deboss_mm", stack.base - stack.deboss, "the floor under the grooves")),
    }[stack.style]
    for key, value, what in heights:
        if value < layers * (1 - 1e-9):
            report.add("thin_layer",
                       f"{what} ({key} = {value:g} mm) is thinner than two layers "
                       f"(2 x layer_height_mm = {layers:g} mm)")

    xmin, ymin, xmax, ymax = outline.bounds
    w, h = xmax - xmin, ymax - ymin
    bw, bh = profile.bed_mm
    eps = 1e-6
    if not ((w <= bw + eps and h <= bh + eps) or (w <= bh + eps and h <= bw + eps)):
        report.add("bed_size",
                   f"the tile is {w:g} x {h:g} mm, larger than the {bw:g} x {bh:g} mm bed of printer profile "
                   f"{profile.name!r} (either way round)")

    if stack.style == "pierced":
        parts = shapely.get_parts(region)
        parts = parts[shapely.area(parts) > 0]
        if len(parts) > 1:
            area = shapely.area(parts)
            loose = np.ones(len(parts), bool)
            loose[np.argmax(area)] = False
            n = int(loose.sum())
            report.add("loose_part",
                       f"{n} piece{'s' if n > 1 else ''} of material not joined to the main piece "
                       f"(a pierced tile falls apart; largest {area[loose].max():.3g} mm^2)",
                       count=n, locations=_locations(shapely.point_on_surface(parts[loose])))
    return report
