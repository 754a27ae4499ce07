"""Draw a sample as a pen plotter fills it: ``python samples/render_plot.py [DESIGN.toml] [OUT.svg]``.

Writes ``samples/renders/plot-mosaic-iznik.svg`` by default: ``fabtiles plot --fill`` of the
Iznik mosaic sample at 60 mm with a 0.4 mm pen and the bands in black (the Iznik painters'
outline; the palette's white bands would not show on white paper), the plot's own SVG: a layer
per pen, each face class hatched in its colour (docs/plotters-and-inkscape.md shows it; a test
checks it is up to date).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).parent
OVERRIDES = ("tile.size=60", 'colour.band_colour="black"')
PEN_MM = 0.4


def render(design_path, out_path) -> Path:
    from fabtiles.core.files import atomic_write
    from fabtiles.designs.design_file import load_design
    from fabtiles.export.plot_svg import svg_bytes
    from fabtiles.making.plot import plot_drawing

    drawing = plot_drawing(load_design(design_path, overrides=OVERRIDES), fill=True, pen_mm=PEN_MM)
    return atomic_write(out_path, svg_bytes(drawing))


if __name__ == "__main__":
    args = sys.argv[1:]
    design = args[0] if args else HERE / "mosaic-iznik.toml"
    out = args[1] if len(args) > 1 else HERE / "renders" / "plot-mosaic-iznik.svg"
    print(f"wrote {render(design, out)}")
