import numpy as np
import pytest
import shapely
from dxf_helpers import hausdorff_distance
from shapely.geometry import MultiLineString

import fabtiles as ft
from fabtiles.geometry import stroke
from fabtiles.pattern.packing import circle_segments


def _segments(radius, stroke_width):
    motif = ft.Star(n=9, radii=(6.4, 1.9, 6.4), alpha=0, spr=9.3, special=3)
    tile = ft.Tile("circle", 30, ft.HexPacking(radius=radius, motif=motif, outline_circles=True), stroke=stroke_width)
    return tile.segments()


def test_dense_strokes_take_the_bucketed_union_with_the_same_result(monkeypatch):
    seg = _segments(2.0, 1.9)
    half = 0.95
    verts, edges = stroke.segment_graph(seg)
    polys = [stroke.band_polygons(verts, edges, half)] + stroke.join_polygons(verts, edges, half)
    contours = [p for block in polys for p in block]
    bucketed = stroke._bucketed_union(contours, per_bucket=16)
    single = stroke._cs().CrossSection(contours, stroke._cs().FillRule.Positive)
    assert bucketed.area() == pytest.approx(single.area(), rel=1e-9)
    a, b = stroke.to_shapely(bucketed), stroke.to_shapely(single)
    assert a.symmetric_difference(b).area < 1e-6

    calls = []
    monkeypatch.setattr(stroke, "_bucketed_union", lambda c: calls.append(len(c)) or single)
    stroke.stroke_cross_section(seg, 1.9)
    assert calls  # dense: bucketed
    calls.clear()
    stroke.stroke_cross_section(_segments(8.0, 0.3), 0.3)
    assert not calls  # sparse: one batch


def test_stroked_region_equals_geos_buffer_away_from_joins():
    # Round joins and caps: the stroked region is the GEOS buffer of the centre-lines.
    seg = ft.Star.preset("table3-3").segments() * 0.1
    ours = stroke.to_shapely(stroke.stroke_cross_section(seg, 1.0, join="round", tolerance=0.001))
    geos = MultiLineString(list(seg)).buffer(0.5, quad_segs=64)
    assert ours.is_valid
    assert ours.symmetric_difference(geos).area < 1e-3 * geos.area


def test_joins_never_leave_loose_pieces():
    # Regression: join polygons touching their bands only along a line came back as specks.
    tile = ft.Tile("square", 100, ft.HexPacking(radius=15, motif=ft.Star.preset("table3-3")), frame=5, stroke=1.0)
    for join in ("miter", "bevel", "round"):
        region = tile.replace(join=join).region()
        assert region.geom_type == "Polygon", join
    assert shapely.get_num_interior_rings(region) > 100


def _motif_and_circles(radius=15.0, size=60, motif="table3-3"):
    """All centre-lines of a square tile with outline circles, its motifs alone, and its circles."""
    pack = ft.HexPacking(radius=radius, motif=ft.Star.preset(motif), outline_circles=True)
    window = (-size / 2, -size / 2, size / 2, size / 2)
    return pack.segments(window), pack.motif_segments(window), pack.circles(window)


@pytest.mark.parametrize("join", ["miter", "round", "bevel"])
@pytest.mark.parametrize("width", [0.4, 1.0, 2.5])
def test_circles_as_annuli_equal_their_stroked_chords(join, width):
    everything, motifs, circles = _motif_and_circles()
    chords = stroke.to_shapely(stroke.stroke_cross_section(everything, width, join=join))
    annuli = stroke.to_shapely(stroke.stroke_cross_section(motifs, width, join=join, circles=circles))
    assert annuli.is_valid
    assert _holes(annuli) == _holes(chords)
    assert len(shapely.get_parts(annuli)) == len(shapely.get_parts(chords))
    # miter: the same set; round and bevel differ by at most 2 * 0.005 * half / r (r: gap circles)
    bound = 1e-6 if join == "miter" else 2 * 0.005 * (width / 2) / circles[1].min() + 1e-6
    assert hausdorff_distance(annuli.boundary, chords.boundary, densify=1.0) <= bound  # at the vertices, as GEOS
    assert annuli.area == pytest.approx(chords.area, rel=1e-5)


def _holes(geom) -> int:
    return sum(len(p.interiors) for p in shapely.get_parts(geom))


def test_small_circle_under_a_thick_stroke_is_a_disk():
    # r cos(pi / k) <= half: the bands cover the middle, so no hole is left there
    centres, radii = np.array([[0.0, 0.0], [10.0, 0.0]]), np.array([0.4, 3.0])
    rings = stroke._annulus_rings(centres, radii, 0.5)
    assert len(rings) == 3  # the small circle: a shell only; the large one: shell and hole
    assert shapely.is_ccw(shapely.linearrings(rings[0])) and not shapely.is_ccw(shapely.linearrings(rings[-1]))
    region = stroke.to_shapely(stroke.stroke_cross_section(np.empty((0, 2, 2)), 1.0, circles=(centres, radii)))
    assert sorted(len(p.interiors) for p in shapely.get_parts(region)) == [0, 1]
    chords = stroke.to_shapely(stroke.stroke_cross_section(circle_segments(centres, radii), 1.0))
    assert region.symmetric_difference(chords).area < 1e-6  # rounding along the edges


def test_tile_region_strokes_outline_circles_as_annuli(monkeypatch):
    pack = ft.HexPacking(radius=10, motif=ft.Star.preset("table1-part1"), outline_circles=True)
    seen = {}
    real = stroke.stroke_cross_section

    def spy(segments, width, **kw):
        seen["segments"], seen["circles"] = len(segments), kw.get("circles")
        return real(segments, width, **kw)

    monkeypatch.setattr("fabtiles.geometry.tile.stroke_cross_section", spy)
    tile = ft.Tile("square", 60, pack, frame=2, stroke=0.8)
    tile.region()
    window = (-30.4, -30.4, 30.4, 30.4)
    assert seen["segments"] == len(pack.motif_segments(window)) < len(tile.segments())
    centres, _ = seen["circles"]
    np.testing.assert_allclose(centres, pack.circles(window)[0] + 30)


def test_speck_holes_are_dropped():
    m3d = stroke._cs()
    square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    speck = np.array([[5, 5], [5, 5 + 1e-6], [5 + 1e-6, 5]], float)  # clockwise, 5e-13 mm^2
    hole = np.array([[2, 2], [2, 3], [3, 3], [3, 2]], float)  # clockwise, 1 mm^2
    region = stroke.to_shapely(m3d.CrossSection([square, speck, hole], m3d.FillRule.EvenOdd))
    assert len(region.interiors) == 1 and region.area == pytest.approx(99)


def test_each_hole_goes_to_the_smallest_shell_around_it():
    """A piece standing in another's hole is a polygon of its own, and the hole inside it is its own."""
    m3d = stroke._cs()

    def square(a, b, ccw=True):
        ring = np.array([[a, a], [b, a], [b, b], [a, b]], float)
        return ring if ccw else ring[::-1]

    rings = [square(0, 10), square(2, 8, ccw=False), square(3, 7), square(4, 6, ccw=False), square(12, 14)]
    region = stroke.to_shapely(m3d.CrossSection(rings, m3d.FillRule.Positive))
    frame = shapely.box(0, 0, 10, 10).difference(shapely.box(2, 2, 8, 8))
    island = shapely.box(3, 3, 7, 7).difference(shapely.box(4, 4, 6, 6))
    assert region.is_valid and region.geom_type == "MultiPolygon" and len(region.geoms) == 3
    assert shapely.equals(region, shapely.union_all([frame, island, shapely.box(12, 12, 14, 14)]))
    assert sorted(len(p.interiors) for p in region.geoms) == [0, 1, 1]
