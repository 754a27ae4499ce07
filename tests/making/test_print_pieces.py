"""A print larger than the printer's bed, made as pieces (fabtiles/making/print_pieces.py).

Checked independently of the code that made them: each piece's mesh by trimesh and by the
repo's slicer-exact check, its place on the bed from its vertices, the pieces put back in
the panel with their matrices (shapely), the volumes against the unsplit panel's built on a
profile copied with a large bed, and PrusaSlicer and CuraEngine slicing every piece.
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import math
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest
import shapely
import trimesh
from designs import design_toml
from real_programs import cura_definitions, program, run

from fabtiles import ParameterError
from fabtiles.designs.design_file import build_tile, design_from_text, load_design
from fabtiles.export.formats import FORMATS, FileOptions
from fabtiles.export.step import check_step_file
from fabtiles.machines.profiles import load_profile
from fabtiles.making.models import BuildOptions, Models
from fabtiles.making.pipeline import build_design
from fabtiles.making.print_pieces import check_clearance, print_pieces
from fabtiles.solid.mesh_check import check_indexed
from fabtiles.solid.print_model import print_model

ROOT = Path(__file__).resolve().parents[2]
B, H = 2.0, 1.2
BED = (120.0, 120.0)
SMALL = dict(preset="table3-3", radius=20, outline="rectangle", size=[200, 120], frame=8, stroke=3.0)


def profile_with(**changes):
    return dataclasses.replace(load_profile("fdm-0.4mm"), **changes)


@pytest.fixture(scope="module")
def tile():
    return build_tile(design_from_text(design_toml(**SMALL)))


@pytest.fixture(scope="module")
def pieces(tile):
    """The 200 x 120 mm relief split for a 120 x 120 mm bed."""
    return print_pieces(
        tile.region(),
        tile.outline_shape(),
        profile=profile_with(bed_mm=BED),
        stroke=tile.stroke,
        fill_small_holes=True,
        period_mm=tile.pattern.period,
        origin=tile.centre,
    )


@pytest.fixture(scope="module")
def unsplit(tile):
    """The same relief built whole, on the profile copied with a large bed."""
    model = print_model(
        tile.region(), tile.outline_shape(), profile=profile_with(bed_mm=(1000.0, 1000.0)), stroke=tile.stroke,
        fill_small_holes=True,
    )  # fmt: skip
    return model.fused.mesh_volume_mm3


def placed(p):
    """A printed piece's footprint put back in the panel by its matrix."""
    m = p.matrix
    return shapely.transform(p.model.outline, lambda xy: xy @ m[:2, :2].T + m[:2, 2])


def neighbours(pieces):
    by_number = {p.piece.number: p for p in pieces.pieces}
    return [(by_number[a], by_number[b]) for a, b in sorted({j.pieces for j in pieces.split.joints})]


def test_the_panel_is_four_pieces_each_joined_to_its_neighbours(pieces):
    assert pieces.split.grid == (2, 2) and len(pieces.pieces) == 4
    assert len(neighbours(pieces)) == 4  # a 2 x 2 grid: two seams, each across two pairs
    assert pieces.line() == "200 x 120 mm panel in 4 pieces for the 120 x 120 mm bed"
    assert [p.piece.number for p in pieces.pieces] == [1, 2, 3, 4]
    assert [s for s, _ in pieces.files()] == ["-piece-01", "-piece-02", "-piece-03", "-piece-04"]


def test_every_piece_is_watertight(pieces):
    for p in pieces.pieces:
        fused = p.model.fused
        mesh = trimesh.Trimesh(fused.vertices, fused.faces)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.body_count == 1
        # the repo's own check, as a slicer merges the float32 corners
        check_indexed(fused.vertices, fused.faces, name=f"piece {p.piece.number}", volume=mesh.volume, bodies=1)


def test_every_piece_fits_the_bed_with_the_margin(pieces):
    margin = profile_with().bed_margin_mm
    for p in pieces.pieces:
        v = p.model.fused.vertices
        assert (v[:, :2].min(axis=0) >= margin - 1e-6).all()
        assert (v[:, :2].max(axis=0) <= np.array(BED) - margin + 1e-6).all()
        assert v[:, 2].min() == 0.0 and v[:, 2].max() == pytest.approx(B + H)


def test_the_pieces_volumes_add_up_to_the_unsplit_panels_within_the_clearance(pieces, unsplit):
    """What the pieces lack is the clearance along the seams, the full height at most, and their numbers."""
    c = pieces.clearance_mm
    seams = seam_length(pieces)
    numbers = sum(p.model.stack.recess.volume for p in pieces.pieces)
    lost = unsplit - sum(p.model.fused.mesh_volume_mm3 for p in pieces.pieces) - numbers
    # at least the plate's strip under every seam, at most the full height's (the corners counted twice)
    assert c * seams * B - 4 * c * c * (B + H) <= lost <= c * seams * (B + H) + 1e-6
    assert seams > 2 * 120  # the two seams, crooked round their dovetails


def test_neighbours_stand_the_clearance_apart(pieces):
    c = profile_with().joint_clearance_mm
    assert pieces.clearance_mm == c == 0.2
    for a, b in neighbours(pieces):
        fa, fb = placed(a), placed(b)
        assert shapely.intersection(fa, fb).area == 0
        assert shapely.distance(fa, fb) == pytest.approx(c, abs=1e-6)
        # the gap is the clearance all along the seam: grown by half of it each, they meet edge to edge
        grown = shapely.intersection(
            fa.buffer(c / 2 + 1e-4, join_style="mitre"), fb.buffer(c / 2 + 1e-4, join_style="mitre")
        )
        assert grown.area > 0.2 * 100 * 0.5 * 1e-4  # a strip 2e-4 mm wide along the seam


def test_neighbours_interlock_in_every_direction(pieces):
    """Moved 2 mm apart in the plane in any direction, two joined pieces collide (the dovetail catches)."""
    for a, b in neighbours(pieces):
        fa, fb = placed(a), placed(b)
        for k in range(16):
            angle = 2 * math.pi * k / 16
            moved = shapely.affinity.translate(fb, 2 * math.cos(angle), 2 * math.sin(angle))
            assert shapely.intersection(fa, moved).area > 0.1, (a.piece.number, b.piece.number, k)


def seam_length(pieces) -> float:
    """The length of the lines the nominal pieces share (the seams, crooked round their joints)."""
    return sum(
        shapely.intersection(shapely.boundary(a.piece.region), shapely.boundary(b.piece.region)).length
        for a, b in neighbours(pieces)
    )


def test_the_pieces_put_back_are_the_panel_less_the_gaps(pieces, tile):
    union = shapely.union_all([placed(p) for p in pieces.pieces])
    outline = tile.outline_shape()
    assert shapely.difference(union, outline).area < 1e-6
    # the panel less a strip as wide as the clearance along every seam (its crossing counted once)
    c = pieces.clearance_mm
    assert outline.area - union.area == pytest.approx(c * seam_length(pieces), abs=4 * c * c)


def test_each_piece_has_its_number_underneath_mirrored(pieces):
    from fabtiles.geometry.stroke_font import text_width

    for p in pieces.pieces:
        recess = p.model.stack.recess
        assert recess.depth == pytest.approx(0.4)  # two 0.2 mm layers
        assert shapely.covers(p.model.outline.buffer(-1.0), recess.region)
        x0, y0, x1, y1 = recess.region.bounds  # 12 mm digits of strokes 1.2 mm wide (three nozzles)
        assert y1 - y0 == pytest.approx(12 + 1.2, abs=0.01)
        assert x1 - x0 <= text_width(str(p.piece.number), height_mm=12) + 1.2 + 0.01
    # "1" read from below: its flag (the stroke from the top to the left) points right in the file
    one = pieces.pieces[0].model.stack.recess.region
    top = shapely.intersection(one, shapely.box(*one.bounds[:3], one.bounds[3] - 2))
    cx = shapely.centroid(one).x
    flag = shapely.intersection(one, shapely.box(cx + 0.8, one.bounds[3] - 4, one.bounds[2], one.bounds[3]))
    assert flag.area > 0 and top.area > 0


def test_stl_3mf_and_step_writers_take_each_piece(pieces, tmp_path):
    p = pieces.pieces[1]
    for fmt in ("stl", "3mf", "step"):
        data = FORMATS[fmt].write(p.model, FileOptions(name="piece-02"))
        path = tmp_path / f"piece-02.{fmt}"
        path.write_bytes(data)
        assert len(data) > 1000
    _, volume, solids = p.model.brep
    assert check_step_file(tmp_path / "piece-02.step", volume=volume, parts=solids) == pytest.approx(
        p.model.fused.mesh_volume_mm3, rel=1e-3
    )


PRUSA_CONFIG = (
    "layer_height = 0.2\nfirst_layer_height = 0.2\nbed_shape = 0x0,120x0,120x120,0x120\n"
    "perimeter_generator = classic\ngap_fill_enabled = 0\nperimeters = 1\nextra_perimeters = 0\nthin_walls = 0\n"
    "fill_density = 0%\ntop_solid_layers = 0\nbottom_solid_layers = 0\n"
)
"""One classic perimeter and no infill, gap fill or solid layers: the layers are what is asserted, and they are
the same without the slowest passes."""

CURA_LEAN = ["infill_sparse_density=0", "wall_line_count=1", "top_layers=0", "bottom_layers=0"]
"""CuraEngine's counterpart of :data:`PRUSA_CONFIG`'s lean walls: its layer count is the same."""


def test_prusaslicer_and_curaengine_slice_every_piece(pieces, tmp_path):
    prusa = program("prusa-slicer", "apt-get install prusa-slicer")
    engine = program("CuraEngine", "apt-get install cura-engine")
    ini = tmp_path / "printer.ini"
    ini.write_text(PRUSA_CONFIG)
    for p in pieces.pieces:
        stl = tmp_path / f"piece-{p.piece.number:02d}.stl"
        stl.write_bytes(FORMATS["stl"].write(p.model, FileOptions()))
        gcode = tmp_path / f"piece-{p.piece.number:02d}.gcode"
        cmd = [prusa, "--loglevel", "1", "--datadir", tmp_path / "prusa-data", "--load", ini, "--export-gcode",
               "--dont-arrange", "--output", gcode, stl]  # fmt: skip
        done = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr[-2000:]
        zs = [float(z) for z in re.findall(r"^;Z:([0-9.]+)$", gcode.read_text(), flags=re.M)]
        assert len(zs) == round((B + H) / 0.2) and zs[-1] == pytest.approx(B + H)
        settings = ["-s", "layer_height=0.2", "-s", "layer_height_0=0.2", "-s", "adhesion_type=none"]
        settings += [arg for setting in CURA_LEAN for arg in ("-s", setting)]
        definitions = cura_definitions() / "fdmprinter.def.json"
        cura = [engine, "slice", "-v", "-j", definitions, *settings, "-l", stl, "-o", tmp_path / "cura.gcode"]
        err = run(cura, timeout=300).stderr
        assert int(re.search(r"^Layer count: (\d+)$", err, re.M).group(1)) == round((B + H) / 0.2)


# --------------------------------------------------------------------------- the build


def test_a_design_larger_than_the_bed_builds_as_pieces_and_pieces_false_warns(tmp_path):
    profile = tmp_path / "small-bed.toml"
    profile.write_text('kind = "printer"\n[printer]\nbed_mm = [120, 120]\n')
    text = design_toml(**SMALL, output={"printer_profile": str(profile)})
    result = build_design(design_from_text(text, name="panel"), tmp_path / "out", ["stl"])
    pieces = [f"panel-piece-0{n}.stl" for n in range(1, 5)]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [
        "panel-assembly.json",
        "panel-assembly.svg",
        *pieces,
    ]
    manifest = json.loads((tmp_path / "out" / "panel-assembly.json").read_text())
    assert manifest["profile"] == {"name": "small-bed", "kind": "printer"} and manifest["bed_mm"] == [120, 120]
    assert [p["files"] for p in manifest["pieces"]] == [[name] for name in pieces]
    assert manifest["bed_margin_mm"] == 5.0 and len(manifest["joints"]) == 4
    ((label, report),) = result.models
    assert "200 x 120 mm panel in 4 pieces for the 120 x 120 mm bed" in report.summary(label)
    assert "piece 4" in report.stats["material"]["line"]
    whole = design_from_text(text, name="panel", overrides=["output.pieces=false"])
    result = build_design(whole, tmp_path / "whole", ["stl"])
    assert [p.name for p in (tmp_path / "whole").iterdir()] == ["panel.stl"]
    assert [f.code for f in result.reports[0].findings] == ["bed_size"]


def test_the_400_mm_relief_sample_is_four_pieces_on_the_256_mm_bed():
    """Checked from the 2D only: the split and every piece's footprint on the bed."""
    design = load_design(ROOT / "samples" / "relief-400x400.toml")
    models = Models(design.build_tile(), BuildOptions.of_design(design))
    assert models.print_in_pieces
    made = models.print
    assert made.split.grid == (2, 2) and len(made.split.joints) == 4
    assert made.line() == "400 x 400 mm panel in 4 pieces for the 256 x 256 mm bed"
    assert made.report.stats["largest_piece_mm"] == [207.9, 207.9]  # a tab out on two sides, less half the gap
    for p in made.pieces:
        x0, y0, x1, y1 = p.model.outline.bounds
        assert x0 >= 5 - 1e-6 and y0 >= 5 - 1e-6 and x1 <= 251 + 1e-6 and y1 <= 251 + 1e-6
        assert p.model.stack.recess is not None
    # the seams run on the pattern's period (the hex packing's 50 mm across), so the grid's pieces are alike
    assert made.split.seams_x == (200.0,) and made.split.seams_y == (200.0,)


# --------------------------------------------------------------------------- bad input


def test_a_bed_too_small_for_a_piece_and_its_joint_is_refused(tile):
    too_small = (
        r"the 200 x 120 mm tile is larger than the 16 x 16 mm bed of printer profile 'fdm-0.4mm', and cannot be "
        r"made as pieces for it: bed_mm \(16\.0, 16\.0\) less the margin of 5 mm all round leaves no room for a "
        r"piece with its joints \(8 mm\)"
    )
    with pytest.raises(ParameterError, match=too_small):
        print_pieces(tile.region(), tile.outline_shape(), profile=profile_with(bed_mm=(16.0, 16.0)))


@pytest.mark.parametrize("value", [-0.1, 0.6])
def test_a_clearance_out_of_range_is_refused(tile, value):
    with pytest.raises(
        ParameterError, match=rf"joint_clearance_mm must be a finite number >= 0 and <= 0.5, got {value}"
    ):
        print_pieces(tile.region(), tile.outline_shape(), profile=profile_with(bed_mm=BED, joint_clearance_mm=value))
    assert check_clearance(0.0) == 0.0


def test_a_profile_file_with_a_negative_clearance_is_refused(tmp_path):
    from fabtiles import ProfileError

    path = tmp_path / "p.toml"
    path.write_text('kind = "printer"\n[printer]\njoint_clearance_mm = -0.1\n')
    with pytest.raises(ProfileError, match=r"printer\.joint_clearance_mm"):
        load_profile(path)


def test_every_pair_sharing_a_seam_is_joined(pieces):
    # every pair of pieces that share a stretch of seam carries a joint
    for a, b in itertools.combinations(pieces.pieces, 2):
        shared = shapely.intersection(shapely.boundary(a.piece.region), shapely.boundary(b.piece.region)).length
        joined = {a.piece.number, b.piece.number} in [set(j.pieces) for j in pieces.split.joints]
        assert joined == (shared > 1.0)


@pytest.mark.parametrize(
    "extra",
    [
        dict(output={"print_style": "mosaic"}, colour={"by": "shape", "palette": "iznik"}),
        dict(tile={"interlace": True}),
        dict(output={"print_style": "deboss"}),
    ],
    ids=["mosaic", "interlaced", "deboss"],
)
def test_every_style_with_a_plate_builds_as_watertight_pieces(tmp_path, extra):
    profile = tmp_path / "small-bed.toml"
    profile.write_text('kind = "printer"\n[printer]\nbed_mm = [120, 120]\n')
    output = {"printer_profile": str(profile), **extra.pop("output", {})}
    text = design_toml(**{**SMALL, "size": [160, 100]}, output=output, **extra)
    result = build_design(design_from_text(text, name="panel"), tmp_path / "out", ["stl", "3mf"])
    assert not result.refused
    stls = sorted((tmp_path / "out").glob("panel-piece-0*.stl"))
    assert {p.name[:13] for p in stls} == {"panel-piece-0"} and len({p.name[:14] for p in stls}) == 2
    for path in stls:
        mesh = trimesh.load_mesh(path)
        assert mesh.is_watertight and mesh.volume > 0
    assert len(list((tmp_path / "out").glob("panel-piece-0*.3mf"))) == 2


def test_a_wedge_a_seam_cuts_off_a_band_is_left_out_and_the_pattern_stays():
    from fabtiles.making.print_pieces import without_slivers

    seam = shapely.LineString([(10, 0), (10, 20)])
    # a band crossing the seam at a slant: its tip beside the seam is thinner than 0.8 mm; a thin band far off
    band = shapely.Polygon([(0, 0), (10, 0), (10, 0.3), (0, 4)])
    thin = shapely.box(0, 10, 8, 10.5)
    kept = without_slivers(shapely.union(band, thin), seam, 0.8)
    assert shapely.covers(kept, thin)
    assert kept.area < band.area + thin.area
    assert kept.bounds[2] < 10 - 0.3  # the tip is gone


def test_a_round_panels_pieces_are_read_back_from_step(tmp_path):
    """A seam cuts the round outline's arcs off their circles: the pieces' STEP walls are planes, which OCCT reads."""
    tile = build_tile(design_from_text(design_toml(**{**SMALL, "outline": "circle", "size": 160})))
    made = print_pieces(tile.region(), tile.outline_shape(), profile=profile_with(bed_mm=BED), stroke=tile.stroke)
    assert len(made.pieces) == 4
    p = made.pieces[0]
    assert not p.model.step_arcs
    path = tmp_path / "piece-01.step"
    path.write_bytes(FORMATS["step"].write(p.model, FileOptions()))
    _, volume, solids = p.model.brep
    assert check_step_file(path, volume=volume, parts=solids) == pytest.approx(volume, rel=1e-3)


def test_the_web_download_of_a_panel_in_pieces_is_a_zip_of_them_and_their_assembly():
    import io
    import zipfile

    from fabtiles.machines.limits import WEB_LIMITS
    from fabtiles.making import build_bytes

    got = build_bytes(load_design(ROOT / "samples" / "relief-400x400.toml"), "stl", limits=WEB_LIMITS)
    assert got.file_name == "relief-400x400-pieces-stl.zip" and got.media_type == "application/zip"
    names = sorted(zipfile.ZipFile(io.BytesIO(got.data)).namelist())
    pieces = [f"relief-400x400-piece-0{n}.stl" for n in range(1, 5)]
    assert names == ["relief-400x400-assembly.json", "relief-400x400-assembly.svg", *pieces]


def test_a_piece_too_narrow_for_its_number_has_none():
    from fabtiles.making.print_pieces import number_recess

    profile = profile_with()
    assert number_recess(7, shapely.box(0, 0, 4, 60), profile=profile) is None
    wide = number_recess(7, shapely.box(0, 0, 60, 60), profile=profile)
    assert shapely.covers(shapely.box(0, 0, 60, 60).buffer(-1.3), wide.region)


def test_check_of_a_print_larger_than_the_bed_says_its_pieces_instead_of_bed_size():
    from fabtiles.making.checks import check_tile

    tile = load_design(ROOT / "samples" / "relief-400x400.toml")
    built = build_tile(tile)
    split = check_tile(built, pieces=True)
    assert "bed_size" not in {f.code for f in split.print.findings}
    assert split.print.stats["notes"] == [
        "400 x 400 mm panel in 4 pieces (2 x 2) for the 256 x 256 mm bed of printer profile 'fdm-0.4mm': "
        "4 dovetail joints"
    ]
    whole = check_tile(built, pieces=False)
    assert "bed_size" in {f.code for f in whole.print.findings} and "notes" not in whole.print.stats
    tiny = check_tile(built, pieces=True, printer_profile=profile_with(bed_mm=(20.0, 20.0)))
    (finding,) = [f for f in tiny.print.findings if f.code == "pieces"]
    assert "the print cannot be made as pieces: the 400 x 400 mm tile is larger than the 20 x 20 mm bed" in (
        finding.message
    )


def test_the_relief_samples_assembly_drawing_is_the_docs_picture(tmp_path):
    result = build_design(load_design(ROOT / "samples" / "relief-400x400.toml"), tmp_path, ["stl"])
    assert [Path(p).name for p in result.assembly] == ["relief-400x400-assembly.svg", "relief-400x400-assembly.json"]
    drawn = (tmp_path / "relief-400x400-assembly.svg").read_bytes()
    assert drawn == (ROOT / "samples" / "pictures" / "relief-400x400-assembly.svg").read_bytes(), (
        "copy the new drawing: fabtiles build samples/relief-400x400.toml -o out --format stl, then "
        "cp out/relief-400x400-assembly.svg samples/pictures/"
    )
    assert "400 x 400 mm panel in 4 pieces (2 x 2) for the 256 x 256 mm bed of printer profile fdm-0.4mm" in (
        drawn.decode()
    )


def test_a_build_cut_and_printed_as_pieces_writes_an_assembly_for_each_machine(tmp_path):
    printer = tmp_path / "small-bed.toml"
    printer.write_text('kind = "printer"\n[printer]\nbed_mm = [120, 120]\n')
    laser = tmp_path / "small-laser.toml"
    laser.write_text('kind = "laser"\n[laser]\nbed_mm = [150, 150]\n')
    text = design_toml(**SMALL, output={"printer_profile": str(printer), "laser_profile": str(laser)})
    result = build_design(design_from_text(text, name="panel"), tmp_path / "out", ["dxf", "stl"])
    assert [Path(p).name for p in result.assembly] == [
        "panel-assembly.svg",
        "panel-assembly.json",
        "panel-print-assembly.svg",
        "panel-print-assembly.json",
    ]
    cut = json.loads((tmp_path / "out" / "panel-assembly.json").read_text())
    printed = json.loads((tmp_path / "out" / "panel-print-assembly.json").read_text())
    assert cut["profile"]["kind"] == "laser" and printed["profile"]["kind"] == "printer"
    assert {f for p in cut["pieces"] for f in p["files"]} == {f"panel-piece-0{n}.dxf" for n in range(1, 3)}
    assert {f for p in printed["pieces"] for f in p["files"]} == {f"panel-piece-0{n}.stl" for n in range(1, 5)}
