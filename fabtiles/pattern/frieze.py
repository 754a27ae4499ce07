"""The motifs of a border's frieze, each drawn in one square cell (``docs/borders.md``).

Pure numpy. A cell is the square ``[-1, 1] x [-1, 1]``: ``x`` runs along the band,
``y`` across it (``-1`` the band's inner edge, ``+1`` its outer edge). Every motif is
symmetric under the square's eight turns and reflections, and its strands end on the
cell's edges at points mirrored across each edge's midpoint, so cells laid side by
side continue each other's lines and a corner cell reads the same from both sides.

``stars``: the paper's two-circle star (:class:`~fabtiles.pattern.star.Star`, ``n = 8``),
its four axial points on the edges' midpoints (touching the next star's point and the
band's edges), its four diagonal points joined to the cell's corners.
``hankin``: Hankin's polygons in contact on the square cell
(:func:`~fabtiles.pattern.hankin.polygon_rays`), two rays from each edge's midpoint at
the contact angle; a row of cells makes the classic frieze of eight-point stars and crosses.

>>> frieze_cell("stars").shape, frieze_cell("hankin", 67.5).shape
((20, 2, 2), (8, 2, 2))
"""

from __future__ import annotations

import functools

import numpy as np

from ..core.errors import ParameterError, did_you_mean
from ..core.schema import register_check, register_choices
from .hankin import polygon_rays
from .star import Star

FRIEZE_MOTIFS = ("stars", "hankin")
"""The motifs a border's frieze repeats."""

STAR_INNER = 0.5
"""The stars' inner circle, a fraction of the outer (the paper's default gap motif's)."""


def check_frieze_motif(motif) -> str:
    """``motif`` checked against :data:`FRIEZE_MOTIFS`.

    >>> check_frieze_motif("star")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: border_motif = 'star' is not valid (did you mean 'stars'?), must be one of: stars, hankin
    """  # noqa: E501 - a doctest's lines are as Python prints them
    if motif not in FRIEZE_MOTIFS:
        hint = did_you_mean(str(motif), FRIEZE_MOTIFS)
        raise ParameterError(
            f"border_motif = {motif!r} is not valid{f' ({hint})' if hint else ''}, "
            f"must be one of: {', '.join(FRIEZE_MOTIFS)}",
            param="border_motif",
        )
    return motif


@functools.lru_cache(maxsize=64)
def _cell(motif: str, angle: float) -> np.ndarray:
    # rounded, so that the ends meeting at a point are one point (the faces close, the strands join)
    if motif == "hankin":
        return np.round(polygon_rays(4, 2.0, angle).reshape(-1, 2, 2), 12) + 0.0
    star = Star(n=8, radii=(1.0, STAR_INNER)).segments()
    diagonal = np.array([1.0, 1.0]) / np.sqrt(2.0)
    signs = np.array([[1, 1], [-1, 1], [-1, -1], [1, -1]], dtype=float)
    spokes = np.stack([signs * diagonal, signs], axis=1)  # a diagonal point to its corner
    return np.round(np.concatenate([star, spokes]), 12) + 0.0


def frieze_cell(motif: str, angle: float = 67.5) -> np.ndarray:
    """The centre-lines ``(k, 2, 2)`` of ``motif`` in the cell ``[-1, 1]^2``; ``angle`` is hankin's (degrees)."""
    return _cell(check_frieze_motif(motif), float(angle)).copy()


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(FRIEZE_MOTIFS, "tile.border_motif")
register_check(check_frieze_motif, "tile.border_motif")
