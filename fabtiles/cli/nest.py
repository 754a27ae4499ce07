"""``fabtiles nest``: tiles of one or more designs packed onto the cutter's sheets.

The command parses its arguments and prints; the work is done by
:func:`fabtiles.making.nesting.nest_designs` (on bad input, exit status 2 and no
file; a format its writer refuses is named, the others written, exit status 3).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import click

from .choices import FormatChoice

# the nesting's rotation modes and default time, as fabtiles.geometry.nest has them (a test keeps the two
# alike): importing it here would import shapely for `fabtiles --help`
ROTATIONS = ("none", "180", "90", "free")
DEFAULT_TIME_S = 5.0

_COUNTED = re.compile(r"^(?P<path>.+):(?P<count>\d+)$")
_SHEET = re.compile(r"^\s*(?P<w>[0-9.]+)\s*[xX]\s*(?P<h>[0-9.]+)\s*$")


def split_count(arg: str) -> tuple[str, int | None]:
    """``DESIGN.toml:N`` -> ``(path, N)``; a plain path -> ``(path, None)``.

    >>> split_count("samples/rosette.toml:3"), split_count("samples/rosette.toml")
    (('samples/rosette.toml', 3), ('samples/rosette.toml', None))
    """
    m = _COUNTED.match(arg)
    if m and not Path(arg).exists():
        return m["path"], int(m["count"])
    return arg, None


def parse_sheet(text: str) -> tuple[float, float]:
    """``600x400`` -> ``(600.0, 400.0)``.

    >>> parse_sheet("600x400")
    (600.0, 400.0)
    """
    m = _SHEET.match(text)
    try:
        return float(m["w"]), float(m["h"])  # type: ignore[index]  # no match: None[...] is the TypeError below
    except (TypeError, ValueError):
        raise click.BadParameter(
            f"expected WIDTHxHEIGHT in mm like 600x400, got {text!r}", param_hint="--sheet"
        ) from None


@click.command("nest")
@click.argument("design_files", metavar="DESIGN.toml[:N] ...", nargs=-1, required=True)
@click.option(
    "-o",
    "--output",
    "outdir",
    required=True,
    type=click.Path(file_okay=False),
    help="Folder to write OUTDIR/<name>-sheet-<k>.<format> into.",
)
@click.option(
    "--count", type=int, metavar="N", help="Copies of each design not given as DESIGN.toml:N (>= 1); default 1."
)
@click.option(
    "--sheet",
    "sheet",
    metavar="WxH",
    help="The sheet in mm, e.g. 600x400; default: the cutter profile's bed (no larger).",
)
@click.option(
    "--gap",
    "gap_mm",
    type=float,
    metavar="MM",
    help="Least distance between two parts' cut paths, mm (>= the kerf); default: kerf + 1.",
)
@click.option(
    "--rotate",
    "rotations",
    type=click.Choice(tuple(ROTATIONS)),
    default="90",
    show_default=True,
    help="Turns a part may take: 90 (quarter turns), 180 (wood grain), free (any angle), none.",
)
@click.option(
    "--time",
    "time_s",
    type=float,
    default=None,
    metavar="SECONDS",
    help=f"The packer's time budget (> 0); at least a second per sheet.  [default: 0.2 s a part, from 1 to "
    f"{DEFAULT_TIME_S:g}]",
)
@click.option(
    "--format",
    "formats",
    multiple=True,
    type=FormatChoice(nests=True),
    help="Cutter format (repeatable); default: dxf.",
)
@click.option("--name", help="The files' stem; default: the design's name, or nest when there are several.")
def command(design_files, outdir, count, sheet, gap_mm, rotations, time_s, formats, name):
    """Nest tiles of one or more designs onto sheets: as few sheets as the packer finds.

    Each design's tile is cut as `fabtiles build` cuts it; its outer cut path (kerf
    included) is its part, packed with Sparrow's strip packing (spyrrow) on sheets
    of the cutter profile's bed (or --sheet), --gap apart; holes are not filled
    with other parts. Writes OUTDIR/<name>-sheet-1.dxf, -sheet-2.dxf, ... (each
    --format; a format its writer refuses is named with the reason, exit status 3,
    and the others written), and reports each sheet's parts, material use (the
    parts' area over the sheet's) and job.

    Copies: --count N for every design, or DESIGN.toml:N for one.

    \b
    fabtiles nest samples/rosette.toml --count 12 -o out/
    fabtiles nest a.toml:10 b.toml:5 -o out/ --sheet 600x400 --rotate 180 --format svg
    """
    from ..designs.design_file import load_design
    from ..making.nesting import nest_designs

    designs = [(load_design(path), n) for path, n in map(split_count, design_files)]
    size = parse_sheet(sheet) if sheet is not None else None
    state: dict = {"done": 0, "bar": None}

    def progress(p):
        _show_progress(p, state)

    try:
        result = nest_designs(
            designs,
            outdir,
            formats or ("dxf",),
            count=count,
            sheet_mm=size,
            gap_mm=gap_mm,
            rotations=rotations,
            time_s=time_s,
            name=name,
            progress=progress,
        )
    finally:
        if state["bar"] is not None:
            state["bar"].__exit__(None, None, None)
    for path in result.build.paths:
        click.echo(f"{'replaced' if path in result.build.replaced else 'wrote'} {path}")
    _echo_sheets(result)
    for label, report in result.build.models:
        if report.findings:
            click.echo(report.summary(label))
    from .build import report_refused

    report_refused(result.build.refused)


def _show_progress(p, state: dict) -> None:
    """The nesting's progress bar moved on to ``p`` (:class:`~fabtiles.geometry.nest.NestProgress`).

    A bar on a terminal only (elsewhere click would print its label as a stray line); opened at
    the packer's first report, so an error before it is still one line on stderr.
    """
    if not sys.stderr.isatty():
        return
    if state["bar"] is None:
        state["bar"] = click.progressbar(
            length=1000, label="nesting", file=sys.stderr, show_eta=False, show_percent=True
        ).__enter__()
    # the budget's fraction spent, and all of it once every part is placed
    done = 1000 if p.placed == p.parts else min(999, int(1000 * p.elapsed_s / p.budget_s))
    if done > state["done"]:
        state["bar"].update(done - state["done"])
        state["done"] = done


def _echo_sheets(result) -> None:
    """The nest's summary: parts, sheets, gap and rotation, then each sheet's parts, material use and job."""
    n = result.nesting
    w, h = n.sheet_mm
    parts = len(n.placements)
    click.echo(
        f"{parts} part{'s' if parts != 1 else ''} on {n.sheets} sheet{'s' if n.sheets != 1 else ''} of "
        f"{w:g} x {h:g} mm, gap {n.gap_mm:g} mm, rotate {n.rotations}"
    )
    for s in result.sheets:
        parts = ", ".join(f"{k} x{v}" for k, v in s["designs"].items())
        click.echo(
            f"sheet {s['sheet']}: {s['parts']} parts ({parts}), material use {s['material_use']:.0%}, "
            f"{s['job']['line']}"
        )
