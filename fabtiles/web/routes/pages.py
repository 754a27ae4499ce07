"""The pages, their static files and the 3D view's library (three.js, when installed)."""

from __future__ import annotations

from pathlib import Path

from fastapi import APIRouter
from fastapi.responses import FileResponse, JSONResponse, Response

STATIC = Path(__file__).resolve().parents[1] / "static"


def media_type(name: str) -> str | None:
    """The media type of a static file, by its name."""
    return (
        "text/javascript"
        if name.endswith(".js")
        else "text/css"
        if name.endswith(".css")
        else "text/html"
        if name.endswith(".html")
        else "text/plain"
        if name.isupper()
        else None
    )


def router() -> APIRouter:
    """``/``, ``/gallery``, ``/nest``, ``/favicon.ico``, ``/static/...`` and ``/api/viewer``."""
    api = APIRouter()

    @api.get("/", include_in_schema=False)
    def index():
        return FileResponse(STATIC / "index.html", media_type="text/html")

    @api.get("/favicon.ico", include_in_schema=False)
    def favicon():
        return Response(status_code=204)

    @api.get("/gallery", include_in_schema=False)
    def gallery_page():
        return FileResponse(STATIC / "gallery.html", media_type="text/html")

    @api.get("/nest", include_in_schema=False)
    def nest_page():
        return FileResponse(STATIC / "nest.html", media_type="text/html")

    @api.get("/static/{name}", include_in_schema=False)
    def static(name: str):
        path = STATIC / name
        if name not in {p.name for p in STATIC.iterdir() if p.is_file()}:
            return JSONResponse({"error": f"no static file {name!r}", "field": None}, status_code=404)
        return FileResponse(path, media_type=media_type(name))

    @api.get("/static/vendor/three/{name:path}", include_in_schema=False)
    def viewer_file(name: str):
        """three.js, as ``fabtiles install-viewer`` put it in the package (only its listed modules)."""
        from ..viewer_files import MODULES, VENDOR

        if name not in MODULES or not (VENDOR / name).is_file():
            return JSONResponse(
                {"error": f"no viewer file {name!r}: run `fabtiles install-viewer`", "field": None}, status_code=404
            )
        return FileResponse(
            VENDOR / name, media_type=media_type(name), headers={"Cache-Control": "public, max-age=86400"}
        )

    @api.get("/api/viewer")
    def viewer():
        """Whether the 3D view's library is installed, and its version."""
        from ..viewer_files import VERSION, installed

        return {"installed": installed(), "three": VERSION, "install": "fabtiles install-viewer"}

    return api
