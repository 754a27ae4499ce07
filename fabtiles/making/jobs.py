"""Run many builds: in local processes, or as tasks on a Dask cluster.

``fabtiles batch`` and ``fabtiles sweep`` hand their designs here as :class:`Job`\\ s;
each is built by :func:`fabtiles.making.run_job` (through a staging folder: each
format written or refused on its own, never a partial file), locally in a process pool or on
the workers of a ``dask.distributed`` scheduler. A job never raises: a failure comes back as a failed
:class:`~fabtiles.making.Outcome` and the others go on. A cluster worker lost in the
middle of a task leaves no partial file (the staging folder never becomes an
output) and the scheduler runs the task again elsewhere.

>>> jobs = [Job("a", lambda: None, "out")]
>>> jobs[0].key
'a'
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

from ..core.errors import FabtilesError
from . import Outcome, remove_stale_staging, run_job

CONNECT_TIMEOUT_S = 6.0
"""How long to wait for a Dask scheduler before giving up: with Python's start-up the CLI answers
within 10 s."""


@dataclass(frozen=True)
class Job:
    """One design to build: a key (for reports), a callable giving the validated design, the output."""

    key: str
    make_design: Callable
    outdir: str
    formats: tuple[str, ...] = ()
    preview: bool = False


def _run(job: Job) -> Outcome:
    return run_job(job.key, job.make_design, job.outdir, job.formats, preview=job.preview)


def run_jobs(jobs: Sequence[Job], *, workers: int = 1, scheduler: str | None = None) -> Iterator[Outcome]:
    """Build ``jobs``, yielding each :class:`~fabtiles.making.Outcome` as it completes.

    Parameters
    ----------
    jobs : sequence of Job
    workers : int
        Local processes (without ``scheduler``); 1 builds in this process.
    scheduler : str, optional
        Address of a ``dask.distributed`` scheduler (``tcp://host:8786``): every job
        runs as a task on its workers.

    Raises
    ------
    FabtilesError
        The scheduler cannot be reached (within :data:`CONNECT_TIMEOUT_S`), or
        ``distributed`` is not installed.
    """
    if scheduler is not None:
        yield from _run_dask(jobs, scheduler)
    elif workers <= 1 or len(jobs) <= 1:
        for job in jobs:
            yield _run(job)
    else:
        with ProcessPoolExecutor(max_workers=min(workers, len(jobs))) as pool:
            for fut in as_completed([pool.submit(_run, job) for job in jobs]):
                yield fut.result()
    for outdir in dict.fromkeys(job.outdir for job in jobs):
        remove_stale_staging(outdir)


def connect(scheduler: str):
    """A ``distributed.Client`` of ``scheduler``, or a FabtilesError within the connect timeout.

    The address is first tried with one bare connection and handshake: a refused,
    silent or wrong address fails there within :data:`CONNECT_TIMEOUT_S`, and leaves
    no half-made client behind (whose clean-up alone takes longer than the timeout).
    A TCP address is tried with a plain socket before that: Dask retries a refused
    connection until its timeout, where the socket is refused at once.
    """
    import asyncio

    try:
        from distributed import Client
        from distributed.comm import connect as open_comm
    except ImportError:
        raise FabtilesError("--scheduler needs the dask extra: pip install 'fabtiles[dask]'") from None

    async def probe():
        comm = await open_comm(scheduler, timeout=CONNECT_TIMEOUT_S)
        await comm.close()

    try:
        _refused_at_once(scheduler)
        asyncio.run(asyncio.wait_for(probe(), CONNECT_TIMEOUT_S + 1))
        return Client(scheduler, timeout=CONNECT_TIMEOUT_S)
    except Exception as exc:  # refused, timed out, a bad address, or not a Dask scheduler at all
        reason = str(exc) or type(exc).__name__
        if isinstance(exc, MemoryError):  # a server that answered with something else
            reason = "it does not answer as a Dask scheduler"
        raise FabtilesError(
            f"cannot reach the Dask scheduler at {scheduler!r} within "
            f"{CONNECT_TIMEOUT_S:g} s ({reason}); check the address (tcp://host:8786) "
            f"and that `dask scheduler` is running there"
        ) from None


def _refused_at_once(scheduler: str) -> None:
    """Raise ConnectionError when ``scheduler`` is a TCP address where nothing listens, or whose host
    has no address.

    Anything else (another protocol, an address Dask will name as bad, a host that does not answer)
    is left to Dask's own connection and its timeout.
    """
    import socket

    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        protocol, location = parse_address(scheduler)
        host, port = parse_host_port(location)
    except ValueError:
        return
    if protocol != "tcp":
        return
    try:
        socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S).close()
    except ConnectionRefusedError:
        raise ConnectionError("connection refused: nothing listens there") from None
    except socket.gaierror:
        raise ConnectionError(f"no address for the host {host!r}") from None
    except OSError:
        return


def _run_dask(jobs: Sequence[Job], scheduler: str) -> Iterator[Outcome]:
    from distributed import as_completed as dask_completed

    client = connect(scheduler)
    try:
        # pure=False: two jobs with equal arguments are still two tasks; the scheduler
        # reruns the task of a lost worker elsewhere (its allowed-failures setting).
        futures = [client.submit(_run, job, pure=False) for job in jobs]
        by_future = {f.key: job for f, job in zip(futures, jobs, strict=True)}
        for fut in dask_completed(futures):
            try:
                yield fut.result()
            except Exception as exc:  # the task itself died (e.g. its workers kept being killed)
                job = by_future[fut.key]
                yield Outcome(job.key, False, f"the cluster could not run this job: {type(exc).__name__}: {exc}")
    finally:
        client.close()
