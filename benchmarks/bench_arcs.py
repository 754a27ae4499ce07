"""Benchmark: curves as arcs in the cutter files (issue 35), before and after, paired.

For the 100 mm circle tile of the issue (3.3.3.4.4, outline circles, round joins), the
600 x 400 mm sheet and the 2440 x 1220 mm router panel: the DXF's vertices and bytes, the
LightBurn project's and the SVG's bytes, and the CPU time of the cut plan and of each
writer, with the arcs ("after") and with the flattened paths as before ("before": the
plan's arc fit switched off, so the writers get no arc). Each pair runs back to back,
``--repeat`` times, best of each kept: CPU time (``time.process_time``), the machine is shared.

Run::

    python benchmarks/bench_arcs.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import time
from contextlib import contextmanager
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CIRCLE = (
    '[packing]\nkind = "archimedean"\ntiling = "3.3.3.4.4"\noutline_circles = true\n'
    '[tile]\noutline = "circle"\nsize = 100\njoin = "round"\n'
)


@contextmanager
def flattened():
    """The cut plan as before issue 35: no arc fitted, every path its flattened chords."""
    from fabtiles.geometry import arcs, cut_plan

    before = cut_plan.curves
    cut_plan.curves = lambda rings, **kw: [arcs.Curve(np.asarray(r, float), np.zeros(len(r))) for r in rings]
    try:
        yield
    finally:
        cut_plan.curves = before


def _cpu(fn):
    t = time.process_time()
    out = fn()
    return time.process_time() - t, out


def measure(design, repeat: int, formats) -> dict:
    from fabtiles.export.dxf import dxf_bytes
    from fabtiles.export.laser_svg import svg_bytes
    from fabtiles.export.lbrn2 import lbrn2_bytes
    from fabtiles.making.models import BuildOptions, Models

    writers = {"dxf": dxf_bytes, "svg": svg_bytes, "lbrn2": lbrn2_bytes}
    tile = design.build_tile()
    options = BuildOptions.of_design(design)
    region = Models(tile, options).cut_region  # the region once: the same input to both
    best: dict = {}
    for _ in range(repeat):
        for label in ("before", "after"):

            def plan():
                m = Models(tile, options)
                m.__dict__["cut_region"] = region
                return m.cut

            if label == "before":
                with flattened():
                    t, p = _cpu(plan)
            else:
                t, p = _cpu(plan)
            row = best.setdefault(label, {"plan_s": t})
            row["plan_s"] = min(row["plan_s"], t)
            for fmt in formats:
                t, data = _cpu(lambda fmt=fmt, p=p: writers[fmt](p))
                row[f"{fmt}_s"] = min(row.get(f"{fmt}_s", t), t)
                row[f"{fmt}_bytes"] = len(data)
            row["vertices"] = (
                p.report.stats["vertices"]
                if label == "after"
                else sum(len(x) for layer in p.layers for x in layer.paths)
            )
            row["arcs"] = p.report.stats.get("arcs", 0) if label == "after" else 0
    return best


def main() -> None:
    from fabtiles.designs.design_file import design_from_text, load_design

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    cases = [
        ("circle tile 100 mm", design_from_text(CIRCLE, name="circle"), ("dxf", "svg", "lbrn2")),
        ("sheet 600 x 400 mm", load_design(ROOT / "samples" / "sheet-600x400.toml"), ("dxf", "svg", "lbrn2")),
        ("panel 2440 x 1220 mm (router)", load_design(ROOT / "samples" / "panel-2440x1220.toml"), ("dxf", "svg")),
    ]
    for name, design, formats in cases:
        res = measure(design, args.repeat, formats)
        b, a = res["before"], res["after"]
        print(f"\n{name}: vertices {b['vertices']:,} -> {a['vertices']:,} ({a['arcs']:,} arcs)")
        print(f"  plan (CPU s)      {b['plan_s']:.3f} -> {a['plan_s']:.3f}")
        for fmt in formats:
            print(
                f"  {fmt:5} bytes {b[f'{fmt}_bytes']:>11,} -> {a[f'{fmt}_bytes']:>11,};"
                f"  write (CPU s) {b[f'{fmt}_s']:.3f} -> {a[f'{fmt}_s']:.3f}"
            )
        total_b = b["plan_s"] + sum(b[f"{f}_s"] for f in formats)
        total_a = a["plan_s"] + sum(a[f"{f}_s"] for f in formats)
        print(f"  plan + every file (CPU s) {total_b:.3f} -> {total_a:.3f} ({total_a / total_b:.2f}x)")


if __name__ == "__main__":
    main()
