"""Hankin's polygons in contact against a construction written here from its definition.

The reference below takes the tilings' polygons (centres, sides, one edge-midpoint direction)
and nothing else of fabtiles: it walks each polygon's corners counter-clockwise, sends two rays
from each edge at the contact angle (``contact_gap`` apart, each starting on the side away
from the corner it leans towards), ends each ray where it meets, by a line intersection, the
ray from the next edge leaning towards the same corner, and, without a gap, joins a ray and
the neighbour's ray that continues it straight across the edge.
"""

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles import ArchimedeanPacking, ParameterError
from fabtiles.pattern.hankin import max_contact_angle
from fabtiles.pattern.tilings import ALL_TILINGS, unit_cell

EDGE = 10.0
HALF = 45.0  # the compared window: (-HALF, -HALF, HALF, HALF)


def corners(centre, p, mid_angle, edge):
    """A regular p-gon's corners, counter-clockwise, from its centre and one edge midpoint's direction."""
    r = edge / (2 * math.sin(math.pi / p))
    t = mid_angle + math.pi / p + 2 * math.pi * np.arange(p) / p
    return centre + r * np.stack([np.cos(t), np.sin(t)], axis=1)


def intersect(p0, u0, p1, u1):
    """Where the lines p0 + s u0 and p1 + t u1 meet (Cramer's rule on s u0 - t u1 = p1 - p0)."""
    (ax, ay), (bx, by), (cx, cy) = u0, -u1, p1 - p0
    s = (cx * by - bx * cy) / (ax * by - bx * ay)
    return p0 + s * u0


def reference_rays(tiling, angle, gap, reach):
    """Every polygon's rays whose polygon centre is within ``reach``: list of (start, end, polygon centre)."""
    cell = unit_cell(tiling)
    lat = cell.lattice * EDGE
    n = int(reach / min(np.hypot(*lat.T))) + 3
    th = math.radians(angle)
    rays = []
    for i in range(-n, n + 1):
        for j in range(-n, n + 1):
            for c, p, a in zip(cell.centres * EDGE, cell.sides, cell.angles, strict=True):
                c = c + i * lat[0] + j * lat[1]
                if np.abs(c).max() > reach:
                    continue
                v = corners(c, int(p), a, EDGE)
                starts, dirs = [], []
                for k in range(p):
                    a0, a1 = v[k], v[(k + 1) % p]
                    d = (a1 - a0) / np.hypot(*(a1 - a0))
                    inward = np.array([-d[1], d[0]])
                    m = (a0 + a1) / 2
                    # towards a1 from the start near a0; towards a0 from the start near a1
                    starts.append((m - gap / 2 * d, m + gap / 2 * d))
                    dirs.append((math.cos(th) * d + math.sin(th) * inward, -math.cos(th) * d + math.sin(th) * inward))
                for k in range(p):
                    nxt = (k + 1) % p  # the corner v[k + 1] between edge k and edge k + 1
                    # a regular polygon's two rays leaning to a corner meet on its bisector (where the
                    # ray from the next edge crosses it too: checked; at 45 degrees in a square the two
                    # rays lie on one line, and the bisector is where they meet)
                    corner = v[nxt]
                    axis = (c - corner) / np.hypot(*(c - corner))
                    end = intersect(starts[k][0], dirs[k][0], corner, axis)
                    off = end - starts[nxt][1]
                    assert abs(off[0] * dirs[nxt][1][1] - off[1] * dirs[nxt][1][0]) < 1e-9
                    rays.append((starts[k][0], end, c))
                    rays.append((starts[nxt][1], end, c))
    return rays


def same_point(a, b) -> bool:
    """``np.allclose(a, b)`` of two points, on plain floats (it is called for every pair of rays at a point)."""
    return abs(a[0] - b[0]) <= 1e-8 + 1e-5 * abs(b[0]) and abs(a[1] - b[1]) <= 1e-8 + 1e-5 * abs(b[1])


def reference_segments(tiling, angle, gap, reach):
    rays = reference_rays(tiling, angle, gap, reach)
    if gap > 0:
        return np.array([(s, e) for s, e, _ in rays])
    # no gap: a ray and the neighbour's ray that continues it straight across the edge are one segment
    by_start = {}
    for s, e, c in rays:
        by_start.setdefault(tuple(np.round(s, 6)), []).append((s, e, c))
    out = []
    for group in by_start.values():
        used = set()
        for x, (s, e, c) in enumerate(group):
            if x in used:
                continue
            partner = None
            for y, (s2, e2, c2) in enumerate(group):
                if y == x or y in used or same_point(c, c2):
                    continue
                u, w = e - s, e2 - s2
                if abs(u[0] * w[1] - u[1] * w[0]) < 1e-9 * np.hypot(*u) * np.hypot(*w) and u @ w < 0:
                    partner = y
            used.add(x)
            if partner is None:
                out.append((s, e))
            else:
                used.add(partner)
                out.append((group[partner][1], e))
    return np.array(out)


def inside(segments, half):
    """The segments with both ends in the box of half side ``half``."""
    return segments[(np.abs(segments).reshape(len(segments), -1) <= half).all(axis=1)]


def canonical(segments):
    """Each segment's ends in lexicographic order, the segments sorted: sets compare as arrays."""
    s = np.asarray(segments, dtype=float).copy()
    key = np.round(s, 6)
    swap = (key[:, 0, 0] > key[:, 1, 0]) | ((key[:, 0, 0] == key[:, 1, 0]) & (key[:, 0, 1] > key[:, 1, 1]))
    s[swap] = s[swap][:, ::-1]
    key = np.round(s, 6).reshape(len(s), -1)
    return s[np.lexsort(key.T[::-1])]


def hankin(tiling, angle, gap=0.0, **kw):
    return ArchimedeanPacking(tiling, EDGE, method="hankin", contact_angle=angle, contact_gap=gap, **kw)


CASES = [(t, a) for t in ("4.4.4.4", "6.6.6", "4.8.8", "3.12.12") for a in (22.5, 45.0, 60.0, 67.5, 80.0)]


@pytest.mark.parametrize(("tiling", "angle"), CASES)
def test_segments_equal_the_reference_construction(tiling, angle):
    ours = inside(hankin(tiling, angle).segments((-HALF, -HALF, HALF, HALF)), HALF)
    ref = inside(reference_segments(tiling, angle, 0.0, HALF + 6 * EDGE), HALF)
    assert len(ours) == len(ref) > 20
    np.testing.assert_allclose(canonical(ours), canonical(ref), atol=1e-9)


@pytest.mark.parametrize(
    ("tiling", "angle", "gap"),
    [
        ("4.4.4.4", 60.0, 2.0),
        ("6.6.6", 45.0, 3.0),
        ("4.8.8", 67.5, 1.5),
        ("3.12.12", 30.0, 4.0),
        ("3.4.6.4", 50.0, 1.0),
    ],
)
def test_with_a_gap_segments_equal_the_reference_construction(tiling, angle, gap):
    ours = inside(hankin(tiling, angle, gap).segments((-HALF, -HALF, HALF, HALF)), HALF)
    ref = inside(reference_segments(tiling, angle, gap, HALF + 6 * EDGE), HALF)
    assert len(ours) == len(ref) > 20
    np.testing.assert_allclose(canonical(ours), canonical(ref), atol=1e-9)


@pytest.mark.parametrize("tiling", ALL_TILINGS)
@pytest.mark.parametrize("gap", [0.0, 1.0])
def test_closed_strands_no_segment_twice_and_the_reference(tiling, gap):
    """Every ray end is shared by exactly two segments; no segment is listed twice; and every tiling
    matches the reference (the 11 and the two-uniform ones at one angle)."""
    segs = hankin(tiling, 55.0, gap).segments((-HALF, -HALF, HALF, HALF))
    ends = np.round(segs.reshape(-1, 2), 6)
    keys, counts = np.unique(ends, axis=0, return_counts=True)
    middle = (np.abs(keys) <= HALF - 3 * EDGE).all(axis=1)
    assert middle.sum() > 10 and (counts[middle] == 2).all()
    assert len(np.unique(np.round(canonical(segs), 6).reshape(len(segs), -1), axis=0)) == len(segs)
    ref = inside(reference_segments(tiling, 55.0, gap, HALF + 6 * EDGE), HALF)
    np.testing.assert_allclose(canonical(inside(segs, HALF)), canonical(ref), atol=1e-9)


@pytest.mark.parametrize("tiling", ["4.8.8", "3.3.4.3.4", "3.3.3.3.6"])
def test_invariant_under_the_tilings_translations(tiling):
    pack = hankin(tiling, 40.0, 0.5)
    half = 25.0
    base = canonical(inside(pack.segments((-half, -half, half, half)), half))
    for v in pack.lattice:
        moved = pack.segments((v[0] - half, v[1] - half, v[0] + half, v[1] + half)) - v
        np.testing.assert_allclose(canonical(inside(moved, half)), base, atol=1e-9)


@pytest.mark.parametrize(("tiling", "gap"), [("4.4.4.4", 2.5), ("3.6.3.6", 1.0), ("4.6.12", 3.0)])
def test_a_gaps_two_rays_start_contact_gap_apart_on_their_edge(tiling, gap):
    segs = hankin(tiling, 50.0, gap).segments((-HALF, -HALF, HALF, HALF))
    ends = segs.reshape(-1, 2)
    cell = unit_cell(tiling)
    checked = 0
    for c, p, a in zip(cell.centres * EDGE, cell.sides, cell.angles, strict=True):
        v = corners(c, int(p), a, EDGE)
        for k in range(p):
            a0, a1 = v[k], v[(k + 1) % p]
            d = (a1 - a0) / EDGE
            t = (ends - a0) @ d
            off = np.abs((ends - a0) @ np.array([-d[1], d[0]]))
            on = np.unique(np.round(t[(off < 1e-9) & (t > 1e-9) & (t < EDGE - 1e-9)], 9))
            assert len(on) == 2, on
            assert on[1] - on[0] == pytest.approx(gap, abs=1e-9)
            assert (on[0] + on[1]) / 2 == pytest.approx(EDGE / 2, abs=1e-9)
            checked += 1
    assert checked >= 4


def test_motifs_in_chosen_kinds_rays_in_the_others():
    mixed = hankin("4.8.8", 60.0, motifs={8: "table3-3"})
    assert dict(mixed.motifs).keys() == {8} and mixed.kinds == (4, 8)
    segs = mixed.segments((-HALF, -HALF, HALF, HALF))
    only = ArchimedeanPacking("4.8.8", EDGE, motifs={8: "table3-3"}).segments((-HALF, -HALF, HALF, HALF))
    # the octagons' motifs are the paper's (the same segments as with method "motifs")
    r = mixed.incircle_radius(8) + 1e-9
    octagon = canonical(only[(np.hypot(*only.transpose(2, 0, 1)) <= r).all(axis=1)])
    ours = canonical(segs[(np.hypot(*segs.transpose(2, 0, 1)) <= r).all(axis=1)])
    assert len(octagon) > 20
    np.testing.assert_allclose(ours, octagon, atol=1e-9)
    # the squares take rays that start at their edges' midpoints, each listed once
    rays = hankin("4.8.8", 60.0).segments((-HALF, -HALF, HALF, HALF))
    assert len(segs) != len(rays)
    assert len(np.unique(np.round(canonical(segs), 6).reshape(len(segs), -1), axis=0)) == len(segs)


def test_the_default_method_is_the_papers_unchanged():
    plain = ArchimedeanPacking("4.8.8", EDGE)
    assert plain.method == "motifs" and plain.contact_angle == 60.0 and plain.contact_gap == 0.0
    assert ArchimedeanPacking("4.8.8", EDGE, method="motifs") == plain
    assert "method" not in repr(plain) and "method='hankin'" in repr(hankin("4.8.8", 60.0))


def test_hankin_has_no_gap_circles_and_a_parameter_round_trip():
    import copy
    import pickle

    pack = hankin("3.4.6.4", 35.0, 1.0)
    assert (pack.circle_sides((-30, -30, 30, 30)) > 0).all()
    assert pickle.loads(pickle.dumps(pack)) == pack == copy.deepcopy(pack)
    assert pack.replace(contact_angle=50.0).contact_angle == 50.0
    assert ArchimedeanPacking("4.8.8", EDGE).replace(method="hankin").method == "hankin"
    assert pack.segment_count((-30, -30, 30, 30)) == len(pack.segments((-30, -30, 30, 30)))


@pytest.mark.parametrize("angle", [0, 90, -5, 120, float("nan"), "60"])
def test_an_angle_outside_0_90_is_refused(angle):
    with pytest.raises(ParameterError, match=r"contact_angle must be .*> 0 and < 90") as err:
        hankin("4.8.8", angle)
    assert err.value.param == "contact_angle"


def test_a_negative_gap_or_one_as_long_as_the_edge_is_refused():
    with pytest.raises(ParameterError, match=r"contact_gap must be a finite number >= 0, got -1"):
        hankin("4.8.8", 60.0, -1.0)
    with pytest.raises(ParameterError, match=r"contact_gap must be >= 0 and < the edge \(10 mm\)"):
        hankin("4.8.8", 60.0, EDGE)


def test_an_angle_with_no_pattern_names_the_tilings_valid_range():
    top = max_contact_angle(3, EDGE, 3.0)
    assert 0 < top < 90
    hankin("3.12.12", top - 0.01, 3.0)
    with pytest.raises(
        ParameterError,
        match=r"contact_angle 70 has no pattern on the tiling 3\.12\.12 with "
        r"contact_gap 3 mm: .*3-gons.* must be > 0 and <= 62\.5",
    ):
        hankin("3.12.12", 70.0, 3.0)
    # the same angle is fine where the triangles keep a motif
    hankin("3.12.12", 70.0, 3.0, motifs={3: "table3-3"})


def test_an_unknown_method_is_refused():
    with pytest.raises(ParameterError, match=r"method = 'kaplan' is not valid, must be one of: motifs, hankin"):
        ArchimedeanPacking("4.8.8", EDGE, method="kaplan")


@settings(max_examples=examples(25), deadline=None)
@given(
    tiling=st.sampled_from(ALL_TILINGS), angle=st.floats(1, 89), gap_fraction=st.floats(0, 0.9), edge=st.floats(2, 30)
)
# the case this property found: a gap of float dust, whose two ray starts are one point
@example(tiling="4.8.8", angle=30.0, gap_fraction=1e-12, edge=10.0)
@example(tiling="3.6.3.6", angle=45.0, gap_fraction=5e-324, edge=2.0)
def test_any_valid_angle_and_gap_closes_every_strand(tiling, angle, gap_fraction, edge):
    """Property: every valid (angle, gap) gives closed strands, each segment once; an invalid one is refused."""
    kinds = set(unit_cell(tiling).sides.tolist())
    gap = gap_fraction * edge
    if any(angle > max_contact_angle(p, edge, gap) for p in kinds):
        with pytest.raises(ParameterError, match=r"has no pattern on the tiling"):
            ArchimedeanPacking(tiling, edge, method="hankin", contact_angle=angle, contact_gap=gap)
        return
    pack = ArchimedeanPacking(tiling, edge, method="hankin", contact_angle=angle, contact_gap=gap)
    half = 4 * edge
    segs = pack.segments((-half, -half, half, half))
    assert (np.hypot(*(segs[:, 1] - segs[:, 0]).T) > 0).all()
    ends = segs.reshape(-1, 2)
    middle = (np.abs(ends) <= half - 2.5 * edge).all(axis=1)
    assert (near_count(ends[middle], ends) == 2).all()
    flat = canonical(segs).reshape(len(segs), -1)
    assert (near_count(flat, flat) == 1).all()  # each segment once


def near_count(points, among, tol=1e-7):
    """How many of ``among`` lie within ``tol`` of each of ``points`` (no rounding: a tie at the 6th
    decimal splits two equal points that rounding would)."""
    return np.concatenate(
        [
            (np.abs(chunk[:, None] - among[None]).max(axis=2) < tol).sum(axis=1)
            for chunk in np.array_split(points, max(1, len(points) // 256))
        ]
    )
