"""HTTP tests of the web API: every endpoint, every format, bad input for every parameter."""

import io
import json
import re

import pytest
from asgi_client import TestClient

from fabtiles.machines.limits import Limits
from fabtiles.web.app import create_app

SMALL = "width=40&frame=3&radius=8"


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_index_and_static(client):
    r = client.get("/")
    assert r.status_code == 200 and "<title>fabtiles" in r.text
    assert client.get("/static/app.js").headers["content-type"].startswith("text/javascript")
    assert client.get("/static/style.css").status_code == 200
    r = client.get("/static/secret.txt")
    assert r.status_code == 404 and r.json()["error"] == "no static file 'secret.txt'"


def test_presets_and_profiles(client):
    presets = client.get("/api/presets").json()
    assert list(presets) == [
        "table1-part1",
        "table1-part2",
        "table2-left",
        "table2-right",
        "table3-1",
        "table3-2",
        "table3-3",
    ]
    assert presets["table3-3"] == {"n": 12, "radii": [123, 85, 178], "alpha": 23, "spr": -7, "special": 2, "note": ""}
    assert client.get("/api/profiles").json() == {
        "laser": [
            "laser-3mm-acrylic",
            "laser-3mm-plywood",
            "router-3.175mm-plywood",
            "router-6mm-mdf",
            "waterjet-1mm-aluminium",
        ],
        "printer": ["fdm-0.4mm", "fdm-0.6mm"],
    }


def test_preview_svg_default_and_changes(client):
    default = client.get("/api/preview.svg")
    assert default.status_code == 200 and default.headers["content-type"] == "image/svg+xml"
    assert 'width="150mm"' in default.text
    other = client.get("/api/preview.svg?n=8&radii=51,70,172&packing=none&outline=circle&width=80")
    assert other.status_code == 200 and 'width="80mm"' in other.text and other.text != default.text
    rect = client.get("/api/preview.svg?outline=rectangle&width=120&height=60&radius=10")
    assert 'width="120mm" height="60mm"' in rect.text


def test_checks_json(client):
    data = client.get(f"/api/checks?{SMALL}").json()
    assert "segments" in data["summary"]
    assert all({"where", "code", "message", "count"} <= set(f) for f in data["findings"])
    thin = client.get(f"/api/checks?{SMALL}&stroke=0.5&laser_profile=laser-3mm-acrylic").json()
    found = {(f["where"], f["code"]): f for f in thin["findings"]}
    # A 0.5 mm stroke is under both the printer's min_wall_mm (0.8) and the laser's min_feature_mm (1.5).
    assert set(found) == {("print", "thin_wall"), ("laser", "thin_bridge")}
    assert found["print", "thin_wall"]["worst"] == pytest.approx(0.5) and found["print", "thin_wall"]["unit"] == "mm"
    assert "min_wall_mm = 0.8 mm" in found["print", "thin_wall"]["message"]
    assert found["laser", "thin_bridge"]["worst"] == pytest.approx(0.513, abs=0.01)


def test_checks_give_the_laser_job(client):
    data = client.get(f"/api/checks?{SMALL}").json()
    job = data["job"]
    assert re.fullmatch(r"[0-9.]+ m of cut, [0-9,]+ pierces?, about [0-9,]+ min", job["line"])
    assert job["cut_total_mm"] > 0 and job["seconds"] > 0
    engraved = client.get(f"/api/checks?{SMALL}&laser_mode=engrave").json()["job"]
    assert engraved["engrave_area_mm2"] > 0 and engraved["pierces"] == 1


def test_checks_of_an_inlay_kit(client):
    """The inlay mode's checks are its lattice's, as a pierced tile's (they answered 422 before)."""
    kit = client.get(f"/api/checks?{SMALL}&laser_mode=inlay")
    assert kit.status_code == 200, kit.text
    pierced = client.get(f"/api/checks?{SMALL}&laser_mode=pierced").json()
    assert kit.json()["job"] == pierced["job"] and kit.json()["findings"] == pierced["findings"]


def test_design_toml_round_trips_through_build(client, tmp_path):
    from click.testing import CliRunner

    from fabtiles.cli.main import cli

    r = client.get(f"/api/design.toml?{SMALL}&preset=table3-1&join=round")
    assert r.status_code == 200 and "attachment" in r.headers["content-disposition"]
    path = tmp_path / "d.toml"
    path.write_text(r.text)
    res = CliRunner().invoke(cli, ["build", str(path), "-o", str(tmp_path / "out"), "--format", "dxf"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "out" / "d.dxf").exists()


@pytest.mark.parametrize("fmt", ["dxf", "svg", "stl", "3mf", "step"])
def test_every_export_format(client, fmt, tmp_path):
    r = client.get(f"/api/export/{fmt}?{SMALL}")
    assert r.status_code == 200, r.text
    assert r.headers["content-disposition"] == f'attachment; filename="table3-3.{fmt}"'
    path = tmp_path / f"t.{fmt}"
    path.write_bytes(r.content)
    if fmt == "dxf":
        import ezdxf

        doc = ezdxf.readfile(path)
        assert doc.header["$INSUNITS"] == 4 and not doc.audit().has_errors
    elif fmt == "svg":
        assert r.content.startswith(b"<?xml") and b'mm"' in r.content
    elif fmt == "stl":
        import trimesh

        mesh = trimesh.load(path, force="mesh")
        assert mesh.is_watertight and mesh.volume > 0
    elif fmt == "3mf":  # one object of parts, each closed
        import trimesh

        from fabtiles.export.threemf import read_3mf

        for part in read_3mf(path).values():
            mesh = trimesh.Trimesh(part.vertices.astype(float), part.faces)
            assert mesh.is_watertight and mesh.volume > 0
    else:
        assert r.content.startswith(b"ISO-10303-21")


def test_export_modes_from_query(client):
    score = client.get(f"/api/export/dxf?{SMALL}&laser_mode=score").content
    pierced = client.get(f"/api/export/dxf?{SMALL}&laser_mode=pierced").content
    assert b"SCORE" in score and score != pierced


BAD = [
    ("n=2&radii=1,2", "n", "n must be an integer >= 3"),
    ("n=x&radii=1,2", "n", "n must be an integer"),
    ("n=8&radii=1", "radii", "radii must hold 2 to 24 numbers"),
    ("n=8&radii=1,-2", "radii", "radii[1] must be a finite number > 0"),
    ("alpha=nan", "alpha", "alpha must be a finite number"),
    ("spr=inf", "spr", "spr must be a finite number"),
    ("special=9", "special", "special must be an integer >= 2 and <= 3"),
    ("rotation=x", "rotation", "rotation must be a number"),
    ("preset=table9", "preset", "preset 'table9' is unknown"),
    ("packing=triangle", "packing", "triangle"),
    ("radius=-1", "radius", "radius must be"),
    ("fill=0", "fill", "fill"),
    ("gap_n=2", "gap_n", "gap_n must be an integer >= 3"),
    ("gap_radii=0.5,-1", "gap_radii", "gap_radii[1] must be a finite number > 0"),
    ("gap_preset=table9", "gap_preset", "gap_preset 'table9' is unknown; did you mean 'table3-3'?"),
    (
        "packing=archimedean&tiling=4.8.8&motif_8=table9",
        "motif_8",
        "motif_8: preset 'table9' is unknown; did you mean 'table3-3'?",
    ),
    ("outline_circles=perhaps", "outline_circles", "outline_circles must be true or false"),
    ("outline=oval", "outline", "'oval' is not valid, must be one of: square, rectangle, hexagon, circle"),
    ("width=0", "width", "width must be a finite number > 0"),
    ("outline=rectangle&width=100&height=0", "width", "height must be a finite number > 0"),
    ("width=5000", "width", "larger than the limit of 3000 mm"),
    ("outline=rectangle&width=100&height=x", "height", "height must be a number"),
    ("frame=-1", "frame", "frame"),
    ("frame=100", "frame", "too small for frame 100 mm"),
    ("stroke=0", "stroke", "stroke must be a finite number > 0"),
    ("join=zigzag", "join", "'zigzag' is not valid, must be one of: miter, round, bevel"),
    ("corner_radius=-2", "corner_radius", "corner_radius"),
    ("laser_profile=../../etc/passwd", "laser_profile", "is not a bundled profile"),
    ("printer_profile=/tmp/x.toml", "printer_profile", "is not a bundled profile, must be one of: fdm-0.4mm"),
    ("laser_mode=etch", "laser_mode", "etch"),
    ("print_style=emboss", "print_style", "emboss"),
    ("bogus=1", "bogus", "'bogus' is not a valid parameter"),
    (
        "packing=archimedean&tiling=4.8.8&method=hankin&contact_angle_to=75&seamless=true",
        "contact_angle_to",
        "contact_angle_to = 75 changes the pattern across the tile, so it cannot repeat without a seam",
    ),
]


@pytest.mark.parametrize("query, field, message", BAD)
@pytest.mark.parametrize("endpoint", ["/api/preview.svg", "/api/checks", "/api/export/dxf"])
def test_bad_input_is_422_with_field(client, endpoint, query, field, message):
    r = client.get(f"{endpoint}?{query}")
    assert r.status_code == 422, r.text
    body = r.json()
    assert body["field"] == field, body
    assert message in body["error"], body


@pytest.mark.parametrize("query, field, message", BAD)
def test_bad_input_is_said_in_the_forms_words(client, query, field, message):
    """No design file's words: not its source ("query:") nor its sections ("[tile]", "gap_motif")."""
    error = client.get(f"/api/checks?{query}").json()["error"]
    assert not error.startswith("query") and "[tile]" not in error and "[packing" not in error, error
    assert "[motif]" not in error and "[output]" not in error and "gap_motif" not in error, error


@pytest.mark.parametrize(
    "query, name",
    [
        ("preset=table1-part1", "table1-part1"),
        ("preset=table3-3&stroke=2", "table3-3"),  # the motif is the preset's: the page names an edited design
        ("n=8&radii=1,2", "custom"),
        ("preset=table3-3&rotation=10", "custom"),
        ("preset=table3-3&name=my tile", "my tile"),
    ],
)
def test_downloads_are_named_after_the_design(client, query, name):
    for fmt in ("dxf", "stl"):
        r = client.get(f"/api/export/{fmt}?{SMALL}&{query}")
        assert r.headers["content-disposition"] == f'attachment; filename="{name}.{fmt}"'
    r = client.get(f"/api/design.toml?{SMALL}&{query}")
    assert r.headers["content-disposition"] == f'attachment; filename="{name}.toml"'
    assert r.text.startswith(f"# fabtiles design: build it with  fabtiles build {name}.toml -o out\n")


def test_unknown_format_is_422(client):
    r = client.get("/api/export/png")
    assert r.status_code == 422 and r.json() == {
        "error": "'png' is not a valid format, must be one of: dxf, svg, lbrn2, stl, 3mf, step",
        "field": "format",
    }


def test_work_limits_refuse_before_work():
    client = TestClient(create_app(limits=Limits(max_segments=5_000, max_size_mm=300, max_step_segments=100)))
    r = client.get("/api/preview.svg?width=300&radius=5")
    assert r.status_code == 422
    assert "more than the limit of 5,000" in r.json()["error"] and r.json()["field"] == "radius"
    r = client.get("/api/export/step?width=60&radius=15")
    assert r.status_code == 422 and "over the limit of 100" in r.json()["error"]
    assert client.get("/api/preview.svg?width=60&radius=15").status_code == 200


def test_openapi_lists_the_api(client):
    paths = json.loads(client.get("/api/openapi.json").text)["paths"]
    assert {"/api/presets", "/api/preview.svg", "/api/export/{fmt}", "/api/checks"} <= set(paths)


def test_router_preview_draws_the_part_its_bit_makes(client):
    from fabtiles.export.preview_svg import tile_svg
    from fabtiles.geometry.tool_opening import open_region
    from fabtiles.machines.limits import WEB_LIMITS
    from fabtiles.web.app import tile_from_dict
    from fabtiles.web.params import DEFAULTS, design_from_query

    q = "width=80&frame=4&radius=15&stroke=2&fill_small_holes=false&laser_profile=router-3.175mm-plywood"
    query = {**DEFAULTS, **dict(p.split("=") for p in q.split("&"))}
    _, tile = tile_from_dict(design_from_query(query), limits=WEB_LIMITS)
    made = open_region(tile.region(), radius_mm=3.175 / 2, tolerance_mm=0.01).region
    assert client.get(f"/api/preview.svg?{q}").text == tile_svg(tile, region=made)
    assert client.get(f"/api/preview.svg?{q}").text != tile_svg(tile)
    checks = client.get(f"/api/checks?{q}").json()
    # the cutter's findings are the router's; the print's (its unfilled small holes) the printer's
    assert checks["cutter"] == "router" and {f["where"] for f in checks["findings"]} == {"router", "print"}
    assert {"small_hole", "rounded_corner"} <= {f["code"] for f in checks["findings"]}
    marked = client.get(f"/api/preview.svg?{q}&findings=true").text
    assert 'data-where="router"' in marked and "rounded_corner" in marked


def test_holding_tabs_from_the_query(client):
    import ezdxf

    r = client.get(f"/api/export/dxf?{SMALL}&tab_mm=0.5&tabs_per_part=3")
    assert r.status_code == 200, r.text
    doc = ezdxf.read(io.StringIO(r.content.decode()))
    outer = [e for e in doc.modelspace() if e.dxf.layer == "OUTER"]
    assert len(outer) == 3 and not any(e.closed for e in outer)
    r = client.get(f"/api/export/dxf?{SMALL}&tab_mm=0.5&laser_profile=router-6mm-mdf&stroke=5")
    assert r.status_code == 422 and r.json()["field"] == "tab_mm"
    assert re.search(r"tab_mm must be 0 for router profile 'router-6mm-mdf', got 0\.5", r.json()["error"])


def test_the_size_limit_is_the_command_lines():
    from fabtiles.machines.limits import CLI_LIMITS, WEB_LIMITS

    assert WEB_LIMITS.max_size_mm == CLI_LIMITS.max_size_mm


def test_the_pages_formats_are_the_format_tables(client):
    """The download buttons and the nest page's formats are made from /api/schema's rows (app.js, nest.js)."""
    formats = client.get("/api/schema").json()["formats"]
    assert [(f["name"], f["label"], f["family"], f["suffix"]) for f in formats] == [
        ("dxf", "DXF", "cut", ".dxf"),
        ("svg", "SVG", "cut", ".svg"),
        ("lbrn2", "LightBurn", "cut", ".lbrn2"),
        ("stl", "STL", "print", ".stl"),
        ("3mf", "3MF", "print", ".3mf"),
        ("step", "STEP", "print", ".step"),
    ]
    assert [f["name"] for f in formats if f["nests"]] == ["dxf", "svg", "lbrn2"]
    page = client.get("/").text
    assert "data-format" not in page and 'id="download-design"' in page  # the buttons come from the schema
