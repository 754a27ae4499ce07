"""The manual's picture of the web app's nest page: samples/screenshots/web-nest.png.

Run by hand after changing the page: ``python samples/render_web_nest.py`` (needs the web
and browser extras and Debian's Chromium). It serves the app on a loopback port, opens
``/nest`` with three gallery designs (a square, a hexagon and a circle tile), nests them on a
300 x 200 mm sheet and saves the form and the sheets drawn.
"""

from __future__ import annotations

from pathlib import Path

OUT = Path(__file__).with_name("screenshots") / "web-nest.png"
DESIGNS = [  # (editor query, count)
    ("preset=table3-1&width=60&outline=square", 3),
    ("preset=table3-2&width=60&outline=hexagon", 3),
    ("preset=table3-3&width=60&outline=circle", 4),
]


def main() -> None:
    from playwright.sync_api import sync_playwright

    from fabtiles.web.app import local_server

    with local_server() as url, sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1300, "height": 900}, device_scale_factor=1)
        page.goto(f"{url}/nest?{DESIGNS[0][0]}")
        page.wait_for_selector("#designs li")
        for query, _ in DESIGNS[1:]:  # the others as the editor's Nest link would add them
            page.evaluate("(q) => window.addDesign && window.addDesign(new URLSearchParams(q))", query)
        page.wait_for_function(f"() => document.querySelectorAll('#designs li').length === {len(DESIGNS)}")
        for k, (_, count) in enumerate(DESIGNS):
            page.fill(f"#count-{k}", str(count))
        page.fill("#sheet-w", "300")
        page.fill("#sheet-h", "200")
        page.click("#nest-button")
        page.wait_for_selector("#sheets figure.sheet svg", timeout=120_000)
        page.wait_for_timeout(300)
        OUT.parent.mkdir(exist_ok=True)
        bottom = max(
            b["y"] + b["height"] for b in (page.locator(sel).bounding_box() for sel in ("#nest-form", "#view"))
        )
        page.screenshot(path=str(OUT), clip={"x": 0, "y": 0, "width": 1300, "height": bottom + 16})
        browser.close()
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
