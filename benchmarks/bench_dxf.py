"""Benchmark: laser DXF of a 600 x 400 mm sheet of table3-3 stars, R = 15 mm.

Issue 4 budget: the DXF of this sheet (about 10,000 holes after the kerf,
70,000 vertices) is written in under 2 s end to end (checks, kerf contours,
DXF) on a 2-core machine. The material region is the input: by default
``TileGeometry("rectangle", (600, 400), HexPacking(15, Star.preset("table3-3")), frame=5,
stroke=1.0).region()``; ``--synthetic`` uses a stand-alone union of stroked
motifs instead (no dependence on the tile module). Either is built once and
cached as WKB in the temporary folder.

Run::

    python benchmarks/bench_dxf.py [--repeat 3] [--svg] [--r12] [--synthetic]
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

import numpy as np
import shapely

CACHE = Path(tempfile.gettempdir()) / "fabtiles-bench-sheet-600x400-R15.wkb"
TILE_CACHE = Path(tempfile.gettempdir()) / "fabtiles-bench-tile-600x400-R15.wkb"
SIZE = (600.0, 400.0)
RADIUS = 15.0
FRAME = 5.0
STROKE = 1.0


def _motif_segments(star, centres, circle_radius):
    seg = star.segments()
    extent = float(np.hypot(seg[..., 0], seg[..., 1]).max())
    seg = seg * (circle_radius / extent)
    return (seg[None] + centres[:, None, None, :]).reshape(-1, 2, 2)


def sheet_centrelines(size=SIZE, radius=RADIUS):
    """Centre-lines of a hex packing of table3-3 stars over ``size``, lattice (0, 0) at the centre."""
    from fabtiles import Star

    w, h = size
    R = radius
    ii, jj = np.meshgrid(np.arange(-40, 41), np.arange(-40, 41))
    p = np.stack([ii.ravel() * 2 * R + jj.ravel() * R, jj.ravel() * math.sqrt(3) * R], axis=-1)
    keep = (np.abs(p[:, 0]) < w / 2 + R) & (np.abs(p[:, 1]) < h / 2 + R)
    p = p[keep]
    gaps = np.concatenate([p + [R, R / math.sqrt(3)], p + [R, -R / math.sqrt(3)]])
    gkeep = (np.abs(gaps[:, 0]) < w / 2 + R) & (np.abs(gaps[:, 1]) < h / 2 + R)
    big = _motif_segments(Star.preset("table3-3"), p, R)
    small = _motif_segments(Star(n=6, radii=(0.5, 1.0)), gaps[gkeep], R * (2 / math.sqrt(3) - 1))
    seg = np.concatenate([big, small]) + [w / 2, h / 2]
    return seg


def sheet_region(size=SIZE, radius=RADIUS, frame=FRAME, stroke=STROKE, *, cache=CACHE):
    """The material region (stroked bands + frame, clipped to the rectangle), cached as WKB."""
    if cache is not None and cache.exists():
        return shapely.from_wkb(cache.read_bytes())
    w, h = size
    seg = sheet_centrelines(size, radius)
    lines = shapely.linestrings(seg)
    bands = shapely.buffer(lines, stroke / 2, cap_style="flat", join_style="mitre")
    outline = shapely.box(0, 0, w, h)
    inner = shapely.box(frame, frame, w - frame, h - frame)
    pattern = shapely.union_all(bands, grid_size=None)
    region = shapely.union(shapely.intersection(pattern, outline), shapely.difference(outline, inner))
    region = shapely.normalize(region)
    if cache is not None:
        cache.write_bytes(shapely.to_wkb(region))
    return region


def tile_region(*, cache=TILE_CACHE):
    """The sheet as a real fabtiles Tile (cached as WKB)."""
    if cache is not None and cache.exists():
        return shapely.from_wkb(cache.read_bytes())
    from fabtiles import Star
    from fabtiles.geometry.tile import TileGeometry
    from fabtiles.pattern.packing import HexPacking

    region = TileGeometry(
        "rectangle", SIZE, HexPacking(RADIUS, Star.preset("table3-3")), frame=FRAME, stroke=STROKE
    ).region()
    if cache is not None:
        cache.write_bytes(shapely.to_wkb(region))
    return region


def main(argv=None):
    from fabtiles.geometry.contours import laser_contours
    from fabtiles.geometry.laser_checks import check_laser
    from fabtiles.machines.profiles import load_profile
    from fabtiles.making import export_region

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--svg", action="store_true", help="also time the laser SVG")
    ap.add_argument("--r12", action="store_true", help="also time the R12 DXF")
    ap.add_argument("--synthetic", action="store_true", help="stand-alone region instead of fabtiles' Tile")
    args = ap.parse_args(argv)

    t = time.perf_counter()
    region = sheet_region() if args.synthetic else tile_region()
    print(f"region: {time.perf_counter() - t:.2f} s (cache {CACHE if args.synthetic else TILE_CACHE})")
    outline = shapely.box(0, 0, *SIZE)
    parts = shapely.get_parts(region)
    holes = int(shapely.get_num_interior_rings(parts).sum())
    nseg = int(shapely.get_num_coordinates(region)) - len(parts) - holes
    print(
        f"sheet {SIZE[0]:g} x {SIZE[1]:g} mm, R = {RADIUS:g}: {len(parts)} parts, {holes} holes, "
        f"{nseg} segments (nominal)"
    )
    profile = load_profile("laser-3mm-plywood", kind="laser")

    def best(label, fn):
        times = []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            out = fn()
            times.append(time.perf_counter() - t0)
        print(f"{label:<28} best {min(times):.3f} s   (runs: {', '.join(f'{x:.3f}' for x in times)})")
        return out, min(times)

    best("checks", lambda: check_laser(region, outline, profile, stroke=STROKE))
    best(
        "kerf contours",
        lambda: laser_contours(region, outline, kerf_mm=profile.kerf_mm, tolerance_mm=profile.tolerance_mm),
    )
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "sheet.dxf"
        report, total = best(
            "DXF end to end",
            lambda: export_region(
                path, region=region, outline=outline, profile=profile, stroke=STROKE, fill_small_holes=False
            ),
        )
        print(f"  {path.stat().st_size / 1e6:.1f} MB; stats: {report.stats}")
        print("  " + report.summary().replace("\n", "\n  "))
        if args.r12:
            best(
                "DXF R12",
                lambda: export_region(
                    path,
                    region=region,
                    outline=outline,
                    profile=profile,
                    stroke=STROKE,
                    fill_small_holes=False,
                    dxf_version="R12",
                ),
            )
        if args.svg:
            best(
                "laser SVG",
                lambda: export_region(
                    Path(tmp) / "sheet.svg",
                    region=region,
                    outline=outline,
                    profile=profile,
                    stroke=STROKE,
                    fill_small_holes=False,
                ),
            )
    verdict = "PASS" if total < 2.0 else "FAIL"
    print(f"budget 2.0 s: {verdict} ({total:.3f} s)")
    return 0 if total < 2.0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
