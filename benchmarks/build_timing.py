"""The time of one ``fabtiles build`` in a process of its own, for the benchmarks that compare whole builds."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def timed_build(design: Path, out: Path, *args: str) -> tuple[float, float]:
    """``(cpu_s, wall_s)`` of one ``fabtiles build`` of ``design`` into ``out`` with ``args`` (the child's
    user + system CPU, imports included)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "fabtiles", "build", str(design), "-o", str(out), *args],
        check=True,
        capture_output=True,
        cwd=ROOT,
        env=dict(os.environ, PYTHONPATH=str(ROOT)),
    )
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall
