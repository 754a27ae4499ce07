"""Holding tabs (issue 34): the outer cut split into open pieces around evenly spread gaps."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import example, given, settings
from hypothesis import strategies as st
from shapely.geometry import Point, box

from fabtiles import ParameterError
from fabtiles.geometry.cut_plan import CutOptions, KitOptions, plan_cut, plan_kit
from fabtiles.geometry.job_time import path_lengths
from fabtiles.geometry.tabs import PIECES_PER_TAB, check_tabs, tab_paths
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")


def ring_of(polygon) -> np.ndarray:
    """The exterior of ``polygon`` counter-clockwise, without the repeated first point."""
    return np.asarray(shapely.get_coordinates(shapely.geometry.polygon.orient(polygon, 1).exterior))[:-1]


def gaps(ring: np.ndarray, pieces: list) -> np.ndarray:
    """The length along ``ring`` of each gap between one piece's end and the next piece's start."""
    line = shapely.LinearRing(ring)
    perimeter = line.length
    starts = np.array([line.project(Point(p[0])) for p in pieces])
    ends = np.array([line.project(Point(p[-1])) for p in pieces])
    return (np.roll(starts, -1) - ends) % perimeter


def star(points: int, outer: float, inner: float) -> np.ndarray:
    t = np.arange(2 * points) * np.pi / points
    r = np.where(np.arange(2 * points) % 2 == 0, outer, inner)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def test_a_squares_tabs_are_at_the_middles_of_its_sides():
    sq = ring_of(box(0, 0, 40, 40))
    tabs = tab_paths([sq], tab_mm=0.8, tabs_per_part=4)
    assert sorted(map(tuple, tabs.midpoints.tolist())) == [(0, 20), (20, 0), (20, 40), (40, 20)]
    assert len(tabs.pieces) == 4 and tabs.count == 4 and len(tabs.short) == 0
    assert gaps(sq, tabs.pieces) == pytest.approx([0.8] * 4, abs=1e-9)
    assert path_lengths(tabs.pieces, closed=False).sum() == pytest.approx(160 - 4 * 0.8, abs=1e-9)


def test_a_hexagons_three_tabs_sit_on_alternate_sides_away_from_its_corners():
    t = np.radians(90 + 60 * np.arange(6))
    hexagon = np.column_stack([30 * np.cos(t), 30 * np.sin(t)])
    tabs = tab_paths([hexagon], tab_mm=1.0, tabs_per_part=3)
    corners = shapely.MultiPoint(hexagon)
    # the middle of a side of 30 mm is 15 mm from either corner
    assert [corners.distance(Point(p)) for p in tabs.midpoints] == pytest.approx([15.0] * 3, abs=1e-6)


def test_a_ring_without_corners_keeps_its_tabs_evenly_spread():
    circle = ring_of(Point(0, 0).buffer(20, quad_segs=32))
    tabs = tab_paths([circle], tab_mm=0.5, tabs_per_part=5)
    line = shapely.LinearRing(circle)
    at = np.sort([line.project(Point(p)) for p in tabs.midpoints])
    assert np.diff(np.r_[at, at[0] + line.length]) == pytest.approx([line.length / 5] * 5, abs=1e-6)


def test_a_short_ring_gets_fewer_tabs_and_a_tiny_one_none():
    small = ring_of(box(0, 0, 3, 3))  # 12 mm round: 4 tabs of 1.5 mm need 18 mm
    tiny = ring_of(box(10, 10, 11, 11))  # 4 mm round, less than 3 tab lengths
    tabs = tab_paths([small, tiny], tab_mm=1.5, tabs_per_part=4)
    assert tabs.per_ring.tolist() == [2, 0] and tabs.short.tolist() == [0, 1]
    assert len(tabs.pieces) == 3
    assert np.array_equal(tabs.pieces[-1][0], tabs.pieces[-1][-1])  # the tiny ring whole, back to its start
    assert "2 parts shorter round than 3 x tab_mm per tab got fewer tabs" in tabs.note()


@settings(max_examples=60, deadline=None)
@given(
    points=st.integers(3, 12),
    outer=st.floats(5, 80),
    ratio=st.floats(0.2, 0.95),
    tab=st.floats(0.1, 3.0),
    per=st.integers(1, 10),
)
@example(points=11, outer=16.02218356003422, ratio=0.5, tab=1.0, per=1)  # 24 points rounded: 1.07e-5 mm off
def test_pieces_and_gaps_make_the_ring(points, outer, ratio, tab, per):
    """Every piece lies on the ring; the gaps are tab_mm long along it; pieces and gaps add up to its length."""
    ring = star(points, outer, outer * ratio)
    perimeter = shapely.LinearRing(ring).length
    tabs = tab_paths([ring], tab_mm=tab, tabs_per_part=per)
    n = min(per, int(perimeter // (PIECES_PER_TAB * tab)))
    assert tabs.count == n == len(tabs.pieces) and len(tabs.midpoints) == n
    line = shapely.LinearRing(ring)
    assert max(line.distance(Point(p)) for piece in tabs.pieces for p in piece) < 1e-5
    assert gaps(ring, tabs.pieces) == pytest.approx([tab] * n, abs=1e-5)
    # each point is on the files' 1e-6 mm grid: a segment's length moves by up to sqrt(2) 1e-6 mm
    grid = sum(len(piece) - 1 for piece in tabs.pieces) * 1.5e-6
    assert path_lengths(tabs.pieces, closed=False).sum() + n * tab == pytest.approx(perimeter, abs=max(grid, 1e-9))
    # each gap's midpoint is the tab's, on the ring
    assert max(line.distance(Point(p)) for p in tabs.midpoints) < 1e-5


def test_plan_cut_tabs_the_outer_cut_only_and_the_estimate_follows():
    plate = box(0, 0, 60, 40).difference(box(10, 10, 20, 20)).difference(box(30, 10, 50, 30))
    plain = plan_cut(plate, box(0, 0, 60, 40), CutOptions.of(profile=PLY))
    plan = plan_cut(plate, box(0, 0, 60, 40), CutOptions.of(profile=PLY, tab_mm=0.6, tabs_per_part=4))
    outer = next(layer for layer in plan.layers if layer.role == "outer")
    inner = next(layer for layer in plan.layers if layer.role == "inner")
    assert not outer.closed and inner.closed and len(inner.paths) == 2
    assert len(outer.paths) == 4
    assert plan.estimate.pierces == plain.estimate.pierces + 3 == 6
    assert plan.estimate.cut_mm["outer_cut"] == pytest.approx(plain.estimate.cut_mm["outer_cut"] - 4 * 0.6, abs=1e-6)
    assert plan.estimate.cut_mm["inner_cut"] == pytest.approx(plain.estimate.cut_mm["inner_cut"], abs=1e-9)
    stats = plan.report.stats
    assert stats["outer_contours"] == 1 and stats["tabs"]["tabs"] == 4 and stats["tabs"]["outer_pieces"] == 4
    assert stats["cut_length_mm"] == pytest.approx(plain.report.stats["cut_length_mm"] - 2.4, abs=1e-3)
    assert any(n.startswith("holding tabs: 4 tabs of 0.6 mm in 1 part (4 per part) at (") for n in stats["notes"])


@pytest.mark.parametrize("mode", ["score", "engrave"])
def test_the_outline_cut_of_the_other_modes_gets_tabs(mode):
    plate = box(0, 0, 30, 30).difference(box(10, 10, 20, 20))
    lines = np.array([[[0, 15], [30, 15]]], float)
    plan = plan_cut(
        plate, box(0, 0, 30, 30), CutOptions.of(profile=PLY, mode=mode, tab_mm=0.5, tabs_per_part=2), centrelines=lines
    )
    assert len(plan.paths("outer")) == 2 and plan.report.stats["tabs"]["tabs"] == 2


def test_an_inlay_kits_lattice_and_pieces_get_tabs():
    plate = box(0, 0, 40, 40).difference(box(5, 5, 15, 15)).difference(box(20, 20, 35, 35))
    kit = plan_kit(plate, box(0, 0, 40, 40), KitOptions.of(profile=PLY, tab_mm=0.5, tabs_per_part=3))
    assert len(kit.lattice.paths("outer")) == 3
    assert len(kit.pieces.paths("outer")) == 6 and kit.pieces.estimate.pierces == 6
    assert kit.report.stats["pieces_tabs"]["tabs"] == 6
    assert any(n.startswith("pieces' holding tabs: 6 tabs") for n in kit.report.stats["notes"])


@pytest.mark.parametrize(
    ("tab", "per", "msg"),
    [
        (-0.5, 4, r"tab_mm must be a number of mm from 0 to 5 \(0: no tabs; else more than the kerf\), got -0\.5"),
        (6, 4, r"tab_mm must be a number of mm from 0 to 5 .*, got 6"),
        (0.5, 0, r"tabs_per_part must be an integer >= 1 and <= 64, got 0"),
        (0.5, 2.5, r"tabs_per_part must be an integer >= 1 and <= 64, got 2\.5"),
        (0.1, 4, r"tab_mm must be 0 \(no tabs\) or more than the kerf \(0\.15 mm\), got 0\.1: .* make tab_mm larger"),
    ],
)
def test_bad_tabs_are_parameter_errors(tab, per, msg):
    with pytest.raises(ParameterError, match=msg):
        plan_cut(box(0, 0, 10, 10), box(0, 0, 10, 10), CutOptions.of(profile=PLY, tab_mm=tab, tabs_per_part=per))


def test_no_tabs_by_default():
    assert check_tabs(None, None) == (0.0, 4)
    plan = plan_cut(box(0, 0, 10, 10), box(0, 0, 10, 10), CutOptions.of(profile=PLY, tab_mm=0.0))
    assert plan.layers[-1].closed and "tabs" not in plan.report.stats


@pytest.mark.parametrize("profile", ["router-6mm-mdf", "waterjet-1mm-aluminium"])
def test_routers_and_waterjets_leave_tabs_to_cam(profile):
    p = load_profile(profile)
    with pytest.raises(
        ParameterError,
        match=rf"tab_mm must be 0 for {p.kind} profile '{profile}', got 0\.5: a "
        rf"{p.kind} file holds the part whole and CAM adds the holding tabs",
    ):
        plan_cut(box(0, 0, 100, 100), box(0, 0, 100, 100), CutOptions.of(profile=p, tab_mm=0.5))


def test_a_kits_tab_no_wider_than_the_kerf_is_refused():
    with pytest.raises(ParameterError, match=r"tab_mm must be 0 \(no tabs\) or more than the kerf \(0\.3 mm\)"):
        plan_kit(
            box(0, 0, 40, 40).difference(box(5, 5, 15, 15)),
            box(0, 0, 40, 40),
            KitOptions.of(profile=PLY, kerf_mm=0.3, tab_mm=0.2),
        )
