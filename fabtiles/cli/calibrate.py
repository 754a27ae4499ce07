"""``fabtiles calibrate``: a laser test card to measure a profile's limits and kerf.

See :mod:`fabtiles.geometry.calibration` for the card and the README for how to
read it. The card is written atomically; a bad profile or file name is one line
and exit status 2, and no file.
"""

from __future__ import annotations

import click


@click.command("calibrate")
@click.option(
    "--profile",
    "profile",
    required=True,
    help="A bundled laser profile name (e.g. laser-3mm-plywood) or the path of a profile file.",
)
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="card.dxf or card.svg")
@click.option("--dxf-version", default=None, help="DXF version (default: the profile's), e.g. R12.")
def command(profile, output, dxf_version):
    """Write a laser test card: bridges, holes and a kerf gauge around the profile's limits.

    \b
    fabtiles calibrate --profile laser-3mm-plywood -o card.dxf
    """
    from ..export.card import write_card

    report = write_card(output, profile, dxf_version=dxf_version)
    w, h = report.stats["size_mm"]
    click.echo(
        f"wrote {output}: test card {w:.0f} x {h:.0f} mm for laser profile {report.stats['profile']} "
        f"(kerf {report.stats['kerf_mm']:g} mm), {report.stats['features']} labelled features"
    )
