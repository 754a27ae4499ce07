"""A pen plotter's files of a :class:`~fabtiles.geometry.pen.PenDrawing`: SVG, a vpype document, HPGL.

The SVG is at true size (``width``/``height`` in mm, one user unit a millimetre, the
y axis flipped so it looks like the laser SVG), one Inkscape layer per pen
(``inkscape:groupmode="layer"``, ``inkscape:label`` the layer's name, which vpype's
``read`` and AxiDraw's Inkscape extension take as the layer), each stroke one
``<path>`` in the layer's colour, as wide as the pen, round caps.
:func:`vpype_document` gives the same layers as a vpype ``Document`` (in vpype's CSS
pixels, ``vp_name``, ``vp_color``, ``vp_pen_width`` set) and :func:`hpgl_bytes` writes
it with vpype's own HPGL writer; both need vpype (``pip install 'fabtiles[vpype]'``).
"""

from __future__ import annotations

from ..core.errors import ParameterError
from ._text import attribute
from ._text import number as _num

PX_PER_MM = 96 / 25.4
"""vpype's unit is the CSS pixel, 1/96 inch."""


def svg_text(drawing) -> str:
    """The drawing as SVG text (see the module's text).

    >>> import numpy as np
    >>> from fabtiles.geometry.pen import PenDrawing, PenLayer
    >>> d = PenDrawing((PenLayer("strands", "#000000", (np.array([[0, 0], [10, 5.0]]),)),), (0, 0, 10, 5), 0.3)
    >>> print(svg_text(d).splitlines()[-3])
    <path d="M0 5 L10 0"/>
    """
    x0, y0, x1, y1 = drawing.bounds
    w, h = x1 - x0, y1 - y0
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" '
        f'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="{_num(w)}mm" '
        f'height="{_num(h)}mm" viewBox="0 0 {_num(w)} {_num(h)}">',
    ]
    for k, layer in enumerate(drawing.layers, start=1):
        name = attribute(layer.name)
        out.append(
            f'<g id="layer{k}" inkscape:groupmode="layer" inkscape:label="{name}" fill="none" '
            f'stroke="{layer.colour}" stroke-width="{_num(drawing.pen_mm)}" stroke-linecap="round" '
            f'stroke-linejoin="round">'
        )
        for p in layer.paths:
            pts = [f"{_num(x - x0)} {_num(y1 - y)}" for x, y in p.tolist()]
            out.append(f'<path d="M{pts[0]} L{" ".join(pts[1:])}"/>')
        out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def svg_bytes(drawing) -> bytes:
    return svg_text(drawing).encode()


def need_vpype(what: str):
    """vpype, or a :class:`~fabtiles.ParameterError` that says how to install it."""
    try:
        import vpype
    except ImportError:
        raise ParameterError(
            f"{what} needs vpype, which is not installed: pip install 'fabtiles[vpype]'", param="format"
        ) from None
    return vpype


def vpype_document(drawing, document=None):
    """The drawing's layers added to a vpype ``Document`` (a new one by default), each a new layer.

    Coordinates in vpype's pixels, y down (as in the SVG); the page the drawing's size.
    """
    vp = need_vpype("a vpype document")
    doc = vp.Document() if document is None else document
    x0, y0, x1, y1 = drawing.bounds
    for layer in drawing.layers:
        lines = vp.LineCollection(
            [((p[:, 0] - x0) + 1j * (y1 - p[:, 1])) * PX_PER_MM for p in layer.paths],
            metadata={
                vp.METADATA_FIELD_NAME: layer.name,
                vp.METADATA_FIELD_COLOR: vp.Color(layer.colour),
                vp.METADATA_FIELD_PEN_WIDTH: drawing.pen_mm * PX_PER_MM,
            },
        )
        doc.add(lines, doc.free_id(), with_metadata=True)
    if doc.page_size is None:
        doc.page_size = ((x1 - x0) * PX_PER_MM, (y1 - y0) * PX_PER_MM)
    return doc


HPGL_DEVICE = "hp7475a"
"""The HPGL device of vpype's built-in configurations the file is written for (AxiDraw users
write SVG; HPGL is for the classic pen plotters vpype knows)."""


def hpgl_bytes(drawing, *, device: str = HPGL_DEVICE, page: str = "a4") -> bytes:
    """The drawing as HPGL, by vpype's writer, for ``device`` on ``page`` (a size its config knows)."""
    vp = need_vpype("HPGL")
    import io

    doc = vpype_document(drawing)
    buf = io.StringIO()
    vp.write_hpgl(
        buf,
        doc,
        page_size=page,
        landscape=doc.page_size[0] > doc.page_size[1],
        center=False,
        device=device,
        velocity=None,
        quiet=True,
    )
    return buf.getvalue().encode()
