"""Parameter sweeps: every combination of some design values, built side by side.

``fabtiles sweep DESIGN.toml --vary packing.radius=8:16:5 --vary tile.stroke=0.8,1.2 -o OUT``
builds the cross product of the varied values (here 10 variants) through the build
pipeline, as :mod:`fabtiles.making.jobs` jobs (local processes or a Dask cluster), and writes
in OUT the files of every variant (``<design name>-001.<format>``, ...), a picture of
each (``<design name>-001.preview.svg``), a contact sheet ``index.html`` (the pictures,
labelled with their values and findings, linking their files) and ``index.csv`` (one
row per variant). A variant that fails is reported there and skipped.

A ``SPEC`` is ``a:b:n`` (n values from a to b inclusive; whole numbers stay whole
when a, b and the step are whole) or a list ``x,y,z`` of TOML values (a bare word is a
string; brackets keep their commas: ``motif.radii=[51,70,172],[60,80,170]``).

>>> parse_vary("packing.radius=8:16:5")
Vary(key='packing.radius', values=(8, 10, 12, 14, 16))
>>> parse_vary("tile.stroke=0.5:1:3").values
(0.5, 0.75, 1.0)
>>> parse_vary("tile.outline=square,hexagon").values
('square', 'hexagon')
"""

from __future__ import annotations

import csv
import functools
import html
import io
import itertools
import math
import re
from dataclasses import dataclass
from pathlib import Path

from ..core.errors import ParameterError, did_you_mean
from ..designs.design_file import MOTIF_KEYS, OUTPUT_KEYS, PACKING_KEYS, SURFACE_KEYS, TILE_KEYS, parse_override

MAX_VARIANTS = 10_000
"""More variants than this need ``yes=True`` (``--yes``): a typo in a range must not start days of work."""

VARY_KEYS = {
    "motif": MOTIF_KEYS,
    "packing": tuple(k for k in PACKING_KEYS if k != "gap_motif"),
    "packing.gap_motif": MOTIF_KEYS,
    "tile": TILE_KEYS,
    "output": tuple(k for k in OUTPUT_KEYS if k not in ("formats", "name")),
    "surface": SURFACE_KEYS,
}
"""The keys a sweep may vary, by section (``formats`` come from ``--format``; names are the sweep's)."""


@dataclass(frozen=True)
class Vary:
    """One varied design key and its values."""

    key: str
    values: tuple


@dataclass(frozen=True)
class Variant:
    """One combination: its name (the files' stem) and its ``(key, value)`` pairs."""

    name: str
    values: tuple[tuple[str, object], ...]

    def overrides(self) -> tuple[str, ...]:
        """The ``section.key=value`` overrides (TOML values) that make this variant."""
        return tuple(f"{key}={_toml(value)}" for key, value in self.values) + (f'output.name="{self.name}"',)

    def label(self) -> str:
        """``packing.radius=10, tile.stroke=1.2``."""
        return ", ".join(f"{key}={_text(value)}" for key, value in self.values)


def parse_vary(text: str) -> Vary:
    """Parse one ``--vary KEY=SPEC``; see the module text.

    Raises
    ------
    ParameterError
        An unknown key, a bad range (not numbers, ``n`` not a whole number >= 1) or an
        empty list; the message names the ``--vary`` option.
    """
    if not isinstance(text, str) or "=" not in text:
        raise ParameterError(f"--vary expects KEY=SPEC (like packing.radius=8:16:5), got {text!r}", param="vary")
    key, spec = (s.strip() for s in text.split("=", 1))
    section, _, name = key.rpartition(".")
    if section not in VARY_KEYS:
        raise ParameterError(
            f"--vary {text}: {key!r} is not a design key section.key, the sections are: {', '.join(VARY_KEYS)}",
            param="vary",
        )
    valid = VARY_KEYS[section]
    if name not in valid:
        hint = did_you_mean(name, valid)
        hint = f"; {hint}" if hint else ""
        raise ParameterError(
            f"--vary {text}: unknown key {name!r} in [{section}]{hint} (keys that can vary: {', '.join(valid)})",
            param="vary",
        )
    if not spec:
        raise ParameterError(f"--vary {text}: no values; give a:b:n or a list x,y,z", param="vary")
    if re.fullmatch(r"[^,\[\]]*:[^,\[\]]*:[^,\[\]]*", spec):
        values = _range(text, *spec.split(":"))
    else:
        values = tuple(_value(text, key, item) for item in _split(spec))
    return Vary(key, values)


def _range(text: str, a: str, b: str, n: str) -> tuple:
    """The ``n`` values from ``a`` to ``b`` of ``--vary KEY=a:b:n``, whole numbers when ``a``, ``b`` and every
    value are."""
    lo, hi = _ends(text, a, b)
    count = _count(text, n)
    if count == 1:
        values = [lo]
    else:
        values = [lo + (hi - lo) * k / (count - 1) for k in range(count)]
    whole = all(re.fullmatch(r"[+-]?\d+", s.strip()) for s in (a, b)) and all(v.is_integer() for v in values)
    # 12 significant digits: 0.1 + 0.2 stays 0.3 in file names and labels
    return tuple(int(v) if whole else float(f"{v:.12g}") for v in values)


def _ends(text: str, a: str, b: str) -> tuple[float, float]:
    """The ends ``a`` and ``b`` of a range, finite numbers."""
    try:
        lo, hi = float(a), float(b)
    except ValueError:
        raise ParameterError(f"--vary {text}: a:b:n needs numbers a and b, got {a!r} and {b!r}", param="vary") from None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ParameterError(f"--vary {text}: a and b must be finite numbers, got {a!r} and {b!r}", param="vary")
    return lo, hi


def _count(text: str, n: str) -> int:
    """The ``n`` of a range, a whole number >= 1."""
    try:
        count = int(n)
    except ValueError:
        raise ParameterError(
            f"--vary {text}: n in a:b:n must be a whole number >= 1, got {n!r}", param="vary"
        ) from None
    if count < 1:
        raise ParameterError(f"--vary {text}: n in a:b:n must be a whole number >= 1, got {count}", param="vary")
    return count


def _split(spec: str) -> list[str]:
    """Split a list on the commas outside brackets and quotes."""
    items, depth, quote, start = [], 0, None, 0
    for k, c in enumerate(spec):
        if quote:
            quote = None if c == quote else quote
        elif c in "\"'":
            quote = c
        elif c in "[{":
            depth += 1
        elif c in "]}":
            depth -= 1
        elif c == "," and depth == 0:
            items.append(spec[start:k])
            start = k + 1
    items.append(spec[start:])
    return [s.strip() for s in items]


def _value(text: str, key: str, item: str):
    if not item:
        raise ParameterError(f"--vary {text}: an empty value in the list", param="vary")
    try:
        return parse_override(f"{key}={item}")[1]
    except Exception as exc:  # the override parser's DesignError, re-worded for --vary
        raise ParameterError(f"--vary {text}: {item!r} is not a TOML value", param="vary") from exc


def variants(varies, name: str, *, yes: bool = False) -> list[Variant]:
    """The cross product of ``varies``, named ``<name>-001``, ``<name>-002``, ... in order.

    >>> [v.label() for v in variants([parse_vary("tile.frame=0,2"), parse_vary("tile.stroke=1,2")], "t")]
    ['tile.frame=0, tile.stroke=1', 'tile.frame=0, tile.stroke=2', 'tile.frame=2, tile.stroke=1', 'tile.frame=2, tile.stroke=2']

    Raises
    ------
    ParameterError
        No ``--vary``, a key varied twice, or more than :data:`MAX_VARIANTS` variants
        without ``yes``.
    """  # noqa: E501 - a doctest's lines are as Python prints them
    varies = list(varies)
    if not varies:
        raise ParameterError(
            "a sweep needs at least one --vary KEY=SPEC (like --vary packing.radius=8:16:5)", param="vary"
        )
    keys = [v.key for v in varies]
    twice = sorted({k for k in keys if keys.count(k) > 1})
    if twice:
        raise ParameterError(f"--vary {twice[0]} is given twice; give each key once", param="vary")
    total = math.prod(len(v.values) for v in varies)
    if total > MAX_VARIANTS and not yes:
        raise ParameterError(
            f"the sweep has {total:,} variants, more than {MAX_VARIANTS:,}; pass --yes to "
            f"build them all, or vary fewer values",
            param="vary",
        )
    width = max(3, len(str(total)))
    return [
        Variant(f"{name}-{k + 1:0{width}d}", tuple(zip(keys, combo, strict=True)))
        for k, combo in enumerate(itertools.product(*(v.values for v in varies)))
    ]


def make_jobs(design_file, variants_, outdir, formats=(), overrides=()):
    """One :class:`~fabtiles.making.jobs.Job` per variant (picklable: it can run on a cluster)."""
    from ..designs.design_file import design_from_text
    from .jobs import Job

    path = Path(design_file)
    text = _read(path)
    return [
        Job(
            v.name,
            functools.partial(
                design_from_text, text, name=path.stem, source=str(path), overrides=tuple(overrides) + v.overrides()
            ),
            str(outdir),
            tuple(formats),
            preview=True,
        )
        for v in variants_
    ]


def _read(path: Path) -> str:
    from ..core.errors import DesignError

    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise DesignError(f"cannot read design file {str(path)!r}: {reason}") from None


def explain(outcome, variant: Variant) -> str:
    """The outcome's message, naming the ``--vary`` value rather than the override it became."""
    message = outcome.message
    # overrides() ends with the output name, which no --vary value made: zip stops before it
    for (key, value), item in zip(variant.values, variant.overrides(), strict=False):
        message = message.replace(f"--set {item}", f"{key}={_text(value)}")
    return message


JOB_COLUMNS = {
    "cut_length_mm": "cut_total_mm",
    "pierces": "pierces",
    "engrave_area_mm2": "engrave_area_mm2",
    "travel_mm": "travel_mm",
    "laser_time_s": "seconds",
    "sheet_m2": "sheet_m2",
    "sheet_cost": "sheet_cost",
    "filament_g": "filament_mass_g",
    "filament_m": "filament_length_m",
    "filament_cost": "filament_cost",
}
"""``index.csv``'s laser job, sheet and filament columns (empty where a variant has no such file, or no price)
and the keys they hold."""


def write_index(outdir, varies, variants_, outcomes) -> tuple[Path, Path]:
    """Write ``index.csv`` and the contact sheet ``index.html`` into ``outdir`` (atomically)."""
    from ..core.files import atomic_write

    outdir = Path(outdir)
    by_name = {o.key: o for o in outcomes}
    keys = [v.key for v in varies]
    rows = [_index_row(v, by_name[v.name]) for v in variants_]
    buf = io.StringIO()
    writer = csv.DictWriter(
        buf, fieldnames=["variant", "status", *keys, "files", "findings", *JOB_COLUMNS, "details"], lineterminator="\n"
    )
    writer.writeheader()
    writer.writerows(rows)
    csv_path = atomic_write(outdir / "index.csv", buf.getvalue())
    html_path = atomic_write(outdir / "index.html", _contact_sheet(varies, variants_, by_name))
    return csv_path, html_path


def _index_row(v, o) -> dict:
    """One variant's row of ``index.csv``: its values, status, files, findings, job figures and details."""
    files = [Path(p).name for p in o.paths]
    figures = o.figures if o.ok else {}
    return dict(
        variant=v.name,
        status=("part" if o.refused else "ok") if o.ok else "failed",
        **{k: _text(val) for k, val in v.values},
        files=" ".join(files),
        findings=len(o.findings),
        **{c: "" if figures.get(k) is None else figures[k] for c, k in JOB_COLUMNS.items()},
        details=" | ".join([f"refused {r}" for r in o.refused] + o.findings) if o.ok else explain(o, v),
    )


def _contact_sheet(varies, variants_, by_name) -> str:
    esc = html.escape
    title = "fabtiles sweep: " + ", ".join(f"{v.key} ({len(v.values)})" for v in varies)
    failed = sum(not by_name[v.name].ok for v in variants_)
    cards = []
    for v in variants_:
        o = by_name[v.name]
        label = "".join(f"<div><b>{esc(k)}</b> = {esc(_text(val))}</div>" for k, val in v.values)
        if o.ok:
            picture = (
                f'<a href="{esc(Path(o.preview).name)}"><img src="{esc(Path(o.preview).name)}" alt="{esc(v.name)}"></a>'
                if o.preview
                else ""
            )
            links = " ".join(f'<a href="{esc(Path(p).name)}">{esc(Path(p).suffix[1:])}</a>' for p in o.paths)
            notes = "".join(f"<li>refused {esc(r)}</li>" for r in o.refused)
            notes += "".join(f"<li>{esc(f)}</li>" for f in o.findings) if o.findings else "<li>no findings</li>"
            cards.append(
                f'<figure class="ok" id="{esc(v.name)}">{picture}<figcaption>{_figures_html(o.figures)}'
                f'<div class="name">{esc(v.name)}</div>{label}<div class="files">{links}</div>'
                f'<ul class="findings">{notes}</ul></figcaption></figure>'
            )
        else:
            cards.append(
                f'<figure class="failed" id="{esc(v.name)}"><div class="error">failed: '
                f'{esc(explain(o, v))}</div><figcaption><div class="name">{esc(v.name)}</div>'
                f"{label}</figcaption></figure>"
            )
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{esc(title)}</title>
<style>
body {{ font: 14px system-ui, sans-serif; margin: 1rem; }}
main {{ display: grid; grid-template-columns: repeat(auto-fill, minmax(220px, 1fr)); gap: 1rem; }}
figure {{ margin: 0; padding: .5rem; border: 1px solid #ccc; border-radius: 4px; }}
figure.failed {{ border-color: #c0392b; background: #fdf0ee; }}
img {{ width: 100%; height: auto; }}
.name {{ font-weight: 600; }}
.findings {{ margin: .3rem 0 0; padding-left: 1.1rem; color: #8a5300; }}
.figures {{ margin-bottom: .3rem; color: #333; font-variant-numeric: tabular-nums; }}
.error {{ color: #c0392b; }}
</style>
</head>
<body>
<h1>{esc(title)}</h1>
<p>{len(variants_) - failed} of {len(variants_)} variants built{f", {failed} failed" if failed else ""}.
The table is in <a href="index.csv">index.csv</a>.</p>
<main>
{chr(10).join(cards)}
</main>
</body>
</html>
"""


def _figures_html(figures: dict) -> str:
    """A variant's cut job and filament under its picture, as the build's summary words them.

    >>> _figures_html({"cutter": "laser", "line": "2.0 m of cut, 65 pierces, about 2 min",
    ...                "filament_line": "23.2 g of filament, 7.78 m"})
    '<div class="figures"><div>laser job: 2.0 m of cut, 65 pierces, about 2 min</div><div>print: 23.2 g of filament, 7.78 m</div></div>'
    >>> _figures_html({})
    ''
    """  # noqa: E501 - a doctest's lines are as Python prints them
    lines = []
    if "line" in figures:
        lines.append(f"{figures.get('cutter', 'laser')} job: {figures['line']}")
    if "filament_line" in figures:
        lines.append(f"print: {figures['filament_line']}")
    if not lines:
        return ""
    return '<div class="figures">' + "".join(f"<div>{html.escape(t)}</div>" for t in lines) + "</div>"


def _toml(value) -> str:
    import tomli_w

    return tomli_w.dumps({"v": value}).split("=", 1)[1].strip()


def _text(value) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, (list, tuple)):
        return "[" + ",".join(_text(v) for v in value) + "]"
    return str(value).lower() if isinstance(value, bool) else str(value)
