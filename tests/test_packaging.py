"""The installed package holds every module: pyproject.toml lists every folder of the package."""

from __future__ import annotations

import sys
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]


def test_every_package_folder_is_listed_for_installation():
    """A folder missing from the list installs nowhere but in an editable checkout (the web routes were)."""
    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    on_disk = {
        ".".join(p.parent.relative_to(ROOT).parts)
        for p in (ROOT / "fabtiles").rglob("__init__.py")
        if not p.parent.is_symlink()
    }
    assert on_disk - listed == set()
    assert listed - on_disk == {"fabtiles.profiles"}  # installed from the repository's profiles/ folder
