"""Benchmark: two-uniform tilings on the sheet sample's 600 x 400 mm, against 4.8.8 at the same size.

The sheet of ``samples/sheet-600x400.toml`` (a 5 mm frame, stroke 1 mm) filled by Hankin's polygons in
contact (60 degrees, edge 14 mm, as ``samples/two-uniform-hankin.toml``) on each of the 20 tilings; each
``fabtiles build`` runs in a fresh process (imports included) for the DXF and the STL, the best of
``--repeat`` runs, 4.8.8 timed in the same run as the reference, and its segment count beside it.

Run by hand (never in CI)::

    python benchmarks/bench_two_uniform.py [--repeat 2] [--only "[3^6; 3^4.6]#2"]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from build_timing import timed_build


def _tilings() -> tuple[str, ...]:
    from fabtiles.pattern.tilings import TWO_UNIFORM

    return ("4.8.8", *TWO_UNIFORM)  # 4.8.8 first: the reference


SHEET = """
[tile]
outline = "rectangle"
size = [600, 400]
frame = 5.0
stroke = 1.0

[output]
laser_profile = "laser-3mm-plywood"
printer_profile = "fdm-0.4mm"
"""
"""The sheet sample's tile and machines (``samples/sheet-600x400.toml``), under a packing of the benchmark's."""

DESIGN = (
    """
[packing]
kind = "archimedean"
tiling = "{tiling}"
edge = 14
method = "hankin"
contact_angle = 60
"""
    + SHEET
)


def segments(tiling: str) -> int:
    from fabtiles.pattern.archimedean import TilingPacking

    return TilingPacking(tiling, edge=14, method="hankin", contact_angle=60).segment_count((-300, -200, 300, 200))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--only", nargs="*", default=None)
    args = parser.parse_args()
    print("| tiling | segments | DXF end to end s | STL end to end s |")
    print("|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for k, tiling in enumerate(args.only or _tilings()):
            design = Path(tmp) / f"sheet-{k}.toml"
            design.write_text(DESIGN.format(tiling=tiling))
            walls = {}
            for fmt in ("dxf", "stl"):
                runs = [timed_build(design, Path(tmp) / f"out-{k}", "--format", fmt)[1] for _ in range(args.repeat)]
                walls[fmt] = min(runs)
            print(f"| `{tiling}` | {segments(tiling):,} | {walls['dxf']:.2f} | {walls['stl']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
