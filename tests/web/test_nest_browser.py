"""The nest page in headless Chromium (Debian's package), driven by Playwright: designs, Nest, the sheets, the zip.

Needs /usr/bin/chromium and the playwright package (see browser_helpers.py).
"""

import io
import re
import zipfile

import pytest

pytestmark = pytest.mark.browser

SMALL = "preset=table3-1&width=40&radius=8&frame=3"


def test_the_editor_links_its_design_to_the_nest_page(page, server):
    page.goto(f"{server}/?{SMALL}")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    href = page.get_attribute("#nest-link", "href")
    assert href.startswith("/nest?") and "preset=table3-1" in href and "width=40" in href


def test_nest_draws_the_sheets_and_downloads_their_zip(page, server, tmp_path):
    page.goto(f"{server}/nest?{SMALL}&gallery=table3-1")
    page.wait_for_selector("#designs li")
    assert page.text_content("#designs .design-name") == "table3-1"  # the gallery entry names it
    page.fill("#count-0", "3")
    page.fill("#sheet-w", "100")
    page.fill("#sheet-h", "60")
    page.fill("#time_s", "1")
    assert page.get_attribute("#download", "aria-disabled") == "true"  # nothing to download yet
    page.click("#nest-button")
    page.wait_for_selector("#sheets figure.sheet svg", timeout=60_000)
    captions = page.locator("#sheets figcaption").all_text_contents()
    assert len(captions) == 2  # two 40 mm tiles side by side on a 100 x 60 mm sheet, the third on another
    uses = [int(u) for c in captions for u in re.findall(r"material use (\d+)%", c)]
    assert len(uses) == 2 and all(0 < u <= 100 for u in uses)
    assert page.locator("#sheets svg path.part").count() == 3
    box = page.locator("#sheets figure.sheet svg").first.bounding_box()
    assert box["width"] <= 1280 and box["height"] > 0  # scaled to fit the page, not at true size
    assert "3 parts on 2 sheets of 100 × 60 mm" in page.text_content("#summary")  # noqa: RUF001 - the page's sign

    with page.expect_download() as info:
        page.click("#download")
    path = tmp_path / "nest.zip"
    info.value.save_as(path)
    with zipfile.ZipFile(io.BytesIO(path.read_bytes())) as zf:
        assert zf.namelist() == ["nest-sheet-1.dxf", "nest-sheet-2.dxf"]


def test_a_bad_count_is_shown_beside_its_design(page, server):
    page.goto(f"{server}/nest?{SMALL}")
    page.wait_for_selector("#designs li")
    page.fill("#count-0", "0")
    page.click("#nest-button")
    page.wait_for_function("() => document.querySelector('.err[data-for=\"designs[0]\"]').textContent.length > 0")
    assert "count must be a whole number >= 1, got 0" in page.text_content('.err[data-for="designs[0]"]')
    assert "bad" in page.get_attribute("#count-0", "class")


def test_a_gallery_entry_is_added_with_its_name(page, server):
    page.goto(f"{server}/nest?{SMALL}")
    page.wait_for_function("() => document.querySelectorAll('#add-design option').length > 1")
    value = page.eval_on_selector("#add-design", "s => [...s.options].find(o => o.value.includes('name=4.8.8')).value")
    page.select_option("#add-design", value)
    assert page.locator("#designs li").count() == 2
    assert page.locator("#designs .design-name").all_text_contents() == ["table3-1", "4.8.8"]
