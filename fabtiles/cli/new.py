"""``fabtiles new NAME.toml``: write a commented starter design that builds as written.

The starter holds the sections a newcomer edits first, each key with a comment
saying what it does and what else it takes: ``[motif]``, ``[packing]``,
``[tile]``, ``[output]`` with its profiles, and a ``[colour]`` section commented
out. Every key and its range is in ``docs/design-files.md``.
"""

from __future__ import annotations

from pathlib import Path

import click

from ..core.errors import ParameterError

STARTER = """\
# {name}: a fabtiles design, a star pattern for a laser (or router) and a 3D printer.
# Build it:  fabtiles build {file} -o out/
# Check it:  fabtiles check {file}
# Every key, its range and default: docs/design-files.md. Try a value without
# editing the file: fabtiles build {file} -o out/ --set tile.size=[120,120]

# The motif: the star drawn in each circle of the packing.
[motif]
preset = "table3-3"      # fabtiles presets lists them; or give n = 8 and radii = [0.5, 1.0]

# The packing: circles of the motif over the plane.
[packing]
kind = "hex"             # "hex" or "square"; "archimedean" with a tiling (docs/tilings.md)
radius = 12.5            # the circles' radius, mm: smaller for a finer pattern
# seamless = true        # fit the radius so tiles laid side by side continue the pattern

# The tile: its outline, its size and the bands' width.
[tile]
outline = "square"       # "square", "rectangle", "circle" or "hexagon"
size = [100, 100]        # mm, width and height (one number for a circle or a hexagon)
frame = 4.0              # a solid border, mm (0 for none)
stroke = 1.2             # the bands' width, mm: at least the laser profile's min_feature_mm

# The output: which files, for which machines.
[output]
formats = ["dxf", "svg", "3mf"]      # also "stl", "step", "lbrn2" (LightBurn)
laser_profile = "laser-3mm-plywood"  # fabtiles profile list: lasers, routers, waterjets
printer_profile = "fdm-0.4mm"
fill_small_holes = true              # holes too small for the machine are left solid
# print_style = "mosaic"             # "relief" (the default), "pierced", "deboss", "mosaic"

# Colours: the faces printed in several filaments (docs/colours.md).
# [colour]
# by = "shape"           # faces of one shape take one colour
# palette = "iznik"      # zellige, iznik, mamluk, alhambra, haft-rangi
# [colour.faces]
# A = "cobalt"           # a palette's or CSS colour name, #rrggbb, "band" or "base"
"""
"""The starter design; ``{name}`` and ``{file}`` are the new file's stem and name."""


@click.command("new")
@click.argument("path", metavar="NAME.toml", type=click.Path())
@click.option("--force", is_flag=True, help="Replace the file if it exists.")
def command(path, force):
    """Write a commented starter design, NAME.toml, that builds as written.

    \b
    fabtiles new my-tile.toml
    fabtiles build my-tile.toml -o out/

    An existing file is left as it is unless --force.
    """
    from ..core.files import atomic_write

    target = Path(path)
    if target.suffix.lower() != ".toml":
        raise ParameterError(f"the design must be a .toml file, got {path!r}", param="path")
    if target.is_dir():
        raise ParameterError(f"{path!r} is a folder; give the design's file name, like {path}/tile.toml", param="path")
    if not target.parent.is_dir():
        raise ParameterError(f"the folder {str(target.parent)!r} of {path!r} does not exist", param="path")
    if target.exists() and not force:
        raise ParameterError(f"{path} exists; give another name, or --force to replace it", param="path")
    existed = target.exists()
    atomic_write(target, STARTER.format(name=target.stem, file=target.name))
    click.echo(f"{'replaced' if existed else 'wrote'} {path}: build it with fabtiles build {path} -o out/")
