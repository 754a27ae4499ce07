"""Draw the pictures of docs/girih.md's subdivision into samples/pictures/girih/.

    python samples/render_girih.py

``rule.svg``: the large decagon, bowtie and hexagon, each with the small tiles the rule puts in it
(the hexagons on its edges half outside it), their strapwork, and the large tile's outline. ``level-0.svg``,
``level-1.svg``, ``level-2.svg``: an 80 mm tile of the decagon-bowtie pattern at those levels, its tiles'
edge 3 mm. The files are reproducible byte for byte; tests/test_doc_pictures.py checks the committed
ones are current.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fabtiles import GirihPacking
from fabtiles.core.files import atomic_write
from fabtiles.export.preview_svg import tile_svg
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.girih import SUBDIVIDED, TAU2, subdivide, tile_corners, tile_strapwork

HERE = Path(__file__).resolve().parent
OUT = HERE / "pictures" / "girih"
LEVELS = (0, 1, 2)
"""The levels of the tile pictures."""
COLOURS = {"decagon": "#f2d7a6", "hexagon": "#a9cce3", "bowtie": "#d5a6bd"}
"""Each small tile's fill in the rule's picture."""
SCALE = 24.0
"""Pixels per small tile edge in the rule's picture."""


def _points(corners: np.ndarray, dx: float, top: float) -> str:
    return " ".join(f"{(x + dx) * SCALE:.2f},{(top - y) * SCALE:.2f}" for x, y in corners)


def rule_svg() -> str:
    """The picture of the rule: each large tile, its small tiles and their strapwork."""
    parts, dx, height = [], 1.0, 0.0
    placed = []
    for kind in SUBDIVIDED:
        big = tile_corners(kind, edge=TAU2)
        big = big - big.min(axis=0)
        placed.append((kind, big, dx))
        height = max(height, float(big[:, 1].max()))
        dx += float(big[:, 0].max()) + 2.0
    top = height + 1.0
    for kind, big, shift in placed:
        for small, corners in subdivide([(kind, big)]):
            parts.append(
                f'<polygon points="{_points(corners, shift, top)}" fill="{COLOURS[small]}" '
                'stroke="#555" stroke-width="0.8"/>'
            )
            for a, b in tile_strapwork(small, corners):
                p, q = _points(np.array([a, b]), shift, top).split()
                x1, y1 = p.split(",")
                x2, y2 = q.split(",")
                parts.append(f'<line x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="#1b2631" stroke-width="1.6"/>')
        parts.append(
            f'<polygon points="{_points(big, shift, top)}" fill="none" stroke="#c0392b" stroke-width="2.4" '
            'stroke-dasharray="7 4"/>'
        )
    width, tall = dx * SCALE, (top + 1.0) * SCALE
    title = (
        "the subdivision rule: a large decagon, bowtie and hexagon (dashed) and their small tiles, tau^2 smaller; "
        "the hexagon on each large edge lies half in each tile sharing it"
    )
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{tall:.0f}" '
        f'viewBox="0 0 {width:.2f} {tall:.2f}">\n<title>{title}</title>\n'
        f'<rect width="100%" height="100%" fill="#ffffff"/>\n' + "\n".join(parts) + "\n</svg>\n"
    )


def level_tile(level: int) -> TileGeometry:
    """The 80 mm tile of the decagon-bowtie pattern at ``level``, edge 3 mm."""
    return TileGeometry("square", 80, GirihPacking("decagon-bowtie", edge=3, level=level), frame=2, stroke=0.4)


def render(out: Path = OUT) -> list[Path]:
    """Write every picture into ``out``; return their paths."""
    out.mkdir(parents=True, exist_ok=True)
    written = [out / "rule.svg"]
    atomic_write(written[0], rule_svg())
    for level in LEVELS:
        path = out / f"level-{level}.svg"
        title = f"the decagon-bowtie girih pattern at girih_level = {level}, edge 3 mm, on an 80 mm tile"
        atomic_write(path, tile_svg(level_tile(level), title=title))
        written.append(path)
    return written


if __name__ == "__main__":
    for p in render():
        print(f"wrote {p.relative_to(HERE.parent)}")
