"""The programs users open fabtiles' files with, found for the tests that run them.

`.ci/run` installs every one of them and sets ``FABTILES_REQUIRE_PROGRAMS=1`` (CI
also sets ``CI``): there a missing program fails its tests instead of skipping
them. Elsewhere they skip, with the command that installs the program.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REQUIRED = bool(os.environ.get("CI")) or os.environ.get("FABTILES_REQUIRE_PROGRAMS") == "1"

SYSTEM_PYTHON = "/usr/bin/python3"
"""Debian's own Python: python3-savitar (Cura's 3MF parser) is installed for it alone."""

INKSCAPE_EXTENSIONS = Path("/usr/share/inkscape/extensions")


def require(found, what: str, install: str):
    """``found`` when it is truthy; else fail (CI) or skip, saying how to install ``what``."""
    if found:
        return found
    message = f"{what} is not installed: {install}"
    if REQUIRED:
        pytest.fail(f"{message} (required here: CI or FABTILES_REQUIRE_PROGRAMS=1)")
    pytest.skip(message)


def program(name: str, install: str) -> str:
    """The path of the command ``name`` on PATH (or in /usr/bin)."""
    path = shutil.which(name) or (f"/usr/bin/{name}" if os.path.exists(f"/usr/bin/{name}") else None)
    return require(path, name, install)


def system_python_module(module: str, install: str) -> str:
    """Debian's python3, once it imports ``module``."""
    ok = (
        os.path.exists(SYSTEM_PYTHON)
        and subprocess.run([SYSTEM_PYTHON, "-c", f"import {module}"], capture_output=True).returncode == 0
    )
    return require(SYSTEM_PYTHON if ok else None, f"{module} for {SYSTEM_PYTHON}", install)


def cura_definitions() -> Path:
    """The folder holding Cura's ``fdmprinter.def.json`` and ``fdmextruder.def.json``.

    ``FABTILES_CURA_DEFINITIONS`` names it (`.ci/run` unpacks Debian's ``cura``
    package there, without installing Cura); else an installed Cura's.
    """
    candidates = [os.environ.get("FABTILES_CURA_DEFINITIONS"), "/usr/share/cura/resources/definitions"]
    found = next((Path(c) for c in candidates if c and (Path(c) / "fdmprinter.def.json").exists()), None)
    return require(
        found,
        "Cura's fdmprinter.def.json",
        "apt-get download cura && dpkg-deb -x cura_*.deb DIR, then "
        "FABTILES_CURA_DEFINITIONS=DIR/usr/share/cura/resources/definitions",
    )


def run(cmd, *, timeout: float = 300, **kwargs) -> subprocess.CompletedProcess:
    """Run ``cmd``; its failure fails the test with everything it printed."""
    done = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=timeout, **kwargs)
    assert done.returncode == 0, f"{cmd} exited {done.returncode}:\n{done.stdout[-4000:]}\n{done.stderr[-4000:]}"
    return done
