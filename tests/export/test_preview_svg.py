"""The tile SVG preview: true size, even-odd material, reproducible bytes."""

import re

from shapely.geometry import Polygon

from fabtiles import Star
from fabtiles.export.preview_svg import region_path_data, tile_svg, write_tile_svg
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking


def test_holes_are_subpaths_and_y_is_flipped():
    square = Polygon([(0, 0), (4, 0), (4, 4), (0, 4)], [[(1, 1), (1, 3), (3, 3), (3, 1)]])
    d = region_path_data(square, height=4)
    assert d.count("M") == 2 and d.count("Z") == 2
    assert d.startswith("M0 4L4 4L4 0L0 0Z")


def test_tile_svg_true_size_and_reproducible(tmp_path):
    tile = TileGeometry("rectangle", (50, 30), HexPacking(radius=6, motif=Star.preset("table3-2")), frame=2)
    svg = tile_svg(tile, title="t")
    assert re.search(r'width="50mm" height="30mm" viewBox="0 0 50 30"', svg)
    assert "<title>t</title>" in svg and 'fill-rule="evenodd"' in svg
    again = tile_svg(
        TileGeometry("rectangle", (50, 30), HexPacking(radius=6, motif=Star.preset("table3-2")), frame=2), title="t"
    )
    assert svg == again
    write_tile_svg(tmp_path / "t.svg", tile, title="t")
    assert (tmp_path / "t.svg").read_text() == svg
    assert [p.name for p in tmp_path.iterdir()] == ["t.svg"]
