"""The build pipeline: from a validated design to its files, for every front end.

``fabtiles build``, ``batch`` and ``sweep``, the web app's downloads, a cluster
worker and ``Tile.export`` all come through here, so an option a design gains
reaches every one of them, and the work limits are checked once, in
:func:`prepare_tile` and :func:`check_format_limits`, for everyone.

One build, one model per machine: the tile's cut plan and print model
(:class:`~fabtiles.making.models.Models`) are made once, and every file is the
format table's pure function of one of them (:mod:`fabtiles.export.formats`).
Each format is made or refused on its own: a model or writer that fails (a
strict check, a solid the STEP's own check refuses) refuses its formats, named
with the reason in :attr:`BuildResult.refused`, and the others are written all
the same. The design's own errors (bad values, the work limits, checked before
any geometry) and a build whose every format is refused raise, with nothing
written. Only this module writes files: into a staging folder inside the output
folder, moved into place when every file that could be made has been made
(:mod:`.staging`). Sheets
(``sheet=True`` or ``copies``) write the cutter formats as
``<design name>-sheet.<format>``: copies of the tile on the cutter profile's bed.

>>> import tempfile
>>> from fabtiles.designs.design_file import design_from_text
>>> d = design_from_text('''
... [motif]
... preset = "table3-1"
... [tile]
... size = 40
... ''', name="demo")
>>> out = tempfile.mkdtemp()
>>> [Path(p).name for p in build_design(d, out, ["svg", "dxf"]).paths]
['demo.svg', 'demo.dxf']
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path

from ..core.errors import FabricationError, FabtilesError, ParameterError
from ..core.report import Report
from ..core.schema import build_options, option_keys
from ..machines import limits as _limits
from ..machines.profiles import DEFAULT_CUTTER_PROFILE, DEFAULT_PRINTER_PROFILE, load_profile
from .models import BuildModels, BuildOptions, Models
from .staging import StagingFolder

SHEET_SUFFIX = "-sheet"
"""Sheet files are ``<design name>-sheet.<format>``, next to (never over) the tile's files."""

PREVIEW_SUFFIX = ".preview.svg"
"""The tile's picture, ``<design name>.preview.svg`` (``build_design(..., preview=True)``)."""


@dataclass(frozen=True)
class Refused:
    """A format a build did not write, and why: its model's or writer's error, as its message says it."""

    format: str
    path: str
    """The file it would have written (a kit's first file)."""
    reason: str
    error: FabtilesError | None = field(default=None, compare=False, repr=False)
    """The error itself (its type and ``param``), when the build raised it in this process."""

    def line(self) -> str:
        """``"refused out/t.step (step): <reason>"``: one line for people."""
        return f"refused {self.path} ({self.format}): {self.reason}"


@dataclass
class BuildResult:
    """What one build wrote: a report per format (``report.path`` its file's final path),
    every path, and one report per model (its findings, once)."""

    reports: list[Report] = field(default_factory=list)
    skipped: tuple[str, ...] = ()
    """Print formats left out of a sheet."""
    preview: str | None = None
    """The path of the tile's picture, when asked for."""
    paths: list[str] = field(default_factory=list)
    """Every file written, in order (an inlay kit's two per format)."""
    models: list[tuple[str, Report]] = field(default_factory=list)
    """``(label, report)`` of each model the build made (``"laser laser-3mm-plywood"``,
    ``"printer fdm-0.4mm"``): each finding is in exactly one of them."""
    replaced: list[str] = field(default_factory=list)
    """The paths of :attr:`paths` that replaced a file already there (the rest are new)."""
    earlier: list[str] = field(default_factory=list)
    """Files of the same name in formats this build did not write (``table3-3.stl`` beside a
    build of ``table3-3.dxf``, or a refused format's): left from an earlier build, not rewritten."""
    refused: list[Refused] = field(default_factory=list)
    """The formats asked for that were refused, each with its reason; their files were not written."""
    assembly: list[str] = field(default_factory=list)
    """A panel cut as pieces: the paths of its assembly drawing and manifest (also in :attr:`paths`)."""

    @property
    def findings(self) -> int:
        """The build's fabrication findings, each counted once whatever the formats."""
        return sum(len(r.findings) for _, r in self.models)


def sheet_formats(formats) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Split ``formats`` into the cutter formats a sheet is written in and the skipped print formats.

    >>> sheet_formats(["svg", "stl", "dxf"])
    (('svg', 'dxf'), ('stl',))
    """
    from ..export.formats import FORMATS

    cut = tuple(f for f in formats if FORMATS[f].family == "cut")
    return cut, tuple(f for f in formats if f not in cut)


def prepare_tile(design, *, limits: _limits.Limits = _limits.CLI_LIMITS):
    """The design's tile, after checking its size and segment count against ``limits``.

    No geometry is built before the limits pass.
    """
    from ..geometry.tile import TileGeometry

    width, height = design.tile_spec.size
    _limits.check_size(width, height, limits)
    tile = design.build_tile(tile_cls=TileGeometry)
    _limits.check_tile(tile.pattern, tile.width_mm, tile.height_mm, limits)
    return tile


def check_format_limits(tile, formats, limits: _limits.Limits) -> None:
    """The formats' own, lower limits (the table's ``limit``: STEP is slow on huge solids)."""
    from ..export.formats import FORMATS

    for fmt in formats:
        f = FORMATS[fmt]
        if f.limit is not None:
            _limits.check_export(tile, f.label, f.limit, limits)


def layout_tile_sheet(
    tile, options: BuildOptions, *, copies=None, gap_mm=None, limits: _limits.Limits = _limits.CLI_LIMITS
):
    """Copies of ``tile`` on the bed of the cutter profile of ``options``.

    ``copies``: exactly this many (default: as many as fit on the bed); ``gap_mm``:
    space between tiles (default: the kerf + 2 mm, a router's bit + 2 mm). The
    sheet's segments (all copies) are checked against ``limits``. Raises
    :class:`~fabtiles.FabricationError` when the copies (or one tile) do not fit on
    the bed, :class:`~fabtiles.LimitError` over the limits.
    """
    from ..geometry.machine_geometry import cut_geometry
    from ..geometry.sheet import layout_sheet

    profile = options.cutter
    fill = dict(copies=1 if copies is None else copies, gap_mm=gap_mm, fill=copies is None)
    outline = tile.outline_shape()
    # Place the outlines alone first (cheap), to refuse an oversized job before any work.
    placed = layout_sheet([(outline, outline)], profile, **fill)
    _limits.check_segments(
        len(tile.segments()) * len(placed.offsets), limits, what=f"the sheet of {len(placed.offsets)} tiles"
    )
    # the tile as its own cutter file holds it (an interlaced tile's score lines broken, its cuts made)
    region, centrelines = cut_geometry(tile, profile=profile, mode=options.laser_mode)
    return layout_sheet([(region, outline)], profile, centrelines=[centrelines], **fill)


def _file_report(model_report: Report, path, fmt: str, figures: dict) -> Report:
    """A file's report: its model's statistics and findings, plus what the format adds."""
    return Report(
        path=str(path), format=fmt, stats={**model_report.stats, **figures}, findings=list(model_report.findings)
    )


def _planned_files(model, f, name: str, *, options: BuildOptions):
    """``([(file name, model), ...], file options)``: the files format ``f`` writes of ``model``
    (several: a kit's lattice and pieces, a nest's sheets, a mosaic's STLs), and what the files
    need beyond their model (the build's 3MF layout and DXF version)."""
    from ..export.formats import FileOptions

    files = [(f"{name}{suffix}{f.suffix}", m) for suffix, m in f.files(model)]
    return files, FileOptions(name=Path(name).stem, layout=options.threemf_layout, dxf_version=options.dxf_version)


def _model_of(models: BuildModels, family: str, failed: dict):
    """``models.model(family)``, its error kept in ``failed`` so that its other formats are refused alike."""
    if family in failed:
        raise failed[family]
    try:
        return models.model(family)
    except FabtilesError as exc:
        failed[family] = exc
        raise


def _made(models: BuildModels, f, name: str, file_name: str | None, failed: dict):
    """``(report, [(file name, bytes), ...])`` of format ``f``: its model made (once) and its files written."""
    model = _model_of(models, f.family, failed)
    files, options = _planned_files(model, f, name, options=models.options)
    if file_name is not None:  # one format: its file (or a kit's two) named after file_name
        stem = Path(file_name).stem
        files = [(file_name, files[0][1])] if len(files) == 1 else [(f"{stem}{n[len(name) :]}", m) for n, m in files]
        options = replace(options, name=stem)
    contents = [(fname, f.write(m, options)) for fname, m in files]
    # a print's figures are its model's (a mosaic's STLs: every colour's), a kit's or a print in pieces' its
    # first file's
    measured = files[0][1] if f.family == "cut" or hasattr(model, "pieces") else model
    report = _file_report(model.report, files[0][0], f.name, f.figures(measured, options))
    if len(files) > 1:
        report.stats["files"] = [n for n, _ in files]
    return report, contents


def refusal_error(refused: list[Refused]) -> FabtilesError:
    """The error of a build whose every format was refused: the one error when they share it, else all named."""
    if len({r.reason for r in refused}) == 1 and refused[0].error is not None:
        return refused[0].error
    return FabricationError("formats refused: " + "; ".join(f"{r.format}: {r.reason}" for r in refused))


def write_files(
    models: BuildModels, formats, outdir, name: str, *, file_name: str | None = None, preview_svg: str | None = None
) -> BuildResult:
    """Make the files of ``formats`` from ``models``, each format on its own, and move them into ``outdir``.

    A format whose model or writer raises a :class:`~fabtiles.FabtilesError` is refused
    (:attr:`BuildResult.refused`: no file of it is written, none is changed); the
    others are staged and moved into place together. When every format is refused,
    the error is raised (the one error, when they share it) and nothing is written.
    ``name`` is the files' stem (``<name>.<format>``); ``file_name`` names the one file
    of a one-format build instead. ``preview_svg``: a picture's text, written as
    ``<name>.preview.svg`` with the rest.
    """
    from ..core.files import atomic_write
    from ..export.formats import FORMATS

    reports: list = []
    contents: list = []
    refused: list[Refused] = []
    failed: dict = {}
    for fmt in formats:
        f = FORMATS[fmt]
        try:
            report, made = _made(models, f, name, file_name, failed)
        except FabtilesError as exc:
            path = file_name if file_name is not None else f"{name}{f.suffix}"
            refused.append(Refused(fmt, str(Path(outdir) / path), str(exc), exc))
            continue
        contents.extend(made)
        reports.append(report)
    if not reports:  # every format refused: the build fails, with nothing written
        raise refusal_error(refused)
    stem = Path(file_name).stem if file_name is not None else name
    assembly = _assembly_files(models, contents, stem, failed)
    contents.extend(assembly)
    with StagingFolder(outdir) as (staging, final):
        staged = [atomic_write(staging / fname, data) for fname, data in contents]
        picture = atomic_write(staging / f"{name}{PREVIEW_SUFFIX}", preview_svg) if preview_svg is not None else None
        # asked just before the moves: which files of this build are already there
        replaced = [str(Path(outdir) / p.name) for p in staged if (Path(outdir) / p.name).exists()]
        paths = [str(final(Path(p))) for p in staged]
        picture = str(final(picture)) if picture is not None else None
    folder = Path(outdir)
    for report in reports:
        report.path = str(folder / report.path)
        if "files" in report.stats:
            report.stats["files"] = [str(folder / n) for n in report.stats["files"]]
    made = [str(folder / n) for n, _ in assembly]
    return BuildResult(reports, (), picture, paths, models.reports(reports), replaced, refused=refused, assembly=made)


def _assembly_files(models: BuildModels, contents: list, stem: str, failed: dict) -> list:
    """A panel made as pieces: ``[(name, bytes), ...]`` of its assembly drawing and manifest, made once
    per build from the cut model (``<stem>-assembly``) and the print model (``<stem>-assembly``
    too, or ``<stem>-print-assembly`` beside a cutter's: each machine's bed splits the panel its
    own way), naming each piece's files among ``contents``; else nothing."""
    from ..export.assembly import assembly_svg, manifest
    from ..export.formats import FORMATS
    from .pieces import ASSEMBLY_SUFFIX, PanelPieces, piece_suffix
    from .print_pieces import PrintPieces

    made = getattr(models, "made", None)
    printed = tuple(f.suffix for f in FORMATS.values() if f.family == "print")
    out: list = []
    for family, kind in (("cut", PanelPieces), ("print", PrintPieces)):
        if family in failed or made is None or not made(family):
            continue
        model = models.model(family)
        if not isinstance(model, kind):
            continue
        n = len(model.pieces)
        names = [f for f, _ in contents if f.endswith(printed) == (family == "print")]
        files = {
            p.number: [f for f in names if f.startswith(f"{stem}{piece_suffix(p.number, n)}")] for p in model.pieces
        }
        base = f"{stem}{'-print' if out else ''}{ASSEMBLY_SUFFIX}"
        out += [(f"{base}.svg", assembly_svg(model, title=stem)), (f"{base}.json", manifest(model, files, name=stem))]
    return out


def earlier_files(outdir, name: str, written) -> list[str]:
    """Files in ``outdir`` named as a build of ``name`` names its files, in formats (or kit files) not in ``written``.

    A build writes only the formats asked for; a file of another format with the same
    name stays from an earlier build, perhaps of other values (``table3-3.stl`` of a
    150 mm tile beside a ``table3-3.dxf`` just built at 200 mm).
    """
    from ..export.formats import FORMATS, design_formats
    from ..export.kit import KIT_FILES
    from .nesting import NEST_SUFFIX
    from .pieces import ASSEMBLY_SUFFIX, PIECE_SUFFIX

    folder = Path(outdir)
    written = {Path(p).name for p in written}
    suffixes = [FORMATS[fmt].suffix for fmt in design_formats()]
    names = [f"{name}{kit}{suffix}" for suffix in suffixes for kit in ("", *(s for s, _ in KIT_FILES))]
    # a coloured kit's pieces files, one per wood; a panel's pieces and its assembly
    names += sorted(p.name for suffix in suffixes for p in folder.glob(f"{name}-pieces-*{suffix}"))
    names += sorted({p.name for suffix in suffixes for p in folder.glob(f"{name}{PIECE_SUFFIX}*{suffix}")})
    names += sorted({p.name for suffix in suffixes for p in folder.glob(f"{name}{NEST_SUFFIX}*{suffix}")})
    names += [f"{name}{ASSEMBLY_SUFFIX}{suffix}" for suffix in (".svg", ".json")]
    return [str(folder / n) for n in names if n not in written and (folder / n).is_file()]


def build_design(
    design,
    outdir,
    formats=None,
    *,
    sheet: bool = False,
    copies: int | None = None,
    gap_mm: float | None = None,
    file_name: str | None = None,
    preview: bool = False,
    limits: _limits.Limits = _limits.CLI_LIMITS,
) -> BuildResult:
    """Write ``OUTDIR/<design name>.<format>`` for each format, each written or refused on its own.

    Parameters
    ----------
    design : Design
        The validated design.
    outdir : str or Path
        Output folder (created when missing; removed again if a failed build created it).
    formats : iterable of str, optional
        Default: the design's ``[output] formats``.
    sheet : bool
        Write the cutter formats as a sheet, ``OUTDIR/<design name>-sheet.<format>``:
        copies of the tile on the cutter profile's bed (as many as fit unless ``copies``
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
        Work limits (:data:`fabtiles.machines.limits.CLI_LIMITS` for the command line).

    Returns
    -------
    BuildResult
        One report per format written, every path, each model's findings once, and
        the formats refused with their reasons (:attr:`BuildResult.refused`): a
        model or writer that fails refuses its own formats only (see :func:`write_files`).

    Raises
    ------
    FabtilesError
        With nothing written: the design's own errors, found before any geometry (a
        sheet asked for with only print formats, copies that do not fit on the bed, a
        job over the limits, a format the cutter does not take), or every format refused.
    """
    formats = tuple(dict.fromkeys(formats or design.output.formats))
    sheet = sheet or copies is not None or gap_mm is not None
    if sheet and (design.surface.cylinder or design.surface.stamp):
        how = "standing on an end" if design.surface.cylinder else "pattern up"
        raise ParameterError(
            f'[surface] shape = "{design.surface.shape}" is printed whole, {how}: it is not laid on a cutter\'s '
            "sheet; drop --sheet, --copies and --gap",
            param="sheet",
        )
    skipped: tuple[str, ...] = ()
    if sheet:
        formats, skipped = sheet_formats(formats)
        if not formats:
            raise FabtilesError(
                f"a sheet is laid out for the laser formats (dxf, svg) only, but the formats asked "
                f"for are: {', '.join(skipped)}; add --format dxf or --format svg"
            )
    if file_name is not None and len(formats) != 1:
        raise ParameterError(
            f"file_name {file_name!r} names one file, but {len(formats)} formats are asked for: {', '.join(formats)}"
        )
    if design.surface.cylinder or design.surface.stamp:
        from .cylinder import check_formats

        check_formats(formats, design.surface.shape)
    tile = prepare_tile(design, limits=limits)
    check_format_limits(tile, formats, limits)
    options = BuildOptions.of_design(design)
    _check_cutter_formats(options, formats)
    if options.surface is not None:  # a cylinder's values refused before any geometry
        from .cylinder import cylinder_of

        cylinder_of(options.surface, options, tile.width_mm)
    if options.stamp is not None:  # a stamp's values refused before any geometry
        from .stamp import stamp_settings

        stamp_settings(options.stamp, options)
    # Compute (and fail) before anything is written; a sheet that cannot fit fails before the tile.
    layout = layout_tile_sheet(tile, options, copies=copies, gap_mm=gap_mm, limits=limits) if sheet else None
    models = Models(tile, options, sheet=layout)
    picture = None
    if preview:
        from .views import tile_picture

        picture = tile_picture(tile, design, models=models)
    name = f"{design.name}{SHEET_SUFFIX}" if layout is not None else design.name
    result = write_files(models, formats, outdir, name, file_name=file_name, preview_svg=picture)
    result.skipped = skipped
    if file_name is None:  # -o FILE writes one file by its own name: no set of files to compare
        result.earlier = earlier_files(outdir, name, result.paths)
    return result


def _check_cutter_formats(options: BuildOptions, formats) -> None:
    """The cutter's kind allows each cutter format (a LightBurn project is for lasers)."""
    from ..export.formats import FORMATS
    from ..machines.cutters import cutter_kind

    for fmt in formats:
        FORMATS[fmt].check_cutter(options.cutter)
    cutter_kind(options.cutter).check_mode(options.cutter, options.laser_mode)


@dataclass(frozen=True)
class Download:
    """One format of a design as bytes (the web app's downloads): an inlay kit's two files as one zip."""

    data: bytes
    report: Report
    media_type: str
    file_name: str


def build_bytes(design, fmt: str, *, limits: _limits.Limits, file_name: str | None = None) -> Download:
    """Build one format of ``design``: the file's bytes, report, media type and name.

    Made through the same pipeline as :func:`build_design` (the same models and
    checks); an inlay kit's two files come as one zip archive, and so do a print's pieces.
    """
    from ..core.files import zip_entry
    from ..export.formats import FORMATS

    name = Path(file_name).stem if file_name else design.name
    suffix = FORMATS[fmt].suffix
    with tempfile.TemporaryDirectory(prefix="fabtiles-") as tmp:
        result = build_design(design, tmp, (fmt,), file_name=f"{name}{suffix}", limits=limits)
        report = result.reports[0]
        if len(result.paths) > 1:
            import io
            import zipfile

            buf = io.BytesIO()
            with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
                for p in result.paths:
                    zf.writestr(zip_entry(Path(p).name), Path(p).read_bytes(), compress_type=zipfile.ZIP_DEFLATED)
            # a panel's pieces (cut or printed), else an inlay kit's files (or a mosaic's STLs)
            what = "pieces" if result.assembly else "kit"
            return Download(buf.getvalue(), report, "application/zip", f"{name}-{what}-{fmt}.zip")
        data = Path(result.paths[0]).read_bytes()
    return Download(data, report, FORMATS[fmt].media_type, f"{name}{suffix}")


# --------------------------------------------------------------------------- the API's exports


_INLAY_OPTIONS = tuple(k.build.name for k in option_keys("cut") if k.requires == 'laser_mode = "inlay"')


def _options_for(fmt, profile, options: dict) -> BuildOptions:
    """The :class:`BuildOptions` of an API call writing ``fmt`` with keyword ``options``."""
    allowed = build_options(fmt.options)
    for key in options:
        if key not in allowed:
            raise ParameterError(
                f"{key!r} is not a valid option for .{fmt.name} files, must be one of: {', '.join(allowed)}", param=key
            )
    o = {k: v for k, v in options.items() if v is not None}
    cutter = load_profile(
        profile if (profile is not None and fmt.family == "cut") else DEFAULT_CUTTER_PROFILE, kind="laser"
    )
    printer = load_profile(
        profile if (profile is not None and fmt.family == "print") else DEFAULT_PRINTER_PROFILE, kind="printer"
    )
    if fmt.family == "cut":
        mode = o.get("mode")
        given = [k for k in _INLAY_OPTIONS if k in o]
        if (mode or cutter.mode) != "inlay" and given:
            raise ParameterError(
                f"{', '.join(_INLAY_OPTIONS[:-1])} and {_INLAY_OPTIONS[-1]} are options of the inlay "
                f"mode; pass mode='inlay'",
                param=given[0],
            )
        from ..machines.cutters import cutter_kind

        fmt.check_cutter(cutter)
        cutter_kind(cutter).check_mode(cutter, mode)
    return BuildOptions(cutter, printer, **BuildOptions.fields_of(o, "cut" if fmt.family == "cut" else "3mf"))


class _Region:
    """A tile-like view of a bare region (``export_region``): region, outline, centre-lines, stroke."""

    interlace = False

    def __init__(self, region, outline, centrelines, stroke):
        self._region, self._outline, self._lines, self.stroke = region, outline, centrelines, stroke

    def region(self):
        return self._region

    def outline_shape(self):
        return self._outline

    def centrelines(self):
        return self._lines


def _write_one(models: Models, path) -> Report:
    from ..export.formats import format_of

    path = Path(path)
    fmt = format_of(path)
    result = write_files(models, (fmt.name,), path.parent, path.stem)
    report = result.reports[0]
    return report


def export_tile(tile, path, *, profile=None, **options) -> Report:
    """Write ``tile`` in the format of ``path``'s suffix (``Tile.export``); return the file's report.

    ``profile``: the cutter profile for dxf/svg/lbrn2 (default ``laser-3mm-plywood``),
    the printer profile for stl/3mf/step (default ``fdm-0.4mm``). Options:
    cutter formats ``mode``, ``dxf_version``, ``kerf_mm``, ``fill_small_holes``,
    ``tab_mm`` and ``tabs_per_part`` (holding tabs in each part's outer cut), and
    with ``mode="inlay"`` ``inlay_fit_mm``, ``inlay_base`` (two files,
    ``<stem>-lattice`` and ``<stem>-pieces``); print formats ``style``, ``base_mm``,
    ``relief_mm``, ``pierced_mm``, ``deboss_mm``, ``fill_small_holes``, and for .3mf
    ``inlay`` and ``layout``. An interlaced tile scores its centre-lines broken where
    a strand passes under, cuts the under gaps with ``interlace_cut``, and dips its
    relief's under strands.
    """
    from ..export.formats import format_of

    fmt = format_of(path)
    return _write_one(Models(tile, _options_for(fmt, profile, options)), path)


def export_region(
    path, *, region, outline, centrelines=None, stroke=None, profile=None, dips=None, **options
) -> Report:
    """Write a bare ``region`` (material, file coordinates in mm) in the format of ``path``.

    As :func:`export_tile` for a region and outline of one's own (``centrelines`` for
    the score mode, ``stroke`` for the checks, ``dips`` an interlaced relief's).
    """
    from ..export.formats import format_of

    fmt = format_of(path)
    build_options = _options_for(fmt, profile, options)
    models = Models(
        _Region(region, outline, centrelines, stroke),
        build_options,
        cut_region=(region, centrelines),
        print_region=(region, dips),
    )
    return _write_one(models, path)
