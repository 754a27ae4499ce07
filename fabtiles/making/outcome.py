"""Outcomes: one job of a batch or sweep, as a picklable summary that crosses processes and machines."""

from __future__ import annotations

import traceback
from dataclasses import dataclass, field
from pathlib import Path

from ..core.errors import FabtilesError


@dataclass
class Outcome:
    """The result of one job of a batch or sweep (picklable: it crosses processes and machines)."""

    key: str
    ok: bool
    message: str
    paths: list[str] = field(default_factory=list)
    findings: list[str] = field(default_factory=list)
    """One line per fabrication finding, ``"<file name>: <code>: <message>"``."""
    preview: str | None = None
    """The tile's picture, when asked for."""
    figures: dict = field(default_factory=dict)
    """The laser job of its first laser file (``Report.stats["job"]``, its ``line`` for people, and
    ``cutter``, the machine), its sheet (``sheet_m2``, ``sheet_cost``) and the filament of its first
    print file (``filament_mass_g``, ..., ``filament_line``): empty without them."""
    counts: list[tuple[str, int]] = field(default_factory=list)
    """The findings of each machine the build made files for: ``[("laser", 0), ("printer", 1)]``."""


def outcome_of(key: str, result: BuildResult) -> Outcome:
    """An :class:`Outcome` for a successful build: its one line (files, findings per machine) and the findings.

    The line counts each machine's findings once, whatever the formats:
    ``"5 files, laser 0, printer 1 warning"``.
    """
    n = len(result.paths)
    counts = [(label.split()[0], len(r.findings)) for label, r in result.models]
    message = ", ".join([f"{n} file{'s' if n != 1 else ''}"] + [f"{machine} {_warnings(k)}" for machine, k in counts])
    # each finding once, by the model it was found on (not once per file of that model)
    lines = [f"{label}: {f.code}: {f.message}" for label, r in result.models for f in r.findings]
    return Outcome(key, True, message, result.paths, lines, result.preview, _figures(result.reports), counts)


def _warnings(n: int) -> str:
    """``"0"``, ``"1 warning"``, ``"3 warnings"``.

    >>> _warnings(0), _warnings(1), _warnings(1200)
    ('0', '1 warning', '1,200 warnings')
    """
    return "0" if n == 0 else f"{n:,} warning{'s' if n != 1 else ''}"


def _figures(reports) -> dict:
    """The laser job, sheet and filament of a build's first laser and first print file, flat (sweep columns)."""
    def first(key):
        return next((r.stats[key] for r in reports if key in r.stats), {})

    job, sheet, material = first("job"), first("sheet"), first("material")
    figures = dict(job)
    if job:  # the job's machine, as its report names it ("router job: ...")
        figures["cutter"] = next(r.stats.get("cutter", "laser") for r in reports if "job" in r.stats)
    if sheet:
        figures.update(sheet_m2=sheet["sheet_m2"], sheet_cost=sheet["cost"])
    if material:
        figures.update(filament_mass_g=material["mass_g"], filament_length_m=material["length_m"],
                       filament_cost=material["cost"], filament_line=material["line"])
    return figures


def run_job(key: str, make_design, outdir, formats=None, *, preview: bool = False) -> Outcome:
    """Build one design for a batch or sweep, never raising: failures become an :class:`Outcome`.

    ``make_design`` is a callable returning the validated design (so that loading
    and validation errors are this job's failure too).
    """
    try:
        from .pipeline import build_design

        result = build_design(make_design(), outdir, formats or None, preview=preview)
        return outcome_of(key, result)
    except FabtilesError as exc:
        return Outcome(key, False, str(exc))
    except Exception:  # a bug: report it with its traceback, keep the batch going
        return Outcome(key, False, "internal error (a bug, please report):\n" + traceback.format_exc())
