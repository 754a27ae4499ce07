"""The web app and the Archimedean tilings: query parameters, the API, the page's menus."""

import pytest
from fastapi.testclient import TestClient
from test_browser import _preview_version, _wait_new_preview, page, server  # noqa: F401 - fixtures

from fabtiles.design import design_from_dict
from fabtiles.pattern.tilings import TILINGS
from fabtiles.web.app import create_app
from fabtiles.web.params import QueryError, design_from_query


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_query_to_design():
    d = design_from_query({"preset": "table3-3", "packing": "archimedean", "tiling": "3.4.6.4", "edge": "9",
                           "motif_6": "table3-1", "motif_4": "", "motif_3": "default", "width": "80"})
    assert d["packing"] == {"kind": "archimedean", "tiling": "3.4.6.4", "edge": 9.0,
                            "motifs": {"6": "table3-1"}}
    spec = design_from_dict(d, source="query")
    pack = spec.build_tile().pattern
    assert pack.tiling == "3.4.6.4" and pack.motifs[6].n == 12 and pack.motifs[4] == pack.motifs[3]


@pytest.mark.parametrize("query, field, match", [
    ({"packing": "hex", "motif_8": "table3-3"}, "motif_8", r"motif_8 is a motif per polygon kind of packing=archimedean"),
    ({"packing": "none", "motif_8": "table3-3"}, "motif_8", r"motif_8 has no meaning with packing=none"),
    ({"packing": "archimedean", "edge": "x"}, "edge", r"edge must be a number, got 'x'"),
])
def test_bad_tiling_query(query, field, match):
    with pytest.raises(QueryError, match=match) as info:
        design_from_query(query)
    assert info.value.field == field


def test_api_tilings_and_preview(client):
    info = client.get("/api/tilings").json()
    assert list(info) == list(TILINGS) and info["4.6.12"] == {"name": "truncated trihexagonal", "kinds": [4, 6, 12]}
    r = client.get("/api/preview.svg", params={"preset": "table3-3", "packing": "archimedean", "tiling": "4.8.8",
                                                "edge": "15", "motif_4": "table1-part1", "width": "80"})
    assert r.status_code == 200 and r.text.startswith("<?xml")


@pytest.mark.parametrize("params, field, match", [
    ({"tiling": "5.5.5"}, "tiling", "tiling '5.5.5' is unknown"),
    ({"motif_6": "table3-3"}, "motif_6", "motifs key 6 is not a polygon of the tiling 4.8.8"),
    ({"motif_8": "nope"}, "motif_8", "preset 'nope' is unknown"),
    ({"edge": "-2"}, "edge", "edge must be a finite number > 0"),
])
def test_api_errors_name_the_field(client, params, field, match):
    base = {"preset": "table3-3", "packing": "archimedean", "tiling": "4.8.8", "edge": "15", "width": "80"}
    r = client.get("/api/preview.svg", params={**base, **params})
    assert r.status_code == 422, r.text
    body = r.json()
    assert body["field"] == field and match in body["error"]


def test_page_tiling_menu_and_motif_per_kind(page, server):  # noqa: F811 - fixture
    page.goto(f"{server}/?preset=table3-3&width=60&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.is_hidden("#tiling-controls") and page.is_hidden("#edge-row")
    v = _preview_version(page)
    page.select_option("#packing", "archimedean")
    _wait_new_preview(page, v)
    assert page.is_visible("#tiling-controls") and page.is_hidden("#radius-row")
    assert "packing=archimedean" in page.url and "tiling=4.8.8" in page.url and "edge=20" in page.url
    v = _preview_version(page)
    page.select_option("#tiling", "4.6.12")
    _wait_new_preview(page, v)
    assert page.locator("#kind-motifs select").count() == 3
    v = _preview_version(page)
    page.select_option("#motif_12", "table3-1")
    _wait_new_preview(page, v)
    assert "tiling=4.6.12" in page.url and "motif_12=table3-1" in page.url
    # The URL's state comes back on reload.
    page.goto(page.url)
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.input_value("#tiling") == "4.6.12" and page.input_value("#motif_12") == "table3-1"


def test_too_much_work_points_at_the_edge(client):
    r = client.get("/api/preview.svg", params={"preset": "table3-3", "packing": "archimedean",
                                                "tiling": "3.3.3.3.6", "edge": "3", "width": "1000",
                                                "stroke": "0.5"})
    assert r.status_code == 422 and r.json()["field"] == "edge"
    assert "the packing edge larger" in r.json()["error"]


def test_design_toml_download_builds_the_same_packing(client):
    from fabtiles.design import design_from_text

    params = {"packing": "archimedean", "tiling": "4.6.12", "edge": "12", "motif_4": "table1-part1",
              "width": "150"}
    text = client.get("/api/design.toml", params=params).text
    assert "[packing.motifs]" in text and '4 = "table1-part1"' in text
    pack = design_from_text(text).build_tile().pattern
    assert pack.tiling == "4.6.12" and pack.edge == 12 and pack.motifs[4].n == 8
