"""Shapely layer: stroking, union, clipping, validation, laying tiles on a sheet.

:class:`TileGeometry` turns a pattern into material (a shapely region in mm);
:func:`seamless_fit` picks a packing radius that makes a tile an exact period;
:func:`~fabtiles.geometry.sheet.layout_sheet` lays copies of a tile on a bed.
"""

from .seamless import SeamlessFit, seamless_fit, seamless_radius
from .tile import OUTLINES, TileGeometry

__all__ = ["OUTLINES", "SeamlessFit", "TileGeometry", "seamless_fit", "seamless_radius"]
