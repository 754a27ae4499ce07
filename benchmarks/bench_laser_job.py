"""The 600 x 400 mm sheet as a LightBurn project against its DXF, and what the job estimate costs.

Run: ``python benchmarks/bench_laser_job.py [--repeat 5]``. Prints, best of ``--repeat``:

- in process: the shared laser preparation (checks, kerf contours), the job estimate
  alone, the DXF text and the ``.lbrn2`` text of the same job;
- whole commands: ``fabtiles build samples/sheet-600x400.toml --format dxf`` and
  ``--format lbrn2`` (imports included), each in a fresh process.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHEET = ROOT / "samples" / "sheet-600x400.toml"


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def in_process(repeat: int) -> dict:
    from fabtiles.designs.design_file import load_design
    from fabtiles.export import dxf, lbrn2
    from fabtiles.export.dispatch import laser_geometry
    from fabtiles.geometry import job_time
    from fabtiles.geometry.laser_checks import prepare_laser
    from fabtiles.making import prepare_tile

    tile = prepare_tile(load_design(SHEET))
    region, _ = laser_geometry(tile)
    outline = tile.outline_shape()
    job, _ = prepare_laser("sheet", "dxf", region=region, outline=outline, profile="laser-3mm-plywood")
    return {
        "prepare (checks, contours, estimate)": best(
            lambda: prepare_laser("sheet", "dxf", region=region, outline=outline, profile="laser-3mm-plywood"), repeat
        ),
        "job estimate alone": best(lambda: job_time.estimate(job.profile, inner=job.inner, outer=job.outer), repeat),
        "DXF text": best(lambda: dxf.dxf_text(job), repeat),
        ".lbrn2 text": best(lambda: lbrn2.lbrn2_text(job), repeat),
    }


def whole(fmt: str, repeat: int) -> float:
    exe = Path(sys.executable).with_name("fabtiles")
    with tempfile.TemporaryDirectory() as out:
        cmd = [str(exe), "build", str(SHEET), "-o", out, "--format", fmt]
        return best(lambda: subprocess.run(cmd, check=True, capture_output=True), repeat)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    for name, seconds in in_process(args.repeat).items():
        print(f"{name:40s} {seconds:7.3f} s")
    for fmt in ("dxf", "lbrn2"):
        print(f"{'whole command, --format ' + fmt:40s} {whole(fmt, args.repeat):7.3f} s")


if __name__ == "__main__":
    main()
