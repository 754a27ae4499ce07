"""A design on a cylinder: a texture roller (relief, deboss) or a lampshade (pierced), made from its unrolled strip.

The design's ``[surface]`` (:class:`~fabtiles.designs.design_file.SurfaceSpec`) has
made its tile the unrolled strip: ``x`` round the circumference ``C = pi D`` (a whole
number of the pattern's periods, so the ends ``x = 0`` and ``x = C`` meet seamlessly),
``y`` along the length. Here the strip is made what the cylinder prints: mirrored
``x -> C - x`` for a roller (what it leaves in clay is the mirror of its surface),
closed by a rim at each ``y`` end, and made into the flat print model as a tile is,
its plate as thick as the roller's wall down to the bore, before
:func:`fabtiles.solid.cylinder.cylinder_print` wraps it round the axis. Every value
that cannot make a cylinder is refused here, before any geometry
(:func:`check_surface`), with the parameter, its value and the limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..core.errors import ParameterError
from ..core.report import Report

if TYPE_CHECKING:
    from ..designs.design_file import SurfaceSpec
    from .models import BuildOptions


@dataclass(frozen=True)
class Cylinder:
    """A cylinder's resolved measures (mm) and choices, for its print style and printer.

    ``outer_radius_mm`` is the pattern's outer surface, ``circumference_mm`` the strip's
    width; ``bore_mm`` a roller's axle hole (0 for a shade), ``rim_mm`` each end's closed
    band, ``heights`` the flat print's heights (a roller's plate reaches down to the bore).
    """

    style: str
    circumference_mm: float
    length_mm: float
    mirror: bool
    bore_mm: float
    rim_mm: float
    lamp_fitting_mm: float | None
    pointed_tops: bool
    heights: dict

    @property
    def outer_radius_mm(self) -> float:
        """The radius of the pattern's outer surface."""
        return self.circumference_mm / (2 * math.pi)

    @property
    def roller(self) -> bool:
        """A roller (relief, deboss) rather than a shade (pierced)."""
        return self.style != "pierced"

    def line(self) -> str:
        """The cylinder in one line for the reports."""
        what = "roller" if self.roller else "shade"
        parts = [f"cylinder ({what}): outer diameter {2 * self.outer_radius_mm:.2f} mm x {self.length_mm:g} mm"]
        if self.roller:
            parts.append(f"bore {self.bore_mm:g} mm")
        parts.append(f"rims {self.rim_mm:g} mm" if self.rim_mm > 0 else "no rims")
        parts.append("mirrored" if self.mirror else "not mirrored")
        if self.lamp_fitting_mm is not None:
            parts.append(f"lamp holder for a {self.lamp_fitting_mm:g} mm fitting")
        if self.pointed_tops:
            parts.append("pointed tops")
        return ", ".join(parts) + "; printed standing on an end"


def cylinder_of(surface: SurfaceSpec, options: BuildOptions, circumference_mm: float) -> Cylinder:
    """The cylinder ``surface`` makes with the printer and style of ``options``, its values checked
    (:func:`check_surface`), at the strip's ``circumference_mm``."""
    from ..geometry.stack import resolve_stack

    printer = options.printer
    style = options.print_style or printer.print_style
    if style not in ("relief", "deboss", "pierced"):
        raise ParameterError(
            f"print_style = {style!r} is not made on a cylinder, must be one of: relief, deboss (a roller), "
            "pierced (a shade)",
            param="output.print_style",
        )
    if "base_mm" in options.heights:
        raise ParameterError(
            f"base_mm = {options.heights['base_mm']:g} is not set on a cylinder: a roller's wall reaches from "
            "its outer surface (diameter) to its bore (bore_mm), a shade's is pierced_mm thick; remove base_mm",
            param="output.base_mm",
        )
    surface_keys(surface, style)
    assert surface.length is not None  # a cylinder's length is required by the design
    stack = resolve_stack(printer, style, **{k: v for k, v in options.heights.items() if k != "base_mm"})
    radius = circumference_mm / (2 * math.pi)
    bore = surface.bore_for(style)
    sunk = stack.relief if style == "relief" else stack.deboss if style == "deboss" else 0.0
    heights = dict(options.heights)
    if style != "pierced":
        heights["base_mm"] = radius - sunk - bore / 2 if style == "relief" else radius - bore / 2
    cylinder = Cylinder(
        style=style,
        circumference_mm=circumference_mm,
        length_mm=surface.length,
        mirror=surface.mirror_for(style),
        bore_mm=bore,
        rim_mm=surface.rim_for(style),
        lamp_fitting_mm=surface.lamp_fitting_mm,
        pointed_tops=surface.pointed_tops,
        heights=heights,
    )
    check_cylinder(cylinder, printer, wall_mm=stack.pierced if style == "pierced" else radius - sunk - bore / 2)
    return cylinder


def surface_keys(surface: SurfaceSpec, style: str) -> None:
    """Refuse a roller's key on a shade and a shade's on a roller."""
    roller = surface.roller(style)
    if not roller and surface.bore_mm is not None:
        raise ParameterError(
            f"bore_mm = {surface.bore_mm:g} is a roller's (print_style relief or deboss), not a pierced "
            "shade's: a shade is open inside; remove bore_mm",
            param="surface.bore_mm",
        )
    if roller and surface.lamp_fitting_mm is not None:
        raise ParameterError(
            f"lamp_fitting_mm = {surface.lamp_fitting_mm:g} is a pierced shade's, not a roller's "
            f"(print_style {style}); remove it or print the shade pierced",
            param="surface.lamp_fitting_mm",
        )


def check_cylinder(cylinder: Cylinder, printer, *, wall_mm: float) -> None:
    """Refuse a cylinder its printer cannot make: longer than the printer builds, wider than its bed, a wall
    thinner than its ``min_wall_mm`` (a bore too wide), a shade's wall or lamp fitting wider than the shade,
    rims that meet."""
    name = f"printer profile {printer.name!r}"
    diameter = 2 * cylinder.outer_radius_mm
    if cylinder.length_mm > printer.height_mm:
        raise ParameterError(
            f"length = {cylinder.length_mm:g} mm is beyond the build height of {name}, {printer.height_mm:g} mm "
            "(a cylinder prints standing on an end); make it at most that long",
            param="surface.length",
        )
    if diameter > min(printer.bed_mm):
        raise ParameterError(
            f"diameter = {diameter:.2f} mm does not stand on the {printer.bed_mm[0]:g} x {printer.bed_mm[1]:g} mm "
            f"bed of {name}; make it at most {min(printer.bed_mm):g} mm (a cylinder is not printed in pieces)",
            param="surface.diameter",
        )
    if 2 * cylinder.rim_mm >= cylinder.length_mm:
        raise ParameterError(
            f"rim_mm = {cylinder.rim_mm:g} leaves no pattern between the two rims of a {cylinder.length_mm:g} mm "
            f"cylinder; it must be less than {cylinder.length_mm / 2:g} mm",
            param="surface.rim_mm",
        )
    if cylinder.roller:
        _check_bore(cylinder, printer, wall_mm, name)
    else:
        _check_shade(cylinder, printer, wall_mm, name)


def _check_bore(cylinder: Cylinder, printer, wall_mm: float, name: str) -> None:
    """A roller's wall, between its bore and the bottom of its pattern, at least the printer's least wall."""
    if wall_mm < printer.min_wall_mm:
        most = 2 * (wall_mm + cylinder.bore_mm / 2 - printer.min_wall_mm)
        raise ParameterError(
            f"bore_mm = {cylinder.bore_mm:g} leaves "
            f"{'no wall' if wall_mm <= 0 else f'a wall of {wall_mm:.2f} mm'} under the pattern of a "
            f"{2 * cylinder.outer_radius_mm:.2f} mm roller, thinner than the min_wall_mm of {name}, "
            f"{printer.min_wall_mm:g} mm; the bore may be at most {max(most, 0):.2f} mm",
            param="surface.bore_mm",
        )


def _check_shade(cylinder: Cylinder, printer, wall_mm: float, name: str) -> None:
    """A shade's wall thinner than its radius, and its lamp fitting (with the holder's ring round it) inside it."""
    radius = cylinder.outer_radius_mm
    if wall_mm >= radius:
        raise ParameterError(
            f"pierced_mm = {wall_mm:g}, the shade's wall, is as thick as its radius, {radius:.2f} mm; "
            "make the wall thinner or the diameter larger",
            param="output.pierced_mm",
        )
    if cylinder.lamp_fitting_mm is None:
        return
    from ..solid.cylinder import LampHolder

    ring = LampHolder(fitting_mm=cylinder.lamp_fitting_mm).ring_mm  # the holder's ring, as it is made
    inside = 2 * (radius - wall_mm)
    room = inside - 4 * ring
    if cylinder.lamp_fitting_mm > room:
        raise ParameterError(
            f"lamp_fitting_mm = {cylinder.lamp_fitting_mm:g} is wider than the shade holds: its inside is "
            f"{inside:.2f} mm across, and the holder's ring round the fitting and its spokes into the wall take "
            f"{ring:g} mm each, each side; the fitting may be at most {room:.2f} mm",
            param="surface.lamp_fitting_mm",
        )


def check_formats(formats, shape: str = "cylinder") -> None:
    """Refuse a cylinder or a stamp (``shape``) whose formats are all a cutter's: it is printed, not cut."""
    from ..export.formats import FORMATS, names_where

    if not any(FORMATS[f].family == "print" for f in formats):
        raise ParameterError(
            f'[surface] shape = "{shape}" is printed, not cut: formats {", ".join(formats)} make none of it; '
            f"a {shape} is made in the print formats, {', '.join(names_where(family='print'))} (its STEP is "
            "refused with the reason: see docs/surfaces.md)",
            param="output.formats",
        )


def unmade_formats(formats, shape: str = "cylinder") -> dict[str, str]:
    """The formats of ``formats`` a cylinder or a stamp (``shape``) is not made in, each with the reason in
    one line: the cutters' (one reason naming them all, :func:`check_formats`' refusal) and STEP
    (:data:`fabtiles.solid.cylinder.NO_STEP`, :data:`fabtiles.solid.stamp.NO_STEP`)."""
    from ..export.formats import FORMATS
    from ..solid import cylinder, stamp

    cut = [f for f in formats if FORMATS[f].family != "print"]
    reasons: dict[str, str] = {}
    if cut:
        try:
            check_formats(cut, shape)
        except ParameterError as err:
            reasons = dict.fromkeys(cut, str(err))
    if "step" in formats:
        reasons["step"] = cylinder.NO_STEP if shape == "cylinder" else stamp.NO_STEP
    return reasons


def strip_region(region, dips, outline, cylinder: Cylinder, printer=None):
    """The strip's material as the cylinder prints it: mirrored ``x -> C - x`` when asked, a rim at each
    ``y`` end (a relief's raised to the pattern's top, a shade's closed; a deboss's plain plate, no groove
    in it) and, with ``pointed_tops``, each opening's top raised to a peak at ``printer``'s overhang limit
    (:func:`~fabtiles.geometry.wall_overhangs.pointed_tops`). ``(region, dips, tops)``: ``tops`` the
    :class:`~fabtiles.geometry.wall_overhangs.PointedTops` made, or None."""
    import shapely

    from ..geometry.interlace import polygonal
    from ..geometry.mirror import mirrored

    c, length, rim = cylinder.circumference_mm, cylinder.length_mm, cylinder.rim_mm
    if cylinder.mirror:  # the strip's outline is [0, C] across: mirrored about it, x -> C - x
        region = mirrored(region, outline)
        dips = None if dips is None else mirrored(dips, outline)
    if rim > 0:
        rims = shapely.union(shapely.box(0, 0, c, rim), shapely.box(0, length - rim, c, length))
        region = shapely.difference(region, rims) if cylinder.style == "deboss" else shapely.union(region, rims)
        if dips is not None:
            dips = shapely.difference(dips, rims)
    region = polygonal(shapely.intersection(region, outline))  # an overlay may leave lines where the rims meet
    tops = None
    if cylinder.pointed_tops:
        region, tops = _pointed(region, outline, cylinder, printer)
        if dips is not None:
            dips = _dips_inside(dips, region)
    if dips is not None:
        dips = polygonal(dips)
    return region, dips, tops


def _dips_inside(dips, region):
    """An interlaced relief's ``dips`` kept :data:`~fabtiles.geometry.interlace.INSET_MM` inside the ``region``
    where a peak cut into them: a dip on the region's edge would cross it once both are put on the mesh's grid."""
    import shapely

    from ..geometry.interlace import INSET_MM, polygonal

    parts = shapely.get_parts(dips)
    if not len(parts):
        return dips
    shapely.prepare(region)
    cut = ~shapely.contains_properly(region, parts)
    if cut.any():
        near = shapely.intersection(region, shapely.envelope(shapely.buffer(shapely.union_all(parts[cut]), 1.0)))
        parts[cut] = shapely.intersection(parts[cut], shapely.buffer(near, -INSET_MM))
    return polygonal(shapely.get_parts(parts))


def _pointed(region, outline, cylinder: Cylinder, printer):
    """``region`` with its openings' tops pointed at the printer's overhang limit, keeping its ``min_wall_mm``:
    a shade's or a relief's openings are the holes in its material, a deboss's its grooves (the region)."""
    import shapely

    from ..geometry.interlace import polygonal
    from ..geometry.wall_overhangs import pointed_tops

    if printer is None:
        raise ParameterError("pointed_tops needs the printer profile whose overhang limit the peaks keep to")
    material = shapely.difference(outline, region) if cylinder.style == "deboss" else region
    tops = pointed_tops(
        material,
        overhang_deg=printer.max_overhang_deg,
        min_wall_mm=printer.min_wall_mm,
        max_bridge_mm=printer.max_bridge_mm,
        outline=outline,
        period_mm=cylinder.circumference_mm,
    )
    pointed = shapely.difference(outline, tops.region) if cylinder.style == "deboss" else tops.region
    return polygonal(shapely.intersection(pointed, outline)), tops


def cylinder_print(models, cylinder: Cylinder):
    """The cylinder's print: the strip's flat print model (:func:`strip_model`) wrapped round the axis by
    :func:`fabtiles.solid.cylinder.cylinder_print`, with the lamp holder when asked for."""
    from ..solid import cylinder as solid_cylinder

    flat = strip_model(models, cylinder)
    holder = None
    if cylinder.lamp_fitting_mm is not None:
        holder = solid_cylinder.LampHolder(fitting_mm=cylinder.lamp_fitting_mm)
    return solid_cylinder.cylinder_print(
        flat, circumference_mm=cylinder.circumference_mm, outer_radius_mm=cylinder.outer_radius_mm, holder=holder
    )


def strip_model(models, cylinder: Cylinder):
    """The unrolled strip's flat :class:`~fabtiles.solid.print_model.PrintModel`: the tile's print made
    as a flat tile's, from the strip's region (:func:`strip_region`) with the cylinder's heights, its
    report saying what the cylinder is."""
    o = models.options
    region, dips = models.print_region
    outline = models.tile.outline_shape()
    region, dips, tops = strip_region(region, dips, outline, cylinder, o.printer)
    model = models.flat_print(
        region, dips, style=cylinder.style, heights=cylinder.heights, period_mm=cylinder.circumference_mm
    )
    notes = [cylinder.line()] + ([] if tops is None else [_tops_line(tops, o.printer)])
    report = model.report.extended(notes=notes, cylinder=cylinder_stats(cylinder))
    findings = [f for f in report.findings if not _not_on_the_cylinder(f, cylinder, models.tile.stroke)]
    findings += _overhangs(model, outline, cylinder, o.printer)
    report = Report(path=report.path, format=report.format, stats=report.stats, findings=findings)
    return model.with_classes(model.mosaic, report)  # a new model with the report: a made report is never changed


def _not_on_the_cylinder(finding, cylinder: Cylinder, stroke: float) -> bool:
    """Whether ``finding`` of the flat strip is none of the cylinder's: the strip's size against the bed (the
    cylinder stands on it, its diameter checked by :func:`check_cylinder`), or thin walls or small holes all
    of them at the seam, within a stroke of ``x = 0`` or ``x = C``: the two halves of a band or an opening the
    seam cuts, whole on the cylinder (its openings are filled judged whole:
    :func:`~fabtiles.geometry.print_checks.fill_periodic_holes`)."""
    if finding.code == "bed_size":
        return True
    c = cylinder.circumference_mm
    at_seam = [min(x, c - x) <= stroke for x, _ in finding.locations]
    return finding.code in ("thin_wall", "small_hole") and len(at_seam) == finding.count and all(at_seam)


def cylinder_stats(cylinder: Cylinder) -> dict:
    """The cylinder's figures for the reports (mm)."""
    return {
        "style": cylinder.style,
        "outer_diameter_mm": round(2 * cylinder.outer_radius_mm, 4),
        "length_mm": cylinder.length_mm,
        "axle_bore_mm": cylinder.bore_mm,
        "end_rims_mm": cylinder.rim_mm,
        "mirrored": cylinder.mirror,
    }


def _tops_line(tops, printer) -> str:
    """What pointed tops did, in one line for the reports."""
    cut = f" ({tops.clipped} cut back to keep min_wall_mm = {printer.min_wall_mm:g} mm)" if tops.clipped else ""
    return (
        f"pointed tops: {tops.raised} ceiling{'s' if tops.raised != 1 else ''} raised to a peak at "
        f"max_overhang_deg = {printer.max_overhang_deg:g} degrees{cut}"
    )


def _overhangs(model, outline, cylinder: Cylinder, printer) -> list:
    """The ``overhang`` finding of the wall printed standing (:func:`~fabtiles.geometry.wall_overhangs.
    check_wall_overhangs`) on the strip as printed: a shade's holes, a deboss's grooves, a relief's gaps."""
    import shapely

    from ..geometry.wall_overhangs import check_wall_overhangs

    style = cylinder.style
    material = shapely.difference(outline, model.region) if style == "deboss" else model.region
    depth = None if style == "pierced" else model.stack.deboss if style == "deboss" else model.stack.relief
    found = check_wall_overhangs(
        material, printer, style=style, depth_mm=depth, outline=outline, period_mm=cylinder.circumference_mm
    )
    return list(found.findings)
