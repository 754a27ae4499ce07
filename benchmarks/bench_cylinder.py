"""Benchmark: a texture roller and a lampshade wrapped onto a cylinder, against the flat strip.

Library calls in one process (the imports paid before the clock starts): the unrolled strip's
flat print (:func:`~fabtiles.solid.print_model.print_model`, its fused body, the STL's bytes)
against the same print wrapped (:func:`~fabtiles.solid.cylinder.cylinder_print`: the flat
body, its wrap, the STL's bytes; the lampshade with its lamp holder fused). The pattern is
table3-2 on the hex packing with 1 mm bands, fitted so the circumference is a whole number of
periods. Wall time, the best of ``--runs``, and the triangles. Run by hand, never in CI::

    python benchmarks/bench_cylinder.py
    python benchmarks/bench_cylinder.py --runs 1 --only roller
"""

from __future__ import annotations

import argparse
import math
import time

import shapely

from fabtiles import Star
from fabtiles.export.stl import model_stl_bytes
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking
from fabtiles.solid.cylinder import LampHolder, cylinder_print
from fabtiles.solid.print_model import print_model

CASES = {
    # name: diameter, length, style, packing periods round, rims (mm), holder
    "roller": (60.0, 80.0, "relief", 12, 0.0, None),
    "shade": (120.0, 150.0, "pierced", 16, 4.0, LampHolder(fitting_mm=40)),
}


def strip(diameter, length, periods, rims):
    """The unrolled strip's region and outline, and its circumference."""
    c = math.pi * diameter
    pack = HexPacking(radius=c / (2 * periods), motif=Star.preset("table3-2"))
    tile = TileGeometry("rectangle", (c, length), pack, stroke=1.0)
    region, outline = tile.region(), tile.outline_shape()
    if rims:
        bands = [shapely.box(0, 0, c, rims), shapely.box(0, length - rims, c, length)]
        region = shapely.union_all([region, *bands]).intersection(outline)
    return region, outline, c


def once(name: str, wrapped: bool) -> tuple[float, int]:
    diameter, length, style, periods, rims, holder = CASES[name]
    region, outline, c = strip(diameter, length, periods, rims)
    start = time.perf_counter()
    model = print_model(region, outline, profile="fdm-0.4mm", style=style)
    if wrapped:
        model = cylinder_print(model, circumference_mm=c, outer_radius_mm=diameter / 2, holder=holder)
    model_stl_bytes(model)
    return time.perf_counter() - start, len(model.fused.faces)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--only", choices=list(CASES))
    args = parser.parse_args()
    print("| print | flat strip: s, triangles | wrapped: s, triangles | ratio |")
    print("|---|---:|---:|---:|")
    for name in [args.only] if args.only else list(CASES):
        flat = min((once(name, False) for _ in range(args.runs)), key=lambda r: r[0])
        cyl = min((once(name, True) for _ in range(args.runs)), key=lambda r: r[0])
        d, length = CASES[name][:2]
        print(
            f"| {name} {d:g} x {length:g} mm | {flat[0]:.2f}, {flat[1]:,} | {cyl[0]:.2f}, {cyl[1]:,} "
            f"| {cyl[0] / flat[0]:.1f}x |"
        )


if __name__ == "__main__":
    main()
