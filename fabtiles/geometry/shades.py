"""Shaded engraving: each face class engraved on a layer of its own, darker colours burnt harder.

One sheet of wood shows a palette as shades of brown: a face class is engraved at a
power that grows with its colour's darkness, ``1 - L*/100`` (CIE L*, the lightness the eye
sees, from the colour's sRGB). The power runs linearly between the profile engrave layer's
``power_range_pct`` (lightest, darkest; default a quarter of its ``power_pct`` to its
``power_pct``), rounded to a whole percent, at the layer's speed and line interval: the energy a
square millimetre gets, ``power / (speed * line_interval)``, is then linear in the darkness, and
a burn darkens with its energy per area. A class's ``power_pct``, ``speed_mm_s``,
``line_interval_mm`` or ``passes`` given in ``[colour.shades]`` replace the derived ones.

Each class's layer is ``SHADE_<letter>`` in an AutoCAD colour of its own (:data:`SHADE_ACI`: none
of the cut's red, the score's blue, the fill's magenta, black, white or grey, so MeerK40t gives
each its own engrave operation; the names hold neither ``CUT`` nor ``ENGRAVE``, which MeerK40t
reads as operations). LightBurn has 30 layers: at most :data:`MAX_SHADES` classes are shaded, the
others being the fill's, the score's and the two cuts'.

>>> from fabtiles.machines.profiles import load_profile
>>> ply = load_profile("laser-3mm-plywood")
>>> [(s.name, s.power_pct) for _, s in shade_layers(ply, [("A", (0.0, 0.0, 0.0)), ("B", (1.0, 1.0, 1.0))])]
[('SHADE_A', 20.0), ('SHADE_B', 5.0)]
"""

from __future__ import annotations

import math
from dataclasses import replace

from ..core.errors import ParameterError
from .laser_checks import engrave_layer

SHADE_ACI = (3, 4, 2, 30, 150, 210, 40, 110, 190, 230, 70, 130, 90, 170, 240, 50, 120, 200, 60, 140, 180, 220, 80, 160)
"""The AutoCAD colours of the shaded layers, in class order: distinct, and none of red (a cut), blue
5 (the score), magenta 6 (the fill), white 7, black or grey, which MeerK40t sends elsewhere."""

MAX_SHADES = len(SHADE_ACI)
"""The most classes a file shades: LightBurn's 30 layers, less the fill, the score and the two cuts, and
two to spare for a profile's own colours."""

SHADE_KEYS = ("power_pct", "speed_mm_s", "line_interval_mm", "passes")
"""What ``[colour.shades]`` may set for a class."""


def darkness(srgb) -> float:
    """``1 - L*/100`` of an sRGB colour (each channel 0 to 1): 0 for white, 1 for black.

    >>> round(darkness((0.5, 0.5, 0.5)), 3), darkness((1.0, 1.0, 1.0)), darkness((0.0, 0.0, 0.0))
    (0.466, 0.0, 1.0)
    """
    lin = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in srgb]
    y = 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]
    lightness = 116 * y ** (1 / 3) - 16 if y > (6 / 29) ** 3 else y * (29 / 3) ** 3
    return min(1.0, max(0.0, 1.0 - lightness / 100))


def shade_power(dark: float, span) -> float:
    """The power (%, whole) of a class of darkness ``dark`` in ``span`` (lightest, darkest).

    >>> shade_power(0.5, (10.0, 30.0)), shade_power(0.0, (10.0, 30.0))
    (20.0, 10.0)
    """
    low, high = span
    return float(max(1, math.floor(low + dark * (high - low) + 0.5)))


def shade_layers(profile, classes, overrides=None) -> tuple:
    """``((letter, Layer), ...)`` of the shaded classes ``classes`` (``(letter, srgb)`` pairs).

    ``overrides`` maps a letter to its ``[colour.shades]`` table. Raises a
    :class:`~fabtiles.ParameterError` for more classes than :data:`MAX_SHADES`, an override of a
    letter not among ``classes``, an unknown key or a value out of its range; a
    :class:`~fabtiles.ProfileError` for a profile without an engrave layer.
    """
    fill = engrave_layer(profile)
    classes = list(classes)
    if len(classes) > MAX_SHADES:
        raise ParameterError(
            f"[colour] shaded names {len(classes)} face classes, more than the {MAX_SHADES} layers a laser "
            f"file holds besides its cuts (LightBurn's 30); give fewer classes in [colour] shaded",
            param="colour.shaded",
        )
    overrides = dict(overrides or {})
    letters = [letter for letter, _ in classes]
    unknown = [k for k in overrides if k not in letters]
    if unknown:
        raise ParameterError(
            f"[colour.shades] {unknown[0]} is not an engraved face class (engraved: {', '.join(letters) or 'none'})",
            param=f"colour.shades.{unknown[0]}",
        )
    span = fill.shade_range_pct
    out = []
    for k, (letter, srgb) in enumerate(classes):
        layer = replace(
            fill,
            name=f"SHADE_{letter}",
            color=SHADE_ACI[k],
            power_pct=shade_power(darkness(srgb), span),
            power_range_pct=None,
        )
        out.append((letter, replace(layer, **checked_override(letter, overrides.get(letter, {})))))
    return tuple(out)


def checked_override(letter: str, table) -> dict:
    """A class's ``[colour.shades]`` table checked: known keys, each in its range."""
    where = f"colour.shades.{letter}"
    if not isinstance(table, dict):
        raise ParameterError(f"[{where}] must be a table like {{ power_pct = 40 }}, got {table!r}", param=where)
    bad = [k for k in table if k not in SHADE_KEYS]
    if bad:
        raise ParameterError(
            f"[{where}] has an unknown key {bad[0]!r} (valid keys: {', '.join(SHADE_KEYS)})", param=f"{where}.{bad[0]}"
        )
    out = {}
    for key, value in table.items():
        number = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
        if key == "passes":
            ok, want = isinstance(value, int) and not isinstance(value, bool) and value >= 1, "a whole number >= 1"
        elif key == "power_pct":
            ok, want = number and 0 < value <= 100, "a percentage > 0 and <= 100"
        else:
            ok, want = number and value > 0, "a number > 0"
        if not ok:
            raise ParameterError(f"{where}.{key} must be {want}, got {value!r}", param=f"{where}.{key}")
        out[key] = value if key == "passes" else float(value)
    return out


def shared_powers(layers) -> list:
    """The groups of classes (letters) whose derived settings came out the same: a report's note each.

    >>> from fabtiles.machines.profiles import Layer
    >>> a = Layer("SHADE_A", 3, power_pct=10.0)
    >>> shared_powers([("A", a), ("B", replace(a, name="SHADE_B")), ("C", replace(a, power_pct=12.0))])
    [('A', 'B')]
    """
    seen: dict = {}
    for letter, layer in layers:
        key = (layer.power_pct, layer.speed_mm_s, layer.line_interval_mm, layer.passes)
        seen.setdefault(key, []).append(letter)
    return [tuple(v) for v in seen.values() if len(v) > 1]


WOOD = "#e6cb9c"
"""Bare plywood, as a picture of a shaded engraving draws the unburnt wood."""

CHAR = "#2e1a0e"
"""The darkest burn a picture draws: the profile's darkest power."""


def burn_colour(power_pct: float, darkest_pct: float) -> str:
    """How a picture draws wood engraved at ``power_pct``: from :data:`WOOD` to :data:`CHAR`, reached at
    ``darkest_pct`` (the engrave layer's darkest power).

    >>> burn_colour(0.0, 20.0), burn_colour(20.0, 20.0), burn_colour(10.0, 20.0)
    ('#e6cb9c', '#2e1a0e', '#8a7255')
    """
    t = min(1.0, max(0.0, power_pct / darkest_pct))
    ends = [[int(c[i : i + 2], 16) for i in (1, 3, 5)] for c in (WOOD, CHAR)]
    mixed = [round(a + t * (b - a)) for a, b in zip(*ends, strict=True)]
    return "#" + "".join(f"{v:02x}" for v in mixed)
