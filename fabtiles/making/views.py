"""What the pictures and the 3D view show, from the same models as the files.

The tile's picture (``build --preview``, ``check -o``, the web app) draws a router's
or waterjet's part as its tool makes it (:func:`made_region`); the kit picture the
kit's lattice and pieces (:func:`inlay_kit_of`); the 3D view the print model's parts
(:func:`print_view`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from ..core.report import Report
from ..machines import limits as _limits
from .models import BuildOptions, Models
from .pipeline import check_format_limits, prepare_tile

VIEW_SEGMENTS = 8_000
"""Most centre-line segments the 3D view shows whole: about twice the 150 mm default tile's. A
bigger tile's view is its centre window holding about this many segments, a lighter preview that
says so: a 300 mm square shown whole is ten times the triangles, more than a view should carry
(``benchmarks/bench_web.py``; the figures in ``docs/speed.md``)."""


def made_region(tile, design, *, models: Models | None = None):
    """The tile's part as a router's bit or a waterjet's jet makes it (the design's cutter profile), else None.

    Every hole opened by the tool's radius (:mod:`fabtiles.geometry.tool_opening`);
    None for a laser (the picture draws the tile's own region). With the build's
    ``models``, the part of its cut plan when that plan is made anyway.
    """
    from ..geometry.machine_geometry import cut_geometry
    from ..geometry.tool_opening import open_region
    from ..machines.cutters import cutter_kind

    options = models.options if models is not None else BuildOptions.of_design(design)
    profile = options.cutter
    kind = cutter_kind(profile)
    if not kind.opens_holes:
        return None
    kind.check_profile(profile)
    if models is not None and models.sheet is None and not options.kit and not options.fill_small_holes:
        part = getattr(models.cut, "part", None)  # a panel's pieces have a part each, not one
        if part is not None:
            return part  # the plan opened the holes already (pierced is a router's only mode)
    region, _ = cut_geometry(tile, profile=profile, mode="pierced", lines=False)
    return open_region(region, radius_mm=profile.tool_radius_mm, tolerance_mm=profile.tolerance_mm).region


def panel_seams(tile, design, *, models: Models | None = None):
    """Where a tile larger than its cutter's bed is cut into pieces, for the pictures
    (:class:`~fabtiles.making.checks.PiecesOverlay`: the seams and the pieces' numbers); None for a
    tile that fits, one not made as pieces, or a split that cannot be made (the checks say why).

    Only the split is made (no piece's cut plan): the web app's preview draws it over the tile.
    """
    from ..core.errors import FabtilesError
    from .checks import PiecesOverlay
    from .pieces import split_for_cutter, too_big

    models = models if models is not None else Models(tile, BuildOptions.of_design(design))
    o = models.options
    if not o.pieces or o.kit or models.sheet is not None or not too_big(tile.outline_shape(), o.cutter):
        return None
    kerf = o.kerf_mm if o.kerf_mm is not None else max(o.cutter.kerf_xy_mm)
    try:
        region, _ = models.cut_region
        split = split_for_cutter(tile, region, o.cutter, mode=o.mode, kerf_mm=kerf)
    except FabtilesError:
        return None
    return PiecesOverlay.of(split)


def tile_picture(
    tile, design, *, models: Models | None = None, title: str | None = None, findings=None, made=False, pieces=None
) -> str:
    """The tile's picture (SVG, true size): a router's part as its tool makes it, and with the design's
    colours its faces filled in their classes' colours and its bands in the band colour.

    ``made`` is the part to draw when the caller has it already (``fabtiles check``'s); by
    default it is :func:`made_region`'s. ``pieces``: a panel's seams and numbers drawn over it
    (:attr:`~fabtiles.making.checks.CheckResult.split`).
    """
    from ..export.preview_svg import tile_svg

    models = models if models is not None else Models(tile, BuildOptions.of_design(design))
    if models.cylinder is not None and (made is False or made is None):
        from .cylinder import strip_region

        # a cylinder's strip as it is printed (mirrored, its rims closed), where its findings are
        printed, dips = models.print_region
        made = strip_region(printed, dips, tile.outline_shape(), models.cylinder, models.options.printer)[0]
    elif models.options.stamp is not None and (made is False or made is None):
        # a stamp's face as it is printed (mirrored unless the design says not), where its findings are
        made = models.print.region
    region = made_region(tile, design, models=models) if made is False else made
    return tile_svg(
        tile,
        title=design.name if title is None else title,
        findings=findings,
        region=region,
        pieces=pieces,
        **models.picture_colours(),
    )


def inlay_kit_of(tile, design):
    """The inlay kit of a tile with the design's cutter profile and fit (the kit picture)."""
    from ..geometry.inlay import inlay_kit
    from ..geometry.machine_geometry import cut_geometry

    out = design.output
    profile = BuildOptions.of_design(design).cutter
    region, _ = cut_geometry(tile, profile=profile, mode="pierced", lines=False)
    fit = profile.inlay_fit_mm if out.inlay_fit_mm is None else out.inlay_fit_mm
    return inlay_kit(
        region,
        tile.outline_shape(),
        fit_mm=fit,
        min_piece_mm=profile.min_piece_or_default_mm,
        kerf_mm=max(profile.kerf_xy_mm),
        tolerance_mm=profile.tolerance_mm,
    )


def print_view(
    design,
    *,
    limits: _limits.Limits,
    max_segments: int = VIEW_SEGMENTS,
    checkpoint: Callable[[], object] | None = None,
) -> tuple[bytes, Report]:
    """The design's print as GLB, one mesh per part (the web app's 3D view), and its report.

    The tile passes the same work limits as an STL or 3MF export, before any geometry is
    built, and the parts are the print model's, after the same checks. A tile of more than
    ``max_segments`` segments shows its centre: ``report.stats["window_mm"]`` is then
    that window's ``[x0, y0, x1, y1]`` in file coordinates, and ``stats["view"]`` says so.
    ``checkpoint`` is called before each stage of the work (the print's region, its model,
    the parts' meshes) and may raise to stop a view nobody waits for any more: the web
    app's, when its browser has asked for a newer one.
    """
    import numpy as np
    import shapely

    from ..export.formats import FORMATS, FileOptions

    go_on = checkpoint or (lambda: None)
    tile = prepare_tile(design, limits=limits)
    check_format_limits(tile, ("3mf",), limits)
    go_on()
    # the view shows the panel whole, however the files split it for the bed
    models = Models(tile, replace(BuildOptions.of_design(design), pieces=False))
    region, dips = models.print_region
    outline = tile.outline_shape()
    count = _limits.estimate_segments(tile.pattern, tile.width_mm, tile.height_mm)
    window = None
    if count > max_segments and models.cylinder is None:  # a cylinder is shown whole: its strip wraps whole
        x0, y0, x1, y1 = outline.bounds
        half = (np.sqrt(max_segments / count) / 2) * np.array([x1 - x0, y1 - y0])
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        window = [float(cx - half[0]), float(cy - half[1]), float(cx + half[0]), float(cy + half[1])]
        box = shapely.box(*window)
        region, outline = region.intersection(box), outline.intersection(box)
        dips = dips.intersection(box) if dips is not None else None
        models = Models(_Window(tile, outline), models.options, print_region=(region, dips))
    go_on()
    glb = FORMATS["glb"]
    model = models.print
    go_on()
    data = glb.write(model, FileOptions())  # the parts' meshes are made here, on first use
    report = Report(
        path="",
        format="glb",
        stats={**model.report.stats, **glb.figures(model, FileOptions())},
        findings=list(model.report.findings),
    )
    report.stats["bytes"] = len(data)
    size = f"{tile.width_mm:g} x {tile.height_mm:g} mm"
    if window is not None:
        report.stats["window_mm"] = window
        report.stats["view"] = (
            f"the centre {window[2] - window[0]:.0f} x {window[3] - window[1]:.0f} mm of the "
            f"{size} tile, a lighter preview (the files hold all of it)"
        )
    elif models.cylinder is not None:
        report.stats["view"] = f"the whole cylinder, its unrolled strip {size}"
    else:
        report.stats["view"] = f"the whole {size} tile"
    return data, report


class _Window:
    """A tile seen through the 3D view's window: its outline clipped, the rest as the tile's."""

    def __init__(self, tile, outline):
        self._tile, self._outline = tile, outline

    def outline_shape(self):
        return self._outline

    def __getattr__(self, name):
        return getattr(self._tile, name)
