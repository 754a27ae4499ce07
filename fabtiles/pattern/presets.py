"""The rows of the paper's tables 1-3 as named motif presets (``docs/construction.md``)."""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

from ..core.schema import register_choices

# name -> (parameters, note). Parameters are exactly Star's keyword arguments.
_ROWS = {
    "table1-part1": (dict(n=8, radii=(51, 70, 172), alpha=0, spr=0, special=None), "8-pointed star"),
    "table1-part2": (
        dict(n=9, radii=(93, 225), alpha=48, spr=-68, special=2),
        "row also lists r4 = 180, unused with S = 2",
    ),
    "table2-left": (dict(n=9, radii=(191, 189, 226), alpha=34, spr=89, special=3), ""),
    "table2-right": (dict(n=10, radii=(172, 109, 133, 125), alpha=62, spr=-100, special=2), ""),
    "table3-1": (
        dict(n=12, radii=(171, 23), alpha=53, spr=-50, special=2),
        "row also lists r3 = 214, unused with S = 2",
    ),
    "table3-2": (
        dict(n=6, radii=(143, 145, 179), alpha=10, spr=-70, special=2),
        "row says S = 4 but gives 3 radii: read as S = 3",
    ),
    "table3-3": (dict(n=12, radii=(123, 85, 178), alpha=23, spr=-7, special=2), ""),
}

PRESETS: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {name: MappingProxyType(params) for name, (params, _) in _ROWS.items()}
)
"""Preset name -> read-only mapping of Star parameters."""

PRESET_NOTES = MappingProxyType({name: note for name, (_, note) in _ROWS.items()})
"""Preset name -> how fabtiles reads the paper's row (empty when the row is plain)."""


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(PRESETS, "motif.preset")
