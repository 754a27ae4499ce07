"""Girih tiles and patterns, checked from ``polygons(window)`` and ``segments(window)`` alone."""

from __future__ import annotations

import math
import pickle
from collections import defaultdict

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString, Polygon, box

from fabtiles import LimitError, ParameterError
from fabtiles.pattern.girih import (
    CONTACT_ANGLE,
    MAX_SUBDIVISION_SEGMENTS,
    PATTERNS,
    SUBDIVIDED,
    TAU2,
    TILES,
    GirihPacking,
    check_tile,
    edge_hexagon,
    girih_cell,
    strapwork,
    subdivide,
    subdivided_segments,
    subdivision_rule,
    tile_corners,
    tile_strapwork,
)

EDGE = 7.0
WINDOW = (-40.0, -30.0, 40.0, 30.0)
INNER = box(-25, -18, 25, 18)  # the window away from its edge
CASES = [(p, 0) for p in PATTERNS] + [("decagon-bowtie", 1), ("decagon-bowtie", 2), ("hexagons", 2)]
"""Every pattern as it is and subdivided: (pattern, level)."""


def angles_of(corners: np.ndarray) -> list[float]:
    """The interior angles (degrees) of a counter-clockwise polygon, corner by corner."""
    prev, nxt = np.roll(corners, 1, axis=0) - corners, np.roll(corners, -1, axis=0) - corners
    turn = np.degrees(np.arctan2(nxt[:, 0] * prev[:, 1] - nxt[:, 1] * prev[:, 0], (nxt * prev).sum(axis=1)))
    return [float(t % 360) for t in turn]


def girih_kind(corners: np.ndarray) -> str | None:
    """The girih tile whose angle sequence (up to a turn) the polygon has, or None."""
    angles = tuple(round(a) for a in angles_of(corners))
    for name, seq in TILES.items():
        if len(seq) == len(angles) and any(angles == seq[k:] + seq[:k] for k in range(len(seq))):
            return name
    return None


@pytest.mark.parametrize("name", list(TILES))
def test_each_tile_has_equal_edges_and_its_angles(name):
    corners = tile_corners(name, edge=EDGE, start=(3, -2), heading=17)
    edges = np.hypot(*(np.roll(corners, -1, axis=0) - corners).T)
    np.testing.assert_allclose(edges, EDGE, atol=1e-9)
    angles = angles_of(corners)
    np.testing.assert_allclose(angles, TILES[name], atol=1e-9)
    assert all(abs(a / 36 - round(a / 36)) < 1e-9 for a in angles)
    assert Polygon(corners).is_valid and Polygon(corners).exterior.is_ccw


@pytest.mark.parametrize(
    ("name", "straight", "bent"),
    [("decagon", 0, 20), ("pentagon", 0, 10), ("hexagon", 2, 8), ("bowtie", 4, 4), ("rhombus", 2, 4)],
)
def test_each_tiles_strapwork_is_its_figure(name, straight, bent):
    corners = tile_corners(name, edge=1.0)
    seg = strapwork(corners)
    mids = (corners + np.roll(corners, -1, axis=0)) / 2
    on_mid = [np.isclose(np.hypot(*(mids - s[0]).T), 0).any() for s in seg]
    both = [np.isclose(np.hypot(*(mids - s[1]).T), 0).any() for s in seg]
    # a straight line joins two midpoints (across a 72-degree corner); the others end where two meet
    assert all(on_mid) and sum(both) == straight and len(seg) == straight + bent
    lines = [LineString(s) for s in seg]
    assert all(Polygon(corners).buffer(1e-9).contains(line) for line in lines)
    assert not any(a.crosses(b) for i, a in enumerate(lines) for b in lines[i + 1 :])
    # every midpoint has two lines at 54 degrees to the edge, one leaning each way
    for k, m in enumerate(mids):
        edge = corners[(k + 1) % len(corners)] - corners[k]
        ends = [s[1] - s[0] if np.allclose(s[0], m) else s[0] - s[1] for s in seg if np.isclose(s, m).all(1).any()]
        assert len(ends) == 2
        turns = sorted(round(math.degrees(math.atan2(_cross(edge, d), edge @ d)), 9) for d in ends)
        assert turns == [CONTACT_ANGLE, 180 - CONTACT_ANGLE]


def test_the_decagon_is_a_ten_pointed_star_and_the_pentagon_a_five():
    for name, n in (("decagon", 10), ("pentagon", 5)):
        corners = tile_corners(name)
        centre = corners.mean(axis=0)
        inner = {tuple(np.round(s[1], 9)) for s in strapwork(corners)}
        radii = np.hypot(*(np.array(sorted(inner)) - centre).T)
        assert len(inner) == n and np.allclose(radii, radii[0])  # the star's inner corners, on one circle


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


@pytest.mark.parametrize(("pattern", "level"), CASES)
def test_polygons_are_girih_tiles_that_tile_the_window(pattern, level):
    polygons = GirihPacking(pattern, edge=EDGE, level=level).polygons(WINDOW)
    for corners in polygons:
        assert girih_kind(corners) is not None
        np.testing.assert_allclose(np.hypot(*(np.roll(corners, -1, axis=0) - corners).T), EDGE, atol=1e-9)
    shapes = [Polygon(c) for c in polygons]
    union = shapely.union_all(shapes)
    assert sum(s.area for s in shapes) == pytest.approx(union.area, rel=1e-9)  # no overlap
    assert union.buffer(1e-6).contains(INNER)  # no gap


@pytest.mark.parametrize(("pattern", "level"), CASES)
def test_angles_round_every_vertex_add_to_360(pattern, level):
    around = defaultdict(float)
    for corners in GirihPacking(pattern, edge=EDGE, level=level).polygons(WINDOW):
        for p, a in zip(np.round(corners, 6).tolist(), angles_of(corners), strict=True):
            around[tuple(p)] += a
    inside = [v for p, v in around.items() if INNER.contains(shapely.Point(p))]
    assert inside and np.allclose(inside, 360)


@pytest.mark.parametrize(("pattern", "level"), CASES)
def test_strands_cross_every_edge_at_its_midpoint_and_go_on(pattern, level):
    pack = GirihPacking(pattern, edge=EDGE, level=level)
    seg = pack.segments(WINDOW)
    ends = defaultdict(list)  # midpoint -> the directions leaving it
    for s in seg:
        for a, b in ((s[0], s[1]), (s[1], s[0])):
            ends[tuple(np.round(a, 6))].append(b - a)
    for corners in pack.polygons(WINDOW):
        for k in range(len(corners)):
            m = (corners[k] + corners[(k + 1) % len(corners)]) / 2
            if not INNER.contains(shapely.Point(m)):
                continue
            out = ends[tuple(np.round(m, 6))]
            assert len(out) == 4  # two lines, each half in each of the two tiles
            unit = [d / np.hypot(*d) for d in out]
            # each direction has its straight continuation in the neighbour
            assert all(any(np.allclose(u, -v, atol=1e-9) for v in unit) for u in unit)
            edge = corners[(k + 1) % len(corners)] - corners[k]
            angles = {round(math.degrees(math.acos(abs(edge @ u) / EDGE)), 6) for u in unit}
            assert angles == {CONTACT_ANGLE}


@pytest.mark.parametrize(("pattern", "level"), CASES)
def test_the_rectangular_period_repeats_the_strapwork(pattern, level):
    pack = GirihPacking(pattern, edge=EDGE, level=level)
    px, py = pack.period

    def keys(seg):
        ends = np.sort(np.round(seg, 5).reshape(-1, 2, 2).view([("x", float), ("y", float)]), axis=1)
        return {tuple(map(tuple, e.view(float).reshape(2, 2))) for e in ends}

    base = keys(pack.segments((-5, -5, 5, 5)))
    for dx, dy in ((px, 0), (0, py), pack.lattice[0], pack.lattice[1]):
        moved = keys(pack.segments((-5 + dx, -5 + dy, 5 + dx, 5 + dy)) - (dx, dy))
        assert base <= moved


@pytest.mark.parametrize(("pattern", "level"), CASES)
def test_cell_area_is_its_tiles(pattern, level):
    cell = girih_cell(pattern, level)
    area = sum(Polygon(c).area for c in cell.corners)
    assert area == pytest.approx(abs(np.linalg.det(cell.lattice)), rel=1e-12)


@pytest.mark.parametrize(("pattern", "level"), CASES)
def test_segment_count_matches_segments(pattern, level):
    pack = GirihPacking(pattern, edge=EDGE, level=level)
    assert pack.segment_count(WINDOW) == len(pack.segments(WINDOW)) == len(pack.motif_segments(WINDOW))


def test_values_pickle_and_replace():
    pack = GirihPacking("hexagons", edge=5)
    assert pickle.loads(pickle.dumps(pack)) == pack and hash(pack) == hash(GirihPacking("hexagons", 5.0))
    assert pack.replace(edge=8).edge == 8.0 and repr(pack) == "GirihPacking('hexagons', edge=5)"
    assert not pack.outline_circles and pack.radius == pytest.approx(5 / 6)
    assert [a.shape for a in pack.circles((-9, -9, 9, 9))] == [(0, 2), (0,)]
    assert [k for k, _ in pack.tiles((-1, -1, 1, 1))] == ["hexagon"]


@pytest.mark.parametrize(
    ("call", "match", "param"),
    [
        (lambda: GirihPacking("decagon-bowties", edge=5), r"did you mean 'decagon-bowtie'\?", "pattern"),
        (lambda: GirihPacking("stars", edge=5), r"must be one of: decagon-bowtie, hexagons, rhombi", "pattern"),
        (lambda: GirihPacking("rhombi", edge=0), r"edge must be a finite number > 0, got 0", "edge"),
        (lambda: GirihPacking("rhombi", edge=-2), r"edge must be a finite number > 0, got -2", "edge"),
        (lambda: GirihPacking("rhombi", edge=5).polygons((0, 0, -1, 1)), r"window must be finite", "window"),
        (lambda: GirihPacking("rhombi", edge=5).segments("big"), r"window must be \(xmin", "window"),
        (lambda: check_tile("kite"), r"'kite' is not a girih tile", "tile"),
    ],
)
def test_bad_input_names_the_value(call, match, param):
    with pytest.raises(ParameterError, match=match) as info:
        call()
    assert info.value.param == param


def test_a_window_of_too_many_tiles_is_refused():
    with pytest.raises(LimitError, match=r"more than the limit of 2000000; use a larger edge \(got 0.001 mm\)"):
        GirihPacking("rhombi", edge=0.001).segments((-100, -100, 100, 100))


# -- subdivision ------------------------------------------------------------------------------------------------------
def _key(kind: str, corners: np.ndarray) -> tuple:
    return (kind, *np.round(corners.mean(axis=0), 6).tolist())


@pytest.mark.parametrize("kind", SUBDIVIDED)
def test_the_rule_fills_its_large_tile_exactly(kind):
    large = tile_corners(kind, edge=TAU2 * 3, start=(2, -1), heading=23)
    small = subdivide([(kind, large)])
    for name, corners in small:
        assert girih_kind(corners) == name and name in SUBDIVIDED
        np.testing.assert_allclose(np.hypot(*(np.roll(corners, -1, axis=0) - corners).T), 3, atol=1e-9)
    shapes, outline = [Polygon(c) for _, c in small], Polygon(large)
    union = shapely.union_all(shapes)
    assert sum(s.area for s in shapes) == pytest.approx(union.area, abs=1e-9)  # no overlap
    inside = [s.intersection(outline).area for s in shapes]
    assert sum(inside) == pytest.approx(outline.area, abs=1e-9) and union.buffer(1e-9).contains(outline)
    # what lies outside is half of each edge's hexagon, the part the neighbour across the edge makes too
    hexagon = Polygon(tile_corners("hexagon", edge=3)).area
    assert sum(s.area for s in shapes) - outline.area == pytest.approx(len(large) * hexagon / 2, abs=1e-9)


def test_the_rules_areas_add_up():
    area = {k: Polygon(tile_corners(k)).area for k in TILES}
    for kind in SUBDIVIDED:
        inner = sum(area[k] for k, _ in subdivision_rule(kind))
        halves = len(TILES[kind]) / 2 * area["hexagon"]
        assert inner + halves == pytest.approx(TAU2**2 * area[kind], abs=1e-9)
    assert TAU2 == pytest.approx(1 + 2 * math.cos(math.radians(36)), abs=1e-12)  # the hexagon's tip to tip


def test_the_edge_hexagon_spans_the_edge_half_on_each_side():
    hexagon = edge_hexagon((1, 2), (1, 2 + TAU2))
    assert girih_kind(hexagon) == "hexagon"
    np.testing.assert_allclose(hexagon[[0, 3]], [[1, 2], [1, 2 + TAU2]], atol=1e-12)
    left, right = (
        shapely.Polygon(hexagon).intersection(box(-9, -9, 1, 9)),
        Polygon(hexagon).difference(box(-9, -9, 1, 9)),
    )
    assert left.area == pytest.approx(right.area, abs=1e-12)


def test_level_one_is_the_pattern_subdivided():
    large = GirihPacking("decagon-bowtie", edge=EDGE * TAU2).tiles((-80, -60, 80, 60))
    want = {_key(k, c) for k, c in subdivide(large) if INNER.contains(shapely.Point(c.mean(axis=0)))}
    pack = GirihPacking("decagon-bowtie", edge=EDGE, level=1)
    got = {_key(k, c) for k, c in pack.tiles(WINDOW) if INNER.contains(shapely.Point(c.mean(axis=0)))}
    assert got == want and len(got) > 20


def _segment_set(seg: np.ndarray) -> set:
    return {tuple(sorted(map(tuple, np.round(s, 6).tolist()))) for s in seg}


def test_each_tiles_strapwork_is_its_own():
    cell = girih_cell("decagon-bowtie", 2)
    for kind, corners in zip(cell.kinds, cell.corners, strict=True):
        assert _segment_set(tile_strapwork(kind, corners)) == _segment_set(strapwork(corners))


@pytest.mark.parametrize("pattern", ["decagon-bowtie", "hexagons"])
def test_the_segments_counted_ahead_are_the_cells(pattern):
    for level in range(3):
        cell = girih_cell(pattern, level)
        assert subdivided_segments(pattern, level) == sum(len(strapwork(c)) for c in cell.corners)


def test_a_level_too_deep_is_refused():
    ok = GirihPacking("decagon-bowtie", edge=5, level=4)
    assert (
        girih_cell("decagon-bowtie", 4).kinds and subdivided_segments("decagon-bowtie", 4) <= MAX_SUBDIVISION_SEGMENTS
    )
    assert repr(ok) == "GirihPacking('decagon-bowtie', edge=5, level=4)" and ok.replace(level=1).level == 1
    with pytest.raises(
        LimitError,
        match=r"^level = 5 would make 692,918 strapwork segments in one repeat of the girih "
        r"pattern decagon-bowtie, more than the limit of 500,000; the deepest level it takes is 4$",
    ) as info:
        GirihPacking("decagon-bowtie", edge=5, level=5)
    assert info.value.param == "level"
    with pytest.raises(LimitError, match=r"level = 6 would make 1,121,194 .* the deepest level it takes is 5$"):
        GirihPacking("hexagons", edge=5, level=6)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (
            lambda: GirihPacking("rhombi", edge=5, level=1),
            r"the girih pattern rhombi has rhombi, which the rule does not "
            r"replace: use 0, or a pattern of those tiles \(decagon-bowtie, hexagons\)",
        ),
        (lambda: GirihPacking("hexagons", edge=5, level=-1), r"level must be an integer >= 0, got -1"),
        (lambda: GirihPacking("hexagons", edge=5, level=1.5), r"level must be an integer >= 0, got 1.5"),
        (lambda: GirihPacking("hexagons", edge=5, level=True), r"level must be an integer >= 0, got True"),
        (
            lambda: subdivision_rule("pentagon"),
            r"tile = 'pentagon' has no subdivision rule, must be one of: decagon, hexagon, bowtie",
        ),
    ],
)
def test_a_bad_level_names_the_value(call, match):
    with pytest.raises(ParameterError, match=match) as info:
        call()
    assert info.value.param in ("level", "tile")
