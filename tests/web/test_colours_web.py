"""The web app's colours: ``/api/faces`` (the face classes in their colours), the preview's faces, the gallery's
palettes, and a bad colour named by its parameter."""

import pytest
from asgi_client import TestClient

from fabtiles.designs.colour import PALETTES
from fabtiles.machines.limits import Limits
from fabtiles.web.app import create_app

SMALL = "width=60&radius=10&frame=3"


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_faces_by_shape_in_the_palettes_colours(client):
    r = client.get(f"/api/faces?{SMALL}&colour_by=shape&palette=iznik")
    assert r.status_code == 200, r.text
    data = r.json()
    iznik = PALETTES["iznik"]
    assert set(data) == {"band", "base", "classes", "plain", "names"}
    assert data["names"]["navy"] == iznik.base.hex  # the names the page resolves as the server does
    assert data["band"] == {"colour": iznik.band.hex, "name": iznik.band.name}
    assert data["base"] == {"colour": iznik.base.hex, "name": iznik.base.name}
    classes = data["classes"]
    assert [c["letter"] for c in classes] == ["A", "B", "C", "D"]
    for i, c in enumerate(classes):
        assert set(c) == {"letter", "count", "description", "area_mm2", "colour", "name"}
        assert c["colour"] == iznik.faces[i].hex and c["name"] == iznik.faces[i].name
        assert c["count"] > 0 and c["area_mm2"] > 0
    # lettered by decreasing total area, as fabtiles check lists them
    areas = [c["area_mm2"] for c in classes]
    assert areas == sorted(areas, reverse=True)
    assert classes[0]["area_mm2"] == pytest.approx(1049.9, abs=0.5)


def test_faces_given_colours_override_the_palettes(client):
    data = client.get(
        f"/api/faces?{SMALL}&colour_by=shape&palette=iznik&face_B=navy&band_colour=%23ffd400&base_colour=black"
    ).json()
    # navy and black are Iznik's own colours of those names (its base's navy, its black), not CSS's
    assert data["classes"][1]["colour"] == "#1e2a5a" and data["classes"][1]["name"] == "navy"
    assert data["classes"][0]["colour"] == PALETTES["iznik"].faces[0].hex  # the others keep the palette's
    assert data["band"] == {"colour": "#ffd400", "name": "ffd400"} and data["base"]["colour"] == "#1b1b1b"


def test_faces_without_colours_is_one_class(client):
    data = client.get(f"/api/faces?{SMALL}").json()
    zellige = PALETTES["zellige"]
    assert [(c["letter"], c["description"], c["colour"]) for c in data["classes"]] == [
        ("A", "faces", zellige.faces[0].hex)
    ]
    assert data["classes"][0]["count"] == 191


def test_faces_respects_the_web_limits():
    client = TestClient(create_app(limits=Limits(max_segments=100)))
    r = client.get(f"/api/faces?{SMALL}&colour_by=shape")
    assert r.status_code == 422 and r.json()["field"] == "radius", r.json()


BAD_COLOURS = [
    ("colour_by=size", "colour_by", "'size' is not valid, must be one of: none, shape"),
    ("palette=persian", "palette", "'persian' is not valid, must be one of: zellige, iznik"),
    ("band_colour=nope", "band_colour", "band_colour 'nope' is not a CSS or palette colour name"),
    ("base_colour=%2312345", "base_colour", "base_colour must be #rrggbb or a CSS colour name"),
    (
        "colour_by=shape&face_A=reddish",
        "face_A",
        "face_A 'reddish' is not a CSS or palette colour name (did you mean 'red'?)",
    ),
    ("colour_by=shape&face_Q=red", "face_Q", "face class 'Q' is not one of this design's: A, B, C, D"),
]


@pytest.mark.parametrize("query, field, message", BAD_COLOURS)
@pytest.mark.parametrize("endpoint", ["/api/faces", "/api/preview.svg"])
def test_a_bad_colour_names_its_parameter(client, endpoint, query, field, message):
    r = client.get(f"{endpoint}?{SMALL}&{query}")
    assert r.status_code == 422, r.text
    assert message in r.json()["error"] and r.json()["field"] == field, r.json()


def test_the_preview_fills_the_faces_in_the_palettes_colours(client):
    svg = client.get(f"/api/preview.svg?{SMALL}&colour_by=shape&palette=mamluk&face_C=%23123456").text
    mamluk = PALETTES["mamluk"]
    for letter, colour in (("A", mamluk.faces[0].hex), ("B", mamluk.faces[1].hex), ("C", "#123456")):
        assert f'class="face-{letter}"' in svg and f'fill="{colour}"' in svg
    plain = client.get(f"/api/preview.svg?{SMALL}").text
    assert 'class="face-' not in plain  # no colours asked for: the plain picture


def test_a_design_given_no_colours_says_so_and_what_the_pictures_show(client):
    from fabtiles.solid.print_model import PART_MATERIALS

    plain = client.get(f"/api/faces?{SMALL}").json()["plain"]
    assert plain["band"] == {"colour": "#1f3b73", "name": "ink"} and plain["face"]["colour"] == "#ffffff"
    # the plate as the 3D view draws it: the base material's linear colour in sRGB
    linear = [int(plain["base"]["colour"][i : i + 2], 16) / 255 for i in (1, 3, 5)]
    linear = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in linear]
    assert linear == pytest.approx(PART_MATERIALS["base"].colour, abs=0.005)
    assert client.get(f"/api/preview.svg?{SMALL}").headers["X-Fabtiles-Coloured"] == "false"
    assert client.get(f"/api/preview.svg?{SMALL}&colour_by=shape").headers["X-Fabtiles-Coloured"] == "true"
