"""The web app's design options (fill_small_holes, heights) and the findings overlay."""

import io
import re

import numpy as np
import pytest
import shapely
from asgi_client import TestClient

from fabtiles.machines.profiles import load_profile
from fabtiles.web.app import create_app

SMALL = "width=60&frame=3&radius=10"
MARK = re.compile(
    r'<circle class="finding (\w+)" data-where="(\w+)" cx="([-\d.]+)" cy="([-\d.]+)" r="[\d.]+" '
    r'stroke="#\w+"><title>([^<]+)</title></circle>'
)


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_defaults_fill_small_holes(client):
    assert client.get("/api/defaults").json()["fill_small_holes"] == "true"
    toml = client.get("/api/design.toml").text
    assert "fill_small_holes = true" in toml
    checks = client.get("/api/checks").json()
    assert checks["findings"] == [] and checks["filled_holes"] == 680
    # the print fills its own: the openings under fdm-0.4mm's min_hole_mm (0.8 mm)
    assert checks["print_filled_holes"] == 626
    assert "(680 too small to cut and 626 too small to print, filled)" in checks["summary"]


def test_default_dxf_has_no_hole_or_bridge_under_the_limits(client, tmp_path):
    """Read the default download back (ezdxf -> shapely) and measure it, trusting no report."""
    import ezdxf

    profile = load_profile("laser-3mm-plywood")
    kerf, lay = profile.kerf_mm, profile.layers
    path = tmp_path / "tile.dxf"
    path.write_bytes(client.get("/api/export/dxf").content)
    msp = ezdxf.readfile(path).modelspace()
    rings = {
        name: [shapely.Polygon(e.get_points("xy")) for e in msp if e.dxf.layer == name]
        for name in (lay.inner_cut.name, lay.outer_cut.name)
    }
    inner, (outer,) = rings[lay.inner_cut.name], rings[lay.outer_cut.name]
    assert len(inner) > 100
    # Every hole as cut (its contour grown back by kerf/2) holds a disc of min_hole_mm.
    holes = shapely.buffer(np.array(inner), kerf / 2, join_style="mitre", mitre_limit=10)
    r = profile.min_hole_mm / 2 - 0.01
    narrow = shapely.is_empty(shapely.buffer(holes, -r))
    assert not narrow.any(), f"{narrow.sum()} holes narrower than {profile.min_hole_mm} mm"
    # Every bridge (material between two cut contours) is at least min_feature_mm wide:
    # contours are kerf/2 away from the material on both sides.
    edges = np.array([shapely.get_exterior_ring(p) for p in [*inner, outer]])
    gap = profile.min_feature_mm + kerf - 0.01
    a, b = shapely.STRtree(edges).query(edges, predicate="dwithin", distance=gap)
    close = [(i, j) for i, j in zip(a, b, strict=True) if i < j]
    assert not close, f"{len(close)} bridges under {profile.min_feature_mm} mm, e.g. {close[:3]}"


def test_without_fill_the_same_tile_has_findings(client):
    checks = client.get("/api/checks?fill_small_holes=false").json()
    codes = {(f["where"], f["code"]): f for f in checks["findings"]}
    assert codes[("laser", "small_hole")]["count"] == 680
    assert codes[("laser", "thin_bridge")]["worst"] == pytest.approx(0.155, abs=0.001)


def test_overlay_marks_each_finding_with_its_size(client):
    text = client.get("/api/preview.svg?fill_small_holes=false&findings=true").text
    marks = MARK.findall(text)
    assert len(marks) == len(re.findall(r'class="finding ', text))  # every mark has the full form
    by, printed = {}, {}
    for code, where, x, y, title in marks:
        assert where in ("laser", "print") and 0 <= float(x) <= 150 and 0 <= float(y) <= 150
        (by if where == "laser" else printed).setdefault(code, []).append((float(x), float(y), title))
    assert len(by["small_hole"]) == 680 and len(by["thin_bridge"]) == 12
    # the print's openings under its 0.8 mm are marked as the printer's
    checks = client.get("/api/checks?fill_small_holes=false").json()
    (hole,) = [f for f in checks["findings"] if (f["where"], f["code"]) == ("print", "small_hole")]
    assert len(printed["small_hole"]) == hole["count"] == 626
    sizes = [float(re.search(r", ([\d.]+) mm", t)[1]) for *_, t in by["thin_bridge"]]
    assert min(sizes) == pytest.approx(0.155, abs=0.001) and max(sizes) < 1.0
    assert all(t.startswith("small hole, ") and t.endswith(" mm (laser)") for *_, t in by["small_hole"])


def test_overlay_of_a_clean_tile_has_no_marks(client):
    text = client.get("/api/preview.svg?findings=true").text
    assert 'class="findings"' in text and not MARK.search(text) and 'class="finding ' not in text
    plain = client.get("/api/preview.svg").text
    assert 'class="findings"' not in plain


def test_overlay_marks_print_findings_too(client):
    text = client.get(f"/api/preview.svg?{SMALL}&stroke=0.6&laser_mode=score&findings=true").text
    codes = {(code, where) for code, where, *_ in MARK.findall(text)}
    assert codes == {("thin_wall", "print")}


def test_bad_findings_flag_is_422(client):
    r = client.get("/api/preview.svg?findings=maybe")
    assert r.status_code == 422 and r.json()["field"] == "findings"
    assert r.json()["error"] == "findings must be true or false, got 'maybe'"
    r = client.get("/api/checks?findings=true")  # a view option of the preview only
    assert r.status_code == 422 and r.json()["field"] == "findings"


def test_heights_reach_the_print_downloads_and_the_design(client):
    import trimesh

    r = client.get(f"/api/export/stl?{SMALL}&base_mm=3&relief_mm=2")
    assert r.status_code == 200, r.text
    mesh = trimesh.load(io.BytesIO(r.content), file_type="stl")
    assert np.ptp(mesh.bounds[:, 2]) == pytest.approx(5.0, abs=0.01)
    toml = client.get(f"/api/design.toml?{SMALL}&base_mm=3&deboss_mm=0.6&print_style=deboss").text
    assert "base_mm = 3.0" in toml and "deboss_mm = 0.6" in toml
    r = client.get(f"/api/export/stl?{SMALL}&relief_mm=-1")
    assert r.status_code == 422 and r.json()["field"] == "relief_mm"


def test_fill_small_holes_reaches_the_laser_downloads(client):
    filled = client.get(f"/api/export/svg?{SMALL}").content
    cut = client.get(f"/api/export/svg?{SMALL}&fill_small_holes=false").content
    assert filled.count(b"<path") < cut.count(b"<path")


def test_name_names_the_downloads(client):
    r = client.get(f"/api/export/svg?{SMALL}&name=my-tile")
    assert r.headers["content-disposition"] == 'attachment; filename="my-tile.svg"'
    assert 'name = "my-tile"' in client.get(f"/api/design.toml?{SMALL}&name=my-tile").text
    r = client.get(f"/api/export/svg?{SMALL}&name=../x")
    assert r.status_code == 422 and r.json()["field"] == "name"


def _pieces_group(text: str) -> str:
    group = text[text.index('<g class="pieces"') :]
    return group[: group.index("</g>")]


def test_a_tile_larger_than_the_bed_is_drawn_with_its_pieces_seams_with_or_without_findings(client):
    # 700 x 300 mm on laser-3mm-plywood's 600 x 400 mm bed: two pieces, one seam
    query = "outline=rectangle&width=700&height=300&radius=40&stroke=4&frame=20"
    checked = _pieces_group(client.get(f"/api/preview.svg?{query}&findings=true").text)
    plain = _pieces_group(client.get(f"/api/preview.svg?{query}").text)
    assert checked.count("<line ") == 1 and checked.count("<text ") == 2
    assert plain == checked  # the same split, made alone for the plain preview
    assert 'class="pieces"' not in client.get(f"/api/preview.svg?{query}&pieces=false").text
    assert 'class="pieces"' not in client.get(f"/api/preview.svg?{SMALL}").text


def test_the_checks_say_how_a_tile_larger_than_the_beds_is_cut_and_printed_as_pieces(client):
    query = "outline=rectangle&width=700&height=300&radius=40&stroke=4&frame=20"
    pieces = client.get(f"/api/checks?{query}").json()["pieces"]
    assert pieces[0].startswith("laser 700 x 300 mm panel in 2 pieces (2 x 1) for the 600 x 400 mm bed")
    assert pieces[1].startswith("print 700 x 300 mm panel in ") and "256 x 256 mm bed" in pieces[1]
    assert client.get(f"/api/checks?{SMALL}").json()["pieces"] == []
