"""Sheets: several tiles laid out on one sheet of the laser bed.

:func:`layout_sheet` places tiles (each a material region and its outline, in file
coordinates with the outline's lower-left at (0, 0)) in rows, left to right and
bottom to top, ``gap_mm`` apart, inside the bed of a laser profile. The result
feeds the laser writers unchanged: ``region`` is the material of every tile,
``outline`` a MultiPolygon with one polygon per tile (the fabrication checks count
loose parts per tile), ``centrelines`` the moved centre-lines when given.

"A large pattern" needs no layout: make the tile as big as the bed.

>>> from shapely.geometry import box
>>> sheet = layout_sheet([(box(0, 0, 100, 100), box(0, 0, 100, 100))], "laser-3mm-plywood", copies=8)
>>> len(sheet.offsets), sheet.outline.bounds
(8, (0.0, 0.0, 508.6, 202.15))
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from ..core.errors import FabricationError, ParameterError
from ..core.validate import check_float, check_int
from ..machines.profiles import load_profile

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry

GAP_EXTRA_MM = 2.0
"""Default gap between tiles: the kerf plus this much."""


@dataclass(frozen=True)
class Sheet:
    """Tiles laid out on a sheet: inputs for :func:`~fabtiles.geometry.cut_plan.plan_cut`."""

    region: BaseGeometry
    outline: BaseGeometry
    centrelines: np.ndarray | None
    offsets: tuple[tuple[float, float], ...]
    size: tuple[float, float]


def layout_sheet(
    tiles, profile, *, copies: int = 1, gap_mm: float | None = None, centrelines=None, fill: bool = False
) -> Sheet:
    """Lay ``tiles`` on the bed of ``profile`` in rows; every tile ``copies`` times.

    Parameters
    ----------
    tiles : list of (region, outline)
        Shapely material region and outline of each tile, outline lower-left at (0, 0).
    profile : str, Path or CutterProfile
        Laser profile: the bed size (``bed_mm``) and, for the default gap, the kerf.
    copies : int
        How many of each tile (>= 1).
    gap_mm : float, optional
        Space between tiles (> kerf, > a router's tool diameter); default: that + 2 mm.
    centrelines : list of ndarray (k, 2, 2), optional
        Centre-lines of each tile (for the score mode), moved with their tiles.
    fill : bool
        Repeat the tiles (in turn) for as long as they fit, instead of ``copies``.

    Raises
    ------
    FabricationError
        When the tiles do not all fit on the bed (or not even one does, with ``fill``).
    """
    profile = load_profile(profile, kind="laser")
    if not isinstance(tiles, (list, tuple)) or not tiles:
        raise ParameterError("tiles must be a non-empty list of (region, outline) pairs", param="tiles")
    copies = check_int("copies", copies, low=1, high=10_000)
    # a router's bit must pass between two tiles: the gap is wider than the cut (the kerf, or the bit)
    cut = max(profile.kerf_mm, 2 * profile.tool_radius_mm)
    gap = check_float("gap_mm", cut + GAP_EXTRA_MM if gap_mm is None else gap_mm, low=cut, low_open=True)
    if centrelines is not None and len(centrelines) != len(tiles):
        raise ParameterError(
            f"centrelines must hold one array per tile ({len(tiles)}), got {len(centrelines)}", param="centrelines"
        )
    sizes = _tile_sizes(tiles)
    order = list(range(len(tiles))) * (copies if not fill else 10_000)
    placed = _rows(sizes, order, gap, profile, fill=fill)
    return _sheet(tiles, centrelines, sizes, placed)


def _tile_sizes(tiles) -> list:
    """Each tile's outline's width, height and lower-left, ``[(w, h, x0, y0), ...]``, the pairs checked."""
    sizes = []
    for k, pair in enumerate(tiles):
        if not isinstance(pair, (list, tuple)) or len(pair) != 2:
            raise ParameterError(f"tiles[{k}] must be a (region, outline) pair, got {pair!r}", param="tiles")
        xmin, ymin, xmax, ymax = pair[1].bounds
        sizes.append((xmax - xmin, ymax - ymin, xmin, ymin))
    return sizes


def _rows(sizes: list, order: list, gap: float, profile, *, fill: bool) -> list:
    """The tiles of ``order`` laid in rows on the bed, ``gap`` apart: ``[(tile index, dx, dy), ...]``.

    ``fill``: as many as fit (at least one); else all of them or a
    :class:`~fabtiles.FabricationError`.
    """
    bed_w, bed_h = profile.bed_mm
    placed: list = []
    x = y = row_h = 0.0
    eps = 1e-6
    for i in order:
        w, h, x0, y0 = sizes[i]
        if x > 0 and x + w > bed_w + eps:  # next row
            x, y, row_h = 0.0, y + row_h + gap, 0.0
        if x + w > bed_w + eps or y + h > bed_h + eps:
            if fill and placed:
                break
            raise _too_large(profile, i, (w, h), fill=fill, gap=gap, tiles=len(order), placed=len(placed))
        placed.append((i, x - x0, y - y0))
        x += w + gap
        row_h = max(row_h, h)
    return placed


def _sheet(tiles, centrelines, sizes: list, placed: list) -> Sheet:
    """The :class:`Sheet` of the tiles moved to their places (``placed``: ``[(tile index, dx, dy), ...]``)."""
    regions, outlines, lines = [], [], []
    for i, dx, dy in placed:
        region, outline = tiles[i]
        regions.extend(shapely.get_parts(shapely.transform(region, lambda c, dx=dx, dy=dy: c + (dx, dy))))
        outlines.extend(shapely.get_parts(shapely.transform(outline, lambda c, dx=dx, dy=dy: c + (dx, dy))))
        if centrelines is not None:
            lines.append(np.asarray(centrelines[i], dtype=float) + (dx, dy))
    used_w = max(dx + sizes[i][2] + sizes[i][0] for i, dx, _ in placed)
    used_h = max(dy + sizes[i][3] + sizes[i][1] for i, _, dy in placed)
    return Sheet(
        region=shapely.multipolygons(regions),
        outline=shapely.multipolygons(outlines),
        centrelines=np.concatenate(lines) if lines else None,
        offsets=tuple((round(dx, 9), round(dy, 9)) for _, dx, dy in placed),
        size=(round(used_w, 9), round(used_h, 9)),
    )


def _too_large(profile, i: int, size: tuple, *, fill: bool, gap: float, tiles: int, placed: int) -> FabricationError:
    """The error for tiles that do not fit on the bed (with ``fill``: not even one)."""
    bed_w, bed_h = profile.bed_mm
    w, h = size
    if fill:
        return FabricationError(
            f"not even one tile fits on the {bed_w:g} x {bed_h:g} mm bed of {profile.kind} profile "
            f"{profile.name!r} (tile {i} is {w:g} x {h:g} mm); use smaller tiles or a profile "
            f"with a larger bed_mm"
        )
    return FabricationError(
        f"{tiles} tiles do not fit on the {bed_w:g} x {bed_h:g} mm bed of {profile.kind} profile "
        f"{profile.name!r} with a gap of {gap:g} mm (tile {i} is {w:g} x {h:g} mm, "
        f"{placed} placed); use fewer copies, smaller tiles or a profile with a larger bed_mm"
    )
