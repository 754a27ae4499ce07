"""The 2D cutters' fabrication checks (the cut plan, :mod:`.cut_plan`, runs them once per plan).

:func:`check_laser` reports, into a :class:`~fabtiles.core.report.Report`:

``small_hole``
    Holes no disc of ``min_hole_mm`` fits in (their inscribed width is smaller):
    they char shut or burn away. ``fill_small_holes=True`` on the writers fills them.
``thin_bridge``
    Material narrower than ``min_feature_mm`` between two boundaries of the same
    part (two holes, or a hole and the outer edge): two rings of one part closer
    than the minimum. Thin dead-end spikes (star tips) are not bridges and are not
    reported; a thin neck with no hole on either side is not seen either.
``loose_part``
    Pieces of material not joined to the main piece of their tile (every piece but
    the largest inside each outline polygon): they fall out of the sheet.
``filled_pattern``
    Filling the small holes (or a router's bit not entering them) left less than
    :data:`~fabtiles.geometry.narrow.PATTERN_KEPT` of the pattern's open area
    (:func:`check_cut_pattern`, run by the cut plan on the region before and after).

A tile larger than the profile's bed (either way round) is not a finding but a
:class:`~fabtiles.FabricationError` (:func:`check_fits_bed`): the file could not be
cut, so it is never written. Likewise a stroke thinner than ``min_feature_mm``, a
kerf below 0 or wider than the stroke are :class:`~fabtiles.ParameterError` (see
``docs/file-conventions.md``), raised by :func:`~fabtiles.geometry.cut_plan.plan_cut` before any work.

>>> from shapely.geometry import box
>>> from fabtiles.machines.profiles import load_profile
>>> plate = box(0, 0, 50, 50).difference(box(10, 10, 10.5, 10.5))
>>> report = check_laser(plate, box(0, 0, 50, 50), load_profile("laser-3mm-plywood"))
>>> [f.code for f in report.findings]
['small_hole']
"""

from __future__ import annotations

import numpy as np
import shapely

from ..core.errors import FabricationError, ProfileError
from ..core.report import Report, distinct
from ..machines.profiles import LaserProfile, load_profile
from .contours import polygon_parts
from .narrow import (
    MAX_LOCATIONS,
    add_small_holes,
    check_pattern_kept,
    hole_polygons,
    locations,
    narrow_places,
    small_hole_mask,
)


def fits_bed(width: float, height: float, bed_mm) -> bool:
    """Whether a ``width`` x ``height`` mm piece fits a bed of ``bed_mm`` either way round (to 1e-6 mm).

    >>> fits_bed(400, 600, (600, 400)), fits_bed(600.15, 400.15, (600, 400))
    (True, False)
    """
    bw, bh = bed_mm
    eps = 1e-6
    return (width <= bw + eps and height <= bh + eps) or (width <= bh + eps and height <= bw + eps)


def check_fits_bed(outline, profile: LaserProfile) -> None:
    """Raise :class:`~fabtiles.FabricationError` if ``outline`` does not fit the bed either way round.

    >>> from shapely.geometry import box
    >>> check_fits_bed(box(0, 0, 400, 600), load_profile("laser-3mm-plywood"))  # fits turned
    >>> check_fits_bed(box(0, 0, 700, 100), load_profile("laser-3mm-plywood"))
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.FabricationError: the tile is 700 x 100 mm, larger than the 600 x 400 mm bed of laser profile 'laser-3mm-plywood' (either way round); make the tile smaller or use a profile with a larger bed_mm
    """  # noqa: E501 - a doctest's lines are as Python prints them
    xmin, ymin, xmax, ymax = outline.bounds
    w, h = xmax - xmin, ymax - ymin
    if fits_bed(w, h, profile.bed_mm):
        return
    bw, bh = profile.bed_mm
    raise FabricationError(
        f"the tile is {w:g} x {h:g} mm, larger than the {bw:g} x {bh:g} mm bed of {profile.kind} profile "
        f"{profile.name!r} (either way round); make the tile smaller or use a profile with a larger bed_mm"
    )


def check_laser(
    region, outline, profile, *, stroke=None, report: Report | None = None, validate: bool = True
) -> Report:
    """Run the fabrication checks of the pierced mode on ``region``; findings go into ``report``.

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The material (nominal, before the kerf offset).
    outline : shapely Polygon or MultiPolygon, optional
        The tile outline(s); on a sheet, one polygon per tile (loose parts are counted per tile).
    profile : str, Path or LaserProfile
    stroke : float, optional
        Stroke width, for messages only.
    report : Report, optional
        Added to and returned; a new one (path ``""``) otherwise.
    validate : bool
        Check ``region`` is valid polygonal geometry (skip when the caller already did).
    """
    profile = load_profile(profile, kind="laser")
    report = report if report is not None else Report(path="", format="laser")
    parts = polygon_parts(region) if validate else shapely.get_parts(region)
    holes, owner = hole_polygons(parts)
    tol2 = profile.tolerance_mm**2
    real = shapely.area(holes) > tol2
    holes, owner = holes[real], owner[real]

    if len(holes):
        small = small_hole_mask(holes, profile.min_hole_mm)
        if small.any():
            add_small_holes(
                report,
                holes[small],
                tolerance_mm=profile.tolerance_mm,
                message=lambda n, w: (
                    f"{n:,} hole{'s' if n > 1 else ''} narrower than min_hole_mm = {profile.min_hole_mm:g} mm "
                    f"(narrowest {distinct(w, profile.min_hole_mm)} mm; they burn away or char shut; fill them with "
                    "fill_small_holes=True, or fill_small_holes = true in a design's [output])"
                ),
                limit_mm=profile.min_hole_mm,
            )

    # thin bridges: two rings of the same part closer than the minimum feature (within the
    # profile's tolerance: a band exactly min_feature_mm wide is fine to cut)
    f = profile.min_feature_mm
    count, width, mids, widths = narrow_places(region, f, tolerance=profile.tolerance_mm)
    if count:
        extra = f"; the stroke is {stroke:g} mm" if stroke is not None else ""
        report.add(
            "thin_bridge",
            f"{count:,} bridge{'s' if count > 1 else ''} narrower than min_feature_mm = {f:g} mm "
            f"(narrowest {distinct(width, f)} mm{extra}): they may burn through or break",
            count=count,
            locations=locations(mids),
            sizes=widths[:MAX_LOCATIONS].round(3),
            worst=round(width, 3),
            limit=f,
        )

    # loose parts: all but the largest piece inside each outline polygon
    if len(parts) > 1:
        _check_loose(parts, outline, report)
    return report


def _check_loose(parts, outline, report: Report) -> None:
    """The report told of the pieces of material not joined to the largest in their outline polygon."""
    group = np.full(len(parts), -1)
    if outline is not None:
        tiles = polygon_parts(outline, "outline")
        pa, pb = shapely.STRtree(tiles).query(shapely.point_on_surface(parts), predicate="within")
        group[pa] = pb
    area = shapely.area(parts)
    loose = np.ones(len(parts), dtype=bool)
    for g in np.unique(group):
        members = np.flatnonzero(group == g)
        loose[members[np.argmax(area[members])]] = False
    add_loose_parts(report, parts, area, loose, falls="they fall out")


def add_loose_parts(report: Report, parts, area, loose, *, falls: str) -> None:
    """The ``loose_part`` finding for the ``parts`` flagged ``loose`` (``area`` each), if any; ``falls``
    says what becomes of them (the laser's and the printer's checks word it their way)."""
    if not loose.any():
        return
    n = int(loose.sum())
    report.add(
        "loose_part",
        f"{n} piece{'s' if n > 1 else ''} of material not joined to the main piece "
        f"({falls}; largest {area[loose].max():.3g} mm^2)",
        count=n,
        locations=locations(shapely.point_on_surface(parts[loose])),
        sizes=area[loose][:MAX_LOCATIONS].round(3),
        worst=round(float(area[loose].max()), 3),
        unit="mm^2",
    )


def check_cut_pattern(before, after, outline, profile, *, stroke=None, report: Report) -> float:
    """Report ``filled_pattern`` when the cutter's part keeps too little of the pattern (returns the share kept).

    ``before`` is the material as designed, ``after`` as the file holds it (its small
    holes filled; a router's or waterjet's holes opened by its tool, those it cannot
    enter left material). The limit is the profile's ``min_hole_mm``, or the tool's
    diameter when that is wider; see :func:`~fabtiles.geometry.narrow.check_pattern_kept`.

    >>> from shapely.geometry import box
    >>> plate = box(0, 0, 20, 20).difference(box(4, 4, 5, 5))
    >>> r = Report(path="", format="")
    >>> check_cut_pattern(plate, box(0, 0, 20, 20), box(0, 0, 20, 20), load_profile("laser-3mm-plywood"),
    ...                   stroke=2.0, report=r)
    0.0
    >>> print(r.findings[0].message)  # doctest: +ELLIPSIS
    filling the holes narrower than min_hole_mm = 1.2 mm of laser profile 'laser-3mm-plywood' left none of ... or a profile with min_hole_mm <= 1 mm
    """  # noqa: E501 - a doctest's lines are as Python prints them
    kind = profile.cutter
    m = profile.min_hole_mm
    limit = f"min_hole_mm = {m:g} mm of {profile.kind} profile {profile.name!r}"
    tool = "a profile with min_hole_mm <= {w} mm"
    if kind.opens_holes and 2 * kind.tool_radius(profile) > m:
        m = 2 * kind.tool_radius(profile)
        limit, tool = kind.tool_name(profile), f"a {kind.tool} of {{w}} mm or narrower"
    return check_pattern_kept(
        report,
        before,
        after,
        outline,
        limit_mm=m,
        limit=limit,
        stroke=stroke,
        min_stroke_mm=profile.min_feature_mm,
        tool=tool,
        tolerance_mm=profile.tolerance_mm,
    )


def check_layers(profile: LaserProfile) -> None:
    """The profile's cut and score layers must have a DXF colour (ACI 1..255) and a valid DXF layer name."""
    for key in ("inner_cut", "outer_cut", "score"):
        layer = getattr(profile.layers, key)
        if isinstance(layer.color, bool) or not isinstance(layer.color, int) or not 1 <= layer.color <= 255:
            raise ProfileError(
                f"profile {profile.name!r}: layers.{key}.color must be an AutoCAD Color "
                f"Index 1..255, got {layer.color!r}"
            )
        if not isinstance(layer.name, str) or not layer.name or any(c in layer.name for c in "<>/\\\":;?*|='"):
            raise ProfileError(
                f"profile {profile.name!r}: layers.{key}.name must be a non-empty DXF layer "
                f"name without <>/\\\":;?*|=', got {layer.name!r}"
            )


def engrave_layer(profile: LaserProfile):
    """The profile's engrave layer, or a :class:`~fabtiles.ProfileError` saying what to add."""
    if profile.layers.engrave is None:
        raise ProfileError(
            f"laser profile {profile.name!r} has no engrave layer, which the engrave mode fills: add "
            'engrave = { name = "FILL", color = 6, speed_mm_s = 250, power_pct = 20, line_interval_mm = 0.1 } '
            "to its [layers]"
        )
    return profile.layers.engrave


def check_engrave(region, profile: LaserProfile, report: Report) -> Report:
    """The engrave mode's check: bands narrower than two fill lines (``thin_fill``).

    Nothing is cut free in this mode, so holes, bridges and loose parts do not matter;
    a band narrower than two lines of the fill comes out as one line or none.
    """
    layer = engrave_layer(profile)
    width = 2 * layer.line_interval_mm
    count, worst, mids, widths = narrow_places(region, width, tolerance=profile.tolerance_mm)
    if count:
        report.add(
            "thin_fill",
            f"{count} band{'s' if count > 1 else ''} of the engraving narrower than two fill lines "
            f"({width:g} mm at line_interval_mm = {layer.line_interval_mm:g}; narrowest {distinct(worst, width)} mm): "
            "they engrave as one line or vanish",
            count=count,
            locations=locations(mids),
            sizes=widths[:MAX_LOCATIONS].round(3),
            worst=round(worst, 3),
            limit=width,
        )
    return report
