"""What a design uses: filament for a print, sheet for a laser job, and their cost.

A print's filament is its volume at the profile's ``filament_density_g_cm3`` (default
PLA, 1.24 g/cm^3), as a length of ``filament_diameter_mm`` (default 1.75 mm):
``mass = volume * density`` and ``length = volume / (pi * (d / 2)^2)``. The volume is
the checked mesh's (the file's), per part for a two-colour 3MF. A laser job's sheet is
the outline's bounding box. A cost is given only when the profile has a price
(``price_per_kg`` for filament, ``price_per_m2`` for sheet), in the profile's own
currency. Print time is the slicer's to tell (it depends on its settings): fabtiles
does not estimate it.

>>> from fabtiles.machines.profiles import load_profile
>>> print(filament({"base": 3200.0, "pattern": 1228.9}, load_profile("fdm-0.4mm")).line())
5.49 g of filament, 1.84 m (base 3.97 g, pattern 1.52 g)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Filament:
    """A print's filament: volume (mm^3), mass (g), length (m) in all and per part, cost if priced."""

    volume_mm3: float
    mass_g: float
    length_m: float
    parts: dict = field(default_factory=dict)
    """Per part (a 3MF's ``base`` and ``pattern``): ``{"mass_g": ..., "length_m": ...}``."""
    cost: float | None = None

    def line(self) -> str:
        """``9.8 g of filament, 3.3 m`` (per part in brackets where there are several; the cost last)."""
        text = f"{self.mass_g:.3g} g of filament, {self.length_m:.3g} m"
        if len(self.parts) > 1:
            text += " (" + ", ".join(f"{n} {p['mass_g']:.3g} g" for n, p in self.parts.items()) + ")"
        if self.cost is not None:
            text += f", cost {self.cost:.2f}"
        return text

    def as_stats(self) -> dict:
        return {
            "volume_mm3": round(self.volume_mm3, 3),
            "mass_g": round(self.mass_g, 3),
            "length_m": round(self.length_m, 4),
            "parts": self.parts,
            "cost": None if self.cost is None else round(self.cost, 4),
            "line": self.line(),
        }


def filament(volumes: dict, profile) -> Filament:
    """The filament of a print whose parts have ``volumes`` (name -> mm^3), with ``profile``'s density."""
    area = math.pi * (profile.filament_diameter_mm / 2) ** 2

    def of(v):
        return {"mass_g": round(v / 1000 * profile.filament_density_g_cm3, 3), "length_m": round(v / area / 1000, 4)}

    total = float(sum(volumes.values()))
    mass = total / 1000 * profile.filament_density_g_cm3
    cost = None if profile.price_per_kg is None else mass / 1000 * profile.price_per_kg
    return Filament(total, mass, total / area / 1000, {n: of(v) for n, v in volumes.items()}, cost)


def stack_volume(region_area: float, outline_area: float, stack) -> float:
    """A print's volume from its areas (mm^2) and heights, before any mesh (``fabtiles check``).

    >>> from types import SimpleNamespace as S
    >>> stack_volume(10.0, 100.0, S(style="relief", base=2.0, relief=1.0, pierced=3.0, deboss=0.5))
    210.0
    """
    if stack.style == "relief":
        return outline_area * stack.base + region_area * stack.relief
    if stack.style == "pierced":
        return region_area * stack.pierced
    if stack.style == "mosaic":
        return outline_area * (stack.base + stack.relief) - (outline_area - region_area) * stack.inset
    return outline_area * stack.base - region_area * stack.deboss


def sheet(outline, profile) -> dict:
    """The sheet a laser job uses: the outline's bounding box (m^2), and its cost if priced."""
    xmin, ymin, xmax, ymax = outline.bounds
    m2 = (xmax - xmin) * (ymax - ymin) / 1e6
    cost = None if profile.price_per_m2 is None else m2 * profile.price_per_m2
    return {"sheet_m2": round(m2, 6), "cost": None if cost is None else round(cost, 4)}
