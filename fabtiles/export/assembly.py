"""A panel's assembly: the drawing a builder prints and the manifest a program reads.

Both are pure functions of a pieces model (:class:`~fabtiles.making.pieces.PanelPieces`, or any
model with the same records: ``pieces`` each with ``number``, ``cell``, ``matrix`` (3 x 3, mm,
its file to the panel), ``region`` (in the panel) and ``size_mm``; ``split`` with ``grid``,
``seams_x``, ``seams_y``, ``joints`` and ``joint``; ``groups``, ``outline`` and ``profile``),
so a printer's pieces are described alike.

- :func:`assembly_svg`: the panel with its pieces' material, each piece's number at its middle,
  the seams dashed and the joints marked, scaled to fit an A4 sheet landscape (the scale is
  written under the drawing).
- :func:`manifest`: ``<name>-assembly.json``: the panel, the bed and profile, the grid and seams;
  for each piece its number, files, cell, matrix, size; for each joint its two pieces and where;
  the groups of congruent pieces.
"""

from __future__ import annotations

import json

import numpy as np
import shapely

from ._text import attribute, number

PAGE_MM = (277.0, 190.0)
"""The drawing's largest extent (mm): an A4 sheet landscape less 10 mm margins."""

MANIFEST_VERSION = 1
"""The manifest's ``version``: raised when a field changes meaning."""


def _num(v: float) -> str:
    return number(v, 2)


def _path_d(geom) -> str:
    """An SVG path's ``d`` of a (Multi)Polygon's rings (even-odd fill keeps the holes open)."""
    out = []
    for ring in shapely.get_rings(shapely.get_parts(geom)):
        xy = shapely.get_coordinates(ring)[:-1]
        if len(xy) < 3:
            continue
        out.append("M" + " L".join(f"{_num(x)} {_num(y)}" for x, y in xy) + " Z")
    return " ".join(out)


def assembly_svg(model, *, title: str = "") -> bytes:
    """The assembly drawing of ``model``: the panel's pieces, numbered, the seams dashed.

    The panel's y axis points up as in its files; the drawing flips it so the top of the panel is at
    the top of the page, where piece 1 is.
    """
    x0, y0, x1, y1 = model.outline.bounds
    w, h = x1 - x0, y1 - y0
    scale = min(PAGE_MM[0] / w, PAGE_MM[1] / (h + 0.12 * h))
    pad = 0.04 * max(w, h)
    vw, vh = w + 2 * pad, h + 2 * pad + 0.1 * h
    fills = ("#e8d8b8", "#c9b48a")
    font = max(w, h) / 20
    flip = f"matrix(1 0 0 -1 {_num(pad - x0)} {_num(pad + y1)})"
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(vw * scale)}mm" height="{_num(vh * scale)}mm" '
        f'viewBox="0 0 {_num(vw)} {_num(vh)}">',
        f"<title>{attribute(title or 'assembly')}</title>",
        f'<g transform="{flip}" stroke-linejoin="round">',
        f'<path d="{_path_d(model.outline)}" fill="none" stroke="#999" stroke-width="{_num(w / 600)}"/>',
    ]
    simple = max(w, h) / 3000  # a drawing to print: a third of a millimetre on a 1 m panel is finer than ink
    for p in model.pieces:
        i, j = p.cell
        lines.append(
            f'<path id="piece-{p.number}" d="{_path_d(_drawn(p.region, simple))}" fill="{fills[(i + j) % 2]}" '
            f'fill-rule="evenodd" stroke="#5a4a2a" stroke-width="{_num(w / 1500)}"/>'
        )
    dash = f'stroke-dasharray="{_num(font / 3)} {_num(font / 5)}"'
    for x in model.split.seams_x:
        lines.append(
            f'<line x1="{_num(x)}" y1="{_num(y0)}" x2="{_num(x)}" y2="{_num(y1)}" stroke="#c0392b" '
            f'stroke-width="{_num(w / 500)}" {dash}/>'
        )
    for y in model.split.seams_y:
        lines.append(
            f'<line x1="{_num(x0)}" y1="{_num(y)}" x2="{_num(x1)}" y2="{_num(y)}" stroke="#c0392b" '
            f'stroke-width="{_num(w / 500)}" {dash}/>'
        )
    for joint in model.split.joints:
        lines.append(f'<path d="{_path_d(joint.tab)}" fill="#c0392b" stroke="none"/>')
    lines.append("</g>")
    for p in model.pieces:
        cx, cy = _middle(p.region)
        lines.append(
            f'<text x="{_num(pad + cx - x0)}" y="{_num(pad + y1 - cy)}" font-family="sans-serif" '
            f'font-size="{_num(font)}" font-weight="bold" text-anchor="middle" dominant-baseline="middle" '
            f'fill="#1b1b1b" stroke="#fff" stroke-width="{_num(font / 12)}" paint-order="stroke">{p.number}</text>'
        )
    bw, bh = model.profile.bed_mm
    gx, gy = model.split.grid
    captions = (
        f"{title + ': ' if title else ''}{_num(w)} x {_num(h)} mm panel in {len(model.pieces)} pieces ({gx} x {gy}) "
        f"for the {_num(bw)} x {_num(bh)} mm bed of {model.profile.kind} profile {model.profile.name}",
        f"seams dashed, joints in red, pieces numbered from the top left along the rows; scale 1:{_num(1 / scale)}",
    )
    size = min(font / 2.5, vw / max(len(c) for c in captions) * 1.6)
    for k, caption in enumerate(captions):
        lines.append(
            f'<text x="{_num(pad)}" y="{_num(h + 2 * pad + size * (1.3 * k + 1))}" font-family="sans-serif" '
            f'font-size="{_num(size)}" fill="#333">{attribute(caption)}</text>'
        )
    lines.append("</svg>")
    return ("\n".join(lines) + "\n").encode()


def _drawn(region, tolerance: float):
    """A piece as the drawing shows it: simplified within ``tolerance``, its holes smaller than a
    disc of 5 ``tolerance`` across left out (too small to see printed; the files hold them)."""
    small = (5 * tolerance) ** 2
    parts = [
        shapely.Polygon(p.exterior, [r for r in p.interiors if shapely.Polygon(r).area >= small])
        for p in shapely.get_parts(region)
    ]
    return shapely.simplify(shapely.MultiPolygon(parts), tolerance)


def _middle(region) -> tuple[float, float]:
    """Where a piece's number goes in the drawing: the middle of its bounding box."""
    x0, y0, x1, y1 = region.bounds
    return (x0 + x1) / 2, (y0 + y1) / 2


def manifest(model, files: dict, *, name: str) -> bytes:
    """``<name>-assembly.json`` of ``model``; ``files`` maps each piece's number to its files' names.

    Each piece's ``matrix`` (3 x 3, mm, row-major) carries a point of its file to its place in the
    panel: ``panel = matrix @ [x, y, 1]``.
    """
    x0, y0, x1, y1 = model.outline.bounds
    split = model.split
    joint = split.joint
    profile = model.profile
    # dict(...) of keywords: the manifest's own field names, which the design's keys do not declare
    data = dict(
        version=MANIFEST_VERSION,
        name=name,
        panel_mm=[round(x1 - x0, 3), round(y1 - y0, 3)],
        bed_mm=list(profile.bed_mm),
        bed_margin_mm=profile.margin_mm,
        profile=dict(name=profile.name, kind=profile.kind),
        grid=list(split.grid),
        seams_x=[round(v, 3) for v in split.seams_x],
        seams_y=[round(v, 3) for v in split.seams_y],
        joint=joint.figures(),
        pieces=[
            dict(
                number=p.number,
                files=list(files.get(p.number, ())),
                cell=list(p.cell),
                matrix=[[round(float(v), 6) + 0.0 for v in row] for row in np.asarray(p.matrix)],
                size_mm=[round(v, 3) for v in p.size_mm],
            )
            for p in model.pieces
        ],
        joints=[dict(pieces=list(j.pieces), at=[round(v, 3) for v in j.at]) for j in split.joints],
        congruent=[list(g) for g in model.groups],
    )
    return (json.dumps(data, indent=1) + "\n").encode()
