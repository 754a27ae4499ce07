"""Laser SVG: the DXF's contours and layers, as stroke colours, at true millimetre size.

For laser software that prefers SVG. One ``<g id="LAYER">`` per operation (score,
inner cuts, outer cut, in cut order), its stroke the RGB of the layer's ACI colour
(1 red ``#FF0000``, 5 blue ``#0000FF``, 6 magenta ``#FF00FF``, ...), no fill, hairline
stroke width. ``width``/``height`` are in mm and the viewBox is in mm, so one user
unit is one millimetre; the y axis is flipped so the picture looks like the DXF.
Coordinates are printed with 4 decimals (0.1 um), so the file is reproducible
byte for byte. Curves are SVG arcs (``A``), at most a half turn each, from the cut plan's
arcs (:mod:`fabtiles.geometry.arcs`).

A shaded engraving's SVG (a face class per layer, :mod:`fabtiles.geometry.shades`) also carries
MeerK40t's operations: one ``meerk40t:operation`` element per layer (in MeerK40t's namespace, so
browsers and Inkscape ignore it) with the layer's kind, power (per mille, as MeerK40t stores it),
speed, passes, raster resolution and the ``id`` of each of its paths. MeerK40t's SVG loader makes
those operations in place of classifying by colour, which would raster every fill together in one
operation at one power.
"""

from __future__ import annotations

import numpy as np

from ..geometry.arcs import subdivide
from ..geometry.cut_plan import CutPlan
from ._text import attribute as _escape
from ._text import number as _num

_QUARTER = np.tan(np.pi / 8) + 1e-12
"""The bulge of a quarter turn."""

MEERK40T_NAMESPACE = "https://github.com/meerk40t/meerk40t/wiki/Namespace"
"""The XML namespace of MeerK40t's own SVG elements (its ``core/svg_io.py``)."""

HAIRLINE_MM = 0.025
"""Stroke width of the paths (a 0.001 inch hairline: "cut, don't engrave" for most drivers)."""


_STANDARD_ACI = ("#FF0000", "#FFFF00", "#00FF00", "#00FFFF", "#0000FF", "#FF00FF", "#FFFFFF", "#808080", "#C0C0C0")
"""The nine standard AutoCAD colours (ACI 1 to 9), the ones laser layers use: an SVG or LightBurn
file of them needs no import of ezdxf (half a second of every such build, ``docs/speed.md``)."""


def aci_to_hex(color: int) -> str:
    """``#RRGGBB`` of an AutoCAD Color Index: the nine standard ones from a table, the rest from ezdxf's.

    >>> aci_to_hex(1), aci_to_hex(3), aci_to_hex(5), aci_to_hex(30)
    ('#FF0000', '#00FF00', '#0000FF', '#FF7F00')
    """
    if 1 <= color <= len(_STANDARD_ACI):
        return _STANDARD_ACI[color - 1]
    from ezdxf.colors import aci2rgb

    r, g, b = aci2rgb(color)
    return f"#{r:02X}{g:02X}{b:02X}"


def _path_data(curve, flip: float, closed: bool) -> str:
    """SVG path data of a :class:`~fabtiles.geometry.arcs.Curve`: lines, and its arcs as ``A`` commands.

    y is flipped (``flip - y``), which turns a counter-clockwise arc (bulge > 0) into
    SVG's negative-angle direction: sweep-flag 0. No piece turns more than a quarter turn
    (:func:`~fabtiles.geometry.arcs.subdivide`), so the large-arc flag is 0.

    >>> import numpy as np
    >>> from fabtiles.geometry.arcs import Curve
    >>> _path_data(Curve(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 0.0])), 0.0, True)
    'M1 0A1 1 0 0 0 0 -1A1 1 0 0 0 -1 0Z'
    """
    if not curve[1].any():
        pts = [f"{_num(x)} {_num(flip - y)}" for x, y in curve[0].tolist()]
        return "M" + "L".join(pts) + ("Z" if closed else "")
    # quarter turns at most: the 4 decimals of a half turn's radius would move its centre by 0.01 mm
    xy, bulge = curve
    if np.abs(bulge).max() > _QUARTER:  # (a router's corners are quarter turns: most paths skip this)
        xy, bulge = subdivide(curve, max_sweep=np.pi / 2, closed=closed)
    pts = [f"{_num(x)} {_num(flip - y)}" for x, y in xy.tolist()]
    n = len(pts)
    nxt = np.roll(xy, -1, axis=0)
    chord = np.hypot(*(nxt - xy).T)
    with np.errstate(divide="ignore", invalid="ignore"):
        radius = chord * (1 + bulge * bulge) / (4 * np.abs(bulge))
    out = ["M", pts[0]]
    for k in range(1, n + (1 if closed else 0)):
        b = bulge[k - 1]
        to = pts[k % n]
        if b:
            out.append(f"A{_num(radius[k - 1])} {_num(radius[k - 1])} 0 0 {0 if b > 0 else 1} {to}")
        elif k < n:  # a straight closing edge: Z draws it
            out.append("L" + to)
    if closed:
        out.append("Z")
    return "".join(out)


def _layer_path_data(curves, closed: bool) -> list:
    """:func:`_path_data` of each of ``curves``, the arcs' radii of all of them in one pass.

    Quicker than path by path on a panel's thousands of paths (``docs/speed.md``).
    """
    curves = _quarter_arcs(curves, closed)
    if not curves:
        return []
    sizes = np.array([len(c.xy) for c in curves])
    xy = np.concatenate([c.xy for c in curves])
    b = np.concatenate([c.bulge for c in curves])
    starts = np.cumsum(sizes) - sizes
    nxt = np.arange(len(xy)) + 1
    nxt[starts + sizes - 1] = starts
    chord = np.hypot(*(xy[nxt] - xy).T)
    with np.errstate(divide="ignore", invalid="ignore"):
        radius = np.where(b != 0, chord * (1 + b * b) / (4 * np.abs(b)), 0.0)
    pts = [f"{_num(x)} {_num(-y)}" for x, y in xy.tolist()]
    rad = [_num(v) if v else "" for v in radius.tolist()]
    bl = b.tolist()
    out = []
    for s0, n in zip(starts.tolist(), sizes.tolist(), strict=True):
        p = pts[s0 : s0 + n]
        if not any(bl[s0 : s0 + n]):
            out.append("M" + "L".join(p) + ("Z" if closed else ""))
        else:
            out.append(_arc_path_data(p, bl[s0 : s0 + n], rad[s0 : s0 + n], closed))
    return out


def _quarter_arcs(curves, closed: bool) -> list:
    """``curves`` with every arc over a quarter turn cut into arcs of at most a quarter (SVG's small-arc flag)."""
    return [
        c
        if not c.bulge.any() or np.abs(c.bulge).max() <= _QUARTER
        else subdivide(c, max_sweep=np.pi / 2, closed=closed)
        for c in curves
    ]


def _arc_path_data(p: list, bl: list, rad: list, closed: bool) -> str:
    """The path data of one path with arcs: its points ``p`` as text, each vertex's bulge ``bl`` and
    the radius ``rad`` (text) of the arc leaving it."""
    n = len(p)
    d = ["M", p[0]]
    for k in range(1, n + (1 if closed else 0)):
        bk = bl[k - 1]
        if bk:
            r = rad[k - 1]
            d.append(f"A{r} {r} 0 0 {0 if bk > 0 else 1} {p[k % n]}")
        elif k < n:
            d.append("L" + p[k])
    if closed:
        d.append("Z")
    return "".join(d)


def svg_text(job: CutPlan) -> str:
    """The laser SVG of a cut plan, as text: one group per layer, in cut order (and, shaded,
    MeerK40t's operation of each layer, see the module's docstring)."""
    xmin, ymin, xmax, ymax = job.bounds
    w, h = xmax - xmin, ymax - ymin
    shaded = _shaded(job)
    xmlns = f' xmlns:meerk40t="{MEERK40T_NAMESPACE}"' if shaded else ""
    head = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg"{xmlns} width="{_num(w)}mm" height="{_num(h)}mm" '
        f'viewBox="{_num(xmin)} {_num(-ymax)} {_num(w)} {_num(h)}">\n'
        f"<title>{_title(job)}</title>\n"
    )
    out = [head]
    ids: list = []  # a shaded file's path ids, a list per layer, for MeerK40t's operations
    prefix = _path_id_prefix([cut.layer.name for cut in job.layers])
    for cut in job.layers:
        layer = cut.layer
        if cut.fill:  # an engraved fill: each polygon one path, its holes as subpaths, filled even-odd
            out.append(
                f'<g id="{_escape(layer.name)}" fill="{aci_to_hex(layer.color)}" fill-rule="evenodd" stroke="none">\n'
            )
            polys: dict = {}
            for r, p in zip(cut.curves_or_paths(), cut.groups, strict=True):
                polys.setdefault(p, []).append(_path_data(r, 0.0, True))
            paths = ["".join(d) for d in polys.values()]
        else:
            out.append(
                f'<g id="{_escape(layer.name)}" fill="none" stroke="{aci_to_hex(layer.color)}" '
                f'stroke-width="{_num(HAIRLINE_MM)}">\n'
            )
            paths = _layer_path_data(cut.curves_or_paths(), cut.closed)
        if shaded:
            first = sum(len(i) for i in ids) + 1
            ids.append([f"{prefix}{k}" for k in range(first, first + len(paths))])
            out.extend(f'<path id="{i}" d="{d}"/>\n' for i, d in zip(ids[-1], paths, strict=True))
        else:
            out.extend(f'<path d="{d}"/>\n' for d in paths)
        out.append("</g>\n")
    if shaded:
        out.extend(_meerk40t_operation(cut, i) for cut, i in zip(job.layers, ids, strict=True))
    out.append("</svg>\n")
    return "".join(out)


def _path_id_prefix(layer_names) -> str:
    """The prefix of a shaded file's path ids (``p1``, ``p2``, ...): ``p``, or ``p_``, ``p__``, ... when a
    layer's name, its group's id, would read as one of them.

    >>> _path_id_prefix(["SHADE_A", "CUT"]), _path_id_prefix(["p3", "p_12"])
    ('p', 'p__')
    """
    prefix = "p"
    while any(n.startswith(prefix) and n[len(prefix) :].isdigit() for n in layer_names):
        prefix += "_"
    return prefix


def _shaded(job: CutPlan) -> bool:
    """Whether ``job`` is a shaded engraving: a fill layer other than the profile's engrave layer."""
    return any(cut.fill and cut.layer != job.profile.layers.engrave for cut in job.layers)


def _meerk40t_operation(cut, ids: list) -> str:
    """MeerK40t's operation of one layer: a raster for a fill (its line interval as a resolution in
    dots per inch), an engrave for open score lines, a cut for contours; its paths by ``id``."""
    layer = cut.layer
    if cut.fill:
        interval = layer.line_interval_mm
        kind, extra = "op raster", f' dpi="{round(25.4 / interval)}"' if interval else ""
    else:
        kind, extra = ("op cut" if cut.closed else "op engrave"), ""
    if layer.passes > 1:  # MeerK40t runs an operation once unless its passes are marked custom
        extra += f' passes="{layer.passes}" passes_custom="True"'
    return (
        f'<meerk40t:operation type="{kind}" label="{_escape(layer.name)}" color="{aci_to_hex(layer.color)}" '
        f'speed="{_num(layer.speed_mm_s)}" power="{_num(layer.power_pct * 10)}"{extra} references="{" ".join(ids)}"/>\n'
    )


def svg_bytes(plan: CutPlan) -> bytes:
    """The laser SVG of ``plan``, as bytes to write."""
    return svg_text(plan).encode("utf-8")


def _title(job: CutPlan) -> str:
    """The picture's title: the laser's mode and kerf, or what a router's or waterjet's file holds."""
    p = job.profile
    return p.cutter.title(p, job.mode, job.kerf_mm, num=_num, escape=_escape)
