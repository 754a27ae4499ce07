"""A tile larger than the cutter's bed, cut as pieces (fabtiles/making/pieces.py), checked on its files.

Most tests build a 300 x 200 mm panel on a profile copy with a 200 x 150 mm bed (four pieces,
shared by the module's fixtures); the pieces are read back from their DXFs with ezdxf and carried
into the panel by the manifest's matrices, and GEOS checks them against the unsplit panel.
"""

from __future__ import annotations

import json
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from dxf_helpers import read_checked, ring_polygons

import fabtiles as ft
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import load_design
from fabtiles.geometry.machine_geometry import cut_geometry
from fabtiles.geometry.narrow import fill_small_holes
from fabtiles.machines.profiles import load_profile
from fabtiles.making import build_design

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT / "tests" / "export") not in sys.path:  # the real programs' helpers live beside the export tests
    sys.path.append(str(ROOT / "tests" / "export"))

BED = """kind = "laser"
description = "a small laser for the tests of pieces"
[laser]
kerf_mm = 0.15
min_feature_mm = 1.0
min_hole_mm = 1.2
bed_mm = [{w}, {h}]
{extra}
"""

PANEL = """[motif]
preset = "table3-3"
[packing]
kind = "hex"
radius = 20
[tile]
outline = "rectangle"
size = [300, 200]
frame = 10.0
stroke = 3.0
[output]
formats = ["dxf", "svg", "lbrn2"]
laser_profile = "{profile}"
"""


def panel(folder: Path, *, w=200, h=150, extra="", name="panel") -> Path:
    """A design of the 300 x 200 mm panel on a laser of a ``w`` x ``h`` mm bed, in ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    profile = folder / f"bed-{w}x{h}.toml"
    profile.write_text(BED.format(w=w, h=h, extra=extra))
    design = folder / f"{name}.toml"
    design.write_text(PANEL.format(profile=profile))
    return design


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The panel built once by the command: (the run's output, the output folder, the design)."""
    folder = tmp_path_factory.mktemp("pieces")
    design = panel(folder)
    result = run("build", design, "-o", folder / "out")
    assert result.exit_code == 0, result.output
    return result.output, folder / "out", design


@pytest.fixture(scope="module")
def placed(built):
    """Each piece read back from its DXF, its material (the kerf taken off) carried into the panel."""
    _, out, _ = built
    manifest = json.loads((out / "panel-assembly.json").read_text())
    kerf = 0.15
    pieces = {}
    for entry in manifest["pieces"]:
        dxf = out / next(f for f in entry["files"] if f.endswith(".dxf"))
        doc = read_checked(dxf)
        rings = ring_polygons(doc, {"INNER", "OUTER"})
        material = rings[0]
        for ring in rings[1:]:
            material = shapely.symmetric_difference(material, ring)
        m = np.asarray(entry["matrix"])
        in_panel = shapely.transform(material, lambda xy, m=m: xy @ m[:2, :2].T + m[:2, 2])
        pieces[entry["number"]] = (in_panel.buffer(-kerf / 2, join_style="mitre"), material, doc)
    return manifest, pieces


def test_the_build_writes_a_file_per_piece_and_the_assembly(built):
    output, out, _ = built
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted(
        [f"panel-piece-0{n}.{fmt}" for n in range(1, 5) for fmt in ("dxf", "svg", "lbrn2")]
        + ["panel-assembly.svg", "panel-assembly.json"]
    )
    lines = output.splitlines()
    assert f"wrote {out}/panel-piece-01..04.dxf (dxf, 4 pieces)" in lines
    assert f"wrote {out}/panel-assembly.svg (assembly drawing)" in lines
    assert "  300 x 200 mm panel in 4 pieces (2 x 2) for the 200 x 150 mm bed of laser profile 'bed-200x150'" in lines
    assert any(line.startswith("  joints: ") and "dovetail" in line for line in lines)
    assert any(line.startswith("  largest piece ") for line in lines)
    assert "laser bed-200x150: ok" in lines  # no piece narrower than the minimum feature, no loose part


def test_the_manifest_says_each_piece_and_joint(placed):
    manifest, _ = placed
    assert manifest["panel_mm"] == [300.0, 200.0] and manifest["grid"] == [2, 2]
    assert [p["number"] for p in manifest["pieces"]] == [1, 2, 3, 4]
    # numbered from the top left along the rows: piece 1 is the top left cell
    assert manifest["pieces"][0]["cell"] == [0, 1] and manifest["pieces"][3]["cell"] == [1, 0]
    pairs = {tuple(sorted(j["pieces"])) for j in manifest["joints"]}
    assert pairs == {(1, 2), (3, 4), (1, 3), (2, 4)}
    for entry in manifest["pieces"]:
        m = np.asarray(entry["matrix"])
        assert m.shape == (3, 3) and np.allclose(m[2], [0, 0, 1])
        assert abs(abs(np.linalg.det(m[:2, :2])) - 1) < 1e-9  # a rigid move


def test_the_pieces_overlap_nowhere_beyond_the_fit_and_make_the_panel(built, placed):
    manifest, pieces = placed
    fit = manifest["joint"]["fit_mm"]
    regions = [pieces[n][0] for n in sorted(pieces)]
    for i in range(len(regions)):
        for j in range(i + 1, len(regions)):
            overlap = shapely.intersection(regions[i], regions[j])
            assert overlap.buffer(-(fit / 2 + 0.02)).is_empty, (i + 1, j + 1, overlap.area)
    # the unsplit panel, built on a copy of the profile with a large bed
    _, _, design = built
    large = load_profile(Path(design).parent / "bed-200x150.toml")
    from dataclasses import replace

    large = replace(large, bed_mm=(1000.0, 1000.0))
    tile = load_design(design).build_tile(tile_cls=ft.Tile)
    region, _ = cut_geometry(tile, profile=large, lines=False)
    region, _ = fill_small_holes(region, large.min_hole_mm, tolerance_mm=large.tolerance_mm)
    union = shapely.union_all(regions)
    differ = shapely.symmetric_difference(union, region)
    assert differ.buffer(-(fit + 0.1)).area < 1e-6  # within the kerf's rounding and the joints' fit
    assert abs(union.area - region.area) < 0.01 * region.area


def test_each_piece_fits_the_bed_with_the_margin(placed):
    manifest, pieces = placed
    margin, (bw, bh) = manifest["bed_margin_mm"], manifest["bed_mm"]
    for _, material, _ in pieces.values():
        x0, y0, x1, y1 = material.bounds
        w, h = x1 - x0, y1 - y0
        assert (w <= bw - 2 * margin + 0.2 and h <= bh - 2 * margin + 0.2) or (
            w <= bh - 2 * margin + 0.2 and h <= bw - 2 * margin + 0.2
        )


def test_each_joined_pair_interlocks(placed):
    """Moved 2 mm apart in the plane, in any direction, two joined pieces collide."""
    manifest, pieces = placed
    for joint in manifest["joints"]:
        a, b = (pieces[n][0] for n in joint["pieces"])
        x, y = joint["at"]
        window = shapely.box(x - 15, y - 15, x + 15, y + 15)
        a, b = a.intersection(window), b.intersection(window)
        for k in range(16):
            t = 2 * math.pi * k / 16
            moved = shapely.affinity.translate(b, 2 * math.cos(t), 2 * math.sin(t))
            assert shapely.intersection(a, moved).area > 0.05, (joint, k)


def test_each_piece_is_numbered_on_its_score_layer(placed):
    _, pieces = placed
    for _, _, doc in pieces.values():
        scored = [e for e in doc.modelspace() if e.dxf.layer == "SCORE"]
        assert scored  # the number's strokes


def test_two_builds_are_byte_identical(built, tmp_path):
    _, out, design = built
    again = tmp_path / "again"
    assert run("build", design, "-o", again).exit_code == 0
    for path in out.iterdir():
        assert (again / path.name).read_bytes() == path.read_bytes(), path.name


def test_check_says_the_pieces_and_writes_nothing(built, tmp_path):
    _, _, design = built
    result = run("check", design)
    assert "laser 300 x 200 mm panel in 4 pieces (2 x 2)" in result.output
    assert "bed_size" not in result.output.split("print")[0]


def test_pieces_off_refuses_as_before(tmp_path):
    design = panel(tmp_path)
    result = run("build", design, "-o", tmp_path / "out", "--format", "dxf", "--set", "output.pieces=false")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert "larger than the 200 x 150 mm bed" in result.output


def test_a_sheet_of_a_tile_larger_than_the_bed_is_refused(tmp_path):
    result = run("build", panel(tmp_path), "-o", tmp_path / "out", "--sheet")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    "w, h, extra, message",
    [
        (
            14,
            14,
            "",
            r"larger than the 14 x 14 mm bed of laser profile 'bed-14x14', and cannot be cut as pieces: bed_mm",
        ),
        (40, 40, "", r"needs 117 pieces on the 40 x 40 mm bed, more than the 100 allowed"),
        (200, 150, 'joint = "finger"', r"laser.joint = 'finger' is not valid, must be one of: dovetail, jigsaw"),
    ],
    ids=["bed-smaller-than-a-joint", "too-many-pieces", "joint-not-valid"],
)
def test_bad_input_is_one_line_exit_2_and_no_file(tmp_path, w, h, extra, message):
    import re

    result = run("build", panel(tmp_path, w=w, h=h, extra=extra), "-o", tmp_path / "out", "--format", "dxf")
    assert result.exit_code == 2, result.output
    assert len(result.output.strip().splitlines()) == 1 and re.search(message, result.output), result.output
    assert not (tmp_path / "out").exists()


def test_an_earlier_builds_pieces_are_named(tmp_path):
    design = panel(tmp_path)
    out = tmp_path / "out"
    assert run("build", design, "-o", out, "--format", "dxf").exit_code == 0
    # the panel made small enough for the bed: one file, the four pieces named as left from before
    result = build_design(load_design(design, overrides=["tile.size=[180, 120]"]), out, ["dxf"])
    assert [Path(p).name for p in result.paths] == ["panel.dxf"]
    earlier = sorted(Path(p).name for p in result.earlier)
    assert earlier == ["panel-assembly.json", "panel-assembly.svg"] + [f"panel-piece-0{n}.dxf" for n in range(1, 5)]


def test_tile_export_of_a_large_tile_writes_the_pieces(tmp_path):
    (tmp_path / "p").mkdir()
    profile = tmp_path / "bed.toml"
    profile.write_text(BED.format(w=200, h=150, extra=""))
    tile = ft.Tile(
        "rectangle", (300, 200), ft.HexPacking(radius=20, motif=ft.Star.preset("table3-3")), frame=10, stroke=3
    )
    report = tile.export(tmp_path / "p" / "t.svg", profile=profile)
    assert report.stats["pieces"] == 4 and len(report.stats["files"]) == 4
    names = sorted(p.name for p in (tmp_path / "p").iterdir())
    assert names == ["t-assembly.json", "t-assembly.svg"] + [f"t-piece-0{n}.svg" for n in range(1, 5)]


def test_the_screen_sample_is_eight_pieces(tmp_path):
    """The sample: a 1200 x 800 mm screen on the 600 x 400 mm bed of laser-3mm-plywood, default settings."""
    design = load_design(ROOT / "samples" / "screen-1200x800.toml")
    result = build_design(design, tmp_path, ["dxf"])
    (report,) = result.reports
    assert report.stats["pieces"] == 8 and report.stats["grid"] == [4, 2]
    notes = report.stats["notes"]
    assert (
        "1200 x 800 mm panel in 8 pieces (4 x 2) for the 600 x 400 mm bed of laser profile 'laser-3mm-plywood'" in notes
    )
    assert result.findings == 0
    w, h = sorted(report.stats["largest_piece_mm"])
    assert w <= 400 - 2 * 5 and h <= 600 - 2 * 5
    # the README's and docs/pieces.md's picture is this build's drawing
    drawn = (tmp_path / "screen-1200x800-assembly.svg").read_bytes()
    assert drawn == (ROOT / "samples" / "pictures" / "screen-1200x800-assembly.svg").read_bytes(), (
        "copy the new drawing: fabtiles build samples/screen-1200x800.toml -o out --format dxf, then "
        "cp out/screen-1200x800-assembly.svg samples/pictures/"
    )


# --------------------------------------------------------------------------- the programs users load the pieces into


def test_meerk40t_loads_each_piece_within_the_bed(built, tmp_path):
    from test_laser_programs import burns, meerk40t_jobs

    _, out, _ = built
    dxfs = [out / f"panel-piece-0{n}.dxf" for n in (1, 4)]  # a piece laid as it is and one of the other row
    for dxf, job in zip(dxfs, meerk40t_jobs(dxfs, tmp_path), strict=True):  # one MeerK40t run loads both
        doc = read_checked(dxf)
        assert job["added"] == len(list(doc.modelspace()))
        paths = np.concatenate(burns(job["gcode"]))
        assert paths.min() >= -0.01 and (paths.max(axis=0) <= [200 - 2 * 5 + 0.2, 150 - 2 * 5 + 0.2]).all()


def test_librecad_draws_each_piece(built, tmp_path):
    from test_dxf_librecad import RGB, _dxf_edges, _print_pdf, _segments_by_colour
    from test_dxf_librecad import librecad as program

    exe = program.__wrapped__()  # the export tests' fixture: LibreCAD, or their skip (or failure) without it
    _, out, _ = built
    profile = load_profile(out.parent / "bed-200x150.toml")
    for n in range(1, 5):
        dxf = tmp_path / f"panel-piece-0{n}.dxf"
        dxf.write_bytes((out / dxf.name).read_bytes())
        drawn = _segments_by_colour(_print_pdf(exe, dxf, tmp_path))
        cuts = _dxf_edges(dxf, profile.layers.inner_cut) + _dxf_edges(dxf, profile.layers.outer_cut)
        assert len(drawn[RGB[profile.layers.inner_cut.color]]) == cuts
        assert len(drawn[RGB[profile.layers.score.color]]) == _dxf_edges(dxf, profile.layers.score)


def test_lbrnts_reads_each_pieces_project(built):
    from test_lbrn2 import lbrnts, read_lbrn2

    _, out, _ = built
    paths = [out / f"panel-piece-0{n}.lbrn2" for n in range(1, 5)]
    for path, got in zip(paths, lbrnts(*paths), strict=True):  # one Node run reads them all
        ours = read_lbrn2(path)
        assert [(s["cutIndex"], s["vertices"]) for s in got["shapes"]] == [
            (s["index"], len(s["vertices"])) for s in ours["shapes"]
        ]


ROUTER = """kind = "router"
[router]
tool_diameter_mm = 3.175
min_feature_mm = 2.0
bed_mm = [220, 170]
thickness_mm = 6
"""


def test_a_routers_pieces_are_rounded_to_its_bit_and_still_lock(tmp_path):
    """A router's bit rounds a socket's inner corners: the tabs are rounded to match, and the pieces
    (the files hold the part contour, no kerf) fit without overlapping beyond the fit and interlock."""
    (tmp_path / "router.toml").write_text(ROUTER)
    design = tmp_path / "r.toml"
    text = PANEL.format(profile=tmp_path / "router.toml").replace("radius = 20", "radius = 30")
    design.write_text(text.replace("frame = 10.0", "frame = 20.0").replace("stroke = 3.0", "stroke = 8.0"))
    result = build_design(load_design(design), tmp_path / "out", ["dxf"])
    (report,) = result.reports
    assert report.stats["joint"]["corner_mm"] == pytest.approx(3.175 / 2, abs=1e-3)
    manifest = json.loads((tmp_path / "out" / "r-assembly.json").read_text())
    placed = {}
    for entry in manifest["pieces"]:
        doc = read_checked(tmp_path / "out" / entry["files"][0])
        rings = ring_polygons(doc, {"INNER", "OUTER"})
        material = rings[0]
        for ring in rings[1:]:
            material = shapely.symmetric_difference(material, ring)
        m = np.asarray(entry["matrix"])
        placed[entry["number"]] = shapely.transform(material, lambda xy, m=m: xy @ m[:2, :2].T + m[:2, 2])
    assert manifest["joints"]
    for joint in manifest["joints"]:
        a, b = (placed[n] for n in joint["pieces"])
        assert shapely.intersection(a, b).buffer(-0.07).is_empty  # no more than the 0.1 mm fit
        x, y = joint["at"]
        near = shapely.box(x - 30, y - 30, x + 30, y + 30)
        a, b = a.intersection(near), b.intersection(near)
        for k in range(16):
            t = 2 * math.pi * k / 16
            assert shapely.intersection(a, shapely.affinity.translate(b, 2 * math.cos(t), 2 * math.sin(t))).area > 0.05


def test_a_joint_the_bit_cannot_cut_is_refused(tmp_path):
    (tmp_path / "router.toml").write_text(ROUTER.replace("thickness_mm = 6", "thickness_mm = 2.5"))
    design = tmp_path / "r.toml"
    design.write_text(PANEL.format(profile=tmp_path / "router.toml"))
    result = run("build", design, "-o", tmp_path / "out", "--format", "dxf")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert "the dovetail joint's neck of 2.5 mm is narrower than the 3.175 mm bit" in result.output


def test_the_pieces_nested_onto_sheets_on_request(tmp_path):
    # a 220 x 80 mm panel: two pieces, nested together onto one sheet (the packer takes a second or
    # more a sheet)
    design = panel(tmp_path)
    design.write_text(design.read_text().replace("size = [300, 200]", "size = [220, 80]"))
    out = tmp_path / "out"
    result = build_design(load_design(design, overrides=["output.pieces_sheets=true"]), out, ["dxf"])
    (report,) = result.reports
    assert report.stats["pieces"] == 2
    sheets = sorted(out.glob("panel-sheet-*.dxf"))
    assert len(sheets) == report.stats["nested_sheets"] >= 1
    pieces_edges = sum(len(list(read_checked(out / f"panel-piece-0{n}.dxf").modelspace())) for n in range(1, 3))
    sheet_edges = 0
    for path in sheets:
        rings = [shapely.Polygon(r.exterior) for r in ring_polygons(read_checked(path), {"OUTER"})]
        x0, y0, x1, y1 = shapely.union_all(rings).bounds
        assert x0 >= -1e-6 and y0 >= -1e-6 and x1 <= 200 - 2 * 5 + 0.2 and y1 <= 150 - 2 * 5 + 0.2
        sheet_edges += len(list(read_checked(path).modelspace()))
    assert sheet_edges == pieces_edges  # every piece's every path on one sheet


def placed_pieces(out: Path, stem: str, layers=("INNER", "OUTER"), kerf=0.15) -> tuple[dict, dict]:
    """The manifest, and each piece read back from its DXF and placed in the panel (the kerf taken off)."""
    manifest = json.loads((out / f"{stem}-assembly.json").read_text())
    placed = {}
    for entry in manifest["pieces"]:
        rings = ring_polygons(read_checked(out / entry["files"][0]), set(layers))
        material = rings[0]
        for ring in rings[1:]:
            material = shapely.symmetric_difference(material, ring)
        m = np.asarray(entry["matrix"])
        in_panel = shapely.transform(material, lambda xy, m=m: xy @ m[:2, :2].T + m[:2, 2])
        placed[entry["number"]] = in_panel.buffer(-kerf / 2, join_style="mitre") if kerf else in_panel
    return manifest, placed


def test_jigsaw_joints_lock_too(tmp_path):
    design = panel(tmp_path, extra='joint = "jigsaw"')
    build_design(load_design(design), tmp_path / "out", ["dxf"])
    manifest, placed = placed_pieces(tmp_path / "out", "panel")
    assert manifest["joint"]["kind"] == "jigsaw" and manifest["joints"]
    for joint in manifest["joints"]:
        a, b = (placed[n] for n in joint["pieces"])
        assert shapely.intersection(a, b).buffer(-0.07).is_empty
        for k in range(16):
            t = 2 * math.pi * k / 16
            assert shapely.intersection(a, shapely.affinity.translate(b, 2 * math.cos(t), 2 * math.sin(t))).area > 0.05


def test_a_strict_profiles_findings_name_the_piece(tmp_path):
    # holes narrower than 5 mm kept: a strict profile refuses them, and says in which piece
    design = panel(tmp_path, extra="strict = true")
    profile = tmp_path / "bed-200x150.toml"
    profile.write_text(profile.read_text().replace("min_hole_mm = 1.2", "min_hole_mm = 5.0"))
    result = run("build", design, "-o", tmp_path / "out", "--format", "dxf", "--set", "output.fill_small_holes=false")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert "fabtiles: error: piece 1: fabrication checks failed (profile is strict)" in result.output


def test_check_says_where_seam_bars_hold_a_lattice_too_thin_for_joints(tmp_path):
    design = panel(tmp_path)
    result = run("check", design, "--set", "tile.stroke=1.0", "--set", "tile.frame=3.0")
    assert re.search(r"seam bars: \d+ \(12 mm wide\) laid along the seams where the bands are too thin", result.output)
    assert not list(tmp_path.glob("*.dxf"))


@pytest.mark.parametrize("command", [("nest",), ("plot", "--what", "cut")], ids=["nest", "plot"])
def test_nest_and_plot_refuse_a_tile_larger_than_the_bed_as_before(tmp_path, command):
    out = tmp_path / ("out" if command[0] == "nest" else "cut.svg")
    result = run(command[0], panel(tmp_path), "-o", out, *command[1:])
    assert result.exit_code == 2 and "larger than the 200 x 150 mm bed" in result.output and not out.exists()


def test_an_inlay_kit_of_a_tile_larger_than_the_bed_is_refused_as_before(tmp_path):
    result = run(
        "build", panel(tmp_path), "-o", tmp_path / "out", "--format", "dxf", "--set", 'output.laser_mode="inlay"'
    )
    assert result.exit_code == 2 and "larger than the 200 x 150 mm bed" in result.output
    assert not (tmp_path / "out").exists()


def test_a_download_of_a_panel_is_a_zip_of_its_pieces_and_assembly(tmp_path):
    import io
    import zipfile

    from fabtiles.machines.limits import CLI_LIMITS
    from fabtiles.making import build_bytes

    download = build_bytes(load_design(panel(tmp_path)), "svg", limits=CLI_LIMITS)
    assert (download.media_type, download.file_name) == ("application/zip", "panel-pieces-svg.zip")
    names = sorted(zipfile.ZipFile(io.BytesIO(download.data)).namelist())
    assert names == ["panel-assembly.json", "panel-assembly.svg"] + [f"panel-piece-0{n}.svg" for n in range(1, 5)]


def test_the_checks_picture_draws_the_seams_and_numbers(built, tmp_path):
    _, _, design = built
    result = run("check", design, "-o", tmp_path / "overlay.svg")
    assert f"wrote {tmp_path / 'overlay.svg'}" in result.output
    svg = (tmp_path / "overlay.svg").read_text()
    group = svg[svg.index('<g class="pieces"') :]
    group = group[: group.index("</g>")]
    assert group.count("<line ") == 2 and group.count("<text ") == 4  # a seam each way, four numbers
