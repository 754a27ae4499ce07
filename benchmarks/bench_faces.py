"""Time the face classes of the 600 x 400 mm sheet (issue 33; run by hand, never in CI).

    python benchmarks/bench_faces.py [--repeat N] [--no-baseline]

The sheet is ``samples/sheet-600x400.toml`` (table3-3 rosettes, hex packing R = 15 mm,
about 10,000 faces). Its region is made once and kept (the tile caches it, and every
build has it already); then ``face_classes`` is timed, best of ``--repeat``: the faces
read from the region, the whole faces of one period of the packing, the look-up of each
tile face's whole face, the congruence of the distinct whole faces. The issue's target:
under 1 s. For comparison, the straightforward way: ``inlay.shape_key`` of every face.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from bench_region import best_of  # the same best-of-N timer (run as a script: benchmarks/ is on the path)

SAMPLE = Path(__file__).resolve().parents[1] / "samples" / "sheet-600x400.toml"
TARGET_S = 1.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-baseline", action="store_true", help="skip shape_key of every face")
    args = ap.parse_args()

    from fabtiles.designs.design_file import load_design
    from fabtiles.geometry import faces as F
    from fabtiles.geometry.narrow import fill_small_holes

    tile = load_design(SAMPLE).build_tile()
    t = time.perf_counter()
    region = tile.region()
    print(f"region (once, cached)        {time.perf_counter() - t:7.3f} s")

    t, faces = best_of(lambda: F._faces(region, tile.outline_shape()), args.repeat)
    print(f"  faces from the region      {t:7.3f} s  ({len(faces)} faces)")
    t, (_wholes, index, _) = best_of(lambda: F._whole_faces(tile, faces), args.repeat)
    print(f"  whole faces and look-up    {t:7.3f} s  ({len(set(index.tolist()))} distinct whole faces)")
    t, fc = best_of(lambda: F.face_classes(tile), args.repeat)
    verdict = "within" if t < TARGET_S else "OVER"
    print(
        f"face_classes(by='shape')     {t:7.3f} s  ({len(fc.faces)} faces, {len(fc.classes)} classes; "
        f"{verdict} the {TARGET_S:g} s target)"
    )
    for c in fc.classes:
        print(f"    {c.letter}  {c.count:6d}  {c.description:<18} {c.area_mm2:12.1f} mm2")
    t, _ = best_of(lambda: F.face_classes(tile, by="none"), args.repeat)
    print(f"face_classes(by='none')      {t:7.3f} s")
    filled, n = fill_small_holes(region, 1.2)
    t, fc = best_of(lambda: F.face_classes(tile, region=filled), args.repeat)
    print(f"small holes filled (1.2 mm)  {t:7.3f} s  ({len(fc.faces)} faces, {n} filled, {len(fc.classes)} classes)")
    if not args.no_baseline:
        from fabtiles.geometry.inlay import shape_key

        t, keys = best_of(lambda: {shape_key(p) for p in faces}, 1)
        print(
            f"baseline: shape_key of every face  {t:7.3f} s  ({len(keys)} keys; the pieces cut by the frame "
            f"each a shape of their own)"
        )


if __name__ == "__main__":
    main()
