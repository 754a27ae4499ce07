"""The web app's pen plot: ``/api/plot.svg`` as ``fabtiles plot`` draws it, and the page's *Pen plot* box."""

from __future__ import annotations

import re
from urllib.parse import unquote

import pytest

pytest.importorskip("fastapi")

from asgi_client import TestClient

from fabtiles.web.app import create_app

SMALL = "preset=table3-3&width=40&radius=10&frame=3"


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def layers(svg: str) -> list:
    """``(label, stroke)`` of each Inkscape layer of an SVG."""
    return re.findall(r'inkscape:label="([^"]*)" fill="none" stroke="(#[0-9a-f]{6})"', svg)


def test_plot_is_the_strands_and_with_fill_a_layer_per_pen(client):
    r = client.get(f"/api/plot.svg?{SMALL}&pen_mm=0.5")
    assert r.status_code == 200 and r.headers["content-type"].startswith("image/svg+xml")
    assert [name for name, _ in layers(r.text)] == ["strands", "outline"] and 'stroke-width="0.5"' in r.text
    r = client.get(f"/api/plot.svg?{SMALL}&colour_by=shape&palette=iznik&fill=true&cross=true&hatch_mm=0.5&angle=30")
    assert r.status_code == 200, r.text
    got = layers(r.text)
    assert got[0] == ("white (strands, outline)", "#f5f1e8") and ("cobalt (A)", "#1e4fa0") in got
    assert r.headers["X-Fabtiles-Pens"].startswith("white (strands, outline): ")


@pytest.mark.parametrize(
    "query, field, message",
    [
        ("&fill=true", "fill", "fill needs the design's colours"),
        ("&colour_by=shape&fill=true&hatch_mm=0.01", "hatch_mm", "hatch_mm must be from 0.03"),
        ("&colour_by=shape&fill=true&angle=steep", "angle", "angle must be a number, got 'steep'"),
        ("&pen_mm=0", "pen_mm", "pen_mm must be a finite number > 0"),
        ("&fill=maybe", "fill", "fill must be true or false"),
    ],
)
def test_bad_plot_options_answer_422_naming_the_field(client, query, field, message):
    r = client.get(f"/api/plot.svg?{SMALL}{query}")
    assert r.status_code == 422 and r.json()["field"] == field and message in r.json()["error"], r.text


@pytest.mark.browser
def test_the_page_draws_the_plot_with_its_pens(page, server):
    page.goto(f"{server}/?{SMALL}&colour_by=shape&palette=iznik")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.get_attribute("#plot", "src") is None  # drawn only once the box is opened
    page.click("#plot-box summary")
    page.wait_for_function("() => !document.querySelector('#plot').hidden")
    names = [n for n, _ in layers(unquote(page.get_attribute("#plot", "src")))]
    assert names[:2] == ["strands", "outline"] and "cobalt" in names  # the faces' outlines, a layer per colour
    page.check("#plot-fill")
    page.wait_for_function("() => (document.querySelector('#plot').src || '').includes('cobalt%20(A)')")
    assert ("cobalt (A)", "#1e4fa0") in layers(unquote(page.get_attribute("#plot", "src")))
    assert "cobalt (A): " in page.text_content("#plot-caption")
