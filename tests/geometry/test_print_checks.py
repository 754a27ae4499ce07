"""Printability checks (issue 5)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import shapely
from shapely.geometry import box

from fabtiles import FabricationError, ParameterError, ProfileError, load_profile
from fabtiles.geometry.narrow import narrow_places
from fabtiles.geometry.print_checks import check_min_hole, check_print, fill_print_holes, small_openings


def codes(report):
    return [f.code for f in report.findings]


def test_clean_tile_has_no_findings():
    plate = box(0, 0, 50, 50).difference(box(5, 5, 45, 45)).union(box(24, 0, 26, 50))
    assert codes(check_print(plate, box(0, 0, 50, 50), "fdm-0.4mm", stroke=2.0)) == []
    assert codes(check_print(plate, box(0, 0, 50, 50), "fdm-0.4mm")) == []


def test_stroke_narrower_than_min_wall():
    r = check_print(box(0, 0, 10, 10), box(0, 0, 10, 10), "fdm-0.4mm", stroke=0.6)
    assert codes(r) == ["thin_wall"]
    assert "0.6 mm, narrower than min_wall_mm = 0.8 mm" in r.findings[0].message


def test_thin_wall_found_from_geometry_without_stroke():
    plate = box(0, 0, 20, 20).difference(box(1, 1, 19.5, 19))  # 0.5 mm wall on the right
    r = check_print(plate, box(0, 0, 20, 20), "fdm-0.4mm")
    assert codes(r) == ["thin_wall"]
    f = r.findings[0]
    assert "narrowest 0.5 mm" in f.message and f.locations
    assert 19.5 <= f.locations[0][0] <= 20
    count, narrowest, _, _ = narrow_places(plate, 0.8)
    assert count == 1 and narrowest == pytest.approx(0.5)


def test_star_tips_are_not_narrow_places():
    tip = shapely.Polygon([(0, 0), (10, 0), (5, 20)])  # a sharp spike: one boundary
    assert narrow_places(tip, 0.8)[0] == 0


@pytest.mark.parametrize(
    "style,kw,what",
    [
        ("relief", dict(relief_mm=0.3), "the relief (relief_mm = 0.3 mm)"),
        ("relief", dict(base_mm=0.2), "the plate (base_mm = 0.2 mm)"),
        ("pierced", dict(pierced_mm=0.35), "the tile (pierced_mm = 0.35 mm)"),
        ("deboss", dict(deboss_mm=0.2), "the groove depth"),
        ("deboss", dict(base_mm=1.0, deboss_mm=0.8), "the floor under the grooves"),
    ],
)
def test_thinner_than_two_layers(style, kw, what):
    r = check_print(box(0, 0, 10, 10), box(0, 0, 10, 10), "fdm-0.4mm", stroke=1.0, style=style, **kw)
    assert codes(r) == ["thin_layer"]
    assert what in r.findings[0].message and "0.4 mm" in r.findings[0].message


def test_larger_than_bed_is_a_finding_either_way_round():
    assert codes(check_print(box(0, 0, 250, 100), box(0, 0, 250, 100), "fdm-0.4mm", stroke=1)) == []
    r = check_print(box(0, 0, 300, 100), box(0, 0, 300, 100), "fdm-0.4mm", stroke=1)
    assert codes(r) == ["bed_size"]
    assert "256 x 256 mm bed" in r.findings[0].message


def test_loose_parts_only_matter_when_pierced():
    two = shapely.MultiPolygon([box(0, 0, 5, 5), box(10, 0, 12, 2)])
    assert codes(check_print(two, box(0, 0, 12, 5), "fdm-0.4mm", stroke=1)) == []
    r = check_print(two, box(0, 0, 12, 5), "fdm-0.4mm", stroke=1, style="pierced")
    assert codes(r) == ["loose_part"] and r.findings[0].count == 1
    f = r.findings[0]
    assert f.locations == ((11.0, 1.0),) and f.sizes == (4.0,) and f.worst == 4.0 and f.unit == "mm^2"


def test_thin_stroke_walls_are_located():
    # two 0.6 mm bands around a hole: the stroke is too thin, the walls are where it shows
    plate = box(0, 0, 10.6, 10).difference(box(0.6, 0.6, 10, 9.4))
    r = check_print(plate, box(0, 0, 10.6, 10), "fdm-0.4mm", stroke=0.6)
    f = r.findings[0]
    assert f.code == "thin_wall" and f.locations and f.worst == pytest.approx(0.6)
    assert all(s == pytest.approx(0.6) for s in f.sizes)


def test_bad_heights_are_errors():
    with pytest.raises(ParameterError, match="relief_mm must be a finite number > 0"):
        check_print(box(0, 0, 1, 1), box(0, 0, 1, 1), "fdm-0.4mm", relief_mm=0)


# --------------------------------------------------------------------------- small holes (issue 30)


FDM = load_profile("fdm-0.4mm")


def _holed(*holes):
    """A 30 mm plate with the given (x, y, w, h) holes."""
    plate = box(0, 0, 30, 30)
    for x, y, w, h in holes:
        plate = plate.difference(box(x, y, x + w, y + h))
    return plate


def test_min_hole_defaults_to_two_nozzle_widths():
    assert FDM.min_hole_mm == 2 * FDM.nozzle_mm == 0.8
    assert load_profile("fdm-0.6mm").min_hole_mm == 1.2


@pytest.mark.parametrize(
    "style,what", [("pierced", "holes through the tile"), ("relief", "gaps in the raised pattern")]
)
def test_small_holes_are_found_counted_and_placed(style, what):
    plate = _holed((5, 5, 0.3, 0.3), (10, 5, 0.35, 4), (15, 5, 0.9, 0.9), (20, 5, 3, 3))
    r = check_print(plate, box(0, 0, 30, 30), FDM, stroke=1.0, style=style)
    (f,) = [f for f in r.findings if f.code == "small_hole"]
    assert f.count == 2 and what in f.message and "min_hole_mm = 0.8 mm" in f.message
    assert "fill_small_holes" in f.message
    assert sorted(f.sizes) == pytest.approx([0.3, 0.35], abs=0.01) and f.worst == pytest.approx(0.3, abs=0.01)
    # each place is inside its hole
    assert sorted(f.locations) == [
        pytest.approx((5.15, 5.15), abs=0.02),
        (pytest.approx(10.175, abs=0.02), pytest.approx(7.0, abs=2.0)),
    ]


def test_narrowest_is_shown_with_the_digits_that_tell_it_from_the_limit():
    plate = _holed((5, 5, 0.7996, 3))
    (f,) = check_print(plate, box(0, 0, 30, 30), FDM, stroke=1.0, style="pierced").findings
    assert "narrowest 0.7996 mm" in f.message


def test_deboss_small_grooves_and_islands():
    # the region is the grooves: a groove 0.3 mm wide, an island of plate 0.25 mm across in a wide groove
    grooves = box(2, 2, 12, 12).difference(box(6, 6, 6.25, 6.25)).union(box(20, 2, 20.3, 20))
    found = small_openings(grooves, box(0, 0, 30, 30), FDM, "deboss")
    assert len(found.holes) == 1 and len(found.islands) == 1
    r = check_print(grooves, box(0, 0, 30, 30), FDM, style="deboss")
    (f,) = [f for f in r.findings if f.code == "small_hole"]
    assert f.count == 2
    assert "1 groove too narrow to stay open and 1 island of the plate" in f.message
    filled, n = fill_print_holes(grooves, box(0, 0, 30, 30), FDM, "deboss")
    assert n == 2
    assert filled.equals(box(2, 2, 12, 12))  # the island became groove, the narrow groove plate
    assert small_openings(filled, box(0, 0, 30, 30), FDM, "deboss").count == 0


def test_deboss_thin_walls_are_the_plate_between_grooves():
    grooves = box(2, 2, 12, 12).difference(box(6, 6, 6.6, 6.6))  # an island 0.6 mm across: > 0.4, < wall
    r = check_print(grooves, box(0, 0, 30, 30), replace(FDM, min_hole_mm=0.4), style="deboss")
    (f,) = r.findings
    assert f.code == "thin_wall" and "island" in f.message and f.worst == pytest.approx(0.6, abs=0.01)


@pytest.mark.parametrize("style", ["pierced", "relief"])
def test_fill_print_holes_fills_only_what_no_nozzle_disc_fits(style):
    plate = _holed((5, 5, 0.3, 0.3), (10, 5, 0.35, 4), (15, 5, 0.9, 0.9), (20, 5, 3, 3), (25, 5, 1e-3, 1e-3))
    filled, n = fill_print_holes(plate, box(0, 0, 30, 30), FDM, style)
    assert n == 2  # the 1 micron sliver goes uncounted
    assert len(filled.interiors) == 2
    assert filled.area == pytest.approx(plate.area + 0.3 * 0.3 + 0.35 * 4 + 1e-6, rel=1e-9)
    assert not list(check_print(filled, box(0, 0, 30, 30), FDM, style=style).findings)


def test_a_deboss_with_only_too_narrow_grooves_is_refused():
    with pytest.raises(FabricationError, match=r"every groove of this deboss is narrower than min_hole_mm = 0.8"):
        fill_print_holes(box(2, 2, 2.3, 20), box(0, 0, 30, 30), FDM, "deboss")


def test_min_hole_zero_turns_the_check_off():
    plate = _holed((5, 5, 0.01, 0.01), (10, 5, 0.3, 0.3))
    off = replace(FDM, min_hole_mm=0.0)
    assert small_openings(plate, box(0, 0, 30, 30), off, "pierced").count == 0
    assert fill_print_holes(plate, box(0, 0, 30, 30), off, "pierced")[1] == 0


def test_slivers_are_thin_walls_whatever_the_stroke():
    # a 1.2 mm stroke cannot make a 0.3 mm wall, but an outline cutting a band lengthwise can
    plate = box(0, 0, 20, 20).difference(box(1, 1, 19.7, 19))
    r = check_print(plate, box(0, 0, 20, 20), FDM, stroke=1.2)
    (f,) = r.findings
    assert f.code == "thin_wall" and "the stroke is 1.2 mm, so they are slivers" in f.message
    assert f.worst == pytest.approx(0.3)


@pytest.mark.parametrize(
    "value,match",
    [
        (-0.1, r"printer profile 'fdm-0.4mm': min_hole_mm must be a finite number of mm >= 0, got -0.1"),
        (float("nan"), r"min_hole_mm must be a finite number of mm >= 0, got nan"),
        (31.0, r"min_hole_mm = 31 mm is larger than the tile \(30 x 30 mm\); give the narrowest hole"),
    ],
)
def test_bad_min_hole(value, match):
    with pytest.raises(ProfileError, match=match):
        check_min_hole(replace(FDM, min_hole_mm=value), box(0, 0, 30, 30))
    with pytest.raises(ProfileError, match=match):
        check_print(box(0, 0, 30, 30), box(0, 0, 30, 30), replace(FDM, min_hole_mm=value))


def test_small_hole_mask_handles_no_limit():
    from fabtiles.geometry.narrow import small_hole_mask

    assert small_hole_mask(np.array([box(0, 0, 0.1, 0.1)]), 0.0).tolist() == [False]


ARC_HOLE = [
    (14.1857, 4.0252),
    (13.4944, 4.294),
    (12.8155, 4.5928),
    (12.1503, 4.9208),
    (11.5, 5.2776),
    (10.8659, 5.6623),
    (10.2492, 6.0744),
    (9.6511, 6.513),
    (9.0726, 6.9772),
    (8.6858, 7.3164),
    (10.0, 7.3939),
    (11.503, 7.3053),
    (12.7711, 6.4936),
    (13.935, 5.5384),
    (14.4837, 4.1363),
    (14.5445, 3.9034),
]
"""A hole along the inner edge of a 40 mm circle tile's frame, that GEOS's ring simplification by 0.02 mm
leaves 0.026 mm off (it drops the ring's first point after the rest)."""


def test_flatten_holes_keeps_every_hole_within_the_tolerance():
    import shapely

    from fabtiles.geometry.print_checks import flatten_holes

    plate = shapely.Polygon([(0, 0), (20, 0), (20, 20), (0, 20)], [ARC_HOLE])  # the hole's ring as it comes
    flat = flatten_holes(plate, 0.02)
    assert flat.is_valid and flat.exterior.equals(plate.exterior)  # the outer ring is kept as it is
    (hole,), (was,) = flat.interiors, plate.interiors
    assert len(hole.coords) < len(was.coords)  # simplified...
    assert shapely.hausdorff_distance(hole, was) <= 0.02  # ...within the tolerance, every point
    assert abs(flat.area - plate.area) <= 0.02 * was.length


# --------------------------------------------------------------------------- a strip that repeats along x


def _edge_ys(region, x: float) -> list:
    cut = shapely.intersection(region.boundary, shapely.LineString([(x, -1), (x, 100)]))
    return sorted(np.round(shapely.get_coordinates(cut)[:, 1], 6).tolist())


def test_a_periodic_strip_is_filled_alike_at_both_ends():
    from fabtiles.geometry.print_checks import fill_periodic_holes

    # an opening 3 mm wide crossing the seam unevenly: 0.3 mm of it at x = 0, 2.7 mm at x = 20
    strip = shapely.box(0, 0, 20, 10).difference(shapely.box(-0.3, 3, 0.3, 7)).difference(shapely.box(17.3, 3, 20, 7))
    outline = shapely.box(0, 0, 20, 10)
    plain, _ = fill_print_holes(strip, outline, "fdm-0.4mm", "pierced")
    assert _edge_ys(plain, 0) != _edge_ys(plain, 20)  # judged in pieces: the thin end filled, the wide one kept
    filled, n = fill_periodic_holes(strip, outline, "fdm-0.4mm", "pierced", period_mm=20)
    assert n == 0 and _edge_ys(filled, 0) == _edge_ys(filled, 20) == [0.0, 3.0, 7.0, 10.0]


def test_a_periodic_fill_needs_the_outline_to_be_one_period():
    from fabtiles.geometry.print_checks import fill_periodic_holes

    with pytest.raises(ParameterError, match=r"period_mm = 15 is not the outline's width, 20 mm"):
        fill_periodic_holes(shapely.box(0, 0, 20, 10), shapely.box(0, 0, 20, 10), "fdm-0.4mm", "pierced", period_mm=15)
