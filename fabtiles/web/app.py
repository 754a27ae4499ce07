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
import tempfile
from pathlib import Path

from fastapi import FastAPI, Request
from fastapi.responses import FileResponse, JSONResponse, Response

from .. import _limits
from .._errors import FabtilesError
from .._profiles import bundled_profiles
from ..export.dispatch import FORMATS, profile_kind
from ..pattern.presets import PRESET_NOTES, PRESETS
from .params import DEFAULTS, FIELDS, QueryError, design_from_query

STATIC = Path(__file__).with_name("static")

MEDIA_TYPES = {
    "dxf": "image/vnd.dxf",
    "svg": "image/svg+xml",
    "stl": "model/stl",
    "3mf": "model/3mf",
    "step": "model/step",
    "toml": "application/toml",
}


def _field_of(message: str) -> str | None:
    """The query field a library error message is about (its first known name)."""
    best = None
    for key in FIELDS:
        names = {key, FIELDS[key][1]} if FIELDS[key][0] != "gap_motif" else {key}
        for name in names:
            m = re.search(rf"(?<![\w.\[]){re.escape(name)}(?![\w])", message)
            if m and (best is None or m.start() < best[0]):
                best = (m.start(), key)
    if best is None and "size" in message:
        return "width"
    return best[1] if best else None


def _error(exc: Exception) -> JSONResponse:
    field = getattr(exc, "field", None) or _field_of(str(exc))
    return JSONResponse({"error": str(exc), "field": field}, status_code=422)


def create_app(*, limits: _limits.Limits | None = None) -> FastAPI:
    """Build the FastAPI application (see ``fabtiles serve``)."""
    limits = limits or _limits.WEB_LIMITS
    app = FastAPI(title="fabtiles", docs_url="/api/docs", openapi_url="/api/openapi.json")

    def build(request: Request):
        query = dict(request.query_params)
        base = dict(DEFAULTS)
        if ("n" in query or "radii" in query) and "preset" not in query:
            del base["preset"]  # the motif's own parameters replace the default preset
        if query.get("packing") == "none":
            del base["radius"]
        design = design_from_query({**base, **query})
        from ..design import tile_from_dict

        tile = tile_from_dict(design, limits=limits)
        return design, tile

    @app.exception_handler(FabtilesError)
    async def fabtiles_error(request, exc):  # noqa: ARG001
        return _error(exc)

    @app.get("/", include_in_schema=False)
    def index():
        return FileResponse(STATIC / "index.html", media_type="text/html")

    @app.get("/static/{name}", include_in_schema=False)
    def static(name: str):
        path = STATIC / name
        if name not in {p.name for p in STATIC.iterdir()}:
            return JSONResponse({"error": f"no static file {name!r}", "field": None}, status_code=404)
        media = "text/javascript" if name.endswith(".js") else "text/css" if name.endswith(".css") else None
        return FileResponse(path, media_type=media)

    @app.get("/api/presets")
    def presets():
        return {name: {**dict(p), "radii": list(p["radii"]), "note": PRESET_NOTES[name]}
                for name, p in PRESETS.items()}

    @app.get("/api/profiles")
    def profiles():
        names = bundled_profiles()
        return {"laser": [n for n in names if n.startswith("laser")],
                "printer": [n for n in names if not n.startswith("laser")]}

    @app.get("/api/defaults")
    def defaults():
        return DEFAULTS

    @app.get("/api/preview.svg")
    def preview(request: Request):
        _, tile = build(request)
        from ..export.preview_svg import tile_svg

        return Response(tile_svg(tile), media_type="image/svg+xml")

    @app.get("/api/checks")
    def checks(request: Request):
        design, tile = build(request)
        from ..design import fabrication_checks

        return fabrication_checks(tile, design)

    @app.get("/api/design.toml")
    def design_toml(request: Request):
        design, _ = build(request)
        from ..design import design_to_toml

        return Response(design_toml_text := design_to_toml(design), media_type=MEDIA_TYPES["toml"],
                        headers={"Content-Disposition": 'attachment; filename="fabtiles-design.toml"',
                                 "Content-Length": str(len(design_toml_text.encode()))})

    @app.get("/api/export/{fmt}")
    def export(fmt: str, request: Request):
        if fmt not in FORMATS:
            raise QueryError(f"{fmt!r} is not a valid format, must be one of: {', '.join(FORMATS)}", "format")
        design, tile = build(request)
        output = design.get("output", {})
        if profile_kind(fmt) == "laser":
            profile = output.get("laser_profile")
            options = {"mode": output.get("laser_mode")}
        else:
            profile = output.get("printer_profile")
            options = {"style": output.get("print_style")}
        if profile is not None and profile not in bundled_profiles():
            raise QueryError(
                f"profile {profile!r} does not exist; choose one of: {', '.join(bundled_profiles())}",
                "laser_profile" if profile_kind(fmt) == "laser" else "printer_profile",
            )
        _limits.check_export(tile, fmt, limits)
        with tempfile.TemporaryDirectory(prefix="fabtiles-web-") as tmp:
            path = Path(tmp) / f"fabtiles-tile.{fmt}"
            tile.export(path, profile=profile, **options)
            data = path.read_bytes()
        return Response(data, media_type=MEDIA_TYPES[fmt],
                        headers={"Content-Disposition": f'attachment; filename="fabtiles-tile.{fmt}"'})

    return app


def serve(host: str = "127.0.0.1", port: int = 8765) -> None:  # pragma: no cover - blocking
    """Run the app with uvicorn until interrupted."""
    import uvicorn

    uvicorn.run(create_app(), host=host, port=port, log_level=os.environ.get("FABTILES_LOG", "warning"))
