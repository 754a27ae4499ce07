"""A request's design: its query read into a design, validated, its tile prepared within the work limits.

Shared by the routers (:mod:`fabtiles.web.routes`). Bad input raises a
:class:`~fabtiles.FabtilesError` whose ``param`` names the design key (or a
:class:`~fabtiles.web.params.QueryError` whose ``field`` names the parameter);
:func:`error_response` turns it into the 422 answer ``{"error": ..., "field": ...}``.
"""

from __future__ import annotations

import re

from fastapi import Request
from fastapi.responses import JSONResponse

from ..machines import limits as _limits
from .params import DEFAULTS, FIELDS, FLAT_ONLY, design_from_query

SOURCE = "query"
"""What a design error of the web names as its source; :func:`user_message` takes it out again."""

EDITED = "custom"
"""The files' name of a design that is not a preset as it stands (the page's Preset menu says so too)."""


def design_name(design: dict) -> str:
    """The files' name of a design with no ``[output] name``: its motif's preset, or :data:`EDITED`.

    >>> design_name({"motif": {"preset": "table3-3"}}), design_name({"motif": {"n": 8, "radii": [1, 2]}})
    ('table3-3', 'custom')
    """
    motif = design.get("motif", {})
    return motif["preset"] if isinstance(motif.get("preset"), str) and len(motif) == 1 else EDITED


def tile_from_dict(design: dict, *, limits: _limits.Limits):
    """Validate a design dictionary and build its tile (no geometry yet) within the work limits."""
    from ..designs.design_file import design_from_dict
    from ..making import prepare_tile

    spec = design_from_dict(design, name=design_name(design), source=SOURCE)
    return spec, prepare_tile(spec, limits=limits)


def build(request: Request, *, limits: _limits.Limits, view=()):
    """``(design dict, design, tile)`` of a request's query (``view``: parameters of the view, not the design)."""
    query = dict(request.query_params)
    for key in view:
        query.pop(key, None)
    return design_of_query(query, limits=limits)


def design_of_query(query: dict, *, limits: _limits.Limits):
    """``(design dict, design, tile)`` of a query's parameters, over the page's defaults (as the editor sends them)."""
    base = dict(DEFAULTS)
    if ("n" in query or "radii" in query) and "preset" not in query:
        del base["preset"]  # the motif's own parameters replace the default preset
    if query.get("packing") in ("none", "archimedean", "girih"):
        del base["radius"]  # no packing radius (a tiling has an edge)
    if query.get("shape") == "cylinder":  # its tile is its unrolled strip: no outline, size or frame
        base = {k: v for k, v in base.items() if k not in FLAT_ONLY}
    design = design_from_query({**base, **query})
    spec, tile = tile_from_dict(design, limits=limits)
    return design, spec, tile


def fabrication_checks(tile, spec) -> dict:
    """Laser and print checks of a tile with the design's profiles and options, as JSON."""
    from ..designs.design_file import design_notes
    from ..making.checks import check_design

    result = check_design(spec, tile, job=True)
    findings = [
        {
            "where": where,
            "code": f.code,
            "message": f.message,
            "count": f.count,
            "worst": f.worst,
            "limit": f.limit,
            "unit": f.unit,
        }
        for where, f in result.findings()
    ]
    region = tile.region()
    holes = sum(len(p.interiors) for p in getattr(region, "geoms", [region]))
    too_small = [f"{result.filled_holes:,} too small to cut"] if result.filled_holes else []
    too_small += [f"{result.print_filled_holes:,} too small to print"] if result.print_filled_holes else []
    filled = f" ({' and '.join(too_small)}, filled)" if too_small else ""
    summary = (
        f"{len(tile.segments()):,} segments, material {region.area:,.0f} mm², {holes:,} holes{filled}; "
        f"{len(findings)} finding{'s' if len(findings) != 1 else ''}"
    )
    job = result.job.as_stats() if result.job is not None else None
    material = result.filament.as_stats() if result.filament is not None else None
    # a tile larger than a machine's bed: how it is cut and printed as pieces (the panel's first line of each)
    pieces = [f"{result.cutter} {line}" for line in result.pieces[:1]]
    cylinder = _cylinder(tile, spec)
    if cylinder is None:  # a cylinder's print note is its line, below: it is never printed in pieces
        pieces += [f"print {line}" for line in result.print.stats.get("notes", ())[:1]]
    checked = cylinder or {"cylinder": None, "fitted": []}
    # a border's fit (its repeats and cells), as the build notes it
    checked["fitted"] = [*checked["fitted"], *(line for line in design_notes(spec) if line.startswith("tile.border"))]
    return {
        **checked,
        "findings": findings,
        "summary": summary,
        "pieces": pieces,
        "filled_holes": result.filled_holes,
        "print_filled_holes": result.print_filled_holes,
        "job": job,
        "material": material,
        "cutter": result.cutter,
    }


def _cylinder(tile, spec) -> dict | None:
    """A cylinder's line for the checks (``cylinder (roller): outer diameter ...``) and what its fit changed
    (``surface: cylinder D 60 mm x 80 mm, 9 periods around ...``); None for a flat tile."""
    if not spec.surface.cylinder:
        return None
    from ..making import BuildOptions, Models

    cylinder = Models(tile, BuildOptions.of_design(spec)).cylinder
    assert cylinder is not None  # a cylinder's design
    return {"cylinder": cylinder.line(), "fitted": [line for line in spec.fitted if line.startswith("surface:")]}


def field_of_param(param: str | None) -> str | None:
    """The query field of the design key an error names (its ``param``).

    A bare parameter name (an error raised after the design was read, while the tile
    is built) is the field of that name when exactly one field has it.

    >>> field_of_param("packing.gap_motif.n"), field_of_param("tile.size"), field_of_param("packing.kind")
    ('gap_n', 'width', 'packing')
    >>> field_of_param("interlace_gap_mm"), field_of_param("n"), field_of_param("packing.motifs.8.preset")
    ('interlace_gap_mm', None, 'motif_8')
    >>> field_of_param("colour.faces.B"), field_of_param("colour.faces"), field_of_param("colour.band_colour")
    ('face_B', None, 'band_colour')
    >>> field_of_param("colour.shades.B.power_pct")
    'shade_B'

    """
    if param and "." not in param:
        named = [key for key, (_, name, _) in FIELDS.items() if name == param]
        return named[0] if len(named) == 1 else None
    parts = (param or "").split(".")
    menu = _menu_field(parts)
    if menu is not None:
        return menu if menu in FIELDS else None
    return _section_field(parts)


def _section_field(parts: list) -> str | None:
    """The field of a ``section.name`` key (the gap motif's keys are their own section's), or None."""
    if len(parts) == 3 and parts[:2] == ["packing", "gap_motif"]:
        parts = parts[1:]
    if len(parts) != 2:
        return None
    if parts == ["tile", "size"]:
        return "width"
    return next((key for key, (section, name, _) in FIELDS.items() if [section, name] == parts), None)


def _menu_field(parts: list) -> str | None:
    """The field a face class's colour (``face_<letter>``) or engrave settings (``shade_<letter>``), or a
    polygon kind's motif (``motif_<sides>``) would have, for a key of those; None for any other key."""
    if len(parts) == 3 and parts[:2] == ["colour", "faces"]:
        return f"face_{parts[2]}"
    if len(parts) >= 3 and parts[:2] == ["colour", "shades"]:  # a class's engrave setting: shade_<letter>
        return f"shade_{parts[2]}"
    if len(parts) >= 3 and parts[:2] == ["packing", "motifs"]:
        return f"motif_{parts[2]}"
    return None


_WHERE = re.compile(r"\[[\w.]+\](?: (?P<sub>gap_motif|\d+))? ")
_SIZE = {"size[0]": "width", "size[1]": "height"}


def user_message(exc: Exception, field: str | None) -> str:
    """The message of a bad input in the form's words: its parameters' names, no design file's section.

    A design error names its source and the design file's section (``query: [tile] stroke
    must be ...``); the page names neither: ``stroke must be ...``, and the gap motif's keys,
    a polygon kind's motif and the tile's size by their parameters (``gap_n``, ``motif_8``,
    ``width``), a face class's colour by its ``face_<letter>``.

    >>> from fabtiles.core.errors import DesignError
    >>> user_message(DesignError("query: [packing] gap_motif n must be >= 3, got 2"), "gap_n")
    'gap_n must be >= 3, got 2'
    >>> user_message(DesignError("query: [tile] size[1] must be > 0, got 0"), "width")
    'height must be > 0, got 0'
    >>> user_message(DesignError("query: [packing.motifs] 8 'x' is not a valid preset"), "motif_8")
    "motif_8: 'x' is not a valid preset"
    >>> user_message(DesignError("query: [colour.faces] A 'x' is not a CSS or palette colour name"), "face_A")
    "face_A 'x' is not a CSS or palette colour name"
    """
    text = str(exc).removeprefix(f"{SOURCE}: ")
    where = _WHERE.match(text)
    if where:
        text = text[where.end() :]
        if where["sub"] and field:  # the gap motif's or a polygon kind's: the parameter names the key
            name = field.removeprefix("gap_")
            text = field + text[len(name) :] if re.match(rf"{re.escape(name)}[ \[]", text) else f"{field}: {text}"
    letter = field.removeprefix("face_") if field and field.startswith("face_") else None
    if letter and text.startswith(f"{letter} "):  # a face class's colour: its parameter names it
        text = f"{field}{text[len(letter) :]}"
    for size, name in _SIZE.items():
        if text.startswith(size):
            text = name + text[len(size) :]
    return text


def error_response(exc: Exception) -> JSONResponse:
    """The 422 answer of a bad input: the message in the form's words, and the field from the error's
    ``field`` or design ``key``."""
    field = getattr(exc, "field", None) or field_of_param(getattr(exc, "key", None))
    return JSONResponse({"error": user_message(exc, field), "field": field}, status_code=422)
