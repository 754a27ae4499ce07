"""A tile's border: the frieze inside its band, a whole number of cells a side, symmetric corners,
continuous strands, the field inside the band, and the refusals."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from fabtiles.core.errors import ParameterError
from fabtiles.geometry.border import border_fit, opening_ratio
from fabtiles.geometry.tile import TOLERANCE, TileGeometry
from fabtiles.pattern.frieze import frieze_cell
from fabtiles.pattern.packing import HexPacking, SquarePacking
from fabtiles.pattern.star import Star

PACKING = HexPacking(radius=8, motif=Star.preset("table3-3"))
OUTLINES = [("square", 80), ("rectangle", (90, 70)), ("hexagon", 80), ("circle", 80)]
MOTIFS = ("stars", "hankin")


def _tile(outline="square", size=80, motif="stars", **kw):
    kw = {"frame": 2, "stroke": 0.8, "border_mm": 10, **kw}
    return TileGeometry(outline, size, PACKING, border_motif=motif, **kw)


def _band(tile):
    return tile.inner_shape().difference(tile.field_shape())


@pytest.mark.parametrize(("outline", "size"), OUTLINES)
@pytest.mark.parametrize("motif", MOTIFS)
def test_the_frieze_lies_in_the_band(outline, size, motif):
    tile = _tile(outline, size, motif)
    frieze = shapely.multilinestrings(tile.border().frieze())
    # within the chord tolerance of a circle's polygon (the sectors' points lie on the true circles)
    assert _band(tile).buffer(TOLERANCE + 1e-6).contains(frieze)
    region = tile.region()
    assert region.is_valid and region.area > 0


@pytest.mark.parametrize(("outline", "size"), OUTLINES)
def test_the_field_lies_inside_the_band(outline, size):
    tile = _tile(outline, size)
    field = shapely.multilinestrings(tile.segments())
    # the field's lines, the frieze and the line between them: none leaves the band or the field
    assert tile.inner_shape().buffer(TOLERANCE + 1e-6).contains(field)
    woven = tile.motif_segments()
    field_only = woven[: len(woven) - len(tile.border().frieze())]
    assert tile.field_shape().buffer(1e-6).contains(shapely.multilinestrings(field_only))
    # the field's material stops at the band's inner line: another field leaves the band's alone
    other = tile.replace(pattern=SquarePacking(radius=6, motif=Star.preset("table3-1")))
    core = _band(tile).difference(tile.field_shape().buffer(tile.stroke / 2 + 1e-3))
    assert other.region().intersection(core).symmetric_difference(tile.region().intersection(core)).area < 1e-4


@pytest.mark.parametrize(
    ("outline", "size", "frame", "band"),
    [("square", 80, 2, 10), ("rectangle", (100, 70), 3, 12), ("rectangle", (61, 97), 0, 9.5)],
)
def test_a_rectangle_has_whole_cells_that_fill_each_side(outline, size, frame, band):
    w, h = (size, size) if outline == "square" else size
    fit = border_fit(outline, (float(w), float(h)), band, frame=frame)
    for n, cell, side in zip(fit.repeats, fit.cell_mm, (w - 2 * frame, h - 2 * frame), strict=True):
        assert isinstance(n, int) and n >= 1
        assert n * cell + 2 * band == pytest.approx(side, abs=1e-9)
        # as near square as a whole number allows: one cell more or fewer is farther from the band
        assert abs(cell - band) <= abs((side - 2 * band) / (n + 1) - band) + 1e-12
        if n > 1:
            assert abs(cell - band) <= abs((side - 2 * band) / (n - 1) - band) + 1e-12
    tile = TileGeometry(outline, size, PACKING, frame=frame, stroke=0.8, border_mm=band)
    cells = tile.border().cells()
    assert len(cells) == 4 + 2 * sum(fit.repeats)
    assert sum(shapely.Polygon(c).area for c in cells) == pytest.approx(_band(tile).area, rel=1e-9)


@pytest.mark.parametrize(("outline", "size"), [("hexagon", 80), ("circle", 80)])
def test_hexagon_and_circle_cells_tile_the_band(outline, size):
    tile = _tile(outline, size)
    fit = tile.border().fit
    n = fit.repeats[0]
    assert n * fit.cell_mm[0] == pytest.approx(fit.side_mm[0])
    cells = [shapely.Polygon(c) for c in tile.border().cells()]
    assert len(cells) == (6 * n if outline == "hexagon" else n)
    if outline == "hexagon":  # the cells' quads fill the band exactly
        assert sum(c.area for c in cells) == pytest.approx(_band(tile).area, rel=1e-9)
        assert shapely.union_all(cells).symmetric_difference(_band(tile)).area < 1e-6


def test_the_fit_is_reported():
    assert border_fit("rectangle", (100.0, 80.0), 12.0, frame=3.0).line("stars") == (
        "tile.border_mm: 6 x 4 repeats of 11.67 x 12.5 mm, a 12 mm square cell at each corner (band 12 mm, stars)"
    )
    assert (
        border_fit("hexagon", (80.0, 80.0), 10.0)
        .line("hankin", 67.5)
        .startswith("tile.border_mm: 6 sides x 4 repeats of ")
    )
    assert "repeats of" in border_fit("circle", (80.0, 80.0), 10.0).line("stars")


def _mirror(seg, p, d):
    """``seg`` reflected in the line through ``p`` along the unit vector ``d``."""
    q = seg - p
    along = (q @ d)[..., None] * d
    return p + 2 * along - q


def _same_sets(a, b, tol=1e-6):
    """Every segment of ``a`` is one of ``b`` (either way round) within ``tol``, and back."""

    def key(s):
        s = np.round(np.asarray(s) / tol).astype(np.int64)
        return {tuple(sorted(map(tuple, x))) for x in s}

    # compare rounded both ways: a tolerance grid, then the nearest match for the few on its lines
    ka, kb = key(a), key(b)
    if ka == kb:
        return True
    from scipy.spatial import cKDTree

    def flat(s):
        s = np.asarray(s)
        return np.concatenate([s.reshape(-1, 4), s[:, ::-1].reshape(-1, 4)])

    ta = cKDTree(flat(a))
    return bool(ta.query(np.asarray(b).reshape(-1, 4))[0].max() < 10 * tol) and bool(
        cKDTree(flat(b)).query(np.asarray(a).reshape(-1, 4))[0].max() < 10 * tol
    )


@pytest.mark.parametrize(("outline", "size"), [("square", 80), ("hexagon", 80)])
@pytest.mark.parametrize("motif", MOTIFS)
def test_the_frieze_is_symmetric_about_each_corners_bisector(outline, size, motif):
    tile = _tile(outline, size, motif)
    frieze = tile.border().frieze()
    centre = np.array(tile.centre)
    corners = np.asarray(tile.inner_shape().exterior.coords)[:-1]
    for corner in corners:
        d = (corner - centre) / np.linalg.norm(corner - centre)
        assert _same_sets(_mirror(frieze, centre, d), frieze)


def test_a_rectangles_corner_cells_are_symmetric_about_their_bisectors():
    tile = _tile("rectangle", (90, 70))
    frieze = tile.border().frieze()
    b = tile.border_mm
    for cell in tile.border().cells()[:4]:  # the four corner cells come first
        box = shapely.Polygon(cell)
        inside = frieze[shapely.contains(box.buffer(1e-9), shapely.linestrings(frieze))]
        c = np.array(box.centroid.coords[0])
        for d in (np.array([1.0, 1.0]) / math.sqrt(2), np.array([1.0, -1.0]) / math.sqrt(2)):
            assert _same_sets(_mirror(inside, c, d), inside)
        assert box.area == pytest.approx(b * b)


@pytest.mark.parametrize(("outline", "size"), OUTLINES)
@pytest.mark.parametrize("motif", MOTIFS)
def test_the_strands_run_on_from_cell_to_cell(outline, size, motif):
    """Every end of the frieze's lines meets another line's end or lies on the band's edges."""
    tile = _tile(outline, size, motif)
    frieze = tile.border().frieze()
    ends = frieze.reshape(-1, 2)
    keys, counts = np.unique(np.round(ends, 6), axis=0, return_counts=True)
    free = keys[counts == 1]
    edges = shapely.MultiLineString([tile.inner_shape().exterior, tile.field_shape().exterior])
    assert len(free) == 0 or shapely.distance(shapely.points(free), edges).max() < 0.01


@pytest.mark.parametrize("motif", MOTIFS)
def test_the_unit_cells_strands_end_in_mirrored_pairs_on_its_edges(motif):
    seg = frieze_cell(motif)
    ends = seg.reshape(-1, 2)
    on_side = ends[np.isclose(np.abs(ends[:, 0]), 1)]
    assert {tuple(p) for p in np.round(on_side * [-1, 1], 9)} == {tuple(p) for p in np.round(on_side, 9)}


@pytest.mark.parametrize(("outline", "size"), OUTLINES)
@pytest.mark.parametrize("motif", MOTIFS)
def test_the_frieze_and_the_field_weave_and_end_on_the_line_between_them(outline, size, motif):
    from fabtiles.geometry.interlace import tile_drawing, tile_score_lines

    tile = _tile(outline, size, motif, stroke=1, interlace=True)
    ring = tile.border_segments()[len(tile.border().frieze()) :]
    woven = tile.motif_segments()
    # the line, and the field's stubs that end on it, are scored whole, not woven
    rest = tile.segments()[len(woven) :]
    assert len(rest) >= len(ring) and np.allclose(rest[len(rest) - len(ring) :], ring)
    weave = tile.weave()
    assert len(weave.sin) > 50 and weave.sin.min() > 0.1 and weave.conflicts == 0
    drawing = tile_drawing(tile)
    assert drawing.is_valid and drawing.area < tile.region().area
    assert len(tile_score_lines(tile)) > len(ring)


def test_a_single_motif_shrinks_inside_the_border():
    star = Star.preset("table3-3")
    tile = TileGeometry("square", 80, star, frame=2, stroke=0.8, border_mm=10)
    assert tile.motif_radius == pytest.approx(28)
    assert tile.region().is_valid


def test_no_border_is_the_tile_as_before():
    a = TileGeometry("square", 60, PACKING, frame=2, stroke=0.8)
    assert a.border() is None and len(a.border_segments()) == 0
    assert a.field_shape().equals(a.inner_shape())


# -- refusals ---------------------------------------------------------------------------------------
def test_a_border_wider_than_a_third_is_refused():
    with pytest.raises(ParameterError, match=r"border_mm must be >= 0 and <= 25\.33 mm .* got 26") as e:
        _tile(border_mm=26)
    assert e.value.param == "border_mm"


def test_a_border_too_narrow_for_the_stroke_names_the_minimum():
    with pytest.raises(ParameterError, match=r"border_mm must be >= (\S+) mm at this stroke") as e:
        _tile(border_mm=3, stroke=0.8)
    low = float(re.search(r">= (\S+) mm", str(e.value)).group(1))
    need = 0.8 / (2 * opening_ratio("stars", 67.5))
    assert low >= need - 0.01
    _tile(border_mm=math.ceil(low * 100) / 100 + 0.01, stroke=0.8)  # the minimum named builds


def test_no_band_fits_at_a_stroke_too_wide():
    with pytest.raises(ParameterError, match=r"no band up to .* is wide enough; make the stroke <="):
        TileGeometry("square", 30, PACKING, stroke=4, border_mm=5)


def test_an_unknown_motif_and_a_bad_angle_are_refused():
    with pytest.raises(ParameterError, match=r"border_motif = 'star' is not valid \(did you mean 'stars'\?\)"):
        _tile(motif="star")
    with pytest.raises(ParameterError, match="border_angle"):
        _tile(motif="hankin", border_angle=90)


def test_rounded_corners_inside_the_frame_are_refused_with_a_border():
    with pytest.raises(ParameterError, match=r"corner_radius must be <= the frame \(2 mm\) with a border"):
        _tile(corner_radius=5)
    assert _tile(corner_radius=2).region().is_valid


@settings(max_examples=200, deadline=None)
@given(
    outline=st.sampled_from(["square", "rectangle", "hexagon", "circle"]),
    width=st.floats(30, 600),
    height=st.floats(30, 600),
    frame=st.floats(0, 10),
    share=st.floats(0.01, 1.0),
)
def test_every_side_holds_whole_near_square_cells(outline, width, height, frame, share):
    height = height if outline == "rectangle" else width
    inside = min(width, height) - 2 * frame
    band = share * inside / 3
    fit = border_fit(outline, (width, height), band, frame=frame)
    for n, cell, side in zip(fit.repeats, fit.cell_mm, fit.side_mm, strict=True):
        assert n >= 1 and n * cell == pytest.approx(side)
        # a band at most a third of the tile leaves each side at least one band long: cells within a third of square
        assert abs(cell - band) <= band / 3 + 1e-9
