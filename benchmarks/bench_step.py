"""Benchmark: STEP of a 200 x 200 mm relief tile (R = 15 mm, table3-3).

Target (issue 12): under 30 s, under 60 MB and under 1.5 GB peak on a 2-core machine, including the
read-back check. Run: ``python benchmarks/bench_step.py [--size 200] [--style relief]``.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--size", type=float, default=200.0)
    ap.add_argument("--style", default="relief", choices=("relief", "pierced", "deboss"))
    ap.add_argument("--out", default=None)
    args = ap.parse_args(argv)
    from fabtiles import Star
    from fabtiles.geometry.tile import TileGeometry
    from fabtiles.making import export_region
    from fabtiles.pattern.packing import HexPacking

    t0 = time.perf_counter()
    tile = TileGeometry("square", args.size, HexPacking(15.0, Star.preset("table3-3")), frame=5.0, stroke=1.0)
    region, outline = tile.region(), tile.outline_shape()
    t1 = time.perf_counter()
    out = Path(args.out or tempfile.mkdtemp()) / "tile.step"
    export_region(
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
        f"region {t1 - t0:.2f} s, step {t2 - t1:.2f} s, total {t2 - t0:.2f} s; "
        f"{out.stat().st_size / 1e6:.1f} MB -> {out}"
    )


if __name__ == "__main__":
    main()
