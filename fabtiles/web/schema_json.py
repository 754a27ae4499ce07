"""The schema of the design keys as the web form reads it (``/api/schema``): one entry per query parameter.

>>> fields = schema_json()["fields"]
>>> fields["stroke"]["widget"]["kind"], fields["stroke"]["key"], fields["stroke"]["range"]["min"]
('slider', 'tile.stroke', 0)
>>> [v for v, _ in fields["packing"]["choices"]]
['hex', 'square', 'archimedean', 'girih', 'none']
"""

from __future__ import annotations

from dataclasses import asdict

from ..core import schema as _schema
from ..export.formats import FORMATS, design_formats
from .building import user_message
from .params import CLASS_TABLES, FIELDS


def _key_json(k: _schema.Key, widget: _schema.Widget | None) -> dict:
    entry = {
        "key": k.path,
        "type": k.type,
        "unit": k.unit,
        "help": k.help,
        "default": k.default,
        "range": asdict(k.range) if k.range is not None else None,
        "widget": None,
        "choices": None,
    }
    if widget is not None:
        entry["widget"] = {n: v for n, v in asdict(widget).items() if n not in ("labels", "extra")}
    if k.type == "choice" and k.choices is not None:
        labels = dict(widget.labels) if widget is not None else {}
        entry["choices"] = [[str(v), labels.get(str(v), str(v))] for v in k.choice_values()]
        entry["choices"] += [list(e) for e in (widget.extra if widget is not None else ())]
    elif widget is not None and widget.kind == "select" and widget.extra:  # a menu of a boolean: its values
        entry["choices"] = [list(e) for e in widget.extra]
    return entry


def schema_json() -> dict:
    """``{"fields": {query parameter: {key, type, unit, help, default, range, widget, choices}}, "formats": [...]}``.

    ``formats``: the format table's rows the web app offers (its download buttons and the nest
    page's formats), a format plugin's included: name, family, suffix, label, media type,
    description, the cutter kinds that take it, whether nested sheets are written in it. ``unmade``: per
    ``[surface] shape``, the offered formats it is not made in, each with the reason (the page disables
    their buttons and says why).

    The gap motif's parameters (``gap_n``, ...) carry the motif key's entry with the gap's
    widget; ``width``/``height`` and ``motif_<sides>`` carry ``tile.size`` and ``packing.motifs``,
    ``face_<letter>`` ``colour.faces`` and ``shade_<letter>`` ``colour.shades``.
    """
    fields = {}
    for query, (section, name, _) in FIELDS.items():
        if section == "gap_motif":
            k = _schema.key(f"motif.{name}")
            fields[query] = {**_key_json(k, _schema.GAP_WIDGETS.get(name)), "key": f"packing.gap_motif.{name}"}
        elif section == "motifs":
            fields[query] = _key_json(_schema.key("packing.motifs"), None)
        elif section in CLASS_TABLES:
            k = _schema.key(f"colour.{section}")
            fields[query] = {**_key_json(k, None), "key": f"colour.{section}.{name}"}
        elif section == "tile" and name in ("width", "height"):
            fields[query] = _key_json(_schema.key("tile.size"), _schema.SIZE_WIDGETS[name])
        else:
            k = _schema.key(f"{section}.{name}")
            fields[query] = _key_json(k, k.widget)
    offered = design_formats()
    from ..making.cylinder import unmade_formats

    return {
        "fields": fields,
        "formats": [FORMATS[n].row() for n in offered],
        # in the form's words, as the page's errors: no design file's section
        "unmade": {
            shape: {f: user_message(Exception(r), None) for f, r in unmade_formats(offered, shape).items()}
            for shape in ("cylinder", "stamp")
        },
    }
