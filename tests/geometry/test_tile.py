"""Tile: outlines, validation, stroking with joins, frame, clipping (docs/file-conventions.md)."""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely.geometry import Point

from fabtiles import ParameterError, Star
from fabtiles.geometry.tile import TileGeometry, outline_polygon
from fabtiles.pattern.packing import HexPacking, SquarePacking

S3 = math.sqrt(3)
PACK = HexPacking(radius=12.5, motif=Star.preset("table3-3"))


@pytest.fixture(scope="module")
def square_tile():
    return TileGeometry("square", (80, 80), PACK, frame=4, stroke=1.0)


# -- outlines and sizes -----------------------------------------------------------
@pytest.mark.parametrize(
    "outline, size, wh",
    [
        ("square", 100, (100, 100)),
        ("square", (100, 100), (100, 100)),
        ("rectangle", (120, 80), (120, 80)),
        ("hexagon", 90, (90, 180 / S3)),
        ("circle", 70, (70, 70)),
    ],
)
def test_outline_bbox_lower_left_at_origin(outline, size, wh):
    t = TileGeometry(outline, size, PACK, frame=2)
    assert (t.width_mm, t.height_mm) == pytest.approx(wh)
    np.testing.assert_allclose(t.outline_shape().bounds, (0, 0, *wh), atol=1e-9)
    assert t.centre == pytest.approx((wh[0] / 2, wh[1] / 2))


def test_hexagon_is_pointy_top_with_size_across_flats():
    t = TileGeometry("hexagon", 60, PACK)
    coords = np.asarray(t.outline_shape().exterior.coords)[:-1]
    assert len(coords) == 6
    top = coords[np.argmax(coords[:, 1])]
    np.testing.assert_allclose(top, (30, 60 / S3 * 2 / 2 * 2), atol=1e-9)
    assert np.ptp(coords[:, 0]) == pytest.approx(60)  # across flats: vertical sides
    assert t.outline_shape().area == pytest.approx(S3 / 2 * 60**2)


def test_circle_outline_chord_error():
    poly = outline_polygon("circle", 200, 200)
    c = np.asarray(poly.exterior.coords)
    half = np.linalg.norm(np.diff(c, axis=0), axis=1).max() / 2
    assert 100 - math.sqrt(100**2 - half**2) <= 0.005


def test_corner_radius_rounds_the_outline():
    t = TileGeometry("rectangle", (100, 60), PACK, frame=3, corner_radius=10)
    shape = t.outline_shape()
    assert shape.is_valid
    # arcs are flattened with chords of sagitta <= 0.005 mm: a little area is lost
    assert shape.area == pytest.approx(100 * 60 - (4 - math.pi) * 100, abs=0.3)
    assert not shape.contains(Point(1, 1)) and shape.contains(Point(5, 30))
    np.testing.assert_allclose(shape.bounds, (0, 0, 100, 60), atol=1e-9)


# -- validation ---------------------------------------------------------------------
@pytest.mark.parametrize(
    "args, kwargs, match",
    [
        (
            ("triangle", 100),
            {},
            r"'triangle' is not a valid outline, must be one of: square, rectangle, hexagon, circle",
        ),
        (("rectangle", 100), {}, r"size of a rectangle must be a pair \(width, height\) in mm, got 100"),
        (
            ("square", (100, 80)),
            {},
            r"size of a square is one number \(its side\) or an equal pair, got \(100, 80\); use outline 'rectangle'",
        ),
        (("hexagon", (100, 80)), {}, r"size of a hexagon is one number \(its width across flats\)"),
        (("circle", (1, 2, 3)), {}, r"size must be a number or a \(width, height\) pair in mm"),
        (("square", "big"), {}, r"size must be a number or a \(width, height\) pair in mm, got 'big'"),
        (("square", -5), {}, r"size must be a finite number > 0, got -5"),
        (("rectangle", (10, float("inf"))), {}, r"size\[1\] must be a finite number > 0, got inf"),
        (
            ("square", 9),
            dict(frame=5),
            r"tile size \(9, 9\) mm is too small for frame 5 mm: "
            r"the square must be wider than twice the frame \(10 mm\)",
        ),
        (("rectangle", (100, 10)), dict(frame=5), r"too small for frame 5 mm"),
        (("square", 100), dict(frame=-1), r"frame must be a finite number >= 0, got -1"),
        (("square", 100), dict(stroke=0), r"stroke must be a finite number > 0, got 0"),
        (("square", 100), dict(stroke=13), r"stroke must be > 0 and <= 12.5 mm \(the packing radius\), got 13"),
        (("square", 100), dict(join="zigzag"), r"^'zigzag' is not a valid join, must be one of: miter, round, bevel$"),
        (("square", 100), dict(miter_limit=0.5), r"miter_limit must be a finite number >= 1, got 0.5"),
        (("square", 100), dict(corner_radius=-1), r"corner_radius must be a finite number >= 0, got -1"),
        (
            ("square", 100),
            dict(corner_radius=51),
            r"corner_radius must be >= 0 and <= 50 \(half the tile's narrowest width\), got 51",
        ),
        (("circle", 100), dict(corner_radius=2), r"corner_radius must be 0 for a circle outline, got 2"),
    ],
)
def test_bad_tiles(args, kwargs, match):
    with pytest.raises(ParameterError, match=match):
        TileGeometry(*args, PACK, **kwargs)


def test_bad_pattern_and_single_star_stroke():
    with pytest.raises(
        ParameterError,
        match=r"pattern must be a HexPacking, SquarePacking, ArchimedeanPacking, GirihPacking or Star, got str",
    ):
        TileGeometry("square", 100, "table3-3")
    with pytest.raises(ParameterError, match=r"stroke must be > 0 and <= 5 mm \(the motif circle's radius\), got 6"):
        TileGeometry("square", 20, Star.preset("table1-part1"), frame=5, stroke=6)


# -- segments -------------------------------------------------------------------------
def test_lattice_origin_at_tile_centre(square_tile):
    seg = square_tile.segments()
    motif = PACK.placed_motif() + np.array(square_tile.centre)
    keys = {tuple(np.round(s.ravel(), 6)) for s in seg}
    assert all(tuple(np.round(m.ravel(), 6)) in keys for m in motif)


def test_segments_cover_the_outline(square_tile):
    seg = square_tile.segments()
    pts = seg.reshape(-1, 2)
    assert pts[:, 0].min() < 0 and pts[:, 1].min() < 0
    assert pts[:, 0].max() > 80 and pts[:, 1].max() > 80


@pytest.mark.parametrize(
    "outline, size, frame, radius",
    [("square", 100, 5, 45), ("rectangle", (100, 60), 2, 28), ("hexagon", 80, 0, 40), ("circle", 50, 1, 24)],
)
def test_single_star_fills_the_circle_inside_the_frame(outline, size, frame, radius):
    star = Star.preset("table2-left")
    t = TileGeometry(outline, size, star, frame=frame)
    pts = t.segments().reshape(-1, 2) - t.centre
    assert np.hypot(*pts.T).max() == pytest.approx(radius)
    np.testing.assert_allclose(t.segments() - t.centre, star.segments() * (radius / star.extent), atol=1e-9)


# -- region ---------------------------------------------------------------------------
def test_region_is_valid_inside_the_outline_and_cached(square_tile):
    region = square_tile.region()
    assert region.is_valid and not region.is_empty
    assert region.difference(square_tile.outline_shape()).area < 1e-9
    assert square_tile.region() is region


def test_region_covers_every_centreline(square_tile):
    region = square_tile.region()
    inner = square_tile.outline_shape().buffer(-square_tile.stroke)
    lines = shapely.intersection(shapely.linestrings(square_tile.segments()), inner)
    assert region.buffer(1e-6).contains(shapely.union_all(lines))
    # and the bands themselves (flat caps, a hair thinner than the stroke)
    bands = shapely.buffer(lines, 0.5 * 0.999, cap_style="flat")
    assert shapely.union_all(bands).difference(region).area < 1e-6


def test_region_stays_within_the_miter_reach(square_tile):
    reach = square_tile.segments()
    limit = square_tile.miter_limit * square_tile.stroke / 2
    bound = shapely.union_all(shapely.buffer(shapely.linestrings(reach), limit)).union(
        square_tile.outline_shape().difference(square_tile.inner_shape())
    )
    assert square_tile.region().difference(bound).area < 1e-9


def test_frame_is_kept(square_tile):
    ring = square_tile.outline_shape().difference(square_tile.inner_shape())
    assert ring.area == pytest.approx(80 * 80 - 72 * 72)
    assert square_tile.region().buffer(1e-6).contains(ring)


def test_round_join_equals_the_geos_round_buffer():
    # Round joins and round caps make the region the Minkowski sum of the segments
    # and a disc: exactly what a GEOS round buffer gives (up to arc flattening).
    t = TileGeometry("square", 50, SquarePacking(radius=8, motif=Star.preset("table1-part1")), stroke=1.2, join="round")
    ref = shapely.union_all(shapely.buffer(shapely.linestrings(t.segments()), 0.6, quad_segs=32))
    ref = ref.intersection(t.outline_shape())
    region = t.region()
    assert region.is_valid
    # equal within the arc flattening tolerance (0.005 mm): nested both ways
    assert region.difference(ref.buffer(1e-3)).area < 1e-6
    assert ref.buffer(-0.006).difference(region).area < 1e-6
    assert region.area == pytest.approx(ref.area, rel=1e-3)


def test_joins_nest_bevel_in_round_in_miter():
    base = TileGeometry("square", 60, HexPacking(radius=10, motif=Star.preset("table3-1")), stroke=1.0)
    bevel, rnd, miter = (base.replace(join=j).region() for j in ("bevel", "round", "miter"))
    assert bevel.difference(rnd.buffer(1e-6)).area < 1e-9
    assert rnd.difference(miter.buffer(1e-3)).area < 1e-6
    assert bevel.area < rnd.area < miter.area


def _tips(tile):
    """Outer tip vertices of a single table1-part1 star and their outward unit rays."""
    pts = tile.segments().reshape(-1, 2) - tile.centre
    r = np.hypot(*pts.T)
    tips = np.unique(np.round(pts[r > r.max() - 1e-9], 9), axis=0)
    return tips + tile.centre, tips / np.hypot(*tips.T)[:, None]


@pytest.mark.parametrize("miter_limit, reach", [(4.0, 4.0), (10.0, 1 / math.sin(math.radians(14.014)))])
def test_miter_keeps_star_tips_sharp(miter_limit, reach):
    # Rotated 22.5 degrees so no tip touches the square's sides; frame 0.
    star = Star.preset("table1-part1", rotation=22.5)
    tile = TileGeometry("square", 100, star, stroke=1.0, miter_limit=miter_limit)
    h = tile.stroke / 2
    tips, rays = _tips(tile)
    assert len(tips) == 8
    others = {j: tile.replace(join=j).region() for j in ("bevel", "round")}
    for tip, ray in zip(tips, rays, strict=True):
        assert tile.region().contains(Point(tip + 0.97 * reach * h * ray))
        assert not tile.region().contains(Point(tip + 1.03 * reach * h * ray))
        assert tile.region().contains(Point(tip + 2 * h * ray))
        for join, region in others.items():
            assert not region.contains(Point(tip + 2 * h * ray)), join
    # Round joins reach h past the tip, bevels less.
    tip, ray = tips[0], rays[0]
    assert others["round"].contains(Point(tip + 0.95 * h * ray))
    assert not others["bevel"].contains(Point(tip + 0.5 * h * ray))


def test_centrelines_are_clipped_to_the_outline():
    t = TileGeometry("hexagon", 70, PACK, frame=3, stroke=0.8)
    cl = t.centrelines()
    assert cl.ndim == 3 and cl.shape[1:] == (2, 2)
    assert (np.linalg.norm(cl[:, 1] - cl[:, 0], axis=1) > 0).all()
    grown = t.outline_shape().buffer(1e-6)
    assert grown.contains(shapely.multilinestrings(cl))
    # Same total length as clipping with shapely directly (duplicates removed).
    ref = shapely.union_all(shapely.intersection(shapely.linestrings(t.segments()), t.outline_shape()))
    assert shapely.multilinestrings(cl).length == pytest.approx(ref.length, rel=1e-9)


@given(
    outline=st.sampled_from(["square", "hexagon", "circle"]),
    size=st.floats(30, 90),
    frame=st.floats(0, 6),
    stroke=st.floats(0.3, 2.0),
    join=st.sampled_from(["miter", "round", "bevel"]),
    motif=st.sampled_from(Star.presets()),
)
@settings(max_examples=examples(12), deadline=None)
def test_region_is_always_valid_and_contained(outline, size, frame, stroke, join, motif):
    t = TileGeometry(
        outline, size, HexPacking(radius=9, motif=Star.preset(motif)), frame=frame, stroke=stroke, join=join
    )
    region = t.region()
    assert region.is_valid
    # Clipper works on a fine integer grid: the region may stick out by ~1e-7 mm
    assert region.difference(t.outline_shape()).area < 1e-6 * t.outline_shape().length
    if frame > 0:
        ring = t.outline_shape().difference(t.inner_shape())
        assert ring.difference(region).area < 1e-6


def test_subclass_friendly():
    class ExportingTile(TileGeometry):
        def export(self, path):
            return path

    t = ExportingTile("square", 40, PACK, stroke=0.5)
    assert isinstance(t.replace(stroke=0.6), ExportingTile)
    t.note = "attributes can be added"
    assert t.export("x.svg") == "x.svg"
    assert repr(t).startswith("ExportingTile('square', (40, 40), HexPacking(")


def test_sheet_region_is_one_valid_piece():
    """The 600 x 400 mm sheet (timings: benchmarks/run.py): valid, and one piece.

    Regression: join polygons that only touched their bands along the butt-end line
    came back from Clipper2 as hundreds of loose specks.
    """
    pack = HexPacking(radius=15, motif=Star.preset("table3-3"))
    t = TileGeometry("rectangle", (600, 400), pack, frame=5, stroke=1.0)
    region = t.region()
    assert region.is_valid
    assert region.geom_type == "Polygon"
    assert len(region.interiors) > 5_000
