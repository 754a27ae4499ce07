"""The local web app: change the nine parameters, watch the tile, download it.

A FastAPI application. Every request's query is turned into a design
dictionary (:mod:`fabtiles.web.params`), checked against the work limits
before anything is built, and built through the same code as ``fabtiles
build``. Bad input answers 422 with ``{"error": ..., "field": ...}``, never 500.
No file path ever comes from a request: profiles are chosen by bundled name.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from fastapi import FastAPI, Request
from fastapi.responses import FileResponse, JSONResponse, Response

from .. import _limits
from .._errors import FabtilesError
from .._profiles import bundled_profiles
from ..export.formats import FILE_FORMATS as FORMATS
from ..pattern.presets import PRESET_NOTES, PRESETS
from .params import DEFAULTS, FIELDS, QueryError, design_from_query, parse_flag

STATIC = Path(__file__).with_name("static")

MEDIA_TYPES = {"toml": "application/toml"}


def _field_of(message: str) -> str | None:
    """The query field a library error message is about (the first known name in it)."""
    if "gap_motif" in message:
        return "gap_radii" if "radii" in message else "gap_n"
    kind = re.search(r"motifs(?: key|\]) '?(\d+)", message)  # a motif per polygon kind
    if kind and f"motif_{kind.group(1)}" in FIELDS:
        return f"motif_{kind.group(1)}"
    if "segments" in message and "limit" in message:
        return "radius"  # too much work: the packing radius is the usual knob
    if re.search(r"\[packing\] kind\b|packing=", message):
        return "packing"
    best = None
    for key, (section, name, _) in FIELDS.items():
        if section in ("gap_motif", "motifs") or key == "packing":
            continue
        for word in {key, name} - {"kind"}:
            m = re.search(rf"(?<![\w.\[]){re.escape(word)}(?![\w])", message)
            if m and (best is None or m.start() < best[0]):
                best = (m.start(), key)
    if best is None and re.search(r"\bsize\b|too small|mm on a side", message):
        return "width"
    if best is None and "segments" in message:
        return "radius"
    return best[1] if best else None


def tile_from_dict(design: dict, *, limits: _limits.Limits):
    """Validate a design dictionary and build its tile (no geometry yet) within the work limits."""
    from ..build import prepare_tile
    from ..design import design_from_dict

    spec = design_from_dict(design, name="fabtiles-tile", source="query")
    return spec, prepare_tile(spec, limits=limits)


def fabrication_checks(tile, spec) -> dict:
    """Laser and print checks of a tile with the design's profiles and options, as JSON."""
    from ..checks import check_design

    result = check_design(spec, tile, job=True)
    findings = [{"where": where, "code": f.code, "message": f.message, "count": f.count, "worst": f.worst,
                 "unit": f.unit} for where, f in result.findings()]
    region = tile.region()
    holes = sum(len(p.interiors) for p in getattr(region, "geoms", [region]))
    too_small = [f"{result.filled_holes:,} too small to cut"] if result.filled_holes else []
    too_small += [f"{result.print_filled_holes:,} too small to print"] if result.print_filled_holes else []
    filled = f" ({' and '.join(too_small)}, filled)" if too_small else ""
    summary = (f"{len(tile.segments()):,} segments, material {region.area:,.0f} mm², {holes:,} holes{filled}; "
               f"{len(findings)} finding{'s' if len(findings) != 1 else ''}")
    job = result.job.as_stats() if result.job is not None else None
    material = result.filament.as_stats() if result.filament is not None else None
    return {"findings": findings, "summary": summary, "filled_holes": result.filled_holes,
            "print_filled_holes": result.print_filled_holes, "job": job, "material": material,
            "cutter": result.cutter}


def field_of_param(param: str | None) -> str | None:
    """The query field of the design key an error names (its ``param``).

    A bare parameter name (an error raised after the design was read, while the tile
    is built) is the field of that name when exactly one field has it.

    >>> field_of_param("packing.gap_motif.n"), field_of_param("tile.size"), field_of_param("packing.kind")
    ('gap_n', 'width', 'packing')
    >>> field_of_param("interlace_gap_mm"), field_of_param("n")
    ('interlace_gap_mm', None)
    """
    if param and "." not in param:
        named = [key for key, (_, name, _) in FIELDS.items() if name == param]
        return named[0] if len(named) == 1 else None
    parts = (param or "").split(".")
    if len(parts) == 3 and parts[:2] in (["packing", "gap_motif"], ["packing", "motifs"]):
        parts = parts[1:]
    if len(parts) != 2:
        return None
    if parts == ["tile", "size"]:
        return "width"
    return next((key for key, (section, name, _) in FIELDS.items() if [section, name] == parts), None)


def _error(exc: Exception) -> JSONResponse:
    # The field from the error's parameter; reading the message is the fallback for the
    # few errors that name no single parameter.
    field = getattr(exc, "field", None) or field_of_param(getattr(exc, "param", None)) or _field_of(str(exc))
    return JSONResponse({"error": str(exc), "field": field}, status_code=422)


def _media(name: str) -> str | None:
    return ("text/javascript" if name.endswith(".js") else "text/css" if name.endswith(".css")
            else "text/html" if name.endswith(".html") else "text/plain" if name.isupper() else None)


def create_app(*, limits: _limits.Limits | None = None) -> FastAPI:
    """Build the FastAPI application (see ``fabtiles serve``)."""
    limits = limits or _limits.WEB_LIMITS
    app = FastAPI(title="fabtiles", docs_url="/api/docs", openapi_url="/api/openapi.json")

    def build(request: Request, *, view=()):
        query = dict(request.query_params)
        for key in view:  # parameters of the view, not of the design
            query.pop(key, None)
        base = dict(DEFAULTS)
        if ("n" in query or "radii" in query) and "preset" not in query:
            del base["preset"]  # the motif's own parameters replace the default preset
        if query.get("packing") in ("none", "archimedean"):
            del base["radius"]  # no packing radius (a tiling has an edge)
        design = design_from_query({**base, **query})
        spec, tile = tile_from_dict(design, limits=limits)
        return design, spec, tile

    @app.exception_handler(FabtilesError)
    async def fabtiles_error(request, exc):  # noqa: ARG001
        return _error(exc)

    @app.get("/", include_in_schema=False)
    def index():
        return FileResponse(STATIC / "index.html", media_type="text/html")

    @app.get("/favicon.ico", include_in_schema=False)
    def favicon():
        return Response(status_code=204)

    @app.get("/gallery", include_in_schema=False)
    def gallery_page():
        return FileResponse(STATIC / "gallery.html", media_type="text/html")

    @app.get("/static/{name}", include_in_schema=False)
    def static(name: str):
        path = STATIC / name
        if name not in {p.name for p in STATIC.iterdir() if p.is_file()}:
            return JSONResponse({"error": f"no static file {name!r}", "field": None}, status_code=404)
        return FileResponse(path, media_type=_media(name))

    @app.get("/static/vendor/three/{name:path}", include_in_schema=False)
    def viewer_file(name: str):
        """three.js, as ``fabtiles install-viewer`` put it in the package (only its listed modules)."""
        from .viewer_files import MODULES, VENDOR

        if name not in MODULES or not (VENDOR / name).is_file():
            return JSONResponse({"error": f"no viewer file {name!r}: run `fabtiles install-viewer`",
                                 "field": None}, status_code=404)
        return FileResponse(VENDOR / name, media_type=_media(name),
                            headers={"Cache-Control": "public, max-age=86400"})

    @app.get("/api/viewer")
    def viewer():
        """Whether the 3D view's library is installed, and its version."""
        from .viewer_files import VERSION, installed

        return {"installed": installed(), "three": VERSION,
                "install": "fabtiles install-viewer"}

    @app.get("/api/presets")
    def presets():
        return {name: {**dict(p), "radii": list(p["radii"]), "note": PRESET_NOTES[name]}
                for name, p in PRESETS.items()}

    @app.get("/api/tilings")
    def tilings():
        """The Archimedean tilings of packing=archimedean: name and polygon kinds (motif_<sides>)."""
        from ..pattern.tilings import NAMES, TILINGS, unit_cell

        return {t: {"name": NAMES[t], "kinds": sorted(set(unit_cell(t).sides.tolist()))} for t in TILINGS}

    @app.get("/api/profiles")
    def profiles():
        # the 2D cutters (lasers, routers, waterjets) share the laser menu: one key, laser_profile, takes them all
        return {"laser": list(bundled_profiles("laser")), "printer": list(bundled_profiles("printer"))}

    @app.get("/api/defaults")
    def defaults():
        return DEFAULTS

    @app.get("/api/preview.svg")
    def preview(request: Request):
        """The tile as SVG; ``findings=true`` marks each finding of the checks where it is."""
        show = parse_flag("findings", request.query_params.get("findings", "false"))
        _, spec, tile = build(request, view=("findings",))
        from ..export.preview_svg import tile_svg

        findings = None
        if show:
            from ..checks import check_design

            result = check_design(spec, tile)
            findings, made = result.findings(), result.made
        else:
            from ..build import made_region

            made = made_region(tile, spec)
        # a router's or waterjet's part is drawn as its tool makes it (None: a laser's, the tile's own)
        return Response(tile_svg(tile, findings=findings, region=made), media_type="image/svg+xml")

    @app.get("/api/kit.svg")
    def kit_picture(request: Request):
        """The design's inlay kit: the lattice, the pieces and the tile assembled, in two materials."""
        from ..build import inlay_kit_of
        from ..export.preview_svg import kit_svg

        _, spec, tile = build(request)
        return Response(kit_svg(inlay_kit_of(tile, spec), tile.outline_shape(), title=spec.name),
                        media_type="image/svg+xml")

    @app.get("/api/view.glb")
    def view_glb(request: Request):
        """The print in 3D: the 3MF's checked parts, one glTF mesh each in its colour.

        The headers say what is shown (``X-Fabtiles-View``: the whole tile, or a big
        tile's centre) and the parts (``X-Fabtiles-Parts``, JSON).
        """
        import json

        from ..build import print_view

        _, spec, _ = build(request)
        data, report = print_view(spec, limits=limits)
        parts = {n: {"triangles": p["triangles"], "volume_mm3": round(p["volume_mm3"], 3)}
                 for n, p in report.stats["parts"].items()}
        return Response(data, media_type="model/gltf-binary",
                        headers={"X-Fabtiles-View": report.stats["view"], "X-Fabtiles-Parts": json.dumps(parts),
                                 "Cache-Control": "no-store"})

    @app.get("/api/gallery")
    def gallery_list():
        """The gallery: the paper's presets and the tilings' samples, each with its editor query."""
        from .gallery import entries

        return [{"key": e.key, "title": e.title, "note": e.note, "query": e.query} for e in entries()]

    @app.get("/api/gallery/{key}.svg")
    def gallery_thumbnail(key: str):
        """One gallery entry drawn by the preview code (cached: drawn once per process)."""
        from .gallery import thumbnail

        return Response(thumbnail(key, limits=limits), media_type="image/svg+xml",
                        headers={"Cache-Control": "public, max-age=3600"})

    @app.get("/api/checks")
    def checks(request: Request):
        _, spec, tile = build(request)
        return fabrication_checks(tile, spec)

    @app.get("/api/design.toml")
    def design_toml(request: Request):
        design, spec, _ = build(request)
        import tomli_w

        design = {**design, "output": {"formats": list(FORMATS), **design.get("output", {})}}
        text = "# fabtiles design: build it with  fabtiles build fabtiles-design.toml -o out\n"
        text += tomli_w.dumps(design)
        return Response(text, media_type=MEDIA_TYPES["toml"],
                        headers={"Content-Disposition": 'attachment; filename="fabtiles-design.toml"'})

    @app.get("/api/export/{fmt}")
    def export(fmt: str, request: Request):
        if fmt not in FORMATS:
            raise QueryError(f"{fmt!r} is not a valid format, must be one of: {', '.join(FORMATS)}", "format")
        from ..build import build_bytes

        _, spec, _ = build(request)
        # The build pipeline, as `fabtiles build`: the design's profiles and options, the limits.
        download = build_bytes(spec, fmt, limits=limits)  # an inlay kit's two files come as one zip
        return Response(download.data, media_type=download.media_type,
                        headers={"Content-Disposition": f'attachment; filename="{download.file_name}"'})

    return app


def serve(host: str = "127.0.0.1", port: int = 8765) -> None:  # pragma: no cover - blocking
    """Run the app with uvicorn until interrupted."""
    import uvicorn

    uvicorn.run(create_app(), host=host, port=port, log_level=os.environ.get("FABTILES_LOG", "warning"))
