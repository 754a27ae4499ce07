"""Staging: the files a build made written into a hidden folder, then moved into place together.

A format the build refused has no file here (:func:`~fabtiles.making.pipeline.write_files`);
a failure while writing leaves no new or partial file and never clobbers an existing
one; a process killed outright leaves only its hidden staging folder, which
:func:`remove_stale_staging` removes later.
"""

from __future__ import annotations

import os
import shutil
import socket
import tempfile
from pathlib import Path

from ..core.errors import FabtilesError

STAGING_PREFIX = ".fabtiles-build-"
"""Staging folders inside an output folder: ``.fabtiles-build-<host>-<pid>-<random>``."""


class StagingFolder:
    """A staging folder inside ``outdir``: ``with StagingFolder(out) as (staging, move): ...``.

    ``move(path)`` puts a staged file into ``outdir`` (an atomic rename) and returns
    its final path. On leaving, the staging folder is removed, and so is ``outdir``
    when it was created here and stayed empty (a failed build leaves no folder).
    The staging folder's name carries the host and process id, so that
    :func:`remove_stale_staging` can tell a dead process's leftovers from a live one's.
    """

    def __init__(self, outdir):
        self.outdir = Path(outdir)

    def __enter__(self):
        outdir = self.outdir
        if outdir.exists() and not outdir.is_dir():
            raise FabtilesError(f"output folder {str(outdir)!r} exists and is not a folder")
        self.existed = outdir.exists()
        try:
            outdir.mkdir(parents=True, exist_ok=True)
            prefix = f"{STAGING_PREFIX}{socket.gethostname()}-{os.getpid()}-"
            self.staging = Path(tempfile.mkdtemp(prefix=prefix, dir=outdir))
        except OSError as exc:
            raise FabtilesError(f"cannot create output folder {str(outdir)!r}: {exc.strerror or exc}") from None
        return self.staging, self._move

    def _move(self, path: Path) -> Path:
        target = self.outdir / path.name
        os.replace(path, target)
        return target

    def __exit__(self, kind, exc, tb):
        shutil.rmtree(self.staging, ignore_errors=True)
        if not self.existed and self.outdir.is_dir() and not any(self.outdir.iterdir()):
            self.outdir.rmdir()  # a failed build leaves no folder it created either
        if isinstance(exc, OSError):
            raise FabtilesError(f"cannot write into {str(self.outdir)!r}: {exc.strerror or exc}") from None
        return False


def remove_stale_staging(outdir) -> int:
    """Remove staging folders in ``outdir`` left by dead processes of this host; return how many.

    A process killed outright (SIGKILL, a lost cluster worker) cannot clean up: its
    staging folder stays, hidden, while the final files are never partial.
    """
    outdir = Path(outdir)
    host = socket.gethostname()
    removed = 0
    if not outdir.is_dir():
        return 0
    for path in outdir.glob(f"{STAGING_PREFIX}*"):
        parts = path.name[len(STAGING_PREFIX) :].rsplit("-", 2)  # host (may hold "-"), pid, random
        if len(parts) != 3 or parts[0] != host or not parts[1].isdigit() or _alive(int(parts[1])):
            continue
        shutil.rmtree(path, ignore_errors=True)
        removed += 1
    return removed


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
