"""The gallery: every entry opens the design its sample holds, drawn once by the preview code."""

from pathlib import Path

import pytest
from asgi_client import TestClient

from fabtiles.designs.design_file import load_design
from fabtiles.machines.limits import WEB_LIMITS
from fabtiles.pattern.presets import PRESETS
from fabtiles.pattern.tilings import TILINGS
from fabtiles.web import gallery
from fabtiles.web.app import create_app, tile_from_dict
from fabtiles.web.params import design_from_query

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_presets_then_tilings_then_hankin_then_cylinders():
    keys = [e.key for e in gallery.entries()]
    hankin = [f"hankin-{t}" for t in gallery._HANKIN]
    last = [
        "two-uniform-hankin",
        "roller",
        "lampshade",
        "girih-decagon-bowtie",
        "girih-subdivided",
        "border-4.8.8",
        "parquet-4.8.8",
    ]
    assert keys == [*PRESETS, *gallery._TILINGS, *hankin, *last]
    assert set(keys[len(PRESETS) : len(PRESETS) + len(TILINGS)]) == set(TILINGS)
    assert len(keys) == 29


@pytest.mark.parametrize("key, sample", [("roller", "roller-60x80"), ("lampshade", "lampshade-120x150")])
def test_cylinder_entry_is_its_sample(key, sample):
    """The entry's design is the sample's, key for key (the sample's formats aside: a download is one format),
    and so is its strip."""
    from fabtiles.designs.design_file import design_from_dict

    ours = design_from_dict(design_from_query(gallery.entry(key).query))
    theirs = load_design(SAMPLES / f"{sample}.toml")
    assert ours.surface == theirs.surface and ours.surface.cylinder
    assert ours.packing == theirs.packing and ours.motif == theirs.motif and ours.tile_spec == theirs.tile_spec
    assert ours.output.heights() == theirs.output.heights()
    assert (ours.output.print_style, ours.output.printer_profile) == (
        theirs.output.print_style,
        theirs.output.printer_profile,
    )
    a, b = ours.build_tile(), theirs.build_tile()
    assert a.region().symmetric_difference(b.region()).area <= 1e-6 * b.region().area
    assert (a.width_mm, a.height_mm) == pytest.approx((b.width_mm, b.height_mm))


@pytest.mark.parametrize("tiling", sorted(gallery._HANKIN))
def test_hankin_entry_is_its_sample(tiling):
    _, tile = tile_from_dict(design_from_query(gallery.entry(f"hankin-{tiling}").query), limits=WEB_LIMITS)
    sample = load_design(SAMPLES / "hankin" / f"{tiling}.toml").build_tile()
    assert tile.pattern == sample.pattern and tile.pattern.method == "hankin"
    a, b = tile.region(), sample.region()
    assert a.symmetric_difference(b).area <= 1e-6 * b.area
    assert tile.stroke == sample.stroke and tile.width_mm == sample.width_mm


@pytest.mark.parametrize("key", sorted(gallery._GIRIH))
def test_girih_entry_is_its_sample(key):
    from fabtiles.designs.design_file import design_from_dict

    ours = design_from_dict(design_from_query(gallery.entry(key).query))
    path = SAMPLES / f"{key}.toml"
    theirs = load_design(path if path.exists() else SAMPLES / "classical" / f"{key}.toml")
    assert ours.packing == theirs.packing and ours.tile_spec == theirs.tile_spec and ours.colour == theirs.colour
    a, b = ours.build_tile().region(), theirs.build_tile().region()
    assert a.symmetric_difference(b).area <= 1e-6 * b.area


@pytest.mark.parametrize("key", sorted(gallery._CLASSICAL))
def test_classical_entry_is_its_sample(key):
    """A border's or a parquet deformation's entry is its sample in samples/classical/, key for key, and so is
    its tile."""
    from fabtiles.designs.design_file import design_from_dict

    ours = design_from_dict(design_from_query(gallery.entry(key).query))
    theirs = load_design(SAMPLES / "classical" / f"{key}.toml")
    assert ours.packing == theirs.packing and ours.tile_spec == theirs.tile_spec and ours.packing.method == "hankin"
    assert ours.tile_spec.border_mm > 0 or ours.packing.contact_angle_to is not None
    a, b = ours.build_tile(), theirs.build_tile()
    assert a.region().symmetric_difference(b.region()).area <= 1e-6 * b.region().area
    assert a.stroke == b.stroke and a.width_mm == b.width_mm


def test_two_uniform_entry_is_its_sample():
    _, tile = tile_from_dict(design_from_query(gallery.entry("two-uniform-hankin").query), limits=WEB_LIMITS)
    sample = load_design(SAMPLES / "two-uniform-hankin.toml").build_tile()
    assert tile.pattern == sample.pattern and tile.pattern.tiling == "[3^3.4^2; 3^2.4.3.4]#2"
    a, b = tile.region(), sample.region()
    assert a.symmetric_difference(b).area <= 1e-6 * b.area
    assert tile.stroke == sample.stroke and tile.width_mm == sample.width_mm


@pytest.mark.parametrize("tiling", sorted(TILINGS))
def test_tiling_entry_is_its_sample(tiling):
    _, tile = tile_from_dict(design_from_query(gallery.entry(tiling).query), limits=WEB_LIMITS)
    sample = load_design(SAMPLES / "tilings" / f"{tiling}.toml").build_tile()
    a, b = tile.region(), sample.region()
    assert a.symmetric_difference(b).area <= 1e-6 * b.area
    assert tile.stroke == sample.stroke and tile.width_mm == sample.width_mm


def test_preset_entry_is_the_editor_default_with_that_preset_in_a_palette():
    from fabtiles.designs.colour import PALETTE_NAMES
    from fabtiles.web.params import DEFAULTS

    palettes = set()
    for name in PRESETS:
        query = gallery.entry(name).query
        palettes.add(query["palette"])
        radius, stroke = gallery._PRESET_TILES.get(name, (DEFAULTS["radius"], 1))
        assert query == {
            **DEFAULTS,
            "preset": name,
            "colour_by": "shape",
            "palette": query["palette"],
            "radius": radius,
            "stroke": f"{stroke:g}",
        }
    assert palettes == set(PALETTE_NAMES)  # every palette shown


@pytest.mark.parametrize("key", [e.key for e in gallery.entries()])
def test_every_entry_opens_with_no_finding(key):
    """A place to start from is one that cuts and prints on the default profiles as it opens."""
    from fabtiles.designs.design_file import design_from_dict
    from fabtiles.making.checks import check_design
    from fabtiles.web.params import design_from_query

    result = check_design(design_from_dict(design_from_query(gallery.entry(key).query)))
    assert [(where, f.code, f.count) for where, f in result.findings()] == []


def test_thumbnails_show_the_colours(client):
    """A preset's thumbnail fills its faces in its palette's colours; a tiling's (no colours) does not."""
    from fabtiles.designs.colour import PALETTES

    svg = client.get("/api/gallery/table1-part2.svg").text
    iznik = PALETTES["iznik"]
    assert 'class="face-A"' in svg and f'fill="{iznik.faces[0].hex}"' in svg and f'fill="{iznik.band.hex}"' in svg
    assert 'class="face-' not in client.get("/api/gallery/3.6.3.6.svg").text


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


def _slider_values(query: dict) -> list[tuple[str, float]]:
    """The values of ``query`` that a slider of the form shows: (parameter, value), a radius each."""
    from fabtiles.web.schema_json import schema_json

    fields = schema_json()["fields"]
    out = []
    for param, raw in query.items():
        widget = fields.get(param, {}).get("widget") or {}
        if widget.get("kind") == "slider":
            out += [(param, float(v)) for v in str(raw).split(",")]
    return out


def _travel(param: str) -> tuple[float, float]:
    from fabtiles.web.schema_json import schema_json

    widget = schema_json()["fields"][param]["widget"]
    return widget["min"], widget["max"]


@pytest.mark.parametrize("key", [e.key for e in gallery.entries()])
def test_every_gallery_value_is_inside_its_slider(key):
    """A gallery entry opens with every slider inside its travel (the 4.8.8 tiling's r1 = 0.55 once pinned
    a slider of 1 to 400 at its end)."""
    query = gallery.entry(key).query
    values = _slider_values(query)
    sized_by = {"diameter", "length"} if query.get("shape") == "cylinder" else {"width", "frame"}
    assert {p for p, _ in values} >= {*sized_by, "stroke"}
    if "radii" in query:
        assert "radii" in {p for p, _ in values}
    for param, value in values:
        low, high = _travel(param)
        assert low <= value <= high, (key, param, value, (low, high))


@pytest.mark.parametrize("name", list(PRESETS))
def test_every_preset_value_is_inside_its_slider(name):
    preset = PRESETS[name]
    query = {
        k: ",".join(f"{r:g}" for r in v) if k == "radii" else v
        for k, v in preset.items()
        if k in ("n", "radii", "alpha", "spr")
    }
    values = _slider_values(query)
    assert len(values) == 3 + len(preset["radii"])
    for param, value in values:
        low, high = _travel(param)
        assert low <= value <= high, (name, param, value, (low, high))
