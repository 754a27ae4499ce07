"""Hatch fills: the scanline fill against GEOS's own clipping, the boustrophedon order."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from fabtiles.geometry.cut_order import POLISH_MAX, TWO_OPT_MAX, order_strokes, travel
from fabtiles.geometry.hatch import hatch, hatch_order


def star(n: int, r0: float, r1: float, at=(0.0, 0.0), turn: float = 0.0):
    t = turn + np.arange(2 * n) * math.pi / n
    r = np.where(np.arange(2 * n) % 2 == 0, r1, r0)
    return shapely.Polygon(np.column_stack([at[0] + r * np.cos(t), at[1] + r * np.sin(t)]))


def geos_lengths(poly, spacing: float, angle_deg: float) -> dict:
    """Line k's length inside ``poly``, by GEOS: a long line at ``k * spacing`` across the angle."""
    t = math.radians(angle_deg)
    d, nrm = np.array([math.cos(t), math.sin(t)]), np.array([-math.sin(t), math.cos(t)])
    xy = shapely.get_coordinates(poly)
    v = xy @ nrm
    far = 10 * (1 + float(np.abs(xy).max()))
    out = {}
    for k in range(math.ceil(v.min() / spacing), math.floor(v.max() / spacing) + 1):
        c = k * spacing * nrm
        line = shapely.LineString([c - far * d, c + far * d])
        out[k] = shapely.intersection(line, poly).length
    return out


@settings(max_examples=40, deadline=None)
@given(
    n=st.integers(3, 12),
    r0=st.floats(0.3, 0.9),
    spacing=st.floats(0.05, 1.0),
    angle=st.floats(-180, 180),
    inset=st.floats(0, 0.2),
    hole=st.booleans(),
)
def test_strokes_are_the_lines_inside_the_shrunk_polygon(n, r0, spacing, angle, inset, hole):
    """Each line's strokes lie in the polygon shrunk by the inset and add up to GEOS's intersection of
    the line with it (holes included); the strokes run at the angle, on the lines k * spacing."""
    poly = star(n, 5 * r0, 5, at=(3.0, -2.0), turn=0.3)
    if hole:
        poly = poly.difference(shapely.Point(3.0, -2.0).buffer(1.0))
    h = hatch([poly], spacing_mm=spacing, angle_deg=angle, inset_mm=inset)
    shrunk = poly.buffer(-inset, quad_segs=8) if inset else poly
    assert len(h.segments)
    lines = shapely.linestrings(h.segments)
    assert shapely.covers(shrunk.buffer(1e-6), lines).all()
    t = math.radians(angle)
    along = (h.segments[:, 1] - h.segments[:, 0]) @ np.array([math.cos(t), math.sin(t)])
    assert np.all(along > 0) and np.allclose(along, shapely.length(lines), atol=1e-9)
    v = h.segments[:, 0] @ np.array([-math.sin(t), math.cos(t)])
    assert np.allclose(v, h.line * spacing, atol=1e-7)
    want = geos_lengths(shrunk, spacing, angle)
    got = np.bincount(h.line - h.line.min(), weights=along) if len(h.line) else []
    for k, length in want.items():
        mine = got[k - h.line.min()] if 0 <= k - h.line.min() < len(got) else 0.0
        assert mine == pytest.approx(length, abs=1e-6)


def test_cross_hatch_adds_the_lines_at_right_angles():
    sq = shapely.box(0.5, 0.5, 9.5, 9.5)
    one = hatch([sq], spacing_mm=1, angle_deg=0)
    both = hatch([sq], spacing_mm=1, angle_deg=0, cross=True)
    assert len(both.segments) == 2 * len(one.segments) == 2 * 9  # lines 1..9 each way
    second = both.segments[both.pass_ == 1]
    assert np.allclose(second[:, 0, 0], second[:, 1, 0])  # vertical


def test_faces_share_one_grid_and_keep_their_index():
    a, b = shapely.box(0, 0, 4, 4), shapely.box(6, 0.5, 9, 3.5)
    h = hatch([a, b], spacing_mm=0.7, angle_deg=0)
    assert set(h.face.tolist()) == {0, 1}
    assert np.allclose(np.unique(h.segments[:, 0, 1]) / 0.7, np.round(np.unique(h.segments[:, 0, 1]) / 0.7))


def test_a_face_narrower_than_the_inset_gets_no_stroke():
    h = hatch([shapely.box(0, 0, 0.2, 10)], spacing_mm=0.1, angle_deg=0, inset_mm=0.15)
    assert len(h.segments) == 0 and hatch_order(h) == []
    assert len(hatch([], spacing_mm=1, angle_deg=0, cross=True).segments) == 0


def test_order_draws_every_stroke_once_and_is_short():
    faces = [star(8, 2, 4, at=(10 * i, 10 * j)) for i in range(3) for j in range(3)]
    h = hatch(faces, spacing_mm=0.4, angle_deg=30, inset_mm=0.2, cross=True)
    paths = hatch_order(h)
    key = {tuple(np.round(np.sort(s, axis=0).ravel(), 9)) for s in h.segments}
    assert {tuple(np.round(np.sort(p, axis=0).ravel(), 9)) for p in paths} == key and len(paths) == len(key)
    as_made = travel(list(h.segments), closed=False)
    assert travel(paths, closed=False) < as_made / 4


def test_order_strokes_improves_small_and_middle_orders_and_keeps_a_large_one():
    rng = np.random.default_rng(3)
    for n in (60, POLISH_MAX + 1):
        first = rng.uniform(0, 100, (n, 2))
        last = first + rng.uniform(-2, 2, (n, 2))
        order, flipped = order_strokes(first, last, given=(np.arange(n), np.zeros(n, bool)))
        paths = [np.array([first[i], last[i]]) for i in range(n)]
        ordered = [paths[i][::-1] if f else paths[i] for i, f in zip(order, flipped, strict=True)]
        assert sorted(order.tolist()) == list(range(n))
        assert travel(ordered, closed=False) < travel(paths, closed=False) / 2
    big = TWO_OPT_MAX + 1
    order, flipped = order_strokes(np.zeros((big, 2)), np.ones((big, 2)), given=(np.arange(big), np.zeros(big, bool)))
    assert order.tolist() == list(range(big)) and not flipped.any()
    assert order_strokes(np.zeros((1, 2)), np.ones((1, 2)))[0].tolist() == [0]
