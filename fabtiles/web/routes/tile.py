"""The tile of a query: its preview, inlay kit, 3D view, checks, design file and downloads."""

from __future__ import annotations

import anyio.from_thread
from fastapi import APIRouter, Request
from fastapi.responses import Response

from ...export.formats import design_formats
from ...machines import limits as _limits
from ..building import build, fabrication_checks
from ..params import QueryError, parse_flag

MEDIA_TYPES = {"toml": "application/toml"}

CLIENT_GONE = 499
"""The status of a request whose client went before its answer was built (nginx's "client closed
request"): the server sends nothing to a closed connection, the code is for the tests."""


class _ClientGone(Exception):
    """The client of a request has gone: the work for its answer stops."""


def _plain() -> dict:
    """The colours the pictures take when a design gives none: the preview's ink for the bands, the 3D
    view's plate, and the faces left open (the picture's white)."""
    from ...export.preview_svg import INK
    from ...solid.print_model import PART_MATERIALS

    linear = PART_MATERIALS["base"].colour
    srgb = [12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055 for c in linear]
    return {
        "band": {"colour": INK, "name": "ink"},
        "base": {"colour": "#" + "".join(f"{round(255 * c):02x}" for c in srgb), "name": "plate"},
        "face": {"colour": "#ffffff", "name": "open"},
    }


PLAIN = _plain()
"""What the pictures show of a design given no colours (``/api/faces``' ``plain``)."""


def _number(query, field: str):
    """A query's number (None when absent or empty); anything else a :class:`QueryError` naming it."""
    from ..params import parse_number as number

    text = query.get(field, "")
    return None if text == "" else number(field, text)


def router(*, limits: _limits.Limits) -> APIRouter:
    """``/api/preview.svg``, ``/api/faces``, ``/api/kit.svg``, ``/api/plot.svg``, ``/api/view.glb``, ``/api/checks``,
    ``/api/design.toml``, ``/api/export/{fmt}``."""
    api = APIRouter()

    @api.get("/api/preview.svg")
    def preview(request: Request):
        """The tile as SVG; ``findings=true`` marks each finding of the checks where it is."""
        show = parse_flag("findings", request.query_params.get("findings", "false"))
        _, spec, tile = build(request, limits=limits, view=("findings",))
        from ...making.views import tile_picture

        findings, made, pieces = None, False, None
        if show:
            from ...making.checks import check_design

            result = check_design(spec, tile)
            findings, made, pieces = result.findings(), result.made, result.split
        else:  # a tile larger than the cutter's bed: where it is cut into pieces
            from ...making.views import panel_seams

            pieces = panel_seams(tile, spec)
        # a router's or waterjet's part is drawn as its tool makes it (None: a laser's, the tile's own);
        # a coloured design's faces in their colours
        # whether the pictures are in the design's colours (else the plain ink and plate: /api/faces "plain")
        return Response(
            tile_picture(tile, spec, title=repr(tile), findings=findings, made=made, pieces=pieces),
            media_type="image/svg+xml",
            headers={"X-Fabtiles-Coloured": "true" if spec.colour.given else "false"},
        )

    @api.get("/api/faces")
    def faces(request: Request):
        """The design's face classes in their colours, and the bands' and the base's colour.

        ``{"band": {colour, name}, "base": {colour, name}, "classes": [{letter,
        count, description, area_mm2, colour, name}], "plain": ...}``: the classes as ``fabtiles
        check`` lists them, each colour as ``#rrggbb`` and its name (the palette's unless the query
        gives it); ``plain``, what the pictures show of a design given no colours (:data:`PLAIN`);
        ``names``, the palette colour names the design reads (``{"cobalt": "#1e4fa0", ...}``).
        """
        from ...making import BuildOptions, Models

        _, spec, tile = build(request, limits=limits)
        models = Models(tile, BuildOptions.of_design(spec))
        colours = models.colouring

        def named(c):
            return {"colour": c.hex, "name": c.name}

        classes = [{**c, **named(colours.face(c["letter"]))} for c in models.face_classes.stats()]
        from ...designs.colour import palette_names

        return {
            "band": named(colours.band),
            "base": named(colours.base),
            "classes": classes,
            "plain": PLAIN,
            "names": palette_names(spec.colour.palette),
        }

    @api.get("/api/kit.svg")
    def kit_picture(request: Request):
        """The design's inlay kit: the lattice, the pieces and the tile assembled, in two materials."""
        from ...export.preview_svg import kit_svg
        from ...making import inlay_kit_of

        _, spec, tile = build(request, limits=limits)
        return Response(
            kit_svg(inlay_kit_of(tile, spec), tile.outline_shape(), title=spec.name), media_type="image/svg+xml"
        )

    @api.get("/api/plot.svg")
    def plot_picture(request: Request):
        """The design as ``fabtiles plot`` draws it, the plot's own SVG: ``pen_mm`` (default 0.3);
        ``fill=true``: a layer per pen, each face class hatched in its colour (``hatch_mm``,
        ``angle`` (degrees, every class), ``cross``); without colours the fill is refused (422)."""
        from ...core.errors import ParameterError
        from ...export.plot_svg import svg_bytes
        from ...making.plot import plot_drawing

        view = ("fill", "pen_mm", "hatch_mm", "angle", "cross")
        q = request.query_params
        _, spec, _ = build(request, limits=limits, view=view)
        try:
            drawing = plot_drawing(
                spec,
                pen_mm=_number(q, "pen_mm"),
                fill=parse_flag("fill", q.get("fill", "false")),
                hatch_mm=_number(q, "hatch_mm"),
                angles_deg=_number(q, "angle"),
                cross=parse_flag("cross", q.get("cross", "false")),
                limits=limits,
            )
        except ParameterError as exc:  # the plot's own options: the answer names the field
            if exc.param not in view:
                raise
            raise QueryError(str(exc), exc.param) from None
        layers = ", ".join(f"{layer.name}: {len(layer.paths)}" for layer in drawing.layers)
        return Response(
            svg_bytes(drawing),
            media_type="image/svg+xml",
            headers={"X-Fabtiles-Pens": layers, "Cache-Control": "no-store"},
        )

    @api.get("/api/view.glb")
    async def view_glb(request: Request):
        """The print in 3D: the 3MF's checked parts, one glTF mesh each in its colour.

        The headers say what is shown (``X-Fabtiles-View``: the whole tile, or a big
        tile's centre) and the parts (``X-Fabtiles-Parts``, JSON). The browser drops a view
        it no longer wants (a newer design came) by closing its request: a request whose
        client has gone is not built, or stops between the build's stages, answered
        :data:`CLIENT_GONE` (which no one reads).
        """
        import json

        from starlette.concurrency import run_in_threadpool

        if await request.is_disconnected():
            return Response(status_code=CLIENT_GONE)

        def checkpoint():  # in the build's worker thread: asks the event loop whether the client is there
            if anyio.from_thread.run(request.is_disconnected):
                raise _ClientGone

        def view():
            from ...making import print_view

            _, spec, _ = build(request, limits=limits)
            return print_view(spec, limits=limits, checkpoint=checkpoint)

        try:  # the build in the thread pool, never on the event loop
            data, report = await run_in_threadpool(view)
        except _ClientGone:
            return Response(status_code=CLIENT_GONE)
        parts = {
            n: {"triangles": p["triangles"], "volume_mm3": round(p["volume_mm3"], 3)}
            for n, p in report.stats["parts"].items()
        }
        return Response(
            data,
            media_type="model/gltf-binary",
            headers={
                "X-Fabtiles-View": report.stats["view"],
                "X-Fabtiles-Parts": json.dumps(parts),
                "Cache-Control": "no-store",
            },
        )

    @api.get("/api/checks")
    def checks(request: Request):
        _, spec, tile = build(request, limits=limits)
        return fabrication_checks(tile, spec)

    @api.get("/api/design.toml")
    def design_toml(request: Request):
        design, spec, _ = build(request, limits=limits)
        import tomli_w

        formats = list(design_formats())
        if spec.surface.shape != "flat":  # the formats a cylinder or stamp is made in: its file builds as it is
            from ...making.cylinder import unmade_formats

            formats = [f for f in formats if f not in unmade_formats(formats, spec.surface.shape)]
        design = {**design, "output": {"formats": formats, **design.get("output", {})}}
        # named after the design, as its files are: the file's stem is their name when [output] name is unset
        text = f"# fabtiles design: build it with  fabtiles build {spec.name}.toml -o out\n"
        text += tomli_w.dumps(design)
        return Response(
            text,
            media_type=MEDIA_TYPES["toml"],
            headers={"Content-Disposition": f'attachment; filename="{spec.name}.toml"'},
        )

    @api.get("/api/export/{fmt}")
    def export(fmt: str, request: Request):
        offered = design_formats()  # the format table's, a plugin's included
        if fmt not in offered:
            raise QueryError(f"{fmt!r} is not a valid format, must be one of: {', '.join(offered)}", "format")
        from ...making import build_bytes

        _, spec, _ = build(request, limits=limits)
        # The build pipeline, as `fabtiles build`: the design's profiles and options, the limits.
        download = build_bytes(spec, fmt, limits=limits)  # an inlay kit's two files come as one zip
        return Response(
            download.data,
            media_type=download.media_type,
            headers={"Content-Disposition": f'attachment; filename="{download.file_name}"'},
        )

    return api
