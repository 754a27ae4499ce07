"""Fabrication checks of laser output."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
from shapely.geometry import Polygon, box

from fabtiles import FabricationError, ParameterError
from fabtiles.geometry.cut_plan import CutOptions, plan_cut
from fabtiles.geometry.laser_checks import check_fits_bed, check_laser
from fabtiles.geometry.narrow import fill_small_holes, small_hole_mask
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")


def codes(report):
    return [f.code for f in report.findings]


def test_clean_plate_has_no_findings():
    plate = box(0, 0, 50, 50).difference(box(10, 10, 20, 20)).difference(box(30, 30, 40, 40))
    assert check_laser(plate, box(0, 0, 50, 50), PLY).ok


def test_small_holes_reported_with_locations():
    plate = box(0, 0, 50, 50).difference(box(10, 10, 10.8, 10.8)).difference(box(30, 30, 30.5, 40))
    plate = plate.difference(box(20, 20, 25, 25))
    report = check_laser(plate, box(0, 0, 50, 50), PLY)
    assert codes(report) == ["small_hole"]
    f = report.findings[0]
    assert f.count == 2 and "min_hole_mm = 1.2 mm" in f.message
    (x1, y1), (x2, y2) = sorted(f.locations)
    assert (x1, y1) == (10.4, 10.4)
    assert x2 == 30.25 and 30.25 <= y2 <= 39.75  # anywhere along the slot's middle line
    # each location carries the hole's width there (its largest inscribed disc)
    sizes = dict(zip(f.locations, f.sizes, strict=True))
    assert sizes[(x1, y1)] == pytest.approx(0.8, abs=0.02) and sizes[(x2, y2)] == pytest.approx(0.5, abs=0.02)
    assert f.worst == pytest.approx(0.5, abs=0.02) and f.unit == "mm"


def test_small_hole_mask_agrees_with_negative_buffer():
    rng = np.random.default_rng(3)
    holes = []
    for _ in range(300):
        n = rng.integers(3, 9)
        t = np.sort(rng.random(n)) * 2 * math.pi
        r = rng.uniform(0.2, 2.5, n)
        p = Polygon(np.c_[r * np.cos(t), r * np.sin(t)])
        if p.is_valid and p.area > 1e-3:
            holes.append(p)
    holes = np.array(holes, dtype=object)
    truth = shapely.is_empty(shapely.buffer(holes, -0.6, quad_segs=16))
    mask = small_hole_mask(holes, 1.2)
    assert (mask == truth).mean() > 0.98  # up to polygonal approximation at the limit


def test_fill_small_holes_keeps_other_parts_and_holes():
    a = box(0, 0, 9, 9).difference(box(1, 1, 1.5, 1.5)).difference(box(4, 4, 8, 8))
    b = box(20, 0, 30, 10).difference(box(22, 2, 28, 8))
    filled, n = fill_small_holes(a.union(b), 1.2)
    assert n == 1
    assert sorted(len(p.interiors) for p in filled.geoms) == [1, 1]
    assert filled.area == pytest.approx(a.union(b).area + 0.25)


def test_thin_bridge_between_holes():
    plate = box(0, 0, 40, 30).difference(box(5, 5, 20, 25)).difference(box(20.4, 5, 35, 25))
    report = check_laser(plate, box(0, 0, 40, 30), PLY, stroke=1.0)
    assert codes(report) == ["thin_bridge"]
    f = report.findings[0]
    assert f.count == 1 and "narrowest 0.4 mm" in f.message
    x, y = f.locations[0]
    assert x == pytest.approx(20.2) and 5 <= y <= 25
    assert f.sizes == pytest.approx((0.4,)) and f.worst == pytest.approx(0.4)


def test_thin_wall_to_the_outline_and_long_rings():
    # the outer ring has many points (a circle): it is split into segments for the index
    disc = shapely.Point(0, 0).buffer(20, quad_segs=64)
    plate = disc.difference(box(-2, -5, 2, 19.6))
    report = check_laser(plate, disc, PLY)
    assert codes(report) == ["thin_bridge"]


def test_spikes_are_not_bridges():
    # a sharp star of material: thin tips, but no bridge
    t = np.arange(16) * math.pi / 8
    r = np.where(np.arange(16) % 2 == 0, 20, 6)
    starplate = Polygon(np.c_[r * np.cos(t), r * np.sin(t)])
    assert check_laser(starplate, starplate.envelope, PLY).ok


def test_loose_parts_per_tile():
    tile = box(0, 0, 50, 50).difference(box(10, 10, 40, 40))
    island = box(20, 20, 30, 30)
    report = check_laser(tile.union(island), box(0, 0, 50, 50), PLY)
    assert codes(report) == ["loose_part"] and report.findings[0].count == 1
    # two tiles, each whole: nothing falls out
    two = shapely.multipolygons([tile, shapely.affinity.translate(tile, 60)])
    outlines = shapely.multipolygons([box(0, 0, 50, 50), box(60, 0, 110, 50)])
    assert check_laser(two, outlines, PLY).ok
    # the same two pieces inside one outline: one of them falls out
    assert codes(check_laser(two, box(0, 0, 110, 50), PLY)) == ["loose_part"]


def test_bed():
    check_fits_bed(box(0, 0, 600, 400), PLY)
    check_fits_bed(box(0, 0, 400, 600), PLY)
    with pytest.raises(FabricationError, match="larger than the 600 x 400 mm bed"):
        check_fits_bed(box(0, 0, 600.1, 400), PLY)


def test_prepare_validates_before_work():
    plate = box(0, 0, 10, 10).difference(box(2, 2, 8, 8))
    outline = box(0, 0, 10, 10)
    with pytest.raises(ParameterError, match="kerf_mm must be >= 0 and <= the stroke"):
        plan_cut(plate, outline, CutOptions.of(profile=PLY, kerf_mm=1.2, stroke=1.1))
    with pytest.raises(ParameterError, match="stroke must be >= min_feature_mm"):
        plan_cut(plate, outline, CutOptions.of(profile=PLY, stroke=0.9))
    with pytest.raises(FabricationError, match="small_hole"):
        plan_cut(plate.difference(box(0.5, 0.5, 1, 1)), outline, CutOptions.of(profile=replace(PLY, strict=True)))
    job = plan_cut(plate, outline, CutOptions.of(profile=PLY, kerf_mm=0))
    report = job.report
    assert job.bounds == (0, 0, 10, 10) and report.stats["cut_length_mm"] == pytest.approx(64)
