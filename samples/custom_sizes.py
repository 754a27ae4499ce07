"""Build a run of tiles in several custom sizes with the Python API.

    python samples/custom_sizes.py OUTDIR

Writes one SVG preview per size into OUTDIR: the table3-3 tiling in square,
rectangular and hexagonal tiles, plus a seamless rectangle whose radius and
height are fitted so neighbouring tiles continue the pattern.
"""

from __future__ import annotations

import sys
from pathlib import Path

from fabtiles import Tile
from fabtiles.export.preview_svg import write_tile_svg
from fabtiles.geometry.seamless import seamless_fit
from fabtiles.pattern.packing import HexPacking
from fabtiles.pattern.star import Star

SIZES = [  # (outline, size in mm, frame in mm)
    ("square", 100, 4),
    ("square", 150, 5),
    ("rectangle", (200, 120), 5),
    ("rectangle", (300, 100), 6),
    ("hexagon", 120, 4),
]


def main(outdir: str) -> None:
    out = Path(outdir)
    motif = Star.preset("table3-3")
    pack = HexPacking(radius=12.5, motif=motif)
    for outline, size, frame in SIZES:
        tile = Tile(outline, size, pack, frame=frame, stroke=1.0)
        name = f"{outline}-{tile.width_mm:g}x{tile.height_mm:.0f}.svg"
        write_tile_svg(out / name, tile)
        print(f"wrote {out / name}")
    # A seamless tile: keep the width, fit R near 12.5 mm and the height to the period.
    fit = seamless_fit("rectangle", (200, 150), 12.5)
    tile = Tile("rectangle", fit.size, pack.replace(radius=fit.radius), frame=0, stroke=1.0)
    name = f"seamless-{fit.size[0]:g}x{fit.size[1]:.2f}-R{fit.radius:g}.svg"
    write_tile_svg(out / name, tile)
    print(f"wrote {out / name}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
