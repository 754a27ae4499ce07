"""SVG preview of a tile: the material region filled (even-odd), the outline drawn.

True size in millimetres (``width="150mm"``), y axis flipped so the picture reads
like the file coordinates (y up). Coordinates are printed with fixed precision and
polygons in a fixed order, so the same tile gives the same bytes on every run.
"""

from __future__ import annotations

import numpy as np

from ..core.files import atomic_write
from ._text import attribute as _attr
from ._text import escape as _escape
from ._text import number

_DIGITS = 3  # 1 micrometre


def _num(x: float) -> str:
    return number(x, _DIGITS)


def _ring_path(coords, height: float) -> str:
    pts = np.asarray(coords, dtype=float)[:-1]  # shapely rings repeat the first point
    if len(pts) < 3:
        return ""
    parts = [f"{_num(x)} {_num(height - y)}" for x, y in pts]
    return "M" + "L".join(parts) + "Z"


def region_path_data(region, height: float) -> str:
    """SVG path data of a shapely (Multi)Polygon, one closed subpath per ring, y flipped.

    >>> from shapely.geometry import box
    >>> region_path_data(box(0, 0, 2, 1), height=1)
    'M2 1L2 0L0 0L0 1Z'
    """
    out = []
    for poly in getattr(region, "geoms", [region]):
        if poly.is_empty:
            continue
        out.append(_ring_path(poly.exterior.coords, height))
        out += [_ring_path(r.coords, height) for r in poly.interiors]
    return "".join(out)


MARK_COLOURS = {
    "small_hole": "#ff8c00",
    "thin_bridge": "#e6007e",
    "thin_wall": "#e6007e",
    "loose_part": "#00a651",
    "uncut_slit": "#00b7eb",
}
"""Stroke colour of each finding's marks (others: :data:`MARK_COLOUR`)."""
MARK_COLOUR = "#ffd400"


def findings_overlay(findings, height: float, *, mark_mm: float = 1.5) -> str:
    """SVG marks, one per location of each finding, in a ``<g class="findings">``.

    Each mark is a circle of class ``finding <code>`` with ``data-where`` (laser or
    print) and a ``<title>`` giving its size; y is flipped like the picture.

    Parameters
    ----------
    findings : iterable of (str, Finding)
        Where each finding comes from and the finding (see :meth:`fabtiles.making.checks.CheckResult.findings`).
    height : float
        Height of the picture (mm), to flip y.
    mark_mm : float
        Radius of a mark.

    >>> from fabtiles.core.report import Finding
    >>> f = Finding("small_hole", "1 hole", 1, ((2.0, 1.0),), (0.62,), 0.62)
    >>> print(findings_overlay([("laser", f)], 10))
    <g class="findings" fill="none" stroke-width="0.375">
    <circle class="finding small_hole" data-where="laser" cx="2" cy="9" r="1.5" stroke="#ff8c00"><title>small hole, 0.62 mm (laser)</title></circle>
    </g>
    """  # noqa: E501 - a doctest's lines are as Python prints them
    out = [f'<g class="findings" fill="none" stroke-width="{_num(mark_mm / 4)}">']
    for where, f in findings:
        colour = MARK_COLOURS.get(f.code, MARK_COLOUR)
        what = f.code.replace("_", " ")
        unit = "mm²" if f.unit == "mm^2" else f.unit
        for k, (x, y) in enumerate(f.locations):
            size = f", {f.sizes[k]:.3g} {unit}" if k < len(f.sizes) else ""
            out.append(
                f'<circle class="finding {_attr(f.code)}" data-where="{_attr(where)}" '
                f'cx="{_num(x)}" cy="{_num(height - y)}" r="{_num(mark_mm)}" stroke="{colour}">'
                f"<title>{_escape(what)}{size} ({_escape(where)})</title></circle>"
            )
    out.append("</g>")
    return "\n".join(out)


def pieces_overlay(pieces, width: float, height: float) -> str:
    """The seams (dashed) and numbers of a panel's pieces, in a ``<g class="pieces">``; y flipped.

    ``pieces`` has ``seams_x``, ``seams_y`` (mm) and ``numbers``, ``((number, x, y), ...)`` where
    each number goes (:class:`~fabtiles.making.checks.CheckResult`'s ``split``).

    >>> from types import SimpleNamespace
    >>> print(pieces_overlay(SimpleNamespace(seams_x=(50.0,), seams_y=(), numbers=((1, 25.0, 10.0),)), 100, 20))
    <g class="pieces" stroke="#c0392b" stroke-width="0.5" stroke-dasharray="2 1.2">
    <line x1="50" y1="0" x2="50" y2="20"/>
    <text x="25" y="10" font-size="8" text-anchor="middle" dominant-baseline="middle" stroke="none" fill="#c0392b">1</text>
    </g>
    """  # noqa: E501 - a doctest's lines are as Python prints them
    line = max(0.2, min(width, height) / 40)
    out = [
        f'<g class="pieces" stroke="#c0392b" stroke-width="{_num(line)}" '
        f'stroke-dasharray="{_num(4 * line)} {_num(2.4 * line)}">'
    ]
    out += [f'<line x1="{_num(x)}" y1="0" x2="{_num(x)}" y2="{_num(height)}"/>' for x in pieces.seams_x]
    out += [
        f'<line x1="0" y1="{_num(height - y)}" x2="{_num(width)}" y2="{_num(height - y)}"/>' for y in pieces.seams_y
    ]
    size = max(width, height) / 12.5
    out += [
        f'<text x="{_num(x)}" y="{_num(height - y)}" font-size="{_num(size)}" text-anchor="middle" '
        f'dominant-baseline="middle" stroke="none" fill="#c0392b">{n}</text>'
        for n, x, y in pieces.numbers
    ]
    out.append("</g>")
    return "\n".join(out)


INK = "#1f3b73"
"""The bands' colour in a picture of a design given no colours.

The print's second filament, as the 3D view shows it.
"""


def tile_svg(
    tile,
    *,
    fill: str = INK,
    outline_color: str = "#c0392b",
    background: str = "#ffffff",
    title: str | None = None,
    findings=None,
    region=None,
    faces=(),
    pieces=None,
) -> str:
    """An SVG picture of ``tile`` at true size: material filled, outline stroked.

    An interlaced tile is drawn woven: each band outlined, and stopped short
    (by its clearance) where it passes under another (see
    :func:`fabtiles.geometry.interlace.tile_drawing`).

    Parameters
    ----------
    tile : TileGeometry
    fill, outline_color, background : str
        SVG colours.
    title : str, optional
        ``<title>`` of the picture; defaults to ``repr(tile)``.
    findings : iterable of (str, Finding), optional
        Fabrication findings to mark where they are (see :func:`findings_overlay`).
    region : shapely geometry, optional
        The material to draw instead of the tile's own: a router's or waterjet's part
        as the tool makes it (:attr:`fabtiles.making.checks.CheckResult.made`, the holes opened).
    faces : sequence of (str, shapely geometry, str), optional
        The pattern's faces in colour, drawn under the material: ``(class letter, faces,
        colour)`` each (a coloured design, ``docs/colours.md``), as ``<path class="face-A">``.
    pieces : PiecesOverlay, optional
        A tile larger than the cutter's bed: the seams its pieces are cut along and their numbers,
        drawn over it (:func:`pieces_overlay`).

    Examples
    --------
    >>> from fabtiles.geometry.tile import TileGeometry
    >>> from fabtiles.pattern.star import Star
    >>> svg = tile_svg(TileGeometry("circle", 40, Star.preset("table1-part1"), frame=2))
    >>> 'width="40mm"' in svg and 'fill-rule="evenodd"' in svg
    True
    """
    w, h = tile.width_mm, tile.height_mm
    woven = getattr(tile, "interlace", False)
    if region is None and woven:
        from ..geometry.interlace import tile_drawing

        region = tile_drawing(tile)
    elif region is None:
        region = tile.region()
    d = region_path_data(region, h)
    # the bands' outlines: a tenth of the stroke
    band_edge = f'stroke="{_BAND_EDGE}" stroke-width="{_num(tile.stroke / 10)}"' if woven else 'stroke="none"'

    outline = region_path_data(tile.outline_shape(), h)
    coloured = "".join(
        f'<path class="face-{_attr(letter)}" d="{region_path_data(g, h)}" fill="{_attr(colour)}" '
        f'fill-rule="evenodd"/>\n'
        for letter, g, colour in faces
        if not g.is_empty
    )
    title = repr(tile) if title is None else title
    line = max(0.1, min(w, h) / 500)
    # marks 1 % of the tile's smaller side (1.5 mm on 150 mm), never under 0.5 mm
    marks = "" if findings is None else findings_overlay(findings, h, mark_mm=max(0.5, min(w, h) / 100)) + "\n"
    if pieces is not None:
        marks = pieces_overlay(pieces, w, h) + "\n" + marks
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(w)}mm" height="{_num(h)}mm" '
        f'viewBox="0 0 {_num(w)} {_num(h)}">\n'
        f"<title>{_escape(title)}</title>\n"
        f'<rect width="100%" height="100%" fill="{background}"/>\n'
        f"{coloured}"
        f'<path d="{d}" fill="{fill}" fill-rule="evenodd" {band_edge}/>\n'
        f'<path d="{outline}" fill="none" stroke="{outline_color}" stroke-width="{_num(line)}"/>\n'
        f"{marks}</svg>\n"
    )


_BAND_EDGE = "#0b1a3a"
"""Colour of a woven drawing's band outlines (darker than the default fill)."""


def write_tile_svg(path, tile, **options) -> None:
    """Write :func:`tile_svg` to ``path`` atomically."""
    atomic_write(path, tile_svg(tile, **options))


KIT_COLOURS = ("#e9c58f", "#6b3e1f")
"""The kit pictures' two materials: a light wood (the lattice) and a dark one (the pieces)."""


def kit_svg(kit, outline, *, title: str = "inlay kit", colours=KIT_COLOURS) -> str:
    """A picture of an inlay kit: the lattice, the pieces, the tile assembled, and the reverse tile.

    ``kit`` is a :class:`~fabtiles.geometry.inlay.InlayKit`; the four panels are at
    true size, a tenth of the tile's width apart. The assembled tile lays the pieces
    over the lattice in the second colour; the reverse tile is the same two files cut
    from the materials swapped.

    >>> import shapely
    >>> from fabtiles.geometry.inlay import inlay_kit
    >>> plate = shapely.box(0, 0, 30, 30).difference(shapely.box(5, 5, 25, 25))
    >>> svg = kit_svg(inlay_kit(plate, shapely.box(0, 0, 30, 30), fit_mm=0.1, min_piece_mm=2, kerf_mm=0.1),
    ...               shapely.box(0, 0, 30, 30))
    >>> svg.count('class="lattice"'), svg.count('class="pieces"')
    (3, 3)
    """
    import shapely

    xmin, ymin, xmax, ymax = outline.bounds
    w, h = xmax - xmin, ymax - ymin
    gap = w / 10
    pieces = shapely.union_all(kit.pieces) if len(kit.pieces) else shapely.Polygon()
    light, dark = colours

    def panel(k, body):
        dx = k * (w + gap) - xmin
        return f'<g transform="translate({_num(dx)} 0)">{body}</g>'

    def fill(region, cls, colour):
        d = region_path_data(region, ymax + ymin)
        return f'<path class="{cls}" d="{d}" fill="{colour}" fill-rule="evenodd" stroke="#333" stroke-width="0.1"/>'

    rim = region_path_data(outline, ymax + ymin)
    frame = f'<path d="{rim}" fill="none" stroke="#999" stroke-width="0.2" stroke-dasharray="1 1"/>'
    total = 4 * w + 3 * gap
    body = "".join(
        [
            panel(0, fill(kit.lattice, "lattice", light)),
            panel(1, frame + fill(pieces, "pieces", dark)),
            panel(2, fill(kit.lattice, "lattice", light) + fill(pieces, "pieces", dark)),
            panel(3, fill(kit.lattice, "lattice", dark) + fill(pieces, "pieces", light)),  # the materials swapped
        ]
    )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(total)}mm" height="{_num(h)}mm" '
        f'viewBox="0 0 {_num(total)} {_num(h)}">\n'
        f"<title>{_escape(title)}: lattice, pieces, assembled, reverse</title>\n"
        f"{body}\n</svg>\n"
    )


NEST_COLOURS = {
    "sheet": "#f3ead8",
    "part": "#d8b98a",
    "outer": "#b03a2e",
    "inner": "#1f3b73",
    "score": "#2e7d32",
    "engrave": "#555555",
}
"""The nested sheet's picture: the sheet, each part's outline, and its cut paths by role."""


def nested_sheet_svg(plan, parts, sheet_mm, *, title: str = "nested sheet") -> str:
    """A picture of one nested sheet, for a screen: the sheet, each part's outline, every cut path.

    The cut paths are drawn a pixel wide whatever the scale (``vector-effect``), since the
    sheet is shown much smaller than true size; an engraved layer is filled.

    Parameters
    ----------
    plan : CutPlan
        The sheet's cut plan (its layers, already placed).
    parts : list of (str, shapely Polygon)
        Each placed part's name and outline, drawn as ``<path class="part" data-part=name>``.
    sheet_mm : (float, float)
        The sheet's width and height, mm.
    title : str
        The picture's title.

    >>> import shapely
    >>> from fabtiles.geometry.cut_plan import CutOptions, plan_cut
    >>> plate = shapely.box(0, 0, 40, 40)
    >>> plan = plan_cut(plate, plate, CutOptions.of(profile="laser-3mm-plywood"))
    >>> svg = nested_sheet_svg(plan, [("a", shapely.box(0, 0, 40, 40))], (100, 50))
    >>> svg.count('class="part"'), 'viewBox="0 0 100 50"' in svg
    (1, True)
    """
    w, h = (float(v) for v in sheet_mm)
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(w)}mm" height="{_num(h)}mm" '
        f'viewBox="0 0 {_num(w)} {_num(h)}">\n<title>{_escape(title)}</title>\n',
        f'<rect class="sheet" x="0" y="0" width="{_num(w)}" height="{_num(h)}" fill="{NEST_COLOURS["sheet"]}" '
        'stroke="#888" stroke-width="1" vector-effect="non-scaling-stroke"/>\n',
    ]
    for name, outline in parts:
        out.append(
            f'<path class="part" data-part="{_attr(name)}" d="{region_path_data(outline, h)}" '
            f'fill="{NEST_COLOURS["part"]}" stroke="none"><title>{_escape(name)}</title></path>\n'
        )
    for layer in plan.layers:
        colour = NEST_COLOURS.get(layer.role, NEST_COLOURS["inner"])
        if layer.fill:
            paint = f'fill="{NEST_COLOURS["engrave"]}" fill-rule="evenodd" stroke="none"'
        else:
            paint = f'fill="none" stroke="{colour}" stroke-width="1" vector-effect="non-scaling-stroke"'
        rings = []
        for r in layer.paths:
            pts = np.asarray(r, dtype=float)
            if len(pts) < 2:
                continue
            d = "M" + "L".join(f"{_num(x)} {_num(h - y)}" for x, y in pts)
            rings.append(d + ("Z" if layer.closed or layer.fill else ""))
        if rings:
            out.append(f'<path class="cut {_attr(layer.role)}" d="{"".join(rings)}" {paint}/>\n')
    out.append("</svg>\n")
    return "".join(out)
