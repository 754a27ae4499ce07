"""Clay stamps (fabtiles/solid/stamp.py), checked independently of the code that makes them.

trimesh reads the STL back: one watertight body whose volume is the relief's and the
block's, the block's from its sections (shapely, Simpson's rule); the faces' normals and
the sections a slicer takes, layer on layer, show no overhang beyond the limit but the
back on the bed; a section near the top is the mirrored pattern, not the pattern;
PrusaSlicer and CuraEngine, asked to add supports where they are needed, add none (and
do add some to a stamp whose limit is set flatter than they allow).
"""

from __future__ import annotations

import dataclasses
import io
import itertools
import math
import re
import subprocess

import numpy as np
import pytest
import shapely
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from mesh_helpers import section_region as section
from real_programs import cura_definitions, program, run

from fabtiles import FabricationError, ParameterError
from fabtiles.export.formats import FORMATS, FileOptions
from fabtiles.export.threemf import read_3mf
from fabtiles.geometry.mirror import mirrored
from fabtiles.geometry.tile import OUTLINES, outline_polygon
from fabtiles.solid.print_model import print_model
from fabtiles.solid.stamp import LAND_MM, NECK_MM, OVERHANG_DEG, StampSettings, stamp_print

B, H = 2.0, 2.0
"""The relief's plate and pattern heights (mm): a clay stamp's pattern stands 2 mm."""
BLOCK, GRIP, GROOVE = 24.0, 4.0, 4.0
TOP = BLOCK + B + H
LAYER = 0.2


def outline_of(name: str, size: float = 40.0):
    """A tile outline about ``size`` across, its bounding box's corner at the origin."""
    width, height = {"rectangle": (size, 0.75 * size), "hexagon": (size, 2 * size / math.sqrt(3))}.get(
        name, (size, size)
    )
    return outline_polygon(name, width, height, centre=(width / 2, height / 2))


def letter(outline):
    """A frame and an F: a pattern that is not its own mirror image."""
    x0, y0, x1, y1 = outline.bounds
    w, h = x1 - x0, y1 - y0
    f = shapely.union_all(
        [
            shapely.box(x0 + 0.3 * w, y0 + 0.25 * h, x0 + 0.4 * w, y0 + 0.75 * h),
            shapely.box(x0 + 0.3 * w, y0 + 0.65 * h, x0 + 0.7 * w, y0 + 0.75 * h),
            shapely.box(x0 + 0.3 * w, y0 + 0.45 * h, x0 + 0.6 * w, y0 + 0.55 * h),
        ]
    )
    return shapely.union(outline.difference(outline.buffer(-3.0)), f)


def relief(region, outline):
    return print_model(region, outline, profile="fdm-0.4mm", style="relief", base_mm=B, relief_mm=H)


def made(outline, **kw):
    """The stamp of the F on ``outline``, its region and its STL read back by trimesh."""
    region = letter(outline)
    stamp = stamp_print(
        relief(mirrored(region, outline), outline),
        settings=StampSettings(block_mm=BLOCK, grip_mm=GRIP, groove_mm=GROOVE, **kw),
    )
    data = FORMATS["stl"].write(stamp, FileOptions())
    return stamp, region, trimesh.load(io.BytesIO(data), file_type="stl")


@pytest.fixture(scope="module", params=OUTLINES)
def stamp(request):
    outline = outline_of(request.param)
    return (outline, *made(outline))


def block_volume(outline, z1, rise, groove, top):
    """The block's volume from its sections: the outline taken in by the groove's depth at each height.

    A chamfer's section is the outline taken in linearly with height: its area is a quadratic in
    the height, which Simpson's rule integrates exactly.
    """

    def area(depth):
        return outline.buffer(-depth, join_style="mitre").area

    chamfer = rise / 6 * (area(0) + 4 * area(GRIP / 2) + area(GRIP))
    return area(0) * z1 + chamfer + area(GRIP) * groove + chamfer + area(0) * (top - z1 - 2 * rise - groove)


# --------------------------------------------------------------------------- the body


def test_the_stl_is_one_watertight_body_of_the_reliefs_and_the_blocks_volume(stamp):
    outline, stamp, region, mesh = stamp
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.body_count == 1
    figures = stamp.report.stats["stamp"]
    z1, zc = figures["groove_from_to_mm"]
    rise = figures["chamfer_rise_mm"]
    assert zc - z1 == pytest.approx(2 * rise + GROOVE)
    expected = block_volume(outline, z1, rise, GROOVE, BLOCK) + outline.area * B + region.area * H
    assert mesh.volume == pytest.approx(expected, rel=2e-3)
    xmin, ymin, xmax, ymax = outline.bounds
    assert mesh.bounds.ravel().tolist() == pytest.approx([xmin, ymin, 0, xmax, ymax, TOP], abs=2e-3)


def test_the_groove_goes_in_as_deep_as_asked_and_keeps_its_lands(stamp):
    outline, stamp, _, mesh = stamp
    z1, zc = stamp.report.stats["stamp"]["groove_from_to_mm"]
    assert z1 >= LAND_MM and BLOCK - zc >= LAND_MM
    waist = section(mesh, (z1 + zc) / 2)
    inset = outline.buffer(-GRIP, join_style="mitre")
    assert waist.symmetric_difference(inset).area < 1e-3 * inset.area
    for z in (z1 / 2, (zc + BLOCK) / 2):  # the foot and the shoulder: the whole outline
        assert section(mesh, z).symmetric_difference(outline).area < 1e-3 * outline.area


def downward_overhangs_deg(mesh) -> np.ndarray:
    """The angle from vertical of every face that looks down, but those lying on the bed."""
    normals = mesh.face_normals
    down = normals[:, 2] < -1e-9
    on_bed = (np.abs(mesh.triangles[:, :, 2]) < 1e-6).all(axis=1)
    return np.degrees(np.arcsin(np.clip(-normals[down & ~on_bed, 2], 0, 1)))


def test_no_face_looks_down_more_than_the_limit_but_the_back_on_the_bed(stamp):
    *_, mesh = stamp
    angles = downward_overhangs_deg(mesh)
    assert len(angles)  # the groove's upper chamfer
    assert angles.max() <= OVERHANG_DEG + 1e-3


def test_no_layer_reaches_beyond_the_one_under_it_more_than_the_limit_allows(stamp):
    # what a slicer's automatic supports look for: a layer's outline outside the one under it, grown
    # by the layer's height times the limit's tangent
    *_, mesh = stamp
    heights = np.arange(LAYER / 2, TOP, LAYER)
    layers = [section(mesh, z) for z in heights]
    reach = LAYER * math.tan(math.radians(OVERHANG_DEG))
    worst = max(upper.difference(lower.buffer(reach + 2e-3)).area for lower, upper in itertools.pairwise(layers))
    assert worst < 1e-6
    # and it does catch an overhang: the layer under the groove's shoulder against the waist's
    block = [g for z, g in zip(heights, layers, strict=True) if z < BLOCK]
    waist = min(block, key=lambda g: g.area)
    assert block[-1].difference(waist.buffer(reach)).area > 1.0


def test_the_stamps_face_is_the_pattern_mirrored(stamp):
    outline, _, region, mesh = stamp
    face = section(mesh, TOP - 0.1)
    flipped = mirrored(region, outline)
    assert face.symmetric_difference(flipped).area < 2e-3 * region.area
    assert face.symmetric_difference(region).area > 0.05 * region.area


def test_the_3mf_holds_the_block_with_its_plate_and_the_pattern_on_it(stamp):
    _, stamp, region, mesh = stamp
    parts = read_3mf(FORMATS["3mf"].write(stamp, FileOptions()))
    assert {n: p.extruder for n, p in parts.items()} == {"block": 1, "pattern": 2}
    meshes = {n: trimesh.Trimesh(p.vertices, p.faces) for n, p in parts.items()}
    assert all(m.is_watertight for m in meshes.values())
    assert meshes["block"].body_count == 1
    assert meshes["pattern"].body_count == len(shapely.get_parts(region))
    assert meshes["pattern"].bounds[:, 2] == pytest.approx([BLOCK + B, TOP], abs=1e-5)
    assert meshes["block"].bounds[:, 2] == pytest.approx([0, BLOCK + B], abs=1e-5)
    assert meshes["pattern"].volume == pytest.approx(region.area * H, rel=2e-3)
    assert sum(m.volume for m in meshes.values()) == pytest.approx(mesh.volume, rel=1e-4)


def test_the_3d_view_shows_both_parts():
    stamp, *_ = made(outline_of("square"))
    scene = trimesh.load(io.BytesIO(FORMATS["glb"].write(stamp, FileOptions())), file_type="glb")
    assert sorted(scene.geometry) == ["block", "pattern"]


def test_a_stamp_has_no_step_file_and_says_so():
    stamp, *_ = made(outline_of("square"))
    with pytest.raises(FabricationError, match=r"no STEP file.*write STL or 3MF"):
        FORMATS["step"].write(stamp, FileOptions())


def test_the_report_says_how_to_print_it():
    stamp, *_ = made(outline_of("circle"))
    assert any("pattern up, no supports" in line for line in stamp.report.stats["notes"])
    figures = stamp.stats()["stamp"]
    assert figures["block_top_mm"] == BLOCK and figures["height_mm"] == pytest.approx(TOP)
    assert figures["overhang_deg"] == OVERHANG_DEG


def test_a_corner_rounder_than_the_groove_is_deep_makes_the_chamfer_taller_not_flatter():
    outline = outline_polygon("square", 40, 40, corner_radius=1.0, centre=(20, 20))
    stamp, _, mesh = made(outline)
    square, *_ = made(outline_of("square"))
    # the sides alone would need the groove's depth; a sharp corner the depth times sqrt(2)
    assert GRIP < stamp.grip.rise_mm < square.grip.rise_mm
    assert downward_overhangs_deg(mesh).max() <= OVERHANG_DEG + 1e-3


def test_a_flatter_limit_from_the_settings_or_the_profile_makes_a_lower_groove():
    steep, *_ = made(outline_of("circle"))
    flat, *_ = made(outline_of("circle"), overhang_deg=60)
    tangents = math.tan(math.radians(45)) / math.tan(math.radians(60))
    assert flat.grip.rise_mm == pytest.approx(steep.grip.rise_mm * tangents, abs=2e-3)
    model = relief(letter(outline_of("circle")), outline_of("circle"))
    model.profile = dataclasses.replace(model.profile, max_overhang_deg=60.0)  # the printer profile's limit
    from_profile = stamp_print(model, settings=StampSettings(block_mm=BLOCK, grip_mm=GRIP, groove_mm=GROOVE))
    assert from_profile.grip.rise_mm == flat.grip.rise_mm


def test_an_interlaced_relief_mirrored_with_its_dips_makes_a_stamp():
    # the dips mirrored with the strands: the imprint's crossings alternate as designed
    import fabtiles as ft
    from fabtiles.geometry.interlace import tile_dips

    tile = ft.Tile("circle", 40, ft.Star.preset("table3-1"), frame=2, stroke=1.6, interlace=True)
    outline = tile.outline_shape()
    dips = mirrored(tile_dips(tile), outline)
    model = print_model(
        mirrored(tile.region(), outline),
        outline,
        profile="fdm-0.4mm",
        style="relief",
        base_mm=B,
        relief_mm=H,
        dips=dips,
    )
    stamp = stamp_print(model, settings=StampSettings(block_mm=BLOCK, grip_mm=GRIP, groove_mm=GROOVE))
    mesh = trimesh.load(io.BytesIO(FORMATS["stl"].write(stamp, FileOptions())), file_type="stl")
    assert mesh.is_watertight and mesh.body_count == 1
    relief_only = trimesh.load(io.BytesIO(FORMATS["stl"].write(model, FileOptions())), file_type="stl")
    figures = stamp.stats()["stamp"]
    z1, _ = figures["groove_from_to_mm"]
    block = block_volume(outline, z1, figures["chamfer_rise_mm"], GROOVE, BLOCK)
    assert mesh.volume == pytest.approx(block + relief_only.volume, rel=1e-4)
    # under a crossing the strand dips: the section just under the top is less than the strands
    assert section(mesh, TOP - 0.05).area < section(mesh, BLOCK + B + 0.05).area - 1.0


@settings(max_examples=examples(6), deadline=None)
@given(
    outline=st.sampled_from(OUTLINES),
    grip=st.floats(1.0, 6.0),
    groove=st.floats(0.0, 6.0),
    overhang=st.floats(30.0, 60.0),
)
def test_any_grip_is_one_watertight_body_within_its_limit(outline, grip, groove, overhang):
    shape = outline_of(outline)
    model = relief(letter(shape), shape)
    stamp = stamp_print(
        model, settings=StampSettings(block_mm=40, grip_mm=grip, groove_mm=groove, overhang_deg=overhang)
    )
    mesh = trimesh.load(io.BytesIO(FORMATS["stl"].write(stamp, FileOptions())), file_type="stl")
    assert mesh.is_watertight and mesh.body_count == 1
    assert downward_overhangs_deg(mesh).max() <= overhang + 1e-3


# --------------------------------------------------------------------------- the slicers


PRUSA_CONFIG = (
    "layer_height = 0.2\nfirst_layer_height = 0.2\nbed_shape = 0x0,120x0,120x120,0x120\n"
    "support_material = 1\nsupport_material_auto = 1\nsupport_material_threshold = 0\n"
)
"""PrusaSlicer asked to add supports wherever its automatic detection finds an overhang."""


def slice_both(stl, tmp_path):
    """``(PrusaSlicer's --info, its G-code, CuraEngine's G-code)`` of ``stl``, supports on where needed."""
    prusa = program("prusa-slicer", "apt-get install prusa-slicer")
    engine = program("CuraEngine", "apt-get install cura-engine")
    ini = tmp_path / "printer.ini"
    ini.write_text(PRUSA_CONFIG)
    info = run([prusa, "--info", stl], timeout=120).stdout
    gcode = tmp_path / "prusa.gcode"
    cmd = [prusa, "--loglevel", "1", "--datadir", tmp_path / "prusa-data", "--load", ini, "--export-gcode",
           "--dont-arrange", "--output", gcode, stl]  # fmt: skip
    done = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    # Cura's own overhang limit: its default support_angle
    settings_ = ["-s", "layer_height=0.2", "-s", "layer_height_0=0.2", "-s", "adhesion_type=none"]
    settings_ += ["-s", "support_enable=true"]
    cura_out = tmp_path / "cura.gcode"
    definitions = cura_definitions() / "fdmprinter.def.json"
    run([engine, "slice", "-j", definitions, *settings_, "-l", stl, "-o", cura_out], timeout=300)
    return info, gcode.read_text(), cura_out.read_text()


def test_prusaslicer_and_curaengine_slice_the_stamp_and_add_no_support(tmp_path):
    stamp, *_ = made(outline_of("square"))
    stl = tmp_path / "stamp.stl"
    stl.write_bytes(FORMATS["stl"].write(stamp, FileOptions()))
    info, prusa, cura = slice_both(stl, tmp_path)
    assert re.search(r"^manifold = yes$", info, re.M) and re.search(r"^number_of_parts =\s+1$", info, re.M)
    assert float(re.search(r"^size_z = ([0-9.]+)$", info, re.M).group(1)) == pytest.approx(TOP)
    assert ";TYPE:Support material" not in prusa
    zs = [float(z) for z in re.findall(r"^;Z:([0-9.]+)$", prusa, flags=re.M)]
    assert len(zs) == round(TOP / LAYER) and zs[-1] == pytest.approx(TOP)
    assert ";TYPE:SUPPORT" not in cura
    assert int(re.search(r"^;LAYER_COUNT:(\d+)$", cura, re.M).group(1)) == round(TOP / LAYER)


def test_the_slicers_do_add_support_to_a_groove_flatter_than_they_allow(tmp_path):
    stamp, *_ = made(outline_of("square"), overhang_deg=65)
    stl = tmp_path / "flat.stl"
    stl.write_bytes(FORMATS["stl"].write(stamp, FileOptions()))
    _, prusa, cura = slice_both(stl, tmp_path)
    assert ";TYPE:Support material" in prusa and ";TYPE:SUPPORT" in cura


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "name, value, text",
    [
        ("block_mm", 0, "block_mm must be a finite number > 0 and <= 200, got 0"),
        ("block_mm", 500, "block_mm must be a finite number > 0 and <= 200, got 500"),
        ("grip_mm", 0, "grip_mm must be a finite number > 0 and <= 20, got 0"),
        ("grip_mm", math.nan, "grip_mm must be a finite number > 0 and <= 20, got nan"),
        ("groove_mm", -1, "groove_mm must be a finite number >= 0 and <= 100, got -1"),
        ("overhang_deg", 80, "overhang_deg must be a finite number >= 20 and <= 70, got 80"),
        ("overhang_deg", "45", "overhang_deg must be a finite number >= 20 and <= 70, got '45'"),
    ],
)
def test_a_setting_out_of_range_is_refused_naming_it_its_value_and_range(name, value, text):
    with pytest.raises(ParameterError, match=re.escape(text)) as info:
        StampSettings(**{name: value})
    assert info.value.param == name


def test_a_block_too_short_for_its_groove_is_refused():
    with pytest.raises(ParameterError, match=r"block_mm must be at least 16 mm .* got 12") as info:
        StampSettings(block_mm=12, grip_mm=4, groove_mm=4)
    assert info.value.param == "block_mm"


def test_a_block_too_short_for_the_taller_chamfer_of_its_outline_is_refused_when_the_stamp_is_made():
    settings_ = StampSettings(block_mm=16.5, grip_mm=4, groove_mm=4)  # enough for a circle
    stamp_print(relief(letter(outline_of("circle")), outline_of("circle")), settings=settings_)
    square = outline_of("square")  # a corner moves the depth times sqrt(2)
    with pytest.raises(ParameterError, match=r"block_mm must be at least 19\.3\d* mm .* got 16\.5") as info:
        stamp_print(relief(letter(square), square), settings=settings_)
    assert info.value.param == "block_mm"


def test_a_groove_too_deep_for_the_outline_is_refused():
    small = outline_of("square", 20.0)
    with pytest.raises(ParameterError, match=r"grip_mm must be at most 5 mm for this outline .* got 6") as info:
        stamp_print(relief(letter(small), small), settings=StampSettings(block_mm=40, grip_mm=6))
    assert info.value.param == "grip_mm"
    assert f"{NECK_MM:g} mm disc" in str(info.value)


def test_an_outline_that_is_not_convex_is_refused():
    ell = shapely.box(0, 0, 40, 40).difference(shapely.box(20, 20, 40, 40))
    with pytest.raises(ParameterError, match=r"outline must be one convex polygon.* 200 mm\^2 larger") as info:
        stamp_print(relief(ell.difference(ell.buffer(-3)), ell))
    assert info.value.param == "outline"


def test_a_print_that_is_not_a_relief_is_refused():
    square = outline_of("square")
    deboss = print_model(letter(square), square, profile="fdm-0.4mm", style="deboss")
    with pytest.raises(ParameterError, match=r"relief print \(style='relief'\), got 'deboss'") as info:
        stamp_print(deboss)
    assert info.value.param == "style"
    with pytest.raises(ParameterError, match="got 'Polygon'"):
        stamp_print(square)


def test_settings_of_another_kind_are_refused():
    square = outline_of("square")
    with pytest.raises(ParameterError, match="settings must be a StampSettings, got dict") as info:
        stamp_print(relief(letter(square), square), settings={"block_mm": 20})
    assert info.value.param == "settings"


def test_the_settings_are_frozen_and_keyword_only():
    with pytest.raises(dataclasses.FrozenInstanceError):
        StampSettings().block_mm = 30  # type: ignore[misc]
    with pytest.raises(TypeError):
        StampSettings(20)  # type: ignore[misc]
