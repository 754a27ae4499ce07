"""A plot's hatch fill at scale: ``plot_drawing(..., fill=True)`` of a large coloured tile.

Run by hand (never in CI): ``python benchmarks/bench_plot_fill.py [--size 300] [--pen 0.3] [--repeat 3]``.
In process, the design loaded once; for the plain hatch and the cross-hatch, the best CPU time
of ``--repeat`` drawings (the tile's faces and classes included: each drawing builds its tile),
the strokes and their pen-up travel, and the part of the time the hatching itself takes
(``geometry.hatch.hatch`` and ``hatch_order`` on the drawing's classes, timed apart).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def best(f, repeat: int):
    """``(least CPU seconds, last result)`` of ``repeat`` calls of ``f``."""
    times, out = [], None
    for _ in range(repeat):
        t = time.process_time()
        out = f()
        times.append(time.process_time() - t)
    return min(times), out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sample", type=Path, default=ROOT / "samples" / "mosaic-iznik.toml")
    ap.add_argument("--size", type=float, default=300.0)
    ap.add_argument("--pen", type=float, default=0.3)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)

    from fabtiles.designs.design_file import load_design
    from fabtiles.geometry.hatch import hatch, hatch_order
    from fabtiles.making.models import BuildOptions, Models
    from fabtiles.making.pipeline import prepare_tile
    from fabtiles.making.plot import ANGLES_DEG, plot_drawing

    design = load_design(args.sample, overrides=[f"tile.size={args.size:g}"])
    classes = Models(prepare_tile(design), BuildOptions.of_design(design)).face_classes
    for cross in (False, True):
        secs, drawing = best(lambda c=cross: plot_drawing(design, fill=True, pen_mm=args.pen, cross=c), args.repeat)
        strokes = sum(len(layer.paths) for layer in drawing.layers)

        def fill_only(c=cross):
            for k, _ in enumerate(classes.classes):
                h = hatch(
                    classes.faces[classes.labels == k],
                    spacing_mm=args.pen,
                    angle_deg=ANGLES_DEG[k % len(ANGLES_DEG)],
                    inset_mm=args.pen / 2,
                    cross=c,
                )
                hatch_order(h)

        fill_secs, _ = best(fill_only, args.repeat)
        print(
            f"{args.sample.stem} at {args.size:g} mm, pen {args.pen:g} mm{', cross-hatched' if cross else ''}: "
            f"{strokes:,} strokes, pen down {drawing.length_mm / 1000:.1f} m, pen up {drawing.travel_mm / 1000:.1f} m; "
            f"drawing {secs:.2f} s CPU, of which the hatching and its order {fill_secs:.2f} s (best of {args.repeat})"
        )


if __name__ == "__main__":
    main()
