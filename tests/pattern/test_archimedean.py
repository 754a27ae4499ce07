"""The 11 Archimedean tilings as packings against docs/tile-operation.md."""

import copy
import math
import pickle
from dataclasses import FrozenInstanceError
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles import ArchimedeanPacking, HexPacking, LimitError, ParameterError, SquarePacking, Star
from fabtiles.pattern.archimedean import rectangular_period
from fabtiles.pattern.tilings import ALL_TILINGS, TILINGS, apollonius_outer, canonical, circumradius, unit_cell

TOL = 1e-7
EXPONENT_FORMS = {
    "3^6": "3.3.3.3.3.3",
    "4^4": "4.4.4.4",
    "6^3": "6.6.6",
    "(3.6)^2": None,
    "3.12^2": "3.12.12",
    "4.8^2": "4.8.8",
    "3^4.6": "3.3.3.3.6",
    "3^3.4^2": "3.3.3.4.4",
    "3^2.4.3.4": "3.3.4.3.4",
    "3.4.6.4": "3.4.6.4",
    "3.6.3.6": "3.6.3.6",
}


def config(name):
    return [int(p) for p in name.split(".")]


def window_circles(pack, half):
    w = (-half, -half, half, half)
    c, r = pack.circles(w)
    return c, r, pack.circle_sides(w)


def pair_gaps(c, r, tol):
    """The smallest gap between two circles, and which touch (their gap within ``tol``), ``(n, n)``.

    Only pairs whose centres lie within the largest diameter and ``tol`` of each other can
    overlap or touch: an R-tree finds them, and every other pair has a gap over ``tol``.
    """
    points = shapely.points(c)
    i, j = shapely.STRtree(points).query(points, predicate="dwithin", distance=2 * r.max() + tol)
    i, j = i[i != j], j[i != j]
    gap = np.hypot(*(c[i] - c[j]).T) - r[i] - r[j]
    touch = np.zeros((len(c), len(c)), dtype=bool)
    touch[i, j] = np.abs(gap) < tol
    return gap.min(initial=np.inf), touch


def nearest(points, to):
    """Index in ``to`` of the point nearest each of ``points`` (an R-tree's, not every pair's distance)."""
    return shapely.STRtree(shapely.points(to)).query_nearest(shapely.points(points))[1]


tilings = st.sampled_from(ALL_TILINGS)  # the two-uniform ones too
edges = st.floats(min_value=0.5, max_value=40, allow_nan=False)


def test_eleven_tilings_and_their_names():
    assert ArchimedeanPacking.tilings()[:11] == TILINGS and len(set(TILINGS)) == 11
    for form, name in EXPONENT_FORMS.items():
        if name is not None:
            assert ArchimedeanPacking(form, 10).tiling == name
    assert canonical("8.4.8") == "4.8.8" and canonical(" 6.3.6.3 ") == "3.6.3.6"
    assert canonical("6.3.3.3.3") == "3.3.3.3.6"


@pytest.mark.parametrize("bad", ["5.5.5", "3.3.3", "hex", "", "3^x", 666, None])
def test_unknown_tiling_lists_the_valid_ones(bad):
    with pytest.raises(
        ParameterError,
        match=r"is unknown(; did you mean '[0-9.]+'\?)? \(tilings: 3\.3\.3\.3\.3\.3, "
        r"4\.4\.4\.4, 6\.6\.6, .*3\.4\.6\.4",
    ):
        ArchimedeanPacking(bad, 10)


@pytest.mark.parametrize("edge", [0, -1, float("nan"), float("inf"), "10"])
def test_bad_edge(edge):
    with pytest.raises(ParameterError, match=r"edge must be a finite number > 0"):
        ArchimedeanPacking("4.8.8", edge)


def test_bad_motifs():
    with pytest.raises(
        ParameterError,
        match=r"motifs key 6 is not a polygon of the tiling 4\.8\.8, "
        r"must be one of: 4, 8",
    ):
        ArchimedeanPacking("4.8.8", 10, {6: Star(n=6, radii=(1, 2))})
    with pytest.raises(
        ParameterError,
        match=r"motifs key 'x' is not a polygon of the tiling 3\.4\.6\.4, "
        r"must be one of: 3, 4, 6",
    ):
        ArchimedeanPacking("3.4.6.4", 10, {"x": "table3-3"})
    with pytest.raises(ParameterError, match=r"motifs must be a mapping"):
        ArchimedeanPacking("4.8.8", 10, ["table3-3"])
    with pytest.raises(ParameterError, match=r"motifs\[8\] must be a Star or a preset name, got 3"):
        ArchimedeanPacking("4.8.8", 10, {8: 3})
    with pytest.raises(ParameterError, match=r"preset 'nope' is unknown"):
        ArchimedeanPacking("4.8.8", 10, {"8": "nope"})
    with pytest.raises(ParameterError, match=r"gap_motif must be a Star or a preset name, got 1"):
        ArchimedeanPacking("4.8.8", 10, gap_motif=1)
    with pytest.raises(ParameterError, match=r"outline_circles must be true or false, got 1"):
        ArchimedeanPacking("4.8.8", 10, outline_circles=1)
    with pytest.raises(ParameterError, match=r"fill must be a finite number > 0 and <= 1, got 2"):
        ArchimedeanPacking("4.8.8", 10, fill=2)


def test_bad_window_and_window_too_large():
    p = ArchimedeanPacking("3.3.3.3.6", 0.5)
    with pytest.raises(ParameterError, match=r"window must be \(xmin, ymin, xmax, ymax\), got 5"):
        p.circles(5)
    with pytest.raises(ParameterError, match=r"window must be finite .* got \(0, 0, -1, 1\)"):
        p.circles((0, 0, -1, 1))
    with pytest.raises(LimitError, match=r"more than the limit of 2000000; use a larger edge \(got 0\.5 mm\)"):
        p.segments((0, 0, 5000, 5000))


def test_immutable_and_hashable():
    p = ArchimedeanPacking("4.8.8", 20, {"8": "table3-3"})
    q = ArchimedeanPacking("4.8^2", 20.0, {8: Star.preset("table3-3")})
    assert p == q and hash(p) == hash(q) and len({p, q}) == 1
    assert p != p.replace(edge=10) and p.replace(edge=10).edge == 10
    with pytest.raises(FrozenInstanceError, match="cannot assign to field 'edge'"):
        p.edge = 5
    with pytest.raises(FrozenInstanceError, match="cannot assign to field '_motifs'"):
        p._motifs = ()
    with pytest.raises(FrozenInstanceError, match="cannot delete field 'tiling'"):
        del p.tiling
    for twin in (pickle.loads(pickle.dumps(p)), copy.deepcopy(p), copy.copy(p)):
        assert twin == p and hash(twin) == hash(p)
        assert np.array_equal(twin.segments((0, 0, 30, 30)), p.segments((0, 0, 30, 30)))
    seg = p.segments((0, 0, 30, 30))
    seg[:] = 0  # a fresh array: the packing's placed motifs are unchanged
    assert p.segments((0, 0, 30, 30)).any()
    with pytest.raises(TypeError):
        p.motifs[8] = Star(n=8, radii=(1, 2))
    assert set(p.motifs) == {4, 8} and "4.8.8" in repr(p)
    with pytest.raises(ValueError):
        unit_cell("4.8.8").centres[0, 0] = 1.0


@settings(max_examples=examples(40), deadline=None)
@given(tilings, edges)
def test_circles_never_overlap_and_touch_as_the_tiling_says(tiling, edge):
    p = ArchimedeanPacking(tiling, edge)
    period = edge * max(rectangular_period(tiling))
    half = 2.5 * period
    c, r, sides = window_circles(p, half)
    least, touch = pair_gaps(c, r, TOL * edge)
    assert least / edge > -TOL  # never overlap
    inc = sides > 0
    # Only circles far from the window's border have all their neighbours listed.
    inner = np.abs(c).max(axis=1) < half - 1.5 * period
    assert inner[inc].sum() >= len(unit_cell(tiling).sides) and inner[~inc].sum() >= 1
    for k in np.flatnonzero(inner & inc):  # each incircle touches exactly p incircles
        assert touch[k, inc].sum() == sides[k]
        # ... at its edge midpoints: the touching incircles' centres lie p-fold around it
        d = c[touch[k] & inc] - c[k]
        assert np.allclose(np.hypot(*d.T), r[k] + r[touch[k] & inc])
    for k in np.flatnonzero(inner & ~inc):  # each gap circle touches at least 3 incircles
        assert touch[k, inc].sum() >= 3 and touch[k, ~inc].sum() == 0


@pytest.mark.parametrize("tiling", TILINGS)
def test_one_gap_circle_per_vertex_and_vertex_configuration(tiling):
    cell = unit_cell(tiling)
    want = config(tiling)
    # Faces meet edge to edge: V - E + F = 0 per cell, with E = (sum of sides) / 2.
    assert len(cell.vertices) - cell.sides.sum() / 2 + len(cell.sides) == 0
    assert len(cell.gap_radii) == len(cell.vertices)
    shifts = np.array([(i, j) for i in range(-2, 3) for j in range(-2, 3)]) @ cell.lattice
    allc = (cell.centres[None] + shifts[:, None]).reshape(-1, 2)
    alls = np.tile(cell.sides, len(shifts))
    for v, g in zip(cell.vertices, cell.gap_centres, strict=True):
        at = np.abs(np.hypot(*(allc - v).T) - [circumradius(s) for s in alls]) < TOL
        around = alls[at][np.argsort(np.arctan2(*(allc[at] - v).T[::-1]))].tolist()
        # The polygons around the vertex, in turn, are the configuration (up to rotation/reflection).
        assert any(around[k:] + around[:k] in (want, want[::-1]) for k in range(len(around)))
        # The angles around the vertex add up to a full turn.
        assert sum(180 * (s - 2) / s for s in around) == pytest.approx(360)
        # Its gap circle lies nearer this vertex than any other.
        verts = (cell.vertices[None] + shifts[:, None]).reshape(-1, 2)
        dist = np.hypot(*(verts - g).T)
        assert np.isclose(dist.min(), np.hypot(*(v - g)))


@pytest.mark.parametrize("tiling", ALL_TILINGS)
def test_gap_circles_in_a_window_are_one_per_vertex(tiling):
    edge = 10
    p = ArchimedeanPacking(tiling, edge)
    half = 3 * max(p.period)
    c, _r, sides = window_circles(p, half)
    gaps = c[sides == 0]
    # The tiling's vertices near the origin, from the unit cell.
    cell = unit_cell(tiling)
    ij = np.array([(i, j) for i in range(-40, 41) for j in range(-40, 41)])
    verts = ((cell.vertices[None] + (ij @ cell.lattice)[:, None]).reshape(-1, 2)) * edge
    verts = verts[np.abs(verts).max(axis=1) < half - edge]
    # Each vertex has exactly one gap circle nearer to it than to any other vertex, and it is its own.
    nearest_gap = nearest(verts, gaps)
    assert len(np.unique(nearest_gap)) == len(verts)
    owner = nearest(gaps[nearest_gap], verts)
    assert np.array_equal(owner, np.arange(len(verts)))
    assert (np.hypot(*(gaps[nearest_gap] - verts).T) < 0.2 * edge).all()


@pytest.mark.parametrize("tiling", TILINGS)
def test_polygon_counts_per_area_match_the_vertex_configuration(tiling):
    cell = unit_cell(tiling)
    share = {}
    for s in config(tiling):  # each vertex has 1/p of each p-gon at it, a p-gon has p vertices
        share[s] = share.get(s, 0) + Fraction(1, s)
    counts = {s: int((cell.sides == s).sum()) for s in share}
    base = min(share.values())
    ratio = {s: share[s] / base for s in share}
    assert {s: Fraction(counts[s], min(counts.values())) for s in counts} == ratio
    # Area of the cell is the area of its polygons.
    area = sum(s / (4 * math.tan(math.pi / s)) for s in cell.sides)
    assert cell.area == pytest.approx(area)
    # In a large window the densities agree too.
    p = ArchimedeanPacking(tiling, 5)
    w = 40 * 5 * max(rectangular_period(tiling))
    _, _, sides = window_circles(p, w)
    found = {s: (sides == s).sum() for s in share}
    for s in share:
        assert found[s] / found[min(share)] == pytest.approx(float(share[s] / share[min(share)]), rel=0.03)


@settings(max_examples=examples(25), deadline=None)
@given(edges, st.tuples(*[st.floats(-80, 80)] * 4), st.sampled_from(Star.presets()))
def test_666_is_the_hex_packing_and_4444_the_square(edge, corners, preset):
    x0, x1 = sorted(corners[:2])
    y0, y1 = sorted(corners[2:])
    w = (x0, y0, x1, y1)
    hexp = HexPacking(radius=edge * math.sqrt(3) / 2, motif=Star.preset(preset))
    arch = ArchimedeanPacking("6.6.6", edge=edge, motifs={6: preset})
    for a, b in (
        (hexp.circles(w), arch.circles(w)),
        (SquarePacking(edge / 2, Star.preset(preset)).circles(w), ArchimedeanPacking("4.4.4.4", edge).circles(w)),
    ):
        assert a[0].shape == b[0].shape
        assert np.allclose(a[0], b[0], atol=1e-9) and np.allclose(a[1], b[1], atol=1e-12)
    assert hexp.period == pytest.approx(arch.period)
    # The motifs too, when the motif's largest circle has points at angle 0 (all presets but one).
    if preset != "table1-part2":

        def canon(s):
            s = np.round(s, 6).reshape(-1, 4) + 0.0
            return s[np.lexsort(s.T[::-1])]

        assert np.array_equal(canon(hexp.segments(w)), canon(arch.segments(w)))


def test_motifs_turned_to_the_tangency_points():
    # A 12-point motif in the dodecagons of 4.6.12 and 8 points in the squares: the
    # points of each motif's largest circle lie on its polygon's edge midpoints.
    p = ArchimedeanPacking(
        "4.6.12", 10, {12: Star(n=12, radii=(0.5, 1)), 4: Star(n=8, radii=(1, 0.5)), 6: Star(n=6, radii=(1, 0.4))}
    )
    c, r, sides = window_circles(p, 60)
    seg = p.motif_segments((-60, -60, 60, 60)).reshape(-1, 2)
    ends = np.unique(np.round(seg, 6), axis=0)
    inc = sides > 0
    touch = pair_gaps(c[inc], r[inc], TOL)[1]
    k = np.flatnonzero(np.abs(c[inc]).max(axis=1) < 30)
    for i in k:
        for j in np.flatnonzero(touch[i]):
            tangency = c[inc][i] + (c[inc][j] - c[inc][i]) * r[inc][i] / (r[inc][i] + r[inc][j])
            assert np.hypot(*(ends - tangency).T).min() < 1e-6


def test_apollonius_degenerate_cases():
    c = np.array([[0.0, 0], [1, 0], [2, 0]])
    assert len(apollonius_outer(c, np.ones(3))[1]) == 0  # centres on a line
    far = np.array([[0.0, 0], [10, 0], [0, 10]])
    centre, rad = apollonius_outer(far, np.array([1.0, 1, 1]))
    assert len(rad) and np.allclose(
        np.hypot(*(far[None] - centre[:, None]).transpose(2, 0, 1)).T - 1, rad[:, None] * np.ones(3)
    )


@pytest.mark.parametrize("tiling", ALL_TILINGS)
def test_rectangular_period_repeats_the_circles(tiling):
    p = ArchimedeanPacking(tiling, 7)
    px, py = p.period
    half = max(80.0, 2 * max(px, py) + 40)  # the two-uniform cells are larger
    c, r = p.circles((-half, -half, half, half))
    key = {tuple(np.round(v, 5)) for v in np.c_[c, r]}
    inner = np.abs(c).max(axis=1) < half - max(px, py) - 20
    assert inner.sum() >= len(unit_cell(tiling).sides)
    for dx, dy in ((px, 0), (0, py)):
        moved = {tuple(np.round(v, 5)) for v in np.c_[c[inner] + (dx, dy), r[inner]]}
        assert moved <= key
    # ... and no smaller axis-aligned translation does.
    for f in (2, 3):
        moved = {tuple(np.round(v, 5)) for v in np.c_[c[inner] + (px / f, 0), r[inner]]}
        assert not moved <= key


def test_segment_count_matches_segments():
    for tiling in TILINGS:
        for outline in (False, True):
            p = ArchimedeanPacking(tiling, 9, outline_circles=outline)
            w = (-23, -11, 31, 17)
            assert p.segment_count(w) == len(p.segments(w))


@pytest.mark.parametrize(
    "call, param",
    [
        (lambda: ArchimedeanPacking("5.5.5", 10), "tiling"),
        (lambda: ArchimedeanPacking("4.8.8", 0), "edge"),
        (lambda: ArchimedeanPacking("4.8.8", 10, {6: "table3-3"}), "motifs"),
        (lambda: ArchimedeanPacking("4.8.8", 10, {8: "nope"}), "motifs"),
        (lambda: ArchimedeanPacking("4.8.8", 10, gap_motif="nope"), "gap_motif"),
        (lambda: ArchimedeanPacking("4.8.8", 10).circles(None), "window"),
        (lambda: ArchimedeanPacking("4.8.8", 0.01).circles((0, 0, 900, 900)), "edge"),
    ],
)
def test_errors_name_their_parameter(call, param):
    with pytest.raises((ParameterError, LimitError)) as info:
        call()
    assert info.value.param == param


def test_motif_rotation_turns_it_further():
    plain = ArchimedeanPacking("4.8.8", 10, {8: Star(n=8, radii=(0.5, 1))})
    turned = ArchimedeanPacking("4.8.8", 10, {8: Star(n=8, radii=(0.5, 1), rotation=10)})
    # The octagon at the origin: its motif's tips at the edge midpoints (0, 45, ... degrees),
    # then 10 degrees further.
    for pack, offset in ((plain, 0.0), (turned, 10.0)):
        seg = pack.motif_segments((-1, -1, 1, 1)).reshape(-1, 2)
        far = seg[np.hypot(*seg.T) > pack.incircle_radius(8) - 1e-6]
        angles = np.sort(np.round(np.degrees(np.arctan2(far[:, 1], far[:, 0])) % 360, 6))
        assert np.allclose(np.unique(angles), (offset + 45 * np.arange(8)) % 360)
