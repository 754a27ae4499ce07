"""A design made as a clay stamp: the tile's relief, mirrored, on a block with a finger grip.

The design's ``[surface] shape = "stamp"`` keeps its tile (outline, size, frame) and makes
its print a :class:`~fabtiles.solid.stamp.StampPrint`: the relief of the pattern mirrored
left to right (what a stamp leaves in clay is the mirror of its face, so the imprint
reads as designed; ``mirror = false`` keeps the face as drawn), its plate on a block of
``block_mm`` with a groove of ``grip_mm`` round its sides whose chamfers keep to the
printer profile's overhang limit. It is printed pattern up, whole: not cut, not laid on a
sheet, not split into pieces. Every value that cannot make a stamp is refused here,
before any geometry (:func:`stamp_settings`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..core.errors import ParameterError

if TYPE_CHECKING:
    from ..designs.design_file import SurfaceSpec
    from ..solid.stamp import StampPrint, StampSettings
    from .models import BuildOptions, Models


def stamp_settings(surface: SurfaceSpec, options: BuildOptions) -> StampSettings:
    """The stamp's block and grip from ``surface``, its print style checked (a stamp is a relief).

    The overhang limit is the printer profile's (``max_overhang_deg``), which the grip's chamfers keep to.
    """
    from ..solid.stamp import StampSettings

    style = options.print_style or options.printer.print_style
    if style != "relief":
        raise ParameterError(
            f'print_style = {style!r} does not make a clay stamp: [surface] shape = "stamp" is the pattern raised '
            'on a block, print_style = "relief"',
            param="output.print_style",
        )
    return StampSettings(
        block_mm=surface.block_mm,
        grip_mm=surface.grip_mm,
        groove_mm=surface.groove_mm,
        overhang_deg=options.printer.max_overhang_deg,
    )


def stamp_print(models: Models) -> StampPrint:
    """The stamp of ``models``' tile: its relief print, mirrored unless the design says not, on the block."""
    from ..geometry.mirror import mirrored
    from ..solid import stamp as solid_stamp

    o = models.options
    assert o.stamp is not None  # a stamp's design
    settings = stamp_settings(o.stamp, o)
    region, dips = models.print_region
    outline = models.tile.outline_shape()
    mirror = o.stamp.mirror_for("relief")
    if mirror:
        region = mirrored(region, outline)
        dips = None if dips is None else mirrored(dips, outline)
    model = models.flat_print(region, dips, style="relief", heights=o.heights)
    if mirror:
        note = "stamp's face mirrored: its imprint reads as designed"
        model = model.with_classes(model.mosaic, model.report.extended(notes=[note]))
    return solid_stamp.stamp_print(model, settings=settings)
