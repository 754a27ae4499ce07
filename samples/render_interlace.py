"""Render the README's interlace pictures: the woven drawing and a relief close up.

    python samples/render_interlace.py [--out DIR]

Writes ``interlace-woven.svg`` (the preview drawing, true size) and
``interlace-relief.png`` (the relief's two 3MF parts, base and pattern, shaded by
:func:`render_3d.render`; needs Pillow) into ``samples/renders/``. The tile: one
table3-1 rosette in a 50 mm circle, stroke 1.6 mm, interlaced with the default
gap (a third of the stroke); the relief is 2.4 mm
high so that the dips (half of it) read in the picture. Deterministic output.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
OUT = HERE / "renders"
RELIEF_MM = 2.4


def woven_tile():
    import fabtiles as ft

    return ft.Tile("circle", 50, ft.Star.preset("table3-1"), frame=2, stroke=1.6, interlace=True)


def relief_parts(tile):
    """The checked ``base`` and ``pattern`` parts of the interlaced relief, as trimesh meshes."""
    import trimesh

    from fabtiles.geometry.interlace import tile_dips
    from fabtiles.geometry.stack import resolve_stack
    from fabtiles.solid.parts import checked_parts

    stack = resolve_stack("fdm-0.4mm", "relief", relief_mm=RELIEF_MM)
    parts = checked_parts(tile.region(), tile.outline_shape(), stack, dips=tile_dips(tile))
    return {name: trimesh.Trimesh(p.vertices, p.faces, process=False) for name, p in parts.items()}


def main(argv=None) -> list[Path]:
    from PIL import Image

    sys.path.insert(0, str(HERE))
    from render_3d import render

    from fabtiles.export.preview_svg import write_tile_svg

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    tile = woven_tile()
    svg = args.out / "interlace-woven.svg"
    write_tile_svg(svg, tile, fill="#e9d8a6", title="table3-1, interlaced (fabtiles)")
    png = args.out / "interlace-relief.png"
    Image.fromarray(render(relief_parts(tile), 900, 700), "RGB").save(png, format="PNG", optimize=True)
    for p in (svg, png):
        print(f"wrote {p}")
    return [svg, png]


if __name__ == "__main__":
    main()
