"""The paper's "desired sketch": radii that put P(1,1)..P(S,1) on one straight ray."""

from __future__ import annotations

import math

from ..core.errors import ParameterError
from ..core.validate import check_float, check_int
from .star import MAX_CIRCLES, MAX_N


def straight_radii(n, r1, r2, count) -> tuple[float, ...]:
    """Radii of ``count`` circles whose first points are collinear (paper section 4.3).

    ``r(w)`` for ``w >= 3`` is where the line through ``P(1,1)`` and ``P(2,1)``
    meets the ray at angle ``(w - 1) * 180 / n``. The paper's closed formula is
    garbled; this is the intersection it describes.

    Parameters
    ----------
    n : int
        Points per circle, 3 to 120.
    r1, r2 : float
        Radii of the first two circles, > 0.
    count : int
        Number of radii to return, 2 to 24.

    Returns
    -------
    tuple of float
        ``count`` radii, mm, starting with ``r1`` and ``r2``.

    Raises
    ------
    ParameterError
        When the line never reaches the ray of some circle (parallel to it, or
        meeting it behind the centre); the message names that circle.

    Examples
    --------
    >>> [round(r, 3) for r in straight_radii(n=8, r1=51, r2=70, count=3)]
    [51.0, 70.0, 147.303]
    """
    n = check_int("n", n, low=3, high=MAX_N)
    r1 = check_float("r1", r1, low=0, low_open=True)
    r2 = check_float("r2", r2, low=0, low_open=True)
    count = check_int("count", count, low=2, high=MAX_CIRCLES)
    step = math.pi / n
    ax, ay = r1, 0.0
    dx, dy = r2 * math.cos(step) - ax, r2 * math.sin(step) - ay
    radii = [r1, r2]
    for w in range(3, count + 1):
        phi = (w - 1) * step
        ux, uy = math.cos(phi), math.sin(phi)
        # Solve A + t*D = s*U for s:  s = cross(A, D) / cross(U, D).
        denom = ux * dy - uy * dx
        s = (ax * dy - ay * dx) / denom if abs(denom) > 1e-12 * math.hypot(dx, dy) else math.inf
        if not math.isfinite(s) or s <= 0:
            ray = f"the ray of circle {w} (at {math.degrees(phi):g} degrees)"
            why = f"is parallel to {ray}" if not math.isfinite(s) else f"meets {ray} only behind the centre"
            raise ParameterError(
                f"straight_radii: circle {w} cannot be reached: the line through P(1,1) and P(2,1) "
                f"{why}; use fewer circles (count <= {w - 1}) or change r1/r2 "
                f"(n={n}, r1={r1:g}, r2={r2:g})"
            )
        radii.append(s)
    return tuple(radii)
