"""``fabtiles sweep``: build every combination of some design values, with a contact sheet.

Parses the arguments and prints; :mod:`fabtiles.making.sweep` makes the variants and the
index files, :mod:`fabtiles.making.jobs` builds them (local processes or a Dask cluster).
"""

from __future__ import annotations

import os

import click

from .choices import FormatChoice


@click.command("sweep")
@click.argument("design_file", metavar="DESIGN.toml", type=click.Path(dir_okay=False))
@click.option(
    "--vary",
    "varies",
    multiple=True,
    metavar="KEY=SPEC",
    help="A design key and its values: a:b:n (n values from a to b) or x,y,z (repeatable; "
    "the sweep builds every combination).",
)
@click.option(
    "-o",
    "--output",
    "outdir",
    required=True,
    type=click.Path(file_okay=False),
    help="Folder for the variants' files, index.html and index.csv.",
)
@click.option(
    "--format",
    "formats",
    multiple=True,
    type=FormatChoice(),
    help="Output format (repeatable); default: the design's [output] formats.",
)
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="SECTION.KEY=VALUE",
    help="Override a value in every variant, TOML syntax (repeatable).",
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
    help="Run every variant as a task on a Dask cluster (e.g. tcp://10.0.0.5:8786); needs the dask extra.",
)
@click.option("--yes", is_flag=True, help="Build more than 10,000 variants.")
@click.option(
    "-v",
    "--verbose",
    is_flag=True,
    help="List each variant's fabrication findings under its line (index.html and index.csv hold them).",
)
def command(design_file, varies, outdir, formats, overrides, jobs, scheduler, yes, verbose):
    """Build every combination of the varied values; a failing variant is reported and skipped.

    Writes OUTDIR/<design name>-001.<format>, ... for each variant, a picture of
    each (<design name>-001.preview.svg), the contact sheet OUTDIR/index.html (the
    pictures, labelled with their values and findings, linking their files) and
    OUTDIR/index.csv (one row per variant). Exit status 0 when every variant was
    built, 2 when some failed or on bad input, else 3 when a variant's formats were
    refused (the others written; "part" in the table, the reasons in its details).

    \b
    fabtiles sweep samples/table3-3.toml --vary packing.radius=10:20:5 --vary tile.stroke=1,1.5 -o sweep/
    fabtiles sweep samples/rosette.toml --vary motif.preset=table3-1,table3-2,table3-3 -o presets/ --format svg
    """
    from ..making.sweep import explain, make_jobs, parse_vary, variants, write_index
    from .batch import finish, run_and_report

    if scheduler is not None and jobs is not None:
        raise click.UsageError("--jobs sets local processes; with --scheduler the cluster's workers build")
    parsed = [parse_vary(v) for v in varies]
    from ..designs.design_file import load_design

    design = load_design(design_file, overrides=overrides)  # the base design must be valid on its own
    todo = variants(parsed, design.name, yes=yes)
    work = make_jobs(design_file, todo, outdir, formats, overrides)
    by_name = {v.name: v for v in todo}
    outcomes = run_and_report(
        work,
        workers=jobs or os.cpu_count() or 1,
        scheduler=scheduler,
        label="sweeping",
        keys=[v.name for v in todo],
        labels={v.name: v.label() for v in todo},
        explain=lambda o: explain(o, by_name[o.key]),
        verbose=verbose,
    )
    csv_path, html_path = write_index(outdir, parsed, todo, outcomes)
    finish(outcomes, "variants", f"; contact sheet {html_path}, table {csv_path}")
