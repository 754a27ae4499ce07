"""The web app's interlace controls: the woven preview, the gap, a bad gap named by its field."""

import pytest
from asgi_client import TestClient

from fabtiles.web.app import create_app
from fabtiles.web.params import design_from_query

SMALL = {"preset": "table3-1", "radius": "12", "width": "50", "frame": "2"}


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_query_keys_reach_the_design():
    d = design_from_query({**SMALL, "interlace": "true", "interlace_gap_mm": "0.2", "interlace_cut": "on"})
    assert d["tile"]["interlace"] is True and d["tile"]["interlace_gap_mm"] == 0.2
    assert d["tile"]["interlace_cut"] is True


def test_preview_is_woven(client):
    plain = client.get("/api/preview.svg", params=SMALL)
    woven = client.get("/api/preview.svg", params={**SMALL, "interlace": "true"})
    assert plain.status_code == woven.status_code == 200
    assert 'stroke="#0b1a3a"' in woven.text and 'stroke="#0b1a3a"' not in plain.text


def test_woven_relief_downloads(client):
    r = client.get("/api/export/stl", params={**SMALL, "interlace": "true"})
    assert r.status_code == 200 and len(r.content) > 84


@pytest.mark.parametrize(
    "gap, message", [("-1", "must be a finite number >= 0, got -1"), ("30", "must be >= 0 and <= ")]
)
def test_bad_gap_names_its_field(client, gap, message):
    r = client.get("/api/preview.svg", params={**SMALL, "interlace": "true", "interlace_gap_mm": gap})
    assert r.status_code == 422
    assert r.json()["field"] == "interlace_gap_mm" and message in r.json()["error"]
