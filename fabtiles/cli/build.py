"""``fabtiles build``: build a design file into output files.

All or nothing: the design is validated and the tile's geometry computed first;
every file is then written into a temporary folder inside OUTDIR and moved into
place only when all formats have succeeded. A failure (exit status 2) leaves no
new or partial file behind and never clobbers an existing one.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import click

from .._errors import FabtilesError
from ..design import FORMATS, load_design


def _export(tile, fmt: str, path: Path, design):
    """Write one format through the exporters' dispatcher; return its report."""
    from ..export import dispatch

    out = design.output
    if dispatch.profile_kind(fmt) == "laser":
        return dispatch.export_tile(tile, path, profile=out.laser_profile, mode=out.laser_mode)
    return dispatch.export_tile(tile, path, profile=out.printer_profile, style=out.print_style)


def build_design(design, outdir, formats=None) -> list[Path]:
    """Write ``OUTDIR/<design name>.<format>`` for each format, all or nothing.

    Returns the paths written. Raises :class:`~fabtiles.FabtilesError` on any
    failure, with nothing written.
    """
    formats = tuple(dict.fromkeys(formats or design.output.formats))
    tile = design.build_tile(tile_cls=_tile_class())
    tile.region()  # compute (and fail) before anything is written
    outdir = Path(outdir)
    if outdir.exists() and not outdir.is_dir():
        raise FabtilesError(f"output folder {str(outdir)!r} exists and is not a folder")
    existed = outdir.exists()
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise FabtilesError(f"cannot create output folder {str(outdir)!r}: {exc.strerror or exc}") from None
    staging = Path(tempfile.mkdtemp(prefix=".fabtiles-build-", dir=outdir))
    try:
        staged = []
        for fmt in formats:
            path = staging / f"{design.name}.{fmt}"
            _export(tile, fmt, path, design)
            staged.append(path)
        written = []
        for path in staged:
            target = outdir / path.name
            os.replace(path, target)
            written.append(target)
        return written
    except OSError as exc:
        raise FabtilesError(f"cannot write into {str(outdir)!r}: {exc.strerror or exc}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
        if not existed and not any(outdir.iterdir()):
            outdir.rmdir()  # a failed build leaves no folder it created either


def _tile_class():
    """The public Tile (the lead's subclass with ``export``) when available, else the base."""
    try:
        import fabtiles

        return getattr(fabtiles, "Tile", None)
    except ImportError:  # pragma: no cover
        return None


@click.command("build")
@click.argument("design_file", metavar="DESIGN.toml", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "outdir", required=True, type=click.Path(file_okay=False),
              help="Folder to write OUTDIR/<design name>.<format> into.")
@click.option("--set", "overrides", multiple=True, metavar="SECTION.KEY=VALUE",
              help="Override a design value, in TOML syntax: --set tile.size=[200,200] (repeatable).")
@click.option("--format", "formats", multiple=True, type=click.Choice(FORMATS),
              help="Output format (repeatable); default: the design's [output] formats.")
def command(design_file, outdir, overrides, formats):
    """Build a design file into laser/print/CAD files.

    \b
    fabtiles build samples/table3-3.toml -o out/
    fabtiles build samples/table3-3.toml -o out/ --set tile.size=[200,200] --format svg
    """
    design = load_design(design_file, overrides=overrides)
    for path in build_design(design, outdir, formats or None):
        click.echo(f"wrote {path}")
