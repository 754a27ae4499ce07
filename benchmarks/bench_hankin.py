"""Benchmark: a 600 x 400 mm Hankin sheet on 4.8.8 against the paper's motifs on the same tiling and size.

Issue 36 budget: Hankin's polygons in contact (``samples/hankin/4.8.8.toml``: 67.5 degrees,
edge 14 mm) within 1.5 times the time of the paper's motifs (``samples/tilings/4.8.8.toml``,
edge 14 mm), on a 600 x 400 mm sheet (frame 5, stroke 1): the pattern, the region and the
laser DXF, end to end. The two are timed in pairs, one after the other, in CPU time
(``time.process_time``: the machine is shared) and each from its design file again (nothing
cached between runs); the figure is the median of the pairs' ratios, and the best of each.

Run by hand (never in CI)::

    python benchmarks/bench_hankin.py [--pairs 5]
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DESIGNS = {
    "motifs": HERE.parent / "samples" / "tilings" / "4.8.8.toml",
    "hankin": HERE.parent / "samples" / "hankin" / "4.8.8.toml",
}
SIZE = (600.0, 400.0)
TARGET = 1.5


def dense_edge(segments: int) -> float:
    """The edge (mm) at which the Hankin sheet holds about ``segments`` segments (bisection on segment_count)."""
    from fabtiles.designs.design_file import load_design

    pack = load_design(DESIGNS["hankin"]).build_tile().pattern
    window = (-SIZE[0] / 2, -SIZE[1] / 2, SIZE[0] / 2, SIZE[1] / 2)
    lo, hi = 1.0, 100.0
    for _ in range(40):
        mid = (lo * hi) ** 0.5
        lo, hi = (mid, hi) if pack.replace(edge=mid).segment_count(window) > segments else (lo, mid)
    return hi


def run_once(method: str, edge: float | None = None) -> dict:
    """One sheet of ``method``'s design (at ``edge``, if given): CPU seconds of each stage and the segments."""
    import fabtiles as ft
    from fabtiles.designs.design_file import load_design

    t = time.process_time()
    extra = [f"packing.edge={edge!r}"] if edge is not None else []
    design = load_design(
        DESIGNS[method], overrides=["tile.outline=rectangle", f"tile.size=[{SIZE[0]}, {SIZE[1]}]", *extra]
    )
    tile = design.build_tile(tile_cls=ft.Tile)
    seg = tile.segments()
    pattern = time.process_time() - t
    t = time.process_time()
    tile.region()
    region = time.process_time() - t
    laser = dataclasses.replace(ft.load_profile("laser-3mm-plywood"), bed_mm=(1300.0, 900.0))
    t = time.process_time()
    with tempfile.TemporaryDirectory() as tmp:
        tile.export(Path(tmp) / "sheet.dxf", profile=laser)
    dxf = time.process_time() - t
    return {
        "edge": design.packing.edge,
        "segments": len(seg),
        "pattern": pattern,
        "region": region,
        "dxf": dxf,
        "total": pattern + region + dxf,
    }


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=5, help="pairs of runs (default 5)")
    args = ap.parse_args(argv)
    first = run_once("motifs")  # also the warm-up: imports, first builds
    edge = dense_edge(first["segments"])  # Hankin at the motifs' segment count, for comparison
    runs = {"motifs": [], "hankin": [], "hankin, as many segments": []}
    ratios = {"hankin": [], "hankin, as many segments": []}
    for _ in range(args.pairs):
        pair = {
            "motifs": run_once("motifs"),
            "hankin": run_once("hankin"),
            "hankin, as many segments": run_once("hankin", edge),
        }
        for m, r in pair.items():
            runs[m].append(r)
        for m in ratios:
            ratios[m].append(pair[m]["total"] / pair["motifs"]["total"])
    print("| design | edge mm | segments | pattern s | region s | DXF s | end to end s (best) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for m, rs in runs.items():
        best = min(rs, key=lambda r: r["total"])
        print(
            f"| {m} | {best['edge']:.2f} | {best['segments']:,} | {best['pattern']:.2f} | {best['region']:.2f} | "
            f"{best['dxf']:.2f} | {best['total']:.2f} |"
        )
    for m, rs in ratios.items():
        print(
            f"\n{m} / motifs, CPU time end to end: median of {args.pairs} pairs {statistics.median(rs):.2f} "
            f"(range {min(rs):.2f} to {max(rs):.2f}; target <= {TARGET:g} for the sample's edge)"
        )


if __name__ == "__main__":
    main()
