"""Strands and over/under (docs/tile-operation.md): crossings against brute force, alternation along strands."""

import itertools
import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

import fabtiles as ft
from fabtiles.pattern.interlace import weave

ROSETTES = ["table1-part2", "table2-left", "table2-right", "table3-1", "table3-2", "table3-3"]


def brute_crossings(seg, eps=1e-6):
    """Interior crossing points of every pair of segments, O(n^2), and four-end straight joints.

    Each segment against every later one, a row of pairs at a time in numpy (the pairs in the order
    of ``itertools.combinations``)."""
    seg = np.asarray(seg, dtype=float)
    p, r = seg[:, 0], seg[:, 1] - seg[:, 0]
    length = np.sqrt(r[:, 0] * r[:, 0] + r[:, 1] * r[:, 1])
    out = []
    for i in range(len(seg) - 1):
        q, s, ls = p[i + 1 :], r[i + 1 :], length[i + 1 :]
        den = r[i, 0] * s[:, 1] - r[i, 1] * s[:, 0]
        crossing = ~(np.abs(den) < 1e-9 * length[i] * ls)  # not parallel
        d = q - p[i]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (d[:, 0] * s[:, 1] - d[:, 1] * s[:, 0]) / den
            u = (d[:, 0] * r[i, 1] - d[:, 1] * r[i, 0]) / den
        lr = length[i]
        crossing &= (eps / lr < t) & (t < 1 - eps / lr) & (eps / ls < u) & (u < 1 - eps / ls)
        out += list(p[i] + t[crossing, None] * r[i])
    # straight joints: four ends at one point, as two straight lines
    ends = {}
    for a, b in seg:
        for x, y in ((a, b), (b, a)):
            key = tuple(np.round(x, 5))
            d = (y - x) / np.linalg.norm(y - x)
            ends.setdefault(key, []).append(d)
    for key, ds in ends.items():
        if len(ds) == 4:
            ang = np.argsort([math.atan2(d[1], d[0]) for d in ds])
            a, b, c, e = (ds[i] for i in ang)  # opposite ends, bending by < 30 degrees
            if a @ c < -math.cos(math.radians(30)) and b @ e < -math.cos(math.radians(30)):
                out.append(np.array(key))
    return np.array(out).reshape(-1, 2)


def sorted_points(p, decimals=5):
    return sorted(map(tuple, np.round(np.asarray(p), decimals) + 0.0))


def check_alternation(w):
    """Every crossing: one visit over, one under; along every strand the visits alternate,
    except next to a conflict (possible only when strands end inside the pattern)."""
    assert len(w.visit_crossing) == 2 * len(w)
    over_count = np.bincount(w.visit_crossing, weights=w.visit_over.astype(float), minlength=len(w))
    assert np.all(over_count == 1)
    order = np.lexsort((w.visit_pos, w.visit_strand))
    st_, over = w.visit_strand[order], w.visit_over[order]
    same = st_[1:] == st_[:-1]
    broken = same & (over[1:] == over[:-1])
    if len(w.ends) == 0:
        assert w.conflicts == 0
    # each conflict breaks the alternation on one strand, next to that one crossing
    assert np.count_nonzero(broken) <= 2 * w.conflicts


@pytest.mark.parametrize("preset", ROSETTES)
def test_rosette_crossings_match_brute_force_and_alternate(preset):
    seg = ft.Star.preset(preset).segments()
    w = weave(seg)
    assert len(w) > 0
    assert sorted_points(w.points) == sorted_points(brute_crossings(seg))
    assert w.conflicts == 0
    check_alternation(w)


def test_small_tile_crossings_match_brute_force():
    tile = ft.Tile("square", 50, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-1")), frame=2)
    seg = tile.segments()
    w = weave(seg)
    assert sorted_points(w.points) == sorted_points(brute_crossings(seg))
    assert w.conflicts == 0
    check_alternation(w)


@pytest.mark.parametrize("radii", [(51, 70, 172), ft.straight_radii(n=8, r1=51, r2=70, count=3)])
def test_plain_star_weaves_through_its_inner_points(radii):
    w = weave(ft.Star(n=8, radii=radii).segments())
    assert len(w) == 8 and len(w.knots) == 0 and w.conflicts == 0
    check_alternation(w)


def test_three_lines_through_one_point_is_a_knot():
    # three lines through the origin and one line crossing them all elsewhere
    ang = np.radians([0, 60, 120])
    d = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    seg = np.concatenate([np.stack([-2 * d, 2 * d], axis=1), [[[-3, 1], [3, 1]]]])
    w = weave(seg)
    assert sorted_points(w.knots) == [(0.0, 0.0)]
    # the three lines go straight through the knot: four strands, each crossing y = 1 once
    # except the horizontal one; only the two-strand crossings carry over/under
    assert len(w) == 2
    assert len(np.unique(w.strand)) == 4
    check_alternation(w)


def test_a_closed_loop_of_strands_always_alternates():
    # a triangle's three lines extended into a closed loop with a figure-eight: no ends
    pts = np.array([[0, 0], [4, 0], [1, 3], [1, -1], [3, -1], [3, 3]], float)
    loop = np.stack([pts, np.roll(pts, -1, axis=0)], axis=1)
    w = weave(loop)
    assert len(w.ends) == 0 and len(w) > 0 and w.conflicts == 0
    check_alternation(w)


def test_a_tip_turns_the_strand():
    # a V whose arms cross two parallel lines: one strand through the tip, crossings alternate on it
    seg = np.array([[[-2, 2], [0, 0]], [[0, 0], [2, 2]], [[-3, 1], [3, 1]], [[-3, 1.5], [3, 1.5]]])
    w = weave(seg)
    assert w.strand[0] == w.strand[1]
    assert len(w) == 4
    check_alternation(w)


def _bent_crossing(bend_deg):
    """A line and a flat V whose tip touches it: the two strands cross there, each bending by ``bend_deg``."""
    t = 10 * math.tan(math.radians(bend_deg))
    return np.array([[[-10, 0], [10, 0]], [[-10, -t], [0, 0]], [[0, 0], [10, -t]]], float)


@pytest.mark.parametrize("bend", [3.0, 10.0, 25.0])
def test_two_strands_bending_at_one_point_cross_at_their_angle(bend):
    # each strand runs from the line on one side to the V's arm on the other: they change sides at the tip,
    # a crossing of two strands that both bend there; their directions are the mean of the pieces
    # arriving and leaving, so they meet at the bend angle (the pieces arriving can be the line's two halves)
    from fabtiles.geometry import interlace as gi

    w = weave(_bent_crossing(bend))
    assert len(w) == 1 and len(w.knots) == 0 and w.conflicts == 0
    assert w.sin[0] == pytest.approx(math.sin(math.radians(bend)))
    assert abs(w.over_dir[0, 1]) == pytest.approx(math.sin(math.radians(bend / 2)))
    assert np.isfinite(w.under_gaps(0.5, 0.3)).all() and np.isfinite(w.max_gap(0.5))
    assert w.straight_reach().tolist() == [[0.0, 0.0]]  # the under strand bends at the crossing
    region = shapely.union_all(shapely.buffer(shapely.linestrings(_bent_crossing(bend)), 0.5))
    woven = gi.woven_region(region, w, 0.5, 0.3)
    assert woven.is_valid and 0 < woven.area < region.area


def test_strands_and_visits_are_linear_not_quadratic_in_count():
    # a grid of 40 + 40 lines: 1600 crossings, every line alternating
    lines = [[[-1, y], [41, y]] for y in range(40)] + [[[x, -1], [x, 41]] for x in range(40)]
    w = weave(np.array(lines, float))
    assert len(w) == 1600 and w.conflicts == 0
    check_alternation(w)


def test_broken_pieces_leave_the_over_strand_whole():
    x = np.array([[[-1, 0], [1, 0]], [[0, -1], [0, 1]]], float)
    w = weave(x)
    b = w.broken_pieces(0.1, 0.05)
    over_is_horizontal = w.over[0] == 0
    horiz = b[np.isclose(b[:, 0, 1], b[:, 1, 1])]
    vert = b[~np.isclose(b[:, 0, 1], b[:, 1, 1])]
    whole, broken = (horiz, vert) if over_is_horizontal else (vert, horiz)
    assert len(whole) == 1 and len(broken) == 2
    gap = np.sort(np.abs(broken[:, :, :]).min(axis=1).max(axis=1))
    assert np.allclose(gap, 0.15)


def test_broken_pieces_without_a_crossing_are_the_segments():
    # strands that never cross (a V and a line apart from it): nothing to break, every segment whole
    seg = np.array([[[0, 0], [1, 1]], [[1, 1], [2, 0]], [[0, 3], [2, 3]]], float)
    w = weave(seg)
    assert len(w) == 0
    pieces = w.broken_pieces(0.2, 0.1)
    assert sorted(map(tuple, pieces.reshape(-1, 4).round(9).tolist())) == sorted(map(tuple, seg.reshape(-1, 4)))


def test_max_gap_is_where_the_gaps_add_up_to_a_whole_strand():
    # a 4 long line under at one of two crossings (limit 2 - 0.25), 2 long crossers (1 - 0.25)
    seg = np.array([[[0, 0], [4, 0]], [[1, -1], [1, 1]], [[3, -1], [3, 1]]], float)
    assert math.isclose(weave(seg).max_gap(0.25), 0.75)
    # at 60 degrees a gap is 1 / sin 60 times longer along the under strand
    c, s = math.cos(math.pi / 3), math.sin(math.pi / 3)
    two = np.array([[[-5, 0], [5, 0]], [[-c, -s], [c, s]]], float)
    w = weave(two)
    under_len = 10.0 if w.under[0] == 0 else 2.0
    assert math.isclose(w.max_gap(0.25), under_len / 2 * s - 0.25)
    assert weave(seg[:1]).max_gap(0.25) == math.inf


def test_empty_and_single_segment():
    assert len(weave(np.empty((0, 2, 2)))) == 0
    w = weave(np.array([[[0, 0], [1, 0]]], float))
    assert len(w) == 0 and w.strand.tolist() == [0]


radius = st.floats(1, 300)


@st.composite
def motifs(draw):
    n = draw(st.integers(3, 16))
    radii = draw(st.lists(radius, min_size=2, max_size=4))
    special = draw(st.none() | st.integers(2, len(radii)))
    return ft.Star(
        n=n,
        radii=radii,
        alpha=draw(st.floats(-80, 80)),
        spr=draw(st.floats(-100, 100)),
        special=special,
        rotation=draw(st.floats(0, 360)),
    )


@settings(max_examples=examples(60), deadline=None)
@given(motifs())
def test_alternation_holds_for_random_motifs(star):
    # conflicts only where strands end inside the motif (check_alternation); closed strands never
    check_alternation(weave(star.segments()))


@settings(max_examples=examples(15), deadline=None)
@given(motifs(), st.sampled_from([ft.HexPacking, ft.SquarePacking]), st.floats(6, 20))
def test_alternation_holds_for_random_packings(star, packing, r):
    # the motifs only: outline circles kiss each other and are not woven (see Tile.weave)
    check_alternation(weave(packing(radius=r, motif=star).motif_segments((-30, -30, 30, 30))))


def test_straight_reach_runs_along_the_under_strand():
    """Each under strand is straight over [-back, forward] from its crossing, by its own segments."""
    tile = ft.Tile("square", 50, ft.HexPacking(radius=12, motif=ft.Star.preset("table3-1")), frame=2)
    seg = tile.motif_segments()
    w = weave(seg)
    reach = w.straight_reach()
    assert reach.shape == (len(w), 2) and (reach >= 0).all()
    a, b = seg[:, 0], seg[:, 1]
    d = (b - a) / np.linalg.norm(b - a, axis=1, keepdims=True)
    checked = 0
    for c in np.flatnonzero(reach.min(axis=1) > 0)[:200]:
        p, du = w.points[c], w.under_dir[c]
        along = np.abs(d[:, 0] * du[1] - d[:, 1] * du[0]) < 1e-9  # segments parallel to the strand
        for t in np.linspace(-reach[c, 0], reach[c, 1], 7):
            q = p + t * du
            s = np.einsum("ij,ij->i", q - a, d)
            off = np.abs((q - a)[:, 0] * d[:, 1] - (q - a)[:, 1] * d[:, 0])
            on = along & (off < 1e-7) & (s > -1e-7) & (s < np.linalg.norm(b - a, axis=1) + 1e-7)
            assert on.any(), f"crossing {c}: {t:+.3f} along the under strand is on no straight segment"
        checked += 1
    assert checked >= 50
    # a strand bending at its crossing (a straight joint may bend by up to BEND_DEG) reaches nowhere
    bent = weave(np.array([[[-2, 0], [0, 0]], [[0, 0], [2, 0.2]], [[0, -1], [0, 0]], [[0, 0], [0, 1]]], float))
    assert len(bent) == 1 and (bent.straight_reach()[0] == 0).all() == (bent.under[0] in (0, 1))


@settings(max_examples=examples(60), deadline=None)
@given(st.lists(st.tuples(st.floats(-3e3, 3e3), st.floats(-3e3, 3e3)), min_size=1, max_size=12), st.booleans())
def test_point_keys_are_the_rounded_rows(points, huge):
    from fabtiles.pattern.interlace import MERGE, _point_keys

    pts = np.array(points + points[:3]) * (1e3 if huge else 0.1)  # repeats; huge: past the int64 packing
    keys = _point_keys(pts)
    rows = np.round(pts / MERGE).astype(np.int64)
    same_key = keys[:, None] == keys[None, :]
    same_row = (rows[:, None, :] == rows[None, :, :]).all(axis=2)
    assert np.array_equal(same_key, same_row)


def greedy_pairs(ends, d, cos_bend):
    """The knot rule written plainly: all pairs within the bend, straightest first (ties by
    end number), each end used once."""
    cand = sorted((float(d[a] @ d[b]), a, b) for a, b in itertools.combinations(ends, 2))
    partner = {}
    for dot, a, b in cand:
        if dot < -cos_bend and a not in partner and b not in partner:
            partner[a], partner[b] = b, a
    return partner


@settings(max_examples=examples(60), deadline=None)
@given(st.integers(3, 6), st.integers(0, 2**31 - 1), st.booleans())
def test_knot_pairing_is_the_greedy_rule(g, seed, snap_angles):
    """The vectorised knot pairing (3 or 4 ends) and the loop (more) pick the pairs the rule does,
    ties included (angles on a 45 degree grid tie often)."""
    from fabtiles.pattern import interlace as pi

    rng = np.random.default_rng(seed)
    m = 7
    ang = rng.uniform(0, 2 * np.pi, (m, g))
    if snap_angles:
        ang = np.round(ang / (np.pi / 4)) * (np.pi / 4)
    d = np.stack([np.cos(ang), np.sin(ang)], axis=-1).reshape(-1, 2)
    ends = np.array([rng.permutation(g) + g * r for r in range(m)])
    partner = np.full(m * g, -1)
    pi._pair_knots(partner, ends, d)
    want = {}
    for row in ends.tolist():
        want.update(greedy_pairs(row, d, pi._COS_BEND))
    assert {e: int(p) for e, p in enumerate(partner) if p >= 0} == want


def test_a_t_junction_ends_the_stem():
    """Three ends at a T: the bar goes straight on, the stem ends there (a knot)."""
    seg = np.array([[[-2, 0], [0, 0]], [[0, 0], [2, 0]], [[0, 0], [0, 2]], [[-1, -1], [-1, 1]]], float)
    w = weave(seg)
    assert sorted_points(w.knots) == [(0.0, 0.0)]
    assert w.strand[0] == w.strand[1] != w.strand[2]
    assert (0.0, 2.0) in sorted_points(w.ends) and (0.0, 0.0) in sorted_points(w.ends)


@settings(max_examples=examples(40), deadline=None)
@given(st.lists(st.integers(0, 70), max_size=15), st.integers(0, 2**31 - 1))
def test_running_sums_along_strands_are_a_loops_floats(count, seed):
    """Positions along strands are summed piece after piece: bit for bit what a walk adds up."""
    from fabtiles.pattern.interlace import _cumulative

    rng = np.random.default_rng(seed)
    values = rng.uniform(0, 10, sum(count)) ** 3  # magnitudes apart, so the order of additions shows
    want, at = [], 0
    for c in count:
        pos = 0.0
        for x in values[at : at + c].tolist():
            pos += x
            want.append(pos)
        at += c
    assert _cumulative(values, np.array(count, np.int64)).tolist() == want
