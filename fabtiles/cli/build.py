"""``fabtiles build``: build a design file into output files.

All or nothing: the design is validated and the tile's geometry computed first;
every file is then written into a temporary folder inside OUTDIR and moved into
place only when all formats have succeeded. A failure (exit status 2) leaves no
new or partial file behind and never clobbers an existing one.

Sheets: with ``--sheet`` (as many copies as fit) or ``--copies N`` the laser
formats are written as ``OUTDIR/<design name>-sheet.<format>``: copies of the tile
laid out in rows on the bed of the design's laser profile by
:func:`~fabtiles.export.sheet.layout_sheet`. Print formats have no sheet and are
skipped (the command says so); asking only for print formats is an error. A large
pattern needs no layout: make the tile as big as the bed (``samples/sheet-600x400.toml``).
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import click

from .. import _limits
from .._errors import FabtilesError
from ..design import FORMATS, load_design

SHEET_SUFFIX = "-sheet"
"""Sheet files are ``<design name>-sheet.<format>``, next to (never over) the tile's files."""


def _export(tile, fmt: str, path: Path, design):
    """Write one format through the exporters' dispatcher; return its report."""
    from ..export import dispatch

    out = design.output
    if dispatch.profile_kind(fmt) == "laser":
        return dispatch.export_tile(tile, path, profile=out.laser_profile, mode=out.laser_mode,
                                    fill_small_holes=out.fill_small_holes)
    return dispatch.export_tile(tile, path, profile=out.printer_profile, style=out.print_style, **out.heights())


def sheet_formats(formats) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Split ``formats`` into the laser formats a sheet is written in and the skipped print formats.

    >>> sheet_formats(["svg", "stl", "dxf"])
    (('svg', 'dxf'), ('stl',))
    """
    from ..export.dispatch import profile_kind

    laser = tuple(f for f in formats if profile_kind(f) == "laser")
    return laser, tuple(f for f in formats if f not in laser)


def layout_tile_sheet(tile, design, *, copies=None, gap_mm=None):
    """Copies of ``tile`` on the bed of the design's laser profile (see :func:`build_design`).

    Parameters
    ----------
    tile : Tile
        The design's tile.
    design : Design
        Gives the laser profile (its bed size and kerf).
    copies : int, optional
        Exactly this many copies; default: as many as fit on the bed.
    gap_mm : float, optional
        Space between tiles; default: the kerf + 2 mm.

    Returns
    -------
    Sheet
        See :func:`~fabtiles.export.sheet.layout_sheet`.

    Raises
    ------
    FabricationError
        The copies (or even one tile) do not fit on the bed.
    LimitError
        The sheet would hold more segments than the work limits of the CLI allow.
    """
    from ..export.dispatch import DEFAULT_LASER_PROFILE
    from ..export.sheet import layout_sheet

    profile = design.output.laser_profile or DEFAULT_LASER_PROFILE
    options = dict(copies=1 if copies is None else copies, gap_mm=gap_mm, fill=copies is None)
    outline = tile.outline_shape()
    # Place the outlines alone first (cheap), to refuse an oversized job before any work.
    placed = layout_sheet([(outline, outline)], profile, **options)
    _limits.check_segments(len(tile.segments()) * len(placed.offsets), _limits.CLI_LIMITS,
                           what=f"the sheet of {len(placed.offsets)} tiles")
    return layout_sheet([(tile.region(), outline)], profile, centrelines=[tile.centrelines()], **options)


def build_design(design, outdir, formats=None, *, sheet: bool = False, copies: int | None = None,
                 gap_mm: float | None = None, file_name: str | None = None) -> list:
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
        Space between tiles on the sheet (> kerf); default: the kerf + 2 mm.
    file_name : str, optional
        The name of the one file written (one format only), instead of
        ``<design name>[-sheet].<format>``.

    Returns
    -------
    list of Report
        One per file written (``report.path`` is its final path), with the
        fabrication checks' findings.

    Raises
    ------
    FabtilesError
        On any failure, with nothing written: among others, a sheet asked for with
        only print formats, or copies that do not fit on the bed.
    """
    formats = tuple(dict.fromkeys(formats or design.output.formats))
    sheet = sheet or copies is not None or gap_mm is not None
    if sheet:
        formats, skipped = sheet_formats(formats)
        if not formats:
            raise FabtilesError(
                f"a sheet is laid out for the laser formats (dxf, svg) only, but the formats asked "
                f"for are: {', '.join(skipped)}; add --format dxf or --format svg")
    tile = design.build_tile(tile_cls=_tile_class())
    # Compute (and fail) before anything is written; a sheet that cannot fit fails before the tile.
    layout = layout_tile_sheet(tile, design, copies=copies, gap_mm=gap_mm) if sheet else None
    tile.region()
    outdir = Path(outdir)
    if outdir.exists() and not outdir.is_dir():
        raise FabtilesError(f"output folder {str(outdir)!r} exists and is not a folder")
    existed = outdir.exists()
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise FabtilesError(f"cannot create output folder {str(outdir)!r}: {exc.strerror or exc}") from None
    staging = Path(tempfile.mkdtemp(prefix=".fabtiles-build-", dir=outdir))
    try:
        staged = []
        for fmt in formats:
            if layout is None:
                path = staging / (file_name or f"{design.name}.{fmt}")
                report = _export(tile, fmt, path, design)
            else:
                path = staging / (file_name or f"{design.name}{SHEET_SUFFIX}.{fmt}")
                report = _export_sheet(layout, tile, path, design)
            staged.append((path, report))
        for path, report in staged:
            target = outdir / path.name
            os.replace(path, target)
            report.path = str(target)
        return [report for _, report in staged]
    except OSError as exc:
        raise FabtilesError(f"cannot write into {str(outdir)!r}: {exc.strerror or exc}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
        if not existed and not any(outdir.iterdir()):
            outdir.rmdir()  # a failed build leaves no folder it created either


def _export_sheet(layout, tile, path: Path, design):
    """Write one laser format of a sheet; return its report."""
    from ..export.dispatch import export_geometry

    out = design.output
    return export_geometry(path, region=layout.region, outline=layout.outline, centrelines=layout.centrelines,
                           stroke=tile.stroke, profile=out.laser_profile, mode=out.laser_mode,
                           fill_small_holes=out.fill_small_holes)


def _tile_class():
    """The public Tile (the lead's subclass with ``export``) when available, else the base."""
    try:
        import fabtiles

        return getattr(fabtiles, "Tile", None)
    except ImportError:  # pragma: no cover
        return None


def single_file_target(output, formats):
    """``(path, format)`` when ``output`` names one file by a format's suffix, else None.

    >>> single_file_target("out/tile.DXF", ())
    (PosixPath('out/tile.DXF'), 'dxf')
    >>> single_file_target("out", ()) is None
    True

    Raises :class:`click.UsageError` (exit status 2) when ``formats`` asks for another
    format or for several.
    """
    path = Path(output)
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in FORMATS:
        return None
    others = [f for f in dict.fromkeys(formats) if f != fmt]
    if others:
        raise click.UsageError(
            f"-o {output} writes one .{fmt} file, but --format asks for {', '.join(dict.fromkeys(formats))}; "
            f"drop --format, or give an output folder for several formats")
    return path, fmt


@click.command("build")
@click.argument("design_file", metavar="DESIGN.toml", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "outdir", required=True, type=click.Path(),
              help="Folder to write OUTDIR/<design name>.<format> into; or one file, named with "
                   "its format's suffix (tile.dxf, tile.STL, ...), to write just that file.")
@click.option("--set", "overrides", multiple=True, metavar="SECTION.KEY=VALUE",
              help="Override a design value, in TOML syntax: --set tile.size=[200,200] (repeatable).")
@click.option("--format", "formats", multiple=True, type=click.Choice(FORMATS),
              help="Output format (repeatable); default: the design's [output] formats.")
@click.option("--sheet", is_flag=True,
              help="Lay as many copies of the tile as fit on the laser profile's bed and write "
                   "OUTDIR/<design name>-sheet.dxf/.svg instead of the tile's laser files. "
                   "Print formats are skipped.")
@click.option("--copies", type=int, metavar="N",
              help="Lay exactly N copies on the sheet (implies --sheet); more than fit is an error.")
@click.option("--gap", "gap_mm", type=float, metavar="MM",
              help="Space between tiles on the sheet, mm (> kerf; implies --sheet); default: kerf + 2.")
def command(design_file, outdir, overrides, formats, sheet, copies, gap_mm):
    """Build a design file into laser/print/CAD files.

    Writes OUTDIR/<design name>.<format> for each format, all or nothing: on an
    error (exit status 2) no file is written or changed.

    With --sheet or --copies N, the laser formats (dxf, svg) are written as one
    sheet of the laser profile's bed size (e.g. 600 x 400 mm), copies of the tile
    in rows: OUTDIR/<design name>-sheet.dxf and .svg. Print formats (stl, 3mf,
    step) have no sheet: they are skipped with a note; asking only for print
    formats is an error. For one large pattern over a whole sheet, make the tile
    the size of the bed instead (tile.outline = "rectangle", size = [600, 400]),
    as samples/sheet-600x400.toml does.

    With -o FILE named with a format's suffix (.dxf .svg .stl .3mf .step, any
    case), writes just that file, in that format.

    \b
    fabtiles build samples/table3-3.toml -o out/
    fabtiles build samples/table3-3.toml -o tile.dxf
    fabtiles build samples/table3-3.toml -o out/ --set tile.size=[200,200] --format svg
    fabtiles build samples/table3-3.toml -o out/ --sheet
    fabtiles build samples/rosette.toml -o out/ --copies 12 --format dxf
    fabtiles build samples/sheet-600x400.toml -o out/
    """
    target = single_file_target(outdir, formats)
    design = load_design(design_file, overrides=overrides)
    sheet = sheet or copies is not None or gap_mm is not None
    if target is not None:
        outdir, formats = target[0].parent, (target[1],)
        reports = build_design(design, outdir, formats, sheet=sheet, copies=copies, gap_mm=gap_mm,
                               file_name=target[0].name)
    else:
        reports = build_design(design, outdir, formats or None, sheet=sheet, copies=copies, gap_mm=gap_mm)
    for report in reports:
        click.echo(f"wrote {report.summary()}")  # the file, then one line per fabrication finding
    skipped = sheet_formats(dict.fromkeys(formats or design.output.formats))[1] if sheet else ()
    if skipped:
        click.echo(f"fabtiles: note: skipped {', '.join(skipped)}: a sheet is laid out for the laser "
                   f"formats (dxf, svg) only", err=True)
