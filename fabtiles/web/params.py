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
import re

from ..core import schema as _schema
from ..core.errors import FabtilesError
from ..machines.profiles import bundled_profiles


class QueryError(FabtilesError, ValueError):
    """A query parameter is malformed; ``field`` names it."""

    def __init__(self, message: str, field: str):
        super().__init__(message)
        self.field = field


def parse_number(field, text, *, integer=False):
    """A query field's number (an int with ``integer``); anything else a :class:`QueryError` naming it.

    >>> parse_number("edge", "12.5"), parse_number("n", "8", integer=True)
    (12.5, 8)
    """
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
    return [parse_number(field, p) for p in parts]


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


def _shade(field, text):
    """A class's ``[colour.shades]`` table from ``power_pct:40,line_interval_mm:0.08`` (empty: none given).

    >>> _shade("shade_B", "power_pct:40, passes:2")
    {'power_pct': 40.0, 'passes': 2}
    """
    table: dict = {}
    for item in (p for p in re.split(r"[,\s]+", str(text).strip()) if p):
        name, _, value = item.partition(":")
        try:
            table[name] = int(value) if name == "passes" else float(value)
        except ValueError:
            raise QueryError(
                f"{field} must be settings like power_pct:40,speed_mm_s:200, got {text!r}", field
            ) from None
    return table


def _special(field, text):
    return None if str(text).lower() in ("", "none") else parse_number(field, text, integer=True)


def _optional_flag(field, text):
    return None if str(text) == "" else parse_flag(field, text)


def _parser(k):
    """The query parser of a schema key, by its type (a select of integers also takes ``none``, a select of a
    boolean an empty value: not given)."""
    if k.type == "boolean" and k.widget is not None and k.widget.kind == "select":
        return _optional_flag
    if k.type == "integer":
        if k.widget is not None and k.widget.kind == "select":
            return _special
        return lambda f, t: parse_number(f, t, integer=True)
    return {"number": parse_number, "numbers": _numbers, "boolean": _flag}.get(k.type, _text)


def _motif_sides() -> tuple[int, ...]:
    from ..pattern.tilings import TILINGS, unit_cell

    return tuple(sorted({int(s) for t in TILINGS for s in unit_cell(t).sides.tolist()}))


FACE_LETTERS = tuple(chr(ord("A") + i) for i in range(26))
"""The face classes the web app colours by letter (``face_A`` ... ``face_Z``); a design file takes more."""

MOTIF_SIDES = _motif_sides()
"""The polygon kinds of the Archimedean tilings (3, 4, 6, 8, 12): packing=archimedean's ``motif_<sides>`` parameters."""


def _fields() -> dict:
    """Query parameter -> (section, design key, parser), from the schema (:mod:`fabtiles.core.schema`).

    A key's parameter is its name, with these exceptions: ``[packing] kind`` is ``packing``;
    ``[colour.faces]`` is ``face_<letter>`` (section ``faces``); ``[colour.shades]`` is ``shade_<letter>``
    (section ``shades``, ``power_pct:40,speed_mm_s:200``);
    the gap motif's keys are ``gap_<key>`` (section ``gap_motif``); ``[packing.motifs]`` is
    ``motif_<sides>`` (section ``motifs``); ``[tile] size`` is ``width`` and ``height``.
    """
    fields = {}
    for k in _schema.KEYS:
        if k.type == "motif":  # the gap motif: a parameter per motif key
            fields.update({f"gap_{m.name}": ("gap_motif", m.name, _parser(m)) for m in _schema.section_keys("motif")})
        elif k.type == "motifs":
            fields.update({f"motif_{p}": ("motifs", str(p), _text) for p in MOTIF_SIDES})
        elif k.type == "colours":  # [colour.faces]: a colour per class letter, face_A=navy
            fields.update({f"face_{letter}": ("faces", letter, _text) for letter in FACE_LETTERS})
        elif k.type == "shades":  # [colour.shades]: a class's engrave settings, shade_B=power_pct:40
            fields.update({f"shade_{letter}": ("shades", letter, _shade) for letter in FACE_LETTERS})
        elif k.type == "size":
            fields.update({"width": ("tile", "width", parse_number), "height": ("tile", "height", parse_number)})
        elif k.query is not None:
            fields[k.query] = (k.section, k.name, _parser(k))
    return fields


CLASS_TABLES = ("faces", "shades")
"""The ``[colour]`` tables keyed by class letter, a parameter per letter (``face_<letter>``, ``shade_<letter>``)."""

FIELDS = _fields()
"""Query parameter -> (section, design key, parser)."""


FLAT_ONLY = ("outline", "width", "height", "frame", "corner_radius", "border_mm")
"""The tile's parameters a cylinder takes none of: its tile is its unrolled strip, sized by ``diameter`` and
``length`` (``docs/surfaces.md``)."""

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

NOT_WEB_PARAMS = {(k.section, k.name) for k in _schema.KEYS if k.query is None and k.type == "formats"}
"""Design keys with no query parameter, and why: each download is one format (the
design TOML from the app lists them all)."""


def design_from_query(query) -> dict:
    """Turn flat query parameters into a nested design dictionary (``docs/design-files.md``).

    Unknown parameters are an error naming the parameter and the valid ones.
    """
    design, gap, motifs = _sections(query)
    motif = design["motif"]
    if "preset" in motif and motif["preset"] == "":
        del motif["preset"]
    if motif.get("special", 0) is None:
        del motif["special"]
    if gap.get("special", 0) is None:
        del gap["special"]
    _packing(design, gap, motifs, query)
    _check_profiles(design["output"])
    # colours are asked for when a [colour] key differs from its default (the page always sends its menus)
    colour = {k: v for k, v in design["colour"].items() if k in CLASS_TABLES or v != _schema.key(f"colour.{k}").default}
    design["colour"] = colour
    _tile_size(design["tile"])
    return {k: v for k, v in design.items() if v or k == "tile"}


def _sections(query) -> tuple[dict, dict, dict]:
    """The parameters parsed and sorted into the design's sections: ``(design, gap motif, motifs)``.

    ``motifs`` are packing=archimedean's presets per polygon kind (``motif_8=table3-3``).
    """
    design: dict = {"motif": {}, "packing": {}, "tile": {}, "output": {}, "colour": {}, "surface": {}}
    gap: dict = {}
    motifs: dict = {}
    for key, raw in query.items():
        if key not in FIELDS:
            raise QueryError(f"{key!r} is not a valid parameter, must be one of: {', '.join(FIELDS)}", key)
        section, name, parse = FIELDS[key]
        value = parse(key, raw)
        if value is None and section == "surface":  # a menu's "the default" (mirror=)
            continue
        if section == "motifs":
            if value not in ("", "default"):
                motifs[name] = value
            continue
        if section in CLASS_TABLES:
            if value not in ("", {}):
                design["colour"].setdefault(section, {})[name] = value
            continue
        (gap if section == "gap_motif" else design[section])[name] = value
    return design, gap, motifs


def _packing(design: dict, gap: dict, motifs: dict, query) -> None:
    """The packing section completed in place: dropped for packing=none (refusing its other keys), given
    its motifs per polygon kind (archimedean only) and its gap motif."""
    if design["packing"].get("kind", "hex") == "none":
        _refuse_with_no_packing(design["packing"], gap, motifs, query)
        del design["packing"]
    if motifs and "packing" in design:
        if design["packing"].get("kind") != "archimedean":
            first = f"motif_{next(iter(motifs))}"
            raise QueryError(
                f"{first} is a motif per polygon kind of packing=archimedean; remove it or choose packing=archimedean",
                first,
            )
        design["packing"]["motifs"] = motifs
    if "packing" in design and gap:
        if "preset" not in gap:  # one of n / radii alone: the other from the default gap motif
            gap = {**{k: list(v) if isinstance(v, tuple) else v for k, v in _schema.GAP_MOTIF.items()}, **gap}
        design["packing"]["gap_motif"] = gap


def _refuse_with_no_packing(packing: dict, gap: dict, motifs: dict, query) -> None:
    """Refuse a packing, gap motif or motif key given with packing=none, naming the first."""
    if gap or motifs or len(packing) > 1:
        extra = sorted(k for k in query if FIELDS[k][0] in ("packing", "gap_motif", "motifs") and k != "packing")
        raise QueryError(
            f"{extra[0]} has no meaning with packing=none; remove it or choose packing=hex or square", extra[0]
        )


def _check_profiles(output: dict) -> None:
    """Refuse a laser or printer profile that is not bundled."""
    for key, family in (("laser_profile", "laser"), ("printer_profile", "printer")):
        name = output.get(key)
        if name is not None and name not in (names := bundled_profiles(family)):
            # Profiles are chosen by bundled name only: no file path ever comes from a request.
            raise QueryError(f"{key} {name!r} is not a bundled profile, must be one of: {', '.join(names)}", key)


def _tile_size(tile: dict) -> None:
    """``width`` and ``height`` made the tile's ``size`` in place (a square when the height is missing)."""
    width, height = tile.pop("width", None), tile.pop("height", None)
    if width is not None or height is not None:
        if width is None:
            raise QueryError("width is missing: give width (and height for a rectangle)", "width")
        tile["size"] = [width, height if height is not None else width]
