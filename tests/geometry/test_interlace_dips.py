"""The relief's dips (issue 16) against GEOS's exact predicates: a sliver dips exactly when it lies in the material."""

import numpy as np
import pytest
import shapely

import fabtiles as ft
from fabtiles.geometry import interlace as gi
from fabtiles.geometry.stack import QUANTUM

TILES = {
    "table3-3 hex": lambda: ft.Tile(
        "square", 60, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-3")), frame=3, stroke=1.0, interlace=True
    ),
    "table3-1 no frame": lambda: ft.Tile(
        "hexagon", 50, ft.HexPacking(radius=12, motif=ft.Star.preset("table3-1")), frame=0, stroke=1.2, interlace=True
    ),
    "4.8.8": lambda: ft.Tile(
        "square", 60, ft.ArchimedeanPacking("4.8.8", edge=14), frame=3, stroke=1.0, interlace=True
    ),
}


def exact_dips(tile):
    """The slivers GEOS says lie in the material (and in the frame's inside), unioned (those
    that overlap snapped back to the meshes' grid once merged, as the dips are)."""
    w, half, gap = tile.weave(), tile.stroke / 2, gi.tile_gap(tile)
    q = gi.dip_quads(w, half, gap)
    parts = shapely.polygons(np.concatenate([q, q[:, :1]], axis=1))
    within = tile.inner_shape() if tile.frame > 0 else tile.outline_shape()
    keep = shapely.contains_properly(tile.region(), parts) & shapely.contains(within, parts)
    kept = parts[keep]
    a, b = shapely.STRtree(kept).query(kept, predicate="intersects")
    overlapping = np.zeros(len(kept), bool)
    overlapping[a[a != b]] = True
    merged = shapely.set_precision(shapely.union_all(kept[overlapping]), QUANTUM)
    return shapely.union_all([*kept[~overlapping], merged]), int(keep.sum()), len(parts)


@pytest.mark.parametrize("name", TILES)
def test_dips_are_the_slivers_inside_the_material(name):
    tile = TILES[name]()
    dips = gi.tile_dips(tile)
    exact, kept, total = exact_dips(tile)
    assert 0 < kept < total  # some slivers leave the material (tips, shallow crossings), most do not
    assert shapely.symmetric_difference(dips, exact).area == pytest.approx(0, abs=1e-9)
    assert shapely.contains_properly(tile.region(), shapely.get_parts(dips)).all()
