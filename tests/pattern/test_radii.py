import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

import fabtiles as ft


def test_paper_example_radii():
    r = ft.straight_radii(n=8, r1=51, r2=70, count=3)
    assert len(r) == 3 and r[:2] == (51.0, 70.0)
    assert r[2] == pytest.approx(147.3033, abs=1e-3)  # hand-computed intersection


def _collinear(star):
    p = star.points()[:, 0]  # P(1,1) .. P(S,1)
    d = p[1:] - p[0]
    cross = d[:, 0] * d[0, 1] - d[:, 1] * d[0, 0]
    return np.abs(cross).max() / (np.linalg.norm(d, axis=1).max() ** 2)


@settings(max_examples=examples(100), deadline=None)
@given(
    n=st.integers(3, 60),
    r1=st.floats(1, 100),
    ratio=st.floats(1.01, 3),
    count=st.integers(2, 6),
)
def test_first_points_are_collinear(n, r1, ratio, count):
    try:
        radii = ft.straight_radii(n=n, r1=r1, r2=r1 * ratio, count=count)
    except ft.ParameterError as exc:
        assert "cannot be reached" in str(exc)
        assume(False)
    assert len(radii) == count and all(r > 0 for r in radii)
    star = ft.Star(n=n, radii=radii)
    assert _collinear(star) < 1e-9


def test_unreachable_circle_is_named():
    # n = 4: circle 3's ray is at 90 degrees; the line from (1, 0) through P(2,1) heading
    # away from the centre meets it behind the centre.
    with pytest.raises(
        ft.ParameterError,
        match=r"circle 4 cannot be reached: .* only behind the centre; use fewer circles \(count <= 3\)",
    ):
        ft.straight_radii(n=8, r1=51, r2=70, count=4)


def test_parallel_line_is_named():
    # r2 = r1 / cos(step) makes the line perpendicular to the x axis... choose r2 so the
    # line through P(1,1), P(2,1) is parallel to the ray of circle 3 (angle 2*step).
    n, r1 = 6, 10.0
    step = math.pi / n
    # Direction of the ray of circle 3 is (cos 2s, sin 2s); P(2,1) = P(1,1) + t*(cos 2s, sin 2s).
    # Solve r2*(cos s, sin s) = (r1, 0) + t*(cos 2s, sin 2s) for r2.
    m = np.array([[math.cos(step), -math.cos(2 * step)], [math.sin(step), -math.sin(2 * step)]])
    r2, _ = np.linalg.solve(m, [r1, 0])
    with pytest.raises(ft.ParameterError, match=r"circle 3 cannot be reached: .* is parallel to the ray"):
        ft.straight_radii(n=n, r1=r1, r2=r2, count=3)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(n=2, r1=1, r2=2, count=3), r"n must be an integer >= 3"),
        (dict(n=8, r1=0, r2=2, count=3), r"r1 must be a finite number > 0, got 0"),
        (dict(n=8, r1=1, r2=float("nan"), count=3), r"r2 must be a finite number > 0, got nan"),
        (dict(n=8, r1=1, r2=2, count=1), r"count must be an integer >= 2 and <= 24, got 1"),
        (dict(n=8, r1=1, r2=2, count=25), r"count must be an integer >= 2 and <= 24, got 25"),
    ],
)
def test_bad_input(kwargs, match):
    with pytest.raises(ft.ParameterError, match=match):
        ft.straight_radii(**kwargs)
