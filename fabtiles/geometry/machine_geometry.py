"""What each machine makes of a tile: the region a cutter cuts, the region and dips a printer prints.

An interlaced tile differs by machine: a cutter scores its centre-lines broken where
a strand passes under (score mode) or cuts the under gaps (pierced mode with
``interlace_cut``, leaving tabs ``min(min_feature_mm, stroke / 2)`` wide); a relief
print dips its under strands. The build's models (:mod:`fabtiles.making`), the
checks and the pictures all take their geometry from here.
"""

from __future__ import annotations

from ..machines.profiles import DEFAULT_CUTTER_PROFILE, DEFAULT_PRINTER_PROFILE, load_profile


def cut_geometry(tile, *, profile=None, mode=None, lines: bool = True):
    """What a cutter's file of ``tile`` cuts and scores: ``(region, centrelines)``.

    ``region`` is the material (with ``interlace_cut`` in pierced mode, the under
    gaps cut, tabs ``min(min_feature_mm, stroke / 2)`` wide left across), and
    ``centrelines`` the score lines (interlaced, broken where a strand passes
    under). ``profile`` is the cutter profile (default ``laser-3mm-plywood``),
    ``mode`` ``"pierced"`` or ``"score"`` (default: the profile's);
    ``lines=False`` (the checks) skips the score lines and gives None for them.

    >>> import numpy as np
    >>> import fabtiles as ft
    >>> pack = ft.HexPacking(radius=8, motif=ft.Star.preset("table3-3"))
    >>> tile = ft.Tile("square", 30, pack, frame=3, interlace=True, interlace_cut=True)
    >>> region, lines = cut_geometry(tile, mode="pierced")
    >>> length = lambda s: float(np.linalg.norm(s[:, 1] - s[:, 0], axis=1).sum())
    >>> region.area < tile.region().area, length(cut_geometry(tile, mode="score")[1]) < length(lines)
    (True, True)
    """
    region, centrelines = tile.region(), tile.centrelines() if lines else None
    if getattr(tile, "interlace", False):
        from . import interlace

        cutter = load_profile(profile if profile is not None else DEFAULT_CUTTER_PROFILE, kind="laser")
        mode = mode or cutter.mode
        if mode == "score":
            centrelines = interlace.tile_score_lines(tile) if lines else None
        elif tile.interlace_cut:
            region = interlace.tile_cut_region(tile, min(cutter.min_feature_mm, tile.stroke / 2))
    return region, centrelines


laser_geometry = cut_geometry
"""The name :func:`cut_geometry` had (any 2D cutter, not only a laser)."""


def print_geometry(tile, *, profile=None, style=None):
    """What a print of ``tile`` is made of: ``(region, dips)``.

    ``dips`` is where an interlaced relief's under strands dip (None when the tile is
    not interlaced or the style, the given one or the printer profile's, is not a relief).
    """
    dips = None
    if (
        getattr(tile, "interlace", False)
        and (
            style
            or load_profile(profile if profile is not None else DEFAULT_PRINTER_PROFILE, kind="printer").print_style
        )
        == "relief"
    ):
        from . import interlace

        dips = interlace.tile_dips(tile)
    return tile.region(), dips
