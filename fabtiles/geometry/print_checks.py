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
from .narrow import MAX_LOCATIONS, locations, narrow_places

WALL_TOLERANCE_MM = 0.01
"""A wall this much thinner than the minimum still counts as the minimum (rounding)."""


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
    from .stack import resolve_stack

    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, base_mm, relief_mm, pierced_mm, deboss_mm)
    report = report if report is not None else Report(path="", format="print")
    wall = profile.min_wall_mm

    if stroke is not None and stroke >= wall * (1 - 1e-9):
        pass  # every band is at least the stroke wide: no wall to look for
    elif stroke is not None:
        # The whole pattern is thin; the places come from the geometry (where two
        # boundaries of one piece are closer than the minimum), for the overlay.
        found = narrow_places(region, wall, tolerance=WALL_TOLERANCE_MM)
        report.add("thin_wall",
                   f"the stroke is {stroke:g} mm, narrower than min_wall_mm = {wall:g} mm "
                   f"(about two line widths of the {profile.nozzle_mm:g} mm nozzle): walls print thin or not at all",
                   count=max(found.count, 1), locations=locations(found.points),
                   sizes=found.widths[:MAX_LOCATIONS].round(3),
                   worst=round(min(stroke, found.narrowest), 3))
    else:
        count, narrowest, mids, widths = narrow_places(region, wall, tolerance=WALL_TOLERANCE_MM)
        if count:
            report.add("thin_wall",
                       f"{count} wall{'s' if count > 1 else ''} narrower than min_wall_mm = {wall:g} mm "
                       f"(narrowest {narrowest:.3g} mm): they print thin or not at all",
                       count=count, locations=locations(mids), sizes=widths[:MAX_LOCATIONS].round(3),
                       worst=round(narrowest, 3))

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
                       count=n, locations=locations(shapely.point_on_surface(parts[loose])),
                       sizes=area[loose][:MAX_LOCATIONS].round(3), worst=round(float(area[loose].max()), 3),
                       unit="mm^2")
    return report
