"""Router and waterjet files: the part as the bit or the jet makes it, read back and checked on its own.

The holes are opened here with GEOS itself (``buffer(-r, quad_segs=64).buffer(r, quad_segs=64)``,
:func:`dxf_helpers.opened_reference`) and compared with the DXF read back by ezdxf; LibreCAD
draws the 2440 x 1220 mm panel's DXF, and OpenSCAD imports it (its area measured from the 2D
SVG OpenSCAD exports of the imported shape: 2 s, where ``linear_extrude`` to STL took 18 s and
a 112 MB file for the same number).
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from dxf_helpers import (
    assert_no_corner_sharper_than,
    check_router_dxf,
    dxf_entities,
    even_odd_area,
    opened_reference,
    raw_vertices,
    read_checked,
    ring_polygons,
    vertices,
)
from model_files import write_cut
from real_programs import program, run
from shapely.geometry import Polygon

import fabtiles as ft
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import load_design
from fabtiles.geometry.contours import MITRE_LIMIT
from fabtiles.machines.profiles import load_profile
from fabtiles.making import build_design

ROOT = Path(__file__).resolve().parents[2]
PANEL = ROOT / "samples" / "panel-2440x1220.toml"
ROUTER = load_profile("router-3.175mm-plywood")
WATERJET = load_profile("waterjet-1mm-aluminium")

DESIGN = """
[motif]
preset = "table3-3"

[packing]
radius = 20

[tile]
outline = "square"
size = 150
frame = 8
stroke = 3.0

[output]
formats = ["dxf", "svg"]
laser_profile = "router-3.175mm-plywood"
"""


@pytest.fixture(scope="module")
def panel_dxf(tmp_path_factory):
    out = tmp_path_factory.mktemp("panel")
    [report] = build_design(load_design(PANEL), out, ["dxf"]).reports
    return Path(report.path), report


def tile_region(size=150.0, radius=20.0, stroke=3.0, frame=8.0):
    tile = ft.Tile(
        "square", size, ft.HexPacking(radius=radius, motif=ft.Star.preset("table3-3")), frame=frame, stroke=stroke
    )
    return tile.region(), tile.outline_shape()


def file_holes(doc, layer):
    return [Polygon(vertices(e)) for e in doc.modelspace() if e.dxf.layer == layer]


def test_the_router_dxf_is_geos_own_opening(tmp_path):
    region, outline = tile_region()
    path = tmp_path / "t.dxf"
    report = write_cut(path, region=region, outline=outline, profile=ROUTER, stroke=3.0)
    doc = check_router_dxf(path, region, ROUTER)
    r = ROUTER.tool_radius_mm
    reference, ref_holes = opened_reference(region, r)
    got = shapely.union_all(ring_polygons(doc, ("OUTSIDE",))).difference(shapely.union_all(file_holes(doc, "INSIDE")))
    assert shapely.symmetric_difference(got, reference).area <= 0.001 * reference.area
    mine = file_holes(doc, "INSIDE")
    assert len(mine) == len(ref_holes) == report.stats["inner_contours"]
    pair = shapely.STRtree(ref_holes).nearest([h.representative_point() for h in mine])
    assert shapely.hausdorff_distance(np.array(mine), np.array(ref_holes)[pair]).max() <= 0.01
    # no kerf: the outline is the tile's own, the stats say which tool
    [outer] = ring_polygons(doc, ("OUTSIDE",))
    assert outer.bounds == pytest.approx((0, 0, 150, 150), abs=1e-9)
    assert report.stats["cutter"] == "router" and report.stats["kerf_mm"] == 0.0
    assert report.stats["tool_radius_mm"] == r


def test_no_hole_corner_in_the_file_is_sharper_than_the_bit(tmp_path):
    region, outline = tile_region()
    path = tmp_path / "t.dxf"
    write_cut(path, region=region, outline=outline, profile=ROUTER)
    doc = read_checked(path)
    for hole in file_holes(doc, "INSIDE"):
        assert_no_corner_sharper_than(hole, ROUTER.tool_radius_mm)


def test_every_removed_hole_is_reported_and_fill_small_holes_counts_them(tmp_path):
    region, outline = tile_region(radius=15, stroke=2.0)  # the gap stars are narrower than the bit
    r = ROUTER.tool_radius_mm
    want = sum(Polygon(h).buffer(-r, quad_segs=64).is_empty for h in region.interiors)
    assert want > 0
    report = write_cut(tmp_path / "a.dxf", region=region, outline=outline, profile=ROUTER)
    [small] = [f for f in report.findings if f.code == "small_hole"]
    assert small.count == want == report.stats["tool_removed_holes"] == len(small.locations)
    assert "the tool cannot enter them" in small.message
    holes = [Polygon(h) for h in region.interiors if Polygon(h).buffer(-r, quad_segs=64).is_empty]
    tree = shapely.STRtree(holes)
    for (x, y), width in zip(small.locations, small.sizes, strict=True):  # each mark inside a removed hole
        near = tree.query(shapely.Point(x, y), predicate="intersects")
        assert len(near) == 1 and width < 2 * r
    filled = write_cut(tmp_path / "b.dxf", region=region, outline=outline, profile=ROUTER, fill_small_holes=True)
    assert filled.stats["filled_holes"] == want and "small_hole" not in {f.code for f in filled.findings}
    assert dxf_entities(tmp_path / "a.dxf") == dxf_entities(tmp_path / "b.dxf")  # the bit makes the same part
    [corners] = [f for f in report.findings if f.code == "rounded_corner"]
    assert corners.count == len(corners.locations) > 0 and f"r = {r:g} mm" in corners.message


def test_the_waterjet_rounds_to_the_jet_then_offsets_half_a_kerf(tmp_path):
    region, outline = tile_region()
    path = tmp_path / "w.dxf"
    report = write_cut(path, region=region, outline=outline, profile=WATERJET, stroke=3.0)
    doc = read_checked(path)
    head = path.read_text()[:400]
    assert head.startswith("999\n") and "kerf 1 mm compensated" in head
    reference, _ = opened_reference(region, WATERJET.tool_radius_mm)
    grown = reference.buffer(WATERJET.kerf_mm / 2, join_style="mitre", mitre_limit=MITRE_LIMIT)
    area = even_odd_area(ring_polygons(doc, ("INSIDE", "OUTSIDE")))
    assert area == pytest.approx(grown.area, rel=0.001)
    [outer] = ring_polygons(doc, ("OUTSIDE",))
    # the outline grown by half the 1 mm kerf, moved by it into the positive quadrant
    assert outer.bounds == pytest.approx((0, 0, 151, 151), abs=1e-6)
    assert report.stats["file_offset_mm"] == [0.5, 0.5]
    assert report.stats["cutter"] == "waterjet" and report.stats["kerf_mm"] == 1.0


def test_inkscape_measures_the_router_svg_as_the_part(tmp_path):
    """Inkscape reads the router SVG in true millimetres: the outline is the part's (no kerf), and the
    inside profiles lie within it, each hole's box at least the bit wide."""
    import xml.etree.ElementTree as ET

    inkscape = program("inkscape", "apt-get install inkscape")
    region, outline = tile_region()
    write_cut(tmp_path / "t.svg", region=region, outline=outline, profile=ROUTER)
    rows = [line.split(",") for line in run([inkscape, "--query-all", tmp_path / "t.svg"]).stdout.splitlines()]
    boxes = {r[0]: np.array([float(v) for v in r[1:]]) * 25.4 / 96 for r in rows}  # px at 96 per inch -> mm
    stroke = float(ET.parse(tmp_path / "t.svg").getroot().find("{http://www.w3.org/2000/svg}g").get("stroke-width"))
    assert boxes["OUTSIDE"][2:] == pytest.approx((150 + stroke,) * 2, abs=0.005)  # the part: no tool offset
    x, _y, w, _h = boxes["INSIDE"]
    assert x > boxes["OUTSIDE"][0] and w < boxes["OUTSIDE"][2]
    holes = [b for k, b in boxes.items() if k not in ("INSIDE", "OUTSIDE") and k != rows[0][0]]
    assert len(holes) > 50 and min(min(b[2], b[3]) for b in holes) >= ROUTER.tool_diameter_mm - 0.01


def test_the_router_svg_holds_the_dxfs_contours_and_says_there_is_no_compensation(tmp_path):
    region, outline = tile_region()
    write_cut(tmp_path / "t.dxf", region=region, outline=outline, profile=ROUTER)
    write_cut(tmp_path / "t.svg", region=region, outline=outline, profile=ROUTER)
    svg = (tmp_path / "t.svg").read_text()
    assert "no tool compensation (CAM offsets the tool)" in svg
    assert svg.count("<path") == len(list(read_checked(tmp_path / "t.dxf").modelspace()))
    assert '<g id="INSIDE"' in svg and svg.index('<g id="INSIDE"') < svg.index('<g id="OUTSIDE"')


def test_the_laser_files_are_unchanged_by_the_kind_field(tmp_path):
    region, outline = tile_region()
    write_cut(tmp_path / "l.dxf", region=region, outline=outline, profile="laser-3mm-plywood")
    text = (tmp_path / "l.dxf").read_text()
    codes = [line.strip() for line in text.split("ENTITIES")[0].splitlines()[::2]]  # the group codes
    assert text.startswith("  0\nSECTION\n") and "999" not in codes


@pytest.mark.parametrize(
    "options, error, match",
    [
        (dict(profile=ROUTER, mode="score"), ft.ParameterError, r"mode must be 'pierced' for router profile"),
        (
            dict(profile=ROUTER, kerf_mm=0.2),
            ft.ParameterError,
            r"kerf_mm must be 0 for router profile 'router-3.175mm-plywood', got 0.2: "
            r"a router file holds the part contour",
        ),
        (
            dict(profile=WATERJET, kerf_mm=0),
            ft.ParameterError,
            r"kerf_mm must be > 0 for waterjet profile 'waterjet-1mm-aluminium' \(the jet's diameter\), got 0",
        ),
        (
            dict(profile=replace(ROUTER, tool_diameter_mm=-1.0)),
            ft.ProfileError,
            r"tool_diameter_mm must be > 0 \(the bit's diameter in mm\), got -1",
        ),
        (
            dict(profile=replace(ROUTER, tool_diameter_mm=60.0)),
            ft.ParameterError,
            r"tool_diameter_mm = 60 mm of router profile 'router-3.175mm-plywood' is wider than every hole",
        ),
        (
            dict(profile=replace(ROUTER, bed_mm=(100.0, 100.0))),
            ft.FabricationError,
            r"the tile is 150 x 150 mm, larger than the 100 x 100 mm bed of router profile 'router-3.175mm-plywood'",
        ),
    ],
)
def test_bad_router_and_waterjet_input_writes_nothing(tmp_path, options, error, match):
    region, outline = tile_region()
    with pytest.raises(error, match=match):
        write_cut(tmp_path / "x.dxf", region=region, outline=outline, **options)
    assert not (tmp_path / "x.dxf").exists()


def test_lightburn_and_laser_modes_are_refused_for_a_router(tmp_path):
    tile = ft.Tile("square", 60, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-3")), frame=4, stroke=2)
    with pytest.raises(ft.ParameterError, match=r"a LightBurn project \(.lbrn2\) is for lasers; router profile"):
        tile.export(tmp_path / "t.lbrn2", profile=ROUTER)
    with pytest.raises(ft.ParameterError, match=r"mode must be 'pierced' for router profile .* got 'inlay'"):
        tile.export(tmp_path / "t.dxf", profile=ROUTER, mode="inlay")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "text, match",
    [
        ('kind = "router"\n[router]\ntool_diameter_mm = 0\n', r"p.toml: router.tool_diameter_mm must be > 0, got 0"),
        ('kind = "router"\n[router]\nmin_feature_mm = 2\n', r"p.toml: a router profile needs router.tool_diameter_mm"),
        ('kind = "router"\n[router]\ntool_diameter_mm = 6\nkerf_mm = 0.2\n', r"p.toml: unknown key router.'kerf_mm'"),
        (
            'kind = "router"\n[router]\ntool_diameter_mm = 6\nmode = "score"\n',
            r"router.mode = 'score' is not valid, must be one of: pierced",
        ),
        ('kind = "waterjet"\n[waterjet]\nkerf_mm = 0\n', r"p.toml: waterjet.kerf_mm must be > 0, got 0"),
        ('kind = "waterjet"\n[waterjet]\nmin_hole_mm = 2\n', r"a waterjet profile needs waterjet.kerf_mm"),
        ('kind = "router"\n[laser]\nkerf_mm = 0.1\n', r"a router profile cannot have a \[laser\] section"),
    ],
)
def test_bad_router_and_waterjet_profiles_name_the_key(tmp_path, text, match):
    path = tmp_path / "p.toml"
    path.write_text(text)
    with pytest.raises(ft.ProfileError, match=match):
        load_profile(path)


def cli_run(*args):
    return CliRunner().invoke(cli, list(map(str, args)), catch_exceptions=False)


@pytest.mark.parametrize(
    "profile_text, match",
    [
        ('kind = "router"\n[router]\ntool_diameter_mm = 40\n', r"tool_diameter_mm = 40 mm of router profile"),
        (
            'kind = "router"\n[router]\ntool_diameter_mm = 3\nbed_mm = [30, 30]\n',  # no room for one piece
            r"larger than the 30 x 30 mm bed of router profile .*, and cannot be cut as pieces",
        ),
        ('kind = "waterjet"\n[waterjet]\nkerf_mm = -1\n', r"waterjet.kerf_mm must be > 0, got -1"),
    ],
)
def test_the_cli_exits_2_on_bad_router_input_and_writes_nothing(tmp_path, profile_text, match):
    (tmp_path / "bad.toml").write_text(profile_text)
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.replace("router-3.175mm-plywood", str(tmp_path / "bad.toml")))
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(out)])
    assert result.exit_code == 2, result.output
    assert re.search(match, result.output) and len(result.output.strip().splitlines()) == 1
    assert not out.exists()


def test_fabtiles_check_lists_and_draws_the_rounded_part(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN)
    result = cli_run("check", design, "-o", tmp_path / "f.svg")
    assert result.exit_code == 1
    assert "router profile router-3.175mm-plywood" in result.output and "router job:" in result.output
    assert re.search(r"router rounded_corner: [\d,]+, worst [\d.]+ mm \(limit 0\.1 mm\), at \(", result.output)
    svg = (tmp_path / "f.svg").read_text()
    assert 'class="finding rounded_corner"' in svg
    # the picture draws the part as the bit makes it: more vertices than the sharp tile (the arcs)
    sharp = ft.export.preview_svg.tile_svg(load_design(design).build_tile(tile_cls=ft.Tile))
    assert svg.count("L") > 2 * sharp.count("L")


def test_the_web_app_lists_the_routers_and_reports_their_findings():
    from asgi_client import TestClient

    from fabtiles.web.app import create_app

    client = TestClient(create_app())
    assert "router-6mm-mdf" in client.get("/api/profiles").json()["laser"]
    r = client.get(
        "/api/checks?preset=table3-3&width=150&radius=20&frame=8&stroke=3&laser_profile=router-3.175mm-plywood"
    )
    assert r.status_code == 200
    assert "rounded_corner" in {f["code"] for f in r.json()["findings"]}


def test_the_panel_dxf_is_the_bits_part(panel_dxf):
    # the file itself (the bit's part: check_router_dxf) is checked on this same build in
    # tests/export/test_sample_goldens.py::test_sample_dxf_is_golden[panel-2440x1220]
    _, report = panel_dxf
    assert report.stats["filled_holes"] == report.stats["tool_removed_holes"] > 0  # fill_small_holes = true
    assert "rounded_corner" in {f.code for f in report.findings}


def test_librecad_draws_the_panel(panel_dxf, tmp_path):
    from test_dxf_librecad import RGB, _print_pdf, _segments_by_colour, assert_draws_the_curves

    librecad = program("librecad", "apt-get install librecad")
    path, _ = panel_dxf
    dxf = tmp_path / "panel.dxf"
    dxf.write_bytes(path.read_bytes())
    drawn = _segments_by_colour(_print_pdf(librecad, dxf, tmp_path))
    profile = load_profile("router-6mm-mdf")
    # red and nothing else; the bit's 10,368 corner arcs drawn as arcs (their middles on the drawing),
    # within the page's resolution (the 2440 mm panel on one page: 0.12 mm a PDF unit)
    assert set(drawn) == {RGB[1]}
    assert_draws_the_curves(
        drawn[RGB[1]], dxf, {profile.layers.inner_cut.name, profile.layers.outer_cut.name}, tol_mm=0.3
    )
    pts = drawn[RGB[1]].reshape(-1, 2)
    w, h = pts.max(0) - pts.min(0)
    assert w / h == pytest.approx(2440 / 1220, rel=1e-3)


def test_openscad_imports_the_panel_with_its_area(panel_dxf, tmp_path):
    openscad = program("openscad", "apt-get install openscad")
    path, report = panel_dxf
    (tmp_path / "panel.dxf").write_bytes(path.read_bytes())
    (tmp_path / "part.scad").write_text('import("panel.dxf");\n')
    run([openscad, "-o", tmp_path / "part.svg", tmp_path / "part.scad"], cwd=tmp_path)
    svg = (tmp_path / "part.svg").read_text()
    rings = []
    for sub in re.findall(r"M([^Mz]*)z", svg):
        xy = np.array([[float(v) for v in p.split(",")] for p in re.findall(r"-?[\d.]+,-?[\d.]+", sub)])
        rings.append(Polygon(xy))
    assert len(rings) == report.stats["inner_contours"] + report.stats["outer_contours"]
    # OpenSCAD 2021 reads a polyline's vertices and not its bulges (openscad/openscad#1307): each of
    # the bit's arcs becomes its chord, holes shrink (the area 2 % over); what it exports is the
    # polylines' vertices joined straight, within its 6 significant digits (0.01 mm here)
    doc = read_checked(tmp_path / "panel.dxf")
    chords = [Polygon(raw_vertices(e)) for e in doc.modelspace()]
    assert even_odd_area(rings) == pytest.approx(even_odd_area(chords), rel=0.001)
    assert even_odd_area(chords) > report.stats["area_mm2"] * 1.01


def test_the_rounding_picture_is_up_to_date(tmp_path):
    import importlib.util

    spec = importlib.util.spec_from_file_location("render_router", ROOT / "samples" / "render_router.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    out = module.render(tmp_path / "router.svg")
    assert out.read_bytes() == (ROOT / "samples" / "pictures" / "router-rounding.svg").read_bytes(), (
        "run python samples/render_router.py"
    )
    assert out.read_text().count('class="left"') == 1


def test_the_calibration_card_is_for_lasers(tmp_path):
    from fabtiles.export.card import write_card

    with pytest.raises(ft.ParameterError, match=r"the test card is for lasers; router profile 'router-6mm-mdf'"):
        write_card(tmp_path / "card.dxf", "router-6mm-mdf")
    assert not (tmp_path / "card.dxf").exists()


def test_a_stroke_thinner_than_the_routers_min_feature_is_refused(tmp_path):
    region, outline = tile_region()
    with pytest.raises(
        ft.ParameterError,
        match=r"stroke must be >= min_feature_mm = 4 mm of router profile "
        r"'router-6mm-mdf', got 3",
    ):
        write_cut(tmp_path / "x.dxf", region=region, outline=outline, profile="router-6mm-mdf", stroke=3.0)


def test_a_router_sheet_leaves_room_for_the_bit_between_tiles(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN)
    [report] = build_design(load_design(design), tmp_path / "out", ["dxf"], copies=2).reports
    doc = read_checked(report.path)
    a, b = ring_polygons(doc, ("OUTSIDE",))
    assert a.distance(b) == pytest.approx(ROUTER.tool_diameter_mm + 2.0)  # the default gap: the bit + 2 mm


def test_build_preview_draws_the_routers_part(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN)
    result = build_design(load_design(design), tmp_path / "out", ["dxf"], preview=True)
    picture = Path(result.preview).read_text()
    sharp = ft.export.preview_svg.tile_svg(load_design(design).build_tile(tile_cls=ft.Tile))
    assert picture.count("L") > 2 * sharp.count("L")  # the rounded corners' arcs
