"""Benchmark: the roller and lampshade samples built whole, against the same pattern as a flat tile.

Whole ``fabtiles build`` processes (imports included, the designs' own formats: STL and 3MF) of
``samples/roller-60x80.toml`` and ``samples/lampshade-120x150.toml``, each against the same
design as a flat tile of its unrolled size: a ``C x L`` rectangle (``C`` the fitted
circumference), the packing as fitted (the radius ``fabtiles build`` reports), frame 0, the
same stroke, print style, heights and printer; the flat tile has no rims, no mirror, no bore
and no lamp holder, its plate is the style's default, and it is made whole (``pieces = false``: the
shade's strip is longer than the printer's bed). Run in turn (flat, cylinder, flat,
...) so that each pair's ratio holds while a shared machine's speed drifts; CPU time (the
child's user + system) and wall time, medians; the STL's triangles and both files' sizes.

``--stages`` also times the cylinder's steps in one process (the imports paid before the
clock starts; CPU time, the best of 3): the design and its fit, the strip's flat print and its
fused body, the wrap of that body (the STL's mesh) and of the 3MF's parts (``--runs 0``: only
those). Run by hand, never in CI::

    python benchmarks/bench_cylinder.py              # both samples, 3 pairs each
    python benchmarks/bench_cylinder.py --runs 1 --only roller --stages
"""

from __future__ import annotations

import argparse
import statistics
import struct
import sys
import tempfile
import time
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10
    import tomli as tomllib

from build_timing import timed_build

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

SAMPLES = {
    "roller": ROOT / "samples" / "roller-60x80.toml",
    "lampshade": ROOT / "samples" / "lampshade-120x150.toml",
}


def flat_design(sample: Path, folder: Path) -> Path:
    """The sample as a flat tile of its unrolled size (see the module text), written into ``folder``."""
    import tomli_w

    from fabtiles.designs.design_file import load_design

    fitted = load_design(sample)  # the packing fitted round the cylinder, the strip's size C x L
    text = tomllib.loads(sample.read_text())
    surface = text.pop("surface")
    text["packing"]["radius"] = fitted.packing.radius
    width, length = fitted.tile_spec.size
    text["tile"] = dict(text.get("tile", {}), outline="rectangle", size=[width, length], frame=0.0)
    text["output"]["pieces"] = False  # whole, as the cylinder is (the shade's strip is longer than the bed)
    assert surface["shape"] == "cylinder"
    path = folder / f"{sample.stem}-flat.toml"
    path.write_text(tomli_w.dumps(text))
    return path


def files(out: Path) -> tuple[int, float, float]:
    """The STL's triangles and the STL's and 3MF's sizes (MB) in ``out``."""
    (stl,) = out.glob("*.stl")
    (tmf,) = out.glob("*.3mf")
    with stl.open("rb") as f:
        f.seek(80)
        (triangles,) = struct.unpack("<I", f.read(4))
    return triangles, stl.stat().st_size / 1e6, tmf.stat().st_size / 1e6


def stages(sample: Path) -> dict:
    """Seconds of the cylinder's steps in this process (see the module text)."""
    from fabtiles.designs.design_file import load_design
    from fabtiles.making.models import BuildOptions, Models

    best: dict = {}
    for _ in range(3):
        out = {}
        t = time.process_time()
        design = load_design(sample)
        models = Models(design.build_tile(), BuildOptions.of_design(design))
        cp = models.print
        out["design and fit"] = time.process_time() - t
        t = time.process_time()
        cp.model.fused  # noqa: B018 (made on first use)
        out["strip's flat print, fused"] = time.process_time() - t
        t = time.process_time()
        cp.fused  # noqa: B018
        out["wrap of the fused body (STL)"] = time.process_time() - t
        t = time.process_time()
        cp.parts  # noqa: B018
        out["wrap of the parts (3MF)"] = time.process_time() - t
        best = {k: min(v, best.get(k, v)) for k, v in out.items()}
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=3, help="pairs of builds per sample (0: none)")
    ap.add_argument("--only", nargs="*", choices=list(SAMPLES), help="run only these samples")
    ap.add_argument("--stages", action="store_true", help="also time the cylinder's steps in process")
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for name, sample in SAMPLES.items():
            if (args.only and name not in args.only) or args.runs < 1:
                continue
            flat = flat_design(sample, folder)
            runs: dict = {"flat": [], "cylinder": []}
            for k in range(args.runs):
                for label, design in (("flat", flat), ("cylinder", sample)):
                    runs[label].append(timed_build(design, folder / f"{name}-{label}-{k}"))
            cpu = {label: statistics.median(c for c, _ in r) for label, r in runs.items()}
            wall = {label: statistics.median(w for _, w in r) for label, r in runs.items()}
            made = {label: files(folder / f"{name}-{label}-0") for label in runs}
            rows.append((name, cpu, wall, made))
            print(f"{name} done", file=sys.stderr, flush=True)
    if rows:
        print("| sample | flat tile C x L: CPU s (wall), triangles, STL + 3MF MB | cylinder: the same | ratio CPU |")
        print("|---|---:|---:|---:|")
    for name, cpu, wall, made in rows:
        cells = [
            f"{cpu[k]:.2f} ({wall[k]:.2f}), {made[k][0]:,}, {made[k][1]:.1f} + {made[k][2]:.1f}"
            for k in ("flat", "cylinder")
        ]
        print(f"| {name} | {cells[0]} | {cells[1]} | {cpu['cylinder'] / cpu['flat']:.2f}x |")
    if args.stages:
        import fabtiles.making.models  # noqa: F401 (the imports paid before the clock)

        for name, sample in SAMPLES.items():
            if args.only and name not in args.only:
                continue
            print(name, ", ".join(f"{k} {v:.2f} s" for k, v in stages(sample).items()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
