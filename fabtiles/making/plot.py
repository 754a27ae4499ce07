"""A design as a pen plotter draws it: the drawing every plotting front end writes.

:func:`plot_drawing` makes a :class:`~fabtiles.geometry.pen.PenDrawing` of a design:

- ``what="centrelines"`` (a pen): the pattern's strands as single strokes, merged into
  long polylines straight through the crossings (an interlaced design's under strands
  broken at their crossings, as its score lines are), on a layer ``strands`` in the band's
  colour; the tile's outline on a layer ``outline``; with ``[colour]``, each face colour's
  faces outlined on a layer of that colour's name;
- ``what="cut"``: the cutter's contours (the cut plan, in its cut order), one layer per
  cutter layer, named and coloured as in the laser SVG.

Its front ends: ``fabtiles plot`` (SVG, or HPGL through vpype), the vpype plugin
(:mod:`fabtiles.cli.vpype_plugin`) and the Inkscape extension.

>>> from fabtiles.designs.design_file import load_design
>>> drawing = plot_drawing(load_design("samples/rosette.toml"))
>>> [layer.name for layer in drawing.layers], drawing.pen_mm
(['strands', 'outline'], 0.3)
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..core.validate import check_choice, check_float
from ..machines import limits as _limits

WHATS = ("centrelines", "cut")
"""What a plot draws: the strands for a pen, or the cutter's contours."""

DEFAULT_PEN_MM = 0.3
"""A fine-liner's width (AxiDraw's own examples use 0.3 to 0.5 mm pens)."""

MAX_PEN_MM = 10.0


def check_plot_options(what: str, pen_mm) -> tuple[str, float]:
    """``(what, pen_mm)`` validated.

    >>> check_plot_options("cut", None)
    ('cut', 0.3)
    """
    what = check_choice("what", what, WHATS)
    pen = DEFAULT_PEN_MM if pen_mm is None else check_float("pen_mm", pen_mm, low=0, high=MAX_PEN_MM, low_open=True)
    return what, pen


def plot_drawing(design, *, what: str = "centrelines", pen_mm=None, limits: _limits.Limits = _limits.CLI_LIMITS):
    """The :class:`~fabtiles.geometry.pen.PenDrawing` of ``design`` (see the module's text).

    Raises :class:`~fabtiles.ParameterError` for a bad ``what`` or ``pen_mm`` and whatever
    the design's build raises (its limits, its cutter's checks for ``what="cut"``).
    """
    from ..geometry.pen import pen_drawing
    from .models import BuildOptions, Models
    from .pipeline import prepare_tile

    what, pen = check_plot_options(what, pen_mm)
    tile = prepare_tile(design, limits=limits)
    # the cut as one plan: a tile larger than the cutter's bed is refused as before, not drawn as pieces
    models = Models(tile, replace(BuildOptions.of_design(design), pieces=False))
    if what == "cut":
        from ..export.laser_svg import aci_to_hex

        (_, plan), *_ = models.cut.files()  # an inlay kit: its first file's, the lattice
        layers = [
            (
                layer.layer.name,
                aci_to_hex(layer.layer.color),
                [np.vstack([p, p[:1]]) if layer.closed else p for p in layer.paths],
            )
            for layer in plan.layers
        ]
        return pen_drawing(
            layers,
            bounds=plan.bounds,
            pen_mm=pen,
            order=False,
            stats={"what": what, "cut_travel_mm": round(plan.estimate.travel_mm, 3)},
        )
    from ..geometry.interlace import tile_score_lines
    from ..geometry.pen import strokes

    centrelines = tile_score_lines(tile)  # an interlaced tile's under strands broken (no region: a pen needs none)
    outline = tile.outline_shape()
    band = models.colouring.band.hex if models.coloured else "#000000"
    layers = [("strands", band, strokes(centrelines)), ("outline", "#000000", _rings(outline))]
    if models.coloured:
        by_colour: dict = {}
        classes = models.face_classes
        for c in classes.classes:
            colour = models.colouring.face(c.letter)
            _, rings = by_colour.setdefault(colour.hex, (colour.name, []))
            rings.extend(_rings(classes.of(c.letter)))
        layers += [(name, hex_, rings) for hex_, (name, rings) in by_colour.items()]
    x0, y0, x1, y1 = outline.bounds
    return pen_drawing(layers, bounds=(min(x0, 0.0), min(y0, 0.0), x1, y1), pen_mm=pen, stats={"what": what})


def _rings(geom) -> list:
    """Every ring of a (Multi)Polygon, closed (its first point repeated)."""
    import shapely  # here, not at the top: `fabtiles --help` imports this module for WHATS and no shapely

    rings = shapely.get_rings(shapely.get_parts(geom))
    return [np.asarray(shapely.get_coordinates(r)) for r in rings]
