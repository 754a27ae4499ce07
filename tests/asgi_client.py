"""A synchronous client of the web app in-process, through httpx's ASGI transport.

Starlette's ``TestClient`` is deprecated with httpx (it wants the httpx2 package);
httpx's own :class:`httpx.ASGITransport` serves the app without a server, so the web
tests call the app the way httpx documents, one event loop per request, run in a thread
of its own (a browser test's Playwright may hold the test's thread's loop).
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import anyio
import httpx


class TestClient:
    """``get``, ``post``, ``request`` on an ASGI ``app``, returning :class:`httpx.Response`; an
    exception the app raises is raised here, as Starlette's client does."""

    __test__ = False  # not a test class, though its name starts with Test

    def __init__(self, app, base_url: str = "http://testserver"):
        self.app = app
        self.base_url = base_url

    def request(self, method: str, url: str, **kwargs) -> httpx.Response:
        async def send():
            transport = httpx.ASGITransport(app=self.app)
            async with httpx.AsyncClient(transport=transport, base_url=self.base_url) as client:
                response = await client.request(method, url, **kwargs)
                await response.aread()
                return response

        with ThreadPoolExecutor(max_workers=1) as pool:
            return pool.submit(anyio.run, send).result()

    def get(self, url: str, **kwargs) -> httpx.Response:
        return self.request("GET", url, **kwargs)

    def post(self, url: str, **kwargs) -> httpx.Response:
        return self.request("POST", url, **kwargs)


def asgi_get(app, url: str, receive) -> list[dict]:
    """The ASGI messages ``app`` sends for a GET of ``url`` whose client's messages come from ``receive``
    (an ``async`` callable): a client that goes away at a chosen moment, which httpx's transport
    cannot be."""
    path, _, query = url.partition("?")
    scope = {
        "type": "http",
        "asgi": {"version": "3.0"},
        "http_version": "1.1",
        "method": "GET",
        "scheme": "http",
        "path": path,
        "raw_path": path.encode(),
        "query_string": query.encode(),
        "root_path": "",
        "headers": [(b"host", b"testserver")],
        "client": ("127.0.0.1", 50000),
        "server": ("testserver", 80),
    }
    sent: list[dict] = []

    async def send(message):
        sent.append(message)

    with ThreadPoolExecutor(max_workers=1) as pool:
        pool.submit(anyio.run, app, scope, receive, send).result()
    return sent
