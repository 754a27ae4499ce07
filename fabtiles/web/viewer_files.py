"""The 3D view's library, three.js, installed into the package from npm's registry.

three.js is not our code, so the repository does not hold it: ``fabtiles
install-viewer`` downloads the pinned npm tarball of ``three``, checks it
against the registry's sha512 integrity (a changed or truncated download is
refused), and extracts the few modules the view imports, with three.js's
licence and a note of its version, into ``fabtiles/web/static/vendor/three/``.
From then on the web app serves them itself and works offline (no CDN). An
offline machine installs from a tarball fetched elsewhere (``npm pack
three@0.187.0``) with ``--tarball``.

>>> MODULES[:2]
('build/three.module.js', 'build/three.core.js')
>>> VERSION
'0.187.0'
"""

from __future__ import annotations

import base64
import hashlib
import io
import tarfile
import urllib.request
from pathlib import Path

from ..core.errors import FabtilesError
from ..core.files import atomic_write

VERSION = "0.187.0"
"""The three.js release the view is written and tested against."""

TARBALL_URL = f"https://registry.npmjs.org/three/-/three-{VERSION}.tgz"
INTEGRITY = "sha512-Qiu7R+Cmh8CstZsY1uJOSWnVlfo7ZtNLV7mF8Jltk3LB3AtDu9cRZlcnRKkAk8Y4z6KKw35z7Y7Urd7jWY8etA=="
"""npm's ``dist.integrity`` of that tarball (``npm view three@0.187.0 dist.integrity``)."""

MODULES = (
    "build/three.module.js",  # the module the import map calls "three"; it imports three.core.js
    "build/three.core.js",
    "examples/jsm/controls/OrbitControls.js",
    "examples/jsm/loaders/GLTFLoader.js",
    "examples/jsm/utils/BufferGeometryUtils.js",  # imported by GLTFLoader
    "examples/jsm/utils/SkeletonUtils.js",  # imported by GLTFLoader
    "LICENSE",
)
"""The files the view needs, by their path in the npm package (a small part of it)."""

VENDOR = Path(__file__).with_name("static") / "vendor" / "three"
"""Where they go: served by the app under ``/static/vendor/three/``."""


class ViewerFilesError(FabtilesError, ValueError):
    """The three.js tarball could not be fetched, or is not the pinned one."""


def installed(folder: Path | None = None) -> bool:
    """Whether every module of the view is in ``folder`` (default :data:`VENDOR`) at the pinned version."""
    folder = VENDOR if folder is None else folder
    stamp = folder / "VERSION"
    return stamp.is_file() and stamp.read_text().split()[0] == VERSION and all((folder / m).is_file() for m in MODULES)


def check_integrity(data: bytes, integrity: str | None = None) -> None:
    """Refuse bytes whose sha512 is not npm's ``integrity`` string (default :data:`INTEGRITY`).

    >>> check_integrity(b"x", "sha512-" + base64.b64encode(hashlib.sha512(b"x").digest()).decode())
    >>> check_integrity(b"y", "sha512-" + base64.b64encode(hashlib.sha512(b"x").digest()).decode())
    Traceback (most recent call last):
    ...
    fabtiles.web.viewer_files.ViewerFilesError: the three.js tarball's sha512 is not npm's integrity for three 0.187.0 (a changed or truncated download); nothing was installed: fetch it again, or give the tarball of `npm pack three@0.187.0` with --tarball
    """  # noqa: E501 - a doctest's lines are as Python prints them
    algorithm, _, digest = (INTEGRITY if integrity is None else integrity).partition("-")
    found = base64.b64encode(hashlib.new(algorithm, data).digest()).decode()
    if found != digest:
        raise ViewerFilesError(
            f"the three.js tarball's {algorithm} is not npm's integrity for three {VERSION} (a changed or "
            f"truncated download); nothing was installed: fetch it again, or give the tarball of "
            f"`npm pack three@{VERSION}` with --tarball"
        )


def download(url: str = TARBALL_URL, *, timeout_s: float = 60.0) -> bytes:
    """The tarball's bytes from npm's registry."""
    try:
        with urllib.request.urlopen(url, timeout=timeout_s) as response:  # a fixed https URL, never from a request
            return response.read()
    except OSError as exc:
        raise ViewerFilesError(
            f"could not download {url} ({exc}); on a machine without the internet, "
            f"run `npm pack three@{VERSION}` elsewhere and pass the file with --tarball"
        ) from None


def install(tarball: bytes | None = None, folder: Path | None = None) -> list[Path]:
    """Check the tarball (downloaded when not given) and extract :data:`MODULES` into ``folder``
    (default :data:`VENDOR`).

    Only the listed members are read from the archive, by name, so nothing in it can
    write elsewhere. Returns the files written.
    """
    folder = VENDOR if folder is None else folder
    data = download() if tarball is None else tarball
    check_integrity(data)
    written = []
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as archive:
        for name in MODULES:
            try:
                member = archive.extractfile(f"package/{name}")
            except KeyError:
                member = None
            if member is None:
                raise ViewerFilesError(f"the three.js tarball has no {name}; nothing more was installed")
            path = folder / name
            path.parent.mkdir(parents=True, exist_ok=True)
            atomic_write(path, member.read())
            written.append(path)
    note = (
        f"{VERSION} three.js (npm package three, {TARBALL_URL}), MIT licence: see LICENSE.\n"
        f"Installed by `fabtiles install-viewer`; integrity {INTEGRITY}.\n"
    )
    atomic_write(folder / "VERSION", note.encode())
    return [*written, folder / "VERSION"]
