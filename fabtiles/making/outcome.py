"""Outcomes: one job of a batch or sweep, as a picklable summary that crosses processes and machines."""

from __future__ import annotations

import traceback
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..core.errors import FabtilesError

if TYPE_CHECKING:  # the pipeline imports this module: its result type is named for the annotations only
    from .pipeline import BuildResult


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
    refused: list[str] = field(default_factory=list)
    """One line per format the build refused while writing the others, ``"<format>: <reason>"``
    (:attr:`~fabtiles.making.pipeline.BuildResult.refused`)."""


def outcome_of(key: str, result: BuildResult) -> Outcome:
    """An :class:`Outcome` for a build that wrote files: its one line (files, findings per machine, formats
    refused) and the findings.

    The line says which files were new and which replaced (as ``fabtiles build`` does) and, for
    each machine, its findings by code and count, each counted once whatever the formats:
    ``"replaced 5 files; laser: nothing found; printer: 1 finding (thin_wall 12)"``; a build that
    refused formats adds them, ``"wrote 4 files; laser: nothing found; printer: nothing found;
    refused step"`` (the reasons in :attr:`Outcome.refused`).
    """
    counts = [(label.split()[0], len(r.findings)) for label, r in result.models]
    machines = [f"{label.split()[0]}: {_findings(r.findings)}" for label, r in result.models]
    refused_note = [f"refused {', '.join(r.format for r in result.refused)}"] if result.refused else []
    message = "; ".join([_files(len(result.paths), len(set(map(str, result.replaced))))] + machines + refused_note)
    # each finding once, by the model it was found on (not once per file of that model)
    lines = [f"{label}: {f.code}: {f.message}" for label, r in result.models for f in r.findings]
    refused = [f"{r.format}: {r.reason}" for r in result.refused]
    return Outcome(key, True, message, result.paths, lines, result.preview, _figures(result.reports), counts, refused)


def _files(n: int, replaced: int) -> str:
    """How many files were written new and how many replaced files that were there.

    >>> _files(5, 0), _files(1, 1), _files(5, 3)
    ('wrote 5 files', 'replaced 1 file', 'wrote 2 files, replaced 3')
    """

    def files(k):
        return f"{k} file{'s' if k != 1 else ''}"

    if replaced == 0:
        return f"wrote {files(n)}"
    if replaced == n:
        return f"replaced {files(n)}"
    return f"wrote {files(n - replaced)}, replaced {replaced}"


def _findings(findings) -> str:
    """A machine's findings in a few words: ``nothing found``, or each code with its count.

    >>> from fabtiles.core.report import Finding
    >>> _findings([]), _findings([Finding("rounded_corner", "", 9476), Finding("thin_bridge", "", 12)])
    ('nothing found', '2 findings (rounded_corner 9,476, thin_bridge 12)')
    """
    if not findings:
        return "nothing found"
    codes = ", ".join(f"{f.code} {f.count:,}" for f in findings)
    return f"{len(findings)} finding{'s' if len(findings) != 1 else ''} ({codes})"


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
        figures.update(
            filament_mass_g=material["mass_g"],
            filament_length_m=material["length_m"],
            filament_cost=material["cost"],
            filament_line=material["line"],
        )
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
