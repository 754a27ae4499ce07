"""One entry point for every output format: pick the writer from the file suffix.

Laser formats (``.dxf``, ``.svg``) take a laser profile, print formats
(``.stl``, ``.3mf``, ``.step``) a printer profile. Each writer module is
imported only when its format is asked for, so a DXF export never loads
manifold3d and only STEP loads build123d/OCP.
"""

from __future__ import annotations

import importlib
from pathlib import Path

from .._errors import FabricationError, ParameterError
from .._profiles import load_profile

FORMATS = ("dxf", "svg", "lbrn2", "stl", "3mf", "step")
"""Output formats, by file suffix."""

LASER_OPTIONS = ("mode", "dxf_version", "kerf_mm", "fill_small_holes", "inlay_fit_mm", "inlay_base")
PRINT_OPTIONS = ("style", "base_mm", "relief_mm", "pierced_mm", "deboss_mm", "fill_small_holes")
THREEMF_OPTIONS = PRINT_OPTIONS + ("inlay", "layout")
"""The 3MF writer's options: the print options, ``inlay`` (deboss grooves filled as a second part) and
``layout`` (``"volumes"`` or ``"components"``, see :mod:`fabtiles.export.threemf`)."""

DEFAULT_LASER_PROFILE = "laser-3mm-plywood"
DEFAULT_PRINTER_PROFILE = "fdm-0.4mm"

# format -> (module, function, kind of profile)
_WRITERS = {
    "dxf": ("dxf", "write_dxf", "laser"),
    "svg": ("laser_svg", "write_laser_svg", "laser"),
    "lbrn2": ("lbrn2", "write_lbrn2", "laser"),
    "stl": ("stl", "write_stl", "printer"),
    "3mf": ("threemf", "write_3mf", "printer"),
    "step": ("step", "write_step", "printer"),
}


def format_of(path) -> str:
    """The output format named by a path's suffix.

    >>> format_of("tile.DXF")
    'dxf'
    >>> format_of("tile.png")
    Traceback (most recent call last):
    ...
    fabtiles._errors.ParameterError: 'png' is not a valid output format (from the suffix of 'tile.png'), must be one of: dxf, svg, lbrn2, stl, 3mf, step
    """
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in FORMATS:
        raise ParameterError(
            f"{suffix!r} is not a valid output format (from the suffix of {str(path)!r}), "
            f"must be one of: {', '.join(FORMATS)}",
            param="path",
        )
    return suffix


def profile_kind(fmt: str) -> str:
    """``"laser"`` or ``"printer"``: which profile a format takes."""
    return _WRITERS[fmt][2]


def export_geometry(path, *, region, outline, centrelines=None, stroke=None, profile=None, dips=None, **options):
    """Write ``region`` (material, file coordinates in mm) in the format of ``path``.

    Parameters
    ----------
    path : str or Path
        Output file; its suffix picks the format (see :data:`FORMATS`).
    region, outline : shapely geometry
        The material and the tile outline, lower-left of the outline's bounds at (0, 0).
    centrelines : ndarray (k, 2, 2), optional
        Centre-lines, for the laser score mode.
    stroke : float, optional
        Stroke width, for the fabrication checks.
    dips : shapely geometry, optional
        Print: where an interlaced relief's under strands dip (see
        :mod:`fabtiles.solid.levels`).
    profile : str, Path or profile, optional
        Laser profile for dxf/svg (default ``laser-3mm-plywood``), printer profile for
        stl/3mf/step (default ``fdm-0.4mm``).
    **options
        Laser: ``mode``, ``dxf_version``, ``kerf_mm``, ``fill_small_holes`` (by the
        cutter profile's ``min_hole_mm``, and a router's bit); with
        ``mode="inlay"`` also ``inlay_fit_mm`` and ``inlay_base`` (the kit: two files,
        see :mod:`fabtiles.export.kit`).
        Print: ``style``, ``base_mm``, ``relief_mm``, ``pierced_mm``, ``deboss_mm``,
        ``fill_small_holes`` (by the printer profile's ``min_hole_mm``); ``.3mf`` also
        ``inlay`` and ``layout``.

    Returns
    -------
    Report
        What was written and what the fabrication checks found.
    """
    fmt = format_of(path)
    module, func, family = _WRITERS[fmt]
    allowed = LASER_OPTIONS if family == "laser" else THREEMF_OPTIONS if fmt == "3mf" else PRINT_OPTIONS
    for key in options:
        if key not in allowed:
            raise ParameterError(
                f"{key!r} is not a valid option for .{fmt} files, must be one of: {', '.join(allowed)}",
                param=key,
            )
    options = {k: v for k, v in options.items() if v is not None}
    if region is None or region.is_empty:
        raise FabricationError(
            "the tile holds no material: every stroke of its pattern falls outside the outline; "
            "add a frame, make the tile larger, or make the packing radius smaller"
        )
    default = DEFAULT_LASER_PROFILE if family == "laser" else DEFAULT_PRINTER_PROFILE
    profile = load_profile(profile if profile is not None else default, kind=family)
    writer = getattr(importlib.import_module(f"{__package__}.{module}"), func)
    if family == "laser":
        profile.cutter.check_format(profile, fmt)
        profile.cutter.check_mode(profile, options.get("mode"))  # before the inlay kit's route below
        kit = options.pop("inlay_fit_mm", None), options.pop("inlay_base", None)
        if (options.get("mode") or profile.mode) == "inlay":  # two files: the lattice and the pieces
            from .kit import write_kit

            options.pop("mode", None)
            return write_kit(path, region=region, outline=outline, centrelines=centrelines, profile=profile,
                             stroke=stroke, inlay_fit_mm=kit[0], inlay_base=kit[1] or "pierced", **options)
        if kit != (None, None):
            raise ParameterError("inlay_fit_mm and inlay_base are options of the inlay mode; pass mode='inlay'",
                                 param="inlay_fit_mm" if kit[0] is not None else "inlay_base")
        return writer(path, region=region, outline=outline, centrelines=centrelines,
                      profile=profile, stroke=stroke, **options)
    if dips is not None and not dips.is_empty:
        import inspect

        if "dips" not in inspect.signature(writer).parameters:
            raise ParameterError(f"an interlaced relief cannot be written as .{fmt} yet; "
                                 "write .stl, or pass interlace=False")
        options["dips"] = dips
    return writer(path, region=region, outline=outline, profile=profile, stroke=stroke, **options)


def laser_geometry(tile, *, profile=None, mode=None, lines: bool = True):
    """What a laser file of ``tile`` cuts and scores: ``(region, centrelines)``.

    ``region`` is the material (with ``interlace_cut`` in pierced mode, the under
    gaps cut, tabs ``min(min_feature_mm, stroke / 2)`` wide left across), and
    ``centrelines`` the score lines (interlaced, broken where a strand passes
    under). ``profile`` is the laser profile (default ``laser-3mm-plywood``),
    ``mode`` ``"pierced"`` or ``"score"`` (default: the profile's). The tile's
    files, its sheets and its checks all take their laser geometry from here;
    ``lines=False`` (the checks) skips the score lines and gives None for them.

    >>> import numpy as np
    >>> import fabtiles as ft
    >>> pack = ft.HexPacking(radius=8, motif=ft.Star.preset("table3-3"))
    >>> tile = ft.Tile("square", 30, pack, frame=3, interlace=True, interlace_cut=True)
    >>> region, lines = laser_geometry(tile, mode="pierced")
    >>> length = lambda s: float(np.linalg.norm(s[:, 1] - s[:, 0], axis=1).sum())
    >>> region.area < tile.region().area, length(laser_geometry(tile, mode="score")[1]) < length(lines)
    (True, True)
    """
    region, centrelines = tile.region(), tile.centrelines() if lines else None
    if getattr(tile, "interlace", False):
        from ..geometry import interlace

        laser = load_profile(profile if profile is not None else DEFAULT_LASER_PROFILE, kind="laser")
        mode = mode or laser.mode
        if mode == "score":
            centrelines = interlace.tile_score_lines(tile) if lines else None
        elif tile.interlace_cut:
            region = interlace.tile_cut_region(tile, min(laser.min_feature_mm, tile.stroke / 2))
    return region, centrelines


def print_geometry(tile, *, profile=None, style=None):
    """What a print of ``tile`` is made of: ``(region, dips)``.

    ``dips`` is where an interlaced relief's under strands dip (None when the tile is
    not interlaced or the style, the given one or the printer profile's, is not a relief).
    The print files and the web app's 3D view take their geometry from here.
    """
    dips = None
    if getattr(tile, "interlace", False) and (style or load_profile(
            profile if profile is not None else DEFAULT_PRINTER_PROFILE, kind="printer").style) == "relief":
        from ..geometry import interlace

        dips = interlace.tile_dips(tile)
    return tile.region(), dips


def export_tile(tile, path, *, profile=None, **options):
    """Write a :class:`~fabtiles.Tile` in the format of ``path``; see :func:`export_geometry`.

    An interlaced tile (``docs/tile-operation.md``, :mod:`fabtiles.geometry.interlace`) scores its
    centre-lines broken where a strand passes under, cuts the under gaps in
    pierced mode with ``interlace_cut`` (leaving tabs ``min(min_feature_mm,
    stroke / 2)`` wide), and dips its relief's under strands.
    """
    fmt = format_of(path)
    centrelines, dips = None, None
    if profile_kind(fmt) == "laser":
        region, centrelines = laser_geometry(tile, profile=profile, mode=options.get("mode"))
    else:
        region, dips = print_geometry(tile, profile=profile, style=options.get("style"))
    return export_geometry(
        path,
        region=region,
        outline=tile.outline_shape(),
        centrelines=centrelines,
        stroke=tile.stroke,
        profile=profile,
        dips=dips,
        **options,
    )
