"""A cylinder in the web app: the query's design, the unrolled strip's preview, the cylinder in 3D, its checks
and its downloads (small cylinders: a 24 x 20 mm roller and a 40 x 30 mm shade)."""

import io
import re

import numpy as np
import pytest
import trimesh
from asgi_client import TestClient

from fabtiles.machines.limits import WEB_LIMITS
from fabtiles.web.app import create_app
from fabtiles.web.building import design_of_query
from fabtiles.web.params import QueryError, design_from_query

ROLLER = "shape=cylinder&diameter=24&length=20&radius=5&stroke=1.2&print_style=relief&relief_mm=1"
SHADE = (
    "shape=cylinder&diameter=40&length=30&radius=6&stroke=1.5&print_style=pierced&pierced_mm=1.6&rim_mm=4"
    "&lamp_fitting_mm=12"
)


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


@pytest.fixture(scope="module")
def roller_glb(client):
    return client.get(f"/api/view.glb?{ROLLER}")


def _query(text: str) -> dict:
    return dict(pair.split("=") for pair in text.split("&"))


def _radii(vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each vertex's distance from the axis (the vertical line through the bounds' centre) and its height."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    centre = (lo + hi)[:2] / 2
    return np.hypot(*(vertices[:, :2] - centre).T), vertices[:, 2] - lo[2]


def test_the_query_is_a_cylinder_with_no_outline_size_or_frame():
    design, spec, tile = design_of_query(_query(ROLLER), limits=WEB_LIMITS)
    assert design["surface"] == {"shape": "cylinder", "diameter": 24.0, "length": 20.0}
    assert not {"outline", "size", "frame"} & set(design["tile"])  # the page's defaults are a flat tile's
    assert spec.surface.cylinder and tile.width_mm == pytest.approx(24 * np.pi) and tile.height_mm == 20


@pytest.mark.parametrize("value, mirror", [("", None), ("false", False), ("true", True)])
def test_mirror_empty_is_the_styles(value, mirror):
    surface = design_from_query({"shape": "cylinder", "diameter": "24", "length": "20", "mirror": value})["surface"]
    assert surface.get("mirror") == mirror


def test_a_bad_mirror_names_its_field():
    with pytest.raises(QueryError, match=r"mirror must be true or false, got 'maybe'") as info:
        design_from_query({"mirror": "maybe"})
    assert info.value.field == "mirror"


@pytest.mark.parametrize(
    "extra, field, words",
    [
        ("&width=100", "width", "size is not a key of a cylinder's tile"),
        ("&frame=2", "frame", "frame is not a key of a cylinder's tile"),
        ("&length=300", "length", "beyond the build height"),
        ("&bore_mm=30", "bore_mm", "the bore may be at most 20.40 mm"),
        ("&print_style=mosaic", "print_style", "is not made on a cylinder"),
    ],
)
def test_a_bad_cylinder_answers_422_at_its_field(client, extra, field, words):
    r = client.get(f"/api/checks?{ROLLER}{extra}")
    assert r.status_code == 422 and r.json()["field"] == field and words in r.json()["error"]


def test_a_surface_key_of_a_flat_tile_names_it(client):
    r = client.get("/api/preview.svg?diameter=60")
    assert r.status_code == 422 and r.json()["field"] == "diameter"


def test_the_preview_is_the_unrolled_strip(client):
    r = client.get(f"/api/preview.svg?{ROLLER}&findings=true")
    assert r.status_code == 200
    width, height = map(float, re.search(r'viewBox="0 0 ([\d.]+) ([\d.]+)"', r.text).groups())
    assert width == pytest.approx(24 * np.pi, abs=1e-3) and height == 20  # round the circumference, the length up


def test_the_preview_is_mirrored_as_the_roller_prints_it(client):
    """The strip as its files hold it: a roller's mirrored (the default), drawn otherwise with mirror=false."""

    def paths(extra):
        return sorted(re.findall(r' d="([^"]+)"', client.get(f"/api/preview.svg?{ROLLER}{extra}").text))

    assert paths("") == paths("&mirror=true") != paths("&mirror=false")


def test_the_3d_view_is_the_cylinder_standing(roller_glb):
    r = roller_glb
    assert r.status_code == 200 and r.content[:4] == b"glTF"
    assert r.headers["X-Fabtiles-View"] == "the whole cylinder, its unrolled strip 75.3982 x 20 mm"
    scene = trimesh.load(io.BytesIO(r.content), file_type="glb", process=False)
    assert set(scene.geometry) == {"base", "pattern"}
    assert all(g.is_watertight for g in scene.geometry.values())
    radius, z = _radii(np.vstack([g.vertices for g in scene.geometry.values()]))
    assert radius.max() == pytest.approx(12, abs=0.01)  # the pattern's outer surface: the diameter's half
    assert z.max() == pytest.approx(20, abs=1e-6)  # standing: its axis up, the length tall
    inner = _radii(scene.geometry["base"].vertices)[0].min()
    assert inner == pytest.approx(8.4 / 2, abs=0.01)  # the default bore, for an 8 mm dowel


def test_the_3d_view_of_a_shade(client):
    r = client.get(f"/api/view.glb?{SHADE}")
    assert r.status_code == 200 and "the whole cylinder" in r.headers["X-Fabtiles-View"]
    scene = trimesh.load(io.BytesIO(r.content), file_type="glb", process=False)
    (pattern,) = scene.geometry.values()
    radius, z = _radii(pattern.vertices)
    assert pattern.is_watertight and radius.max() == pytest.approx(20, abs=0.01) and z.max() == pytest.approx(30)


def test_the_checks_say_the_cylinder_and_its_findings(client):
    from fabtiles.making.checks import check_design

    data = client.get(f"/api/checks?{ROLLER}").json()
    assert data["cylinder"] == (
        "cylinder (roller): outer diameter 24.00 mm x 20 mm, bore 8.4 mm, rims 3 mm, mirrored; "
        "printed standing on an end"
    )
    assert data["fitted"] == [
        "surface: cylinder D 24 mm x 20 mm, 8 periods around (packing radius 5.00 -> 4.71 mm, -5.8 %)"
    ]
    assert data["pieces"] == [] and data["cutter"] == "none" and data["job"] is None
    _, spec, tile = design_of_query(_query(ROLLER), limits=WEB_LIMITS)
    found = [(where, f.code) for where, f in check_design(spec, tile).findings()]
    assert [(f["where"], f["code"]) for f in data["findings"]] == found == [("print", "filled_pattern")]


def test_the_checks_of_a_flat_tile_say_no_cylinder(client):
    data = client.get("/api/checks?width=40&frame=3&radius=8").json()
    assert data["cylinder"] is None and data["fitted"] == []


@pytest.mark.parametrize("fmt", ["stl", "3mf"])
def test_the_print_downloads_are_the_cylinder(client, fmt):
    r = client.get(f"/api/export/{fmt}?{ROLLER}")
    assert r.status_code == 200
    mesh = trimesh.load(io.BytesIO(r.content), file_type=fmt, force="mesh")
    radius, z = _radii(mesh.vertices)
    assert radius.max() == pytest.approx(12, abs=0.01) and z.max() == pytest.approx(20)


def test_the_unmade_formats_are_refused_with_the_reason_the_page_shows(client):
    unmade = client.get("/api/schema").json()["unmade"]["cylinder"]
    assert set(unmade) == {"dxf", "svg", "lbrn2", "step"}
    assert "is printed, not cut: formats dxf, svg, lbrn2 make none of it" in unmade["dxf"]
    assert unmade["step"].startswith("a cylinder's STEP is not made")
    for fmt in unmade:
        r = client.get(f"/api/export/{fmt}?{ROLLER}")
        assert r.status_code == 422, fmt
        assert ("is printed, not cut" if fmt != "step" else unmade["step"]) in r.json()["error"]


def test_the_design_file_lists_the_formats_a_cylinder_is_made_in(client, tmp_path):
    from fabtiles.designs.design_file import load_design

    r = client.get(f"/api/design.toml?{SHADE}")
    path = tmp_path / "shade.toml"
    path.write_text(r.text, encoding="utf-8")
    design = load_design(path)
    assert design.output.formats == ("stl", "3mf")
    assert design.surface.lamp_fitting_mm == 12 and design.surface.rim_mm == 4


def test_the_surface_controls_show_for_a_cylinder_only(client):
    fields = client.get("/api/schema").json()["fields"]
    assert fields["shape"]["widget"]["when"] == []
    assert [v for v, _ in fields["mirror"]["choices"]] == ["", "true", "false"]
    for param in ("diameter", "length", "fit", "bore_mm", "rim_mm", "lamp_fitting_mm", "pointed_tops"):
        assert ["shape", ["cylinder"]] in fields[param]["widget"]["when"], param
    assert ["shape", ["cylinder", "stamp"]] in fields["mirror"]["widget"]["when"]
    for param in ("block_mm", "grip_mm", "groove_mm"):
        assert ["shape", ["stamp"]] in fields[param]["widget"]["when"], param
    for param in ("outline", "width", "height", "frame", "corner_radius"):  # a stamp keeps the tile's
        assert ["shape", ["flat", "stamp"]] in fields[param]["widget"]["when"], param


def test_a_cylinder_is_not_nested_on_sheets(client):
    """The nest page takes the editor's design: a cylinder's is refused at the designs, with the reason."""
    body = {"designs": [{"query": ROLLER, "count": 1}], "sheet": None, "gap_mm": None, "rotate": "90", "time_s": 1}
    r = client.post("/api/nest", json={**body, "format": "dxf"})
    assert r.status_code == 422 and r.json()["field"] == "designs" and "is printed, not cut" in r.json()["error"]


# --------------------------------------------------------------------------- a stamp

STAMP = "shape=stamp&outline=hexagon&width=40&frame=2&radius=8&stroke=1.6&print_style=relief&block_mm=16"


def test_a_stamp_query_keeps_its_tile_and_gives_its_block():
    design, spec, tile = design_of_query(_query(STAMP), limits=WEB_LIMITS)
    assert design["surface"] == {"shape": "stamp", "block_mm": 16.0}
    assert spec.surface.stamp and design["tile"]["outline"] == "hexagon" and tile.width_mm == pytest.approx(40)


def test_a_stamps_download_is_one_body_on_its_block(client):
    r = client.get(f"/api/export/stl?{STAMP}")
    assert r.status_code == 200
    mesh = trimesh.load(io.BytesIO(r.content), file_type="stl")
    assert mesh.is_watertight and mesh.bounds[1][2] == pytest.approx(16 + 2.0 + 1.2, abs=0.01)


def test_a_stamps_unmade_formats_are_refused_with_the_reason(client):
    unmade = client.get("/api/schema").json()["unmade"]["stamp"]
    assert set(unmade) == {"dxf", "svg", "lbrn2", "step"}
    assert unmade["step"].startswith("a clay stamp has no STEP file")
    r = client.get(f"/api/export/dxf?{STAMP}")
    assert r.status_code == 422 and '"stamp" is printed, not cut' in r.json()["error"]


def test_pointed_tops_reach_the_cylinder_from_the_query(client):
    plain = client.get(f"/api/checks?{SHADE}").json()
    pointed = client.get(f"/api/checks?{SHADE}&pointed_tops=true").json()
    assert "pointed tops" in pointed["cylinder"] and "pointed tops" not in plain["cylinder"]
