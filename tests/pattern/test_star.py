"""The motif engine against docs/construction.md, to the letter."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

import fabtiles as ft
from fabtiles.pattern.star import MAX_CIRCLES, MAX_N

PRESET_COUNTS = {
    "table1-part1": 32,
    "table1-part2": 36,
    "table2-left": 54,
    "table2-right": 80,
    "table3-1": 48,
    "table3-2": 36,
    "table3-3": 72,
}


def spec_segments(n, radii, alpha=0.0, spr=0.0, special=None, rotation=0.0):
    """docs/construction.md transcribed literally, 1-based, one segment at a time."""

    def theta(w, i):
        return rotation + (w - 1) * 180 / n + (i - 1) * 360 / n

    def at(r, deg):
        return (r * math.cos(math.radians(deg)), r * math.sin(math.radians(deg)))

    def P(w, i):
        return at(radii[w - 1], theta(w, i))

    out = []
    for w in range(1, len(radii)):
        for i in range(1, n + 1):
            j = i % n + 1
            if special is not None and w + 1 == special:
                T = P(w + 1, i)
                L = at(radii[w] - spr, theta(w + 1, i) - alpha)
                R = at(radii[w] - spr, theta(w + 1, i) + alpha)
                out += [(P(w, i), L), (P(w, j), R), (L, T), (R, T)]
            else:
                out += [(P(w, i), P(w + 1, i)), (P(w, j), P(w + 1, i))]
    return np.array(out, dtype=float)


def canon(seg, decimals=6):
    """Segments as a sorted set of rounded, direction-free tuples."""
    rows = set()
    for a, b in np.round(np.asarray(seg), decimals) + 0.0:
        a, b = tuple(a), tuple(b)
        rows.add(min(a, b) + max(a, b))
    return sorted(rows)


def same_set(s1, s2, tol=1e-6):
    """True when every segment of each set has a match (either direction) in the other."""
    s1, s2 = np.asarray(s1), np.asarray(s2)
    if len(s1) != len(s2):
        return False

    def covered(a, b):
        fwd = np.abs(a[:, None] - b[None]).max(axis=(2, 3))
        rev = np.abs(a[:, None] - b[None, :, ::-1]).max(axis=(2, 3))
        return bool((np.minimum(fwd, rev).min(axis=1) <= tol).all())

    return covered(s1, s2) and covered(s2, s1)


@pytest.mark.parametrize("name", list(PRESET_COUNTS))
def test_preset_segments_follow_the_spec(name):
    star = ft.Star.preset(name)
    seg = star.segments()
    assert seg.shape == (PRESET_COUNTS[name], 2, 2)
    assert seg.dtype == np.float64
    expected = spec_segments(**dict(star.params().items()))
    assert canon(seg) == canon(expected)


def test_presets_cover_the_papers_tables():
    assert ft.Star.presets() == tuple(PRESET_COUNTS)


def test_table1_part1_hand_computed_coordinates():
    seg = ft.Star.preset("table1-part1").segments()
    c, s = math.cos(math.radians(22.5)), math.sin(math.radians(22.5))
    # First point of circle 1 to first point of circle 2, and its mirror partner.
    np.testing.assert_allclose(seg[0], [[51, 0], [70 * c, 70 * s]], atol=1e-12)
    assert any(
        np.allclose(sg, [[51 * math.cos(math.pi / 4), 51 * math.sin(math.pi / 4)], [70 * c, 70 * s]]) for sg in seg
    )
    # Outer tip of the star: P(3,1) at 45 degrees, radius 172.
    tip = [172 * math.cos(math.pi / 4), 172 * math.sin(math.pi / 4)]
    assert (np.abs(seg - tip).max(axis=-1) < 1e-9).sum() == 2


def test_rosette_special_points_hand_computed():
    # table1-part2: n=9, radii (93, 225), alpha 48, spr -68: special points at r = 293.
    seg = ft.Star.preset("table1-part2").segments()
    t = 180 / 9  # theta(2, 1)
    left = [293 * math.cos(math.radians(t - 48)), 293 * math.sin(math.radians(t - 48))]
    right = [293 * math.cos(math.radians(t + 48)), 293 * math.sin(math.radians(t + 48))]
    np.testing.assert_allclose(seg[0], [[93, 0], left], atol=1e-9)
    p12 = [93 * math.cos(math.radians(40)), 93 * math.sin(math.radians(40))]
    np.testing.assert_allclose(seg[1], [p12, right], atol=1e-9)
    assert ft.Star.preset("table1-part2").extent == pytest.approx(293)


def test_extent_is_largest_endpoint_distance():
    # table2-right: special points at r2 - spr = 109 + 100 = 209 lie beyond r1 = 172.
    assert ft.Star.preset("table2-right").extent == pytest.approx(209)
    assert ft.Star(n=6, radii=(1, 3, 2)).extent == pytest.approx(3)


def test_rotation_turns_every_point():
    base = ft.Star(n=7, radii=(10, 20), alpha=5, spr=2, special=2)
    turned = base.replace(rotation=30)
    r = np.radians(30)
    rot = np.array([[np.cos(r), -np.sin(r)], [np.sin(r), np.cos(r)]])
    assert same_set(base.segments() @ rot.T, turned.segments())


def test_degenerate_segments_are_dropped():
    # alpha = 0 and spr = 0: L = R = T, so the two L-T and R-T segments vanish.
    star = ft.Star(n=5, radii=(1, 2), alpha=0, spr=0, special=2)
    seg = star.segments()
    assert len(seg) == 10  # P(w,i)-L and P(w,j)-R remain, L-T and R-T have zero length
    assert (np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1) > 0).all()


def test_duplicate_segments_are_merged():
    # alpha = 180/n makes R of point i coincide with L of point i+1: P(w,j)-R(i) and
    # P(w,i+1)-L(i+1) are the same segment.
    n = 6
    star = ft.Star(n=n, radii=(1, 2), alpha=180 / n, spr=0.5, special=2)
    seg = star.segments()
    assert len(canon(seg)) == len(seg)
    assert len(seg) < n * 4


def test_segments_returns_a_copy():
    star = ft.Star(n=8, radii=(1, 2))
    star.segments()[:] = 0
    assert star.segments().any()


def test_repr_and_equality():
    a = ft.Star(n=9, radii=(93, 225), alpha=48, spr=-68, special=2)
    assert repr(a) == "Star(n=9, radii=(93, 225), alpha=48, spr=-68, special=2)"
    assert a == ft.Star.preset("table1-part2") and hash(a) == hash(ft.Star.preset("table1-part2"))
    assert a != a.replace(rotation=1)


# -- properties ---------------------------------------------------------------

radius = st.floats(min_value=0.05, max_value=500, allow_nan=False)


@st.composite
def stars(draw):
    n = draw(st.integers(3, 24))
    radii = draw(st.lists(radius, min_size=2, max_size=5))
    special = draw(st.none() | st.integers(2, len(radii)))
    return ft.Star(
        n=n,
        radii=radii,
        alpha=draw(st.floats(-200, 200)),
        spr=draw(st.floats(-300, 300)),
        special=special,
        rotation=draw(st.floats(-360, 360)),
    )


def _rotate(seg, deg):
    r = math.radians(deg)
    m = np.array([[math.cos(r), -math.sin(r)], [math.sin(r), math.cos(r)]])
    return seg @ m.T


def _mirror(seg, deg):
    r = math.radians(2 * deg)
    m = np.array([[math.cos(r), math.sin(r)], [math.sin(r), -math.cos(r)]])
    return seg @ m.T


@settings(max_examples=examples(60), deadline=None)
@given(stars())
def test_n_fold_rotational_symmetry(star):
    seg = star.segments()
    tol = 1e-7 * max(1.0, float(np.abs(seg).max()))
    assert same_set(_rotate(seg, 360 / star.n), seg, tol)


@settings(max_examples=examples(60), deadline=None)
@given(stars())
def test_mirror_symmetry_about_the_first_ray(star):
    seg = star.segments()
    tol = 1e-7 * max(1.0, float(np.abs(seg).max()))
    assert same_set(_mirror(seg, star.rotation), seg, tol)


@settings(max_examples=examples(60), deadline=None)
@given(stars())
def test_count_formula_when_nothing_degenerates(star):
    seg = star.segments()
    formula = star.n * (2 * (len(star.radii) - 1) + 2 * (star.special is not None))
    raw = spec_segments(**star.params())
    assert len(raw) == formula
    lengths = np.linalg.norm(raw[:, 1] - raw[:, 0], axis=1)
    tol = 1e-9 * max(1.0, float(np.abs(raw).max()))
    nondegenerate = raw[lengths > tol]
    assert len(seg) == len(canon(nondegenerate, decimals=5)) or len(seg) <= formula
    if (lengths > tol).all() and len(canon(raw, decimals=5)) == formula:
        assert len(seg) == formula


@settings(max_examples=examples(40), deadline=None)
@given(stars())
def test_extent_is_max_endpoint_radius(star):
    seg = star.segments()
    assert star.extent == pytest.approx(np.hypot(seg[..., 0], seg[..., 1]).max())


# -- bad input ----------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(n=2, radii=(1, 2)), r"n must be an integer >= 3 and <= 120, got 2"),
        (dict(n=MAX_N + 1, radii=(1, 2)), r"n must be an integer >= 3 and <= 120, got 121"),
        (dict(n=8.5, radii=(1, 2)), r"n must be an integer >= 3 and <= 120, got 8.5"),
        (dict(n=True, radii=(1, 2)), r"n must be an integer"),
        (dict(n="8", radii=(1, 2)), r"n must be an integer .* got '8'"),
        (dict(n=8, radii=(1,)), r"radii must hold 2 to 24 numbers, got 1"),
        (dict(n=8, radii=tuple(range(1, MAX_CIRCLES + 2))), r"radii must hold 2 to 24 numbers, got 25"),
        (dict(n=8, radii=5), r"radii must be a sequence of 2 to 24 numbers, got 5"),
        (dict(n=8, radii=(1, 0)), r"radii\[1\] must be a finite number > 0, got 0"),
        (dict(n=8, radii=(1, -3)), r"radii\[1\] must be a finite number > 0, got -3"),
        (dict(n=8, radii=(float("nan"), 2)), r"radii\[0\] must be a finite number > 0, got nan"),
        (dict(n=8, radii=(1, float("inf"))), r"radii\[1\] must be a finite number > 0, got inf"),
        (dict(n=8, radii=(1, 2), alpha=float("nan")), r"alpha must be a finite number, got nan"),
        (dict(n=8, radii=(1, 2), spr=float("-inf")), r"spr must be a finite number, got -inf"),
        (dict(n=8, radii=(1, 2), rotation=float("inf")), r"rotation must be a finite number, got inf"),
        (dict(n=8, radii=(1, 2), special=1), r"special must be an integer >= 2 and <= 2, got 1"),
        (dict(n=8, radii=(1, 2, 3), special=4), r"special must be an integer >= 2 and <= 3, got 4"),
        (dict(n=8, radii=(1, 2), alpha="x"), r"alpha must be a finite number, got 'x'"),
    ],
)
def test_bad_parameters_name_the_parameter_and_range(kwargs, match):
    with pytest.raises(ft.ParameterError, match=match) as info:
        ft.Star(**kwargs)
    assert isinstance(info.value, ValueError) and isinstance(info.value, ft.FabtilesError)


def test_unknown_preset_lists_the_valid_ones():
    with pytest.raises(
        ft.ParameterError,
        match=r"preset 'table4' is unknown; did you mean 'table3-3'\? "
        r"\(presets: table1-part1, ",
    ):
        ft.Star.preset("table4")


def test_integral_float_n_is_accepted():
    assert ft.Star(n=8.0, radii=(1, 2)).n == 8
