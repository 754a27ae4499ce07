"""Benchmark: what interlace adds to the 600 x 400 mm sheet's DXF and STL (issue 16).

Sheet: rectangle 600 x 400 mm, HexPacking R = 15 mm, table3-3, frame 5 mm, stroke
1 mm (34,152 centre-line segments). Each file is written end to end from a fresh
tile (region, checks, contours or mesh, file), plain and interlaced, best of
``--repeat`` runs; the weave alone (strands and over/under) is timed too.
Target: interlace adds at most 50 % to the DXF and the STL time.

Run by hand: ``python benchmarks/bench_interlace.py [--repeat 2] [--stages]``. Timings
on a shared machine vary; run it when the machine is quiet. ``--stages`` also times
the STL's stages one by one (best of ``--repeat``), plain against interlaced: where
the interlaced relief's extra time goes.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path


def sheet(interlace: bool):
    import fabtiles as ft

    pack = ft.HexPacking(radius=15, motif=ft.Star.preset("table3-3"))
    return ft.Tile("rectangle", (600, 400), pack, frame=5.0, stroke=1.0, interlace=interlace)


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def stl_stages(woven: bool) -> dict:
    """Seconds of each stage of the relief STL of the sheet, as the STL's print model runs them."""
    from fabtiles.export import stl
    from fabtiles.geometry import interlace
    from fabtiles.solid import _mesh_build as mb
    from fabtiles.solid import levels, mesh_check, parts

    out, t = {}, time.perf_counter()

    def lap(name):
        nonlocal t
        now = time.perf_counter()
        out[name] = out.get(name, 0.0) + now - t
        t = now

    tile = sheet(woven)
    region, outline = tile.region(), tile.outline_shape()
    lap("tile and region")
    dips = interlace.tile_dips(tile) if woven else None
    lap("weave and dips")
    _, stack, _ = parts.prepare_print(region, outline, "fdm-0.4mm", None, {}, tile.stroke, path="t.stl", fmt="stl")
    r, o = parts._snapped(region, outline)
    dips = parts._leveled(dips)
    lap("print checks, snapping")
    if woven:
        cov = levels.body_coverage("relief", r, o, stack, dips, leveled=True)
    else:
        cov = mb.coverage_pair(r, o, region_z=stack.base + stack.relief, rest_z=stack.base, bottom=0.0)
    lap("cells (coverage)")
    verts, faces = mb.mesh_coverage(cov)
    lap("triangles and walls")
    volume, bodies = parts._expected("relief", r, o, stack, dips)
    mverts, mfaces = mesh_check.check_indexed(verts, faces, volume=volume, bodies=bodies)
    lap("slicer-exact check")
    stl.stl_bytes(mverts, mfaces)
    lap("STL bytes")
    out["triangles"] = len(mfaces)
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--stages", action="store_true", help="also time the STL's stages")
    args = ap.parse_args(argv)
    from fabtiles.pattern.interlace import weave

    out = Path(tempfile.mkdtemp())
    segments = sheet(False).segments()
    rows = [("weave alone", None, best(lambda: weave(segments), args.repeat))]
    for label, name, opts in (
        ("DXF pierced", "t.dxf", {}),
        ("DXF score", "t.dxf", {"mode": "score"}),
        ("STL relief", "t.stl", {}),
    ):
        plain = best(lambda name=name, opts=opts: sheet(False).export(out / name, **opts), args.repeat)
        woven = best(lambda name=name, opts=opts: sheet(True).export(out / name, **opts), args.repeat)
        rows.append((label, plain, woven))
    print(f"600 x 400 mm sheet, {len(segments):,} segments; best of {args.repeat}")
    print("| file | plain (s) | interlaced (s) | added |")
    print("|---|---|---|---|")
    for label, plain, woven in rows:
        if plain is None:
            print(f"| {label} | | {woven:.2f} | |")
        else:
            print(f"| {label} | {plain:.2f} | {woven:.2f} | {100 * (woven / plain - 1):+.0f} % |")
    if args.stages:
        runs = {w: [stl_stages(w) for _ in range(args.repeat)] for w in (False, True)}
        best_of = {w: {k: min(r[k] for r in runs[w]) for k in runs[w][0]} for w in runs}
        print()
        print("| STL stage | plain (s) | interlaced (s) | added (s) |")
        print("|---|---|---|---|")
        for k in best_of[True]:
            p, w = best_of[False][k], best_of[True][k]
            fmt = "{:,.0f}" if k == "triangles" else "{:.2f}"
            print(f"| {k} | {fmt.format(p)} | {fmt.format(w)} | {fmt.format(w - p)} |")


if __name__ == "__main__":
    main()
