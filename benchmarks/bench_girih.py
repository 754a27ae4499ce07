"""Benchmark: girih patterns on the sheet sample's 600 x 400 mm, against 4.8.8 at the same size.

The sheet of ``samples/sheet-600x400.toml`` (a 5 mm frame, stroke 1 mm) filled by each girih pattern at
level 0 (edge 12 mm, as ``samples/girih-decagon-bowtie.toml``) and by the decagon-bowtie pattern
subdivided once, twice and three times (edge 6 mm, as ``samples/classical/girih-subdivided.toml``), and
by Hankin's rays on 4.8.8 (edge 14 mm, 60 degrees, the reference of ``bench_two_uniform.py``) in the same
run. Each ``fabtiles build`` runs in a fresh process (imports included) for the DXF and the STL, the best
of ``--repeat`` wall times, with the sheet's segment count beside it. Then the subdivision alone: the
time to make one repeat of the subdivided pattern (:func:`~fabtiles.pattern.girih.girih_cell` and its
strapwork) at each level, in process, the best of ``--repeat``.

Run by hand (never in CI)::

    python benchmarks/bench_girih.py [--repeat 3] [--no-sheets] [--only "level 2" 4.8.8]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from bench_two_uniform import SHEET
from build_timing import timed_build

WINDOW = (-300.0, -200.0, 300.0, 200.0)
REFERENCE = """
[packing]
kind = "archimedean"
tiling = "4.8.8"
edge = 14
method = "hankin"
contact_angle = 60
"""
GIRIH = """
[packing]
kind = "girih"
girih_pattern = "{pattern}"
girih_level = {level}
edge = {edge}
"""
# label -> (pattern, level, edge mm); None is the 4.8.8 reference
SHEETS = {
    "4.8.8 (reference)": None,
    "decagon-bowtie": ("decagon-bowtie", 0, 12),
    "hexagons": ("hexagons", 0, 12),
    "rhombi": ("rhombi", 0, 12),
    "decagon-bowtie, level 1": ("decagon-bowtie", 1, 6),
    "decagon-bowtie, level 2": ("decagon-bowtie", 2, 6),
    "decagon-bowtie, level 3": ("decagon-bowtie", 3, 6),
}


def segments(spec) -> int:
    import fabtiles as ft

    if spec is None:
        return ft.ArchimedeanPacking("4.8.8", edge=14, method="hankin", contact_angle=60).segment_count(WINDOW)
    pattern, level, edge = spec
    return ft.GirihPacking(pattern, edge=edge, level=level).segment_count(WINDOW)


def sheets(repeat: int, only=None) -> None:
    print("| sheet | segments | DXF end to end s | STL end to end s |")
    print("|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for k, (label, spec) in enumerate(SHEETS.items()):
            if only and not any(word in label for word in only):
                continue
            design = Path(tmp) / f"sheet-{k}.toml"
            packing = REFERENCE if spec is None else GIRIH.format(pattern=spec[0], level=spec[1], edge=spec[2])
            design.write_text(packing + SHEET)
            walls = {}
            for fmt in ("dxf", "stl"):
                runs = [timed_build(design, Path(tmp) / f"out-{k}", "--format", fmt)[1] for _ in range(repeat)]
                walls[fmt] = min(runs)
            print(f"| {label} | {segments(spec):,} | {walls['dxf']:.2f} | {walls['stl']:.2f} |", flush=True)


def subdivision(repeat: int) -> None:
    from fabtiles.pattern import girih

    print()
    print("| level | tiles in one repeat | segments in one repeat | made in s |")
    print("|---:|---:|---:|---:|")
    for level in range(5):
        best = float("inf")
        for _ in range(repeat):
            girih.girih_cell.cache_clear()
            girih._cell_strapwork.cache_clear()
            t = time.perf_counter()
            seg, _ = girih._cell_strapwork("decagon-bowtie", level)
            best = min(best, time.perf_counter() - t)
        tiles = len(girih.girih_cell("decagon-bowtie", level).kinds)
        print(f"| {level} | {tiles:,} | {len(seg):,} | {best:.3f} |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--no-sheets", action="store_true", help="time the subdivision alone")
    parser.add_argument("--only", nargs="*", default=None, help="the sheets whose label holds one of these words")
    args = parser.parse_args()
    if not args.no_sheets:
        sheets(args.repeat, args.only)
    subdivision(args.repeat)


if __name__ == "__main__":
    main()
