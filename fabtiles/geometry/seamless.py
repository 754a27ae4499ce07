"""Seamless tiles: fit the packing radius so a tile is an exact period of the packing.

Periods (``docs/tile-operation.md``): the hex packing repeats every ``2R`` across and
``2 sqrt(3) R`` up; the square packing every ``2R`` both ways. A rectangle
``W x H`` is seamless when ``W = 2R m`` and ``H = 2 sqrt(3) R k`` (hex) or
``H = 2R k`` (square); a pointy-top hexagon of across-flats ``2R m`` centred on a
lattice point is seamless with the hex packing (its neighbours sit at
``(2R m, 0)`` and ``(R m, sqrt(3) R m)``, both lattice vectors). Tiles laid edge to
edge then continue each other's pattern; use ``frame=0`` for them.

An Archimedean tiling (``packing="4.8.8"`` etc., the scale is then its edge ``a``)
repeats every ``(px a, py a)`` (:func:`~fabtiles.pattern.archimedean.rectangular_period`):
rectangles fit every tiling, squares those with ``px = py`` (4.4.4.4, 4.8.8,
3.3.4.3.4), hexagons those on a triangular lattice whose first vector ``(px a, 0)``
and second ``(px a / 2, px a sqrt(3) / 2)`` are the hexagon's neighbours for ``m = 1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.errors import ParameterError
from ..core.validate import check_choice, check_float
from ..pattern.archimedean import rectangular_period
from ..pattern.tilings import ALL_TILINGS, canonical, unit_cell
from .tile import OUTLINES, check_tile_size


@dataclass(frozen=True)
class SeamlessFit:
    """A seamless radius and tile size.

    Attributes
    ----------
    radius : float
        Packing radius R, mm (for an Archimedean tiling: its edge ``a``).
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

    @property
    def edge(self) -> float:
        """The same number under the name an Archimedean tiling uses: its edge ``a``, mm."""
        return self.radius


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
        As for :class:`~fabtiles.geometry.tile.TileGeometry`, mm.
    radius : float
        The packing radius wanted, mm (> 0); for a tiling, the edge wanted.
    packing : {"hex", "square"} or str
        Or a tiling of :meth:`~fabtiles.ArchimedeanPacking.tilings` (any form it takes).

    Returns
    -------
    SeamlessFit
        The radius (or edge), the tile size to use and the periods across and up.

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
    >>> fit = seamless_fit("square", 150, 20, packing="4.8.8")
    >>> round(fit.edge, 4), fit.repeats
    (20.7107, (3, 3))
    """
    outline = check_choice("outline", outline, OUTLINES)
    if isinstance(packing, str) and packing not in ("hex", "square") and packing.lstrip("[ ")[:1].isdigit():
        return _tiling_fit(outline, size, radius, canonical(packing))
    if not isinstance(packing, str) or packing not in ("hex", "square"):
        raise ParameterError(
            f"{packing!r} is not a valid packing, must be one of: hex, square, or a tiling ({', '.join(ALL_TILINGS)})",
            param="packing",
        )
    w, h = check_tile_size(outline, size)
    radius = check_float("radius", radius, low=0, low_open=True)
    _check_outline(outline, packing)
    m = max(1, round(w / (2 * radius)))
    r = w / (2 * m)
    if outline == "rectangle":
        up = 2 * math.sqrt(3) * r if packing == "hex" else 2 * r
        k = max(1, round(h / up))
        return SeamlessFit(radius=r, size=(w, k * up), repeats=(m, k))
    return SeamlessFit(radius=r, size=(w, w), repeats=(m, m))


def _check_outline(outline: str, packing: str) -> None:
    """Refuse an outline that cannot repeat with the packing's periods."""
    if outline == "circle":
        raise ParameterError(
            "a circle outline cannot be seamless (circles do not tile the plane); use a rectangle, square or hexagon",
            param="outline",
        )
    if outline == "square" and packing == "hex":
        raise ParameterError(
            "a square tile cannot be seamless with the hex packing (periods 2R and "
            "2*sqrt(3)*R are incommensurable); use outline 'rectangle' or 'hexagon'",
            param="outline",
        )
    if outline == "hexagon" and packing == "square":
        raise ParameterError(
            "a hexagon tile cannot be seamless with the square packing; "
            "use the hex packing or a square/rectangle outline",
            param="outline",
        )


def _tiling_fit(outline, size, edge, tiling) -> SeamlessFit:
    w, h = check_tile_size(outline, size)
    edge = check_float("edge", edge, low=0, low_open=True)
    px, py = rectangular_period(tiling)
    lat = unit_cell(tiling).lattice
    hexagonal = abs(lat[1, 0] - px / 2) < 1e-9 and abs(lat[1, 1] - px * math.sqrt(3) / 2) < 1e-9
    if outline == "circle":
        raise ParameterError(
            "a circle outline cannot be seamless (circles do not tile the plane); use a rectangle, square or hexagon",
            param="outline",
        )
    if outline == "square" and abs(px - py) > 1e-9:
        raise ParameterError(
            f"a square tile cannot be seamless with the tiling {tiling} (its periods "
            f"{px:.4g}a and {py:.4g}a are incommensurable); use outline 'rectangle'"
            + (" or 'hexagon'" if hexagonal else ""),
            param="outline",
        )
    if outline == "hexagon" and not hexagonal:
        raise ParameterError(
            f"a hexagon tile cannot be seamless with the tiling {tiling} (its lattice "
            f"is not triangular); use outline 'rectangle'" + (" or 'square'" if abs(px - py) < 1e-9 else ""),
            param="outline",
        )
    m = max(1, round(w / (px * edge)))
    a = w / (px * m)
    if outline == "rectangle":
        k = max(1, round(h / (py * a)))
        return SeamlessFit(radius=a, size=(w, k * py * a), repeats=(m, k))
    return SeamlessFit(radius=a, size=(w, w), repeats=(m, m))


def seamless_radius(outline, size, radius, *, packing="hex") -> float:
    """Just the radius of :func:`seamless_fit` (the rectangle's height may need moving too).

    Parameters
    ----------
    outline, size, radius, packing
        As for :func:`seamless_fit`.

    Returns
    -------
    float
        ``seamless_fit(...).radius``, mm.

    Examples
    --------
    >>> seamless_radius("square", 100, 7, packing="square")
    7.142857142857143
    """
    return seamless_fit(outline, size, radius, packing=packing).radius


def period_fit(outline, size, edge, period, what: str) -> SeamlessFit:
    """The edge nearest to ``edge`` that makes a rectangle an exact number of a pattern's rectangular
    ``period`` ``(px, py)`` (mm, at that ``edge``): the width kept, the height moved to whole periods.

    For a pattern whose two periods are incommensurable (a girih pattern's, with five-fold angles), so
    only a rectangle fits; ``what`` names the pattern in the message refusing another outline.

    >>> fit = period_fit("rectangle", (200, 100), 10, (49.8, 36.18), "the girih pattern decagon-bowtie")
    >>> round(fit.edge, 4), fit.repeats
    (10.0402, (4, 3))
    >>> period_fit("square", 100, 10, (49.8, 36.18), "the girih pattern decagon-bowtie")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: a square tile cannot be seamless with the girih pattern decagon-bowtie (its periods 49.8 and 36.18 mm are incommensurable); use outline 'rectangle'
    """  # noqa: E501 - a doctest's lines are as Python prints them
    outline = check_choice("outline", outline, OUTLINES)
    w, h = check_tile_size(outline, size)
    edge = check_float("edge", edge, low=0, low_open=True)
    px, py = (float(v) / edge for v in period)
    if outline != "rectangle":
        raise ParameterError(
            f"a {outline} tile cannot be seamless with {what} (its periods {px * edge:.4g} and {py * edge:.4g} mm "
            "are incommensurable); use outline 'rectangle'",
            param="outline",
        )
    m = max(1, round(w / (px * edge)))
    a = w / (px * m)
    k = max(1, round(h / (py * a)))
    return SeamlessFit(radius=a, size=(w, k * py * a), repeats=(m, k))
