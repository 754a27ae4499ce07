"""The browser tests' helpers: headless Chromium pages (the fixtures are in ``conftest.py``).

Chromium is Debian's package, driven by Playwright; `.ci/run` installs both and sets
FABTILES_REQUIRE_BROWSER=1, so there a missing browser fails instead of skipping.
"""

import contextlib
import os
import shutil

import pytest

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
REQUIRED = os.environ.get("FABTILES_REQUIRE_BROWSER") == "1"

# WebGL in a headless browser with no GPU: ANGLE on SwiftShader, Chromium's CPU renderer. The page's
# other content is rasterized by Skia on the CPU: rasterized through SwiftShader, the gallery's SVG
# thumbnails and the preview took seconds each and held up the page's requests behind them.
WEBGL_ARGS = ["--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-rasterization"]
NO_GPU_ARGS = ["--disable-gpu"]


def need(ok, why):
    """Skip when ``ok`` is false, or fail where the browser is required (CI)."""
    if not ok:
        if REQUIRED:
            pytest.fail(f"browser test required but {why}")
        pytest.skip(why)


@contextlib.contextmanager
def playwright():
    """Playwright's driver (one a process: its sync API runs one at a time)."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        need(False, "playwright is not installed")
    need(os.path.exists(CHROMIUM), f"{CHROMIUM} is not installed")
    with sync_playwright() as pw:
        yield pw


@contextlib.contextmanager
def chromium(pw, extra_args):
    """Headless Chromium, launched by Playwright ``pw`` with ``extra_args`` (pages: :func:`new_page`)."""
    browser = pw.chromium.launch(
        executable_path=CHROMIUM,
        args=[
            "--no-sandbox",
            *extra_args,
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ],
    )
    yield browser
    browser.close()


@contextlib.contextmanager
def new_page(browser):
    """A page of its own (1280 x 900, downloads accepted) in a fresh context of ``browser``: no
    cookies, storage or downloads shared with another test module's page."""
    context = browser.new_context(accept_downloads=True, viewport={"width": 1280, "height": 900})
    pg = context.new_page()
    pg.set_default_timeout(30_000)
    yield pg
    context.close()
