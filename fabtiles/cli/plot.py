"""``fabtiles plot``: a design as a pen plotter draws it (SVG; HPGL through vpype).

The command parses its arguments and prints; the drawing is
:func:`fabtiles.making.plot.plot_drawing`'s, the files :mod:`fabtiles.export.plot_svg`'s.
"""

from __future__ import annotations

from pathlib import Path

import click

from ..making.plot import WHATS

_OPTIONS = {"pen_mm": "--pen", "hatch_mm": "--hatch-mm"}
"""The plot's API keywords whose errors the commands (``fabtiles plot``, ``vpype fabtiles``) say with the option's
name."""


def drawing_of(design_file, *, overrides=(), what, pen_mm, fill, hatch_mm, angles, cross):
    """The pen drawing of a design file as ``fabtiles plot`` and ``vpype fabtiles`` take their options
    (``angles``: the ``--angle`` texts); a bad ``--pen`` or ``--hatch-mm`` is refused naming that option, not
    :func:`~fabtiles.making.plot.plot_drawing`'s keyword."""
    from ..core.errors import ParameterError
    from ..designs.design_file import load_design
    from ..making.plot import angles_from_text, plot_drawing

    design = load_design(design_file, overrides=list(overrides))
    try:
        return plot_drawing(
            design,
            what=what,
            pen_mm=pen_mm,
            fill=fill,
            hatch_mm=hatch_mm,
            angles_deg=angles_from_text(angles) if angles else None,
            cross=cross,
        )
    except ParameterError as exc:
        option = _OPTIONS.get(exc.param or "")
        if option is None or not str(exc).startswith(f"{exc.param} "):
            raise
        raise ParameterError(option + str(exc)[len(exc.param or "") :], param=exc.param) from None


@click.command("plot")
@click.argument("design_file", metavar="DESIGN.toml", type=click.Path(dir_okay=False))
@click.option(
    "-o",
    "--output",
    required=True,
    type=click.Path(dir_okay=False),
    help="The file to write: .svg, or .hpgl (needs vpype: pip install 'fabtiles[vpype]').",
)
@click.option(
    "--what",
    type=click.Choice(WHATS),
    default="centrelines",
    show_default=True,
    help="centrelines: the strands as single strokes, for a pen; cut: the cutter's contours.",
)
@click.option(
    "--pen", "pen_mm", type=float, default=None, help="The pen's width in mm, the strokes' width (default 0.3)."
)
@click.option(
    "--fill",
    is_flag=True,
    help="Hatch each face in its class's colour, a layer per pen (needs the design's [colour]).",
)
@click.option(
    "--hatch-mm",
    type=float,
    default=None,
    help="With --fill: the distance between hatch lines in mm (default the pen's width: the strokes touch).",
)
@click.option(
    "--angle",
    "angles",
    multiple=True,
    metavar="[CLASS=]DEGREES",
    help="With --fill: the hatch angle, of every class (30) or of one (B=60); repeatable "
    "(default 45, 135, 0, 90, ... in class order).",
)
@click.option("--cross", is_flag=True, help="With --fill: cross-hatch, a second set of lines at right angles.")
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="SECTION.KEY=VALUE",
    help="Override a design key for this run (repeatable), as in `fabtiles build`.",
)
def command(design_file, output, what, pen_mm, fill, hatch_mm, angles, cross, overrides):
    """Write a design for a pen plotter: merged single strokes, ordered for the least pen-up travel.

    \b
    fabtiles plot samples/table3-3.toml -o table.svg --pen 0.5
    fabtiles plot samples/mosaic-iznik.toml -o mosaic.hpgl
    fabtiles plot samples/mosaic-iznik.toml -o filled.svg --fill --cross

    One layer per pen: the strands, the outline, each face colour (with [colour]); with --fill
    one layer per colour, the band's pen drawing the strands and each class's pen hatching its faces.
    """
    from ..core.errors import ParameterError
    from ..core.files import atomic_write
    from ..export.formats import FORMATS, FileOptions

    pens = [f for f in FORMATS.values() if f.family == "pen"]  # the format table's pen drawings
    suffix = Path(output).suffix.lower()
    fmt = next((f for f in pens if f.suffix == suffix), None)
    if fmt is None:
        raise ParameterError(
            f"the plot's output (-o) must end in {' or '.join(f.suffix for f in pens)}, got {output!r}",
            param="output",
        )
    if fmt.requires is not None:
        fmt.requires()  # a library it needs (HPGL: vpype), before any geometry
    drawing = drawing_of(
        design_file,
        overrides=overrides,
        what=what,
        pen_mm=pen_mm,
        fill=fill,
        hatch_mm=hatch_mm,
        angles=angles,
        cross=cross,
    )
    atomic_write(output, fmt.write(drawing, FileOptions(name=Path(output).stem)))
    layers = ", ".join(
        f"{layer.name} {len(layer.paths):,} stroke{'' if len(layer.paths) == 1 else 's'}" for layer in drawing.layers
    )
    click.echo(
        f"{output}: {layers}; pen down {drawing.length_mm / 1000:.3g} m, pen up {drawing.travel_mm / 1000:.3g} m"
    )
    bare = drawing.stats.get("fill", {}).get("not_hatched")
    if bare:
        click.echo(
            f"not hatched (no line fits in the faces, narrower than the {drawing.pen_mm:g} mm pen or the spacing): "
            f"class{'es' if len(bare) > 1 else ''} {', '.join(bare)}"
        )
