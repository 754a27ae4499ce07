"""The printed part's style and heights: a :class:`Stack` of levels over the material.

Every 3D part fabtiles makes is a stack: the material region and the rest of the
outline raised to their own levels above a common bottom (relief: the pattern at
``b + h`` on a plate of ``b``; pierced: the pattern alone, ``t`` thick; deboss: a
plate of ``b`` with the pattern sunk ``d`` deep; mosaic: a plate of ``b`` with the bands and
every face of the pattern on it up to ``b + h``, the faces ``i`` lower). The printability checks
(:mod:`fabtiles.geometry.print_checks`), the design files and the mesh and STEP
writers all resolve a part's heights here.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..core.errors import ParameterError
from ..core.schema import key, register_check
from ..core.validate import check_choice, check_float
from ..machines.profiles import PRINT_STYLES, PrinterProfile, load_profile

QUANTUM = 2.0**-10
"""Grid of every x, y coordinate of a printed part (mm): about 1 micron, exact in float32 up to
16 m, so a binary STL stores the very vertices the mesh was checked with (see
:mod:`fabtiles.solid._mesh_build`); the STEP writer's vertices sit on the same grid."""

MAX_HEIGHT_MM = key("output.base_mm").bounds.max  # the schema's range of every print height
"""Largest base, relief, pierced or deboss height accepted (mm)."""


@dataclass(frozen=True)
class Stack:
    """The resolved style and heights of one printed part (mm).

    ``base`` is the plate thickness b (relief, deboss), ``relief`` the pattern
    height h above the plate (relief), ``pierced`` the thickness t (pierced),
    ``deboss`` the groove depth d (deboss), ``inset`` how far a mosaic's faces sit below
    its bands (mosaic; 0: flush), ``recess`` a shallow :class:`Recess` in the bottom face
    (None: the bottom is flat).
    """

    style: str
    base: float
    relief: float
    pierced: float
    deboss: float
    inset: float = 0.0
    recess: Recess | None = None

    @property
    def top(self) -> float:
        """Height of the highest point of the part."""
        return {
            "relief": self.base + self.relief,
            "pierced": self.pierced,
            "deboss": self.base,
            "mosaic": self.base + self.relief,
        }[self.style]

    def expected_volume(self, region_area: float, outline_area: float) -> float:
        """Volume of the part from the areas of the material region and the outline."""
        if self.style == "relief":
            return outline_area * self.base + region_area * self.relief
        if self.style == "pierced":
            return region_area * self.pierced
        if self.style == "mosaic":  # the bands to the top, the faces (the rest of the outline) inset
            return outline_area * (self.base + self.relief) - (outline_area - region_area) * self.inset
        return outline_area * self.base - region_area * self.deboss


@dataclass(frozen=True)
class Recess:
    """A shallow recess sunk into the bottom face of a printed part: a piece's number, mirrored so
    that it reads from below.

    ``region`` is (Multi)Polygons on the :data:`QUANTUM` grid, strictly inside the part's solid
    bottom (the outline of a relief, deboss or mosaic; the region of a pierced part), and
    ``depth`` (mm) less than the material over it. Its roof bridges the recess as the slicer
    lays the layer over it: nothing under it needs support.
    """

    region: Any
    depth: float

    @property
    def volume(self) -> float:
        """The material the recess takes away (mm^3)."""
        return float(self.region.area) * self.depth


def resolve_stack(
    profile, style=None, base_mm=None, relief_mm=None, pierced_mm=None, deboss_mm=None, mosaic_inset_mm=None
) -> Stack:
    """The style and heights of a part: the call's values, else the profile's.

    Parameters
    ----------
    profile : str, Path or PrinterProfile
        Printer profile giving the defaults.
    style : {"relief", "pierced", "deboss", "mosaic"}, optional
    base_mm, relief_mm, pierced_mm, deboss_mm : float, optional
        Heights in mm, each > 0 and at most ``MAX_HEIGHT_MM``; a deboss must be
        shallower than the plate.
    mosaic_inset_mm : float, optional
        A mosaic's faces below its bands (mm, >= 0 and below ``relief_mm``; default 0).

    Examples
    --------
    >>> resolve_stack("fdm-0.4mm", relief_mm=2).top
    4.0
    >>> resolve_stack("fdm-0.4mm", style="deboss", deboss_mm=2.5)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: deboss_mm must be smaller than base_mm (the plate is 2 mm thick), got 2.5
    >>> resolve_stack("fdm-0.4mm", style="mosaic", mosaic_inset_mm=2)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: mosaic_inset_mm must be smaller than relief_mm (the bands stand 1.2 mm above the plate), got 2
    """  # noqa: E501 - a doctest's lines are as Python prints them
    profile = load_profile(profile, kind="printer")
    assert isinstance(profile, PrinterProfile)
    style = check_choice("style", profile.print_style if style is None else style, PRINT_STYLES)
    values = {}
    for name, given in (
        ("base_mm", base_mm),
        ("relief_mm", relief_mm),
        ("pierced_mm", pierced_mm),
        ("deboss_mm", deboss_mm),
    ):
        value = getattr(profile, name) if given is None else given
        values[name] = check_float(name, value, low=0, low_open=True, high=MAX_HEIGHT_MM)
    if style == "deboss" and values["deboss_mm"] >= values["base_mm"]:
        raise ParameterError(
            f"deboss_mm must be smaller than base_mm (the plate is {values['base_mm']:g} mm thick), "
            f"got {values['deboss_mm']:g}",
            param="deboss_mm",
        )
    inset = check_float(
        "mosaic_inset_mm", 0.0 if mosaic_inset_mm is None else mosaic_inset_mm, low=0, high=MAX_HEIGHT_MM
    )
    if style == "mosaic" and inset >= values["relief_mm"]:
        raise ParameterError(
            f"mosaic_inset_mm must be smaller than relief_mm (the bands stand {values['relief_mm']:g} mm above the "
            f"plate), got {inset:g}",
            param="mosaic_inset_mm",
        )
    return Stack(
        style,
        values["base_mm"],
        values["relief_mm"],
        values["pierced_mm"],
        values["deboss_mm"],
        inset if style == "mosaic" else 0.0,
    )


# The schema names no module above it: the values and checks of its keys are registered from here.
register_check(resolve_stack, "output.mosaic_inset_mm")
