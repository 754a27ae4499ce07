"""``fabtiles check``: run a design's fabrication checks without writing its files.

The laser checks of the design's laser profile (on the region as the laser files
would hold it: with ``fill_small_holes``, its small holes filled) and the print
checks of its printer profile, style and heights (see :mod:`fabtiles.making.checks`).
Each finding is one line: where (laser or print), code, count, worst value and
the first places. ``-o overlay.svg`` writes a picture of the tile with a mark at
every place (written atomically).

Exit status: 0 when nothing was found, 1 when there are findings, 2 on bad input
(one line on stderr, no file written).
"""

from __future__ import annotations

from pathlib import Path

import click

from ..core.errors import ParameterError

SHOWN_PLACES = 3
"""Places listed per finding on the terminal (the overlay shows them all)."""


def finding_line(where: str, finding) -> str:
    """One line for a finding: where, code, count, worst value, first places.

    >>> from fabtiles.core.report import Finding
    >>> f = Finding("thin_bridge", "...", 12, ((1.0, 2.0),), (0.155,), 0.155)
    >>> finding_line("laser", f)
    'laser thin_bridge: 12, worst 0.155 mm, at (1, 2) and 11 more'
    >>> finding_line("laser", Finding("thin_bridge", "...", 1, ((1.0, 2.0),), (0.155,), 0.155, limit=0.3))
    'laser thin_bridge: 1, worst 0.155 mm (limit 0.3 mm), at (1, 2)'
    """
    parts = [f"{where} {finding.code}: {finding.count:,}"]
    if finding.worst is not None:
        unit = "mm²" if finding.unit == "mm^2" else finding.unit
        limit = f" (limit {finding.limit:g} {unit})" if finding.limit is not None else ""
        parts.append(f"worst {finding.worst:g} {unit}{limit}")
    if finding.locations:
        parts.append(f"at {finding.where(SHOWN_PLACES)}")
    else:
        parts.append(finding.message)
    return ", ".join(parts)


@click.command("check")
@click.argument("design_file", metavar="DESIGN.toml", type=click.Path(dir_okay=False))
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    help="Write an SVG picture of the tile with a mark at every finding.",
)
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="SECTION.KEY=VALUE",
    help="Override a design value, in TOML syntax: --set output.fill_small_holes=false (repeatable).",
)
@click.option(
    "--deep",
    is_flag=True,
    help="Also write the print files (the design's, else STL, 3MF and STEP) to a temporary folder and "
    "read each back: STEP by OCCT, STL and 3MF by trimesh (slower: the STEP's B-rep is built).",
)
def command(design_file, output, overrides, deep):
    """Run the laser and print checks of a design; write no fabrication file.

    \b
    fabtiles check samples/table3-3.toml
    fabtiles check my-tile.toml -o overlay.svg --set output.fill_small_holes=false
    fabtiles check samples/table3-3.toml --deep

    Exit status 0: clean; 1: findings; 2: bad input.
    """
    import fabtiles

    from ..designs.design_file import load_design
    from ..making.checks import check_design

    if output is not None and Path(output).suffix.lower() != ".svg":
        raise ParameterError(f"the overlay (-o) must be an .svg file, got {output!r}")
    design = load_design(design_file, overrides=overrides)
    from ..designs.design_file import design_notes, profile_of

    cutter = profile_of(design, "laser").kind  # an unknown profile is refused before any geometry
    profile_of(design, "printer")
    tile = design.build_tile(tile_cls=fabtiles.Tile)  # checks the work limits first
    out = design.output
    style = out.print_style or profile_of(design, "printer").print_style
    models = _colour_models(design, design_file, tile, style)
    result = check_design(design, tile, job=True)
    class_lines = _class_lines(models, result, style, out.fill_small_holes)
    laser, printer = _profile_words(result, cutter, out)
    for line in design_notes(design):  # what the checked tile has that the file does not say (a seamless fit)
        click.echo(f"fabtiles: note: {line}", err=True)
    click.echo(f"{design_file}: {printer}" if design.surface.shape != "flat" else f"{design_file}: {laser}, {printer}")
    _echo_figures(result, cutter, class_lines)
    findings = result.findings()
    for where, f in findings:
        click.echo("  " + finding_line(where, f))
    if output is not None:
        # a router's or waterjet's part is drawn as the tool makes it (the holes opened)
        from ..core.files import atomic_write
        from ..making.views import tile_picture

        atomic_write(
            output,
            tile_picture(
                tile,
                design,
                title=f"{design.name}: fabrication findings",
                findings=findings,
                made=result.made,
                pieces=result.split,  # a panel larger than the bed: its pieces' seams and numbers
            ),
        )
        click.echo(f"wrote {output}")
    if deep:
        from ..making.deep import read_back

        for back in read_back(design):
            click.echo("  " + back.line())
    n = len(findings)
    click.echo(f"{n} finding{'s' if n != 1 else ''}" if n else "ok: nothing found")
    if n:
        click.get_current_context().exit(1)


def _colour_models(design, design_file, tile, style: str):
    """The build's models when the tile is coloured (or a mosaic print), its colouring made so that a class
    letter the design lacks is refused before anything is printed; None otherwise."""
    if not (design.colour.given or style == "mosaic"):
        return None
    from ..making.models import BuildOptions, Models

    models = Models(tile, BuildOptions.of_design(design))
    try:
        _ = models.colouring
    except ParameterError as exc:
        raise ParameterError(f"{design_file}: {exc}", param=exc.param) from None
    return models


def _class_lines(models, result, style: str, fill_small_holes: bool) -> list:
    """The print's parts and face classes as the print makes them (classes filled with the bands print no
    colour), one line each; none without models."""
    if models is None:
        return []
    from ..core.report import face_class_lines

    filled = models.filled_classes(result.print_region) if fill_small_holes else frozenset()
    lines = [models.print_parts_line(result.print_region, style)]
    return lines + face_class_lines(models.face_class_stats(filled))


def _profile_words(result, cutter: str, out) -> tuple[str, str]:
    """The cutter's and the printer's profile as the summary names them, with the holes filled for each."""
    from ..making.checks import DEFAULT_LASER_PROFILE, DEFAULT_PRINTER_PROFILE

    laser = f"{cutter} profile {out.laser_profile or DEFAULT_LASER_PROFILE}"
    if result.filled_holes:
        laser += f" ({result.filled_holes:,} small holes filled)"
    printer = f"printer profile {out.printer_profile or DEFAULT_PRINTER_PROFILE}"
    if result.print_filled_holes:
        printer += f" ({result.print_filled_holes:,} small holes filled)"
    return laser, printer


def _echo_figures(result, cutter: str, class_lines: list) -> None:
    """The check's figures: the cutter's job and travel, the print's material, the classes."""
    for line in result.pieces:  # a panel larger than the bed, checked as its pieces
        click.echo(f"  {cutter} {line}")
    if result.job is not None:
        click.echo(f"  {cutter} job: {result.job.line()}")
        click.echo(f"  {cutter} {result.job.travel_line()}")
    if result.filament is not None:
        click.echo(f"  print material: {result.filament.line()} (print time: ask the slicer)")
    for line in result.print.stats.get("notes", ()):  # a print larger than the bed: its pieces
        click.echo(f"  print {line}")
    for line in class_lines:
        click.echo("  " + line)
