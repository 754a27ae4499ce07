"""Draw the inlay kit of a sample: ``python samples/render_kit.py [DESIGN.toml] [OUT.svg]``.

Writes ``samples/pictures/kit-table3-3.svg`` by default: the lattice, the pieces (each in
its hole's place) and the tile assembled, in a light and a dark wood, at true size, with the
design's laser profile and fit (the README shows it; a test checks it is up to date).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).parent


def render(design_path, out_path) -> Path:
    from fabtiles.core.files import atomic_write
    from fabtiles.designs.design_file import load_design
    from fabtiles.export.preview_svg import kit_svg
    from fabtiles.making import inlay_kit_of, prepare_tile

    design = load_design(design_path)
    tile = prepare_tile(design)
    kit = inlay_kit_of(tile, design)
    return atomic_write(out_path, kit_svg(kit, tile.outline_shape(), title=f"{design.name} inlay kit"))


if __name__ == "__main__":
    args = sys.argv[1:]
    design = args[0] if args else HERE / "table3-3.toml"
    out = args[1] if len(args) > 1 else HERE / "pictures" / "kit-table3-3.svg"
    print(f"wrote {render(design, out)}")
