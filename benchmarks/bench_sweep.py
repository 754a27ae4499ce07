"""Benchmark: a 40-variant sweep on a local Dask cluster of 2 workers vs 1 (issue 13).

Targets: 2 workers at least 1.6 times as fast as 1; the per-variant overhead of going
through the cluster (1 worker against building the same variants in this process, one
after the other) under 0.2 s. Every configuration is warmed up first (imports in the
workers) and timed over the same 40 variants: table3-3 on a 100 mm tile, the packing
radius from 8 to 16 mm, SVG and DXF each.

Run by hand (not in the tests): ``python benchmarks/bench_sweep.py [--variants 40] [--repeat 2]``.
The figures depend on the machine being otherwise idle.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import tempfile
import time
from pathlib import Path

DESIGN = """
[motif]
preset = "table3-3"
[packing]
radius = 12
[tile]
size = {size}
frame = 4
stroke = 1.0
[output]
formats = ["svg", "dxf"]
"""


def jobs(n: int, outdir: Path, size: float = 100.0):
    from fabtiles.making.sweep import make_jobs, parse_vary, variants

    design = outdir.parent / "bench.toml"
    design.write_text(DESIGN.format(size=size))
    todo = variants([parse_vary(f"packing.radius=8:16:{n}")], "bench")
    return make_jobs(design, todo, outdir, ())


def timed(run, n: int, root: Path, size: float = 100.0) -> float:
    from fabtiles.making.jobs import run_jobs

    out = root / "out"
    shutil.rmtree(out, ignore_errors=True)
    work = jobs(n, out, size)
    t0 = time.perf_counter()
    outcomes = list(run_jobs(work, **run))
    dt = time.perf_counter() - t0
    assert all(o.ok for o in outcomes), [o.message for o in outcomes if not o.ok]
    return dt


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--variants", type=int, default=40)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--size", type=float, default=100.0, help="tile size, mm (default 100)")
    ap.add_argument("--skip-local", action="store_true", help="only the cluster runs")
    args = ap.parse_args(argv)
    from distributed import LocalCluster

    root = Path(tempfile.mkdtemp(prefix="fabtiles-bench-sweep-"))
    results = {}
    size = args.size
    if not args.skip_local:
        timed({"workers": 1}, 2, root, size)  # warm up this process
        results["in process"] = [timed({"workers": 1}, args.variants, root, size) for _ in range(args.repeat)]
        # For comparison: what two local processes (--jobs 2) get from the same machine right now.
        results["local, 2 procs"] = [timed({"workers": 2}, args.variants, root, size) for _ in range(args.repeat)]
    for workers in (1, 2):
        with LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
        ) as cluster:
            address = cluster.scheduler_address
            timed({"scheduler": address}, 2 * workers, root, size)  # warm up the workers
            results[f"dask, {workers} worker{'s' if workers > 1 else ''}"] = [
                timed({"scheduler": address}, args.variants, root, size) for _ in range(args.repeat)
            ]
    best = {k: min(v) for k, v in results.items()}
    for name, times in results.items():
        print(
            f"{name:<16} best {min(times):6.2f} s  median {statistics.median(times):6.2f} s  "
            f"({min(times) / args.variants * 1000:.0f} ms per variant)"
        )
    speedup = best["dask, 1 worker"] / best["dask, 2 workers"]
    print(f"2 workers vs 1: {speedup:.2f}x (target >= 1.6)")
    if not args.skip_local:
        overhead = (best["dask, 1 worker"] - best["in process"]) / args.variants
        print(
            f"per-variant overhead of the cluster: {overhead * 1000:.0f} ms (target < 200 ms); "
            f"2 local processes vs this process: {best['in process'] / best['local, 2 procs']:.2f}x"
        )
    shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main()
