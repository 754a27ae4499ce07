"""Nesting (issue 34): every part placed once, rigidly, inside its sheet, no two closer than the gap."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from shapely.geometry import Point, box

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from hypothesis_scale import examples

from fabtiles import FabricationError, ParameterError
from fabtiles.geometry.nest import ROTATIONS, Nesting, Placement, nest

HEX = shapely.Polygon([(30 * np.cos(a), 30 * np.sin(a)) for a in np.arange(6) * np.pi / 3])


def check_nesting(n: Nesting, parts, gap: float) -> None:
    """Every part once, its placed outline the part moved rigidly, inside its sheet, ``gap`` from the others."""
    w, h = n.sheet_mm
    assert [p.id for p in n.placements] == [i for i, _ in parts]
    for (_pid, shape), p, outline in zip(parts, n.placements, n.outlines, strict=True):
        moved = p.place(shapely.Polygon(shape.exterior))
        assert shapely.hausdorff_distance(moved, outline) < 1e-3 * 1e-3  # under 1 um
        # the inverse: turned back and moved back, the outline is the part
        a = np.radians(p.rotation)
        back = shapely.transform(
            outline,
            lambda xy, p=p, a=a: (xy - p.translation) @ np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]),
        )
        assert shapely.hausdorff_distance(back, shapely.Polygon(shape.exterior)) < 1e-6
        x0, y0, x1, y1 = outline.bounds
        assert x0 >= 0 and y0 >= 0 and x1 <= w and y1 <= h
        if n.rotations != "free":
            assert any(np.isclose(p.rotation % 360, a) for a in ROTATIONS[n.rotations])
    for k in range(n.sheets):
        on = n.on_sheet(k)
        assert on, "no sheet is empty"
        for i in on:
            for j in on:
                if i < j:
                    assert shapely.distance(n.outlines[i], n.outlines[j]) >= gap - 1e-9


@pytest.fixture(scope="module")
def thirty():
    """Thirty parts of three shapes on two sheets: the parts and their nesting."""
    parts = [(f"sq{k}", box(0, 0, 100, 100)) for k in range(10)]
    parts += [(f"hex{k}", HEX) for k in range(10)]
    parts += [(f"c{k}", Point(0, 0).buffer(50, quad_segs=16)) for k in range(10)]
    return parts, nest(parts, sheet_mm=(600, 400), gap_mm=1.15, time_s=2)


def test_thirty_parts_of_three_shapes_on_two_sheets(thirty):
    parts, n = thirty
    check_nesting(n, parts, 1.15)
    # 0.20 m^2 of parts on 0.24 m^2 sheets: two sheets (0.84 of one is beyond any packing of these)
    assert n.sheets <= 2
    assert sum(n.material_use()) == pytest.approx(sum(s.area for _, s in parts) / 240_000, abs=1e-3)


def test_each_sheets_parts_lie_in_its_corner(thirty):
    """Every sheet's block of parts at the sheet's corner, not half-way up its edge (a lone tile's
    corner: test_parts_far_smaller_than_the_sheet_are_placed)."""
    _, n = thirty
    assert n.sheets == 2  # the block of the full sheet and the few parts left for the next
    for k in range(n.sheets):
        corner = np.min([n.outlines[i].bounds[:2] for i in n.on_sheet(k)], axis=0)
        assert corner == pytest.approx((0, 0), abs=1e-9)


def test_a_part_with_holes_is_its_outer_boundary_and_the_dict_form():
    frame = box(0, 0, 50, 50).difference(box(10, 10, 40, 40))
    n = nest({"frame": frame, "small": box(0, 0, 10, 10)}, sheet_mm=(70, 52), gap_mm=1, time_s=1)
    assert n.sheets == 1  # the small square is not put in the frame's hole: it waits beside it
    assert n.outlines[0].area == pytest.approx(2500)
    assert not shapely.intersects(n.outlines[0], n.outlines[1])


def test_half_turns_only_and_no_turns():
    parts = [(k, box(0, 0, 80, 20)) for k in range(4)]
    for mode in ("180", "none"):
        n = nest(parts, sheet_mm=(100, 100), gap_mm=2, rotations=mode, time_s=1)
        check_nesting(n, parts, 2)
        allowed = {0.0, 180.0} if mode == "180" else {0.0}
        assert {round(p.rotation % 360, 6) for p in n.placements} <= allowed


def test_placement_moves_points_rigidly():
    p = Placement("a", 0, 90.0, (5.0, 0.0))
    assert p.move([[1.0, 0.0], [0.0, 1.0]]) == pytest.approx(np.array([[5.0, 1.0], [4.0, 0.0]]))


@settings(max_examples=examples(3), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.lists(st.tuples(st.floats(5, 60), st.floats(5, 60), st.integers(3, 8)), min_size=1, max_size=8),
    st.sampled_from(tuple(ROTATIONS)),
    st.floats(0, 3),
)
def test_any_parts_are_placed_once_inside_and_apart(sizes, rotations, gap):
    # rectangles and regular polygons of any size that fits, any rotation mode and gap
    parts = []
    for k, (w, h, sides) in enumerate(sizes):
        if k % 2:
            parts.append((k, box(0, 0, w, h)))
        else:
            a = np.arange(sides) * 2 * np.pi / sides
            parts.append((k, shapely.Polygon(np.c_[w / 2 * np.cos(a), w / 2 * np.sin(a)] + (100, -40))))
    n = nest(parts, sheet_mm=(120, 90), gap_mm=gap, rotations=rotations, time_s=1)
    check_nesting(n, parts, gap)


@pytest.mark.parametrize(
    "kwargs, error, match",
    [
        (
            dict(sheet_mm=(90, 90)),
            FabricationError,
            r"part 'big' \(100 x 20 mm\) does not fit on the 90 x 90 mm sheet either way round",
        ),
        (
            dict(sheet_mm=(30, 120), rotations="none"),
            FabricationError,
            r"does not fit on the 30 x 120 mm sheet unturned.*--rotate 90",
        ),
        (dict(sheet_mm=(30, 120), rotations="180"), FabricationError, r"unturned \(rotations '180'\)"),
        (dict(gap_mm=-1), ParameterError, r"gap_mm must be .*>= 0, got -1"),
        (dict(rotations="45"), ParameterError, r"rotations must be one of: none, 180, 90, free, got '45'"),
        (dict(time_s=0), ParameterError, r"time_s must be .*> 0, got 0"),
        (dict(time_s=-2), ParameterError, r"time_s must be .*> 0, got -2"),
        (dict(sheet_mm=(600,)), ParameterError, r"sheet_mm must be \(width, height\) in mm, got \(600,\)"),
        (dict(sheet_mm=(600, 0)), ParameterError, r"sheet_mm\[1\] must be .*> 0, got 0"),
    ],
)
def test_bad_input_is_refused_naming_the_value(kwargs, error, match):
    args = dict(sheet_mm=(200, 200), gap_mm=1, time_s=1) | kwargs
    with pytest.raises(error, match=match):
        nest([("big", box(0, 0, 100, 20))], **args)


@pytest.mark.parametrize(
    "parts, match",
    [
        ([], r"parts must be a non-empty list of \(id, shapely Polygon\) pairs"),
        ([("a", box(0, 0, 1, 1).boundary)], r"parts\[0\] must be an \(id, shapely Polygon of area > 0\) pair"),
        ([("a", box(0, 0, 1, 1)), ("a", box(0, 0, 2, 2))], r"ids must be distinct, got 'a' twice"),
    ],
)
def test_bad_parts_are_refused(parts, match):
    with pytest.raises(ParameterError, match=match):
        nest(parts, sheet_mm=(100, 100), gap_mm=1, time_s=1)


def test_the_default_budget_is_a_fifth_of_a_second_a_part_from_one_to_five_and_progress_is_reported():
    from fabtiles.geometry.nest import DEFAULT_TIME_S, default_time_s

    seen = []
    parts = [(f"p{k}", box(0, 0, 40, 30)) for k in range(3)]
    result = nest(parts, sheet_mm=(200, 200), gap_mm=1, progress=seen.append)
    assert {p.budget_s for p in seen} == {1.0} and len(result.placements) == 3
    # the progress is reported until every part is placed
    assert seen[-1].placed == seen[-1].parts == 3 and seen[-1].sheets == 1
    assert [default_time_s(n) for n in (1, 5, 10, 25, 400)] == [1.0, 1.0, 2.0, DEFAULT_TIME_S, DEFAULT_TIME_S]


def _hexagon(radius):
    a = np.radians(np.arange(6) * 60)
    return shapely.Polygon(np.c_[radius * np.cos(a), radius * np.sin(a)])


@pytest.mark.parametrize("radius,count", [(10, 1), (1, 1), (1, 2)])
def test_parts_far_smaller_than_the_sheet_are_placed(radius, count):
    """The packer panicked on a strip much taller than the parts' area needs (a pyo3 PanicException,
    which is no Exception: a traceback); the strip is lowered, and a lone part it still fails on is
    placed at the corner. A lone part the packer places (radius 10) is at the sheet's corner too, not
    half-way up its edge."""
    parts = [(str(i), _hexagon(radius)) for i in range(count)]
    n = nest(parts, sheet_mm=(400, 300), gap_mm=1, time_s=1)
    placed = n.outlines
    assert [p.sheet for p in n.placements] == [0] * count
    corner = np.min([shape.bounds[:2] for shape in placed], axis=0)
    assert corner == pytest.approx((0, 0), abs=1e-9)
    for shape in placed:
        x0, y0, x1, y1 = shape.bounds
        assert x0 >= 0 and y0 >= 0 and x1 <= 400 and y1 <= 300
    if count == 2:
        assert placed[0].distance(placed[1]) >= 1 - 1e-9


def test_parts_too_small_for_the_packer_at_the_gap_are_a_fabrication_error():
    parts = [(str(i), _hexagon(0.5)) for i in range(2)]
    with pytest.raises(FabricationError, match=r"cannot place 2 parts of at most .* mm across .* apart"):
        nest(parts, sheet_mm=(400, 300), gap_mm=1, time_s=1)
