"""Overhangs of the openings in a wall printed upright, and the pointed tops that remove them."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely import affinity
from shapely.geometry import box

import fabtiles as ft
from fabtiles import ParameterError, load_profile
from fabtiles.geometry.wall_overhangs import (
    ANGLE_TOLERANCE_DEG,
    OVERLAP_MM,
    PEAK_MARGIN_DEG,
    check_wall_overhangs,
    pointed_tops,
    wall_ceilings,
)

FDM = load_profile("fdm-0.4mm")


def codes(report):
    return [f.code for f in report.findings]


def wall_with(*holes, size=(60.0, 60.0)):
    return box(0, 0, *size).difference(shapely.union_all(holes))


def flat_length(region, outline, limit_deg, *, above: bool) -> float:
    """The x length of the openings' edges leaning beyond ``limit_deg`` with material above
    (``above``) or below, found by probing either side of each edge: no ring orientation."""
    openings = shapely.get_parts(outline.difference(region))
    total = 0.0
    eps = 1e-5
    for opening in openings:
        for ring in shapely.get_rings(opening):
            xy = shapely.get_coordinates(ring)
            for a, b in itertools.pairwise(xy):
                dx, dy = b - a
                if math.hypot(dx, dy) < 1e-3 or math.degrees(math.atan2(abs(dx), abs(dy))) <= limit_deg:
                    continue
                m = (a + b) / 2
                if outline.boundary.distance(shapely.Point(m)) < 1e-6:
                    continue
                up = opening.contains(shapely.Point(m[0], m[1] + eps))
                down = opening.contains(shapely.Point(m[0], m[1] - eps))
                if (down and not up) if above else (up and not down):
                    total += abs(dx)
    return total


# --- what counts as a ceiling ------------------------------------------------------------


@pytest.mark.parametrize("limit", [30.0, 45.0, 60.0])
def test_a_round_holes_ceiling_is_its_arc_flatter_than_the_limit(limit):
    r = 8.0
    found = wall_ceilings(wall_with(shapely.Point(30, 30).buffer(r, quad_segs=128)), overhang_deg=limit)
    assert len(found) == 1
    # the edge leans beyond the limit within 90 - limit degrees of the top: 2 r cos(limit) wide
    assert found.span_mm[0] == pytest.approx(2 * r * math.cos(math.radians(limit + ANGLE_TOLERANCE_DEG)), abs=0.05)
    ((x, y),) = found.middles()
    assert (x, y) == (pytest.approx(30, abs=1e-6), pytest.approx(38, abs=1e-3))


def test_a_flat_top_is_one_stretch_as_wide_as_the_hole_and_the_floor_is_none():
    found = wall_ceilings(wall_with(box(10, 10, 23, 14)))
    assert len(found) == 1 and found.span_mm.tolist() == [13.0]
    assert found.middles().tolist() == [[16.5, 14.0]]
    xy = shapely.get_coordinates(found.lines[0])
    assert xy[0].tolist() == [23.0, 14.0] and xy[-1].tolist() == [10.0, 14.0]  # right to left


def test_the_outlines_edges_are_no_ceiling_but_a_notchs_top_is():
    # a notch open at the strip's top has no ceiling; one open at its bottom has its top
    region = box(0, 0, 40, 30).difference(box(5, 20, 15, 30)).difference(box(25, 0, 35, 10))
    found = wall_ceilings(region, outline=box(0, 0, 40, 30))
    assert found.middles().tolist() == [[30.0, 10.0]]


def test_an_island_in_an_opening_has_its_underside_as_a_ceiling():
    island = box(20, 20, 30, 24)
    region = box(0, 0, 50, 50).difference(box(10, 10, 40, 40)).union(island)
    found = wall_ceilings(region)
    assert sorted(found.span_mm.tolist()) == [10.0, 30.0]
    assert [25.0, 20.0] in found.middles().tolist()


def shapes():
    """Openings of a 60 x 60 mm wall: circles, convex polygons and stars, turned at random."""
    circle = st.builds(
        lambda x, y, r: shapely.Point(x, y).buffer(r, quad_segs=8),
        st.floats(12, 48),
        st.floats(12, 48),
        st.floats(1, 8),
    )

    def star(x, y, r, n, turn):
        a = np.radians(turn) + np.pi * np.arange(2 * n) / n
        rad = np.where(np.arange(2 * n) % 2 == 0, r, r * 0.5)
        return shapely.Polygon(np.c_[x + rad * np.cos(a), y + rad * np.sin(a)])

    stars = st.builds(star, st.floats(12, 48), st.floats(12, 48), st.floats(2, 9), st.integers(3, 10), st.floats(0, 90))
    hull = st.lists(st.tuples(st.floats(8, 52), st.floats(8, 52)), min_size=3, max_size=8).map(
        lambda pts: shapely.MultiPoint(pts).convex_hull
    )
    one = st.one_of(circle, stars, hull).filter(lambda g: g.geom_type == "Polygon" and g.area > 1)
    return st.lists(one, min_size=1, max_size=4)


@settings(max_examples=examples(40))
@given(shapes(), st.sampled_from([30.0, 45.0, 60.0]))
def test_the_ceilings_are_the_edges_with_material_above_and_turned_over_the_floors(holes, limit):
    region, outline = wall_with(*holes), box(0, 0, 60, 60)
    limit_plus = limit + ANGLE_TOLERANCE_DEG
    found = wall_ceilings(region, overhang_deg=limit, outline=outline)
    # within the edges shorter than 1e-3 mm the probing skips (where two openings' edges meet)
    assert found.span_mm.sum() == pytest.approx(flat_length(region, outline, limit_plus, above=True), abs=0.01)
    turned = affinity.rotate(region, 180, origin=(30, 30))
    floors = wall_ceilings(turned, overhang_deg=limit, outline=outline)
    assert floors.span_mm.sum() == pytest.approx(flat_length(region, outline, limit_plus, above=False), abs=0.01)
    # left and right are alike: a mirror has the same stretches
    mirrored = wall_ceilings(affinity.scale(region, -1, 1, origin=(30, 30)), overhang_deg=limit, outline=outline)
    assert sorted(mirrored.span_mm.round(6)) == sorted(found.span_mm.round(6))


def upright(x, y, w, h, peak):
    """A vertical-sided opening w x h at (x, y), its top flat (peak 0) or pointed ``peak`` high."""
    top = [(x + w, y + h), (x + w / 2, y + h + peak), (x, y + h)] if peak else [(x + w, y + h), (x, y + h)]
    return shapely.Polygon([(x, y), (x + w, y), *top])


@settings(max_examples=examples(40))
@given(
    st.lists(
        st.tuples(st.floats(2, 50), st.floats(2, 40), st.floats(0.5, 8), st.floats(0.5, 10), st.floats(1.0, 3.0)),
        min_size=1,
        max_size=6,
    ),
    st.sampled_from([30.0, 45.0, 60.0]),
)
def test_vertical_sided_openings_with_pointed_tops_have_no_overhang(openings, limit):
    # each top's sides lean ``lean`` times less than the limit allows (its peak at least w / 2 / tan(limit))
    holes = [upright(x, y, w, h, w / 2 / math.tan(math.radians(limit)) * lean) for x, y, w, h, lean in openings]
    region = wall_with(*holes)
    assert len(wall_ceilings(region, overhang_deg=limit)) == 0
    profile = replace(FDM, max_overhang_deg=limit, max_bridge_mm=0.0)
    assert codes(check_wall_overhangs(region, profile)) == []


# --- the check ---------------------------------------------------------------------------


def test_a_flat_top_narrower_than_the_bridge_is_bridged_and_a_wider_one_is_found():
    narrow = wall_with(box(10, 10, 14.5, 14), box(30, 30, 35, 31))  # 4.5 and 5 mm: bridged
    assert codes(check_wall_overhangs(narrow, FDM)) == []
    wide = wall_with(box(10, 10, 14.5, 14), box(30, 30, 36, 31), box(10, 40, 22, 44))
    (f,) = check_wall_overhangs(wide, FDM).findings
    assert f.code == "overhang" and f.count == 2
    assert f.locations == ((16.0, 44.0), (33.0, 31.0))  # widest first
    assert f.sizes == (12.0, 6.0) and f.worst == 12.0 and f.limit == 5.0
    assert f.message.startswith(
        "2 ceilings of holes through the wall lean more than max_overhang_deg = 45 degrees from vertical over up "
        "to 12 mm, wider than max_bridge_mm = 5 mm"
    )
    assert codes(check_wall_overhangs(narrow, replace(FDM, max_bridge_mm=0.0))) == ["overhang"]


def test_a_shallow_groove_has_no_overhang_and_a_deeper_one_is_judged_as_a_hole():
    grooves = wall_with(box(10, 10, 30, 12))
    step = FDM.layer_height_mm * math.tan(math.radians(FDM.max_overhang_deg))
    assert codes(check_wall_overhangs(grooves, FDM, style="deboss", depth_mm=step)) == []
    (f,) = check_wall_overhangs(grooves, FDM, style="deboss").findings  # the profile's deboss_mm, 0.8 mm
    assert f.message.startswith("1 ceiling of a groove leans more than")
    assert codes(check_wall_overhangs(grooves, replace(FDM, deboss_mm=step), style="deboss")) == []
    report = ft.Report(path="x", format="stl")
    assert check_wall_overhangs(grooves, "fdm-0.4mm", style="deboss", report=report) is report


def test_a_reliefs_gaps_are_judged_by_the_relief_height():
    raised = box(0, 0, 60, 60).difference(box(10, 10, 30, 12))  # the gap between two raised bands
    (f,) = check_wall_overhangs(raised, FDM, style="relief").findings
    assert f.message.startswith("1 ceiling of a gap in the raised pattern leans")
    assert codes(check_wall_overhangs(raised, FDM, style="relief", depth_mm=0.2)) == []


def test_a_hole_across_the_seam_of_a_periodic_strip_is_judged_whole_once():
    strip = box(0, 0, 50, 30)
    wall = strip.difference(shapely.union_all([shapely.Point(x, 15).buffer(6, quad_segs=32) for x in (0, 50)]))
    cut = wall_ceilings(wall, outline=strip)
    whole = wall_ceilings(wall, outline=strip, period_mm=50)
    assert len(cut) == 2 and len(whole) == 1
    assert whole.span_mm[0] == pytest.approx(2 * cut.span_mm.max(), abs=1e-6)
    ((x, _y),) = whole.middles(50)
    assert x == pytest.approx(0, abs=1e-6) or x == pytest.approx(50, abs=1e-6)
    (f,) = check_wall_overhangs(wall, replace(FDM, max_bridge_mm=6), outline=strip, period_mm=50).findings
    assert f.count == 1 and 0 <= f.locations[0][0] < 50


@settings(max_examples=examples(25))
@given(
    st.floats(0, 50), st.lists(st.tuples(st.floats(0, 50), st.floats(8, 22), st.floats(1, 6)), min_size=1, max_size=3)
)
def test_a_periodic_strips_ceilings_do_not_depend_on_where_its_seam_is(shift, circles):
    strip = box(0, 0, 50, 30)

    def wall(dx):
        holes = [
            shapely.Point((x + dx) % 50 + k * 50, y).buffer(r, quad_segs=16) for x, y, r in circles for k in (-1, 0, 1)
        ]
        return strip.difference(shapely.union_all(holes))

    a = wall_ceilings(wall(0), outline=strip, period_mm=50)
    b = wall_ceilings(wall(shift), outline=strip, period_mm=50)
    assert sorted(a.span_mm.round(4)) == pytest.approx(sorted(b.span_mm.round(4)), abs=1e-3)


# --- pointed tops ------------------------------------------------------------------------


@pytest.mark.parametrize("limit", [30.0, 45.0, 60.0])
def test_a_round_hole_becomes_the_classic_teardrop(limit):
    r = 6.0
    region = wall_with(shapely.Point(30, 30).buffer(r, quad_segs=256))
    out = pointed_tops(region, overhang_deg=limit, min_wall_mm=0.8)
    assert (out.raised, out.clipped, out.clipped_at) == (1, 0, ())
    a = math.radians(limit - PEAK_MARGIN_DEG)  # a degree inside the limit
    # the kite of the two tangents at the limit less the circle's sector between them
    assert out.removed_mm2 == pytest.approx(r * r * (1 / math.tan(a) - math.pi / 2 + a), rel=0.01)
    (hole,) = shapely.get_parts(box(0, 0, 60, 60).difference(out.region))
    assert hole.bounds[3] == pytest.approx(30 + r / math.sin(a), abs=0.01)  # the apex
    assert len(wall_ceilings(out.region, overhang_deg=limit - PEAK_MARGIN_DEG)) == 0


def openings_apart(region, out, outline, wall):
    """Each opening after is one before with its peaks; none comes closer to another than ``wall`` or
    than it was."""
    before = shapely.get_parts(outline.difference(region))
    after = shapely.get_parts(outline.difference(out))
    assert len(after) == len(before)
    tree = shapely.STRtree(after)
    for i, j in zip(*tree.query(after, predicate="dwithin", distance=wall - 1e-6), strict=True):
        if i < j:
            was = min(
                shapely.distance(a, b)
                for a in before
                if a.intersects(after[i])
                for b in before
                if b.intersects(after[j])
            )
            assert shapely.distance(after[i], after[j]) >= min(was, wall) - 2 * OVERLAP_MM


def only_over_clipped(region, out, *, overhang_deg, max_bridge_mm=0.0, outline=None):
    """Every stretch left after pointed tops (wider than ``max_bridge_mm``) lies over a clipped peak's
    stretch (of the limit less the peaks' margin): within its x range, not below it."""
    left = wall_ceilings(out.region, overhang_deg=overhang_deg, outline=outline)
    left_xy = left.middles()[left.span_mm > max_bridge_mm]
    before = wall_ceilings(region, overhang_deg=overhang_deg - PEAK_MARGIN_DEG, outline=outline)
    said = {tuple(p) for p in np.round(out.clipped_at, 3).tolist()}
    clipped = [k for k, p in enumerate(np.round(before.middles(), 3).tolist()) if tuple(p) in said]
    assert len(clipped) == out.clipped
    x0, y0, x1, _ = shapely.bounds(before.lines[clipped]).T if clipped else np.empty((4, 0))
    for x, y in left_xy:
        assert ((x0 - 1e-6 <= x) & (x <= x1 + 1e-6) & (y0 - 1e-6 <= y)).any()
    return len(left_xy)


@settings(max_examples=examples(40))
@given(shapes(), st.sampled_from([30.0, 45.0, 60.0]))
def test_pointed_tops_take_only_material_keep_the_walls_and_leave_only_clipped_peaks_overhanging(holes, limit):
    region, outline = wall_with(*holes), box(0, 0, 60, 60)
    out = pointed_tops(region, overhang_deg=limit, min_wall_mm=0.8, outline=outline)
    assert out.region.is_valid and shapely.difference(out.region, region).area < 1e-9
    assert region.area - out.region.area == pytest.approx(out.removed_mm2, abs=1e-9)
    openings_apart(region, out.region, outline, 0.8)
    only_over_clipped(region, out, overhang_deg=limit, outline=outline)


def test_a_flat_top_becomes_a_pointed_arch_and_bridged_ones_stay_flat():
    region = wall_with(box(10, 10, 20, 14), box(40, 10, 44, 14))
    out = pointed_tops(region, overhang_deg=45, min_wall_mm=0.8)
    # a peak over a top w wide, its sides leaning a from vertical, is w / 2 / tan(a) high
    cot = 1 / math.tan(math.radians(45 - PEAK_MARGIN_DEG))
    assert out.raised == 2 and out.removed_mm2 == pytest.approx((25 + 4) * cot, abs=1e-3)
    kept = pointed_tops(region, overhang_deg=45, min_wall_mm=0.8, max_bridge_mm=5)
    assert kept.raised == 1 and kept.removed_mm2 == pytest.approx(25 * cot, abs=1e-3)
    assert wall_ceilings(kept.region).span_mm.tolist() == [4.0]


def test_a_peak_that_would_thin_a_band_is_clipped_and_said():
    below, above = shapely.Point(30, 20).buffer(6, quad_segs=64), box(20, 28, 40, 40)
    region = wall_with(below, above)
    out = pointed_tops(region, overhang_deg=45, min_wall_mm=0.8)
    assert (out.raised, out.clipped) == (2, 1) and out.clipped_at[0] == (
        pytest.approx(30, abs=1e-3),
        pytest.approx(26, abs=1e-3),
    )
    lower, upper = sorted(shapely.get_parts(box(0, 0, 60, 60).difference(out.region)), key=lambda g: g.bounds[1])
    assert upper.intersection(box(0, 0, 60, 40)).symmetric_difference(above).area < 1e-9  # its own peak is above
    assert 0.8 <= shapely.distance(lower, upper) <= 0.82  # the room is kept, rounded up
    # the teardrop's apex would be at 20 + 6 / sin 44 degrees = 28.6, inside the hole above: its top is cut
    # 0.8 mm below
    assert 28 - 0.82 <= lower.bounds[3] <= 28 - 0.8


def test_a_peak_goes_neither_through_nor_around_another_opening():
    # a 30 mm flat top: its peak (15 mm high) meets a slot bridged as it is; the material over the slot stays
    region = wall_with(box(10, 10, 40, 12), box(20, 14, 24, 15))
    out = pointed_tops(region, overhang_deg=45, min_wall_mm=0.8, max_bridge_mm=5)
    assert (out.raised, out.clipped) == (1, 1)
    over_slot = box(20 - 0.8, 14, 24 + 0.8, 60)
    assert out.region.intersection(over_slot).symmetric_difference(region.intersection(over_slot)).area < 1e-9
    assert out.region.geom_type == "Polygon"  # no loose ring around the slot
    assert (
        shapely.distance(box(20, 14, 24, 15), box(0, 0, 60, 60).difference(out.region).difference(box(20, 14, 24, 15)))
        >= 0.8
    )


def test_pointed_tops_on_a_periodic_strip_raise_the_hole_across_the_seam_at_both_ends():
    strip = box(0, 0, 50, 30)
    wall = strip.difference(shapely.union_all([shapely.Point(x, 15).buffer(6, quad_segs=64) for x in (0, 50)]))
    out = pointed_tops(wall, overhang_deg=45, min_wall_mm=0.8, outline=strip, period_mm=50)
    a = math.radians(45 - PEAK_MARGIN_DEG)
    assert out.raised == 1 and out.removed_mm2 == pytest.approx(36 * (1 / math.tan(a) - math.pi / 2 + a), rel=0.01)
    assert len(wall_ceilings(out.region, outline=strip, period_mm=50)) == 0
    # the strip still meets itself at the seam, and the teardrop is whole across it
    ends = [out.region.intersection(shapely.LineString([(x, 0), (x, 30)])) for x in (0, 50)]
    assert ends[0].symmetric_difference(affinity.translate(ends[1], -50)).length < 1e-9
    # on the seam: material up to the hole's bottom and from the teardrop's apex
    ys = np.unique(shapely.get_coordinates(ends[0])[:, 1].round(6))
    assert ys.tolist() == pytest.approx([0, 9, 15 + 6 / math.sin(a), 30], abs=0.01)


# --- real patterns -----------------------------------------------------------------------


def hankin(tiling, edge, angle, stroke):
    pack = ft.ArchimedeanPacking(tiling, edge=edge, method="hankin", contact_angle=angle)
    return ft.Tile("square", 40, pack, frame=2, stroke=stroke).region()


PATTERNS = {
    "table3-3 hex": lambda: ft.Tile(
        "square", 40, ft.HexPacking(radius=8, motif=ft.Star.preset("table3-3")), frame=2, stroke=1
    ).region(),
    "table3-1 hex": lambda: ft.Tile(
        "square", 40, ft.HexPacking(radius=8, motif=ft.Star.preset("table3-1")), frame=2, stroke=1
    ).region(),
    "hankin 4.8.8": lambda: hankin("4.8.8", 10, 67.5, 2.0),
    "hankin 4.6.12": lambda: hankin("4.6.12", 8, 60, 1.0),
    "hankin 4.4.4.4": lambda: hankin("4.4.4.4", 10, 60, 1.0),
}


@pytest.mark.parametrize("name", PATTERNS)
def test_after_pointed_tops_a_pattern_has_no_overhang_and_its_bands_keep_their_width(name):
    region = PATTERNS[name]()
    assert codes(check_wall_overhangs(region, replace(FDM, max_bridge_mm=0.0))) == ["overhang"]
    out = pointed_tops(region, overhang_deg=FDM.max_overhang_deg, min_wall_mm=FDM.min_wall_mm)
    assert out.raised > 0 and out.region.is_valid
    assert codes(check_wall_overhangs(out.region, FDM)) == []
    only_over_clipped(region, out, overhang_deg=FDM.max_overhang_deg)  # what is left to bridge
    # only material is taken, and no two openings come closer than min_wall_mm or than they were
    assert shapely.difference(out.region, region).area < 1e-9
    assert region.area - out.region.area == pytest.approx(out.removed_mm2)
    openings_apart(region, out.region, box(0, 0, 40, 40), FDM.min_wall_mm)


def test_where_a_band_is_too_thin_for_a_peak_only_clipped_peaks_still_overhang():
    region = hankin("4.8.8", 10, 67.5, 1.0)  # bands of 1 mm at 22.5 degrees from horizontal
    out = pointed_tops(region, overhang_deg=45, min_wall_mm=0.8)
    (f,) = check_wall_overhangs(out.region, FDM).findings
    assert 0 < f.count == only_over_clipped(region, out, max_bridge_mm=FDM.max_bridge_mm, overhang_deg=45)


# --- bad input ---------------------------------------------------------------------------


@pytest.mark.parametrize("angle", [0, 90, -5, float("nan"), True, "45"])
def test_a_limit_outside_0_to_90_degrees_is_refused(angle):
    with pytest.raises(ParameterError, match=r"overhang_deg must be a number of degrees from vertical, > 0 and < 90"):
        wall_ceilings(wall_with(box(1, 1, 2, 2)), overhang_deg=angle)
    with pytest.raises(ParameterError, match=r"overhang_deg"):
        pointed_tops(wall_with(box(1, 1, 2, 2)), overhang_deg=angle)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"min_wall_mm": -1}, r"min_wall_mm must be a finite number of mm >= 0, got -1"),
        ({"max_bridge_mm": float("nan")}, r"max_bridge_mm must be a finite number of mm >= 0, got nan"),
        ({"period_mm": 0, "outline": box(0, 0, 60, 60)}, r"period_mm must be a finite number of mm > 0, got 0"),
        (
            {"period_mm": 50, "outline": box(0, 0, 60, 60)},
            r"period_mm = 50 mm must be the strip's width along x \(60 mm\): the strip is one turn",
        ),
    ],
)
def test_bad_lengths_are_refused_by_name(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        pointed_tops(wall_with(box(10, 10, 20, 12)), **kwargs)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"style": "deboss", "depth_mm": 0}, r"depth_mm must be a finite number of mm > 0, got 0"),
        ({"style": "mosaic"}, r"style must be one of: pierced, deboss, relief, got 'mosaic'"),
        ({"depth_mm": 0.8}, r"depth_mm = 0.8 is for a deboss or a relief: a pierced wall's holes go through it"),
    ],
)
def test_a_bad_style_or_depth_is_refused(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        check_wall_overhangs(wall_with(box(10, 10, 20, 12)), FDM, **kwargs)
