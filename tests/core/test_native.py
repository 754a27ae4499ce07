"""A compiled module's import is never cut half-way by Ctrl+C or SIGTERM."""

import ast
import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest
from designs import default_sigint

import fabtiles
from fabtiles.core.native import import_uninterrupted

# A module whose initialisation receives the signal while it is still running Python code.
SLOW_INIT = """
import os, signal
os.kill(os.getpid(), signal.{sig})
total = sum(i for i in range(200_000))
DONE = True
"""

SCRIPT = """
import importlib, signal, sys
sys.path.insert(0, {folder!r})
from fabtiles.core.native import import_uninterrupted
if {sig!r} == "SIGTERM":
    def stop(signum, frame):
        print("stopped; module complete:", getattr(sys.modules.get("slow_init"), "DONE", False), flush=True)
        raise SystemExit(143)
    signal.signal(signal.SIGTERM, stop)
try:
    {how}("slow_init")
except KeyboardInterrupt:
    print("interrupted; module complete:", getattr(sys.modules.get("slow_init"), "DONE", False))
"""


def _run(tmp_path, sig, how):
    (tmp_path / "slow_init.py").write_text(SLOW_INIT.format(sig=sig))
    code = SCRIPT.format(folder=str(tmp_path), sig=sig, how=how)
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, preexec_fn=default_sigint
    )


@pytest.mark.parametrize("sig", ["SIGINT", "SIGTERM"])
def test_a_signal_during_the_import_is_raised_once_the_module_is_complete(tmp_path, sig):
    done = _run(tmp_path, sig, "import_uninterrupted")
    assert done.stdout.split("\n")[0] in ("interrupted; module complete: True", "stopped; module complete: True")
    assert done.returncode == (143 if sig == "SIGTERM" else 0), done.stderr


def test_a_plain_import_is_cut_half_way(tmp_path):
    """What the guard prevents (manifold3d aborts the process when this happens inside it)."""
    done = _run(tmp_path, "SIGINT", "importlib.import_module")
    assert done.stdout.strip() == "interrupted; module complete: False"


def test_the_handlers_are_put_back():
    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    sys.modules.pop("colorsys", None)
    assert import_uninterrupted("colorsys").rgb_to_hsv(1, 0, 0) == (0, 1, 1)
    assert {s: signal.getsignal(s) for s in before} == before


def test_off_the_main_thread_it_is_a_plain_import():
    sys.modules.pop("colorsys", None)
    got = []
    thread = threading.Thread(target=lambda: got.append(import_uninterrupted("colorsys")))
    thread.start()
    thread.join()
    assert got[0] is sys.modules["colorsys"]


def test_every_import_of_manifold3d_in_the_package_goes_through_it():
    package = Path(fabtiles.__file__).parent
    plain = []
    for path in package.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else []
            if isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            if any(n.split(".")[0] == "manifold3d" for n in names):
                plain.append(f"{path.relative_to(package)}:{node.lineno}")
    assert plain == []
