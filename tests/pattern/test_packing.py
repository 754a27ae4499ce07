"""Circle packings against docs/tile-operation.md: centres, radii, tangency, motif placement."""

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles import LimitError, ParameterError, Star
from fabtiles.pattern.packing import (
    HexPacking,
    SquarePacking,
    circle_segments,
    default_gap_motif,
)

S3 = math.sqrt(3)
MOTIF = Star.preset("table3-3")


def brute_hex(R, window, reach):
    """Big circle centres i*(2R,0)+j*(R,sqrt3 R) whose bounding box meets the window."""
    x0, y0, x1, y1 = window
    out = []
    for i, j in itertools.product(range(-60, 61), repeat=2):
        x, y = i * 2 * R + j * R, j * S3 * R
        if x0 - reach <= x <= x1 + reach and y0 - reach <= y <= y1 + reach:
            out.append((x, y))
    return sorted(out)


def as_set(points, decimals=6):
    return sorted(map(tuple, np.round(np.asarray(points), decimals) + 0.0))


def test_hex_big_centres_follow_the_formula():
    p = HexPacking(radius=7, motif=MOTIF)
    window = (-40, -25, 55, 30)
    assert as_set(p.lattice_points(window)) == as_set(brute_hex(7, window, 7))


def test_hex_gap_circles_at_triangle_centroids():
    R = 10.0
    p = HexPacking(radius=R, motif=MOTIF)
    assert p.gap_radius == pytest.approx(R * (2 / S3 - 1))
    gaps = p.gap_centres((-1, -8, 12, 8))
    # The up triangle (0,0),(2R,0),(R,sqrt3 R) and the down one (0,0),(2R,0),(R,-sqrt3 R).
    up = np.mean([[0, 0], [2 * R, 0], [R, S3 * R]], axis=0)
    down = np.mean([[0, 0], [2 * R, 0], [R, -S3 * R]], axis=0)
    found = as_set(gaps)
    assert tuple(np.round(up, 6)) in found and tuple(np.round(down, 6)) in found


def test_hex_tangency():
    R = 12.5
    p = HexPacking(radius=R, motif=MOTIF)
    big = p.lattice_points((-60, -60, 60, 60))
    gap = p.gap_centres((-30, -30, 30, 30))
    d = np.linalg.norm(big[:, None] - big[None], axis=-1)
    d[d == 0] = np.inf
    # Big circles touch their neighbours (nearest centre distance 2R) and never overlap.
    assert d.min() == pytest.approx(2 * R)
    near = np.sort(np.linalg.norm(gap[:, None] - big[None], axis=-1), axis=1)
    # Each surrounded circle touches exactly three big circles.
    np.testing.assert_allclose(near[:, :3], R + p.gap_radius, rtol=1e-12)
    assert (near[:, 3] > R + p.gap_radius + 1).all()
    assert p.period == pytest.approx((2 * R, 2 * S3 * R))


def test_square_packing_formulas_and_tangency():
    R = 10.0
    p = SquarePacking(radius=R, motif=MOTIF)
    big = p.lattice_points((-25, -25, 25, 25))
    assert as_set(big) == as_set([(2 * R * i, 2 * R * j) for i in range(-1, 2) for j in range(-1, 2)])
    assert p.gap_radius == pytest.approx((math.sqrt(2) - 1) * R)
    gap = p.gap_centres((-7, -7, 7, 7))
    assert as_set(gap) == as_set([(sx * R, sy * R) for sx in (-1, 1) for sy in (-1, 1)])
    near = np.sort(np.linalg.norm(gap[:, None] - big[None], axis=-1), axis=1)
    np.testing.assert_allclose(near[:, :4], R + p.gap_radius, rtol=1e-12)
    assert p.period == (2 * R, 2 * R)


@pytest.mark.parametrize("cls", [HexPacking, SquarePacking])
@pytest.mark.parametrize("fill", [1.0, 0.8])
def test_motif_scaling(cls, fill):
    p = cls(radius=9, motif=Star.preset("table2-right"), fill=fill)
    big, gap = p.placed_motif("big"), p.placed_motif("gap")
    assert np.hypot(*big.reshape(-1, 2).T).max() == pytest.approx(9 * fill)
    assert np.hypot(*gap.reshape(-1, 2).T).max() == pytest.approx(p.gap_radius * fill)
    # Same shape as the motif: a pure scale (rotation is already inside the segments).
    star = Star.preset("table2-right")
    np.testing.assert_allclose(big, star.segments() * (9 * fill / star.extent))


def test_rotation_of_the_motif_is_kept():
    turned = Star.preset("table3-3", rotation=15)
    p = HexPacking(radius=5, motif=turned)
    np.testing.assert_allclose(p.placed_motif(), turned.segments() * (5 / turned.extent))


def test_default_gap_motif():
    assert default_gap_motif() == Star(n=6, radii=(0.5, 1.0))
    assert HexPacking(radius=3, motif=MOTIF).gap_motif == Star(n=6, radii=(0.5, 1.0))


def test_segments_are_motifs_translated_to_every_centre():
    p = HexPacking(radius=6, motif=MOTIF)
    window = (-20, -15, 20, 15)
    seg = p.segments(window)
    big, gap = p.lattice_points(window), p.gap_centres(window)
    kb, kg = len(p.placed_motif("big")), len(p.placed_motif("gap"))
    assert seg.shape == (len(big) * kb + len(gap) * kg, 2, 2)
    np.testing.assert_allclose(seg[:kb], p.placed_motif("big") + big[0])
    np.testing.assert_allclose(seg[len(big) * kb : len(big) * kb + kg], p.placed_motif("gap") + gap[0])


def test_outline_circles_are_fine_chords_through_the_tangency_points():
    p = HexPacking(radius=15, motif=MOTIF, outline_circles=True)
    window = (-1, -1, 16, 1)
    plain = HexPacking(radius=15, motif=MOTIF).segments(window)
    seg = p.segments(window)
    chords = seg[len(plain) :]
    centres, radii = p.circles(window)
    assert len(chords) > 0
    # Every chord end lies on one of the circles, and sagitta <= 0.005 mm.
    for c, r in zip(centres, radii, strict=True):
        mine = chords[np.abs(np.hypot(*(chords[:, 0] - c).T) - r) < 1e-9]
        length = np.linalg.norm(mine[:, 1] - mine[:, 0], axis=1)
        sagitta = r - np.sqrt(r**2 - (length / 2) ** 2)
        assert sagitta.max() <= 0.005
    # The tangency point of the two big circles at (0,0) and (2R,0) is a vertex of both.
    assert (np.abs(chords.reshape(-1, 2) - [15, 0]).max(axis=1) < 1e-9).sum() >= 4


def test_circle_segments_tolerance():
    seg = circle_segments([[1.0, 2.0]], [50.0], tolerance=0.001)
    assert len(seg) % 24 == 0
    half = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1) / 2
    assert (50 - np.sqrt(50**2 - half**2)).max() <= 0.001


@given(R=st.floats(0.5, 30), x0=st.floats(-100, 100), y0=st.floats(-100, 100), w=st.floats(0, 80), h=st.floats(0, 80))
@settings(max_examples=examples(40), deadline=None)
def test_every_circle_meeting_the_window_is_listed(R, x0, y0, w, h):
    p = HexPacking(radius=R, motif=MOTIF)
    window = (x0, y0, x0 + w, y0 + h)
    got = p.lattice_points(window)
    # Brute force around the window: a big circle meeting it must be listed.
    cand = []
    jlo, jhi = math.floor((y0 - R) / (S3 * R)) - 1, math.ceil((y0 + h + R) / (S3 * R)) + 1
    for j in range(jlo, jhi + 1):
        ilo = math.floor((x0 - R - j * R) / (2 * R)) - 1
        ihi = math.ceil((x0 + w + R - j * R) / (2 * R)) + 1
        for i in range(ilo, ihi + 1):
            c = np.array([2 * R * i + R * j, S3 * R * j])
            nearest = np.clip(c, [x0, y0], [x0 + w, y0 + h])
            if np.linalg.norm(c - nearest) < R * (1 - 1e-9):
                cand.append(c)
    got_set = set(as_set(got, 5))
    assert all(tuple(np.round(c, 5) + 0.0) in got_set for c in cand)


def test_sheet_segment_count():
    # The 600 x 400 mm sheet of the issues: about 40,000 segments (timings: benchmarks/).
    p = HexPacking(radius=15, motif=MOTIF)
    seg = p.segments((-300, -200, 300, 200))
    assert 30_000 < len(seg) < 45_000


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(radius=0, motif=MOTIF), r"radius must be a finite number > 0, got 0"),
        (dict(radius=float("nan"), motif=MOTIF), r"radius must be a finite number"),
        (dict(radius=5, motif="table3-3"), r"motif must be a Star"),
        (dict(radius=5, motif=MOTIF, gap_motif=3), r"gap_motif must be a Star or None"),
        (dict(radius=5, motif=MOTIF, outline_circles="yes"), r"outline_circles must be true or false"),
        (dict(radius=5, motif=MOTIF, fill=0), r"fill must be a finite number > 0 and <= 1, got 0"),
        (dict(radius=5, motif=MOTIF, fill=1.5), r"fill must be a finite number > 0 and <= 1, got 1.5"),
    ],
)
def test_bad_parameters(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        HexPacking(**kwargs)


def test_bad_window_and_limits():
    p = SquarePacking(radius=5, motif=MOTIF)
    with pytest.raises(ParameterError, match=r"window must be \(xmin, ymin, xmax, ymax\)"):
        p.segments((0, 0, 1))
    with pytest.raises(ParameterError, match=r"min <= max"):
        p.segments((0, 0, -1, 1))
    with pytest.raises(LimitError, match=r"more than the limit"):
        HexPacking(radius=0.001, motif=MOTIF).segments((0, 0, 1000, 1000))
    with pytest.raises(ParameterError, match=r"'tiny' is not a valid motif, must be one of: big, gap"):
        p.placed_motif("tiny")


def test_equality_replace_and_repr():
    a = HexPacking(radius=5, motif=MOTIF)
    assert a == HexPacking(radius=5.0, motif=Star.preset("table3-3"))
    assert a != SquarePacking(radius=5, motif=MOTIF)
    assert hash(a) == hash(a.replace())
    assert a.replace(radius=6).radius == 6
    assert repr(a).startswith("HexPacking(radius=5, motif=Star(n=12")
