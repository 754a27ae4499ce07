"""The cut plan (fabtiles.geometry.cut_plan): the modes it refuses, and its paths moved into the positive quadrant."""

from __future__ import annotations

from dataclasses import FrozenInstanceError, replace

import numpy as np
import pytest
import shapely
from shapely.geometry import box

from fabtiles import FabricationError, ParameterError
from fabtiles.geometry.cut_plan import CutOptions, KitOptions, make_plan, plan_cut, plan_kit
from fabtiles.machines.profiles import load_profile

PLATE = box(0, 0, 40, 40)


def test_the_options_take_the_profiles_defaults_once_and_are_frozen():
    ply = load_profile("laser-3mm-plywood")
    o = CutOptions.of(profile="laser-3mm-plywood")
    assert (o.profile, o.mode, (o.kerf_mm, o.kerf_y_mm)) == (ply, ply.mode, ply.kerf_xy_mm)
    assert not hasattr(o, "dxf_version")  # a DXF's version is its file's option, not the plan's
    assert (o.stroke_mm, o.fill_small_holes, o.tab_mm, o.tabs_per_part, o.path, o.fmt) == (None, False, 0.0, 4, "", "")
    given = CutOptions.of(profile=ply, mode="engrave", kerf_mm=0.2, stroke=1.5, tab_mm=0.5, tabs_per_part=2)
    assert (given.mode, given.kerf_mm, given.kerf_y_mm, given.stroke_mm, given.tab_mm, given.tabs_per_part) == (
        "engrave",
        0.2,
        0.2,
        1.5,
        0.5,
        2,
    )
    with pytest.raises(FrozenInstanceError):
        o.kerf_mm = 0.3
    with pytest.raises(TypeError):
        CutOptions(ply, "pierced", 0.15, 0.15)  # keyword-only fields
    kit = KitOptions.of(profile=ply, inlay_base="pocket", stroke=0.5)
    assert (kit.lattice.mode, kit.inlay_fit_mm, kit.inlay_base, kit.stroke_mm) == (
        "engrave",
        ply.inlay_fit_mm,
        "pocket",
        0.5,
    )
    assert KitOptions.of(profile=ply).lattice.mode == "pierced"


def test_the_inlay_mode_is_a_kit_not_one_plan():
    with pytest.raises(
        ParameterError,
        match=r"^the inlay mode writes a kit of two files \(lattice and pieces\): "
        r"export it with Tile\.export\(\.\.\., mode='inlay'\), fabtiles\.making\.export_region\(\.\.\., "
        r"mode='inlay'\) or fabtiles build$",
    ) as err:
        plan_cut(PLATE.difference(box(10, 10, 30, 30)), PLATE, CutOptions.of(profile="laser-3mm-plywood", mode="inlay"))
    assert err.value.param == "mode"


def test_the_score_mode_needs_centrelines():
    with pytest.raises(
        ParameterError,
        match=r"^the score mode needs centrelines \(an array of shape \(k, 2, 2\)\), got none$",
    ) as err:
        plan_cut(PLATE, PLATE, CutOptions.of(profile="laser-3mm-plywood", mode="score"), centrelines=None)
    assert err.value.param == "centrelines"


def test_the_score_mode_with_no_centre_line_in_the_outline_is_refused():
    with pytest.raises(FabricationError, match=r"^the score mode has no line to score: every centre-line"):
        plan_cut(PLATE, PLATE, CutOptions.of(profile="laser-3mm-plywood", mode="score"), centrelines=[])


def test_a_pocket_kit_needs_a_hole_large_enough_for_a_piece():
    # holes of 0.5 mm: far under the profile's smallest piece (twice min_hole_mm, 2.4 mm)
    holes = [box(x, y, x + 0.5, y + 0.5) for x in range(5, 35, 5) for y in range(5, 35, 5)]
    region = PLATE.difference(shapely.union_all(holes))
    with pytest.raises(
        ParameterError, match=r"^the tile has no hole large enough for a piece; nothing to pocket$"
    ) as err:
        plan_kit(region, PLATE, KitOptions.of(profile="laser-3mm-plywood", inlay_base="pocket"))
    assert err.value.param == "region"


# --------------------------------------------------------------------------- the positive quadrant


def _low(plan):
    return np.concatenate([r for layer in plan.layers for r in layer.paths]).min(axis=0)


@pytest.mark.parametrize(
    "outline, kerf_y, want",
    [
        (PLATE, None, (0.075, 0.075)),  # a square's kerf: exactly half the 0.15 mm kerf
        (PLATE, 0.25, (0.075, 0.125)),  # kerf_y_mm: half of it in y
        (shapely.Point(20, 20).buffer(20, quad_segs=64).normalize(), None, (0.075, 0.075)),  # a circle: a little more
    ],
)
def test_the_paths_are_moved_by_their_own_lower_left(outline, kerf_y, want):
    outline = shapely.transform(outline, lambda c: c - shapely.bounds(outline)[:2])
    region = outline.difference(box(15, 15, 25, 25))
    plan = plan_cut(
        region, outline, CutOptions.of(profile=replace(load_profile("laser-3mm-plywood"), kerf_y_mm=kerf_y))
    )
    assert _low(plan).tolist() == [0.0, 0.0] and plan.bounds[:2] == (0.0, 0.0)
    assert plan.offset == pytest.approx(want, abs=1e-5) and min(np.subtract(plan.offset, want)) >= 0
    assert plan.report.stats["file_offset_mm"] == pytest.approx(list(plan.offset), abs=1e-6)
    assert plan.part.equals(region)  # the part stays in the tile's coordinates (the pictures, the findings)


def test_a_kits_plans_share_the_lattices_offset_and_bounds():
    plate = PLATE.difference(box(10, 10, 30, 30))
    kit = plan_kit(plate, PLATE, KitOptions.of(profile="laser-3mm-plywood"))
    assert kit.lattice.offset == kit.pieces.offset == pytest.approx((0.075, 0.075))
    assert kit.pieces.bounds == kit.lattice.bounds
    # the piece (the 20 mm hole grown by the fit and half the kerf) at its hole's place, moved alike
    fit = load_profile("laser-3mm-plywood").inlay_fit_mm
    [piece] = kit.pieces.paths("outer")
    assert piece.min(axis=0) == pytest.approx([10 - fit - 0.075 + 0.075] * 2, abs=1e-6)


def test_bounds_given_frame_the_file_and_an_empty_plan_is_not_moved():
    ply = load_profile("laser-3mm-plywood")
    ring = np.array([[5.0, 5.0], [15.0, 5.0], [15.0, 15.0]])
    framed = make_plan(ply, "pierced", 0.15, {"outer": [ring]}, bounds=(0, 0, 100, 50))
    assert framed.offset == (0.0, 0.0) and framed.bounds == (0.0, 0.0, 100.0, 50.0)
    assert framed.paths("outer")[0].tolist() == ring.tolist()
    moved = make_plan(ply, "pierced", 0.15, {"outer": [ring - 10]}, bounds=(0, 0, 100, 50))
    assert moved.offset == (5.0, 5.0) and moved.bounds == (0.0, 0.0, 105.0, 55.0)
    empty = make_plan(ply, "pierced", 0.15, {})
    assert empty.offset == (0.0, 0.0) and empty.bounds == (0.0, 0.0, 0.0, 0.0)


@pytest.mark.parametrize("size, noted", [((600, 400), True), ((400, 600), True), ((599.8, 399.8), False)])
def test_a_tile_of_the_beds_size_is_noted_where_its_cut_runs_past_the_bed(size, noted):
    # the cut path lies half the 0.15 mm kerf outside the tile: 600.15 x 400.15 mm for a 600 x 400 tile
    tile = box(0, 0, *size)
    plan = plan_cut(
        tile.difference(box(100, 100, 200, 200)), tile, CutOptions.of(profile=load_profile("laser-3mm-plywood"))
    )
    notes = [n for n in plan.report.stats.get("notes", []) if "beyond the 600 x 400 mm bed" in n]
    assert bool(notes) is noted
    if noted:
        assert f"span {size[0] + 0.15:.2f} x {size[1] + 0.15:.2f} mm" in notes[0]
