"""Every test file and every doctest is collected by the README's command (``python -m pytest``).

pytest skips some folders by name (its default ``norecursedirs`` holds ``build``, ``dist``,
``venv``, ...) and a file or a folder it skips fails no test: it is simply never run. So what
pytest collects is compared with the files on disk: each ``tests/**/test_*.py``, and each
module of the package whose source holds a doctest (``>>>``), must give at least one test.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def collected_by_pytest(root: Path, env: dict | None = None) -> set[str]:
    """The files of which ``python -m pytest --collect-only`` run in ``root`` collects a test."""
    proc = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider"],
        cwd=root,
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
    )
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return {line.split("::", 1)[0] for line in proc.stdout.splitlines() if "::" in line}


def uncollected(root: Path, env: dict | None = None, collected: set[str] | None = None) -> list[str]:
    """The test files and doctest modules under ``root`` of which pytest collects nothing (``collected``:
    what a run already collected there, else what ``pytest --collect-only`` does)."""
    if collected is None:
        collected = collected_by_pytest(root, env)
    expected = {p.relative_to(root).as_posix() for p in (root / "tests").rglob("test_*.py")}
    package = root / "fabtiles"
    if package.is_dir():
        expected |= {
            p.relative_to(root).as_posix() for p in package.rglob("*.py") if ">>>" in p.read_text(encoding="utf-8")
        }
    return sorted(expected - collected)


def test_every_test_file_and_doctest_is_collected(pytestconfig, collected_files):
    """Run by the README's command (no paths), this run's own collection is the one checked;
    run with paths, ``pytest --collect-only`` in a process of its own."""
    if collected_files is not None:
        assert pytestconfig.rootpath == ROOT
    assert uncollected(ROOT, collected=collected_files) == []


def test_a_folder_pytest_skips_is_found(tmp_path):
    """The comparison is live: a test file in a folder named ``build`` (skipped by default) is reported."""
    (tmp_path / "pyproject.toml").write_text((ROOT / "pyproject.toml").read_text(encoding="utf-8"), encoding="utf-8")
    for folder in ("tests/build", "tests/geometry", "fabtiles/build"):
        (tmp_path / folder).mkdir(parents=True)
    (tmp_path / "fabtiles" / "__init__.py").write_text("")
    (tmp_path / "fabtiles" / "build" / "__init__.py").write_text("")
    (tmp_path / "fabtiles" / "build" / "steps.py").write_text(
        'def two():\n    """\n    >>> two()\n    2\n    """\n    return 2\n'
    )
    (tmp_path / "fabtiles" / "seen.py").write_text('"""\n>>> 1 + 1\n2\n"""\n')
    for test in ("tests/build/test_hidden.py", "tests/geometry/test_seen.py"):
        (tmp_path / test).write_text("def test_one():\n    assert True\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # the copy's package, not this one
    assert uncollected(tmp_path, env) == ["fabtiles/build/steps.py", "tests/build/test_hidden.py"]
