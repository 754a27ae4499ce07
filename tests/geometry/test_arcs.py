"""Arcs recovered from flattened rings (fabtiles.geometry.arcs)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely.geometry import LineString, Point, Polygon, box

from fabtiles.geometry.arcs import (
    Curve,
    arc_runs,
    arc_runs_many,
    bezier_error,
    beziers,
    bulge_path,
    curves,
    fit_distance,
    piece_lengths,
)


def _ring(geom) -> np.ndarray:
    return np.asarray(geom.exterior.coords)[:-1]


def _run_vertices(ring, first, last):
    n = len(ring)
    idx = np.arange(first, last + (n if last < first else 0) + 1) % n
    return ring[idx]


@settings(max_examples=examples(40), deadline=None)
@given(st.floats(-300, 300), st.floats(-300, 300), st.floats(0.05, 200), st.integers(2, 64))
def test_a_flattened_circle_is_one_full_arc_with_its_centre_and_radius(x, y, r, quad_segs):
    ring = _ring(Point(x, y).buffer(r, quad_segs=quad_segs))
    sag = r * (1 - np.cos(np.pi / (4 * quad_segs)))
    runs = arc_runs(ring, tolerance_mm=max(sag, 1e-4) * 1.01)
    assert runs.full
    assert len(runs.first) == 1
    assert np.allclose(runs.centre[0], [x, y], atol=1e-6)
    assert runs.radius[0] == pytest.approx(r, abs=1e-6)
    assert abs(runs.sweep[0]) == pytest.approx(2 * np.pi)


@settings(max_examples=examples(40), deadline=None)
@given(st.floats(0.5, 50), st.floats(-np.pi, np.pi), st.floats(0.3, 2.9), st.integers(3, 32), st.booleans())
def test_an_arc_between_straight_edges_is_found_exactly(r, start, sweep, pieces, ccw):
    # an arc of `pieces` chords, then two long straight edges closing the ring
    ang = start + np.linspace(0, sweep, pieces + 1) * (1 if ccw else -1)
    arc = np.column_stack([10 + r * np.cos(ang), 20 + r * np.sin(ang)])
    far = (
        10
        + np.array([np.cos(start + sweep / 2 * (1 if ccw else -1)), np.sin(start + sweep / 2 * (1 if ccw else -1))])
        * -5
        * r
    )
    far[1] += 10
    ring = np.vstack([arc, far])
    tol = r * (1 - np.cos(sweep / pieces / 2)) * 1.01 + 1e-9
    runs = arc_runs(ring, tolerance_mm=tol)
    assert not runs.full
    assert runs.first.tolist() == [0] and runs.last.tolist() == [pieces]
    assert np.allclose(runs.centre[0], [10, 20], atol=1e-6)
    assert runs.radius[0] == pytest.approx(r, abs=1e-6)
    assert runs.sweep[0] == pytest.approx(sweep * (1 if ccw else -1), abs=1e-9)


@pytest.mark.parametrize("sides", [3, 4, 5, 6, 8, 12])
def test_regular_polygons_with_few_sides_have_no_arcs(sides):
    ang = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    ring = np.column_stack([50 * np.cos(ang), 50 * np.sin(ang)])
    assert len(arc_runs(ring, tolerance_mm=0.01).first) == 0


def test_a_square_and_a_subdivided_straight_edge_have_no_arcs():
    # collinear vertices on a straight edge fit a circle of huge radius within the sagitta: no arc
    ring = np.array([[0, 0], [1, 0], [2, 0], [3, 0], [4, 0], [4, 4], [0, 4]], dtype=float)
    assert len(arc_runs(ring, tolerance_mm=0.01).first) == 0
    assert len(arc_runs(_ring(box(0, 0, 10, 10)), tolerance_mm=0.01).first) == 0


@settings(max_examples=examples(30), deadline=None)
@given(
    st.lists(st.tuples(st.floats(-50, 50), st.floats(-50, 50)), min_size=3, max_size=6, unique=True),
    st.floats(0.2, 3),
    st.integers(3, 16),
)
def test_round_joins_of_a_stroked_path_are_arcs_exactly_at_the_joins(points, r, quad_segs):
    pts = np.asarray(points)
    seg = np.diff(pts, axis=0)
    cosines = (seg[:-1] * seg[1:]).sum(axis=1) / np.hypot(*seg[:-1].T) / np.hypot(*seg[1:].T)
    # joins as a pattern's strokes have them: edges longer than the stroke, no turn back
    assume(np.hypot(*seg.T).min() > 4 * r and (cosines > -0.8).all() and LineString(points).is_simple)
    path = LineString(points)
    shape = path.buffer(r, quad_segs=quad_segs, join_style="round", cap_style="round")
    if shape.geom_type != "Polygon" or len(shape.interiors):
        return
    ring = _ring(shape)
    # GEOS divides a join into round(angle / step) chords, so a chord may span 1.5 steps
    tol = r * (1 - np.cos(1.5 * np.pi / (4 * quad_segs))) * 1.01
    runs = arc_runs(ring, tolerance_mm=tol)
    eps = fit_distance(tol)
    for first, last, c, rad in zip(runs.first, runs.last, runs.centre, runs.radius, strict=True):
        # every arc is a join or a cap: its centre is a vertex of the path, its radius the stroke's
        assert np.hypot(*(np.asarray(points) - c).T).min() == pytest.approx(0, abs=1e-6)
        assert rad == pytest.approx(r, abs=1e-6)
        pts = _run_vertices(ring, first, last)
        assert np.abs(np.hypot(*(pts - c).T) - rad).max() <= eps
        # the fitted circle passes exactly through the run's end vertices
        assert np.hypot(*(pts[[0, -1]] - c).T) == pytest.approx([rad, rad], abs=1e-9)
    # arcs exactly at the joins: each maximal stretch of >= 4 ring vertices on the circle of one
    # path vertex (a join or a cap of >= 3 chords) is covered by arcs, and nothing else is
    n = len(ring)
    covered = np.zeros(n, dtype=bool)
    for first, last in zip(runs.first, runs.last, strict=True):
        covered[np.arange(first, last + (n if last < first else 0) + 1) % n] = True
    dist = np.hypot(*(ring[:, None, :] - np.asarray(points)[None, :, :]).transpose(2, 0, 1))
    on = np.abs(dist - r) <= 1e-6
    label = np.where(on.any(axis=1), on.argmax(axis=1), -1)
    start = int(np.flatnonzero(np.r_[label, label[0]][1:] != label)[0]) + 1 if len(set(label)) > 1 else 0
    rolled, cov = np.roll(label, -start), np.roll(covered, -start)
    bounds = np.flatnonzero(np.diff(np.r_[-2, rolled, -2]) != 0)
    for a, b in itertools.pairwise(bounds):
        if rolled[a] >= 0 and b - a >= 4:
            assert cov[a:b].all()
    assert not cov[rolled < 0].any()


def test_two_caps_and_a_join_give_three_arcs_of_the_stroke_radius():
    ring = _ring(LineString([(0, 0), (10, 0), (10, 10)]).buffer(1.0, quad_segs=8))
    runs = arc_runs(ring, tolerance_mm=0.1)
    assert sorted(np.round(runs.radius, 9).tolist()) == [1.0, 1.0, 1.0]
    assert sorted(np.round(np.abs(runs.sweep), 9).tolist()) == pytest.approx([np.pi / 2, np.pi, np.pi])


def test_an_arc_whose_chords_stand_off_more_than_the_tolerance_is_no_arc():
    ring = _ring(Point(0, 0).buffer(10.0, quad_segs=4))
    sag = 10 * (1 - np.cos(np.pi / 16))
    assert arc_runs(ring, tolerance_mm=sag * 1.01).full
    assert len(arc_runs(ring, tolerance_mm=sag * 0.99).first) == 0


def test_an_ellipse_is_split_into_arcs_that_fit():
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    ring = np.column_stack([10 * np.cos(t), 6 * np.sin(t)])
    runs = arc_runs(ring, tolerance_mm=0.01)
    assert not runs.full and len(runs.first) > 4
    for first, last, c, rad in zip(runs.first, runs.last, runs.centre, runs.radius, strict=True):
        pts = _run_vertices(ring, first, last)
        assert len(pts) >= 4
        assert np.abs(np.hypot(*(pts - c).T) - rad).max() <= fit_distance(0.01)


def test_an_open_path_keeps_its_ends_and_holes_stay_clockwise():
    ang = np.linspace(0, np.pi, 17)
    path = np.column_stack([np.cos(ang), np.sin(ang)]) * 5
    runs = arc_runs(path, tolerance_mm=0.1, closed=False)
    assert runs.first.tolist() == [0] and runs.last.tolist() == [16] and not runs.full
    hole = _ring(Polygon(Point(0, 0).buffer(5.0, quad_segs=8).exterior.coords[::-1]))
    assert arc_runs(hole, tolerance_mm=0.1).sweep[0] == pytest.approx(-2 * np.pi)


def test_a_circle_on_a_coarse_grid_is_one_circle():
    """Three points' circle is unsure where the chords are short against the points' noise: a 100 mm
    circle of 1.3 mm chords (0.0043 mm sagitta) rounded to the print's 2**-10 mm grid is still one circle."""
    t = np.linspace(0, 2 * np.pi, 240, endpoint=False)
    ring = np.round(np.column_stack([50 * np.cos(t), 50 * np.sin(t)]) * 1024) / 1024
    runs = arc_runs(ring, tolerance_mm=0.02)
    assert runs.full and runs.radius[0] == pytest.approx(50, abs=1e-3)


def test_short_rings_and_a_tolerance_of_zero_give_no_arcs():
    assert len(arc_runs(np.zeros((3, 2)), tolerance_mm=0.01).first) == 0
    assert len(arc_runs(_ring(Point(0, 0).buffer(1.0)), tolerance_mm=0.0).first) == 0


def _flatten(curve, closed=True, step=0.01):
    """The curve's points, its arcs flattened finely (for the tests: an independent reading of the bulges)."""
    xy, b = curve.xy, curve.bulge
    out = []
    m = len(xy) if closed else len(xy) - 1
    for i in range(m):
        a, z = xy[i], xy[(i + 1) % len(xy)]
        out.append(a)
        if b[i] == 0:
            continue
        sweep = 4 * np.arctan(b[i])
        chord = np.hypot(*(z - a))
        r = chord / (2 * np.sin(abs(sweep) / 2))
        mid = (a + z) / 2
        normal = np.array([-(z - a)[1], (z - a)[0]]) / chord
        # the centre is to the left of the chord for a counter-clockwise arc of less than a half turn
        c = mid + normal * np.sign(sweep) * r * np.cos(abs(sweep) / 2)
        a0 = np.arctan2(*(a - c)[::-1])
        k = max(2, int(abs(sweep) * r / step))
        t = a0 + sweep * np.arange(1, k) / k
        out.extend(c + r * np.column_stack([np.cos(t), np.sin(t)]))
    if not closed:
        out.append(xy[-1])
    return np.array(out)


@settings(max_examples=examples(25), deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(0, 80).map(lambda v: v / 2), st.integers(0, 80).map(lambda v: v / 2)),
        min_size=2,
        max_size=6,
        unique=True,
    ),
    st.floats(0.3, 4),
    st.sampled_from([np.pi, np.pi / 2]),
    st.integers(0, 50),
)
def test_a_bulge_path_draws_the_ring_within_the_tolerance(points, r, max_sweep, roll):
    from shapely.geometry import Polygon as P

    shape = LineString(points).buffer(r, quad_segs=8)
    if shape.geom_type != "Polygon" or shape.area < 1 or len(shape.interiors):
        return
    ring = np.roll(_ring(shape), roll, axis=0)
    tol = 0.05
    curve = bulge_path(ring, arc_runs(ring, tolerance_mm=tol), max_sweep=max_sweep)
    assert np.array_equal(curve.xy[0], ring[0])  # starts where the ring did
    assert np.abs(4 * np.arctan(curve.bulge)).max() <= max_sweep + 1e-9
    drawn = P(_flatten(curve))
    assert drawn.is_valid
    assert drawn.hausdorff_distance(P(ring)) <= tol
    # the arcs are the true curves: the area of the stroke drawn at a high resolution, within 0.01 %
    # (or as close as the flattened ring, where joins of one or two chords stay chords)
    true = LineString(points).buffer(r, quad_segs=512).area
    assert abs(drawn.area - true) <= max(1e-4 * true, abs(shape.area - true))
    lengths = piece_lengths(curve)
    assert lengths.sum() == pytest.approx(drawn.length, rel=1e-4)


def test_an_open_arc_keeps_its_ends_and_a_full_circle_is_two_half_turns():
    ang = np.linspace(0, np.pi, 17)
    path = np.column_stack([np.cos(ang), np.sin(ang)]) * 5
    curve = bulge_path(path, arc_runs(path, tolerance_mm=0.1, closed=False), closed=False)
    assert curve.xy.tolist() == [path[0].tolist(), path[-1].tolist()]
    assert curve.bulge[0] == pytest.approx(1.0)
    assert piece_lengths(curve, closed=False).tolist() == pytest.approx([5 * np.pi])
    quarter = bulge_path(path, arc_runs(path, tolerance_mm=0.1, closed=False), closed=False, max_sweep=np.pi / 2)
    assert len(quarter.xy) == 3 and quarter.xy[1] == pytest.approx([0, 5])
    circle = curves([_ring(Point(1, 1).buffer(3.0, quad_segs=32))], tolerance_mm=0.01)[0]
    assert len(circle.xy) == 2 and circle.bulge == pytest.approx([1, 1])


@settings(max_examples=examples(30), deadline=None)
@given(
    st.floats(0.1, 500),
    st.floats(-np.pi, np.pi),
    st.floats(0.05, np.pi),
    st.booleans(),
    st.sampled_from([0.001, 0.01, 0.1]),
)
def test_beziers_stay_within_a_tenth_of_the_tolerance_of_the_arc(r, start, sweep, ccw, tol):
    s = sweep if ccw else -sweep
    ends = np.array([[np.cos(start), np.sin(start)], [np.cos(start + s), np.sin(start + s)]]) * r
    curve = Curve(ends, np.array([np.tan(s / 4), 0.0]))
    b = beziers(curve, tolerance_mm=tol, closed=False)
    assert np.array_equal(b.xy[0], ends[0]) and np.array_equal(b.xy[-1], ends[1])
    t = np.linspace(0, 1, 41)[:, None]
    for i in np.flatnonzero(b.bezier):
        p0, p1, p2, p3 = b.xy[i], b.c0[i], b.c1[i], b.xy[i + 1]
        pts = (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t**2 * p2 + t**3 * p3
        assert np.abs(np.hypot(*pts.T) - r).max() <= 0.1 * tol + 1e-9 * r
        # turning the arc's way
        cross = (p3 - p0)[0] * (p1 - p0)[1] - (p3 - p0)[1] * (p1 - p0)[0]
        assert (cross < 0) == ccw


@pytest.mark.parametrize("sweep", [0.1, 0.7, np.pi / 2, 2.5, np.pi])
def test_bezier_error_bounds_the_cubics_distance_from_its_arc(sweep):
    r = 70.0
    h = 4 / 3 * np.tan(sweep / 4) * r
    p0, p3 = np.array([r, 0.0]), r * np.array([np.cos(sweep), np.sin(sweep)])
    p1, p2 = p0 + [0, h], p3 - h * np.array([-np.sin(sweep), np.cos(sweep)])
    t = np.linspace(0, 1, 20001)[:, None]
    pts = (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t**2 * p2 + t**3 * p3
    largest = np.abs(np.hypot(*pts.T) - r).max()
    assert 0.99 * bezier_error(sweep, r) <= largest <= bezier_error(sweep, r) + 1e-12  # a bound, within 1 %


def _narrow_join(turn_deg: float, r: float = 0.6, segs: int = 3) -> np.ndarray:
    """A stroke of two lines turning ``turn_deg``: its join flattened in two chords at quad_segs ``segs``."""
    t = np.radians(turn_deg)
    path = LineString([(0, 0), (5, 0), (5 + 5 * np.cos(t), 5 * np.sin(t))])
    return _ring(path.buffer(r, quad_segs=segs, cap_style="flat"))


def test_two_chords_on_a_known_radius_are_an_arc_and_on_another_radius_not():
    """A 58-degree round join of a 1.2 mm stroke in two chords (within 0.02 mm): three points prove
    no circle, three on the join's radius do."""
    ring = _narrow_join(58)
    assert len(arc_runs(ring, tolerance_mm=0.02).first) == 0
    runs = arc_runs(ring, tolerance_mm=0.02, radii=(0.6,))
    assert len(runs.first) == 1 and (runs.last - runs.first).tolist() == [2]
    assert runs.radius[0] == pytest.approx(0.6, abs=1e-9)
    assert abs(runs.sweep[0]) == pytest.approx(np.radians(58), abs=1e-9)
    assert len(arc_runs(ring, tolerance_mm=0.02, radii=(0.7,)).first) == 0  # 17 % off: no
    # the arc through the three vertices: its ends exactly on the ring, as bulge_path draws it
    curve = bulge_path(ring, runs)
    assert len(curve.xy) == len(ring) - 1 and np.count_nonzero(curve.bulge) == 1


def test_a_radius_that_recurs_among_the_arcs_found_is_known_without_being_given():
    """Three wide joins of one stroke (four chords each) give their radius; the narrow join's two chords
    of that radius then are an arc too, searched together; alone they are not."""
    wide = [_narrow_join(100 + 10 * k, segs=4) + (20 * k, 0) for k in range(3)]
    assert all(len(arc_runs(w, tolerance_mm=0.02).first) == 1 for w in wide)
    narrow = _narrow_join(40, segs=4)
    found = arc_runs_many([*wide, narrow], tolerance_mm=0.02)
    assert (found[-1].last - found[-1].first).tolist() == [2]
    assert found[-1].radius[0] == pytest.approx(0.6, abs=1e-9)
    assert len(arc_runs_many([wide[0], narrow], tolerance_mm=0.02)[-1].first) == 0  # one wide join: no


def test_one_chord_and_straight_bends_stay_straight_whatever_the_radii():
    """A bevel's chord is a one-chord join's: no arc. Two slight bends of a straight edge whose circle
    happens to have the radius given: their middle vertex stands off the chord by less than the fit's
    distance, so they stay straight."""
    bevel = _ring(LineString([(0, 0), (5, 0), (5, 5)]).buffer(0.6, join_style="bevel", cap_style="flat"))
    assert len(arc_runs(bevel, tolerance_mm=0.02, radii=(0.6,)).first) == 0
    r = 100.0
    h = r - np.sqrt(r * r - 0.25)  # the middle vertex's offset on a 100 mm circle over a 1 mm chord
    assert h < fit_distance(0.02)
    bends = np.array([[10, -5], [10, 0], [10.5, h], [11, 0], [11, -5]])  # between two square corners
    assert len(arc_runs(bends, tolerance_mm=0.02, radii=(r,)).first) == 0
    deeper = bends * [1, 2]  # twice the offset: an arc
    assert len(arc_runs(deeper, tolerance_mm=0.02, radii=(r / 2,)).first) == 1


def test_a_run_round_a_whole_ring_is_no_arc_and_no_warning():
    # a run from a vertex round the ring back to it (its ends one point): no chord to fit a circle on
    import warnings

    from fabtiles.geometry.arcs import _fit_runs

    t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    p = np.column_stack([np.cos(t), np.sin(t)]) * 5
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a division by the zero chord warned, and gave NaNs
        runs = _fit_runs(
            p, np.arange(12), np.array([0]), np.array([12]), np.array([0]), np.array([0]), np.array([12]), 1e-3
        )
    assert [len(column) for column in runs] == [0] * 6  # ring, v0, v1, centre, radius, sweep
