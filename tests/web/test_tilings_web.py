"""The web app and the Archimedean tilings: query parameters, the API, the page's menus."""

import pytest
from asgi_client import TestClient
from test_browser import _preview_version, _wait_new_preview

from fabtiles.designs.design_file import design_from_dict
from fabtiles.pattern.tilings import ALL_TILINGS
from fabtiles.web.app import create_app
from fabtiles.web.params import QueryError, design_from_query


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_query_to_design():
    d = design_from_query(
        {
            "preset": "table3-3",
            "packing": "archimedean",
            "tiling": "3.4.6.4",
            "edge": "9",
            "motif_6": "table3-1",
            "motif_4": "",
            "motif_3": "default",
            "width": "80",
        }
    )
    assert d["packing"] == {"kind": "archimedean", "tiling": "3.4.6.4", "edge": 9.0, "motifs": {"6": "table3-1"}}
    spec = design_from_dict(d, source="query")
    pack = spec.build_tile().pattern
    assert pack.tiling == "3.4.6.4" and pack.motifs[6].n == 12 and pack.motifs[4] == pack.motifs[3]


@pytest.mark.parametrize(
    "query, field, match",
    [
        (
            {"packing": "hex", "motif_8": "table3-3"},
            "motif_8",
            r"motif_8 is a motif per polygon kind of packing=archimedean",
        ),
        ({"packing": "none", "motif_8": "table3-3"}, "motif_8", r"motif_8 has no meaning with packing=none"),
        ({"packing": "archimedean", "edge": "x"}, "edge", r"edge must be a number, got 'x'"),
    ],
)
def test_bad_tiling_query(query, field, match):
    with pytest.raises(QueryError, match=match) as info:
        design_from_query(query)
    assert info.value.field == field


def test_api_tilings_and_preview(client):
    info = client.get("/api/tilings").json()
    assert list(info) == list(ALL_TILINGS) and info["4.6.12"] == {"name": "truncated trihexagonal", "kinds": [4, 6, 12]}
    r = client.get(
        "/api/preview.svg",
        params={
            "preset": "table3-3",
            "packing": "archimedean",
            "tiling": "4.8.8",
            "edge": "15",
            "motif_4": "table1-part1",
            "width": "80",
        },
    )
    assert r.status_code == 200 and r.text.startswith("<?xml")


def test_a_two_uniform_tiling_previews(client):
    info = client.get("/api/tilings").json()
    assert info["[3^6; 3^4.6]#2"] == {"name": "triangles, hexagons sqrt 13 apart", "kinds": [3, 6]}
    params = {"preset": "table3-3", "packing": "archimedean", "tiling": "[3^6; 3^4.6]#2", "edge": "12", "width": "80"}
    plain = client.get("/api/preview.svg", params=params)
    hankin = client.get("/api/preview.svg", params={**params, "method": "hankin", "contact_angle": "60"})
    assert plain.status_code == hankin.status_code == 200 and plain.text != hankin.text


@pytest.mark.parametrize(
    "params, field, match",
    [
        ({"tiling": "5.5.5"}, "tiling", "tiling '5.5.5' is unknown"),
        ({"tiling": "[3^6; 3^4.6]#3"}, "tiling", "did you mean '[3^6; 3^4.6]#"),
        ({"motif_6": "table3-3"}, "motif_6", "motifs key 6 is not a polygon of the tiling 4.8.8"),
        ({"motif_8": "nope"}, "motif_8", "preset 'nope' is unknown"),
        ({"edge": "-2"}, "edge", "edge must be a finite number > 0"),
    ],
)
def test_api_errors_name_the_field(client, params, field, match):
    base = {"preset": "table3-3", "packing": "archimedean", "tiling": "4.8.8", "edge": "15", "width": "80"}
    r = client.get("/api/preview.svg", params={**base, **params})
    assert r.status_code == 422, r.text
    body = r.json()
    assert body["field"] == field and match in body["error"]


def test_page_tiling_menu_and_motif_per_kind(page, server):
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
    r = client.get(
        "/api/preview.svg",
        params={
            "preset": "table3-3",
            "packing": "archimedean",
            "tiling": "3.3.3.3.6",
            "edge": "3",
            "width": "1000",
            "stroke": "0.5",
        },
    )
    assert r.status_code == 422 and r.json()["field"] == "edge"
    assert "the packing edge larger" in r.json()["error"]


def test_design_toml_download_builds_the_same_packing(client):
    from fabtiles.designs.design_file import design_from_text

    params = {"packing": "archimedean", "tiling": "4.6.12", "edge": "12", "motif_4": "table1-part1", "width": "150"}
    text = client.get("/api/design.toml", params=params).text
    assert "[packing.motifs]" in text and '4 = "table1-part1"' in text
    pack = design_from_text(text).build_tile().pattern
    assert pack.tiling == "4.6.12" and pack.edge == 12 and pack.motifs[4].n == 8


def test_hankin_design_toml_download_builds_the_same_packing(client):
    from fabtiles.designs.design_file import design_from_text

    params = {
        "packing": "archimedean",
        "tiling": "6.6.6",
        "edge": "14",
        "method": "hankin",
        "contact_angle": "60",
        "contact_gap": "1.5",
        "width": "150",
    }
    text = client.get("/api/design.toml", params=params).text
    assert 'method = "hankin"' in text and "contact_gap = 1.5" in text
    pack = design_from_text(text).build_tile().pattern
    assert pack == load_design_pattern("hankin/6.6.6.toml")


def test_parquet_design_toml_download_builds_the_same_packing(client):
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.web.gallery import entry

    text = client.get("/api/design.toml", params=entry("parquet-4.8.8").query).text
    assert "contact_angle_to = 75" in text and 'parquet_direction = "x"' in text and 'parquet_curve = "linear"' in text
    assert design_from_text(text).build_tile().pattern == load_design_pattern("classical/parquet-4.8.8.toml")


def load_design_pattern(name):
    from pathlib import Path

    from fabtiles.designs.design_file import load_design

    return load_design(Path(__file__).resolve().parents[2] / "samples" / name).build_tile().pattern


def test_hankin_query_to_design_and_preview(client):
    d = design_from_query(
        {
            "preset": "table3-3",
            "packing": "archimedean",
            "tiling": "4.8.8",
            "edge": "14",
            "method": "hankin",
            "contact_angle": "67.5",
            "contact_gap": "0.5",
            "motif_8": "table3-3",
            "width": "80",
        }
    )
    assert d["packing"]["method"] == "hankin" and d["packing"]["contact_angle"] == 67.5
    pack = design_from_dict(d, source="query").build_tile().pattern
    assert pack.method == "hankin" and pack.contact_gap == 0.5 and dict(pack.motifs).keys() == {8}
    r = client.get(
        "/api/preview.svg",
        params={
            "preset": "table3-3",
            "packing": "archimedean",
            "tiling": "3.12.12",
            "edge": "15",
            "method": "hankin",
            "contact_angle": "70",
            "width": "80",
        },
    )
    assert r.status_code == 200 and r.text.startswith("<?xml")


@pytest.mark.parametrize(
    "params, field, match",
    [
        ({"method": "kaplan"}, "method", "method = 'kaplan' is not valid, must be one of: motifs, hankin"),
        (
            {"method": "hankin", "contact_angle": "95"},
            "contact_angle",
            "contact_angle must be a finite number > 0 and < 90",
        ),
        ({"method": "hankin", "contact_gap": "-1"}, "contact_gap", "contact_gap must be a finite number >= 0"),
        ({"method": "hankin", "contact_gap": "15"}, "contact_gap", "contact_gap must be >= 0 and < the edge (15 mm)"),
        (
            {"method": "hankin", "contact_angle": "85", "contact_gap": "6"},
            "contact_angle",
            "contact_angle 85 has no pattern on the tiling 4.8.8",
        ),
        ({"contact_angle": "50"}, "contact_angle", 'contact_angle is a key of method = "hankin"'),
        (
            {"method": "hankin", "contact_angle_to": "85", "contact_gap": "3"},
            "contact_angle_to",
            "contact_angle_to 85 has no pattern on the tiling 4.8.8 with contact_gap 3 mm",
        ),
        (
            {"method": "hankin", "contact_angle_to": "75", "parquet_curve": "cubic"},
            "parquet_curve",
            "parquet_curve = 'cubic' is not valid, must be one of: linear, smooth",
        ),
        (
            {"packing": "hex", "radius": "10", "tiling": None, "edge": None, "method": "hankin"},
            "method",
            'is a key of kind = "archimedean"',
        ),
    ],
)
def test_api_hankin_errors_name_the_field(client, params, field, match):
    base = {"preset": "table3-3", "packing": "archimedean", "tiling": "4.8.8", "edge": "15", "width": "80"}
    query = {k: v for k, v in {**base, **params}.items() if v is not None}
    r = client.get("/api/preview.svg", params=query)
    assert r.status_code == 422, r.text
    body = r.json()
    assert body["field"] == field and match in body["error"]


def test_page_hankin_method_and_its_sliders(page, server):
    page.goto(f"{server}/?preset=table3-3&width=60&frame=3&packing=archimedean&tiling=4.8.8&edge=14")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.is_visible("#method") and page.input_value("#method") == "motifs"
    assert page.is_hidden("#contact_angle-row") and page.is_hidden("#contact_gap-row")
    assert "method=" not in page.url  # the paper's method: the query as before
    assert page.is_visible("#motif-box") and page.is_visible("#gap_n") and page.is_visible("#gap_inner")
    old = _preview_version(page)
    page.select_option("#method", "hankin")
    _wait_new_preview(page, old)
    assert page.is_visible("#contact_angle-row") and page.is_visible("#contact_gap-row")
    # Hankin's rays take neither the motif nor gap circles: their controls go
    assert page.is_hidden("#motif-box") and page.is_hidden("#gap_n") and page.is_hidden("#gap_inner")
    assert "method=hankin" in page.url and "contact_angle=60" in page.url and "contact_gap" not in page.url
    assert page.locator("#motif_8 option").first.inner_text() == "Hankin's rays"
    old = _preview_version(page)
    page.fill("#contact_angle", "67.5")
    page.dispatch_event("#contact_angle", "change")
    _wait_new_preview(page, old)
    assert "contact_angle=67.5" in page.url
    assert page.locator(".err[data-for='contact_angle']").inner_text() == ""
    # a gap too long: the error under its slider, and the link opens the same state
    old = _preview_version(page)
    page.fill("#contact_gap", "14")
    page.dispatch_event("#contact_gap", "change")
    page.wait_for_function("() => document.querySelector(\".err[data-for='contact_gap']\").textContent.length > 0")
    assert "< the edge" in page.locator(".err[data-for='contact_gap']").inner_text()
    page.fill("#contact_gap", "1")
    page.dispatch_event("#contact_gap", "change")
    page.wait_for_function("() => !document.querySelector(\".err[data-for='contact_gap']\").textContent")
    page.goto(page.url)
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.input_value("#method") == "hankin" and page.input_value("#contact_angle") == "67.5"
    assert page.input_value("#contact_gap") == "1"
    page.select_option("#method", "motifs")  # back to the paper's: the motif and the gap circles again
    assert page.is_visible("#motif-box") and page.is_visible("#gap_n")


def test_the_schema_offers_the_parquet_controls_where_hankins_rays_need_not_repeat(client):
    fields = client.get("/api/schema").json()["fields"]
    to, direction, curve = (fields[k]["widget"] for k in ("contact_angle_to", "parquet_direction", "parquet_curve"))
    assert (
        to["kind"] == "slider" and (to["min"], to["max"]) == (1, 89) and direction["kind"] == curve["kind"] == "select"
    )
    assert to["when"] == direction["when"] == curve["when"]
    assert ["seamless", ["false"]] in to["when"] and ["method", ["hankin"]] in to["when"]
    assert ["shape", ["flat", "stamp"]] in to["when"] and ["parquet", ["true"]] in to["when"]
    assert [c[0] for c in fields["parquet_direction"]["choices"]] == ["x", "y", "radial"]


def test_page_parquet_deformation_controls(page, server):
    page.goto(f"{server}/?preset=table3-3&width=60&frame=3&packing=archimedean&tiling=4.8.8&edge=10&method=hankin")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.is_visible("#parquet") and not page.is_checked("#parquet") and "contact_angle_to" not in page.url
    assert page.is_hidden("#contact_angle_to-row") and page.is_hidden("#parquet_direction")
    old = _preview_version(page)
    page.check("#parquet")
    _wait_new_preview(page, old)
    assert page.is_visible("#contact_angle_to-row") and page.is_visible("#parquet_curve")
    assert "contact_angle_to=75&parquet_direction=x&parquet_curve=linear" in page.url
    old = _preview_version(page)
    page.fill("#contact_angle_to", "40")
    page.dispatch_event("#contact_angle_to", "change")
    page.select_option("#parquet_direction", "radial")
    page.select_option("#parquet_curve", "smooth")
    _wait_new_preview(page, old)
    page.wait_for_function("() => location.search.includes('parquet_curve=smooth')")
    assert "contact_angle_to=40&parquet_direction=radial" in page.url
    assert "contact_angle_to=40" in page.get_attribute("#download-design", "href")
    assert page.locator(".err:visible").count() == 0
    # the link opens the same state; a seamless tile cannot vary: the controls go, and the query's keys
    page.goto(page.url)
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.is_checked("#parquet") and page.input_value("#contact_angle_to") == "40"
    assert page.input_value("#parquet_direction") == "radial" and page.input_value("#parquet_curve") == "smooth"
    old = _preview_version(page)
    page.check("#seamless")
    _wait_new_preview(page, old)
    assert page.is_hidden("#parquet") and page.is_hidden("#contact_angle_to-row") and page.is_hidden("#parquet_curve")
    assert "seamless=true" in page.url and "contact_angle_to" not in page.url
