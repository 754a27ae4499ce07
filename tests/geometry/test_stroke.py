import numpy as np
import pytest
import shapely
from shapely.geometry import MultiLineString

import fabtiles as ft
from fabtiles.geometry import stroke


def _segments(radius, stroke_width):
    motif = ft.Star(n=9, radii=(6.4, 1.9, 6.4), alpha=0, spr=9.3, special=3)
    tile = ft.Tile("circle", 30, ft.HexPacking(radius=radius, motif=motif, outline_circles=True), stroke=stroke_width)
    return tile.segments()


def test_dense_strokes_take_the_bucketed_union_with_the_same_result(monkeypatch):
    seg = _segments(2.0, 1.9)
    half = 0.95
    verts, edges = stroke._graph(seg)
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
    geos = MultiLineString([s for s in seg]).buffer(0.5, quad_segs=64)
    assert ours.is_valid
    assert ours.symmetric_difference(geos).area < 1e-3 * geos.area


def test_joins_never_leave_loose_pieces():
    # Regression: join polygons touching their bands only along a line came back as specks.
    tile = ft.Tile("square", 100, ft.HexPacking(radius=15, motif=ft.Star.preset("table3-3")), frame=5, stroke=1.0)
    for join in ("miter", "bevel", "round"):
        region = tile.replace(join=join).region()
        assert region.geom_type == "Polygon", join
    assert shapely.get_num_interior_rings(region) > 100
