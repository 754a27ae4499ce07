"""Shapely layer: stroking, union, clipping, validation.

:class:`Tile` turns a pattern into material (a shapely region in mm);
:func:`seamless_fit` picks a packing radius that makes a tile an exact period.
"""

from .seamless import SeamlessFit, seamless_fit, seamless_radius
from .tile import OUTLINES, Tile

__all__ = ["OUTLINES", "SeamlessFit", "Tile", "seamless_fit", "seamless_radius"]
