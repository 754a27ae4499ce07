"""Laser fabrication checks, and the one preparation step shared by the laser writers.

:func:`check_laser` reports, into a :class:`~fabtiles._report.Report`:

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

A tile larger than the profile's bed (either way round) is not a finding but a
:class:`~fabtiles.FabricationError` (:func:`check_fits_bed`): the file could not be
cut, so it is never written. Likewise a stroke thinner than ``min_feature_mm``, a
kerf below 0 or wider than the stroke are :class:`~fabtiles.ParameterError` (see
``docs/file-conventions.md``), raised by :func:`prepare_laser` before any work.

>>> from shapely.geometry import box
>>> from fabtiles._profiles import load_profile
>>> plate = box(0, 0, 50, 50).difference(box(10, 10, 10.5, 10.5))
>>> report = check_laser(plate, box(0, 0, 50, 50), load_profile("laser-3mm-plywood"))
>>> [f.code for f in report.findings]
['small_hole']
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import shapely

from .._errors import FabricationError, ParameterError, ProfileError
from .._profiles import DXF_VERSIONS, LASER_MODES, LaserProfile, load_profile
from .narrow import MAX_LOCATIONS, add_small_holes, fill_small_holes, hole_polygons, locations, narrow_places, \
    small_hole_mask
from .._report import Report, distinct
from .._validate import check_choice, check_float
from .contours import clean_rings, laser_contours, outline_contours, polygon_parts, score_paths
from .job_time import estimate
from .material import sheet
from .tool_opening import check_tool



_fill_small_holes = fill_small_holes  # the option of prepare_laser has the same name


def check_fits_bed(outline, profile: LaserProfile) -> None:
    """Raise :class:`~fabtiles.FabricationError` if ``outline`` does not fit the bed either way round.

    >>> from shapely.geometry import box
    >>> check_fits_bed(box(0, 0, 400, 600), load_profile("laser-3mm-plywood"))  # fits turned
    >>> check_fits_bed(box(0, 0, 700, 100), load_profile("laser-3mm-plywood"))
    Traceback (most recent call last):
    ...
    fabtiles._errors.FabricationError: the tile is 700 x 100 mm, larger than the 600 x 400 mm bed of laser profile 'laser-3mm-plywood' (either way round); make the tile smaller or use a profile with a larger bed_mm
    """
    xmin, ymin, xmax, ymax = outline.bounds
    w, h = xmax - xmin, ymax - ymin
    bw, bh = profile.bed_mm
    eps = 1e-6
    if (w <= bw + eps and h <= bh + eps) or (w <= bh + eps and h <= bw + eps):
        return
    raise FabricationError(
        f"the tile is {w:g} x {h:g} mm, larger than the {bw:g} x {bh:g} mm bed of {profile.kind} profile "
        f"{profile.name!r} (either way round); make the tile smaller or use a profile with a larger bed_mm"
    )


def check_laser(region, outline, profile, *, stroke=None, report: Report | None = None,
                validate: bool = True) -> Report:
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
    tol2 = profile.tolerance_mm ** 2
    real = shapely.area(holes) > tol2
    holes, owner = holes[real], owner[real]

    if len(holes):
        small = small_hole_mask(holes, profile.min_hole_mm)
        if small.any():
            add_small_holes(report, holes[small], tolerance_mm=profile.tolerance_mm, message=lambda n, w: (
                f"{n} hole{'s' if n > 1 else ''} narrower than min_hole_mm = {profile.min_hole_mm:g} mm "
                f"(narrowest {distinct(w, profile.min_hole_mm)} mm; they burn away or char shut; fill them with "
                "fill_small_holes=True, or fill_small_holes = true in a design's [output])"))

    # thin bridges: two rings of the same part closer than the minimum feature (within the
    # profile's tolerance: a band exactly min_feature_mm wide is fine to cut)
    f = profile.min_feature_mm
    count, width, mids, widths = narrow_places(region, f, tolerance=profile.tolerance_mm)
    if count:
        extra = f"; the stroke is {stroke:g} mm" if stroke is not None else ""
        report.add("thin_bridge",
                   f"{count} bridge{'s' if count > 1 else ''} narrower than min_feature_mm = {f:g} mm "
                   f"(narrowest {distinct(width, f)} mm{extra}): they may burn through or break",
                   count=count, locations=locations(mids), sizes=widths[:MAX_LOCATIONS].round(3),
                   worst=round(width, 3))

    # loose parts: all but the largest piece inside each outline polygon
    if len(parts) > 1:
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
        if loose.any():
            n = int(loose.sum())
            report.add("loose_part",
                       f"{n} piece{'s' if n > 1 else ''} of material not joined to the main piece "
                       f"(they fall out; largest {area[loose].max():.3g} mm^2)",
                       count=n, locations=locations(shapely.point_on_surface(parts[loose])),
                       sizes=area[loose][:MAX_LOCATIONS].round(3), worst=round(float(area[loose].max()), 3),
                       unit="mm^2")
    return report


@dataclass
class LaserJob:
    """Everything a laser writer needs: resolved options and the contours in cut order."""

    profile: LaserProfile
    mode: str
    dxf_version: str
    kerf_mm: float
    inner: list = field(default_factory=list)
    outer: list = field(default_factory=list)
    score: list = field(default_factory=list)
    engrave: list = field(default_factory=list)
    """Engrave mode: the rings of the filled bands (exteriors counter-clockwise, holes clockwise)."""
    engrave_parts: list = field(default_factory=list)
    """The polygon (0, 1, ...) each engrave ring belongs to: a fill's outline and its holes."""
    engrave_area_mm2: float = 0.0
    bounds: tuple = (0.0, 0.0, 0.0, 0.0)
    estimate: object = None
    """The job's length and time (:class:`~fabtiles.geometry.job_time.JobEstimate`)."""


def _check_profile(profile: LaserProfile) -> None:
    profile.cutter.check_profile(profile)
    for key in ("inner_cut", "outer_cut", "score"):
        layer = getattr(profile.layers, key)
        if isinstance(layer.color, bool) or not isinstance(layer.color, int) or not 1 <= layer.color <= 255:
            raise ProfileError(f"profile {profile.name!r}: layers.{key}.color must be an AutoCAD Color "
                               f"Index 1..255, got {layer.color!r}")
        if not isinstance(layer.name, str) or not layer.name or any(c in layer.name for c in '<>/\\":;?*|=\''):
            raise ProfileError(f"profile {profile.name!r}: layers.{key}.name must be a non-empty DXF layer "
                               f"name without <>/\\\":;?*|=', got {layer.name!r}")


def _length(rings, closed: bool) -> float:
    """Total length of polylines (closed: with the closing edge)."""
    if not rings:
        return 0.0
    flat = np.concatenate(rings)
    total = float(np.hypot(*np.diff(flat, axis=0).T).sum())
    starts = np.cumsum([0] + [len(r) for r in rings])
    # remove the jumps between polylines, add the closing edges
    jumps = flat[starts[1:-1]] - flat[starts[1:-1] - 1]
    total -= float(np.hypot(*jumps.T).sum())
    if closed:
        close = flat[starts[:-1]] - flat[starts[1:] - 1]
        total += float(np.hypot(*close.T).sum())
    return total


def engrave_layer(profile: LaserProfile):
    """The profile's engrave layer, or a :class:`~fabtiles.ProfileError` saying what to add."""
    if profile.layers.engrave is None:
        raise ProfileError(
            f"laser profile {profile.name!r} has no engrave layer, which the engrave mode fills: add "
            'engrave = { name = "FILL", color = 6, speed_mm_s = 250, power_pct = 20, line_interval_mm = 0.1 } '
            "to its [layers]")
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
        report.add("thin_fill",
                   f"{count} band{'s' if count > 1 else ''} of the engraving narrower than two fill lines "
                   f"({width:g} mm at line_interval_mm = {layer.line_interval_mm:g}; narrowest {distinct(worst, width)} mm): "
                   "they engrave as one line or vanish",
                   count=count, locations=locations(mids), sizes=widths[:MAX_LOCATIONS].round(3),
                   worst=round(worst, 3))
    return report


def _engrave(job: LaserJob, region, outline, report: Report, kerf_y: float) -> None:
    """Engrave mode: the outline cut, the material's bands filled on the engrave layer."""
    profile = job.profile
    check_engrave(region, profile, report)
    report.raise_if_strict(profile.strict)
    job.outer = outline_contours(outline, kerf_mm=job.kerf_mm, kerf_y_mm=kerf_y, tolerance_mm=profile.tolerance_mm)
    parts = shapely.get_parts(region)
    rings, part = shapely.get_rings(parts, return_index=True)
    exterior = np.zeros(len(rings), dtype=bool)
    starts = np.concatenate([[0], np.cumsum(shapely.get_num_interior_rings(parts) + 1)[:-1]])
    exterior[starts] = True
    cleaned, kept = clean_rings(rings, min_area=profile.tolerance_mm ** 2, ccw=exterior)
    job.engrave, job.engrave_parts = cleaned, part[kept].tolist()
    job.engrave_area_mm2 = float(shapely.area(parts).sum())
    report.stats.update(area_mm2=round(job.engrave_area_mm2, 3), engrave_rings=len(cleaned))


def prepare_laser(path, fmt, *, region, outline, centrelines=None, profile, mode=None, dxf_version=None,
                  kerf_mm=None, fill_small_holes: bool = False, stroke=None):
    """Validate the options, run the checks and build the contours: ``(LaserJob, Report)``.

    Raises before anything is written: :class:`~fabtiles.ParameterError` for bad
    options, :class:`~fabtiles.ProfileError` for a bad profile,
    :class:`~fabtiles.FabricationError` for a tile larger than the bed or, with a
    strict profile, any finding.
    """
    profile = load_profile(profile, kind="laser")
    _check_profile(profile)
    mode = profile.mode if mode is None else mode
    if mode == "inlay":
        raise ParameterError("the inlay mode writes a kit of two files (lattice and pieces): export it with "
                             "fabtiles.export.kit.write_kit, Tile.export(..., mode='inlay') or fabtiles build",
                             param="mode")
    mode = check_choice("mode", mode, LASER_MODES)
    cutter = profile.cutter
    cutter.check_mode(profile, mode)
    cutter.check_format(profile, fmt)
    dxf_version = check_choice("dxf_version", profile.dxf_version if dxf_version is None else dxf_version,
                               DXF_VERSIONS)
    if kerf_mm is None:  # the profile's kerf, along X and along Y
        kerf, kerf_y = profile.kerf_xy_mm
    else:
        kerf = kerf_y = check_float("kerf_mm", kerf_mm, low=0)
        cutter.check_kerf(profile, kerf)
    if stroke is not None:
        stroke = check_float("stroke", stroke, low=0, low_open=True)
        if stroke < profile.min_feature_mm:
            raise ParameterError(f"stroke must be >= min_feature_mm = {profile.min_feature_mm:g} mm of {profile.kind} "
                                 f"profile {profile.name!r}, got {stroke:g}", param="stroke")
        if max(kerf, kerf_y) > stroke:
            raise ParameterError(f"kerf_mm must be >= 0 and <= the stroke ({stroke:g} mm), got {max(kerf, kerf_y):g}",
                                 param="kerf_mm")
    if not isinstance(fill_small_holes, bool):
        raise ParameterError(f"fill_small_holes must be True or False, got {fill_small_holes!r}",
                             param="fill_small_holes")
    parts = polygon_parts(region)
    outline_parts = polygon_parts(outline, "outline")
    check_fits_bed(outline, profile)

    report = Report(path=str(path), format=fmt)
    job = LaserJob(profile, mode, dxf_version, kerf)
    report.stats.update(profile=profile.name, mode=mode, kerf_mm=kerf)
    if kerf_y != kerf:
        report.stats["kerf_y_mm"] = kerf_y
    if fmt == "dxf":
        report.stats["dxf_version"] = dxf_version
    report.stats.update(cutter.report_stats())
    if mode == "pierced":
        tool_filled = 0
        if cutter.opens_holes:  # the part as the bit or the jet makes it: holes opened by its radius
            region, _, tool_filled = check_tool(region, profile, fill_small_holes=fill_small_holes, report=report)
            parts = shapely.get_parts(region)
        if fill_small_holes:
            region, filled = _fill_small_holes(region, profile.min_hole_mm,
                                                tolerance_mm=profile.tolerance_mm)
            report.stats["filled_holes"] = filled + tool_filled
            parts = shapely.get_parts(region)
            if tool_filled:
                report.note(f"filled {tool_filled:,} hole{'s' if tool_filled != 1 else ''} that "
                            f"{cutter.tool_name(profile)} cannot enter")
            if filled:
                report.note(f"filled {filled:,} hole{'s' if filled != 1 else ''} narrower than min_hole_mm = "
                            f"{profile.min_hole_mm:g} mm of {profile.kind} profile {profile.name!r}")
        check_laser(region, outline, profile, stroke=stroke, report=report, validate=False)
        report.raise_if_strict(profile.strict)
        job.inner, job.outer = laser_contours(region, outline, kerf_mm=kerf, kerf_y_mm=kerf_y,
                                              tolerance_mm=profile.tolerance_mm, validate=False)
        report.stats["area_mm2"] = round(float(shapely.area(parts).sum()), 3)
    elif mode == "engrave":
        _engrave(job, region, outline, report, kerf_y)
    else:
        if centrelines is None or len(np.asarray(centrelines)) == 0:
            raise ParameterError("the score mode needs centrelines (an array of shape (k, 2, 2)), got none",
                                 param="centrelines")
        job.outer = outline_contours(outline, kerf_mm=kerf, kerf_y_mm=kerf_y, tolerance_mm=profile.tolerance_mm)
        job.score = score_paths(centrelines, outline, tolerance_mm=profile.tolerance_mm)
        report.stats["area_mm2"] = round(float(shapely.area(outline_parts).sum()), 3)
        report.stats["score_paths"] = len(job.score)
        report.stats["score_length_mm"] = round(_length(job.score, False), 3)
    allr = job.inner + job.outer + job.score + job.engrave
    flat = np.concatenate(allr) if allr else np.zeros((1, 2))
    job.bounds = (*flat.min(axis=0).tolist(), *flat.max(axis=0).tolist())
    report.stats.update(inner_contours=len(job.inner), outer_contours=len(job.outer),
                        vertices=int(sum(len(r) for r in allr)),
                        cut_length_mm=round(_length(job.inner + job.outer, True), 3))
    job.estimate = estimate(profile, inner=job.inner, outer=job.outer, score=job.score, engrave=job.engrave,
                            engrave_area_mm2=job.engrave_area_mm2)
    report.stats["job"] = job.estimate.as_stats()
    report.stats["sheet"] = sheet(outline, profile)
    return job, report
