"""The part as a bit of radius r makes it (fabtiles.geometry.tool_opening), checked against GEOS on its own."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
from dxf_helpers import assert_no_corner_sharper_than, motif_tile, opened_reference, star_plate, star_polygon
from hypothesis import given
from hypothesis import strategies as st
from shapely.geometry import Polygon, box

from fabtiles import ParameterError, ProfileError
from fabtiles.geometry.tool_opening import VISIBLE_MM, check_tool, open_region, quad_segs_for
from fabtiles.machines.profiles import load_profile

ROUTER = load_profile("router-3.175mm-plywood")
R = ROUTER.tool_radius_mm


def hole_polygons(region):
    return [Polygon(h) for p in getattr(region, "geoms", [region]) for h in p.interiors]


def test_quad_segs_keep_the_chord_error_within_a_quarter_of_the_tolerance():
    for r in (0.5, 1.5875, 3.0, 10.0):
        q = quad_segs_for(r, 0.01)
        assert r * (1 - math.cos(math.pi / (4 * q))) <= 0.0025
        assert r * (1 - math.cos(math.pi / (4 * (q - 1)))) > 0.0025 or q == 2  # the fewest that do


def test_holes_match_geos_opening_at_64_segments():
    region, _, _ = motif_tile(size=100, frame=5, stroke=1.2)
    made = open_region(region, radius_mm=R, tolerance_mm=0.01)
    reference, ref_holes = opened_reference(region, R)
    assert shapely.symmetric_difference(made.region, reference).area <= 0.001 * reference.area
    mine = hole_polygons(made.region)
    assert len(mine) == len(ref_holes)
    tree = shapely.STRtree(ref_holes)
    pair = tree.nearest([h.representative_point() for h in mine])
    hd = shapely.hausdorff_distance(np.array(mine), np.array(ref_holes)[pair])
    assert hd.max() <= 0.01


def test_no_hole_corner_is_sharper_than_the_tool():
    region, _ = star_plate(size=60, grid=3, r_out=9, r_in=4.5)
    made = open_region(region, radius_mm=R, tolerance_mm=0.01)
    for hole in hole_polygons(made.region):
        assert_no_corner_sharper_than(hole, R)
    with pytest.raises(AssertionError):  # the check sees a sharp star
        assert_no_corner_sharper_than(hole_polygons(region)[0], R)


def test_a_square_hole_gets_four_rounded_corners_where_they_were():
    plate = box(0, 0, 30, 30).difference(box(10, 10, 20, 20))
    made = open_region(plate, radius_mm=2, tolerance_mm=0.01)
    got = sorted(map(tuple, shapely.get_coordinates(made.corners).round(6).tolist()))
    assert got == [(10.0, 10.0), (10.0, 20.0), (20.0, 10.0), (20.0, 20.0)]
    assert made.moved == pytest.approx([2 * math.sqrt(2) - 2] * 4, abs=0.006)
    # four fillets of r^2 (1 - pi/4) stay material, within the chords' error
    assert made.region.area - plate.area == pytest.approx(4 * 4 * (1 - math.pi / 4), abs=0.05)
    assert made.region.exterior.equals(plate.exterior)  # the convex outline is kept exactly


def test_a_hole_narrower_than_the_tool_vanishes_and_a_neck_splits_a_hole():
    plate = box(0, 0, 60, 30).difference(box(5, 5, 7, 25))  # 2 mm slot: a 3.175 mm bit cannot enter
    dumbbell = box(20, 5, 30, 25).union(box(40, 5, 50, 25)).union(box(29, 14, 41, 16))  # 2 mm neck
    plate = plate.difference(dumbbell)
    made = open_region(plate, radius_mm=R, tolerance_mm=0.01)
    assert made.holes == 2 and made.vanished == 1
    assert made.vanished_holes[0].equals(box(5, 5, 7, 25))
    assert len(made.region.interiors) == 2  # the dumbbell's two ends; the neck stays material
    assert made.region.contains(shapely.Point(35, 15))


def test_concave_outline_corners_are_rounded_convex_ones_kept():
    ell = Polygon([(0, 0), (40, 0), (40, 20), (20, 20), (20, 40), (0, 40)])
    made = open_region(ell, radius_mm=3, tolerance_mm=0.01)
    assert made.closed_shells == 1
    assert made.region.area - ell.area == pytest.approx(9 * (1 - math.pi / 4), abs=0.02)
    for corner in [(0, 0), (40, 0), (40, 20), (0, 40), (20, 40)]:
        assert shapely.Point(corner).distance(made.region.exterior) < 1e-9
    assert shapely.get_coordinates(made.corners).round(6).tolist() == [[20.0, 20.0]]


def test_an_island_in_a_hole_is_opened_around():
    plate = box(0, 0, 50, 50).difference(box(10, 10, 40, 40)).union(box(20, 20, 30, 30))
    made = open_region(plate, radius_mm=2, tolerance_mm=0.01)
    free = box(10, 10, 40, 40).difference(box(20, 20, 30, 30))
    opened = free.buffer(-2, quad_segs=64).buffer(2, quad_segs=64)
    reference = box(0, 0, 50, 50).difference(opened)
    assert shapely.symmetric_difference(made.region, reference).area <= 0.001 * reference.area
    assert made.vanished == 0 and len(made.corners) == 4  # the hole's corners; the island's stay sharp


def test_check_tool_reports_every_removed_hole_and_can_fill_them():
    plate, _ = star_plate(size=60, grid=3, r_out=7, r_in=3.5)
    plate = plate.difference(shapely.union_all([box(x, 2, x + 1.5, 4) for x in (5, 25, 45)]))
    reference, _ = opened_reference(plate, R)
    want = sum(Polygon(h).buffer(-R, quad_segs=64).is_empty for h in plate.interiors)
    made, report, filled = check_tool(plate, ROUTER)
    [small] = [f for f in report.findings if f.code == "small_hole"]
    assert small.count == want == 3 and filled == 0
    assert "the 3.175 mm bit (tool_diameter_mm of router profile 'router-3.175mm-plywood')" in small.message
    for x, y in small.locations:  # each at the place of a removed hole, its width given
        assert 2 <= y <= 4 and any(s <= x <= s + 1.5 for s in (5, 25, 45))
    assert small.sizes == pytest.approx([1.5] * 3, abs=0.02)
    [corner] = [f for f in report.findings if f.code == "rounded_corner"]
    assert corner.count == 9 * 8 and min(corner.sizes) > VISIBLE_MM and "r = 1.5875 mm" in corner.message
    _, report, filled = check_tool(plate, ROUTER, fill_small_holes=True)
    assert filled == 3 and "small_hole" not in {f.code for f in report.findings}
    assert made.area == pytest.approx(reference.area, rel=1e-3)


def test_a_tool_wider_than_every_hole_is_refused():
    plate, _ = star_plate(size=60, grid=3, r_out=7, r_in=3.5)
    big = replace(ROUTER, tool_diameter_mm=20.0)
    with pytest.raises(
        ParameterError,
        match=r"tool_diameter_mm = 20 mm of router profile 'router-3.175mm-plywood' "
        r"is wider than every hole of the design \(the widest is 7(\.\d+)? mm\)",
    ):
        check_tool(plate, big)
    with pytest.raises(ParameterError, match=r"kerf_mm = 40 mm of waterjet profile"):
        check_tool(plate, replace(load_profile("waterjet-1mm-aluminium"), kerf_mm=40.0))


@pytest.mark.parametrize(
    "profile,match",
    [
        (replace(ROUTER, tool_diameter_mm=0.0), r"tool_diameter_mm must be > 0 \(the bit's diameter in mm\), got 0\.0"),
        (replace(ROUTER, tool_diameter_mm=None), r"tool_diameter_mm must be > 0 .*got None"),
        (replace(load_profile("waterjet-1mm-aluminium"), kerf_mm=0.0), r"kerf_mm must be > 0 \(the jet's diameter"),
    ],
)
def test_bad_tools_are_profile_errors(profile, match):
    with pytest.raises(ProfileError, match=match):
        profile.cutter.check_profile(profile)


def test_open_region_needs_a_positive_radius():
    with pytest.raises(ParameterError, match=r"the tool radius must be > 0 mm, got -1"):
        open_region(box(0, 0, 1, 1), radius_mm=-1)


@st.composite
def star_holes(draw):
    n = draw(st.integers(5, 12))
    r_out = draw(st.floats(4.0, 12.0))
    r_in = draw(st.floats(0.3, 0.9)) * r_out
    rot = draw(st.floats(0, 90))
    r = draw(st.floats(0.3, 3.0))
    return star_polygon(20, 20, r_out, r_in, n=n, rotation=rot), r


@given(star_holes())
def test_opening_is_idempotent_adds_no_hole_area_and_leaves_no_corner_sharper_than_r(case):
    hole, r = case
    plate = box(0, 0, 40, 40).difference(hole)
    once = open_region(plate, radius_mm=r, tolerance_mm=0.01).region
    # the tool cuts no material of the design, but within the tolerance at its corners (the chords)
    overcut = shapely.difference(plate, once)
    assert shapely.difference(overcut, hole.exterior.buffer(0.01)).area <= 1e-9
    twice = open_region(once, radius_mm=r, tolerance_mm=0.01).region
    # idempotent within three times the tolerance: a flattened arc of radius r erodes to a point whose
    # place moves with the chords (measured up to 0.0203 mm, tolerance 0.01 mm)
    assert shapely.hausdorff_distance(once, twice, densify=0.05) <= 0.03
    for h in hole_polygons(once):
        assert_no_corner_sharper_than(h, r)
