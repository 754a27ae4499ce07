"""Atomic file output: a failure never leaves a truncated file or clobbers a good one."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path


def atomic_write(path, data: bytes | str | Callable[[Path], None]) -> Path:
    """Write ``data`` to ``path`` through a temporary file in the same folder, then rename.

    ``data`` is bytes, text (written as UTF-8), or a callable that writes the file
    at the temporary path it is given (for libraries that only write to paths).
    If anything fails, or the process is interrupted, the temporary file is removed
    and an existing file at ``path`` is left as it was.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    tmp_path = Path(tmp)
    try:
        if callable(data):
            os.close(fd)
            fd = -1
            data(tmp_path)
        else:
            with os.fdopen(fd, "wb") as fh:
                fd = -1
                fh.write(data.encode("utf-8") if isinstance(data, str) else data)
                fh.flush()
                os.fsync(fh.fileno())
        os.chmod(tmp_path, 0o644)
        os.replace(tmp_path, path)
    except BaseException:
        if fd >= 0:
            os.close(fd)
        tmp_path.unlink(missing_ok=True)
        raise
    return path


ZIP_TIME = (1980, 1, 1, 0, 0, 0)
"""The date of every zip entry fabtiles writes (the earliest a zip can hold): the same bytes every run."""


def zip_entry(name: str):
    """A :class:`zipfile.ZipInfo` for ``name`` dated :data:`ZIP_TIME`, deflated."""
    import zipfile

    info = zipfile.ZipInfo(name, date_time=ZIP_TIME)
    info.compress_type = zipfile.ZIP_DEFLATED
    return info
