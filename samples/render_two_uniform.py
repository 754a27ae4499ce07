"""Draw the 20 two-uniform tilings into samples/renders/two-uniform.svg (docs/tilings.md's picture).

    python samples/render_two_uniform.py

Each panel is a tiling's polygons (``TilingPacking.polygons``) in a square window, clipped to it,
filled by their number of sides, the tiling's name under it. Byte-identical on every run
(tests/export/test_two_uniform_outputs.py compares a new drawing with the committed file).
"""

from __future__ import annotations

from pathlib import Path

from shapely.geometry import Polygon, box

from fabtiles.core.files import atomic_write
from fabtiles.export.preview_svg import region_path_data
from fabtiles.pattern.archimedean import TilingPacking
from fabtiles.pattern.two_uniform import TWO_UNIFORM

HERE = Path(__file__).resolve().parent
OUT = HERE / "renders" / "two-uniform.svg"
PANEL, GAP, LABEL, COLUMNS = 60.0, 6.0, 8.0, 5
EDGE = 7.0
FILLS = {3: "#f2c14e", 4: "#d9534f", 6: "#5b8fd9", 12: "#6cbf84"}


def svg() -> str:
    """The picture: the tilings in rows of five panels, each ``PANEL`` mm square."""
    rows = -(-len(TWO_UNIFORM) // COLUMNS)
    width = COLUMNS * PANEL + (COLUMNS + 1) * GAP
    height = rows * (PANEL + LABEL) + (rows + 1) * GAP
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:g}mm" height="{height:g}mm" '
        f'viewBox="0 0 {width:g} {height:g}">',
        f'<rect width="{width:g}" height="{height:g}" fill="white"/>',
    ]
    for k, name in enumerate(TWO_UNIFORM):
        x0 = GAP + (k % COLUMNS) * (PANEL + GAP)
        y0 = GAP + (k // COLUMNS) * (PANEL + LABEL + GAP)
        window = box(-PANEL / 2, -PANEL / 2, PANEL / 2, PANEL / 2)
        parts.append(f'<g transform="translate({x0 + PANEL / 2:g} {y0 + PANEL / 2:g})">')
        for corners in TilingPacking(name, edge=EDGE).polygons(window.bounds):
            shape = Polygon(corners).intersection(window)
            if shape.geom_type != "Polygon" or shape.area < 1e-9:
                continue  # a polygon meeting the window along an edge or at a corner only
            data = region_path_data(shape, 0.0)  # y up, as the tiling's frame
            parts.append(f'<path d="{data}" fill="{FILLS[len(corners)]}" stroke="#333" stroke-width="0.25"/>')
        parts.append("</g>")
        parts.append(
            f'<text x="{x0 + PANEL / 2:g}" y="{y0 + PANEL + LABEL - 2:g}" font-family="sans-serif" '
            f'font-size="4.2" text-anchor="middle">{name}</text>'
        )
    parts.append("</svg>\n")
    return "\n".join(parts)


def main() -> None:
    atomic_write(OUT, svg())
    print(f"wrote {OUT.relative_to(HERE.parent)}")


if __name__ == "__main__":
    main()
