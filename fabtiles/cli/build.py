"""``fabtiles build``: build a design file into output files.

The command parses its arguments and prints; the work is done by the build
pipeline, :func:`fabtiles.making.build_design`. Bad input is exit status 2 with no
new or partial file and no existing file changed; a format whose model or writer
fails is refused on its own (its file not written, the line says why) while the
others are written, and the exit status is then 3 (:data:`~fabtiles.cli.main.REFUSED_EXIT`).

Sheets: with ``--sheet`` (as many copies as fit) or ``--copies N`` the laser
formats are written as ``OUTDIR/<design name>-sheet.<format>``: copies of the tile
laid out in rows on the bed of the design's laser profile. Print formats have no
sheet and are skipped (the command says so); asking only for print formats is an
error. A large pattern needs no layout: make the tile as big as the bed
(``samples/sheet-600x400.toml``).
"""

from __future__ import annotations

import re
from pathlib import Path

import click

from ..core.errors import ParameterError
from ..designs.design_file import design_notes, load_design, override_notes
from .choices import FormatChoice


def single_file_target(output, formats):
    """``(path, format)`` when ``output`` names one file by a format's suffix, else None.

    >>> single_file_target("out/tile.DXF", ())
    (PosixPath('out/tile.DXF'), 'dxf')
    >>> single_file_target("out", ()) is None
    True

    Raises :class:`click.UsageError` (exit status 2) when ``formats`` asks for another
    format or for several, and a :class:`ParameterError` when ``output`` names a file of
    a type fabtiles does not write (``tile.png``).
    """
    from ..export.formats import FORMATS, design_formats

    path = Path(output)
    suffix = path.suffix.lower()
    suffixes = {FORMATS[f].suffix: f for f in reversed(design_formats())}  # the first format of a suffix
    if suffix not in suffixes:
        if _file_suffix(output):
            raise ParameterError(
                f"-o {output}: fabtiles does not write {suffix} files; name the file with a format's suffix "
                f"({', '.join(FORMATS[f].suffix for f in design_formats())}) or give a folder",
                param="output",
            )
        return None
    fmt = suffixes[suffix]
    others = [f for f in dict.fromkeys(formats) if f != fmt]
    if others:
        raise click.UsageError(
            f"-o {output} writes one .{fmt} file, but --format asks for {', '.join(dict.fromkeys(formats))}; "
            f"drop --format, or give an output folder for several formats"
        )
    return path, fmt


OTHER_FILE_SUFFIXES = (
    "gcode",
    "nc",
    "ngc",
    "tap",
    "dwg",
    "stp",
    "iges",
    "igs",
    "obj",
    "glb",
    "gltf",
    "lbrn",
    "plt",
    "hpgl",
    "ai",
    "cdr",
    "f3d",
)
"""Suffixes of machine and CAD files :mod:`mimetypes` does not know: ``-o tile.gcode`` is a mistake, not a folder."""


def _file_suffix(output) -> bool:
    """Whether ``output`` ends in a file type's suffix (``tile.png``, ``t.pdf``, ``t.gcode``): a file
    fabtiles does not write, never meant as a folder. A folder that exists, a trailing ``/`` or an
    unknown suffix (``tiles.v2``) is a folder.

    >>> _file_suffix("tile.png"), _file_suffix("t.PDF"), _file_suffix("tiles.v2"), _file_suffix("tile.png/")
    (True, True, False, False)
    """
    import mimetypes

    text = str(output)
    path = Path(text)
    if text.endswith(("/", "\\")) or path.is_dir() or not path.suffix:
        return False
    suffix = path.suffix.lower()
    return mimetypes.guess_type("f" + suffix, strict=False)[0] is not None or suffix[1:] in OTHER_FILE_SUFFIXES


@click.command("build")
@click.argument("design_file", metavar="DESIGN.toml", type=click.Path(dir_okay=False))
@click.option(
    "-o",
    "--output",
    "outdir",
    required=True,
    type=click.Path(),
    help="Folder to write OUTDIR/<design name>.<format> into; or one file, named with "
    "its format's suffix (tile.dxf, tile.STL, ...), to write just that file; a file of "
    "another type (tile.png) is an error.",
)
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="SECTION.KEY=VALUE",
    help="Override a design value, in TOML syntax: --set tile.size=[200,200] (repeatable).",
)
@click.option(
    "--format",
    "formats",
    multiple=True,
    type=FormatChoice(),
    help="Output format (repeatable); default: the design's [output] formats.",
)
@click.option(
    "--sheet",
    is_flag=True,
    help="Lay as many copies of the tile as fit on the laser profile's bed and write "
    "OUTDIR/<design name>-sheet.dxf/.svg instead of the tile's laser files. "
    "Print formats are skipped.",
)
@click.option(
    "--copies",
    type=int,
    metavar="N",
    help="Lay exactly N copies on the sheet (implies --sheet); more than fit is an error.",
)
@click.option(
    "--gap",
    "gap_mm",
    type=float,
    metavar="MM",
    help="Space between tiles on the sheet, mm (> kerf; implies --sheet); default: kerf + 2.",
)
def command(design_file, outdir, overrides, formats, sheet, copies, gap_mm):
    """Build a design file into laser/print/CAD files.

    Writes OUTDIR/<design name>.<format> for each format. On bad input (exit
    status 2) no file is written or changed. A format whose model or writer
    fails (a strict profile's findings, a solid the STEP check refuses) is
    refused on its own: "refused PATH (fmt): why" on stderr, its file not
    written, the other formats written, exit status 3. Each file is reported as
    "wrote" (new) or "replaced" (it was there); each --set as what it changed; and
    files of the design's name in formats this build did not write are named, as
    left from an earlier build.

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
    from ..making import build_design

    target = single_file_target(outdir, formats)
    design = load_design(design_file, overrides=overrides)
    file_name = None
    if target is not None:
        outdir, formats, file_name = target[0].parent, (target[1],), target[0].name
    result = build_design(
        design, outdir, formats or None, sheet=sheet, copies=copies, gap_mm=gap_mm, file_name=file_name
    )
    # what this build changed from the file, and what the file says that the tile does not show
    for line in override_notes(design_file, overrides) + design_notes(design):
        click.echo(f"fabtiles: note: {line}", err=True)
    _echo_files(result)
    _note_earlier(result)
    report_refused(result.refused, result.earlier)


def _echo_files(result) -> None:
    """The files written (or replaced), then each model's figures and findings once, and the formats skipped."""
    from ..making.pieces import PIECE_SUFFIX

    replaced = set(result.replaced)
    for report in result.reports:
        files = [str(p) for p in report.stats.get("files", [report.path])]
        # a panel's pieces (cut or printed; a mosaic piece's STLs, one per colour, each stay a line)
        pieces = [p for p in files if re.search(rf"{PIECE_SUFFIX}\d+$", Path(p).stem)]
        if result.assembly and len(pieces) > 2:  # one line per format
            verb = "replaced" if all(p in replaced for p in pieces) else "wrote"
            click.echo(f"{verb} {piece_range(pieces)} ({report.format}, {len(pieces)} pieces)")
            files = [p for p in files if p not in pieces]  # the nested sheets, one line each
        for path in files:
            click.echo(f"{'replaced' if path in replaced else 'wrote'} {path} ({report.format})")
    for path in result.assembly:
        what = "assembly drawing" if path.endswith(".svg") else "assembly manifest"
        click.echo(f"{'replaced' if path in replaced else 'wrote'} {path} ({what})")
    for label, report in result.models:
        click.echo(report.summary(label))
    skipped = result.skipped
    if skipped:
        click.echo(
            f"fabtiles: note: skipped {', '.join(skipped)}: a sheet is laid out for the laser formats (dxf, svg) only",
            err=True,
        )


def piece_range(files) -> str:
    """A panel's piece files in one name: ``out/screen-piece-01..08.dxf``.

    >>> piece_range(["o/s-piece-01.dxf", "o/s-piece-02.dxf", "o/s-piece-08.dxf"])
    'o/s-piece-01..08.dxf'
    """
    first, last = Path(files[0]), Path(files[-1])
    number = last.stem.rsplit("-", 1)[-1]
    return f"{first.parent / first.stem}..{number}{first.suffix}"


def _note_earlier(result) -> None:
    """A note naming the files of an earlier build in the folder that this build did not rewrite."""
    refused = {r.path for r in result.refused}
    earlier = [p for p in result.earlier if p not in refused]
    if not earlier:
        return
    one = len(earlier) == 1
    it = "it" if one else "them"
    others = " ".join(f"--format {f}" for f in dict.fromkeys(Path(p).suffix[1:] for p in earlier))
    click.echo(
        f"fabtiles: note: {', '.join(earlier)} {'is' if one else 'are'} from an earlier build and "
        f"{'was' if one else 'were'} not rewritten (this build wrote "
        f"{', '.join(r.format for r in result.reports)}); add {others} to rebuild {it}, or delete {it}",
        err=True,
    )


def report_refused(refused, earlier=()) -> None:
    """One line on stderr per refused format (its file, format and why), then exit with status 3.

    A file of that name from an earlier build is said to be left as it was.
    """
    if not refused:
        return
    from .main import REFUSED_EXIT

    for r in refused:
        old = f" ({r.path}, from an earlier build, was left as it was)" if r.path in earlier else ""
        click.echo(f"fabtiles: {r.line()}{old}", err=True)
    click.get_current_context().exit(REFUSED_EXIT)
