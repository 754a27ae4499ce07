"""Batches and sweeps on a Dask cluster (a scheduler and two workers on 127.0.0.1, started here).

The cluster writes the same files as a local run; a worker killed in the middle of a run
leaves no partial file and every output still arrives; an unreachable scheduler is a
clear error (exit 2).
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from designs import design_toml
from distributed import Client
from dxf_helpers import assert_same_file

from fabtiles.core.errors import FabtilesError
from fabtiles.making import STAGING_PREFIX

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"
DASK = str(Path(sys.executable).with_name("dask"))
SMALL = design_toml(radius=8, outline=None)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Cluster:
    """A scheduler and ``n`` workers (no nanny: killing a worker kills its process), all on 127.0.0.1."""

    def __init__(self, tmp: Path, n: int = 2):
        self.address = f"tcp://127.0.0.1:{_free_port()}"
        port = self.address.rsplit(":", 1)[1]
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", DASK_DISTRIBUTED__WORKER__DAEMON="False")
        log = (tmp / "cluster.log").open("ab")
        self.scheduler = subprocess.Popen(
            [DASK, "scheduler", "--host", "127.0.0.1", "--port", port, "--no-dashboard"],
            stdout=log,
            stderr=log,
            env=env,
            cwd=tmp,
        )
        self.workers = [
            subprocess.Popen(
                [
                    DASK,
                    "worker",
                    self.address,
                    "--host",
                    "127.0.0.1",
                    "--nthreads",
                    "1",
                    "--no-nanny",
                    "--no-dashboard",
                    "--name",
                    f"w{k}",
                    "--local-directory",
                    str(tmp / f"w{k}"),
                ],
                stdout=log,
                stderr=log,
                env=env,
                cwd=tmp,
            )
            for k in range(n)
        ]
        with Client(self.address, timeout=60, set_as_default=False) as client:
            client.wait_for_workers(n, timeout=120)

    def close(self):
        # The workers first, while their scheduler still answers: a worker that has run a task and
        # is told to close by its scheduler and by the signal at once can hang in its own close.
        for group in (self.workers, [self.scheduler]):
            for proc in group:
                if proc.poll() is None:
                    proc.terminate()
            for proc in group:
                try:
                    proc.wait(timeout=30)
                except subprocess.TimeoutExpired:  # pragma: no cover - a stuck process
                    proc.kill()
                    proc.wait()


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    c = Cluster(tmp_path_factory.mktemp("cluster"))
    yield c
    c.close()


def fabtiles(*args, **kw):
    return subprocess.run(
        [sys.executable, "-m", "fabtiles", *map(str, args)], capture_output=True, text=True, timeout=900, **kw
    )


def files(folder: Path) -> dict:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def test_batch_on_the_cluster_writes_what_a_local_run_writes(cluster, tmp_path):
    designs = [SAMPLES / n for n in ("rosette.toml", "table3-1.toml", "seamless-hexagon.toml")]
    local = fabtiles("batch", *designs, "-o", tmp_path / "local", "--format", "svg", "--jobs", "1")
    remote = fabtiles("batch", *designs, "-o", tmp_path / "dask", "--format", "svg", "--scheduler", cluster.address)
    assert local.returncode == 0 and remote.returncode == 0, remote.stderr
    assert remote.stdout == local.stdout  # the same report, findings and all
    want = files(tmp_path / "local")
    assert len(want) == len(designs) and files(tmp_path / "dask") == want  # byte-identical SVGs


def test_sweep_on_the_cluster_writes_what_a_local_run_writes(cluster, tmp_path):
    design = tmp_path / "small.toml"
    design.write_text(SMALL)
    args = ("sweep", design, "--vary", "packing.radius=6:10:3", "--vary", "tile.stroke=1,30", "--format", "svg")
    local = fabtiles(*args, "-o", tmp_path / "local", "--jobs", "1")
    remote = fabtiles(*args, "-o", tmp_path / "dask", "--scheduler", cluster.address)
    assert local.returncode == remote.returncode == 2  # three variants fail validation, on both
    want = files(tmp_path / "local")
    assert sum(n.endswith(".preview.svg") for n in want) == 3
    got = files(tmp_path / "dask")
    assert got.keys() == want.keys()
    for name in want:  # the contact sheet names its output folder nowhere: identical too
        assert got[name] == want[name], name


def test_a_worker_killed_mid_run_still_gives_every_output(cluster, tmp_path):
    """The last test of the module's cluster: it kills one of its two workers (no later test uses it)."""
    design = tmp_path / "big.toml"
    design.write_text(SMALL.replace("size = 60", "size = 160"))
    args = ("sweep", design, "--vary", "packing.radius=7:12:6", "--format", "svg", "--format", "dxf")
    local = fabtiles(*args, "-o", tmp_path / "local", "--jobs", "1")
    assert local.returncode == 0, local.stderr
    c = cluster
    assert all(w.poll() is None for w in c.workers)
    out = tmp_path / "dask"
    run = subprocess.Popen(
        [sys.executable, "-m", "fabtiles", *map(str, args), "-o", str(out), "--scheduler", c.address],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    # Kill a worker in the middle of a task: while it is writing into its staging folder
    # (named with its process id), so that task must be run again on the other worker.
    victim = c.workers[0]
    staging = f"{STAGING_PREFIX}{socket.gethostname()}-{victim.pid}-"
    deadline = time.monotonic() + 600
    while not (out.exists() and any(p.name.startswith(staging) for p in out.iterdir())):
        assert run.poll() is None and time.monotonic() < deadline, "the worker never started a build"
        time.sleep(0.005)
    victim.send_signal(signal.SIGKILL)
    victim.wait()
    stdout, stderr = run.communicate(timeout=900)
    assert run.returncode == 0, stdout + stderr
    want, got = files(tmp_path / "local"), files(out)
    assert got.keys() == want.keys()  # every output; the killed worker's staging folder is gone
    for name in want:  # the same files, a DXF up to its time and GUIDs of writing
        assert_same_file(name, got[name], want[name])


def test_unreachable_scheduler_is_a_clear_error(tmp_path):
    from fabtiles.making.jobs import CONNECT_TIMEOUT_S

    assert CONNECT_TIMEOUT_S < 10
    proc = fabtiles(
        "batch", SAMPLES / "rosette.toml", "-o", tmp_path / "out", "--scheduler", f"tcp://127.0.0.1:{_free_port()}"
    )
    assert proc.returncode == 2
    assert proc.stderr.startswith("fabtiles: error: cannot reach the Dask scheduler at 'tcp://127.0.0.1:")
    assert proc.stderr.count("\n") == 1 and not (tmp_path / "out").exists()
    bad = fabtiles(
        "sweep",
        SAMPLES / "rosette.toml",
        "--vary",
        "tile.stroke=1,2",
        "-o",
        tmp_path / "s",
        "--scheduler",
        "not-an-address",
    )
    assert bad.returncode == 2 and "missing port number in address 'not-an-address'" in bad.stderr


def test_a_refused_port_or_an_unknown_host_fails_at_once_not_after_the_timeout(monkeypatch):
    """Dask retries a refused connection until its timeout; the plain socket tried first does not."""
    from fabtiles.making import jobs

    def refuse(address, timeout):
        raise ConnectionRefusedError(111, "Connection refused")

    monkeypatch.setattr(socket, "create_connection", refuse)
    with pytest.raises(FabtilesError, match=r"'tcp://127.0.0.1:1' .*\(connection refused: nothing listens there\)"):
        jobs.connect("tcp://127.0.0.1:1")

    def unknown(address, timeout):
        raise socket.gaierror(-2, "Name or service not known")

    monkeypatch.setattr(socket, "create_connection", unknown)
    with pytest.raises(FabtilesError, match=r"\(no address for the host 'scheduler.invalid'\)"):
        jobs.connect("tcp://scheduler.invalid:8786")


def test_jobs_and_scheduler_together_is_a_usage_error(tmp_path):
    proc = fabtiles("batch", SAMPLES / "rosette.toml", "-o", tmp_path, "--jobs", "2", "--scheduler", "tcp://x:1")
    assert proc.returncode == 2 and "--jobs sets local processes" in proc.stderr
