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
def chromium_page(extra_args):
    """A Playwright page in headless Chromium (1280 x 900, downloads accepted)."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        need(False, "playwright is not installed")
    need(os.path.exists(CHROMIUM), f"{CHROMIUM} is not installed")
    with sync_playwright() as pw:
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
        context = browser.new_context(accept_downloads=True, viewport={"width": 1280, "height": 900})
        pg = context.new_page()
        pg.set_default_timeout(30_000)
        yield pg
        browser.close()
