"""The browser tests' fixtures: the web app served by ``fabtiles serve`` in a process of its own.

The app runs apart from the test process, as a user runs it: a crash in the server (native code
under its thread pool) fails the test that met it and shows the server's last output, instead of
taking the test worker down with it; and Playwright's greenlets never share a process with the
server's threads.
"""

import contextlib
import os
import socket
import subprocess
import sys
import time
import urllib.request

import pytest
from browser_helpers import NO_GPU_ARGS, chromium, new_page, playwright

START_TIMEOUT_S = 60.0
NO_MODEL = "not built: this test reads the 2D page only"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _tail(path, lines=30) -> str:
    with contextlib.suppress(OSError):
        return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])
    return ""


@pytest.fixture(scope="session")
def _served(tmp_path_factory):
    """``fabtiles serve`` on a free loopback port: (process, URL, its log file)."""
    log = tmp_path_factory.mktemp("server") / "serve.log"
    env = {**os.environ, "PYTHONFAULTHANDLER": "1"}  # a native crash prints its Python stacks
    with open(log, "w") as out:
        port = _free_port()
        proc = subprocess.Popen(
            [sys.executable, "-m", "fabtiles", "serve", "--port", str(port)], stdout=out, stderr=out, env=env
        )
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + START_TIMEOUT_S
    while True:
        if proc.poll() is not None:
            pytest.fail(f"fabtiles serve exited ({proc.returncode}) before answering:\n{_tail(log)}")
        with contextlib.suppress(OSError):
            with urllib.request.urlopen(f"{url}/api/schema", timeout=5) as reply:
                if reply.status == 200:
                    break
        if time.monotonic() > deadline:
            proc.kill()
            pytest.fail(f"fabtiles serve did not answer in {START_TIMEOUT_S:.0f} s:\n{_tail(log)}")
        time.sleep(0.1)
    yield proc, url, log
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()


@pytest.fixture
def server(_served):
    """The app's URL; a test during which the server died fails, showing the server's output."""
    proc, url, log = _served
    if proc.poll() is not None:
        pytest.fail(f"fabtiles serve died earlier ({proc.returncode}):\n{_tail(log)}")
    yield url
    if proc.poll() is not None:
        pytest.fail(f"fabtiles serve died during this test ({proc.returncode}):\n{_tail(log)}")


@pytest.fixture(scope="session")
def _playwright():
    """Playwright's driver, one a worker (its sync API allows one at a time)."""
    with playwright() as pw:
        yield pw


@pytest.fixture(scope="session")
def _chromium(_playwright):
    """Headless Chromium without a GPU, launched once a worker (a launch takes about a second)."""
    with chromium(_playwright, NO_GPU_ARGS) as browser:
        yield browser


@pytest.fixture(scope="module")
def page(request, _served, _chromium):
    """A page in a fresh context of the worker's Chromium, one per test module.

    The editor's 3D view asks the server for the print's model (``/api/view.glb``) after every good
    design; the modules using this page never look at the model, so the request is answered at once
    with the error the view shows, and the server's time goes to the pictures and checks these tests
    read. A module that does not read the 3D view's caption either (no ``READS_3D_CAPTION = True``)
    gets no three.js: the view says it is missing, as without ``fabtiles install-viewer``, and
    Chromium neither compiles it nor draws with WebGL on its CPU at each page load. The 3D view's own
    tests (``test_view3d_browser.py``) have a page of their own with WebGL.
    """
    with new_page(_chromium) as pg:
        pg.route("**/api/view.glb?*", lambda route: route.fulfill(status=503, json={"error": NO_MODEL}))
        if not getattr(request.module, "READS_3D_CAPTION", False):
            pg.route("**/static/vendor/three/**", lambda route: route.abort())
        yield pg
