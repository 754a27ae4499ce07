"""``fabtiles batch``: build many designs in parallel processes or on a Dask cluster.

One failing design is reported and skipped; the others go on. The builds run in
:mod:`fabtiles.making.jobs` through the build pipeline: a design that fails leaves no
file, and a design some of whose formats are refused writes the others and is
reported with the formats refused and why. Exit status 0 only when every design
wrote every format; 2 when a design failed, else 3 when formats were refused.
"""

from __future__ import annotations

import functools
import os
import sys
from pathlib import Path

import click

from .choices import FormatChoice


def run_and_report(
    jobs, *, workers, scheduler, label: str, keys, labels=None, explain=None, verbose: bool = False
) -> list:
    """Run ``jobs`` with a progress bar on a terminal; print one line per outcome, in order.

    The line is the status, the key, the files (new or replaced) and each machine's findings by
    code and count (``ok     samples/table3-2.toml: wrote 3 files; laser: nothing found; printer:
    1 finding (thin_wall 12)``); with
    ``verbose``, each finding follows on a line of its own. ``labels`` adds a text to
    a job's key in the report (a sweep's varied values); ``explain(outcome)`` words a
    failure (default: its message).
    """
    from ..making.jobs import run_jobs

    outcomes = []
    with click.progressbar(length=len(jobs), label=label, file=sys.stderr, hidden=not sys.stderr.isatty()) as bar:
        for outcome in run_jobs(jobs, workers=workers, scheduler=scheduler):
            outcomes.append(outcome)
            bar.update(1)
    order = {k: i for i, k in enumerate(keys)}
    outcomes.sort(key=lambda o: order[o.key])
    labels = labels or {}
    for o in outcomes:
        name = f"{o.key} ({labels[o.key]})" if o.key in labels else o.key
        if o.ok:
            click.echo(f"{'part' if o.refused else 'ok':<6} {name}: {o.message}")
            for line in o.refused:
                click.echo(f"         refused {line}", err=True)
            for line in o.findings if verbose else ():
                click.echo(f"         - {line}")
        else:
            click.echo(f"FAILED {name}: {explain(o) if explain else o.message}", err=True)
    return outcomes


@click.command("batch")
@click.argument("design_files", metavar="DESIGN.toml...", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option(
    "-o",
    "--output",
    "outdir",
    required=True,
    type=click.Path(file_okay=False),
    help="Folder to write OUTDIR/<design name>.<format> into.",
)
@click.option(
    "-j",
    "--jobs",
    type=click.IntRange(1, 64),
    default=None,
    help="Parallel processes (default: the number of CPU cores).",
)
@click.option(
    "--scheduler",
    metavar="ADDRESS",
    help="Run every design as a task on a Dask cluster (e.g. tcp://10.0.0.5:8786); needs the dask extra.",
)
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="SECTION.KEY=VALUE",
    help="Override a value in every design, TOML syntax (repeatable).",
)
@click.option(
    "--format",
    "formats",
    multiple=True,
    type=FormatChoice(),
    help="Output format (repeatable); default: each design's [output] formats.",
)
@click.option("-v", "--verbose", is_flag=True, help="List each design's fabrication findings under its line.")
def command(design_files, outdir, jobs, scheduler, overrides, formats, verbose):
    """Build many designs in parallel; a failing design is reported and skipped.

    One line per design: its status, the files it wrote or replaced and each
    machine's findings by code and count (ok     samples/table3-3.toml: wrote 5
    files; laser: nothing found; printer: nothing found); with -v, each finding
    under it. A design whose model or writer refused some formats writes the
    others and is "part", each format refused on a line of its own with the
    reason. Exit status 0 when every design wrote every format, 2 when a design
    failed, else 3 when formats were refused.

    \b
    fabtiles batch samples/*.toml -o out/ --jobs 2
    fabtiles batch samples/*.toml -o out/ --scheduler tcp://10.0.0.5:8786
    """
    from ..designs.design_file import load_design
    from ..making.jobs import Job

    _check_stems(design_files)
    if scheduler is not None and jobs is not None:
        raise click.UsageError("--jobs sets local processes; with --scheduler the cluster's workers build")
    design_files = list(dict.fromkeys(design_files))
    work = [
        Job(f, functools.partial(load_design, f, overrides=tuple(overrides)), str(outdir), tuple(formats))
        for f in design_files
    ]
    outcomes = run_and_report(
        work,
        workers=jobs or os.cpu_count() or 1,
        scheduler=scheduler,
        label="building",
        keys=design_files,
        verbose=verbose,
    )
    finish(outcomes, "designs")


def _check_stems(design_files) -> None:
    """Refuse two design files of one stem (they would write the same files)."""
    stems: dict = {}
    for f in design_files:
        stem = Path(f).stem
        if stem in stems and stems[stem] != f:
            raise click.UsageError(f"two designs would write the same files: {stems[stem]} and {f}; rename one")
        stems[stem] = f


def finish(outcomes, what: str, tail: str = "") -> None:
    """The line saying how many of the ``what`` were built (in part, failed), then the exit: 2 when one failed,
    :data:`~fabtiles.cli.main.REFUSED_EXIT` when one was built in part."""
    failed = [o for o in outcomes if not o.ok]
    part = [o for o in outcomes if o.ok and o.refused]
    click.echo(
        f"{len(outcomes) - len(failed) - len(part)} of {len(outcomes)} {what} built"
        + (f", {len(part)} in part (formats refused)" if part else "")
        + (f", {len(failed)} failed" if failed else "")
        + tail
    )
    if failed:
        sys.exit(2)
    if part:
        from .main import REFUSED_EXIT

        sys.exit(REFUSED_EXIT)
