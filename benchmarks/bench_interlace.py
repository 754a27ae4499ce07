"""Benchmark: what interlace adds to the 600 x 400 mm sheet's DXF and STL (issue 16).

Sheet: rectangle 600 x 400 mm, HexPacking R = 15 mm, table3-3, frame 5 mm, stroke
1 mm (34,152 centre-line segments). Each file is written end to end from a fresh
tile (region, checks, contours or mesh, file), plain and interlaced, best of
``--repeat`` runs; the weave alone (strands and over/under) is timed too.
Target: interlace adds at most 50 % to the DXF and the STL time.

Run by hand: ``python benchmarks/bench_interlace.py [--repeat 2]``. Timings on a
shared machine vary; run it when the machine is quiet.
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


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    from fabtiles.pattern.interlace import weave

    out = Path(tempfile.mkdtemp())
    segments = sheet(False).segments()
    rows = [("weave alone", None, best(lambda: weave(segments), args.repeat))]
    for label, name, opts in (("DXF pierced", "t.dxf", {}), ("DXF score", "t.dxf", {"mode": "score"}),
                              ("STL relief", "t.stl", {})):
        plain = best(lambda: sheet(False).export(out / name, **opts), args.repeat)
        woven = best(lambda: sheet(True).export(out / name, **opts), args.repeat)
        rows.append((label, plain, woven))
    print(f"600 x 400 mm sheet, {len(segments):,} segments; best of {args.repeat}")
    print("| file | plain (s) | interlaced (s) | added |")
    print("|---|---|---|---|")
    for label, plain, woven in rows:
        if plain is None:
            print(f"| {label} | | {woven:.2f} | |")
        else:
            print(f"| {label} | {plain:.2f} | {woven:.2f} | {100 * (woven / plain - 1):+.0f} % |")


if __name__ == "__main__":
    main()
