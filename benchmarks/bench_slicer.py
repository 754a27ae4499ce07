"""Benchmark: PrusaSlicer slicing fabtiles' print files, with and without ``fill_small_holes``.

Issue 30: a pierced 150.8 mm tile whose STL held 3,017 holes (2,396 narrower than 0.8 mm)
kept PrusaSlicer 2.5 busy for over 12 minutes. This times whole ``prusa-slicer
--export-gcode`` runs (PrusaSlicer's own defaults, 0.2 mm layers) on:

- the issue's design, with its small openings filled and, with ``--unfilled``, without;
- ``--random N`` random designs (every tiling, print style, outline circles, joins;
  seeded, 40 to 150 mm), filled; each must slice within ``--limit`` seconds and its
  G-code must hold the expected number of layers.

Run by hand (never in CI: timings belong here, not in tests)::

    python benchmarks/bench_slicer.py --random 12 [--unfilled] [--seed 30]

Prints one line per file: triangles, holes at mid-height, slicing time, layers, and
whether it kept within the limit.
"""

from __future__ import annotations

import argparse
import random
import re
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

ISSUE_DESIGN = Path(__file__).resolve().parent.parent / "tests" / "export" / "test_print_small_holes.py"
PRUSA_CONFIG = "layer_height = 0.2\nfirst_layer_height = 0.2\nbed_shape = 0x0,300x0,300x300,0x300\n"
PRESETS = ("table1-part1", "table1-part2", "table2-left", "table2-right", "table3-1", "table3-2", "table3-3")


def issue_design(fill: bool) -> str:
    """The design of issue 30, as the tests hold it."""
    text = ISSUE_DESIGN.read_text()
    start = text.index('ISSUE_DESIGN = """') + len('ISSUE_DESIGN = """')
    return text[start : text.index('"""', start)].format(fill="true" if fill else "false", size=150.8)


def random_design(rng: random.Random) -> str:
    from fabtiles.pattern.tilings import TILINGS

    size = rng.uniform(40, 150)
    return f"""
[motif]
preset = "{rng.choice(PRESETS)}"
[packing]
kind = "archimedean"
tiling = "{rng.choice(sorted(TILINGS))}"
edge = {rng.uniform(8, 18):.2f}
outline_circles = {str(rng.random() < 0.5).lower()}
[tile]
outline = "{rng.choice(["square", "circle", "hexagon"])}"
size = {size:.1f}
frame = {rng.choice([1, 2, 3])}
stroke = {rng.uniform(0.8, 1.6):.2f}
join = "{rng.choice(["miter", "round", "bevel"])}"
[output]
print_style = "{rng.choice(["relief", "pierced", "deboss"])}"
fill_small_holes = true
"""


def slice_file(prusa: str, path: Path, work: Path, timeout: float) -> tuple[float, int | None]:
    ini = work / "printer.ini"
    ini.write_text(PRUSA_CONFIG)
    gcode = path.with_suffix(".gcode")
    t0 = time.perf_counter()
    try:
        subprocess.run(
            [
                prusa,
                "--loglevel",
                "1",
                "--datadir",
                str(work / "prusa-data"),
                "--load",
                str(ini),
                "--export-gcode",
                "--center",
                "150,150",
                "--output",
                str(gcode),
                str(path),
            ],
            capture_output=True,
            check=True,
            timeout=timeout,
        )
    except subprocess.TimeoutExpired:
        return time.perf_counter() - t0, None
    return time.perf_counter() - t0, len(re.findall(r"^;Z:", gcode.read_text(), flags=re.M))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--random", type=int, default=8, help="random designs to slice (default 8)")
    ap.add_argument("--seed", type=int, default=30)
    ap.add_argument("--unfilled", action="store_true", help="also slice the issue design unfilled (about 13 min)")
    ap.add_argument("--limit", type=float, default=120.0, help="seconds each filled file must slice in")
    args = ap.parse_args(argv)

    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making import build_design

    prusa = shutil.which("prusa-slicer")
    if prusa is None:
        raise SystemExit("prusa-slicer is not installed: apt-get install prusa-slicer")
    work = Path(tempfile.mkdtemp(prefix="bench-slicer-"))
    rng = random.Random(args.seed)
    jobs = [("issue design, filled", issue_design(True), True)]
    if args.unfilled:
        jobs.append(("issue design, unfilled", issue_design(False), False))
    jobs += [(f"random {k + 1}", random_design(rng), True) for k in range(args.random)]
    print(f"{'design':<24} {'style':<8} {'triangles':>9} {'filled':>7} {'slice s':>8} {'layers':>7}  within")
    for name, text, filled in jobs:
        d = design_from_text(text, name=name.replace(" ", "-").replace(",", ""))
        (report,) = build_design(d, work, ["stl"]).reports
        stack = report.stats["heights_mm"]
        height = sum(stack.values()) if report.stats["style"] == "relief" else next(iter(stack.values()))
        if report.stats["style"] == "deboss":
            height = stack["base"]
        seconds, layers = slice_file(prusa, Path(report.path), work, timeout=max(args.limit * 8, 900))
        expected = round(height / 0.2)
        ok = layers == expected and (not filled or seconds <= args.limit)
        print(
            f"{name:<24} {report.stats['style']:<8} {report.stats['triangles']:>9,} "
            f"{report.stats.get('filled_holes', 0):>7,} {seconds:>8.1f} {layers!s:>7}  "
            f"{'yes' if ok else 'NO'} (expected {expected} layers)",
            flush=True,
        )
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
