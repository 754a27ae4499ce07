"""Benchmark: whole ``fabtiles build`` commands, paired (issue 31: one model per build).

Each figure is a whole process (imports included), run in turn with the command it
is compared with (A B A B ...), so the ratio of each pair holds while a shared
machine's speed drifts; the medians are quoted. Run by hand, never in CI::

    python benchmarks/bench_build.py                  # this checkout, 5 pairs each
    python benchmarks/bench_build.py --before ../old  # also the README's job on another checkout
    python benchmarks/bench_build.py --runs 3 --only sheet-cut

The comparisons and their targets (issue 31):

- ``sheet-cut``: ``samples/sheet-600x400.toml`` in dxf + svg + lbrn2 against dxf alone: <= 1.2x;
- ``sheet-print``: the same in stl + 3mf against stl alone: <= 1.2x;
- ``step-vs-stl``: the 150 mm sample (``samples/table3-3.toml``) in STEP against STL: <= 4x;
- ``relief-step``: a 200 x 200 mm relief (table3-3, R = 15 mm, 5 mm frame) in STEP: < 5 s;
- ``readme-job``: the README's main job (``samples/table3-3.toml``, its five formats), against
  ``--before`` when given: at least 2x faster than before.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

RELIEF_200 = """
[motif]
preset = "table3-3"
[packing]
radius = 15
[tile]
outline = "square"
size = 200
frame = 5
stroke = 1.0
[output]
formats = ["step"]
print_style = "relief"
"""


def command(checkout: Path, design: Path, formats, out: Path):
    args = [sys.executable, "-m", "fabtiles", "build", str(design), "-o", str(out)]
    for f in formats:
        args += ["--format", f]
    # run from the checkout: ``python -m`` puts the working folder ahead of PYTHONPATH
    return args, dict(os.environ, PYTHONPATH=str(checkout)), checkout


def timed(args, env, cwd) -> float:
    t0 = time.perf_counter()
    proc = subprocess.run(args, env=env, cwd=cwd, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(args)} failed:\n{proc.stderr}")
    return dt


def paired(a, b, runs: int) -> tuple[float, float, float]:
    """Median seconds of A and B and the median of the ratios A/B, A and B run in turn after a warm-up."""
    timed(*a), timed(*b)
    ta, tb = [], []
    for _ in range(runs):
        ta.append(timed(*a))
        tb.append(timed(*b))
    return statistics.median(ta), statistics.median(tb), statistics.median(x / y for x, y in zip(ta, tb, strict=True))


def single(a, runs: int) -> float:
    timed(*a)
    return statistics.median(timed(*a) for _ in range(runs))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--before", type=Path, help="another checkout, for the README's job before and after")
    ap.add_argument("--only", action="append", default=[])
    args = ap.parse_args(argv)

    def want(name):
        return not args.only or name in args.only

    sheet, sample = ROOT / "samples" / "sheet-600x400.toml", ROOT / "samples" / "table3-3.toml"
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        relief = tmp / "relief-200.toml"
        relief.write_text(RELIEF_200)
        out = tmp / "out"
        rows = []
        if want("sheet-cut"):
            ma, mb, r = paired(
                command(ROOT, sheet, ["dxf", "svg", "lbrn2"], out), command(ROOT, sheet, ["dxf"], out), args.runs
            )
            rows.append(("sheet 600x400: dxf + svg + lbrn2 / dxf", f"{ma:.2f} / {mb:.2f}", f"{r:.2f}x", "<= 1.2x"))
        if want("sheet-print"):
            ma, mb, r = paired(command(ROOT, sheet, ["stl", "3mf"], out), command(ROOT, sheet, ["stl"], out), args.runs)
            rows.append(("sheet 600x400: stl + 3mf / stl", f"{ma:.2f} / {mb:.2f}", f"{r:.2f}x", "<= 1.2x"))
        if want("step-vs-stl"):
            ma, mb, r = paired(command(ROOT, sample, ["step"], out), command(ROOT, sample, ["stl"], out), args.runs)
            rows.append(("table3-3 150 mm: step / stl", f"{ma:.2f} / {mb:.2f}", f"{r:.2f}x", "<= 4x"))
        if want("relief-step"):
            m = single(command(ROOT, relief, ["step"], out), args.runs)
            rows.append(("200 x 200 mm relief: step", f"{m:.2f}", "", "< 5 s"))
        if want("readme-job"):
            five = ["dxf", "svg", "stl", "3mf", "step"]
            if args.before:
                old = args.before / "samples" / "table3-3.toml"
                ma, mb, r = paired(command(args.before, old, five, out), command(ROOT, sample, five, out), args.runs)
                rows.append(
                    ("README job (5 formats): before / after", f"{ma:.2f} / {mb:.2f}", f"{r:.2f}x faster", ">= 2x")
                )
            else:
                m = single(command(ROOT, sample, five, out), args.runs)
                rows.append(("README job (5 formats)", f"{m:.2f}", "", ""))
    print("| command | seconds (median) | ratio (median of pairs) | target |")
    print("|---|---:|---:|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
