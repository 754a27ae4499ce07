"""The vpype plugin: ``vpype fabtiles [--what centrelines|cut] [--set k=v] [--pen MM] [--fill] DESIGN.toml ...``.

Installed with the extra (``pip install 'fabtiles[vpype]'``), fabtiles registers this
command in vpype's ``vpype.plugins`` entry-point group, so a design enters a vpype
pipeline like any generator::

    vpype fabtiles samples/table3-3.toml linesort write out.svg

It is a vpype *global processor* (as vpype's own ``read``): a generator fills one
layer, and a design has several (the strands, the outline, each face colour; or each
cutter layer), each added as a new layer with its name (``vp_name``), colour
(``vp_color``) and the pen's width (``vp_pen_width``). The drawing is
:func:`fabtiles.making.plot.plot_drawing`'s, at true size. fabtiles' errors reach
vpype's error channel as one line (``Error: fabtiles: ...``, exit status 1), never a
traceback.
"""

from __future__ import annotations

import click

from ..making.plot import WHATS

try:
    import vpype_cli
except ImportError:  # only vpype loads this module (its entry point), so vpype is there then; a doctest
    vpype_cli = None  # run without the extra imports it too, and must not fail


def _global_processor(f):
    return vpype_cli.global_processor(f) if vpype_cli is not None else f


@click.command("fabtiles")
@click.argument("design", type=str)
@click.option(
    "--what",
    type=click.Choice(WHATS),
    default="centrelines",
    show_default=True,
    help="centrelines: the strands as single strokes, for a pen; cut: the cutter's contours.",
)
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="SECTION.KEY=VALUE",
    help="Override a design key, as in `fabtiles build --set` (repeatable).",
)
@click.option("--pen", "pen_mm", type=float, default=None, help="The pen's width in mm (default 0.3).")
@click.option("--fill", is_flag=True, help="Hatch each face in its class's colour, a layer per pen (needs [colour]).")
@click.option(
    "--hatch-mm", type=float, default=None, help="With --fill: the hatch lines' distance in mm (default the pen's)."
)
@click.option(
    "--angle",
    "angles",
    multiple=True,
    metavar="[CLASS=]DEGREES",
    help="With --fill: the hatch angle, of every class (30) or of one (B=60); repeatable.",
)
@click.option("--cross", is_flag=True, help="With --fill: cross-hatch, a second set of lines at right angles.")
@_global_processor
def fabtiles_command(document, design, what, overrides, pen_mm, fill, hatch_mm, angles, cross):
    """Draw a fabtiles design (a TOML file): one layer per pen, named and coloured."""
    return add_design(
        document,
        design,
        what=what,
        overrides=overrides,
        pen_mm=pen_mm,
        fill=fill,
        hatch_mm=hatch_mm,
        angles=angles,
        cross=cross,
    )


def add_design(
    document,
    design,
    *,
    what="centrelines",
    overrides=(),
    pen_mm=None,
    fill=False,
    hatch_mm=None,
    angles=(),
    cross=False,
):
    """``document`` with the design's drawing added, a layer per pen; fabtiles' errors as click's.

    ``fill``, ``hatch_mm``, ``angles`` (``--angle`` texts) and ``cross`` as ``fabtiles plot``'s.
    """
    from ..core.errors import FabtilesError
    from ..export.plot_svg import vpype_document
    from .plot import drawing_of

    try:
        drawing = drawing_of(
            design,
            overrides=overrides,
            what=what,
            pen_mm=pen_mm,
            fill=fill,
            hatch_mm=hatch_mm,
            angles=angles,
            cross=cross,
        )
    except FabtilesError as exc:
        raise click.ClickException(f"fabtiles: {exc}") from None
    return vpype_document(drawing, document)
