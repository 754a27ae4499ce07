"""Benchmark: a panel larger than the bed built as pieces, against the same panel built whole.

Whole ``fabtiles build --format dxf`` processes (imports included), each panel built as
pieces for the 600 x 400 mm bed of ``laser-3mm-plywood`` and whole on a copy of that
profile with a bed larger than the panel, run in turn (A B A B ...) so that the ratio of
each pair holds while a shared machine's speed drifts; CPU time (the child's user +
system) and wall time, medians. Run by hand, never in CI::

    python benchmarks/bench_pieces.py              # both panels, 2 pairs each
    python benchmarks/bench_pieces.py --runs 1 --only sheet-2440

The panels:

- ``sheet-2440``: 2440 x 1220 mm (a full plywood sheet) of the sheet sample's pattern
  (``samples/sheet-600x400.toml``: table3-3 at R = 15 mm, 1 mm bands, a 5 mm frame), whose
  bands are too thin for a joint: the seams get bars. The target: at most 3x the whole build.
- ``screen``: ``samples/screen-1200x800.toml`` (R = 40 mm, 4 mm bands, a 20 mm frame).
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
from pathlib import Path

from build_timing import timed_build

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

SHEET_2440 = """
[motif]
preset = "table3-3"
[packing]
kind = "hex"
radius = 15
[tile]
outline = "rectangle"
size = [2440, 1220]
frame = 5.0
stroke = 1.0
[output]
formats = ["dxf"]
laser_profile = "{profile}"
"""


def _large_bed_profile(folder: Path, bed) -> Path:
    """``laser-3mm-plywood`` with a bed of ``bed`` mm: the panel fits it whole."""
    text = (ROOT / "profiles" / "laser-3mm-plywood.toml").read_text()
    text = text.replace("bed_mm = [600, 400]", f"bed_mm = [{bed[0]}, {bed[1]}]")
    path = folder / "laser-3mm-plywood-large.toml"
    path.write_text(text)
    return path


def _designs(folder: Path) -> dict:
    """``{panel: (design as pieces, design whole)}``."""
    large = _large_bed_profile(folder, (2600, 1400))
    out = {}
    for name, profile in (("pieces", "laser-3mm-plywood"), ("whole", str(large))):
        sheet = folder / f"sheet-2440-{name}.toml"
        sheet.write_text(SHEET_2440.format(profile=profile))
        screen = folder / f"screen-{name}.toml"
        text = (ROOT / "samples" / "screen-1200x800.toml").read_text()
        screen.write_text(text.replace('"laser-3mm-plywood"', f'"{profile}"'))
        out.setdefault("sheet-2440", []).append(sheet)
        out.setdefault("screen", []).append(screen)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=2, help="pairs of builds per panel")
    ap.add_argument("--only", nargs="*", choices=["sheet-2440", "screen"], help="run only these panels")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for panel, (pieces, whole) in _designs(folder).items():
            if args.only and panel not in args.only:
                continue
            runs: dict = {"pieces": [], "whole": []}
            for k in range(args.runs):
                for label, design in (("whole", whole), ("pieces", pieces)):
                    runs[label].append(timed_build(design, folder / f"{panel}-{label}-{k}", "--format", "dxf"))
            cpu = {label: statistics.median(c for c, _ in r) for label, r in runs.items()}
            wall = {label: statistics.median(w for _, w in r) for label, r in runs.items()}
            files = sorted(p.name for p in (folder / f"{panel}-pieces-0").iterdir())
            print(
                f"{panel}: whole {cpu['whole']:.1f} s CPU ({wall['whole']:.1f} s wall), as pieces "
                f"{cpu['pieces']:.1f} s CPU ({wall['pieces']:.1f} s wall): {cpu['pieces'] / cpu['whole']:.2f}x; "
                f"{sum(f.endswith('.dxf') for f in files)} piece files"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
