"""The build pipeline: from a validated design to its files, for every front end.

``fabtiles build``, ``batch`` and ``sweep``, the web app's downloads and a cluster
worker all come through here, so an option a design gains reaches every one of them,
and the work limits are checked once, in :func:`prepare_tile` and
:func:`check_format_limits`, for everyone (the STEP limit too).

All or nothing: the tile's geometry is computed first; every file is then written
into a staging folder inside the output folder and moved into place only when all
formats have succeeded. A failure leaves no new or partial file and never clobbers
an existing one. Sheets (``sheet=True`` or ``copies``) write the laser formats as
``<design name>-sheet.<format>``: copies of the tile on the laser profile's bed.

>>> import tempfile
>>> from fabtiles.design import design_from_text
>>> d = design_from_text('''
... [motif]
... preset = "table3-1"
... [tile]
... size = 40
... ''', name="demo")
>>> out = tempfile.mkdtemp()
>>> [Path(r.path).name for r in build_design(d, out, ["svg", "dxf"]).reports]
['demo.svg', 'demo.dxf']
"""

from __future__ import annotations

import os
import shutil
import socket
import tempfile
import traceback
from dataclasses import dataclass, field
from pathlib import Path

from . import _limits
from ._errors import FabtilesError, ParameterError
from ._report import Report

SHEET_SUFFIX = "-sheet"
"""Sheet files are ``<design name>-sheet.<format>``, next to (never over) the tile's files."""

PREVIEW_SUFFIX = ".preview.svg"
"""The tile's picture, ``<design name>.preview.svg`` (``build_design(..., preview=True)``)."""

STAGING_PREFIX = ".fabtiles-build-"
"""Staging folders inside an output folder: ``.fabtiles-build-<host>-<pid>-<random>``."""


@dataclass
class BuildResult:
    """What one build wrote: a report per file (``report.path`` is its final path)."""

    reports: list[Report] = field(default_factory=list)
    skipped: tuple[str, ...] = ()
    """Print formats left out of a sheet."""
    preview: str | None = None
    """The path of the tile's picture, when asked for."""

    @property
    def paths(self) -> list[str]:
        return [p for r in self.reports for p in r.stats.get("kit_files", [r.path])]

    @property
    def findings(self) -> int:
        return sum(len(r.findings) for r in self.reports)


def sheet_formats(formats) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Split ``formats`` into the laser formats a sheet is written in and the skipped print formats.

    >>> sheet_formats(["svg", "stl", "dxf"])
    (('svg', 'dxf'), ('stl',))
    """
    from .export.dispatch import profile_kind

    laser = tuple(f for f in formats if profile_kind(f) == "laser")
    return laser, tuple(f for f in formats if f not in laser)


def prepare_tile(design, *, limits: _limits.Limits = _limits.CLI_LIMITS):
    """The design's tile, after checking its size and segment count against ``limits``.

    No geometry is built before the limits pass.
    """
    from .geometry.tile import TileGeometry

    width, height = design.tile_spec.size
    _limits.check_size(width, height, limits)
    tile = design.build_tile(tile_cls=TileGeometry)
    _limits.check_tile(tile.pattern, tile.width_mm, tile.height_mm, limits)
    return tile


def check_format_limits(tile, formats, limits: _limits.Limits) -> None:
    """The formats' own, lower limits (STEP is slow on huge solids)."""
    for fmt in formats:
        _limits.check_export(tile, fmt, limits)


def layout_tile_sheet(tile, design, *, copies=None, gap_mm=None, limits: _limits.Limits = _limits.CLI_LIMITS):
    """Copies of ``tile`` on the bed of the design's laser profile.

    Parameters
    ----------
    tile : TileGeometry
        The design's tile.
    design : Design
        Gives the laser profile (its bed size and kerf).
    copies : int, optional
        Exactly this many copies; default: as many as fit on the bed.
    gap_mm : float, optional
        Space between tiles; default: the kerf + 2 mm.
    limits : Limits
        The sheet's segments (all copies) are checked against them.

    Returns
    -------
    Sheet
        See :func:`~fabtiles.geometry.sheet.layout_sheet`.

    Raises
    ------
    FabricationError
        The copies (or even one tile) do not fit on the bed.
    LimitError
        The sheet would hold more segments than ``limits`` allow.
    """
    from .export.dispatch import DEFAULT_LASER_PROFILE, laser_geometry
    from .geometry.sheet import layout_sheet

    profile = design.output.laser_profile or DEFAULT_LASER_PROFILE
    options = dict(copies=1 if copies is None else copies, gap_mm=gap_mm, fill=copies is None)
    outline = tile.outline_shape()
    # Place the outlines alone first (cheap), to refuse an oversized job before any work.
    placed = layout_sheet([(outline, outline)], profile, **options)
    _limits.check_segments(len(tile.segments()) * len(placed.offsets), limits,
                           what=f"the sheet of {len(placed.offsets)} tiles")
    # the tile as its own laser file holds it (an interlaced tile's score lines broken, its cuts made)
    region, centrelines = laser_geometry(tile, profile=profile, mode=design.output.laser_mode)
    return layout_sheet([(region, outline)], profile, centrelines=[centrelines], **options)


def inlay_kit_of(tile, design):
    """The inlay kit of a tile with the design's laser profile and fit (the pictures' kit; see :mod:`fabtiles.export.kit`)."""
    from ._profiles import load_profile
    from .export.dispatch import DEFAULT_LASER_PROFILE, laser_geometry
    from .geometry.inlay import inlay_kit

    out = design.output
    profile = load_profile(out.laser_profile or DEFAULT_LASER_PROFILE, kind="laser")
    region, _ = laser_geometry(tile, profile=profile, mode="pierced", lines=False)
    fit = profile.inlay_fit_mm if out.inlay_fit_mm is None else out.inlay_fit_mm
    return inlay_kit(region, tile.outline_shape(), fit_mm=fit, min_piece_mm=profile.min_piece_or_default_mm,
                     kerf_mm=max(profile.kerf_xy_mm), tolerance_mm=profile.tolerance_mm)


def made_region(tile, design):
    """The tile's part as a router's bit or a waterjet's jet makes it (the design's laser profile), else None.

    What the pictures draw for such a profile (``build --preview``, ``check -o``): every
    hole opened by the tool's radius, see :mod:`fabtiles.geometry.tool_opening`. None
    for a laser profile (the picture draws the tile's own region).
    """
    from ._profiles import load_profile
    from .export.dispatch import DEFAULT_LASER_PROFILE, laser_geometry
    from .geometry.tool_opening import open_region

    profile = load_profile(design.output.laser_profile or DEFAULT_LASER_PROFILE, kind="laser")
    if not profile.cutter.opens_holes:
        return None
    profile.cutter.check_profile(profile)
    region, _ = laser_geometry(tile, profile=profile, mode="pierced", lines=False)
    return open_region(region, radius_mm=profile.tool_radius_mm, tolerance_mm=profile.tolerance_mm).region


def _inlay(design) -> bool:
    """Whether the design's laser files are an inlay kit (its mode, or its laser profile's)."""
    from ._profiles import load_profile
    from .export.dispatch import DEFAULT_LASER_PROFILE

    mode = design.output.laser_mode
    return (mode or load_profile(design.output.laser_profile or DEFAULT_LASER_PROFILE, kind="laser").mode) == "inlay"


def export_format(tile, fmt: str, path: Path, design) -> Report:
    """Write one format of the tile with the design's profiles and options; return its report."""
    from .export import dispatch

    out = design.output
    if dispatch.profile_kind(fmt) == "laser":
        kit = dict(inlay_fit_mm=out.inlay_fit_mm, inlay_base=out.inlay_base) if _inlay(design) else {}
        return dispatch.export_tile(tile, path, profile=out.laser_profile, mode=out.laser_mode,
                                    fill_small_holes=out.fill_small_holes, **kit)
    extra = {}
    if fmt == "3mf":  # the inlay is a 3MF part; the layout picks the slicers the parts are for
        extra = {"inlay": True} if out.inlay else {}
        extra["layout"] = out.threemf_layout
    return dispatch.export_tile(tile, path, profile=out.printer_profile, style=out.print_style, **out.heights(),
                                fill_small_holes=out.fill_small_holes, **extra)


def export_sheet(layout, tile, path: Path, design) -> Report:
    """Write one laser format of a sheet; return its report."""
    from .export.dispatch import export_geometry

    out = design.output
    return export_geometry(path, region=layout.region, outline=layout.outline, centrelines=layout.centrelines,
                           stroke=tile.stroke, profile=out.laser_profile, mode=out.laser_mode,
                           fill_small_holes=out.fill_small_holes)


def build_design(design, outdir, formats=None, *, sheet: bool = False, copies: int | None = None,
                 gap_mm: float | None = None, file_name: str | None = None, preview: bool = False,
                 limits: _limits.Limits = _limits.CLI_LIMITS) -> BuildResult:
    """Write ``OUTDIR/<design name>.<format>`` for each format, all or nothing.

    Parameters
    ----------
    design : Design
        The validated design.
    outdir : str or Path
        Output folder (created when missing; removed again if a failed build created it).
    formats : iterable of str, optional
        Default: the design's ``[output] formats``.
    sheet : bool
        Write the laser formats as a sheet, ``OUTDIR/<design name>-sheet.<format>``:
        copies of the tile on the laser profile's bed (as many as fit unless ``copies``
        is given). Print formats are skipped (see :func:`sheet_formats`).
    copies : int, optional
        Lay exactly this many copies on the sheet (implies ``sheet``).
    gap_mm : float, optional
        Space between tiles on the sheet (> kerf; implies ``sheet``); default: the kerf + 2 mm.
    file_name : str, optional
        The name of the one file written (one format only), instead of
        ``<design name>[-sheet].<format>``.
    preview : bool
        Also write ``<design name>.preview.svg``, the tile's picture (the material
        filled, see :func:`~fabtiles.export.preview_svg.tile_svg`), staged with the rest.
    limits : Limits
        Work limits (:data:`fabtiles._limits.CLI_LIMITS` for the command line).

    Returns
    -------
    BuildResult
        One report per file written, with the fabrication checks' findings.

    Raises
    ------
    FabtilesError
        On any failure, with nothing written: among others, a sheet asked for with
        only print formats, copies that do not fit on the bed, a job over the limits.
    """
    formats = tuple(dict.fromkeys(formats or design.output.formats))
    sheet = sheet or copies is not None or gap_mm is not None
    skipped: tuple[str, ...] = ()
    if sheet:
        formats, skipped = sheet_formats(formats)
        if not formats:
            raise FabtilesError(
                f"a sheet is laid out for the laser formats (dxf, svg) only, but the formats asked "
                f"for are: {', '.join(skipped)}; add --format dxf or --format svg")
    if file_name is not None and len(formats) != 1:
        raise ParameterError(f"file_name {file_name!r} names one file, but {len(formats)} formats are asked "
                             f"for: {', '.join(formats)}")
    tile = prepare_tile(design, limits=limits)
    check_format_limits(tile, formats, limits)
    # Compute (and fail) before anything is written; a sheet that cannot fit fails before the tile.
    layout = layout_tile_sheet(tile, design, copies=copies, gap_mm=gap_mm, limits=limits) if sheet else None
    tile.region()
    with StagingFolder(outdir) as (staging, final):
        staged = []
        for fmt in formats:
            if layout is None:
                path = staging / (file_name or f"{design.name}.{fmt}")
                report = export_format(tile, fmt, path, design)
            else:
                path = staging / (file_name or f"{design.name}{SHEET_SUFFIX}.{fmt}")
                report = export_sheet(layout, tile, path, design)
            staged.append((path, report))
        picture = None
        if preview:
            from ._io import atomic_write
            from .export.preview_svg import tile_svg

            picture = atomic_write(staging / f"{design.name}{PREVIEW_SUFFIX}",
                                   tile_svg(tile, title=design.name, region=made_region(tile, design)))
        for path, report in staged:
            if "kit_files" in report.stats:  # an inlay kit: the lattice and the pieces
                report.stats["kit_files"] = [str(final(Path(p))) for p in report.stats["kit_files"]]
                report.path = report.stats["kit_files"][0]
            else:
                report.path = str(final(path))
        picture = str(final(picture)) if picture is not None else None
    return BuildResult([report for _, report in staged], skipped, picture)


class StagingFolder:
    """A staging folder inside ``outdir``: ``with StagingFolder(out) as (staging, move): ...``.

    ``move(path)`` puts a staged file into ``outdir`` (an atomic rename) and returns
    its final path. On leaving, the staging folder is removed, and so is ``outdir``
    when it was created here and stayed empty (a failed build leaves no folder).
    The staging folder's name carries the host and process id, so that
    :func:`remove_stale_staging` can tell a dead process's leftovers from a live one's.
    """

    def __init__(self, outdir):
        self.outdir = Path(outdir)

    def __enter__(self):
        outdir = self.outdir
        if outdir.exists() and not outdir.is_dir():
            raise FabtilesError(f"output folder {str(outdir)!r} exists and is not a folder")
        self.existed = outdir.exists()
        try:
            outdir.mkdir(parents=True, exist_ok=True)
            prefix = f"{STAGING_PREFIX}{socket.gethostname()}-{os.getpid()}-"
            self.staging = Path(tempfile.mkdtemp(prefix=prefix, dir=outdir))
        except OSError as exc:
            raise FabtilesError(f"cannot create output folder {str(outdir)!r}: {exc.strerror or exc}") from None
        return self.staging, self._move

    def _move(self, path: Path) -> Path:
        target = self.outdir / path.name
        os.replace(path, target)
        return target

    def __exit__(self, kind, exc, tb):
        shutil.rmtree(self.staging, ignore_errors=True)
        if not self.existed and self.outdir.is_dir() and not any(self.outdir.iterdir()):
            self.outdir.rmdir()  # a failed build leaves no folder it created either
        if isinstance(exc, OSError):
            raise FabtilesError(f"cannot write into {str(self.outdir)!r}: {exc.strerror or exc}") from None
        return False


def remove_stale_staging(outdir) -> int:
    """Remove staging folders in ``outdir`` left by dead processes of this host; return how many.

    A process killed outright (SIGKILL, a lost cluster worker) cannot clean up: its
    staging folder stays, hidden, while the final files are never partial.
    """
    outdir = Path(outdir)
    host = socket.gethostname()
    removed = 0
    if not outdir.is_dir():
        return 0
    for path in outdir.glob(f"{STAGING_PREFIX}*"):
        parts = path.name[len(STAGING_PREFIX):].rsplit("-", 2)  # host (may hold "-"), pid, random
        if len(parts) != 3 or parts[0] != host or not parts[1].isdigit() or _alive(int(parts[1])):
            continue
        shutil.rmtree(path, ignore_errors=True)
        removed += 1
    return removed


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


VIEW_SEGMENTS = 8_000
"""Most centre-line segments the 3D view shows whole: twice the 150 mm default tile's 4,032
(30,544 triangles, 530 KB of GLB, 0.23 s). A bigger tile's view is its centre window holding
about this many segments, a lighter preview that says so: a 300 mm square shown whole was
290,788 triangles, 5.1 MB and 2.9 s (benchmarks/bench_web.py), more than a view should carry."""


def print_view(design, *, limits: _limits.Limits, max_segments: int = VIEW_SEGMENTS) -> tuple[bytes, Report]:
    """The design's print as GLB, one mesh per part (the web app's 3D view), and its report.

    The tile passes the same work limits as an STL or 3MF export, before any geometry is
    built, and the parts are the 3MF's, after the same checks. A tile of more than
    ``max_segments`` segments shows its centre: ``report.stats["window_mm"]`` is then
    that window's ``[x0, y0, x1, y1]`` in file coordinates, and ``stats["view"]`` says so.
    """
    import numpy as np
    import shapely

    from .export.dispatch import DEFAULT_PRINTER_PROFILE, print_geometry
    from .export.glb import print_glb

    tile = prepare_tile(design, limits=limits)
    check_format_limits(tile, ("3mf",), limits)
    out = design.output
    profile = out.printer_profile or DEFAULT_PRINTER_PROFILE
    region, dips = print_geometry(tile, profile=profile, style=out.print_style)
    outline = tile.outline_shape()
    count = _limits.estimate_segments(tile.pattern, tile.width_mm, tile.height_mm)
    window = None
    if count > max_segments:
        x0, y0, x1, y1 = outline.bounds
        half = (np.sqrt(max_segments / count) / 2) * np.array([x1 - x0, y1 - y0])
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        window = [float(cx - half[0]), float(cy - half[1]), float(cx + half[0]), float(cy + half[1])]
        box = shapely.box(*window)
        region, outline = region.intersection(box), outline.intersection(box)
        dips = dips.intersection(box) if dips is not None else None
    data, report = print_glb(region=region, outline=outline, profile=profile, style=out.print_style,
                             stroke=tile.stroke, inlay=bool(out.inlay), dips=dips,
                             fill_small_holes=out.fill_small_holes, **out.heights())
    size = f"{tile.width_mm:g} x {tile.height_mm:g} mm"
    if window is not None:
        report.stats["window_mm"] = window
        report.stats["view"] = (f"the centre {window[2] - window[0]:.0f} x {window[3] - window[1]:.0f} mm of the "
                                f"{size} tile, a lighter preview (the files hold all of it)")
    else:
        report.stats["view"] = f"the whole {size} tile"
    return data, report


def build_bytes(design, fmt: str, *, limits: _limits.Limits, file_name: str | None = None) -> tuple[bytes, Report]:
    """Build one format of ``design`` and return the file's bytes and report (the web app's downloads).

    An inlay kit's two files come as one zip archive (``report.stats["kit_files"]`` names them).
    """
    with tempfile.TemporaryDirectory(prefix="fabtiles-") as tmp:
        result = build_design(design, tmp, (fmt,), file_name=file_name, limits=limits)
        report = result.reports[0]
        if "kit_files" in report.stats:
            import io
            import zipfile

            buf = io.BytesIO()
            with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
                for p in report.stats["kit_files"]:
                    zf.writestr(zipfile.ZipInfo(Path(p).name, date_time=(1980, 1, 1, 0, 0, 0)),
                                Path(p).read_bytes(), compress_type=zipfile.ZIP_DEFLATED)
            data = buf.getvalue()
        else:
            data = Path(report.path).read_bytes()
    return data, report


@dataclass
class Outcome:
    """The result of one job of a batch or sweep (picklable: it crosses processes and machines)."""

    key: str
    ok: bool
    message: str
    paths: list[str] = field(default_factory=list)
    findings: list[str] = field(default_factory=list)
    """One line per fabrication finding, ``"<file name>: <code>: <message>"``."""
    preview: str | None = None
    """The tile's picture, when asked for."""
    figures: dict = field(default_factory=dict)
    """The laser job of its first laser file (``Report.stats["job"]``), its sheet (``sheet_m2``,
    ``sheet_cost``) and the filament of its first print file (``filament_mass_g``, ...): empty without them."""


def outcome_of(key: str, result: BuildResult) -> Outcome:
    """An :class:`Outcome` for a successful build."""
    n = len(result.reports)
    message = f"{n} file{'s' if n != 1 else ''}"
    if result.findings:
        message += f", {result.findings} fabrication warning{'s' if result.findings != 1 else ''}"
    lines = [f"{Path(r.path).name}: {f.code}: {f.message}" for r in result.reports for f in r.findings]
    return Outcome(key, True, message, result.paths, lines, result.preview, _figures(result.reports))


def _figures(reports) -> dict:
    """The laser job, sheet and filament of a build's first laser and first print file, flat (sweep columns)."""
    def first(key):
        return next((r.stats[key] for r in reports if key in r.stats), {})

    job, sheet, material = first("job"), first("sheet"), first("material")
    figures = dict(job)
    if sheet:
        figures.update(sheet_m2=sheet["sheet_m2"], sheet_cost=sheet["cost"])
    if material:
        figures.update(filament_mass_g=material["mass_g"], filament_length_m=material["length_m"],
                       filament_cost=material["cost"])
    return figures


def run_job(key: str, make_design, outdir, formats=None, *, preview: bool = False) -> Outcome:
    """Build one design for a batch or sweep, never raising: failures become an :class:`Outcome`.

    ``make_design`` is a callable returning the validated design (so that loading
    and validation errors are this job's failure too).
    """
    try:
        result = build_design(make_design(), outdir, formats or None, preview=preview)
        return outcome_of(key, result)
    except FabtilesError as exc:
        return Outcome(key, False, str(exc))
    except Exception:  # a bug: report it with its traceback, keep the batch going
        return Outcome(key, False, "internal error (a bug, please report):\n" + traceback.format_exc())
