"""fabtiles: Islamic star patterns turned into laser-cut and 3D-printable tiles.

The public API, fixed for scripts (SPEC section 6), is exactly ``__all__``.

>>> import fabtiles as ft
>>> ft.Star(n=8, radii=(51, 70, 172)).segments().shape
(32, 2, 2)
"""

from ._errors import (
    DesignError,
    FabricationError,
    FabtilesError,
    LimitError,
    ParameterError,
    ProfileError,
)
from .pattern.radii import straight_radii
from .pattern.star import Star

__version__ = "0.1.0"

__all__ = [
    "DesignError",
    "FabricationError",
    "FabtilesError",
    "LimitError",
    "ParameterError",
    "ProfileError",
    "Star",
    "straight_radii",
]
