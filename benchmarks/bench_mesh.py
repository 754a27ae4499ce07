"""Benchmark: relief STL of a 600 x 400 mm sheet (R = 15 mm, table3-3), end to end.

Target (issue 5): under 6 s from the tile's parameters to the checked file, on
a 2-core machine. Run: ``python benchmarks/bench_mesh.py [--style relief] [--out DIR]``.
Prints the time of each stage.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path


def sheet_tile(width=600.0, height=400.0, radius=15.0, preset="table3-3"):
    from fabtiles import Star
    from fabtiles.geometry.tile import TileGeometry
    from fabtiles.pattern.packing import HexPacking

    return TileGeometry("rectangle", (width, height), HexPacking(radius, Star.preset(preset)), frame=5.0, stroke=1.0)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--style", default="relief", choices=("relief", "pierced", "deboss"))
    ap.add_argument("--format", default="stl", choices=("stl", "3mf"))
    ap.add_argument("--out", default=None)
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    from fabtiles.making import export_region

    tile = sheet_tile()
    region, outline = tile.region(), tile.outline_shape()
    t1 = time.perf_counter()
    out = Path(args.out or tempfile.mkdtemp()) / f"sheet.{args.format}"
    report = export_region(
        out,
        region=region,
        outline=outline,
        profile="fdm-0.4mm",
        style=args.style,
        stroke=tile.stroke,
        fill_small_holes=False,
    )
    t2 = time.perf_counter()
    print(
        f"region {t1 - t0:.2f} s, {args.format} {t2 - t1:.2f} s, total {t2 - t0:.2f} s; "
        f"{report.stats['triangles']} triangles, {out.stat().st_size / 1e6:.1f} MB -> {out}"
    )


if __name__ == "__main__":
    main()
