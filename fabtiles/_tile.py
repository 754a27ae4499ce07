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

from .core import schema as _schema
from .geometry.tile import TileGeometry
from .machines import limits as _limits


class Tile(TileGeometry):
    """A tile to fabricate: an outline of a size, a frame, and a stroked pattern.

    See :class:`fabtiles.geometry.tile.TileGeometry` for the geometry. Construction also
    checks the work limits (:data:`fabtiles.machines.limits.CLI_LIMITS`) from the
    parameters alone, before any geometry is built, so a tile too large to make is refused
    at once rather than after minutes of work.

    Parameters
    ----------
    *args, **kwargs
        Those of :class:`~fabtiles.geometry.tile.TileGeometry`: ``outline``, ``size``,
        ``pattern``, ``frame``, ``stroke``, ``join`` and the keyword-only options.

    Raises
    ------
    ParameterError
        A parameter out of its range (the message names it, its value and the range).
    LimitError
        A tile larger than the work limits allow (its size, or its pattern's segments).

    Examples
    --------
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

        ``.dxf``, ``.svg`` and ``.lbrn2`` take a cutter profile (default ``laser-3mm-plywood``;
        a CNC router's or waterjet's, ``router-6mm-mdf``, writes the part as its bit makes it,
        see docs/cnc-and-waterjet.md), ``.stl``, ``.3mf`` and ``.step`` a printer profile
        (default ``fdm-0.4mm``). The keyword options, below, are those of design files'
        ``[output]`` section under the API's names; an option a format does not take is an
        error that lists the ones it does. The file is written atomically: on any error
        nothing is left behind.

        Returns
        -------
        Report
            What was written and what the fabrication checks found.

        """
        from .making import export_tile

        return export_tile(self, path, profile=profile, **options)


# help(Tile.export) lists every option from the schema of design keys, so it cannot drift
Tile.export.__doc__ = (
    (Tile.export.__doc__ or "").rstrip()
    + "\n\n"
    + "\n".join("        " + line for line in _schema.api_options_doc().splitlines())
    + "\n"
)
