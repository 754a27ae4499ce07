"""docs/web-app.md cannot drift from the app: every route in its table, the formats, the default radius."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import tomllib

pytest.importorskip("fastapi")

from fabtiles.export.formats import FILE_FORMATS
from fabtiles.web.app import create_app
from fabtiles.web.params import DEFAULTS

ROOT = Path(__file__).resolve().parents[2]
PAGE = (ROOT / "docs" / "web-app.md").read_text(encoding="utf-8")


def _routes(routes):
    """``(method, path)`` of every route, included routers' too (``{name:path}`` written ``{name}``)."""
    for r in routes:
        if hasattr(r, "path"):
            for method in sorted(set(getattr(r, "methods", None) or ()) - {"HEAD"}):
                yield method, re.sub(r"\{(\w+):\w+\}", r"{\1}", r.path)
        else:  # an included router, kept whole by newer FastAPI versions
            yield from _routes(getattr(r, "original_router", r).routes)


ROUTES = sorted(set(_routes(create_app().routes)))


def _table() -> list[str]:
    """The routes of the page's table, as written: ``GET /api/checks``."""
    return [re.sub(r"\?…$", "", m) for m in re.findall(r"^\| `(\w+ [^`]+)` \|", PAGE, re.M)]


def test_the_app_has_routes():
    assert len(ROUTES) >= 20 and ("GET", "/api/export/{fmt}") in ROUTES


@pytest.mark.parametrize("method, path", ROUTES)
def test_every_route_is_in_the_manual(method, path):
    assert f"{method} {path}" in _table()


def test_the_manual_lists_no_route_the_app_lacks():
    assert sorted(set(_table()) - {f"{m} {p}" for m, p in ROUTES}) == []


def test_every_download_format_is_in_the_manual():
    line = next(row for row in PAGE.splitlines() if row.startswith("| `GET /api/export/{fmt}"))
    assert [f for f in FILE_FORMATS if f"`{f}`" not in line] == []
    assert "LightBurn" in line


def test_the_default_radii_stated_are_the_apps_and_the_samples():
    sample = tomllib.loads((ROOT / "samples" / "table3-3.toml").read_text(encoding="utf-8"))
    web, ours = float(DEFAULTS["radius"]), float(sample["packing"]["radius"])
    assert web != ours  # else the paragraph explaining the difference is to go
    assert f"with\nR = {web:g} mm" in PAGE or f"with R = {web:g} mm" in PAGE
    assert f"has R = {ours:g} mm" in PAGE
    assert f"`?radius={ours:g}`" in PAGE


def test_the_3d_views_size_and_figures_stated_are_the_apps():
    """The default tile's 3D view (web-app.md's table, the README) and its checks' filament line are
    what the app answers: the GLB's kB and triangles, the grams and metres."""
    import json

    from asgi_client import TestClient

    client = TestClient(create_app())
    view = client.get("/api/view.glb")
    assert view.status_code == 200
    triangles = sum(p["triangles"] for p in json.loads(view.headers["X-Fabtiles-Parts"]).values())
    kb = f"{len(view.content) / 1000:.0f} kB"
    assert re.search(rf"^\| default 150 mm square, relief \| [\d,]+ \| {kb} \| {triangles:,} \|$", PAGE, re.M), (
        kb,
        triangles,
    )
    readme = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    assert f"{triangles:,} triangles, {kb} for the 150 mm default tile" in readme
    material = client.get("/api/checks").json()["material"]["line"]
    assert f'("{material}",' in " ".join(PAGE.split())
