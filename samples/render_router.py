"""Draw a tile before and after a router bit rounds it: ``python samples/render_router.py [OUT.svg]``.

Writes ``samples/pictures/router-rounding.svg`` by default (docs/cnc-and-waterjet.md shows it;
a test checks it is up to date): a 120 mm table3-3 tile with 4 mm bands (hex packing R = 40 mm), as designed
(left) and as the 3.175 mm (1/8 in) bit of ``router-3.175mm-plywood`` makes it (right): the part in wood, what the
bit cannot
cut (the corners it rounds, the holes it cannot enter) in orange, the design's sharp holes
outlined in blue. Drawn from fabtiles' own geometry (:mod:`fabtiles.geometry.tool_opening`).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).parent

DESIGN = """
[motif]
preset = "table3-3"

[packing]
kind = "hex"
radius = 40

[tile]
outline = "square"
size = 120
frame = 6
stroke = 4

[output]
formats = ["dxf"]
laser_profile = "router-3.175mm-plywood"
"""

WOOD, LEFT, DESIGN_FILL, HOLE_EDGE = "#d9b382", "#e8590c", "#1f3b73", "#1f3b73"


def render(out_path) -> Path:
    import shapely

    from fabtiles.core.files import atomic_write
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.export.preview_svg import _num, region_path_data
    from fabtiles.making import made_region, prepare_tile

    design = design_from_text(DESIGN, name="router-rounding")
    tile = prepare_tile(design)
    region, made = tile.region(), made_region(tile, design)
    left = shapely.difference(made, region)  # what the bit leaves: rounded corners, holes it cannot enter
    w, h = tile.width_mm, tile.height_mm
    gap = w / 10
    holes = shapely.multipolygons([shapely.Polygon(r) for p in getattr(region, "geoms", [region]) for r in p.interiors])

    def path(geom, **attrs):
        extra = " ".join(f'{k.replace("_", "-")}="{v}"' for k, v in attrs.items())
        return f'<path d="{region_path_data(geom, h)}" fill-rule="evenodd" {extra}/>'

    before = path(region, fill=DESIGN_FILL, stroke="none")
    after = "".join(
        [
            path(made, fill=WOOD, stroke="none"),
            path(left, fill=LEFT, stroke="none", **{"class": "left"}),
            path(holes, fill="none", stroke=HOLE_EDGE, stroke_width="0.3"),
        ]
    )
    total = 2 * w + gap
    svg = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(total)}mm" height="{_num(h)}mm" '
        f'viewBox="0 0 {_num(total)} {_num(h)}">\n'
        "<title>a 120 mm tile as designed (left) and as a 3.175 mm router bit cuts it (right): the part in wood, "
        "what the bit cannot cut in orange, the design's holes outlined in blue</title>\n"
        f'<rect width="100%" height="100%" fill="#ffffff"/>\n{before}\n'
        f'<g transform="translate({_num(w + gap)} 0)">{after}</g>\n</svg>\n'
    )
    return atomic_write(out_path, svg)


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else HERE / "pictures" / "router-rounding.svg"
    print(f"wrote {render(out)}")
