"""A border on the web: the form's controls from the schema, the preview, the fit in the checks, a bad
width named on its field, the design file."""

import pytest
from asgi_client import TestClient

from fabtiles.designs.design_file import design_from_text
from fabtiles.web.app import create_app


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


BORDER = {"preset": "table3-3", "radius": "8", "width": "60", "frame": "2", "border_mm": "8", "border_motif": "hankin"}


def test_the_schema_offers_the_border_keys(client):
    fields = client.get("/api/schema").json()["fields"]
    assert {"border_mm", "border_motif", "border_angle"} <= set(fields)
    assert fields["border_motif"]["key"] == "tile.border_motif" and fields["border_mm"]["widget"]["kind"] == "slider"
    assert [c[0] if isinstance(c, list) else c for c in fields["border_motif"]["choices"]] == ["stars", "hankin"]


def test_a_bordered_preview_and_its_fit(client):
    r = client.get("/api/preview.svg", params=BORDER)
    assert r.status_code == 200 and r.text.count("<path") >= 1
    checks = client.get("/api/checks", params=BORDER).json()
    assert any(line.startswith("tile.border_mm: 5 x 5 repeats of 8 x 8 mm") for line in checks["fitted"])


@pytest.mark.parametrize(
    ("change", "words"),
    [({"border_mm": "30"}, "border_mm must be >= 0 and <= 18.67 mm"), ({"border_motif": "star"}, "did you mean")],
)
def test_a_bad_border_names_its_field(client, change, words):
    r = client.get("/api/preview.svg", params={**BORDER, **change})
    assert r.status_code == 422 and r.json()["field"] == next(iter(change)) and words in r.json()["error"]


def test_the_design_file_keeps_the_border(client):
    text = client.get("/api/design.toml", params=BORDER).text
    assert "border_mm = 8" in text and 'border_motif = "hankin"' in text
    assert design_from_text(text).build_tile().border().fit.repeats == (5, 5)


def test_page_border_controls(page, server):
    from test_browser import _preview_version, _wait_new_preview

    page.goto(f"{server}/?preset=table3-3&width=60&radius=8&frame=2&border_mm=8")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.locator("#border_mm-row").is_visible() and page.locator("#border_angle").is_hidden()
    page.wait_for_function("() => document.querySelector('#status').textContent.includes('tile.border_mm')")
    assert "tile.border_mm: 5 x 5 repeats of 8 x 8 mm" in page.locator("#status").inner_text()
    assert "border_mm=8" in page.url
    v = _preview_version(page)
    page.select_option("#border_motif", "hankin")
    _wait_new_preview(page, v)
    assert page.locator("#border_angle").is_visible() and "border_motif=hankin" in page.url
    assert page.locator(".err:visible").count() == 0
