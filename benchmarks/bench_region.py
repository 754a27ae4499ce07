"""Time the material region of a 600 x 400 mm sheet (run by hand).

    python benchmarks/bench_region.py [--no-baseline] [--repeat N]

Sheet: rectangle 600 x 400 mm, HexPacking R = 15 mm, main motif table3-3, default
gap motif, stroke 1.0 mm, frame 5 mm. Prints the time of the pattern segments, of
``Tile.region()`` for each join, and of the naive baseline: every segment buffered
by GEOS (flat caps, mitre joins) and unioned in one ``shapely.union_all``.
"""

from __future__ import annotations

import argparse
import time

import shapely

from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking
from fabtiles.pattern.star import Star


def sheet(join: str = "miter") -> TileGeometry:
    pack = HexPacking(radius=15, motif=Star.preset("table3-3"))
    return TileGeometry("rectangle", (600, 400), pack, frame=5.0, stroke=1.0, join=join)


def best_of(fn, repeat: int) -> tuple[float, object]:
    best, out = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-baseline", action="store_true", help="skip the slow GEOS baseline")
    args = ap.parse_args()

    import manifold3d  # noqa: F401  (import cost is not the region's)

    t, seg = best_of(lambda: sheet().segments(), args.repeat)
    print(f"pattern segments      {t:7.3f} s  ({len(seg)} segments)")
    for join in ("miter", "bevel", "round"):
        t, reg = best_of(lambda join=join: sheet(join).region(), args.repeat)
        parts = len(getattr(reg, "geoms", [reg]))
        print(f"region join={join:<6}    {t:7.3f} s  (valid={reg.is_valid}, parts={parts}, area={reg.area:.1f} mm2)")
    t, cl = best_of(lambda: sheet().centrelines(), args.repeat)
    print(f"centrelines (clipped) {t:7.3f} s  ({len(cl)} segments)")
    if not args.no_baseline:
        tile = sheet()

        def naive():
            bands = shapely.buffer(shapely.linestrings(tile.segments()), 0.5, cap_style="flat", join_style="mitre")
            return shapely.union_all(bands)

        t, _ = best_of(naive, 1)
        print(f"naive GEOS union      {t:7.3f} s  (bands only: no joins, frame or clip)")


if __name__ == "__main__":
    main()
