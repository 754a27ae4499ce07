"""Layers you can trust: the import contracts of `.importlinter`, and no borrowed private names."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "fabtiles"


def test_import_contracts_are_kept():
    """core -> machines | pattern -> geometry -> solid -> export -> designs -> making -> front ends: none goes up."""
    lint = Path(sys.executable).with_name("lint-imports")
    proc = subprocess.run(
        [str(lint), str(ROOT / ".importlinter")], cwd=ROOT, capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Contracts: 4 kept, 0 broken." in proc.stdout


def lint_with(tmp_path, module: str, text: str) -> subprocess.CompletedProcess:
    """``lint-imports`` on a copy of the package with one module added (``geometry/upward.py``)."""
    import shutil

    copy = tmp_path / "fabtiles"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__", "static", "*.toml"))
    (copy / module).write_text(text)
    lint = Path(sys.executable).with_name("lint-imports")
    proc = subprocess.run(
        [str(lint), str(ROOT / ".importlinter")],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
        env={"PYTHONPATH": str(tmp_path), "PATH": ""},
    )
    assert proc.returncode == 1, proc.stdout + proc.stderr
    return proc


def test_the_layer_contract_catches_an_import_going_up(tmp_path):
    """The contract is live: a geometry module importing export breaks it."""
    proc = lint_with(tmp_path, "geometry/upward.py", "from ..export import formats\n")
    assert "fabtiles.geometry is not allowed to import fabtiles.export" in proc.stdout
    assert "fabtiles.geometry.upward -> fabtiles.export.formats" in proc.stdout


def test_the_solid_layer_writes_no_file(tmp_path):
    """solid builds bodies; a module of it reaching for a writer or the atomic file writer breaks a contract."""
    proc = lint_with(tmp_path, "solid/writes.py", "from ..core.files import atomic_write\nfrom ..export import stl\n")
    assert "fabtiles.solid is not allowed to import fabtiles.export" in proc.stdout
    assert "fabtiles.solid.writes -> fabtiles.core.files" in proc.stdout


def _module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _resolve(path: Path, root: Path, node: ast.ImportFrom) -> str:
    if not node.level:
        return node.module or ""
    base = _module_name(path, root).split(".")
    base = base if path.name == "__init__.py" else base[:-1]
    base = base[: len(base) - node.level + 1]
    return ".".join(base + ([node.module] if node.module else []))


def borrowed_private_names(package: Path = PACKAGE) -> list[str]:
    """``from module import _name`` where ``_name`` is not a module: a private name of another module."""
    found = []
    root = package.parent
    for path in sorted(package.rglob("*.py")):
        rel = str(path.relative_to(root))
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.ImportFrom):
                continue
            source = _resolve(path, root, node)
            for alias in node.names:
                name = alias.name
                if not name.startswith("_") or name.startswith("__"):
                    continue
                if (root / Path(*source.split("."), f"{name}.py")).exists():
                    continue  # a private module of the package (fabtiles.solid._triangulate): that is its purpose
                found.append(f"{rel}:{node.lineno} imports {name} from {source}")
    return found


def test_no_module_imports_another_modules_private_names():
    assert borrowed_private_names() == []


def test_the_private_name_check_finds_one(tmp_path):
    pkg = tmp_path / "fabtiles"
    (pkg / "geometry").mkdir(parents=True)
    (pkg / "geometry" / "borrow.py").write_text("from .tile import _secret\n")
    assert borrowed_private_names(pkg) == ["fabtiles/geometry/borrow.py:1 imports _secret from fabtiles.geometry.tile"]
