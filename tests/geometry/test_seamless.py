"""Seamless tiles: fitted radius/size, and neighbouring tiles continue each other's pattern."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely import affinity

from fabtiles import ParameterError, Star
from fabtiles.geometry.seamless import SeamlessFit, seamless_fit, seamless_radius
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking, SquarePacking

S3 = math.sqrt(3)


def test_rectangle_hex_fit():
    fit = seamless_fit("rectangle", (200, 150), 13)
    assert isinstance(fit, SeamlessFit)
    m, k = fit.repeats
    assert fit.size[0] == 200 and fit.radius == pytest.approx(200 / (2 * m))
    assert fit.size[1] == pytest.approx(2 * S3 * fit.radius * k)
    assert (m, k) == (8, 3)


def test_hexagon_and_square_fits_keep_the_size():
    assert seamless_fit("hexagon", 150, 14) == SeamlessFit(15.0, (150.0, 150.0), (5, 5))
    fit = seamless_fit("square", 100, 7, packing="square")
    assert fit.size == (100.0, 100.0) and fit.radius == pytest.approx(100 / 14)
    assert seamless_radius("hexagon", 150, 14) == 15.0


@given(w=st.floats(20, 500), h=st.floats(20, 500), r=st.floats(1, 40))
@settings(max_examples=examples(60), deadline=None)
def test_fit_is_an_exact_period_nearest_the_radius(w, h, r):
    fit = seamless_fit("rectangle", (w, h), r)
    m, k = fit.repeats
    assert m >= 1 and k >= 1
    assert 2 * fit.radius * m == pytest.approx(w, rel=1e-12)
    assert 2 * S3 * fit.radius * k == pytest.approx(fit.size[1], rel=1e-12)
    # No other whole number of periods gives a radius nearer the one asked for
    # (in periods: m is the nearest integer to w / 2r).
    assert abs(w / (2 * r) - m) <= 0.5 + 1e-9 or m == 1


@pytest.mark.parametrize(
    "args, kwargs, match",
    [
        (("circle", 100, 10), {}, r"a circle outline cannot be seamless"),
        (
            ("square", 100, 10),
            {},
            r"a square tile cannot be seamless with the hex packing .* use outline 'rectangle' or 'hexagon'",
        ),
        (("hexagon", 100, 10), dict(packing="square"), r"a hexagon tile cannot be seamless with the square packing"),
        (
            ("square", 100, 10),
            dict(packing="triangle"),
            r"'triangle' is not a valid packing, must be one of: hex, square",
        ),
        (("oval", 100, 10), {}, r"'oval' is not a valid outline"),
        (("rectangle", (100, 50), 0), {}, r"radius must be a finite number > 0, got 0"),
    ],
)
def test_bad_fits(args, kwargs, match):
    with pytest.raises(ParameterError, match=match):
        seamless_fit(*args, **kwargs)


def _neighbours_continue(tile, steps):
    """For each lattice step t of the tiling, the tile moved by t equals the pattern there.

    The pattern "there" is cut from one big tile of the same packing (lattice origin
    at its centre, too), which holds the centre tile and all its neighbours.
    """
    w, h = tile.width_mm, tile.height_mm
    big = tile.replace(outline="rectangle", size=(3 * w, 3 * h))
    reference = big.region()
    centre = np.array(big.centre) - np.array(tile.centre)  # file offset of the centre tile
    worst = 0.0
    for step in steps:
        dx, dy = centre + np.asarray(step)
        moved = affinity.translate(tile.region(), dx, dy)
        cut = reference.intersection(affinity.translate(tile.outline_shape(), dx, dy))
        worst = max(worst, moved.symmetric_difference(cut).area)
    return worst


def test_seamless_rectangle_neighbours_continue_the_pattern():
    fit = seamless_fit("rectangle", (60, 50), 7)
    pack = HexPacking(radius=fit.radius, motif=Star.preset("table3-2"))
    tile = TileGeometry("rectangle", fit.size, pack, stroke=0.8)
    w, h = fit.size
    steps = [(0, 0), (w, 0), (-w, 0), (0, h), (w, h), (-w, -h)]
    assert _neighbours_continue(tile, steps) < 1e-4


def test_seamless_hexagon_neighbours_continue_the_pattern():
    fit = seamless_fit("hexagon", 60, 7)
    pack = HexPacking(radius=fit.radius, motif=Star.preset("table3-3"), outline_circles=True)
    tile = TileGeometry("hexagon", fit.size, pack, stroke=0.8)
    w = fit.size[0]
    steps = [(w, 0), (w / 2, S3 / 2 * w), (-w / 2, S3 / 2 * w), (-w, 0)]
    assert _neighbours_continue(tile, steps) < 1e-4


def test_seamless_square_with_square_packing():
    fit = seamless_fit("square", 50, 6, packing="square")
    tile = TileGeometry(
        "square", fit.size, SquarePacking(radius=fit.radius, motif=Star.preset("table1-part1")), stroke=0.8
    )
    assert _neighbours_continue(tile, [(50, 0), (0, 50), (50, 50)]) < 1e-4


def test_double_width_tile_is_two_tiles_side_by_side():
    # m even: the wide tile's centre is a lattice point of both halves.
    pack = HexPacking(radius=5, motif=Star.preset("table3-1"))
    narrow = TileGeometry("rectangle", (40, 2 * S3 * 5 * 3), pack, stroke=0.6)  # m = 4, k = 3
    wide = narrow.replace(size=(80, narrow.height_mm))
    both = narrow.region().union(affinity.translate(narrow.region(), 40, 0))
    assert wide.region().symmetric_difference(both).area < 1e-4


def test_a_radius_that_does_not_fit_is_not_seamless():
    pack = HexPacking(radius=7.3, motif=Star.preset("table3-2"))
    tile = TileGeometry("rectangle", (60, 50), pack, stroke=0.8)
    assert _neighbours_continue(tile, [(60, 0)]) > 1.0
