"""Kerf contours, ring cleaning, cut order and score paths."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely.geometry import LinearRing, Polygon, box

from fabtiles import ParameterError
from fabtiles.geometry.contours import (
    MITRE_LIMIT,
    clean_rings,
    dissolve_overlaps,
    hilbert_order,
    laser_contours,
    outline_contours,
    score_paths,
)


def star(cx, cy, ro, ri, n=6, rot=0.0):
    t = math.radians(rot) + np.arange(2 * n) * math.pi / n
    r = np.where(np.arange(2 * n) % 2 == 0, ro, ri)
    return Polygon(np.c_[cx + r * np.cos(t), cy + r * np.sin(t)])


def grid_plate(nx=8, ny=6, pitch=10.0):
    outline = box(0, 0, nx * pitch, ny * pitch)
    holes = [star(pitch * (i + 0.5), pitch * (j + 0.5), 4, 2, rot=7 * i) for i in range(nx) for j in range(ny)]
    return outline.difference(shapely.union_all(holes)), outline


def even_odd(rings):
    out = shapely.Polygon()
    for r in rings:
        out = out.symmetric_difference(Polygon(r))
    return out.area


def signed_area(r):
    x, y = r[:, 0], r[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


@pytest.mark.parametrize("kerf", [0.0, 0.1, 0.3, 1.0])
def test_kerf_grows_material(kerf):
    region, outline = grid_plate()
    inner, outer = laser_contours(region, outline, kerf_mm=kerf)
    grown = region.buffer(kerf / 2, join_style="mitre", mitre_limit=MITRE_LIMIT) if kerf else region
    assert len(outer) == 1 and len(inner) == 48
    assert even_odd(inner + outer) == pytest.approx(grown.area, rel=1e-7)
    assert all(signed_area(r) < 0 for r in inner) and all(signed_area(r) > 0 for r in outer)
    for r in inner + outer:
        assert len(r) >= 3 and not np.any(np.all(r == np.roll(r, -1, axis=0), axis=1))


def test_holes_narrower_than_kerf_close():
    region = box(0, 0, 20, 20).difference(box(5, 5, 5.1, 10)).difference(box(10, 10, 15, 15))
    inner, _ = laser_contours(region, kerf_mm=0.2)
    assert len(inner) == 1


def test_inlet_closed_by_kerf_becomes_hole():
    # a C-shape whose 0.1 mm slot closes under a 0.2 mm kerf: the cavity is a new inner contour
    c = box(0, 0, 20, 20).difference(box(5, 5, 15, 15)).difference(box(9.95, 15, 10.05, 20))
    inner, outer = laser_contours(c, kerf_mm=0.2)
    assert len(outer) == 1 and len(inner) == 1
    assert even_odd(inner + outer) == pytest.approx(c.buffer(0.1, join_style="mitre").area, rel=1e-7)


def test_parts_closer_than_kerf_merge():
    two = box(0, 0, 10, 10).union(box(10.05, 0, 20, 10))
    _, outer = laser_contours(two, kerf_mm=0.2)
    assert len(outer) == 1
    apart = box(0, 0, 10, 10).union(box(15, 0, 20, 10))
    _, outer = laser_contours(apart, kerf_mm=0.2)
    assert len(outer) == 2


def test_nested_parts_order():
    region = (
        box(0, 0, 50, 50)
        .difference(box(10, 10, 40, 40))
        .union(box(15, 15, 35, 35).difference(box(20, 20, 30, 30)))
        .union(box(22, 22, 28, 28))
    )
    inner, outer = laser_contours(region, kerf_mm=0)
    assert [r[:, 0].min() for r in inner] == [22, 20, 15, 10]  # deepest first
    assert [r[:, 0].min() for r in outer] == [0]


def test_inner_order_does_not_zigzag():
    region, outline = grid_plate(20, 12)
    inner, _ = laser_contours(region, outline, kerf_mm=0.1)
    centres = np.array([r.mean(axis=0) for r in inner])
    travel = np.hypot(*np.diff(centres, axis=0).T).sum()
    assert travel < 1.35 * 10 * (len(inner) - 1)  # close to one pitch per move
    rng = np.random.default_rng(1)
    shuffled = centres[rng.permutation(len(centres))]
    assert travel < 0.2 * np.hypot(*np.diff(shuffled, axis=0).T).sum()


def test_hilbert_order_is_a_permutation():
    pts = np.random.default_rng(0).random((500, 2)) * 100
    order = hilbert_order(pts)
    assert sorted(order.tolist()) == list(range(500))
    assert hilbert_order(np.zeros((1, 2))).tolist() == [0]


def test_clean_rings_drops_repeats_and_degenerate():
    rings = [
        LinearRing([(0, 0), (1, 0), (1, 0), (1, 1), (0, 1), (0, 0)]),
        LinearRing([(0, 0), (1e-4, 0), (1e-4, 1e-4)]),
    ]
    out, kept = clean_rings(rings, min_area=1e-6, ccw=np.array([False, True]))
    assert kept.tolist() == [0]
    assert out[0].tolist() == [[0, 1], [1, 1], [1, 0], [0, 0]]  # clockwise, no repeats


def test_outline_contours_circle_keeps_vertices():
    circle = shapely.Point(50, 50).buffer(50, quad_segs=64)
    (ring,) = outline_contours(circle, kerf_mm=0.2)
    assert len(ring) == 256
    assert np.hypot(*(ring - 50).T).min() >= 50.09 * math.cos(math.pi / 256)


def test_score_paths_merge_clip_and_dedupe():
    seg = np.array(
        [
            [[0, 0], [5, 0]],
            [[5, 0], [10, 0]],
            [[10, 0], [5, 0]],
            [[10, 0], [10, 5]],
            [[3, 3], [3, 3]],
            [[-5, 8], [5, 8]],
            [[2, 2], [4, 4]],
            [[4, 4], [2, 6]],
            [[4, 4], [6, 4]],
        ],
        float,
    )
    paths = score_paths(seg, box(0, 0, 10, 10))
    lengths = sorted(round(float(np.hypot(*np.diff(p, axis=0).T).sum()), 6) for p in paths)
    # chain through degree-2 vertices merged; duplicate and dot dropped; clipped; the Y split at its node
    assert lengths == [2.0, 2.828427, 2.828427, 5.0, 15.0]
    with pytest.raises(ParameterError, match=r"shape \(k, 2, 2\)"):
        score_paths(np.zeros((3, 2)), box(0, 0, 1, 1))
    with pytest.raises(ParameterError, match="finite"):
        score_paths(np.full((1, 2, 2), np.nan), box(0, 0, 1, 1))


def test_score_paths_run_straight_through_crossings_and_score_overlaps_once():
    # an X of two lines is two paths, not four; a line drawn again in two overlapping pieces (one a 1e-7 mm
    # off, as two motifs compute a shared line) is one path as long as their union
    x = np.array([[[0, 0], [4, 4]], [[0, 4], [4, 0]]], float)
    assert sorted(len(p) for p in score_paths(x, box(-1, -1, 5, 5))) == [2, 2]
    overlap = np.array([[[0, 6], [3, 6]], [[2, 6 + 1e-7], [5, 6 + 1e-7]], [[5, 6], [5, 8]]], float)
    (path,) = score_paths(overlap, box(-1, -1, 9, 9))
    assert float(np.hypot(*np.diff(path, axis=0).T).sum()) == pytest.approx(7.0, abs=1e-6)


@given(
    angle=st.floats(-89, 89),
    cuts=st.lists(st.tuples(st.floats(0, 10), st.floats(0.01, 4)), min_size=1, max_size=6),
    wobble=st.floats(-1e-7, 1e-7),
)
def test_dissolve_overlaps_covers_each_line_once(angle, cuts, wobble):
    # pieces of one line at any direction (near horizontal: either way round pi), each end a little off the
    # line: the dissolved segments cover their union, none overlapping another
    u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    n = np.array([-u[1], u[0]])
    seg = np.array([[u * a + n * wobble, u * (a + length) - n * wobble] for a, length in cuts])
    out = dissolve_overlaps(seg)
    runs = []  # the pieces' union along the line, as intervals
    for a, b in sorted((a, a + length) for a, length in cuts):
        if runs and a <= runs[-1][1] + 1e-5:
            runs[-1][1] = max(runs[-1][1], b)
        else:
            runs.append([a, b])
    lengths = np.sort(np.hypot(*(out[:, 1] - out[:, 0]).T))
    assert lengths == pytest.approx(sorted(b - a for a, b in runs), abs=1e-5)


@settings(max_examples=examples(25), deadline=None)
@given(kerf=st.floats(0, 0.6), n=st.integers(3, 9), rot=st.floats(0, 90), ri=st.floats(0.8, 3.5))
def test_kerf_area_property(kerf, n, rot, ri):
    plate = box(0, 0, 30, 20).difference(star(10, 10, 4, ri, n, rot)).difference(star(21, 10, 4, ri, n, -rot))
    inner, outer = laser_contours(plate, kerf_mm=kerf)
    grown = plate.buffer(kerf / 2, join_style="mitre", mitre_limit=MITRE_LIMIT) if kerf > 1e-6 else plate
    assert even_odd(inner + outer) == pytest.approx(grown.area, rel=1e-6)


@pytest.mark.parametrize("kerf", [0.0, 0.2, 0.5])
def test_island_close_to_its_hole_merges_exactly(kerf):
    # islands 0.1 mm from the hole's edge and from each other: under the kerf they join the plate
    region = (
        box(0, 0, 50, 50)
        .difference(box(10, 10, 40, 40))
        .union(box(10.1, 12, 20, 20))
        .union(box(20.1, 12, 30, 20))
        .union(box(25, 25, 30, 30).difference(box(26, 26, 29, 29)))
    )
    inner, outer = laser_contours(region, kerf_mm=kerf)
    grown = region.buffer(kerf / 2, join_style="mitre", mitre_limit=MITRE_LIMIT) if kerf else region
    assert even_odd(inner + outer) == pytest.approx(grown.area, rel=1e-7)
    parts = shapely.get_parts(grown)
    assert len(inner) + len(outer) == len(parts) + shapely.get_num_interior_rings(parts).sum()
