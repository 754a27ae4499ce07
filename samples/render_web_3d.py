"""The README's picture of the web app's 3D view: samples/screenshots/web-3d.png.

Run by hand after changing the page: ``python samples/render_web_3d.py`` (needs the web
and browser extras, Debian's Chromium and ``fabtiles install-viewer``). It serves the app
on a loopback port, opens the default design in headless Chromium (WebGL through
SwiftShader), turns the model a little, zooms in and saves the preview, the 3D view and the
job and material lines below them.
"""

from __future__ import annotations

from pathlib import Path

OUT = Path(__file__).with_name("screenshots") / "web-3d.png"
QUERY = "preset=table3-3&radius=15&width=150&interlace=true&stroke=1.5"


def main() -> None:
    from playwright.sync_api import sync_playwright

    from fabtiles.web.app import local_server

    with local_server() as url, sync_playwright() as pw:
        browser = pw.chromium.launch(
            executable_path="/usr/bin/chromium",
            args=["--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
        )
        page = browser.new_page(viewport={"width": 1500, "height": 1000}, device_scale_factor=1)
        page.goto(f"{url}/?{QUERY}")
        page.wait_for_function("() => document.querySelector('#view3d-canvas').dataset.version", timeout=120_000)
        page.wait_for_function("() => document.querySelector('#job').dataset.version", timeout=120_000)
        box = page.locator("#view3d-canvas").bounding_box()
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x + 50, y - 40, steps=5)
        page.mouse.up()
        page.mouse.wheel(0, -1000)  # closer: the strands' dips and the two colours
        page.wait_for_timeout(300)
        top = page.locator("#pictures").bounding_box()
        bottom = page.locator("#material").bounding_box()
        clip = {
            "x": top["x"] - 4,
            "y": top["y"] - 4,
            "width": top["width"] + 8,
            "height": bottom["y"] + bottom["height"] - top["y"] + 8,
        }
        OUT.parent.mkdir(exist_ok=True)
        page.screenshot(path=str(OUT), clip=clip)
        browser.close()
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
