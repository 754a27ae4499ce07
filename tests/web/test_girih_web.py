"""packing=girih on the web: the preview, a bad pattern named on its field, the design file."""

import pytest
from asgi_client import TestClient

from fabtiles import GirihPacking
from fabtiles.designs.design_file import design_from_text
from fabtiles.web.app import create_app


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


GIRIH = {"packing": "girih", "girih_pattern": "hexagons", "edge": "10", "width": "60", "frame": "3"}


def test_girih_preview(client):
    r = client.get("/api/preview.svg", params=GIRIH)
    assert r.status_code == 200 and r.text.count("<path") >= 1


def test_unknown_girih_pattern_names_its_field(client):
    r = client.get("/api/preview.svg", params={**GIRIH, "girih_pattern": "hexagon"})
    assert r.status_code == 422 and r.json()["field"] == "girih_pattern"
    assert "did you mean 'hexagons'?" in r.json()["error"]


def test_a_subdivided_pattern_previews_and_a_level_too_deep_names_its_field(client):
    r = client.get("/api/preview.svg", params={**GIRIH, "girih_level": "2"})
    assert r.status_code == 200 and r.text.count("<path") >= 1
    r = client.get("/api/preview.svg", params={**GIRIH, "girih_level": "9"})
    assert r.status_code == 422 and r.json()["field"] == "girih_level"
    assert "girih_level = 9 would make" in r.json()["error"] and "the deepest level it takes is 5" in r.json()["error"]
    text = client.get("/api/design.toml", params={**GIRIH, "girih_level": "2"}).text
    assert design_from_text(text).build_tile().pattern == GirihPacking("hexagons", edge=10, level=2)


def test_design_toml_download_builds_the_same_packing(client):
    text = client.get("/api/design.toml", params=GIRIH).text
    assert 'kind = "girih"' in text and 'girih_pattern = "hexagons"' in text
    assert design_from_text(text).build_tile().pattern == GirihPacking("hexagons", edge=10)


def test_page_girih_menu_and_controls(page, server):
    from test_browser import _preview_version, _wait_new_preview

    page.goto(f"{server}/?preset=table3-3&width=60&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.locator("#girih_pattern").is_hidden()
    v = _preview_version(page)
    page.select_option("#packing", "girih")
    _wait_new_preview(page, v)
    assert page.locator("#girih_pattern").is_visible() and page.locator("#edge-row").is_visible()
    assert page.locator("#radius-row").is_hidden() and page.locator("#gap_n-row").is_hidden()
    assert page.locator("#motif-box").is_hidden()  # the strapwork is the pattern: no motif to set
    assert page.locator("#outline_circles").is_hidden() and page.locator("#seamless").is_visible()
    assert "packing=girih" in page.url and "girih_pattern=decagon-bowtie" in page.url and "gap_n" not in page.url
    v = _preview_version(page)
    page.select_option("#girih_pattern", "rhombi")
    _wait_new_preview(page, v)
    assert "girih_pattern=rhombi" in page.url and page.locator(".err:visible").count() == 0
    assert page.locator("#girih_level").is_visible()
    v = _preview_version(page)
    page.select_option("#girih_pattern", "hexagons")
    _wait_new_preview(page, v)
    v = _preview_version(page)
    page.fill("#girih_level", "2")
    page.dispatch_event("#girih_level", "change")
    _wait_new_preview(page, v)
    assert "girih_level=2" in page.url and page.locator(".err:visible").count() == 0
    v = _preview_version(page)
    page.select_option("#packing", "hex")  # the level is the girih packing's own: not sent with another
    _wait_new_preview(page, v)
    assert "girih_level" not in page.url and page.locator("#girih_level").is_hidden()
    assert page.locator("#motif-box").is_visible()
