"""A design as a pen plotter draws it: the drawing every plotting front end writes.

:func:`plot_drawing` makes a :class:`~fabtiles.geometry.pen.PenDrawing` of a design:

- ``what="centrelines"`` (a pen): the pattern's strands as single strokes, merged into
  long polylines straight through the crossings (an interlaced design's under strands
  broken at their crossings, as its score lines are), on a layer ``strands`` in the band's
  colour; the tile's outline on a layer ``outline``; with ``[colour]``, each face colour's
  faces outlined on a layer of that colour's name;
- with ``fill=True`` (``what="centrelines"``, a design with ``[colour]``): one layer per pen,
  that is per distinct colour, named after the colour and what it draws (``"white (strands,
  outline)"``, ``"cobalt (A, C)"``): the band colour's pen draws the strands and the outline,
  each face class's colour hatches that class's faces (:mod:`fabtiles.geometry.hatch`: lines
  ``hatch_mm`` apart, by default the pen's width so neighbouring strokes touch, at an angle per
  class, optionally cross-hatched), the strokes clipped inside each face shrunk by half the
  pen's width, so no ink crosses the strapwork; each layer ordered for a short pen-up travel;
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

from ..core.errors import ParameterError
from ..core.validate import check_choice, check_float
from ..machines import limits as _limits

WHATS = ("centrelines", "cut")
"""What a plot draws: the strands for a pen, or the cutter's contours."""

DEFAULT_PEN_MM = 0.3
"""A fine-liner's width (AxiDraw's own examples use 0.3 to 0.5 mm pens)."""

MAX_PEN_MM = 10.0

ANGLES_DEG = (45.0, 135.0, 0.0, 90.0, 22.5, 112.5, 67.5, 157.5)
"""The hatch angles of classes A, B, C, ... by default (then again from the first): distinct for
eight classes, the first four the furthest apart, so neighbouring faces read as different."""

MIN_HATCH_PENS = 0.1
"""The closest hatch lines, in pen widths: ten strokes on one line's width is no longer hatching
(and the plot's strokes grow tenfold)."""


def check_plot_options(what: str, pen_mm) -> tuple[str, float]:
    """``(what, pen_mm)`` validated.

    >>> check_plot_options("cut", None)
    ('cut', 0.3)
    """
    what = check_choice("what", what, WHATS)
    pen = DEFAULT_PEN_MM if pen_mm is None else check_float("pen_mm", pen_mm, low=0, high=MAX_PEN_MM, low_open=True)
    return what, pen


def angles_from_text(values) -> dict:
    """``--angle`` values (``"30"``: every class; ``"B=60"``: class B) as :func:`plot_drawing`'s
    ``angles_deg`` (``""`` the key of every class).

    >>> angles_from_text(["30", "B=60.5"])
    {'': 30.0, 'B': 60.5}
    """
    out = {}
    for text in values:
        letter, _, number = str(text).rpartition("=")
        letter = letter.strip().upper()
        try:
            out[letter] = float(number)
        except ValueError:
            raise ParameterError(
                f"angle must be degrees (30) or a class and degrees (B=60), got {text!r}", param="angle"
            ) from None
    return out


def plot_drawing(
    design,
    *,
    what: str = "centrelines",
    pen_mm=None,
    fill: bool = False,
    hatch_mm=None,
    angles_deg=None,
    cross: bool = False,
    limits: _limits.Limits = _limits.CLI_LIMITS,
):
    """The :class:`~fabtiles.geometry.pen.PenDrawing` of ``design`` (see the module's text).

    Parameters
    ----------
    what, pen_mm
        What is drawn (:data:`WHATS`) and the pen's width (default :data:`DEFAULT_PEN_MM`).
    fill : bool
        Hatch each face in its class's colour, a layer per pen (``what="centrelines"``, a design
        with ``[colour]``).
    hatch_mm : float, optional
        The distance between hatch lines (default the pen's width: the strokes touch), from a
        tenth of the pen's width to the largest face's size.
    angles_deg : float or dict, optional
        The hatch lines' angle in degrees from the x axis: one for every class, or a dict of class
        letters (``""`` for every class) to angles; default :data:`ANGLES_DEG` in class order.
    cross : bool
        Cross-hatch: a second set of lines at right angles to the first.

    Raises :class:`~fabtiles.ParameterError` for a bad ``what`` or ``pen_mm``, for ``fill`` with
    ``what="cut"`` or on a design without colours, a hatch spacing out of its range, an angle
    that is not a number or a letter no class has; and whatever the design's build raises (its
    limits, its cutter's checks for ``what="cut"``).
    """
    from ..geometry.pen import pen_drawing
    from .models import BuildOptions, Models
    from .pipeline import prepare_tile

    what, pen = check_plot_options(what, pen_mm)
    if fill and what != "centrelines":
        raise ParameterError(
            f"fill hatches the faces of a pen's drawing: what must be centrelines, got {what!r}", param="fill"
        )
    if fill and not design.colour.given:
        raise ParameterError(
            "fill needs the design's colours: add a [colour] section (docs/colours.md), "
            "e.g. --set colour.by=shape for the faces classed by shape in the zellige palette",
            param="fill",
        )
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
    if fill:
        return _filled(models, centrelines, outline, pen, hatch_mm=hatch_mm, angles_deg=angles_deg, cross=cross)
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


def _filled(models, centrelines, outline, pen: float, *, hatch_mm, angles_deg, cross: bool):
    """The drawing with ``fill``: a layer per pen, the band's strands and outline and the classes'
    hatching, each layer ordered (see :func:`plot_drawing`)."""
    from ..geometry.cut_order import order_paths
    from ..geometry.hatch import hatch, hatch_order
    from ..geometry.pen import join_ordered, pen_drawing, strokes

    classes, colouring = models.face_classes, models.colouring
    spacing = _check_hatch(hatch_mm, pen, classes.faces)
    angle_of = _class_angles(angles_deg, [c.letter for c in classes.classes])
    band = colouring.band
    lines = order_paths({"score": strokes(centrelines) + _rings(outline)}, thorough=True)["score"]
    pens: dict = {band.hex: (band.name, ["strands", "outline"], [lines])}
    bare = []  # the classes no line fits in: faces narrower than the pen or the spacing
    for k, c in enumerate(classes.classes):
        h = hatch(
            classes.faces[classes.labels == k],
            spacing_mm=spacing,
            angle_deg=angle_of[c.letter],
            inset_mm=pen / 2,
            cross=cross,
        )
        if not len(h.segments):
            bare.append(c.letter)
            continue
        colour = colouring.face(c.letter)
        _, what, groups = pens.setdefault(colour.hex, (colour.name, [], []))
        what.append(c.letter)
        groups.append(hatch_order(h))
    layers = [
        (f"{name} ({', '.join(what)})", hex_, join_ordered(groups)) for hex_, (name, what, groups) in pens.items()
    ]
    x0, y0, x1, y1 = outline.bounds
    stats = {
        "what": "centrelines",
        "fill": {"hatch_mm": spacing, "angles_deg": angle_of, "cross": bool(cross), "not_hatched": bare},
    }
    return pen_drawing(layers, bounds=(min(x0, 0.0), min(y0, 0.0), x1, y1), pen_mm=pen, stats=stats, order=False)


def _check_hatch(hatch_mm, pen: float, faces) -> float:
    """The hatch spacing (default ``pen``), checked: from a tenth of the pen's width (a spacing
    finer draws no more colour, only more strokes) to the largest face's size (the longer side of
    its bounding box: a spacing beyond it leaves every face with one line at most)."""
    import shapely

    if hatch_mm is None:
        return pen
    b = shapely.bounds(np.asarray(faces, dtype=object)) if len(faces) else np.zeros((1, 4))
    largest = float(np.max(np.maximum(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]))) if len(b) else 0.0
    low = MIN_HATCH_PENS * pen
    value = check_float("hatch_mm", hatch_mm)
    if not low <= value <= largest:
        raise ParameterError(
            f"hatch_mm must be from {low:.4g} (a tenth of the {pen:g} mm pen) to {largest:.4g} mm "
            f"(the largest face's size), got {value:g}",
            param="hatch_mm",
        )
    return value


def _class_angles(angles, letters: list) -> dict:
    """Each class letter's hatch angle (degrees): ``angles`` (a number, or letters to numbers, ``""``
    every class) over :data:`ANGLES_DEG`."""
    if angles is None:
        given: dict = {}
    elif isinstance(angles, dict):
        given = dict(angles)
    else:
        given = {"": angles}
    for letter in given:
        if letter and letter not in letters:
            raise ParameterError(
                f"angle's class {letter!r} is not one of this design's face classes ({', '.join(letters)})",
                param="angle",
            )
    out = {}
    for k, letter in enumerate(letters):
        value = given.get(letter, given.get("", ANGLES_DEG[k % len(ANGLES_DEG)]))
        try:
            out[letter] = check_float(f"angle of class {letter}", value)
        except ParameterError as exc:
            raise ParameterError(str(exc), param="angle") from None
    return out
