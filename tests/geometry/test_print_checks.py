"""Printability checks (issue 5)."""

from __future__ import annotations

import pytest
import shapely
from shapely.geometry import box

from fabtiles import ParameterError
from fabtiles.geometry.narrow import narrow_places
from fabtiles.geometry.print_checks import check_print


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


@pytest.mark.parametrize("style,kw,what", [
    ("relief", dict(relief_mm=0.3), "the relief (relief_mm = 0.3 mm)"),
    ("relief", dict(base_mm=0.2), "the plate (base_mm = 0.2 mm)"),
    ("pierced", dict(pierced_mm=0.35), "the tile (pierced_mm = 0.35 mm)"),
    ("deboss", dict(deboss_mm=0.2), "the groove depth"),
    ("deboss", dict(base_mm=1.0, deboss_mm=0.8), "the floor under the grooves"),
])
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
