"""The pen's strokes (issue 37): centre-lines merged straight through crossings, ordered."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from fabtiles.geometry.pen import PenLayer, pen_drawing, strokes


def total(paths) -> float:
    return float(sum(np.hypot(*np.diff(p, axis=0).T).sum() for p in paths))


def test_a_cross_is_two_strokes_and_a_star_crossing_four():
    plus = np.array([[[-1, 0], [0, 0]], [[0, 0], [1, 0]], [[0, -1], [0, 0]], [[0, 0], [0, 1]]], float)
    out = strokes(plus)
    assert len(out) == 2 and all(len(p) == 3 for p in out)
    # eight rays from one point: four straight strokes
    ang = np.arange(8) * np.pi / 4
    rays = np.stack([np.zeros((8, 2)), np.c_[np.cos(ang), np.sin(ang)]], axis=1)
    out = strokes(rays)
    assert len(out) == 4
    for p in out:
        assert np.allclose(p[0], -p[-1])  # through the centre, straight on


def test_strokes_keep_every_segment_once():
    rng = np.random.default_rng(3)
    grid = np.array(
        [[[x, y], [x + 1, y]] for x in range(6) for y in range(6)]
        + [[[x, y], [x, y + 1]] for x in range(6) for y in range(6)],
        float,
    )
    seg = np.concatenate([grid, grid[rng.permutation(len(grid))][:10]])  # with repeats
    out = strokes(seg)
    assert total(out) == pytest.approx(len(grid))
    assert shapely.union_all([shapely.LineString(p) for p in out]).equals(shapely.union_all(shapely.linestrings(grid)))
    assert len(out) == 11  # six rows and six columns straight through every crossing; the corner (0, 0) joins two


def test_a_closed_strand_comes_back_to_its_start():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], float)
    [p] = strokes(np.stack([square[:-1], square[1:]], axis=1))
    assert np.array_equal(p[0], p[-1]) and len(p) == 5


def test_nothing_and_zero_length():
    assert strokes(np.zeros((0, 2, 2))) == []
    assert strokes(np.array([[[1, 1], [1, 1]]], float)) == []


def test_drawing_orders_each_layer_and_keeps_its_length():
    lines = [np.array([[x, 0.0], [x, 10.0]]) for x in (50, 0, 30, 10, 40, 20)]
    d = pen_drawing([("a", "#000000", lines), ("empty", "#ff0000", [])], bounds=(0, 0, 50, 10), pen_mm=0.5)
    assert [layer.name for layer in d.layers] == ["a"]
    assert d.length_mm == pytest.approx(60.0)
    assert d.travel_mm == pytest.approx(50.0)  # 0 -> 50 in 10 mm steps, up and down alternately
    assert PenLayer("x", "#000000").length_mm == 0
