"""The cut order (issue 37): short travel, and no contour cut after one that encloses it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely
from designs import printed_only
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely.geometry import box

from fabtiles.designs.design_file import load_design
from fabtiles.geometry.cut_order import enclosing_pairs, order_paths, order_rings, travel
from fabtiles.geometry.cut_plan import CutOptions, plan_cut
from fabtiles.making.models import BuildOptions, Models
from fabtiles.making.pipeline import prepare_tile

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = sorted(p for p in (ROOT / "samples").glob("*.toml") if p.stem != "screen-1200x800" and not printed_only(p))
"""The samples of one plan each (the screen, larger than its bed, is pieces: tests/making/test_panel_pieces.py)."""


def square(x, y, size, ccw=True):
    ring = np.array([[x, y], [x + size, y], [x + size, y + size], [x, y + size]], float)
    return ring if ccw else ring[::-1]


def late_enclosures(paths) -> list:
    """``(i, j)`` where path ``j``, cut before path ``i``, encloses it: what the order must never do.

    Told by GEOS alone (every ring as a polygon, one point of each ring), not by the code under test.
    """
    polys = np.array([shapely.Polygon(p) for p in paths], dtype=object)
    tree = shapely.STRtree(polys)
    probe = shapely.points(np.array([p[0] for p in paths]))
    i, j = tree.query(probe, predicate="within")
    return [(a, b) for a, b in zip(i.tolist(), j.tolist(), strict=True) if a != b and b < a]


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: p.stem)
def test_no_contour_after_one_around_it_on_every_sample(sample):
    design = load_design(sample)
    plan = Models(prepare_tile(design), BuildOptions.of_design(design)).cut
    plan = getattr(plan, "lattice", plan)
    closed = [p for layer in plan.layers if layer.closed and not layer.fill for p in layer.paths]
    assert closed
    assert late_enclosures(closed) == []
    assert [layer.role for layer in plan.layers][-1] == "outer"
    job = plan.estimate
    assert job.travel_before_mm is not None and job.travel_mm <= job.travel_before_mm * (1 + 1e-9)


def test_islands_in_holes_are_cut_before_their_holes():
    # a plate with a hole; in the hole an island with its own hole; the island nearer the start
    plate = (
        box(0, 0, 100, 100).difference(box(10, 10, 90, 90)).union(box(20, 20, 80, 80).difference(box(40, 40, 60, 60)))
    )
    plan = plan_cut(plate, box(0, 0, 100, 100), CutOptions.of(profile="laser-3mm-plywood"))
    inner = plan.paths("inner")
    assert len(inner) == 3
    assert late_enclosures(inner + plan.paths("outer")) == []
    areas = [abs(shapely.area(shapely.Polygon(r))) for r in inner]
    assert areas == sorted(areas)  # the island's hole, the island, the hole around it


@settings(max_examples=examples(25), deadline=None)
@given(
    st.dictionaries(st.tuples(st.integers(0, 25), st.integers(0, 25)), st.integers(0, 3), min_size=2, max_size=80),
    st.integers(0, 2**31),
)
def test_order_keeps_nesting_and_shortens_travel(cells, seed):
    # squares on a 20 mm grid, each with up to three squares nested inside it
    rings = [
        square(20 * x + 2 * d, 20 * y + 2 * d, 16 - 4 * d, ccw=d % 2 == 1)
        for (x, y), depth in cells.items()
        for d in range(depth + 1)
    ]
    # shuffled, then the deepest first: an order that keeps the nesting, the one to beat
    shuffled = [rings[i] for i in np.random.default_rng(seed).permutation(len(rings))]
    shuffled.sort(key=lambda r: np.ptp(r[:, 0]))
    order = order_rings(shuffled)
    assert sorted(order.tolist()) == list(range(len(shuffled)))
    ordered = [shuffled[i] for i in order]
    assert late_enclosures(ordered) == []
    assert len(enclosing_pairs(rings)) == sum(d * (d + 1) // 2 for d in cells.values())
    assert travel(ordered) <= travel(shuffled) + 1e-6


def test_nested_squares_have_their_pairs():
    rings = [square(0, 0, 10), square(2, 2, 6, ccw=False), square(4, 4, 2), square(20, 0, 5)]
    assert sorted(map(tuple, enclosing_pairs(rings).tolist())) == [(1, 0), (2, 0), (2, 1)]
    assert (
        order_rings(rings).tolist().index(2)
        < order_rings(rings).tolist().index(1)
        < order_rings(rings).tolist().index(0)
    )


def test_score_lines_may_run_backwards_closed_rings_never():
    lines = [np.array([[10.0, 0], [0, 0]]), np.array([[20.0, 0], [30, 0]]), np.array([[50.0, 0], [40, 0]])]
    rings = [square(100, 0, 5, ccw=False), square(200, 0, 5, ccw=False)]
    out = order_paths({"score": lines, "inner": rings})
    assert [p[0].tolist() for p in out["score"]] == [[0.0, 0.0], [20.0, 0.0], [40.0, 0.0]]
    assert travel(out["score"], closed=False) == pytest.approx(20.0)
    for r in out["inner"]:  # the same rings, same start, same direction
        assert any(np.array_equal(r, s) for s in rings)


def test_tab_pieces_keep_their_direction():
    plate = box(0, 0, 50, 50).union(box(60, 0, 110, 50))
    plan = plan_cut(plate, plate, CutOptions.of(profile="laser-3mm-plywood", tab_mm=1.0))
    pieces = plan.paths("outer")
    assert len(pieces) == 8
    for p in pieces:  # every piece still runs counter-clockwise around its square
        centre = np.array([25.0, 25.0]) if p[:, 0].mean() < 55 else np.array([85.0, 25.0])
        a, b = p[0] - centre - plan.offset, p[-1] - centre - plan.offset
        assert a[0] * b[1] - a[1] * b[0] > 0
    # the pieces of one square follow each other
    sides = [p[:, 0].mean() < 55 for p in pieces]
    assert sides == sorted(sides, reverse=True) or sides == sorted(sides)


def test_travel_of_nothing_and_one():
    assert travel([]) == 0.0
    assert order_rings([square(3, 4, 1)]).tolist() == [0]
    assert travel([square(3, 4, 1)]) == pytest.approx(5.0)


def test_the_estimate_reports_both_travels():
    plate = box(0, 0, 200, 200).difference(
        shapely.union_all([box(x, y, x + 5, y + 5) for x in range(10, 190, 20) for y in (10, 180)])
    )
    plan = plan_cut(plate, box(0, 0, 200, 200), CutOptions.of(profile="laser-3mm-plywood"))
    stats = plan.report.stats["job"]
    assert stats["travel_mm"] <= stats["travel_before_mm"]
    assert "head travel" in plan.estimate.travel_line()


def test_neighbours_of_crowded_ends_are_found_without_gathering_the_crowd(monkeypatch):
    # 400 ends in half a millimetre square among 4,000 over a 100 mm square: one query at the radius the mean
    # density gives hands every crowded exit the whole crowd (53 points an exit over all); the radius grown
    # from a 64th of it stops where each exit has its k
    from fabtiles.geometry.cut_order import _near

    rng = np.random.default_rng(5)
    ends = np.concatenate([rng.uniform(0, 0.5, (400, 2)), rng.uniform(0, 100, (4000, 2))])
    exits = ends[::-1].copy()
    found = []
    query = shapely.STRtree.query

    def counted(self, *args, **kwargs):
        out = query(self, *args, **kwargs)
        found.append(out.shape[1])
        return out

    monkeypatch.setattr(shapely.STRtree, "query", counted)
    near = _near(ends, exits, 9)
    assert sum(found) < 35 * len(exits)
    for i in rng.choice(len(exits), 300, replace=False):  # the k nearest, as a brute force finds them
        d = np.hypot(*(ends - exits[i]).T)
        assert 0 < len(near[i]) <= 9 and sorted(d[near[i]]) == pytest.approx(np.sort(d)[: len(near[i])])
