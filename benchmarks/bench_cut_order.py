"""The cut order's travel on the 600 x 400 mm sheet: ours, vpype's, the order before (issue 37).

Run by hand (never in CI): ``python benchmarks/bench_cut_order.py [--repeat 5] [--sample PATH]``.

The sheet's cut plan is made once; its inner and outer layers, in the order the
contours were made (the Hilbert-curve order of ``geometry/contours.py``), are then

- ordered by :func:`fabtiles.geometry.cut_order.order_paths` (CPU time, best of ``--repeat``);
- ordered by vpype's ``linesort --two-opt`` (the same layers, each a vpype layer of closed
  lines, in process through ``vpype_cli.execute``; needs ``pip install vpype``).

Each order's travel is measured the same way: from the origin, through the inner
layer then the outer, closed contours ending where they start (vpype's own
pen-up length leaves out the move from the origin: printed beside it).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SHEET = ROOT / "samples" / "sheet-600x400.toml"


def contours(sample: Path) -> dict:
    """The sample's cut plan's paths, role -> list, in the order the contours were made."""
    from unittest import mock

    from fabtiles.designs.design_file import load_design
    from fabtiles.geometry import cut_plan
    from fabtiles.making.models import BuildOptions, Models
    from fabtiles.making.pipeline import prepare_tile

    design = load_design(sample)
    # the plan as it was made, before the cut order: path_orders stood aside (no role reordered)
    with mock.patch.object(cut_plan, "path_orders", lambda paths, **_: {}):
        plan = Models(prepare_tile(design), BuildOptions.of_design(design)).cut
    return {layer.role: list(layer.paths) for layer in plan.layers}


def travel(paths: dict) -> float:
    from fabtiles.geometry.cut_order import travel as layer_travel

    rings = [r for role in ("inner", "outer") for r in paths.get(role, ())]
    return layer_travel(rings)


def ours(paths: dict, repeat: int):
    from fabtiles.geometry.cut_order import order_paths

    best, out = float("inf"), None
    for _ in range(repeat):
        t = time.process_time()
        out = order_paths(paths)
        best = min(best, time.process_time() - t)
    return out, best


def vpype_order(paths: dict):
    import vpype as vp
    import vpype_cli

    doc = vp.Document()
    for k, role in enumerate(("inner", "outer"), start=1):
        if paths.get(role):
            doc.add(
                vp.LineCollection([np.append(r[:, 0] + 1j * r[:, 1], r[0, 0] + 1j * r[0, 1]) for r in paths[role]]), k
            )
    t = time.process_time()
    out = vpype_cli.execute("linesort --two-opt", doc)
    seconds = time.process_time() - t
    result = {
        role: [np.column_stack([line.real, line.imag])[:-1] for line in out.layers[k]]
        for k, role in enumerate(("inner", "outer"), start=1)
        if k in out.layers
    }
    pen_up = sum(out.layers[k].pen_up_length()[0] for k in out.layers)
    return result, seconds, pen_up


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sample", type=Path, default=SHEET)
    args = ap.parse_args(argv)
    paths = contours(args.sample)
    print(f"{args.sample.name}: {len(paths.get('inner', ())):,} inner contours, {len(paths.get('outer', ())):,} outer")
    print(f"{'order the contours were made in':40s} travel {travel(paths) / 1000:8.3f} m")
    mine, seconds = ours(paths, args.repeat)
    print(
        f"{'fabtiles cut order':40s} travel {travel(mine) / 1000:8.3f} m   {seconds:6.3f} s CPU (best of {args.repeat})"
    )
    try:
        theirs, vs, pen_up = vpype_order(paths)
    except ImportError:
        print("vpype is not installed: pip install vpype")
        return
    print(
        f"{'vpype linesort --two-opt':40s} travel {travel(theirs) / 1000:8.3f} m   {vs:6.3f} s CPU "
        f"(its pen-up length, without the move from the origin: {pen_up / 1000:.3f} m)"
    )
    print(f"ours / vpype's: {travel(mine) / travel(theirs):.4f}; ours / before: {travel(mine) / travel(paths):.4f}")


if __name__ == "__main__":
    main()
