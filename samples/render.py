"""Re-render the SVG previews of every sample design into samples/renders/.

    python samples/render.py

The samples go to ``samples/renders/``, the 11 Archimedean tiling samples
(``samples/tilings/``) to ``samples/renders/tilings/`` (the README's gallery), their Hankin
counterparts (``samples/hankin/``) to ``samples/renders/hankin/``. The files
are reproducible byte for byte; tests/cli/test_build.py and
tests/export/test_tiling_samples.py check that rendering a sample gives exactly the
committed file.
"""

from __future__ import annotations

from pathlib import Path

import fabtiles
from fabtiles.core.files import atomic_write
from fabtiles.designs.design_file import load_design
from fabtiles.making.views import tile_picture

HERE = Path(__file__).resolve().parent


def render(design_path, out_dir) -> Path:
    """Write the preview SVG of one design into ``out_dir``; return its path."""
    design = load_design(design_path)
    path = Path(out_dir) / f"{design.name}.svg"
    atomic_write(path, tile_picture(design.build_tile(tile_cls=fabtiles.Tile), design, made=None))
    return path


def main() -> None:
    for designs, out in (
        (HERE, HERE / "renders"),
        (HERE / "tilings", HERE / "renders" / "tilings"),
        (HERE / "hankin", HERE / "renders" / "hankin"),
    ):
        out.mkdir(parents=True, exist_ok=True)
        for path in sorted(designs.glob("*.toml")):
            written = render(path, out)
            print(f"wrote {written.relative_to(HERE.parent)}")


if __name__ == "__main__":
    main()
