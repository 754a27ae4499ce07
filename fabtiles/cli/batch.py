"""``fabtiles batch``: build many designs in parallel processes.

One failing design is reported and skipped; the others go on. Each design is
built all-or-nothing by :func:`fabtiles.cli.build.build_design`, so a failure
leaves no partial file. Exit status 0 only when every design succeeded.
"""

from __future__ import annotations

import os
import sys
import traceback
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import click


def build_one(design_file: str, outdir: str, formats, overrides) -> tuple[str, bool, str, list[str]]:
    """Build one design (in a worker process): ``(design, ok, message, written paths)``."""
    from .._errors import FabtilesError
    from ..design import load_design
    from .build import build_design

    try:
        design = load_design(design_file, overrides=overrides)
        reports = build_design(design, outdir, formats or None)
        warnings = sum(len(r.findings) for r in reports)
        message = f"{len(reports)} file{'s' if len(reports) != 1 else ''}"
        if warnings:
            message += f", {warnings} fabrication warning{'s' if warnings != 1 else ''}"
        return design_file, True, message, [r.path for r in reports]
    except FabtilesError as exc:
        return design_file, False, str(exc), []
    except Exception:  # a bug: report it with its traceback, keep the batch going
        return design_file, False, "internal error (a bug, please report):\n" + traceback.format_exc(), []


@click.command("batch")
@click.argument("design_files", metavar="DESIGN.toml...", nargs=-1, required=True,
                type=click.Path(dir_okay=False))
@click.option("-o", "--output", "outdir", required=True, type=click.Path(file_okay=False),
              help="Folder to write OUTDIR/<design name>.<format> into.")
@click.option("-j", "--jobs", type=click.IntRange(1, 64), default=None,
              help="Parallel processes (default: the number of CPU cores).")
@click.option("--set", "overrides", multiple=True, metavar="SECTION.KEY=VALUE",
              help="Override a value in every design, TOML syntax (repeatable).")
@click.option("--format", "formats", multiple=True, type=click.Choice(("dxf", "svg", "stl", "3mf", "step")),
              help="Output format (repeatable); default: each design's [output] formats.")
def command(design_files, outdir, jobs, overrides, formats):
    """Build many designs in parallel; a failing design is reported and skipped.

    \b
    fabtiles batch samples/*.toml -o out/ --jobs 2
    """
    stems = {}
    for f in design_files:
        stem = Path(f).stem
        if stem in stems and stems[stem] != f:
            raise click.UsageError(f"two designs would write the same files: {stems[stem]} and {f}; rename one")
        stems[stem] = f
    jobs = jobs or os.cpu_count() or 1
    show_bar = sys.stderr.isatty()
    results = []
    with ProcessPoolExecutor(max_workers=min(jobs, len(design_files))) as pool:
        futures = [pool.submit(build_one, f, outdir, tuple(formats), tuple(overrides)) for f in design_files]
        with click.progressbar(length=len(futures), label="building", file=sys.stderr,
                               hidden=not show_bar) as bar:
            for fut in as_completed(futures):
                results.append(fut.result())
                bar.update(1)
    order = {f: k for k, f in enumerate(design_files)}
    results.sort(key=lambda r: order[r[0]])
    failed = [r for r in results if not r[1]]
    for design, ok, message, written in results:
        if ok:
            click.echo(f"ok     {design}: {message}")
        else:
            click.echo(f"FAILED {design}: {message}", err=True)
    click.echo(f"{len(results) - len(failed)} of {len(results)} designs built"
               + (f", {len(failed)} failed" if failed else ""))
    if failed:
        sys.exit(2)
