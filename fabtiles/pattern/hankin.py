"""Hankin's "polygons in contact" on a regular polygon (``docs/hankin.md``).

Pure numpy. E. H. Hankin's construction as C. S. Kaplan formalised it (Islamic Star
Patterns from Polygons in Contact, Graphics Interface 2005): two rays leave each edge
of a polygon near its midpoint, each at the *contact angle* to the edge, leaning
towards one end of the edge; each ray stops where it meets the ray from the adjacent
edge that leans towards the same corner. On a regular p-gon that meeting point lies
on the corner's bisector, so a ray's length is found by the sine rule in the
triangle (corner, ray start, meeting point).

With a *contact gap* ``g`` the two rays of an edge start ``g`` apart, ``g / 2`` each
side of the midpoint, and each starts on the side away from the corner it leans
towards (the two rays cross just inside the edge), as in Taprats and the patterns
drawn after Kaplan's paper; so both rays leaning to a corner start ``(a + g) / 2`` from it.

The rays of a p-gon always meet on the bisector between the corner and the centre when
``g = 0`` (at the centre as the angle nears 90 degrees); with a gap the meeting point
passes the centre once ``g / a > cot(angle) cot(pi / p)``. Such an angle has no pattern
(the rays of opposite corners would overlap): :func:`max_contact_angle` gives the
limit and :func:`check_contact` refuses it, naming the valid range. On the way to its
partner a ray may cross other rays of the polygon (large angles on polygons of many
sides): it is *extended* across them to its partner, as in Kaplan's construction,
never stopped at the first crossing, so the strands stay whole.

>>> rays = polygon_rays(4, 2.0, 45.0)
>>> rays.shape, rays[0].round(6).tolist()
((4, 2, 2, 2), [[[1.0, 0.0], [0.5, 0.5]], [[1.0, 0.0], [0.5, -0.5]]])
"""

from __future__ import annotations

import math

import numpy as np

from ..core.errors import ParameterError
from ..core.schema import register_check, register_choices
from ..core.validate import check_float
from .tilings import inradius

METHODS = ("motifs", "hankin")
"""The constructions of an Archimedean packing: the paper's motifs in the incircles, or Hankin's rays."""


def check_method(method) -> str:
    """``method`` checked against :data:`METHODS`.

    >>> check_method("hankin")
    'hankin'
    >>> check_method("kaplan")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: method = 'kaplan' is not valid, must be one of: motifs, hankin
    """
    if method not in METHODS:
        raise ParameterError(f"method = {method!r} is not valid, must be one of: {', '.join(METHODS)}", param="method")
    return method


def max_contact_angle(p: int, edge: float, gap: float) -> float:
    """The largest contact angle (degrees) whose rays meet inside a regular p-gon with a gap.

    90 without a gap; else ``atan(edge cot(pi / p) / gap)``.

    >>> max_contact_angle(8, 10, 0), round(max_contact_angle(3, 10, 5), 4)
    (90.0, 49.1066)
    """
    if gap <= 0:
        return 90.0
    return math.degrees(math.atan(edge / (math.tan(math.pi / p) * gap)))


def check_contact(angle, gap, edge: float, kinds, tiling: str, *, name: str = "contact_angle") -> tuple[float, float]:
    """``(contact_angle, contact_gap)`` checked for the polygons ``kinds`` of ``tiling`` with ``edge``.

    ``name`` is the angle's key in the messages (``contact_angle_to`` for a parquet deformation's far side).

    >>> check_contact(60, 0, 10, (4, 8), "4.8.8")
    (60.0, 0.0)
    >>> check_contact(80, 5, 10, (3, 12), "3.12.12")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: contact_angle 80 has no pattern on the tiling 3.12.12 with contact_gap 5 mm: the rays of its 3-gons would meet past their centres; with this gap contact_angle must be > 0 and <= 49.1066, or contact_gap <= 1.01802 mm for this angle
    """  # noqa: E501 - a doctest's lines are as Python prints them
    angle = check_float(name, angle, low=0, high=90, low_open=True, high_open=True)
    gap = check_float("contact_gap", gap, low=0)
    if gap >= edge:
        raise ParameterError(
            f"contact_gap must be >= 0 and < the edge ({edge:g} mm) so both rays start on the edge, got {gap:g} mm",
            param="contact_gap",
        )
    for p in sorted(kinds):  # the triangles' limit is the smallest
        top = max_contact_angle(p, edge, gap)
        if angle > top * (1 + 1e-12):
            most = edge / (math.tan(math.radians(angle)) * math.tan(math.pi / p))
            raise ParameterError(
                f"{name} {angle:g} has no pattern on the tiling {tiling} with contact_gap {gap:g} mm: "
                f"the rays of its {p}-gons would meet past their centres; with this gap {name} must be "
                f"> 0 and <= {top:.6g}, or contact_gap <= {most:.6g} mm for this angle",
                param=name,
            )
    return angle, gap


def polygon_rays(p: int, edge: float, angle: float, gap: float = 0.0, turn: float = 0.0) -> np.ndarray:
    """The rays of a regular p-gon centred on the origin, ``(p, 2, 2, 2)``: edge, ray, start/end, xy.

    Edge ``k``'s midpoint lies at direction ``turn + 2 pi k / p`` (radians); its ray 0 leans
    towards the corner counter-clockwise of the midpoint, ray 1 towards the other. Across an
    edge shared by two polygons, ray 0 of one and ray 0 of the other lie on one line when
    ``gap = 0`` (the edge runs the other way round the second polygon), and so do the rays 1.
    """
    theta = math.radians(angle)
    half = math.pi / 2 - math.pi / p  # half the interior angle
    length = (edge + gap) / 2 * math.sin(half) / math.sin(half + theta)
    phi = turn + 2 * math.pi * np.arange(p) / p
    out = np.stack([np.cos(phi), np.sin(phi)], axis=1)  # outward normal = the midpoint's direction
    mid = inradius(p, edge) * out
    along = np.stack([-out[:, 1], out[:, 0]], axis=1)  # counter-clockwise along the edge
    rays = np.empty((p, 2, 2, 2))
    for r, sign in ((0, 1.0), (1, -1.0)):
        start = mid - sign * (gap / 2) * along
        direction = sign * math.cos(theta) * along - math.sin(theta) * out
        rays[:, r, 0] = start
        rays[:, r, 1] = start + length * direction
    return rays


PARQUET_DIRECTIONS = ("x", "y", "radial")
"""Across which a parquet deformation's angle changes: left to right (``x``), bottom to top (``y``),
or from the centre outwards (``radial``: the near side the centre, the far side the inscribed circle)."""

PARQUET_CURVES = ("linear", "smooth")
"""How the angle goes from one side to the other: in proportion, or by smoothstep ``3 t^2 - 2 t^3``
(flat at both sides, so the pattern settles into each end's angle)."""


def check_parquet(direction, curve) -> tuple[str, str]:
    """``(parquet_direction, parquet_curve)`` checked against their choices.

    >>> check_parquet("y", "smooth")
    ('y', 'smooth')
    >>> check_parquet("z", "linear")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: parquet_direction = 'z' is not valid, must be one of: x, y, radial
    """
    for name, value, valid in (
        ("parquet_direction", direction, PARQUET_DIRECTIONS),
        ("parquet_curve", curve, PARQUET_CURVES),
    ):
        if value not in valid:
            raise ParameterError(f"{name} = {value!r} is not valid, must be one of: {', '.join(valid)}", param=name)
    return direction, curve


def parquet_angles(centres, window, angle: float, angle_to: float, direction: str = "x", curve: str = "linear"):
    """The contact angle (degrees) of the polygons centred at ``centres`` ``(m, 2)`` in a parquet deformation.

    ``t`` runs from 0 at the window's near side (left for ``"x"``, bottom for ``"y"``, its centre for
    ``"radial"``) to 1 at its far side (``"radial"``: the circle inscribed in the window), clamped
    outside; the angle is ``angle + (angle_to - angle) f(t)``, ``f`` the curve.

    >>> parquet_angles([[-10, 0], [0, 0], [10, 0], [20, 0]], (-10, -5, 10, 5), 40, 80).tolist()
    [40.0, 60.0, 80.0, 80.0]
    >>> parquet_angles([[0, -2.5]], (-10, -5, 10, 5), 40, 80, "y", "smooth").round(4).tolist()
    [46.25]
    >>> parquet_angles([[0, 0], [3, 4], [0, 9]], (-10, -5, 10, 5), 40, 80, "radial").tolist()
    [40.0, 80.0, 80.0]
    """
    centres = np.asarray(centres, dtype=float).reshape(-1, 2)
    x0, y0, x1, y1 = (float(v) for v in window)
    if direction == "radial":
        x = np.hypot(centres[:, 0] - (x0 + x1) / 2, centres[:, 1] - (y0 + y1) / 2)
        low, high = 0.0, min(x1 - x0, y1 - y0) / 2
    else:
        axis = PARQUET_DIRECTIONS.index(direction)
        x, low, high = centres[:, axis], (x0, y0)[axis], (x1, y1)[axis]
    t = np.clip((x - low) / (high - low), 0.0, 1.0) if high > low else np.zeros(len(x))
    if curve == "smooth":
        t = t * t * (3 - 2 * t)
    return angle + (angle_to - angle) * t


def polygons_rays(p: int, edge: float, angles, gap: float, turns) -> np.ndarray:
    """:func:`polygon_rays` of ``m`` regular p-gons at once, each its own angle (degrees) and
    turn (radians), centred on the origin: ``(m, p, 2, 2, 2)``.

    The rays' starts depend on the edge alone, never on the angle, so two polygons sharing an edge
    start their rays there at the same points whatever their angles.
    """
    theta = np.radians(np.asarray(angles, dtype=float))[:, None, None]
    half = math.pi / 2 - math.pi / p
    length = (edge + gap) / 2 * math.sin(half) / np.sin(half + theta)
    phi = np.asarray(turns, dtype=float)[:, None] + 2 * math.pi * np.arange(p) / p  # (m, p)
    out = np.stack([np.cos(phi), np.sin(phi)], axis=-1)  # (m, p, 2)
    mid = inradius(p, edge) * out
    along = np.stack([-out[..., 1], out[..., 0]], axis=-1)
    rays = np.empty((len(phi), p, 2, 2, 2))
    for r, sign in ((0, 1.0), (1, -1.0)):
        start = mid - sign * (gap / 2) * along
        rays[:, :, r, 0] = start
        rays[:, :, r, 1] = start + length * (sign * np.cos(theta) * along - np.sin(theta) * out)
    return rays


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(METHODS, "packing.method")
register_check(check_method, "packing.method")
register_check(check_contact, "packing.contact_angle", "packing.contact_gap", "packing.contact_angle_to")
register_choices(PARQUET_DIRECTIONS, "packing.parquet_direction")
register_choices(PARQUET_CURVES, "packing.parquet_curve")
