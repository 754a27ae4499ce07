"""The gallery: places to start from, each a shareable editor query and a thumbnail.

The paper's seven presets on the default hexagonal packing (a smaller packing or
a wider stroke where the default's bands would be thinner than the default
profiles cut and print), their faces coloured by shape in the palettes
(``docs/colours.md``), and the eleven Archimedean
tilings as their samples in ``samples/tilings/`` have them (a test builds each
entry and its sample and compares the tiles, so the two cannot drift; the
samples have no colours, so neither have these entries), then four tilings by
Hankin's polygons in contact as ``samples/hankin/`` has them (compared likewise), and two
cylinders, a texture roller and a lampshade, as ``samples/roller-60x80.toml`` and
``samples/lampshade-120x150.toml`` have them (compared likewise), then the girih patterns of
``samples/girih-decagon-bowtie.toml`` and ``samples/classical/girih-subdivided.toml`` (compared
likewise), then two classical devices on Hankin's rays, a border of stars and a parquet deformation,
as ``samples/classical/`` has them (compared likewise). The thumbnails are
drawn by the preview code (:func:`~fabtiles.making.views.tile_picture`, the
coloured faces too; a cylinder's unrolled strip as it prints) and kept for the life of the process.

>>> [e.key for e in entries()][:3]
['table1-part1', 'table1-part2', 'table2-left']
>>> next(e for e in entries() if e.key == "4.8.8").query["motif_8"]
'table1-part1'
>>> entry("table1-part2").query["palette"]
'iznik'
>>> entry("hankin-4.8.8").query["contact_angle"]
'67.5'
>>> entry("roller").query["shape"], entry("lampshade").query["lamp_fitting_mm"]
('cylinder', '40')
>>> entry("parquet-4.8.8").query["contact_angle_to"], entry("border-4.8.8").query["border_mm"]
('75', '15')
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

from ..core.errors import ParameterError
from ..pattern.presets import PRESET_NOTES, PRESETS
from ..pattern.tilings import NAMES, TILINGS

# preset -> the palette its gallery entry is coloured in (by shape): each palette shown at least once
_PRESET_PALETTES = {
    "table1-part1": "zellige",
    "table1-part2": "iznik",
    "table2-left": "mamluk",
    "table2-right": "alhambra",
    "table3-1": "haft-rangi",
    "table3-2": "iznik",
    "table3-3": "zellige",
}

# preset -> packing radius and stroke (mm) where it differs from 15 and 1: each entry opens with no finding
# on the default profiles (a stroke of 1 leaves bridges under 1 mm where these presets' bands meet at a
# sharp angle; table2-left's long thin points need a smaller packing as well)
_PRESET_TILES = {
    "table1-part2": ("15", 1.5),
    "table2-left": ("10", 2),
    "table2-right": ("15", 1.5),
    "table3-2": ("15", 1.5),
}

_GAP_STAR: dict[str, Any] = {"n": 6, "radii": (0.5, 1)}  # a six-point star of radii 0.5 and 1, the tilings' small motif

# tiling -> edge (mm), preset per polygon kind, the motif above (for the kinds with none), gap motif,
# stroke (mm): the values of samples/tilings/<tiling>.toml
_TILINGS: dict[str, tuple[float, dict[int, str], dict[str, Any] | None, int | None, float]] = {
    "3.12.12": (9, {12: "table3-1"}, _GAP_STAR, None, 1),
    "3.3.3.3.3.3": (18, {}, _GAP_STAR, None, 1.2),
    "3.3.3.3.6": (12, {6: "table3-3"}, _GAP_STAR, 3, 1),
    "3.3.3.4.4": (16, {4: "table1-part1"}, _GAP_STAR, 4, 1),
    "3.3.4.3.4": (20, {4: "table1-part1"}, _GAP_STAR, None, 1),
    "3.4.6.4": (11, {6: "table3-3", 4: "table1-part1"}, _GAP_STAR, None, 1.2),
    "3.6.3.6": (18, {6: "table3-3"}, _GAP_STAR, 3, 1.2),
    "4.4.4.4": (18, {4: "table1-part1"}, None, 8, 1),
    "4.6.12": (8, {12: "table3-1", 6: "table3-3", 4: "table1-part1"}, None, None, 1),
    "4.8.8": (14, {8: "table1-part1"}, {"n": 8, "radii": (0.55, 1)}, None, 1),
    "6.6.6": (14.4, {6: "table3-3"}, None, None, 1),
}

# tiling -> contact angle (degrees), contact gap (mm): the values of samples/hankin/<tiling>.toml (edge 14,
# stroke 1); a contact gap of 0 is not sent
_HANKIN = {
    "4.8.8": (67.5, 0),
    "6.6.6": (60, 1.5),
    "3.12.12": (70, 0),
    "4.6.12": (60, 1),
}

# key -> two-uniform tiling, contact angle (degrees): the values of samples/<key>.toml (edge 14, stroke 1, no gap)
_TWO_UNIFORM = {"two-uniform-hankin": ("[3^3.4^2; 3^2.4.3.4]#2", 60)}


# key -> title, note and query: the cylinders of samples/roller-60x80.toml and samples/lampshade-120x150.toml
_CYLINDERS = {
    "roller": (
        "Texture roller",
        "table3-3 rosettes round a 60 x 80 mm roller, raised 2 mm and mirrored so the imprint in clay reads as "
        "designed, bored for an 8 mm dowel, the bands' undersides pointed to print without supports",
        {
            "preset": "table3-3",
            "radius": "10",
            "stroke": "1.6",
            "diameter": "60",
            "length": "80",
            "pointed_tops": "true",
            "print_style": "relief",
            "relief_mm": "2",
        },
    ),
    "lampshade": (
        "Lampshade",
        "table1-part2 stars pierced through a 120 x 150 mm shade with 8 mm rims and a holder for an E27 lamp "
        "fitting, the openings' tops pointed to print without supports",
        {
            "preset": "table1-part2",
            "radius": "20",
            "stroke": "2",
            "diameter": "120",
            "length": "150",
            "rim_mm": "8",
            "lamp_fitting_mm": "40",
            "pointed_tops": "true",
            "print_style": "pierced",
            "pierced_mm": "2",
        },
    ),
}


# key -> title, note, query and stroke (mm): the girih patterns of samples/<key>.toml, the subdivided one in
# samples/classical/ (the every-sample tests leave that folder out)
_GIRIH = {
    "girih-decagon-bowtie": (
        "Girih decagons and bowties",
        "the Lu-Steinhardt girih tiles: decagons on a rhombic lattice with bowties between, their strapwork "
        "crossing each edge's midpoint at 54 degrees",
        {
            "packing": "girih",
            "girih_pattern": "decagon-bowtie",
            "edge": "12",
            "colour_by": "shape",
            "palette": "zellige",
        },
        1.2,
    ),
    "girih-subdivided": (
        "Girih subdivided",
        "the decagons and bowties subdivided once into girih tiles of edge 6 mm: each large decagon a "
        "ten-pointed star in a ring of bowties and hexagons",
        {
            "packing": "girih",
            "girih_pattern": "decagon-bowtie",
            "girih_level": "1",
            "edge": "6",
            "colour_by": "shape",
            "palette": "zellige",
        },
        1,
    ),
}


_HANKIN_488 = {"preset": "table3-3", "packing": "archimedean", "tiling": "4.8.8", "method": "hankin"}

# key -> title, note and query: the classical devices of samples/classical/<key>.toml, on Hankin's rays (the
# parquet's direction and curve sent as the page sends them, with its far-side angle)
_CLASSICAL = {
    "border-4.8.8": (
        "Border of stars",
        "Hankin's polygons in contact on the 4.8.8 tiling, rays at 67.5 degrees, framed by a 15 mm border of "
        "eight-point stars, a whole number on each side",
        {**_HANKIN_488, "edge": "14", "contact_angle": "67.5", "border_mm": "15"},
    ),
    "parquet-4.8.8": (
        "Parquet deformation",
        "Hankin's polygons in contact on the 4.8.8 tiling, the contact angle going from 30 degrees at the left "
        "to 75 at the right, the strands unbroken",
        {
            **_HANKIN_488,
            "edge": "10",
            "contact_angle": "30",
            "contact_angle_to": "75",
            "parquet_direction": "x",
            "parquet_curve": "linear",
        },
    ),
}


@dataclass(frozen=True)
class Entry:
    """One place to start: ``query`` opens it in the editor (``/?`` + the query)."""

    key: str
    title: str
    note: str
    query: dict
    group: str = "preset"
    """``"preset"``, ``"tiling"``, ``"hankin"``, ``"two-uniform"``, ``"cylinder"``, ``"girih"`` or
    ``"classical"``: the gallery's header counts each."""


def _tile_query(stroke=1) -> dict:
    return {"outline": "square", "width": "150", "frame": "5", "stroke": f"{stroke:g}", "fill_small_holes": "true"}


def _tiling_query(tiling: str, edge: float, motifs: dict, main, gap_n) -> dict:
    """The query of a tiling's entry: its edge, its main motif (or the preset per polygon kind), the gap motif."""
    query = {"packing": "archimedean", "tiling": tiling, "edge": f"{edge:g}"}
    if main is None:
        query["preset"] = "table3-3"  # not shown: every polygon kind has its own preset
    else:
        query.update(
            n=str(main["n"]),
            radii=",".join(f"{r:g}" for r in main["radii"]),
            alpha="0",
            spr="0",
            special="none",
            rotation="0",
        )
    query.update({f"motif_{p}": name for p, name in motifs.items()})
    if gap_n is not None:
        query.update(gap_n=str(gap_n), gap_radii="0.5,1")
    return query


@functools.cache
def entries() -> tuple[Entry, ...]:
    """The gallery's entries: the presets, then the tilings, then the tilings by Hankin's method (a two-uniform
    one last), then the cylinders, then the girih patterns, then the classical devices (a border, a parquet
    deformation)."""
    out = []
    for name in PRESETS:
        radius, stroke = _PRESET_TILES.get(name, ("15", 1))
        out.append(
            Entry(
                name,
                f"Preset {name}",
                PRESET_NOTES[name] or "the paper's parameters, as printed",
                {
                    "preset": name,
                    "packing": "hex",
                    "radius": radius,
                    **_tile_query(stroke),
                    "colour_by": "shape",
                    "palette": _PRESET_PALETTES[name],
                },
            )
        )
    for tiling, (edge, motifs, main, gap_n, stroke) in _TILINGS.items():
        query = _tiling_query(tiling, edge, motifs, main, gap_n)
        out.append(
            Entry(tiling, f"Tiling {tiling}", f"the {NAMES[tiling]} tiling", {**query, **_tile_query(stroke)}, "tiling")
        )
    for tiling, (angle, gap) in _HANKIN.items():
        query = {
            "preset": "table3-3",
            "packing": "archimedean",
            "tiling": tiling,
            "edge": "14",
            "method": "hankin",
            "contact_angle": f"{angle:g}",
        }
        if gap:
            query["contact_gap"] = f"{gap:g}"
        gap_words = f", {gap:g} mm apart" if gap else ""
        out.append(
            Entry(
                f"hankin-{tiling}",
                f"Hankin {tiling}",
                f"the {NAMES[tiling]} tiling by Hankin's polygons in contact, rays at {angle:g} degrees{gap_words}",
                {**query, **_tile_query(1)},
                "hankin",
            )
        )
    for key, (tiling, angle) in _TWO_UNIFORM.items():
        query = {"preset": "table3-3", "packing": "archimedean", "tiling": tiling, "edge": "14", "method": "hankin"}
        query["contact_angle"] = f"{angle:g}"
        note = f"the two-uniform tiling {tiling} ({NAMES[tiling]}) by Hankin's polygons in contact"
        note += f", rays at {angle:g} degrees"
        out.append(Entry(key, f"Hankin {tiling}", note, {**query, **_tile_query(1)}, "two-uniform"))
    for key, (title, note, values) in _CYLINDERS.items():
        query = {"packing": "hex", "shape": "cylinder", **values}
        query.update(printer_profile="fdm-0.4mm", fill_small_holes="true")
        out.append(Entry(key, title, note, query, "cylinder"))
    for key, (title, note, values, stroke) in _GIRIH.items():
        out.append(Entry(key, title, note, {**values, **_tile_query(stroke)}, "girih"))
    for key, (title, note, values) in _CLASSICAL.items():
        out.append(Entry(key, title, note, {**values, **_tile_query(1)}, "classical"))
    assert set(_TILINGS) == set(TILINGS), "a tiling is missing from the gallery"
    assert set(_PRESET_PALETTES) == set(PRESETS), "a preset has no palette in the gallery"
    return tuple(out)


def entry(key: str) -> Entry:
    """The entry named ``key``; an unknown key lists the valid ones."""
    for e in entries():
        if e.key == key:
            return e
    raise ParameterError(
        f"{key!r} is not a gallery entry, must be one of: {', '.join(e.key for e in entries())}", param="key"
    )


@functools.lru_cache(maxsize=64)
def thumbnail(key: str, *, limits) -> str:
    """The entry's tile drawn as SVG by the preview code, in its colours (kept once drawn)."""
    from ..making.views import tile_picture
    from .app import tile_from_dict
    from .params import design_from_query

    e = entry(key)
    spec, tile = tile_from_dict(design_from_query(e.query), limits=limits)
    return tile_picture(tile, spec, title=e.title)
