"""The pattern in colours on the page, in headless Chromium: the palette menu and the colour pickers fill the
preview's faces (the mosaic's 3D view in its colours is test_view3d_browser's)."""

import re
from urllib.parse import unquote

import pytest

from fabtiles.designs.colour import PALETTES

pytestmark = pytest.mark.browser

SMALL = "preset=table3-3&width=60&radius=10&frame=3"


def _wait_new_preview(page, old):
    page.wait_for_function(
        "old => { const v = document.querySelector('#preview').dataset.version; return v && v !== old; }", arg=old
    )


def _changed(page, action):
    """Do ``action`` and wait for the preview it brings."""
    old = page.get_attribute("#preview", "data-version")
    action()
    _wait_new_preview(page, old)


def _fills(page) -> dict:
    """The preview's face classes and their fills: ``{"A": "#1e4fa0", ...}``."""
    src = page.get_attribute("#preview", "src")
    svg = unquote(src.split(",", 1)[1])
    return dict(re.findall(r'<path class="face-([A-Z]+)" d="[^"]*" fill="(#[0-9a-f]{6})"', svg))


def _wait_faces(page, letter, colour):
    page.wait_for_function(
        "([l, c]) => { const p = document.querySelector(`#face_${l}`); return p && p.value === c; }",
        arg=[letter, colour],
    )


def test_palette_and_pickers_fill_the_faces(page, server):
    page.goto(f"{server}/?{SMALL}")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert _fills(page) == {}  # no colours asked for: the plain picture
    _changed(page, lambda: page.select_option("#colour_by", "shape"))
    _changed(page, lambda: page.select_option("#palette", "iznik"))
    iznik = PALETTES["iznik"]
    assert _fills(page) == {k: iznik.faces[i].hex for i, k in enumerate("ABCD")}
    assert "colour_by=shape" in page.url and "palette=iznik" in page.url

    # the list of classes: a row each with its swatch, count, shape and picker in the palette's colour
    _wait_faces(page, "D", iznik.faces[3].hex)
    rows = page.locator("#face-classes .face-row")
    assert rows.count() == 4
    assert re.fullmatch(r"[\d,]+ × .+", rows.nth(0).locator(".what").text_content())  # noqa: RUF001 - the page's sign
    assert page.input_value("#band_colour") == iznik.band.hex and page.input_value("#base_colour") == iznik.base.hex

    # a class's picker changes that class's fill only, and the URL keeps it
    _changed(page, lambda: page.fill("#face_B", "#123456"))
    fills = _fills(page)
    assert fills["B"] == "#123456" and fills["A"] == iznik.faces[0].hex
    assert "face_B=%23123456" in page.url
    assert page.is_enabled('.face-row[data-letter="B"] .reset')

    # another palette: the classes not chosen take its colours, the chosen one keeps its own
    mamluk = PALETTES["mamluk"]
    _changed(page, lambda: page.select_option("#palette", "mamluk"))
    _wait_faces(page, "A", mamluk.faces[0].hex)
    assert page.input_value("#face_B") == "#123456" and page.input_value("#band_colour") == mamluk.band.hex
    fills = _fills(page)
    assert fills == {"A": mamluk.faces[0].hex, "B": "#123456", "C": mamluk.faces[2].hex, "D": mamluk.faces[3].hex}

    # the band's picker; "palette's" gives a class its palette colour back
    _changed(page, lambda: page.fill("#band_colour", "#ffd400"))
    assert "band_colour=%23ffd400" in page.url
    assert 'fill="#ffd400"' in unquote(page.get_attribute("#preview", "src"))
    _changed(page, lambda: page.click('.face-row[data-letter="B"] .reset'))
    assert "face_B" not in page.url and _fills(page)["B"] == mamluk.faces[1].hex
    _wait_faces(page, "B", mamluk.faces[1].hex)

    # a link opens with its colours (a CSS name, a palette's) in the pickers as in the picture: navy is
    # Iznik's own, teal CSS's
    page.goto(f"{server}/?{SMALL}&colour_by=shape&palette=iznik&face_C=navy&face_D=teal")
    _wait_faces(page, "C", iznik.base.hex)
    _wait_faces(page, "D", "#008080")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert _fills(page)["C"] == iznik.base.hex and _fills(page)["D"] == "#008080"


def test_a_chosen_colour_of_a_class_the_design_lacks_is_dropped(page, server):
    """Fewer classes after an edit: the colour of a class that is gone is dropped, the preview stays good."""
    page.goto(f"{server}/?{SMALL}&colour_by=shape&face_D=%23123456")
    _wait_faces(page, "D", "#123456")
    _changed(page, lambda: page.select_option("#colour_by", "none"))
    page.wait_for_function("() => !location.search.includes('face_D')")
    page.wait_for_function("() => document.querySelectorAll('#face-classes .face-row').length === 1")
    assert "✗" not in page.text_content("#status")


def test_mosaic_is_a_print_style_with_its_inset(page, server):
    page.goto(f"{server}/?{SMALL}")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert "mosaic" in page.eval_on_selector_all("#print_style option", "os => os.map(o => o.value)")
    assert not page.is_visible("#mosaic_inset_mm")
    _changed(page, lambda: page.select_option("#print_style", "mosaic"))
    assert page.is_visible("#mosaic_inset_mm") and "print_style=mosaic" in page.url
