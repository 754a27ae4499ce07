"""fabtiles: Islamic star patterns turned into laser-cut and 3D-printable tiles.

The public API, fixed for scripts (``docs/file-conventions.md``), is exactly ``__all__``.

>>> import fabtiles as ft
>>> ft.Star(n=8, radii=(51, 70, 172)).segments().shape
(32, 2, 2)
"""

from .core.errors import (
    DesignError,
    FabricationError,
    FabtilesError,
    LimitError,
    ParameterError,
    ProfileError,
)
from .core.report import Report
from .designs.colour import Colours
from .designs.design_file import load_design
from .export.formats import Format
from .machines.profiles import CutterProfile, LaserProfile, PrinterProfile, load_profile
from .pattern.archimedean import ArchimedeanPacking, TilingPacking
from .pattern.girih import GirihPacking
from .pattern.packing import HexPacking, SquarePacking
from .pattern.radii import straight_radii
from .pattern.star import Star

# Names whose modules import shapely are loaded on first use, so that
# `import fabtiles` (and `fabtiles --help`) stays light.
_LAZY = {
    "Tile": "._tile",
    "nest": "._nesting",
    "SeamlessFit": ".geometry.seamless",
    "seamless_fit": ".geometry.seamless",
    "seamless_radius": ".geometry.seamless",
}


def __getattr__(name):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'fabtiles' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__version__ = "0.1.0"

__all__ = [
    "ArchimedeanPacking",
    "Colours",
    "CutterProfile",
    "DesignError",
    "FabricationError",
    "FabtilesError",
    "Format",
    "GirihPacking",
    "HexPacking",
    "LaserProfile",
    "LimitError",
    "ParameterError",
    "PrinterProfile",
    "ProfileError",
    "Report",
    "SeamlessFit",
    "SquarePacking",
    "Star",
    "Tile",
    "TilingPacking",
    "load_design",
    "load_profile",
    "nest",
    "seamless_fit",
    "seamless_radius",
    "straight_radii",
]
