"""Kill a real `fabtiles build` mid-work: never a partial file, never a damaged earlier one."""

import os
import signal
import subprocess
import sys
import time

import pytest
from designs import default_sigint, design_toml
from dxf_helpers import assert_same_file

DESIGN = design_toml(outline="rectangle", size=[250, 200], frame=5, output={"formats": ["dxf", "svg", "stl"]})
"""Fits the printer's bed and the laser's: one file per format (a larger tile is made as pieces)."""


def _start(design, out):
    return subprocess.Popen(
        [sys.executable, "-X", "faulthandler", "-m", "fabtiles", "build", str(design), "-o", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        preexec_fn=default_sigint,
    )


@pytest.fixture(scope="module")
def full_build(tmp_path_factory):
    """The design, the files of a complete build and how long that build took here (one for both signals)."""
    tmp = tmp_path_factory.mktemp("interrupt")
    design = tmp / "sheet.toml"
    design.write_text(DESIGN)
    durations = []
    for k in range(2):  # the first may also compile the package's bytecode: the shorter is what a build takes
        t = time.perf_counter()
        full = _start(design, tmp / f"full-{k}")
        assert full.wait(timeout=300) == 0, full.stderr.read().decode()
        durations.append(time.perf_counter() - t)
    return design, {p.name: p.read_bytes() for p in (tmp / "full-1").iterdir()}, min(durations)


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_interrupted_build_leaves_old_files_and_no_partial_ones(tmp_path, sig, full_build):
    out = tmp_path / "out"
    out.mkdir()
    old = {f"sheet.{fmt}": f"good {fmt} file from an earlier build".encode() for fmt in ("dxf", "svg", "stl")}
    for name, data in old.items():
        (out / name).write_bytes(data)

    # A full run, to know how long it takes here; then interrupt at fractions of it.
    design, complete, duration = full_build
    assert set(complete) == set(old)

    interrupted = 0
    for fraction in (0.3, 0.55, 0.8, 0.95):
        t = time.perf_counter()
        proc = _start(design, out)
        time.sleep(duration * fraction)
        if proc.poll() is None:
            proc.send_signal(sig)
            interrupted += 1
        else:  # done sooner than the full build was (a machine less loaded now): time the next ones by this
            duration = min(duration, time.perf_counter() - t)
        _, err = proc.communicate(timeout=120)
        rc = proc.returncode
        names = sorted(os.listdir(out))
        # Nothing else in the folder: no temporary, staging or partial file.
        assert names == sorted(old), names
        for name in names:
            data = (out / name).read_bytes()
            if rc == 0:  # a complete new build replaced the old files
                assert_same_file(name, data, complete[name])
            elif data != old[name]:  # interrupted: every file is either the earlier one or a complete new one
                assert_same_file(name, data, complete[name])
        if rc == 0:  # restore the earlier files for the next round
            for name, data in old.items():
                (out / name).write_bytes(data)
        else:
            # click reports Ctrl+C as "Aborted!", status 1; a crash shows its traceback (faulthandler)
            assert rc in (1, 2, 128 + sig, -sig), (rc, err.decode()[-3000:])
    assert interrupted >= 2
