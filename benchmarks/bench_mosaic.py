"""Benchmark: the pattern in colours (issue 33) on the 600 x 400 mm sheet.

- the face classes of the sheet's tile (about 10,000 faces), in process, its region made first:
  target under 1 s (``benchmarks/bench_faces.py`` breaks it down);
- whole ``fabtiles build`` commands, paired (A B A B ...; medians of the pairs' ratios, wall and
  CPU): the sheet's mosaic 3MF (``print_style = "mosaic"``, ``[colour] by = "shape"``) against its
  relief 3MF: target within 2x.

Run by hand, never in CI::

    python benchmarks/bench_mosaic.py            # 5 pairs
    python benchmarks/bench_mosaic.py --runs 9
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
SHEET = ROOT / "samples" / "sheet-600x400.toml"
MOSAIC = ("--set", 'output.print_style="mosaic"', "--set", 'colour.by="shape"')


def run(args) -> tuple[float, float]:
    """``(wall, CPU)`` seconds of one whole command (CPU: the child's user + system time)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(args, cwd=ROOT, env=dict(os.environ, PYTHONPATH=str(ROOT)), capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(map(str, args))} failed:\n{proc.stderr}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def face_class_seconds(runs: int) -> float:
    """Median seconds of :func:`~fabtiles.geometry.faces.face_classes` on the sheet's tile, its region made."""
    sys.path.insert(0, str(ROOT))
    from fabtiles.designs.design_file import load_design
    from fabtiles.geometry.faces import face_classes

    tile = load_design(SHEET).build_tile()
    tile.region()
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        classes = face_classes(tile, by="shape")
        times.append(time.perf_counter() - t0)
    print(f"sheet: {len(classes.faces):,} faces in {len(classes.classes)} classes")
    return statistics.median(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args(argv)
    classes = face_class_seconds(args.runs)
    with tempfile.TemporaryDirectory() as tmp:
        base = [sys.executable, "-m", "fabtiles", "build", str(SHEET), "--format", "3mf"]
        mosaic = base + ["-o", str(Path(tmp) / "mosaic"), *MOSAIC]
        relief = base + ["-o", str(Path(tmp) / "relief")]
        run(mosaic), run(relief)  # warm-up
        pairs = [(run(mosaic), run(relief)) for _ in range(args.runs)]
    wall_m, wall_r = (statistics.median(p[i][0] for p in pairs) for i in (0, 1))
    cpu_m, cpu_r = (statistics.median(p[i][1] for p in pairs) for i in (0, 1))
    wall_ratio = statistics.median(m[0] / r[0] for m, r in pairs)
    cpu_ratio = statistics.median(m[1] / r[1] for m, r in pairs)
    print("| what | seconds (median) | ratio (median of pairs) | target |")
    print("|---|---:|---:|---|")
    print(f"| face classes of the 600 x 400 mm sheet, in process | {classes:.3f} | | < 1 s |")
    print(f"| sheet 600x400: mosaic 3MF / relief 3MF, wall | {wall_m:.2f} / {wall_r:.2f} | {wall_ratio:.2f}x | <= 2x |")
    print(f"| the same, CPU | {cpu_m:.2f} / {cpu_r:.2f} | {cpu_ratio:.2f}x | <= 2x |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
