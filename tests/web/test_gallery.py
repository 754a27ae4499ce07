"""The gallery: every entry opens the design its sample holds, drawn once by the preview code."""

from pathlib import Path

import pytest

from fastapi.testclient import TestClient

from fabtiles._limits import WEB_LIMITS
from fabtiles.design import load_design
from fabtiles.pattern.presets import PRESETS
from fabtiles.pattern.tilings import TILINGS
from fabtiles.web import gallery
from fabtiles.web.app import create_app, tile_from_dict
from fabtiles.web.params import design_from_query

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_presets_then_tilings():
    keys = [e.key for e in gallery.entries()]
    assert keys == [*PRESETS, *gallery._TILINGS] and set(keys[len(PRESETS):]) == set(TILINGS)
    assert len(keys) == 18


@pytest.mark.parametrize("tiling", sorted(TILINGS))
def test_tiling_entry_is_its_sample(tiling):
    _, tile = tile_from_dict(design_from_query(gallery.entry(tiling).query), limits=WEB_LIMITS)
    sample = load_design(SAMPLES / "tilings" / f"{tiling}.toml").build_tile()
    a, b = tile.region(), sample.region()
    assert a.symmetric_difference(b).area <= 1e-6 * b.area
    assert tile.stroke == sample.stroke and tile.width_mm == sample.width_mm


def test_preset_entry_is_the_editor_default_with_that_preset():
    from fabtiles.web.params import DEFAULTS

    for name in PRESETS:
        assert gallery.entry(name).query == {**DEFAULTS, "preset": name}


def test_unknown_entry_lists_the_valid_ones(client):
    with pytest.raises(ValueError, match=r"'nope' is not a gallery entry, must be one of: table1-part1, .*6\.6\.6"):
        gallery.entry("nope")
    r = client.get("/api/gallery/nope.svg")
    assert r.status_code == 422 and "must be one of" in r.json()["error"]


def test_api_and_thumbnails_cached(client):
    items = client.get("/api/gallery").json()
    assert [i["key"] for i in items] == [e.key for e in gallery.entries()]
    assert all(i["title"] and i["note"] for i in items)
    r = client.get("/api/gallery/4.8.8.svg")
    assert r.status_code == 200 and r.headers["content-type"] == "image/svg+xml"
    assert r.text.startswith("<?xml") or r.text.startswith("<svg")
    assert "Tiling 4.8.8" in r.text and "max-age" in r.headers["cache-control"]
    hits = gallery.thumbnail.cache_info().hits
    assert client.get("/api/gallery/4.8.8.svg").text == r.text
    assert gallery.thumbnail.cache_info().hits == hits + 1  # drawn once
    page = client.get("/gallery")
    assert page.status_code == 200 and '<script src="/static/gallery.js">' in page.text
