"""Draw the pictures of docs/borders.md into samples/pictures/borders/.

    python samples/render_borders.py

One bordered tile per outline and frieze, 80 mm, the table3-3 rosettes of radius 8 mm in the field:
a square with stars, a square with Hankin's rays, a hexagon with stars, a circle with Hankin's rays.
The files are reproducible byte for byte; tests/test_doc_pictures.py checks the committed ones
are current.
"""

from __future__ import annotations

from pathlib import Path

from fabtiles import HexPacking, Star
from fabtiles.core.files import atomic_write
from fabtiles.export.preview_svg import tile_svg
from fabtiles.geometry.tile import TileGeometry

HERE = Path(__file__).resolve().parent
OUT = HERE / "pictures" / "borders"
TILES = (("square", "stars"), ("square", "hankin"), ("hexagon", "stars"), ("circle", "hankin"))
"""The pictures: an outline and its frieze each."""


def tile(outline: str, motif: str) -> TileGeometry:
    """The bordered tile of one picture."""
    pack = HexPacking(radius=8, motif=Star.preset("table3-3"))
    return TileGeometry(outline, 80, pack, frame=2, stroke=0.8, border_mm=10, border_motif=motif)


def render(out: Path = OUT) -> list[Path]:
    """Write every picture into ``out``; return their paths."""
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for outline, motif in TILES:
        t = tile(outline, motif)
        path = out / f"{outline}-{motif}.svg"
        title = f"{outline}, 80 mm: a border of {motif} ({t.border().fit.line(motif)})"
        atomic_write(path, tile_svg(t, title=title))
        written.append(path)
    return written


if __name__ == "__main__":
    for p in render():
        print(f"wrote {p.relative_to(HERE.parent)}")
