"""Query parameters of the web API, flattened from the design file's keys.

``?preset=table3-3&radius=15&width=150`` becomes the same nested dictionary a
design file holds (``docs/design-files.md``), so the web app and ``fabtiles build`` share
one validation path. Problems raise :class:`QueryError`, which names the field.

>>> design = design_from_query({"n": "8", "radii": "51,70,172", "packing": "none", "width": "100"})
>>> design["motif"], design["tile"]["size"]
({'n': 8, 'radii': [51.0, 70.0, 172.0]}, [100.0, 100.0])
"""

from __future__ import annotations

import math

from .._errors import FabtilesError
from .._profiles import bundled_profiles


class QueryError(FabtilesError, ValueError):
    """A query parameter is malformed; ``field`` names it."""

    def __init__(self, message: str, field: str):
        super().__init__(message)
        self.field = field


def _number(field, text, *, integer=False):
    try:
        value = float(text)
    except (TypeError, ValueError):
        kind = "an integer" if integer else "a number"
        raise QueryError(f"{field} must be {kind}, got {text!r}", field) from None
    if not math.isfinite(value):
        raise QueryError(f"{field} must be a finite number, got {text!r}", field)
    if integer:
        if not value.is_integer():
            raise QueryError(f"{field} must be an integer, got {text!r}", field)
        return int(value)
    return value


def _numbers(field, text):
    parts = [p for p in str(text).replace(" ", "").split(",") if p]
    if not parts:
        raise QueryError(f"{field} must be comma-separated numbers like 51,70,172, got {text!r}", field)
    return [_number(field, p) for p in parts]


def parse_flag(field, text):
    """``true``/``false`` (also 1/0, yes/no, on/off) as a bool; anything else is a :class:`QueryError`.

    >>> parse_flag("findings", "on"), parse_flag("findings", "0")
    (True, False)
    """
    low = str(text).lower()
    if low in ("1", "true", "yes", "on"):
        return True
    if low in ("0", "false", "no", "off", ""):
        return False
    raise QueryError(f"{field} must be true or false, got {text!r}", field)


_flag = parse_flag


def _text(field, text):
    return str(text)


def _special(field, text):
    return None if str(text).lower() in ("", "none") else _number(field, text, integer=True)


# query key -> (section, design key, parser)
FIELDS = {
    "preset": ("motif", "preset", _text),
    "n": ("motif", "n", lambda f, t: _number(f, t, integer=True)),
    "radii": ("motif", "radii", _numbers),
    "alpha": ("motif", "alpha", _number),
    "spr": ("motif", "spr", _number),
    "special": ("motif", "special", _special),
    "rotation": ("motif", "rotation", _number),
    "packing": ("packing", "kind", _text),
    "radius": ("packing", "radius", _number),
    "fill": ("packing", "fill", _number),
    "outline_circles": ("packing", "outline_circles", _flag),
    "gap_n": ("gap_motif", "n", lambda f, t: _number(f, t, integer=True)),
    "gap_radii": ("gap_motif", "radii", _numbers),
    "gap_preset": ("gap_motif", "preset", _text),
    "gap_alpha": ("gap_motif", "alpha", _number),
    "gap_spr": ("gap_motif", "spr", _number),
    "gap_special": ("gap_motif", "special", _special),
    "gap_rotation": ("gap_motif", "rotation", _number),
    "seamless": ("packing", "seamless", _flag),
    "tiling": ("packing", "tiling", _text),
    "edge": ("packing", "edge", _number),
    **{f"motif_{p}": ("motifs", str(p), _text) for p in (3, 4, 6, 8, 12)},
    "outline": ("tile", "outline", _text),
    "width": ("tile", "width", _number),
    "height": ("tile", "height", _number),
    "frame": ("tile", "frame", _number),
    "stroke": ("tile", "stroke", _number),
    "join": ("tile", "join", _text),
    "corner_radius": ("tile", "corner_radius", _number),
    "miter_limit": ("tile", "miter_limit", _number),
    "interlace": ("tile", "interlace", _flag),
    "interlace_gap_mm": ("tile", "interlace_gap_mm", _number),
    "interlace_cut": ("tile", "interlace_cut", _flag),
    "laser_profile": ("output", "laser_profile", _text),
    "printer_profile": ("output", "printer_profile", _text),
    "laser_mode": ("output", "laser_mode", _text),
    "print_style": ("output", "print_style", _text),
    "fill_small_holes": ("output", "fill_small_holes", _flag),
    "inlay": ("output", "inlay", _flag),
    "threemf_layout": ("output", "threemf_layout", _text),
    "inlay_fit_mm": ("output", "inlay_fit_mm", _number),
    "inlay_base": ("output", "inlay_base", _text),
    "base_mm": ("output", "base_mm", _number),
    "relief_mm": ("output", "relief_mm", _number),
    "pierced_mm": ("output", "pierced_mm", _number),
    "deboss_mm": ("output", "deboss_mm", _number),
    "name": ("output", "name", _text),
}

DEFAULTS = {
    "preset": "table3-3",
    "packing": "hex",
    "radius": "15",
    "outline": "square",
    "width": "150",
    "frame": "5",
    "stroke": "1",
    "fill_small_holes": "true",
}
"""What the page starts with: the paper's third tiling result on a 150 mm square.

Holes too small for the machines are filled by default, as the flagship sample
``samples/table3-3.toml`` does: the default tile has 680 holes under the plywood
profile's 1.2 mm, and the bridges between them are as thin as 0.155 mm; filled, the
DXF cuts cleanly, and the print's openings under the printer's ``min_hole_mm`` are
filled likewise. ``fill_small_holes=false`` keeps them (and reports them).
"""

NOT_WEB_PARAMS = {("output", "formats")}
"""Design keys with no query parameter, and why: each download is one format (the
design TOML from the app lists them all)."""


def design_from_query(query) -> dict:
    """Turn flat query parameters into a nested design dictionary (``docs/design-files.md``).

    Unknown parameters are an error naming the parameter and the valid ones.
    """
    design: dict = {"motif": {}, "packing": {}, "tile": {}, "output": {}}
    gap: dict = {}
    motifs: dict = {}  # packing=archimedean: a preset per polygon kind (motif_8=table3-3)
    for key, raw in query.items():
        if key not in FIELDS:
            raise QueryError(
                f"{key!r} is not a valid parameter, must be one of: {', '.join(FIELDS)}", key
            )
        section, name, parse = FIELDS[key]
        value = parse(key, raw)
        if section == "motifs":
            if value not in ("", "default"):
                motifs[name] = value
            continue
        (gap if section == "gap_motif" else design[section])[name] = value
    motif = design["motif"]
    if "preset" in motif and motif["preset"] == "":
        del motif["preset"]
    if motif.get("special", 0) is None:
        del motif["special"]
    if gap.get("special", 0) is None:
        del gap["special"]
    if design["packing"].get("kind", "hex") == "none":
        if gap or motifs or len(design["packing"]) > 1:
            extra = sorted(k for k in query if FIELDS[k][0] in ("packing", "gap_motif", "motifs") and k != "packing")
            raise QueryError(f"{extra[0]} has no meaning with packing=none; remove it or choose packing=hex or square", extra[0])
        del design["packing"]
    if motifs and "packing" in design:
        if design["packing"].get("kind") != "archimedean":
            first = f"motif_{next(iter(motifs))}"
            raise QueryError(f"{first} is a motif per polygon kind of packing=archimedean; remove it or "
                             f"choose packing=archimedean", first)
        design["packing"]["motifs"] = motifs
    if "packing" in design and gap:
        if "preset" not in gap:  # one of n / radii alone: the other from the default gap motif
            gap = {"n": 6, "radii": [0.5, 1.0], **gap}
        design["packing"]["gap_motif"] = gap
    for key, family in (("laser_profile", "laser"), ("printer_profile", "printer")):
        name = design["output"].get(key)
        if name is not None and name not in (names := bundled_profiles(family)):
            # Profiles are chosen by bundled name only: no file path ever comes from a request.
            raise QueryError(f"{key} {name!r} is not a bundled profile, must be one of: {', '.join(names)}", key)
    tile = design["tile"]
    width, height = tile.pop("width", None), tile.pop("height", None)
    if width is not None or height is not None:
        if width is None:
            raise QueryError("width is missing: give width (and height for a rectangle)", "width")
        tile["size"] = [width, height if height is not None else width]
    return {k: v for k, v in design.items() if v or k == "tile"}
