"""Seamless tiles of the 11 Archimedean tilings: fitted edge/size, neighbours continue the pattern."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely import affinity

from fabtiles import ArchimedeanPacking, ParameterError
from fabtiles.geometry.seamless import seamless_fit
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.archimedean import rectangular_period
from fabtiles.pattern.tilings import TILINGS

SQUARE = ("4.4.4.4", "4.8.8", "3.3.4.3.4")
HEXAGON = ("3.3.3.3.3.3", "6.6.6", "3.6.3.6", "3.12.12", "4.6.12", "3.3.3.3.6", "3.4.6.4")


def neighbours_continue(tile, steps):
    """Largest area where the tile moved by a step differs from a bigger tile, centred on it, cut there.

    The bigger tile is the smallest rectangle about the tile's centre that holds every moved copy (with a
    hair's margin): its pattern is the same, and the cost of its region grows with its area.
    """
    w, h = tile.width_mm, tile.height_mm
    reach = np.abs(np.asarray(steps, dtype=float)).max(axis=0)
    big = tile.replace(outline="rectangle", size=(2 * reach[0] + w + 0.02, 2 * reach[1] + h + 0.02))
    reference = big.region()
    centre = np.array(big.centre) - np.array(tile.centre)
    worst = 0.0
    for step in steps:
        dx, dy = centre + np.asarray(step)
        outline = affinity.translate(tile.outline_shape(), dx, dy)
        assert big.outline_shape().contains(outline)
        moved = affinity.translate(tile.region(), dx, dy)
        cut = reference.intersection(outline)
        worst = max(worst, moved.symmetric_difference(cut).area)
    return worst


@pytest.mark.parametrize("tiling", TILINGS)
def test_rectangle_fit_of_every_tiling(tiling):
    # 40 x 30 mm is large enough: a window grown by half the stroke alone (missing the miter tips of
    # motifs just outside) leaves specks on the 3.3.3.3.6 and 3.3.4.3.4 tiles here as on larger ones
    fit = seamless_fit("rectangle", (40, 30), 6, packing=tiling)
    px, py = rectangular_period(tiling)
    m, k = fit.repeats
    assert fit.size[0] == 40 and px * fit.edge * m == pytest.approx(40)
    assert fit.size[1] == pytest.approx(py * fit.edge * k)
    assert abs(40 / (px * 6) - m) <= 0.5 + 1e-9 or m == 1
    pack = ArchimedeanPacking(tiling, fit.edge)
    tile = TileGeometry("rectangle", fit.size, pack, stroke=0.5)
    w, h = fit.size
    assert neighbours_continue(tile, [(w, 0), (0, h), (-w, h)]) < 1e-4


@pytest.mark.parametrize(("tiling", "gap"), [("4.8.8", 0.0), ("3.4.6.4", 0.8), ("3.3.3.3.6", 0.0)])
def test_hankin_seamless_rectangle_continues(tiling, gap):
    """Hankin's rays (method "hankin") repeat with the tiling as the motifs do."""
    fit = seamless_fit("rectangle", (60, 45), 6, packing=tiling)
    pack = ArchimedeanPacking(tiling, fit.edge, method="hankin", contact_angle=55, contact_gap=gap)
    tile = TileGeometry("rectangle", fit.size, pack, stroke=0.5)
    w, h = fit.size
    assert neighbours_continue(tile, [(w, 0), (0, h), (-w, h)]) < 1e-4


@pytest.mark.parametrize("tiling", SQUARE)
def test_square_fit(tiling):
    fit = seamless_fit("square", 50, 7, packing=tiling)
    assert fit.size == (50.0, 50.0) and fit.repeats[0] == fit.repeats[1]
    tile = TileGeometry("square", 50, ArchimedeanPacking(tiling, fit.edge), stroke=0.5)
    assert neighbours_continue(tile, [(50, 0), (0, 50), (50, 50)]) < 1e-4


@pytest.mark.parametrize("tiling", HEXAGON)
def test_hexagon_fit(tiling):
    # 40 mm holds two to eight periods of each tiling across: seamlessness is the period's, not the count's
    fit = seamless_fit("hexagon", 40, 5, packing=tiling)
    w = fit.size[0]
    assert fit.repeats[0] >= 2
    assert w == 40 and rectangular_period(tiling)[0] * fit.edge * fit.repeats[0] == pytest.approx(40)
    tile = TileGeometry("hexagon", 40, ArchimedeanPacking(tiling, fit.edge, outline_circles=True), stroke=0.5)
    s3 = math.sqrt(3)
    assert neighbours_continue(tile, [(w, 0), (w / 2, s3 / 2 * w), (-w / 2, s3 / 2 * w)]) < 1e-4


@pytest.mark.parametrize("tiling", sorted(set(TILINGS) - set(SQUARE)))
def test_square_refused_where_periods_are_incommensurable(tiling):
    with pytest.raises(ParameterError, match=rf"a square tile cannot be seamless with the tiling {tiling}"):
        seamless_fit("square", 100, 10, packing=tiling)


@pytest.mark.parametrize("tiling", sorted(set(TILINGS) - set(HEXAGON)))
def test_hexagon_refused_off_triangular_lattices(tiling):
    with pytest.raises(ParameterError, match=rf"a hexagon tile cannot be seamless with the tiling {tiling}"):
        seamless_fit("hexagon", 100, 10, packing=tiling)


def test_bad_tiling_fits():
    with pytest.raises(ParameterError, match=r"a circle outline cannot be seamless"):
        seamless_fit("circle", 100, 10, packing="4.8.8")
    with pytest.raises(ParameterError, match=r"tiling '5.5.5' is unknown \(tilings: "):
        seamless_fit("rectangle", (100, 80), 10, packing="5.5.5")
    with pytest.raises(ParameterError, match=r"edge must be a finite number > 0, got -1"):
        seamless_fit("rectangle", (100, 80), -1, packing="3^6")
    with pytest.raises(ParameterError, match=r"None is not a valid packing, must be one of: hex, square"):
        seamless_fit("rectangle", (100, 80), 10, packing=None)


@given(tiling=st.sampled_from(TILINGS), w=st.floats(20, 500), h=st.floats(20, 500), edge=st.floats(1, 40))
@settings(max_examples=examples(60), deadline=None)
def test_fit_is_an_exact_period_nearest_the_edge(tiling, w, h, edge):
    fit = seamless_fit("rectangle", (w, h), edge, packing=tiling)
    px, py = rectangular_period(tiling)
    m, k = fit.repeats
    assert m >= 1 and k >= 1 and fit.size[0] == w
    assert px * fit.edge * m == pytest.approx(w, rel=1e-12)
    assert py * fit.edge * k == pytest.approx(fit.size[1], rel=1e-12)
    assert abs(w / (px * edge) - m) <= 0.5 + 1e-9 or m == 1
    assert abs(h / (py * fit.edge) - k) <= 0.5 + 1e-9 or k == 1
