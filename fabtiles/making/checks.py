"""The fabrication checks of a design, without writing any file.

:func:`check_tile` runs what the exporters would run on a tile: the laser checks
of the laser profile (pierced mode; in the score mode only the outline is cut and
there is nothing to check but the bed), on the region as the laser file would hold
it (an interlaced tile's ``interlace_cut`` gaps cut; with ``fill_small_holes``, the
small holes filled first), and the print checks
of the printer profile with the design's style and heights. Used by
``fabtiles check``, the web app's checks and the preview's findings overlay.

Unlike an export, nothing here raises for the fabrication problems themselves: a
tile larger than the laser bed is a ``bed_size`` finding, a stroke thinner than
the profile allows shows up as thin bridges.

>>> import fabtiles as ft
>>> tile = ft.Tile("square", 40, ft.HexPacking(radius=8, motif=ft.Star.preset("table3-3")), frame=3)
>>> result = check_tile(tile, fill_small_holes=True)
>>> [(where, f.code) for where, f in result.findings()], result.filled_holes > 0
([], True)
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from ..core.errors import FabricationError
from ..core.report import Finding, Report
from ..geometry.machine_geometry import cut_geometry as laser_geometry
from ..machines.profiles import DEFAULT_LASER_PROFILE, DEFAULT_PRINTER_PROFILE, load_profile

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry

    from ..geometry.job_time import JobEstimate
    from ..geometry.material import Filament


@dataclass(frozen=True)
class PiecesOverlay:
    """Where a panel's pieces are cut apart: the seams (mm) and each piece's number where it is drawn."""

    seams_x: tuple[float, ...]
    seams_y: tuple[float, ...]
    numbers: tuple[tuple[int, float, float], ...]

    @classmethod
    def of(cls, split) -> PiecesOverlay:
        """The overlay of a :class:`~fabtiles.geometry.pieces.PanelSplit`: each number in the middle of its piece's
        box."""
        return cls(split.seams_x, split.seams_y, tuple((p.number, *_middle(p.region)) for p in split.pieces))


@dataclass(frozen=True)
class CheckResult:
    """The reports of :func:`check_tile`: ``laser`` and ``print`` (paths are empty)."""

    laser: Report
    print: Report
    filled_holes: int = 0
    """The cutter's holes filled (``fill_small_holes``): narrower than its ``min_hole_mm``, or than a router's bit."""
    job: JobEstimate | None = None
    """The laser job's length and time (:class:`~fabtiles.geometry.job_time.JobEstimate`), when asked for."""
    filament: Filament | None = None
    """The print's filament (:class:`~fabtiles.geometry.material.Filament`), with the job."""
    made: BaseGeometry | None = None
    """A router's or waterjet's part as the tool makes it (holes opened by its radius), None for a laser."""
    cutter: str = "laser"
    """The 2D cutter's kind (the laser profile's ``kind``): ``"laser"``, ``"router"`` or ``"waterjet"``."""
    print_filled_holes: int = 0
    """The print's openings filled (``fill_small_holes``): narrower than the printer profile's ``min_hole_mm``."""
    print_region: object = None
    """The print's material as its files hold it (small openings filled with ``fill_small_holes``)."""
    pieces: tuple[str, ...] = ()
    """A tile larger than the cutter's bed, checked as the pieces it is cut as: what the split made (lines)."""
    split: PiecesOverlay | None = None
    """Those pieces' seams and numbers, for the pictures (:func:`~fabtiles.export.preview_svg.pieces_overlay`)."""

    def findings(self) -> list[tuple[str, Finding]]:
        """Every finding with where it comes from: the cutter's kind (``"laser"``, ``"router"``,
        ``"waterjet"``) or ``"print"``."""
        return [(self.cutter, f) for f in self.laser.findings] + [("print", f) for f in self.print.findings]

    @property
    def ok(self) -> bool:
        """True when neither check found anything."""
        return self.laser.ok and self.print.ok


def check_tile(
    tile,
    *,
    laser_profile=None,
    printer_profile=None,
    laser_mode=None,
    fill_small_holes=False,
    print_style=None,
    heights=None,
    job: bool = False,
    pieces: bool = False,
) -> CheckResult:
    """Run the laser and print checks of ``tile`` (see the module text).

    Parameters
    ----------
    tile : Tile
    laser_profile, printer_profile : str, Path or profile, optional
        Defaults: ``laser-3mm-plywood`` and ``fdm-0.4mm``.
    laser_mode : {"pierced", "score", "engrave", "inlay"}, optional
        Default: the laser profile's. An inlay kit's lattice is checked as a pierced tile.
    fill_small_holes : bool
        Check the laser region with the holes too small for the cutter filled, and the
        print's with the openings too small for the printer filled (as the files would be).
    print_style : {"relief", "pierced", "deboss"}, optional
        Default: the printer profile's.
    heights : dict, optional
        ``base_mm``, ``relief_mm``, ``pierced_mm``, ``deboss_mm`` overrides.
    job : bool
        Also estimate the laser job's length and time (its contours are built, as
        for the laser files): ``CheckResult.job``. None when the tile cannot be cut
        (larger than the bed).
    pieces : bool
        A tile larger than the cutter's bed is checked as the pieces the build cuts it as
        (:mod:`fabtiles.making.pieces`): the split's figures in ``CheckResult.pieces``, each
        piece's findings in the cutter's report, the job summed; a split that cannot be made
        is a ``pieces`` finding. Else such a tile is a ``bed_size`` finding.
    """
    from ..geometry.laser_checks import check_fits_bed

    laser = load_profile(laser_profile or DEFAULT_LASER_PROFILE, kind="laser")
    printer = load_profile(printer_profile or DEFAULT_PRINTER_PROFILE, kind="printer")
    original_mode = laser_mode or laser.mode
    if original_mode == "inlay":  # an inlay kit's lattice is checked (and timed) as a pierced tile
        laser_mode = "pierced"
    region, outline = tile.region(), tile.outline_shape()
    # the laser file's material: with interlace_cut, the under gaps cut and their tabs
    cut_region, _ = laser_geometry(tile, profile=laser, mode=laser_mode, lines=False)
    laser_report = Report(path="", format="laser")
    try:
        check_fits_bed(outline, laser)
    except FabricationError as exc:
        if pieces and (laser_mode or laser.mode) != "inlay" and original_mode != "inlay":
            return _check_pieces(tile, laser, laser_mode, fill_small_holes, printer, print_style, heights, job)
        laser_report.add("bed_size", str(exc))
    filled, made = _check_cut(tile, cut_region, outline, laser, laser_mode, fill_small_holes, laser_report)
    print_report, print_filled, print_region = _check_printed(
        tile, region, outline, printer, print_style, heights, fill_small_holes, pieces
    )
    estimate = (
        _job(tile, cut_region, laser, laser_mode, fill_small_holes)
        if job and "bed_size" not in {f.code for f in laser_report.findings}
        else None
    )
    material = _filament(print_region, outline, printer, print_style, heights) if job else None
    return CheckResult(
        laser_report, print_report, filled, estimate, material, made, laser.kind, print_filled, print_region
    )


def _check_pieces(tile, laser, laser_mode, fill_small_holes, printer, print_style, heights, job) -> CheckResult:
    """:func:`check_tile` of a tile larger than the cutter's bed, as its pieces (see its ``pieces``)."""
    from ..core.errors import FabtilesError
    from ..geometry.cut_plan import CutOptions
    from .pieces import pieces_model

    region, outline = tile.region(), tile.outline_shape()
    print_report, print_filled, print_region = _check_printed(
        tile, region, outline, printer, print_style, heights, fill_small_holes, True
    )
    material = _filament(print_region, outline, printer, print_style, heights) if job else None
    cut_region, lines = laser_geometry(tile, profile=laser, mode=laser_mode)
    options = CutOptions.of(
        profile=replace(laser, strict=False), mode=laser_mode, fill_small_holes=fill_small_holes, fmt="check"
    )
    try:
        model = pieces_model(tile, cut_region, lines, laser, options)
    except FabtilesError as exc:
        report = Report(path="", format="laser")
        report.add("pieces", str(exc))
        return CheckResult(report, print_report, 0, None, material, None, laser.kind, print_filled, print_region)
    report = model.report
    filled = sum(int(p.plan.report.stats.get("filled_holes", 0)) for p in model.pieces)
    from ..geometry.job_time import JobEstimate

    stats = report.stats["job"]
    estimate = JobEstimate(
        dict(stats["cut_mm"]), stats["pierces"], stats["engrave_area_mm2"], stats["travel_mm"], stats["seconds"]
    )
    lines_out = tuple(report.stats.get("notes", ()))
    laser_report = Report(path="", format="laser", findings=list(report.findings))
    overlay = PiecesOverlay.of(model.split)
    return CheckResult(
        laser_report,
        print_report,
        filled,
        estimate if job else None,
        material,
        None,
        laser.kind,
        print_filled,
        print_region,
        lines_out,
        overlay,
    )


def _middle(region) -> tuple[float, float]:
    x0, y0, x1, y1 = region.bounds
    return (x0 + x1) / 2, (y0 + y1) / 2


def _check_cut(tile, cut_region, outline, laser, laser_mode, fill_small_holes: bool, report: Report) -> tuple:
    """The cutter's checks of the laser files' material, into ``report``: ``(holes filled, part as the tool
    makes it or None)``. A pierced part is checked as the tool makes it (holes opened by a router's bit,
    small holes filled when asked); an engraved one for its engraving."""
    from ..geometry.laser_checks import check_cut_pattern, check_engrave, check_laser
    from ..geometry.narrow import fill_small_holes as fill

    filled = 0
    made = None
    if (laser_mode or laser.mode) == "pierced" and not cut_region.is_empty:
        cut = cut_region
        if laser.cutter.opens_holes:  # a router's or waterjet's part: holes opened by the tool's radius
            from ..geometry.tool_opening import check_tool

            cut, _, filled = check_tool(cut, laser, fill_small_holes=fill_small_holes, report=report)
            made = cut
        if fill_small_holes:
            cut, more = fill(cut, laser.min_hole_mm, tolerance_mm=laser.tolerance_mm)
            filled += more
        check_laser(cut, outline, laser, stroke=tile.stroke, report=report, validate=False)
        check_cut_pattern(cut_region, cut, outline, laser, stroke=tile.stroke, report=report)
    elif (laser_mode or laser.mode) == "engrave" and not cut_region.is_empty:
        check_engrave(cut_region, laser, report)
    return filled, made


def _check_printed(
    tile, region, outline, printer, print_style, heights, fill_small_holes: bool, pieces: bool = False
) -> tuple:
    """The printer's checks of the print's region as its files hold it: ``(report, openings filled, region)``;
    with ``pieces``, a tile larger than the printer's bed is split as the build prints it (a line
    saying into how many pieces, or a ``pieces`` finding where it cannot be) instead of ``bed_size``."""
    from ..geometry.print_checks import check_print, check_print_pattern
    from ..geometry.print_checks import print_region as made_print_region

    # the print's region as its files hold it (an interlaced relief unthinned)
    style = print_style or printer.print_style
    designed, _ = made_print_region(
        region, outline, printer, style, flatten=not (getattr(tile, "interlace", False) and style == "relief")
    )
    print_region, print_filled = made_print_region(
        designed, outline, printer, style, fill_small_holes=fill_small_holes, flatten=False
    )
    print_report = check_print(
        print_region,
        outline,
        printer,
        stroke=tile.stroke,
        style=print_style,
        report=Report(path="", format="print"),
        **(heights or {}),
    )
    if print_filled:
        check_print_pattern(designed, print_region, outline, printer, style, stroke=tile.stroke, report=print_report)
    if pieces and "bed_size" in {f.code for f in print_report.findings}:
        _print_in_pieces(tile, designed, outline, printer, print_style, heights, print_report)
    return print_report, print_filled, print_region


def _print_in_pieces(tile, region, outline, printer, print_style, heights, report: Report) -> None:
    """A print larger than the printer's bed, checked as its pieces' split: ``bed_size`` becomes the
    line of the pieces, or a ``pieces`` finding where the split cannot be made."""
    from ..core.errors import FabtilesError
    from .pieces import pattern_period
    from .print_pieces import print_split

    report.findings[:] = [f for f in report.findings if f.code != "bed_size"]
    period, origin = pattern_period(tile)
    try:
        split = print_split(
            region,
            outline,
            profile=printer,
            style=print_style,
            heights=heights,
            period_mm=period,
            origin=origin,
        )
    except FabtilesError as exc:
        report.add("pieces", f"the print cannot be made as pieces: {exc}")
        return
    x0, y0, x1, y1 = outline.bounds
    (nx, ny), (bw, bh) = split.grid, printer.bed_mm
    report.note(
        f"{x1 - x0:g} x {y1 - y0:g} mm panel in {len(split.pieces)} pieces ({nx} x {ny}) for the {bw:g} x {bh:g} mm "
        f"bed of printer profile {printer.name!r}: {len(split.joints)} {split.joint.kind} joints"
    )


def _filament(region, outline, printer, style, heights):
    """The print's filament from its areas and heights (no mesh is built: the file's is within 0.5 %)."""
    from ..geometry.material import filament, stack_volume
    from ..geometry.stack import resolve_stack

    stack = resolve_stack(printer, style, **(heights or {}))
    return filament({"print": stack_volume(region.area, outline.area, stack)}, printer)


def _job(tile, cut_region, laser, mode, fill_small_holes):
    """The laser job of the tile's laser files (their contours, kerf and order).

    ``cut_region`` is the laser files' material, already made by :func:`check_tile`; only
    the score mode needs the score lines as well.
    """
    from ..geometry.cut_plan import CutOptions, plan_cut

    region, lines = cut_region, None
    if (mode or laser.mode) == "score":
        region, lines = laser_geometry(tile, profile=laser, mode=mode)
    plan = plan_cut(
        region,
        tile.outline_shape(),
        CutOptions.of(profile=replace(laser, strict=False), mode=mode, fill_small_holes=fill_small_holes, fmt="check"),
        centrelines=lines,
    )
    return plan.estimate


def check_design(design, tile=None, *, job: bool = False) -> CheckResult:
    """:func:`check_tile` with the profiles, modes and options of a :class:`~fabtiles.designs.design_file.Design`."""
    out = design.output
    tile = tile if tile is not None else design.build_tile()
    if design.surface.cylinder:
        return _check_cylinder(design, tile)
    if design.surface.stamp:
        return _check_stamp(design, tile)
    from ..designs.design_file import profile_of

    return check_tile(
        tile,
        laser_profile=profile_of(design, "laser"),
        printer_profile=profile_of(design, "printer"),
        laser_mode=out.laser_mode,
        fill_small_holes=out.fill_small_holes,
        print_style=out.print_style,
        heights=out.heights(),
        job=job,
        pieces=out.pieces,
    )


def _check_cylinder(design, tile) -> CheckResult:
    """:func:`check_design` of a cylinder: the printer's checks of its unrolled strip as its files hold it
    (mirrored, rims closed, small openings filled), its bad values refused; a cylinder is not cut, so its
    cutter's report is empty."""
    from .cylinder import strip_model
    from .models import BuildOptions, Models

    models = Models(tile, BuildOptions.of_design(design))
    assert models.cylinder is not None  # a cylinder's design
    model = strip_model(models, models.cylinder)
    return CheckResult(Report(path="", format="laser"), model.report, print_region=model.region, cutter="none")


def _check_stamp(design, tile) -> CheckResult:
    """:func:`check_design` of a clay stamp: the printer's checks of its face as its files hold it (mirrored),
    its block and grip refused if they cannot be made; a stamp is not cut, so its cutter's report is empty."""
    from .models import BuildOptions, Models
    from .stamp import stamp_print

    model = stamp_print(Models(tile, BuildOptions.of_design(design)))
    return CheckResult(Report(path="", format="laser"), model.report, print_region=model.region, cutter="none")
