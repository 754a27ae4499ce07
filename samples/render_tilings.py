"""Re-render the previews of the 11 Archimedean tiling samples into samples/renders/tilings/.

    python samples/render_tilings.py

One SVG per ``samples/tilings/<tiling>.toml``, reproducible byte for byte (the
tests render one and compare), shown in the README's gallery.
"""

from __future__ import annotations

from pathlib import Path

import fabtiles
from fabtiles.design import load_design
from fabtiles.export.preview_svg import write_tile_svg

HERE = Path(__file__).resolve().parent


def render(design_path, out_dir) -> Path:
    """Write the preview SVG of one design into ``out_dir``; return its path."""
    design = load_design(design_path)
    path = Path(out_dir) / f"{design.name}.svg"
    write_tile_svg(path, design.build_tile(tile_cls=fabtiles.Tile), title=design.name)
    return path


def main() -> None:
    out = HERE / "renders" / "tilings"
    out.mkdir(parents=True, exist_ok=True)
    for path in sorted((HERE / "tilings").glob("*.toml")):
        written = render(path, out)
        print(f"wrote {written.relative_to(HERE.parent)}")


if __name__ == "__main__":
    main()
