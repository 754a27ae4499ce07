"""The laser job estimate (fabtiles.geometry.job_time) on small jobs, against hand-computed figures.

Every expectation below is worked out by hand from the formula in the module's text:
cut time ``length / speed * passes``, a pierce per path per pass, travel from (0, 0) through
the cut order once per pass at ``travel_mm_s``, an engrave fill's swept lines at its speed.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fabtiles.geometry.job_time import JobEstimate, estimate, path_lengths, total, travel_mm
from fabtiles.machines.profiles import CutterProfile, LaserLayers, Layer


def profile(*, inner=(10.0, 1), outer=(5.0, 1), score=(20.0, 1), engrave=None, pierce_s=0.5, travel_mm_s=100.0):
    """A laser profile whose layers run at ``(speed_mm_s, passes)``; ``engrave`` is ``(speed, passes, interval)``."""
    fill = (
        None
        if engrave is None
        else Layer("FILL", 6, speed_mm_s=engrave[0], passes=engrave[1], line_interval_mm=engrave[2])
    )
    layers = LaserLayers(
        inner_cut=Layer("INNER", 1, speed_mm_s=inner[0], passes=inner[1]),
        outer_cut=Layer("OUTER", 1, speed_mm_s=outer[0], passes=outer[1]),
        score=Layer("SCORE", 5, speed_mm_s=score[0], passes=score[1]),
        engrave=fill,
    )
    return CutterProfile("test", pierce_s=pierce_s, travel_mm_s=travel_mm_s, layers=layers)


def square(x, y, side=10.0):
    """A closed ring (its last point not repeated), first point at ``(x, y)``."""
    return np.array([[x, y], [x + side, y], [x + side, y + side], [x, y + side]], float)


def test_one_inner_square():
    job = estimate(profile(), inner=[square(20, 20)])
    assert job.cut_mm == {"inner_cut": pytest.approx(40.0)}
    assert job.pierces == 1 and job.engrave_area_mm2 == 0.0
    assert job.travel_mm == pytest.approx(20 * math.sqrt(2))  # (0, 0) to (20, 20)
    # 40 mm at 10 mm/s, one pierce of 0.5 s, the travel at 100 mm/s
    assert job.seconds == pytest.approx(4.0 + 0.5 + 20 * math.sqrt(2) / 100)


def test_passes_repeat_the_cut_and_the_pierce_but_count_one_pierce():
    job = estimate(profile(inner=(10.0, 3)), inner=[square(20, 20)])
    assert job.cut_mm == {"inner_cut": pytest.approx(40.0)}  # the path's length, not the laser's
    assert job.pierces == 1
    # Each pass starts where the closed ring ended, its own first point: no travel between passes.
    assert job.travel_mm == pytest.approx(20 * math.sqrt(2))
    assert job.seconds == pytest.approx(3 * 4.0 + 3 * 0.5 + 20 * math.sqrt(2) / 100)


def test_inner_cuts_then_outer_cut_in_the_given_order():
    inner = [square(10, 0), square(10, 30)]
    outer = [square(40, 0, side=50)]
    job = estimate(profile(), outer=outer, inner=inner)  # keyword order does not matter: inner cuts first
    assert job.cut_mm == {"inner_cut": pytest.approx(80.0), "outer_cut": pytest.approx(200.0)}
    assert job.cut_total_mm == pytest.approx(280.0)
    assert job.pierces == 3
    # (0, 0) -> (10, 0) -> (10, 30) -> (40, 0): 10 + 30 + 30 sqrt 2
    travel = 10 + 30 + 30 * math.sqrt(2)
    assert job.travel_mm == pytest.approx(travel)
    assert job.seconds == pytest.approx(80 / 10 + 2 * 0.5 + 200 / 5 + 0.5 + travel / 100)


def test_open_score_paths_end_at_their_last_point():
    score = [np.array([[0, 0], [3, 4]], float), np.array([[10, 0], [10, 5]], float)]
    job = estimate(profile(score=(20.0, 2)), score=score)
    assert job.cut_mm == {"score": pytest.approx(10.0)}  # 5 + 5: open paths are not closed
    assert job.pierces == 2
    # Pass 1: (0, 0) -> (0, 0), then (3, 4) -> (10, 0); pass 2 from (10, 5) back to (0, 0), then again.
    travel = 0 + math.sqrt(65) + math.sqrt(125) + math.sqrt(65)
    assert job.travel_mm == pytest.approx(travel)
    assert job.seconds == pytest.approx(10 / 20 * 2 + 2 * 2 * 0.5 + travel / 100)


def test_engrave_is_its_swept_lines_without_pierces():
    p = profile(engrave=(250.0, 2, 0.1))
    job = estimate(p, engrave=[square(0, 0)], engrave_area_mm2=100.0)
    assert job.cut_mm == {} and job.pierces == 0
    assert job.engrave_area_mm2 == 100.0
    assert job.travel_mm == 0.0  # the outline starts at the origin and each pass ends there
    # 100 mm^2 in lines 0.1 mm apart is 1000 mm of line, at 250 mm/s, twice
    assert job.seconds == pytest.approx(1000 / 250 * 2)


def test_the_cut_order_is_engrave_score_inner_outer():
    p = profile(engrave=(250.0, 1, 0.5))
    job = estimate(
        p,
        outer=[square(0, 40)],
        inner=[square(30, 0)],
        score=[np.array([[0, 20], [5, 20]], float)],
        engrave=[square(0, 10)],
        engrave_area_mm2=50.0,
    )
    assert job.cut_mm == {
        "score": pytest.approx(5.0),
        "inner_cut": pytest.approx(40.0),
        "outer_cut": pytest.approx(40.0),
    }
    assert job.pierces == 3 and job.engrave_area_mm2 == 50.0
    # (0, 0) -> engrave (0, 10) -> score (0, 20), ends (5, 20) -> inner (30, 0) -> outer (0, 40)
    travel = 10 + 10 + math.hypot(25, 20) + math.hypot(30, 40)
    assert job.travel_mm == pytest.approx(travel)
    seconds = 50 / 0.5 / 250 + 5 / 20 + 0.5 + 40 / 10 + 0.5 + 40 / 5 + 0.5 + travel / 100
    assert job.seconds == pytest.approx(seconds)


@pytest.mark.parametrize("passes", [1, 3])
@pytest.mark.parametrize("outer_closed", [True, False])
def test_travel_alone_is_the_estimates_travel(passes, outer_closed):
    """The cut plan measures the travel before its cut order with travel_mm, not a whole estimate."""
    p = profile(engrave=(250.0, 1, 0.5), inner=(10.0, passes))
    rng = np.random.default_rng(passes)
    paths = dict(
        outer=[square(*rng.uniform(0, 90, 2)) for _ in range(3)],
        inner=[square(*rng.uniform(0, 90, 2), side=2) for _ in range(5)],
        score=[rng.uniform(0, 90, (3, 2))],
        engrave=[square(0, 10)],
    )
    job = estimate(p, **paths, engrave_area_mm2=50.0, outer_closed=outer_closed)
    assert travel_mm(p, **paths, outer_closed=outer_closed) == pytest.approx(job.travel_mm, rel=1e-12)
    assert job.travel_mm > 0


def test_no_engrave_layer_or_no_engrave_paths_cost_nothing():
    # The profile has no engrave layer (the cut plan refuses engraving with it): the rings cost no
    # time and no travel; the area stays reported as given.
    assert estimate(profile(), engrave=[square(5, 5)], engrave_area_mm2=100.0) == JobEstimate({}, 0, 100.0, 0.0, 0.0)
    # An area without the rings that fill it is no engraving either.
    p = profile(engrave=(250.0, 1, 0.1))
    assert estimate(p, engrave_area_mm2=100.0) == JobEstimate({}, 0, 0.0, 0.0, 0.0)


def test_an_empty_job():
    job = estimate(profile())
    assert job == JobEstimate({}, 0, 0.0, 0.0, 0.0)
    assert job.line() == "0 m of cut, 0 pierces, about 1 min"


def test_the_report_entry_rounds_the_figures():
    job = estimate(profile(), inner=[square(20, 20)])
    stats = job.as_stats()
    assert stats == {
        "cut_mm": {"inner_cut": 40.0},
        "cut_total_mm": 40.0,
        "pierces": 1,
        "engrave_area_mm2": 0.0,
        "travel_mm": round(20 * math.sqrt(2), 3),
        "seconds": 4.8,
        "line": "0.04 m of cut, 1 pierce, about 1 min",
    }


def test_path_lengths_of_open_and_closed_paths():
    paths = [np.array([[0, 0], [3, 0], [3, 4]], float), square(0, 0, side=2)]
    assert path_lengths(paths, closed=False).tolist() == pytest.approx([7.0, 6.0])
    assert path_lengths(paths, closed=True).tolist() == pytest.approx([12.0, 8.0])
    assert path_lengths([], closed=True).tolist() == []


def test_total_sums_every_figure():
    a = estimate(profile(), inner=[square(20, 20)])
    b = estimate(profile(), outer=[square(0, 0)], score=[np.array([[0, 0], [0, 7]], float)])
    both = total([a, b])
    assert both.cut_mm == {
        "inner_cut": pytest.approx(40.0),
        "outer_cut": pytest.approx(40.0),
        "score": pytest.approx(7.0),
    }
    assert both.pierces == 3
    assert both.travel_mm == pytest.approx(a.travel_mm + b.travel_mm)
    assert both.seconds == pytest.approx(a.seconds + b.seconds)
