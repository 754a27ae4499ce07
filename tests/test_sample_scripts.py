"""The scripts in samples/ (the pictures' renderers, custom sizes) import only what fabtiles has.

They are not run by the suite (each draws for seconds to minutes), so a module they import that
was renamed or removed would only show when someone next draws a picture; this reads their
imports instead.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
SCRIPTS = sorted(SAMPLES.glob("*.py"))


def _fabtiles_imports(path: Path) -> list[tuple[str, str | None]]:
    """``(module, name)`` of every ``import fabtiles...`` / ``from fabtiles... import name`` in a script."""
    found: list[tuple[str, str | None]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] == "fabtiles":
            found += [(node.module, alias.name) for alias in node.names]
        elif isinstance(node, ast.Import):
            found += [(alias.name, None) for alias in node.names if alias.name.split(".")[0] == "fabtiles"]
    return found


def _missing(module: str, name: str | None) -> str | None:
    try:
        mod = importlib.import_module(module)
    except ImportError:
        return f"no module {module}"
    if name is None or hasattr(mod, name):
        return None
    try:
        importlib.import_module(f"{module}.{name}")
    except ImportError:
        return f"{module} has no {name}"
    return None


def test_there_are_scripts_to_read():
    assert len(SCRIPTS) >= 5


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_a_sample_script_imports_only_what_exists(script):
    problems = [p for p in (_missing(m, n) for m, n in _fabtiles_imports(script)) if p]
    assert not problems, f"{script.name}: {problems}"


def test_the_reader_finds_a_missing_module(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    from fabtiles.export.no_such_module import X\n    import fabtiles.nowhere\n")
    found = _fabtiles_imports(bad)
    assert found == [("fabtiles.export.no_such_module", "X"), ("fabtiles.nowhere", None)]
    assert all(_missing(m, n) for m, n in found)
    assert _missing("fabtiles.machines.profiles", "DEFAULT_PRINTER_PROFILE") is None
