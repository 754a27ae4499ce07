"""The local web app: change the parameters, watch the tile, download it.

A FastAPI application made of four routers (:mod:`fabtiles.web.routes`): the
pages and static files, the catalogue the form is made from (the schema of the
design keys, presets, tilings, profiles, the gallery), the tile's answers
(preview, checks, downloads), and the nest (several designs on the cutter's
sheets). Every request's query is turned into a design dictionary (:mod:`fabtiles.web.params`), checked against the
work limits before
anything is built, and built through the same code as ``fabtiles build``. Bad
input answers 422 with ``{"error": ..., "field": ...}``, never 500; the field
comes from the error's key. No file path ever comes from a request: profiles are
chosen by bundled name.
"""

from __future__ import annotations

import contextlib
import os

from fastapi import FastAPI

from ..core.errors import FabtilesError
from ..machines import limits as _limits
from .building import error_response, fabrication_checks, field_of_param, tile_from_dict
from .routes import catalogue, nest, pages, tile
from .routes.pages import STATIC
from .routes.tile import MEDIA_TYPES

__all__ = [
    "MEDIA_TYPES",
    "STATIC",
    "create_app",
    "fabrication_checks",
    "field_of_param",
    "local_server",
    "serve",
    "tile_from_dict",
]


def create_app(*, limits: _limits.Limits | None = None) -> FastAPI:
    """Build the FastAPI application (see ``fabtiles serve``) with ``limits`` (default: the web's)."""
    limits = limits or _limits.WEB_LIMITS
    # the API's pages under /api, and no others: no ReDoc copy, no OAuth (the app has no login)
    app = FastAPI(
        title="fabtiles",
        docs_url="/api/docs",
        openapi_url="/api/openapi.json",
        redoc_url=None,
        swagger_ui_oauth2_redirect_url=None,
    )

    @app.exception_handler(FabtilesError)
    async def fabtiles_error(request, exc):
        return error_response(exc)

    app.include_router(pages.router())
    app.include_router(catalogue.router(limits=limits))
    app.include_router(tile.router(limits=limits))
    app.include_router(nest.router(limits=limits))
    return app


def serve(host: str = "127.0.0.1", port: int = 8765) -> None:  # pragma: no cover - blocking
    """Run the app with uvicorn until interrupted."""
    import uvicorn

    uvicorn.run(create_app(), host=host, port=port, log_level=os.environ.get("FABTILES_LOG", "warning"))


@contextlib.contextmanager
def local_server(*, start_timeout_s: float = 10.0):
    """The app on a free loopback port, served from a thread while the block runs: yields its URL.

    For scripts that drive the app in a browser (the tests, the manual's screenshots). Only
    127.0.0.1: nothing beyond this machine reaches it.

    >>> import urllib.request
    >>> with local_server() as url:
    ...     urllib.request.urlopen(f"{url}/api/schema").status
    200
    """
    import socket
    import threading
    import time

    import uvicorn

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    server = uvicorn.Server(uvicorn.Config(create_app(), host="127.0.0.1", port=port, log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + start_timeout_s
    while not server.started and time.monotonic() < deadline:
        time.sleep(0.05)
    try:
        yield f"http://127.0.0.1:{port}"
    finally:
        server.should_exit = True
        thread.join(timeout=10)
