"""The vpype plugin against ``fabtiles build --format svg`` for the same design (issue 37).

Run by hand (never in CI): ``python benchmarks/bench_plot.py [--pairs 5] [--sample PATH]``.
Whole commands in fresh processes, run in turn as pairs (the machine is shared):
``vpype fabtiles DESIGN write out.svg`` (vpype's start-up and SVG writer included) and
``fabtiles build DESIGN --format svg``; the medians of each one's CPU time (user + system of
the child) and the ratio. The plugin must be registered (``pip install -e '.[vpype]'``), or
``--site DIR`` names a folder with a dist-info declaring it (as tests/cli/test_vpype_plugin.py makes).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def cpu(cmd, env) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, capture_output=True, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--sample", type=Path, default=ROOT / "samples" / "table3-3.toml")
    ap.add_argument("--site", type=Path, default=None)
    args = ap.parse_args(argv)
    env = dict(os.environ)
    if args.site is not None:
        env["PYTHONPATH"] = os.pathsep.join([str(ROOT), str(args.site)])
    else:
        env["PYTHONPATH"] = str(ROOT)
    bindir = Path(sys.executable).parent
    with tempfile.TemporaryDirectory() as out:
        plug = [str(bindir / "vpype"), "fabtiles", str(args.sample), "write", str(Path(out) / "v.svg")]
        build = [sys.executable, "-m", "fabtiles", "build", str(args.sample), "-o", out, "--format", "svg"]
        a, b = [], []
        for _ in range(args.pairs):
            a.append(cpu(plug, env))
            b.append(cpu(build, env))
    ma, mb = statistics.median(a), statistics.median(b)
    print(
        f"{args.sample.name}: vpype fabtiles ... write {ma:.2f} s CPU, fabtiles build --format svg {mb:.2f} s CPU, "
        f"ratio {ma / mb:.2f}x (medians of {args.pairs} pairs)"
    )


if __name__ == "__main__":
    main()
