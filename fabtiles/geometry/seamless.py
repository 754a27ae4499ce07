"""Seamless tiles: fit the packing radius so a tile is an exact period of the packing.

Periods (SPEC section 2): the hex packing repeats every ``2R`` across and
``2 sqrt(3) R`` up; the square packing every ``2R`` both ways. A rectangle
``W x H`` is seamless when ``W = 2R m`` and ``H = 2 sqrt(3) R k`` (hex) or
``H = 2R k`` (square); a pointy-top hexagon of across-flats ``2R m`` centred on a
lattice point is seamless with the hex packing (its neighbours sit at
``(2R m, 0)`` and ``(R m, sqrt(3) R m)``, both lattice vectors). Tiles laid edge to
edge then continue each other's pattern; use ``frame=0`` for them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._errors import ParameterError
from .._validate import check_choice, check_float
from .tile import OUTLINES, _check_size


@dataclass(frozen=True)
class SeamlessFit:
    """A seamless radius and tile size.

    Attributes
    ----------
    radius : float
        Packing radius R, mm.
    size : tuple of float
        Tile size to use: ``(W, H)`` for a rectangle, ``(s, s)`` otherwise. The
        width is the one asked for; a rectangle's height is moved to the nearest
        period.
    repeats : tuple of int
        ``(m, k)``: packing periods across and up the tile (for a hexagon, ``m``
        big circles across flats and ``k == m``).
    """

    radius: float
    size: tuple[float, float]
    repeats: tuple[int, int]


def seamless_fit(outline, size, radius, *, packing="hex") -> SeamlessFit:
    """The radius nearest to ``radius`` that makes the tile an exact period of the packing.

    The width ``W`` is kept and ``R = W / (2 m)`` with ``m`` the nearest whole
    number of periods (at least 1). For a rectangle the height then moves to the
    nearest whole number ``k`` of vertical periods (``2 sqrt(3) R`` hex, ``2R``
    square). A square with the square packing and a pointy-top hexagon with the
    hex packing keep their size.

    Parameters
    ----------
    outline : {"square", "rectangle", "hexagon"}
    size : float or (float, float)
        As for :class:`~fabtiles.geometry.tile.Tile`, mm.
    radius : float
        The packing radius wanted, mm (> 0).
    packing : {"hex", "square"}

    Raises
    ------
    ParameterError
        For outlines that cannot be periods of the packing: circles, squares with
        the hex packing (``2R`` and ``2 sqrt(3) R`` are incommensurable: use a
        rectangle or a hexagon) and hexagons with the square packing.

    Examples
    --------
    >>> fit = seamless_fit("rectangle", (200, 150), 12.5)
    >>> round(fit.radius, 4), tuple(round(v, 3) for v in fit.size), fit.repeats
    (12.5, (200.0, 129.904), (8, 3))
    >>> seamless_fit("hexagon", 150, 13).radius
    12.5
    """
    outline = check_choice("outline", outline, OUTLINES)
    packing = check_choice("packing", packing, ("hex", "square"))
    w, h = _check_size(outline, size)
    radius = check_float("radius", radius, low=0, low_open=True)
    if outline == "circle":
        raise ParameterError("a circle outline cannot be seamless (circles do not tile the plane); "
                             "use a rectangle, square or hexagon")
    if outline == "square" and packing == "hex":
        raise ParameterError("a square tile cannot be seamless with the hex packing (periods 2R and "
                             "2*sqrt(3)*R are incommensurable); use outline 'rectangle' or 'hexagon'")
    if outline == "hexagon" and packing == "square":
        raise ParameterError("a hexagon tile cannot be seamless with the square packing; "
                             "use the hex packing or a square/rectangle outline")
    m = max(1, round(w / (2 * radius)))
    r = w / (2 * m)
    if outline == "rectangle":
        up = 2 * math.sqrt(3) * r if packing == "hex" else 2 * r
        k = max(1, round(h / up))
        return SeamlessFit(radius=r, size=(w, k * up), repeats=(m, k))
    return SeamlessFit(radius=r, size=(w, w), repeats=(m, m))


def seamless_radius(outline, size, radius, *, packing="hex") -> float:
    """Just the radius of :func:`seamless_fit` (the rectangle's height may need moving too).

    >>> seamless_radius("square", 100, 7, packing="square")
    7.142857142857143
    """
    return seamless_fit(outline, size, radius, packing=packing).radius
