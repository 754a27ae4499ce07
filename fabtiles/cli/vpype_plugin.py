"""The vpype plugin: ``vpype fabtiles DESIGN.toml [--what centrelines|cut] [--set k=v] [--pen MM] ...``.

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
@_global_processor
def fabtiles_command(document, design, what, overrides, pen_mm):
    """Draw a fabtiles design (a TOML file): one layer per pen, named and coloured."""
    return add_design(document, design, what=what, overrides=overrides, pen_mm=pen_mm)


def add_design(document, design, *, what="centrelines", overrides=(), pen_mm=None):
    """``document`` with the design's drawing added, a layer per pen; fabtiles' errors as click's."""
    from ..core.errors import FabtilesError
    from ..designs.design_file import load_design
    from ..export.plot_svg import vpype_document
    from ..making.plot import plot_drawing

    try:
        drawing = plot_drawing(load_design(design, overrides=list(overrides)), what=what, pen_mm=pen_mm)
    except FabtilesError as exc:
        raise click.ClickException(f"fabtiles: {exc}") from None
    return vpype_document(drawing, document)
