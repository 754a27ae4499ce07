"""mirrored (fabtiles/geometry/mirror.py): a stamp's face, so that its imprint reads as designed."""

from __future__ import annotations

import math

import pytest
import shapely

from fabtiles.geometry.mirror import mirrored
from fabtiles.geometry.tile import OUTLINES, outline_polygon


def outline_of(name):
    width, height = (60.0, 2 * 60 / math.sqrt(3)) if name == "hexagon" else (60.0, 40.0)
    if name in ("square", "circle"):
        height = width
    return outline_polygon(name, width, height, centre=(width / 2, height / 2))


@pytest.mark.parametrize("name", OUTLINES)
def test_every_tile_outline_is_its_own_mirror_image(name):
    outline = outline_of(name)
    assert mirrored(outline, outline).symmetric_difference(outline).area < 1e-9 * outline.area


def test_a_point_goes_to_the_other_side_of_the_outlines_centre_at_the_same_height():
    outline = shapely.box(10, 0, 70, 40)
    assert mirrored(shapely.Point(15, 7), outline).equals(shapely.Point(65, 7))


def test_mirroring_twice_gives_the_region_back_and_keeps_its_rings_counter_clockwise():
    outline = shapely.box(0, 0, 50, 50)
    f = shapely.union_all([shapely.box(10, 10, 15, 40), shapely.box(10, 35, 35, 40), shapely.box(10, 22, 28, 27)])
    once = mirrored(f.difference(shapely.box(11, 11, 12, 12)), outline)
    assert not once.equals(f)
    assert once.exterior.is_ccw and not once.interiors[0].is_ccw
    assert (
        mirrored(once, outline).normalize().equals_exact(f.difference(shapely.box(11, 11, 12, 12)).normalize(), 1e-12)
    )
