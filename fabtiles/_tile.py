"""The public :class:`Tile`: a tile's geometry, plus the work limits and ``export()``.

One class is called ``Tile``: this one, the class users hold. Its geometry is
:class:`fabtiles.geometry.tile.TileGeometry` (stroking, clipping, checks), which the
lower layers take and the build pipeline builds (it checks the limits of its own front
end: the web app's are tighter). ``export()`` cannot live on the geometry class: the
geometry layer may not import the writers (``.importlinter``), and a method's lazy
import counts as one. So the public class adds the writers and the command-line
limits, and nothing else.
"""

from __future__ import annotations

from . import _limits
from .geometry.tile import TileGeometry


class Tile(TileGeometry):
    """A tile to fabricate: an outline of a size, a frame, and a stroked pattern.

    See :class:`fabtiles.geometry.tile.TileGeometry` for the geometry. Construction also
    checks the work limits (:data:`fabtiles._limits.CLI_LIMITS`) from the
    parameters alone, before any geometry is built.

    >>> import fabtiles as ft
    >>> tile = ft.Tile("square", 60, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-3")),
    ...                frame=3, stroke=1.0)
    >>> tile.region().is_valid
    True
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        _limits.check_tile(self.pattern, self.width_mm, self.height_mm, _limits.CLI_LIMITS)

    def export(self, path, *, profile=None, **options):
        """Write the tile to ``path``; the suffix picks the format.

        ``.dxf`` and ``.svg`` take a laser profile (default ``laser-3mm-plywood``), or a CNC router's
        or waterjet's (``router-6mm-mdf``: the part as its bit makes it, see docs/cnc-and-waterjet.md),
        ``.stl``, ``.3mf`` and ``.step`` a printer profile (default ``fdm-0.4mm``).
        Options: laser ``mode``, ``dxf_version``, ``kerf_mm``; print ``style``, ``base_mm``,
        ``relief_mm``, ``pierced_mm``, ``deboss_mm``; both ``fill_small_holes`` (fill what the
        machine cannot make: holes narrower than the profile's ``min_hole_mm``); and for
        ``.3mf`` ``inlay`` (deboss: the grooves filled flush as a second part) and
        ``layout`` (``"volumes"``, default, one object of parts in PrusaSlicer, Bambu
        Studio and OrcaSlicer; ``"components"``, for UltiMaker Cura).
        The file is written atomically: on any error nothing is left behind.

        Returns
        -------
        Report
            What was written and what the fabrication checks found.
        """
        from .build import export_tile

        return export_tile(self, path, profile=profile, **options)
