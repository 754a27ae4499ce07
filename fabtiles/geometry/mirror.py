"""A pattern mirrored left to right, so what a stamp or a roller leaves in clay reads as designed.

A stamp pressed into clay leaves the mirror image of its face: text reads backwards and a
chiral pattern (a spiral, a rosette turning one way, an interlace's crossings) turns the
other way. Mirroring the pattern on the stamp cancels that: the imprint is the design.
"""

from __future__ import annotations

import shapely
from shapely.geometry.base import BaseGeometry


def mirrored(region: BaseGeometry, outline: BaseGeometry) -> BaseGeometry:
    """``region`` mirrored left to right across the vertical line through ``outline``'s centre.

    The centre is that of the outline's bounding box, so the bounding box maps onto
    itself and a tile's outline that is symmetric about it (every tile outline:
    square, rectangle, pointy-top hexagon, circle) maps onto itself: the mirrored
    region still fits the same outline. Polygons come out counter-clockwise, as
    before.

    >>> r = mirrored(shapely.box(0, 0, 1, 2), shapely.box(0, 0, 10, 10))
    >>> r.bounds, r.exterior.is_ccw
    ((9.0, 0.0, 10.0, 2.0), True)
    """
    xmin, _, xmax, _ = outline.bounds
    flipped = shapely.transform(region, lambda xy: xy * (-1.0, 1.0) + (xmin + xmax, 0.0))
    return shapely.orient_polygons(flipped)
