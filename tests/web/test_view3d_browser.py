"""The 3D view and the gallery in headless Chromium, WebGL through SwiftShader (no GPU)."""

import io

import numpy as np
import pytest
from browser_helpers import WEBGL_ARGS, chromium, need, new_page

pytestmark = pytest.mark.browser

SMALL = "preset=table3-3&width=60&radius=10&frame=3&stroke=1.5"


@pytest.fixture(scope="module")
def page(_served, _playwright):
    from fabtiles.web.viewer_files import installed

    need(installed(), "three.js is not installed in the package: run `fabtiles install-viewer`")
    with chromium(_playwright, WEBGL_ARGS) as browser, new_page(browser) as pg:
        yield pg


def _version(page):
    return page.get_attribute("#view3d-canvas", "data-version")


def _wait_model(page, old=None):
    page.wait_for_function(
        "old => { const v = document.querySelector('#view3d-canvas').dataset.version; return v && v !== old; }",
        arg=old,
        timeout=60_000,
    )


def _pixels(page) -> np.ndarray:
    from PIL import Image

    png = page.locator("#view3d-canvas").screenshot()
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)


def _colour_counts(rgb: np.ndarray) -> dict:
    """Pixels of the background, the light base (warm: red over blue) and the dark blue pattern."""
    r, _g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    background = np.abs(rgb - [0xEE, 0xF1, 0xF5]).sum(axis=-1) < 12
    base = ~background & (r > 150) & (r > b + 12)
    pattern = ~background & (b > r + 40) & (r < 120)
    return {"background": int(background.sum()), "base": int(base.sum()), "pattern": int(pattern.sum())}


def test_the_relief_turns_in_3d(page, server):
    page.goto(f"{server}/?{SMALL}")
    _wait_model(page)
    rgb = _pixels(page)
    counts = _colour_counts(rgb)
    total = rgb.shape[0] * rgb.shape[1]
    assert counts["background"] < 0.9 * total  # the model is drawn
    assert counts["base"] > 0.02 * total and counts["pattern"] > 0.1 * total, counts  # both parts (8 %, 42 %)
    assert page.get_attribute("#view3d", "data-parts") == "base,pattern"
    assert "Showing the whole 60 x 60 mm tile" in page.text_content("#view3d-caption")

    # Orbit: a drag turns the model, reset brings the first view back.
    box = page.locator("#view3d-canvas").bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(cx, cy)
    page.mouse.down()
    page.mouse.move(cx + 120, cy + 40, steps=6)
    page.mouse.up()
    turned = _pixels(page)
    assert np.abs(turned - rgb).sum(axis=-1).astype(bool).mean() > 0.05
    page.click("#view3d-reset")
    back = _pixels(page)
    assert np.abs(back - rgb).sum(axis=-1).astype(bool).mean() < 0.01

    # A parameter change redraws it.
    v = _version(page)
    page.fill("#stroke", "3")
    page.dispatch_event("#stroke", "change")
    _wait_model(page, v)
    assert np.abs(_pixels(page) - rgb).sum(axis=-1).astype(bool).mean() > 0.02

    # A bad parameter shows the field's error and keeps the last good model.
    good, v = _pixels(page), _version(page)
    page.fill("#stroke", "0")
    page.dispatch_event("#stroke", "change")
    page.wait_for_function("() => document.querySelector('.err[data-for=stroke]').textContent.length > 0")
    # the view has dropped any model still coming once its caption says so: none is drawn after this
    page.wait_for_function(
        "() => document.querySelector('#view3d-caption').textContent.startsWith('3D view not updated')"
    )
    assert "stroke" in page.text_content(".err[data-for=stroke]")
    assert _version(page) == v
    assert np.abs(_pixels(page) - good).sum(axis=-1).astype(bool).mean() < 0.01
    page.fill("#stroke", "1.5")
    page.dispatch_event("#stroke", "change")
    _wait_model(page, v)


DESIGN = "q => document.dispatchEvent(new CustomEvent('fabtiles:design', { detail: q }))"


def test_a_newer_design_aborts_the_model_on_its_way(page, server):
    """Two designs in a row: the first's model, still being built, is aborted (the browser closes its request,
    the server stops); the view ends on the second's, and no caption on the way said anything went wrong."""
    page.goto(f"{server}/?{SMALL}")
    _wait_model(page)
    v = _version(page)
    page.evaluate(
        """() => { window.captions = [];
        new MutationObserver(() => window.captions.push(document.querySelector('#view3d-caption').textContent))
          .observe(document.querySelector('#view3d-caption'), { childList: true, characterData: true, subtree: true });
        }"""
    )
    big = "preset=table3-3&width=300&radius=10&frame=3&stroke=1.5"  # a second or more to build

    def glb(width):
        return lambda r: "/api/view.glb" in r.url and f"width={width}&" in r.url

    with page.expect_request(glb(300)):
        page.evaluate(DESIGN, big)
    with page.expect_event("requestfailed", predicate=glb(300), timeout=20_000) as failed:
        page.evaluate(DESIGN, f"{SMALL}&stroke=2")
    assert "ERR_ABORTED" in failed.value.failure
    _wait_model(page, v)
    assert _version(page) == str(int(v) + 2)  # the second design's model
    assert page.text_content("#view3d-caption").startswith("Showing the whole 60 x 60 mm tile")
    captions = page.evaluate("() => window.captions")
    assert captions and not any("not updated" in c or "could not be read" in c for c in captions), captions


def _background(rgb: np.ndarray) -> np.ndarray:
    return np.abs(rgb - [0xEE, 0xF1, 0xF5]).sum(axis=-1) < 12


def test_the_camera_frames_the_whole_tile(page, server):
    """The default 150 mm tile: no part of it touches the canvas's edge, and it fills most of the canvas."""
    page.goto(f"{server}/")
    _wait_model(page)
    assert "Showing the whole 150 x 150 mm tile" in page.text_content("#view3d-caption")
    rgb = _pixels(page)
    ground = _background(rgb)
    inner = ground[:, 6:-6]  # not the rounded corners (border-radius 4 px: the figure's white shows there)
    edge = np.concatenate([inner[:3].ravel(), inner[-3:].ravel(), ground[6:-6, :3].ravel(), ground[6:-6, -3:].ravel()])
    assert edge.all(), f"{(~edge).sum()} pixels of the model on the canvas's edge"
    rows, cols = np.nonzero(~ground)
    height, width = ground.shape
    # the model spans most of the canvas one way (the fit's 10 % margin, the view's perspective)
    assert max((cols.max() - cols.min()) / width, (rows.max() - rows.min()) / height) > 0.7


def test_the_camera_stays_above_the_plate(page, server):
    """A drag towards the horizon stops at 80 degrees from straight down: never under the plate."""
    page.goto(f"{server}/?{SMALL}")
    _wait_model(page)
    assert 40 < float(page.get_attribute("#view3d-canvas", "data-polar")) < 60  # the first view, from above
    box = page.locator("#view3d-canvas").bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    for _ in range(3):  # upwards: the camera goes down towards the plate's plane, and would pass under it
        page.mouse.move(cx, cy + box["height"] / 3)
        page.mouse.down()
        page.mouse.move(cx, cy - box["height"] / 3, steps=8)
        page.mouse.up()
    polar = float(page.get_attribute("#view3d-canvas", "data-polar"))
    assert 79.5 < polar <= 80.01, polar
    # a right-drag moves the view over the plate's plane: the camera keeps its angle and its height
    page.mouse.move(cx, cy)
    page.mouse.down(button="right")
    page.mouse.move(cx, cy + 150, steps=6)
    page.mouse.up(button="right")
    assert float(page.get_attribute("#view3d-canvas", "data-polar")) <= 80.01
    page.click("#view3d-reset")
    assert 40 < float(page.get_attribute("#view3d-canvas", "data-polar")) < 60


def test_a_deboss_inlay_shows_both_parts(page, server):
    page.goto(f"{server}/?{SMALL}&print_style=deboss&inlay=true")
    _wait_model(page)
    assert page.get_attribute("#view3d", "data-parts") == "plate,inlay"


def _close(a: str, b: str, tol: int = 2) -> bool:
    return all(abs(int(a[i : i + 2], 16) - int(b[i : i + 2], 16)) <= tol for i in (1, 3, 5))


def test_a_mosaic_shows_its_parts_in_their_colours(page, server):
    """A mosaic print: a part per colour (base, bands, each class), each drawn in its colour."""
    import json
    import urllib.request

    from fabtiles.designs.colour import PALETTES

    query = f"{SMALL}&colour_by=shape&palette=iznik&print_style=mosaic"

    with urllib.request.urlopen(f"{server}/api/view.glb?{query}") as r:
        parts = list(json.loads(r.headers["X-Fabtiles-Parts"]))
    iznik = PALETTES["iznik"]
    by_name = {c.name: c.hex for c in (iznik.base, iznik.band, *iznik.faces)}
    expected = [by_name[p.split(" (")[0]] for p in parts]
    assert len(parts) >= 4 and parts[:2] == ["navy (base)", "white (bands)"]
    page.goto(f"{server}/?{query}")
    _wait_model(page)
    assert page.get_attribute("#view3d", "data-parts") == ",".join(parts)
    shown = page.get_attribute("#view3d", "data-colours").split(",")
    assert len(shown) == len(parts) and all(_close(a, b) for a, b in zip(shown, expected, strict=True)), (
        shown,
        expected,
    )
    caption = page.text_content("#view3d-caption")
    assert all(p in caption for p in parts)


def test_one_colour_mode_shows_the_pictures_colours_in_the_colours_box(page, server):
    """No colours given: the pickers show the bands as the preview draws them and the plate as the 3D view does."""
    page.goto(f"{server}/?{SMALL}")
    _wait_model(page)
    page.wait_for_function("() => document.querySelector('#face-classes .face-row')")
    svg = page.evaluate("() => decodeURIComponent(document.querySelector('#preview').src.split(',')[1])")
    band = page.input_value("#band_colour")
    assert band == "#1f3b73" and f'fill="{band}"' in svg  # the bands as the preview draws them
    base = page.get_attribute("#view3d", "data-colours").split(",")[0]  # the relief's base, its first part
    assert page.get_attribute("#view3d", "data-parts").split(",")[0] == "base"
    assert _close(page.input_value("#base_colour"), base), (page.input_value("#base_colour"), base)
    assert (
        page.locator("#face-classes .swatch").first.evaluate("e => getComputedStyle(e).backgroundColor")
        == "rgb(255, 255, 255)"
    )  # the faces are open: the picture's white
    # colours asked for: the pickers show the palette's, as the pictures then do
    old = page.get_attribute("#preview", "data-version")
    page.select_option("#colour_by", "shape")
    page.wait_for_function("old => document.querySelector('#preview').dataset.version !== old", arg=old)
    from fabtiles.designs.colour import PALETTES

    page.wait_for_function(f"() => document.querySelector('#base_colour').value === '{PALETTES['zellige'].base.hex}'")
    assert page.input_value("#band_colour") == PALETTES["zellige"].band.hex


def test_the_gallery_opens_a_tiling_in_the_editor(page, server):
    page.goto(f"{server}/gallery")
    from fabtiles.web.gallery import entries

    page.wait_for_function(f"() => document.querySelectorAll('#gallery a').length === {len(entries())}")
    # the header counts what the page shows
    counts = [int(n) for n in __import__("re").findall(r"\d+", page.text_content("#gallery-intro"))]
    assert counts == [7, 11, 4, 1, 2, 2, 2] and sum(counts) == page.locator("#gallery a").count()
    assert "2 cylinders (texture roller, lampshade), 2 girih patterns" in page.text_content("#gallery-intro")
    assert "2 classical devices (border of stars, parquet deformation)" in page.text_content("#gallery-intro")
    page.wait_for_function(
        "() => { const i = document.querySelector('#gallery a[data-key=\"4.8.8\"] img');"
        " return i.complete && i.naturalWidth > 0; }",
        timeout=60_000,
    )
    page.click('#gallery a[data-key="4.8.8"]')
    page.wait_for_url("**/?*tiling=4.8.8*")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.input_value("#packing") == "archimedean" and page.input_value("#tiling") == "4.8.8"
    assert page.input_value("#motif_8") == "table1-part1" and page.input_value("#n") == "8"
    assert "✗" not in page.text_content("#status")
    # the sliders hold the entry's values (r1 = 0.55 was once pinned at a slider's minimum of 1)
    assert float(page.input_value("#r1-range")) == 0.55 and float(page.input_value("#r2-range")) == 1
    assert float(page.get_attribute("#r1-range", "min")) < 0.55
    # the design is named after the entry: the Preset menu, the downloads, the shared link
    label = page.evaluate(
        "() => { const s = document.querySelector('#preset'); return s.options[s.selectedIndex].text; }"
    )
    assert label == "4.8.8 (gallery)"
    assert page.get_attribute("#downloads a[data-format=dxf]", "download") == "4.8.8.dxf"
    assert "gallery=4.8.8" in page.url
    _wait_model(page)
    assert "packing=archimedean" in page.url and "edge=14" in page.url  # the editor's URL stays shareable


def _shown(page, selector) -> bool:
    return page.locator(selector).first.is_visible()


def test_the_gallery_opens_the_roller_standing_in_3d(page, server):
    """The roller from the gallery: the surface's controls instead of the tile's outline, size and frame, the
    strip in 2D, the cylinder standing in 3D inside the canvas, its line in the checks, its print downloads."""
    page.goto(f"{server}/gallery")
    page.wait_for_selector('#gallery a[data-key="roller"]')
    page.click('#gallery a[data-key="roller"]')
    page.wait_for_url("**/?*shape=cylinder*")
    _wait_model(page)
    assert "width=" not in page.url and "frame=" not in page.url and "diameter=60" in page.url
    assert "Showing the whole cylinder, its unrolled strip" in page.text_content("#view3d-caption")
    assert page.get_attribute("#view3d", "data-parts") == "base,pattern"
    # the controls: the surface's for a roller, not the flat tile's nor a shade's
    assert page.input_value("#shape") == "cylinder" and page.input_value("#diameter") == "60"
    assert page.input_value("#length") == "80"
    for selector in ("#diameter-row", "#length-row", "#fit", "#mirror", "#bore_mm", "#rim_mm", "#surface-note"):
        assert _shown(page, selector), selector
    for selector in ("#width-row", "#frame-row", "#outline", "#lamp_fitting_mm"):
        assert not _shown(page, selector), selector
    # the 3D view frames the standing cylinder: none of it on the canvas's edge, most of the height used
    ground = _background(_pixels(page))
    inner = ground[:, 6:-6]
    edge = np.concatenate([inner[:3].ravel(), inner[-3:].ravel(), ground[6:-6, :3].ravel(), ground[6:-6, -3:].ravel()])
    assert edge.all(), f"{(~edge).sum()} pixels of the model on the canvas's edge"
    rows, _ = np.nonzero(~ground)
    assert (rows.max() - rows.min()) / ground.shape[0] > 0.6
    # the checks' line; the downloads: STL and 3MF, the cutters' and STEP disabled with the reason shown
    page.wait_for_function("() => document.querySelector('#status').textContent.includes('cylinder (roller)')")
    assert "9 periods around" in page.text_content("#status")
    assert page.get_attribute("#downloads a[data-format=stl]", "download") == "roller.stl"
    for fmt in ("dxf", "svg", "lbrn2", "step"):
        assert page.get_attribute(f"#downloads a[data-format={fmt}]", "href") is None, fmt
    unmade = page.text_content("#unmade")
    assert _shown(page, "#unmade") and "is printed, not cut" in unmade and "STEP is not made" in unmade
    # back to a flat tile: its controls and every download again
    v = _version(page)
    page.select_option("#shape", "flat")
    _wait_model(page, v)
    assert _shown(page, "#width-row") and not _shown(page, "#diameter-row") and not _shown(page, "#unmade")
    assert page.get_attribute("#downloads a[data-format=dxf]", "href").startswith("/api/export/dxf?")


def test_a_stamp_keeps_the_tiles_controls_and_shows_its_block(page, server):
    """A stamp from the shape menu: the tile's outline, size and frame stay, the block's and the groove's
    controls show, the cylinder's hide; the 3D view shows the block and the pattern; the cutters' files and
    STEP are disabled with the reason shown."""
    page.goto(f"{server}/?preset=table3-3&outline=hexagon&width=50&radius=8&frame=2&stroke=1.6&print_style=relief")
    _wait_model(page)
    v = _version(page)
    page.select_option("#shape", "stamp")
    _wait_model(page, v)
    assert "shape=stamp" in page.url and "width=50" in page.url
    for selector in ("#width-row", "#frame-row", "#outline", "#block_mm", "#grip_mm", "#groove_mm", "#mirror"):
        assert _shown(page, selector), selector
    for selector in ("#diameter-row", "#fit", "#bore_mm", "#pointed_tops", "#surface-note"):
        assert not _shown(page, selector), selector
    assert page.get_attribute("#view3d", "data-parts") == "block,pattern"
    for fmt in ("dxf", "svg", "lbrn2", "step"):
        assert page.get_attribute(f"#downloads a[data-format={fmt}]", "href") is None, fmt
    assert "a clay stamp has no STEP file" in page.text_content("#unmade")
    v = _version(page)
    page.fill("#block_mm", "16")
    page.dispatch_event("#block_mm", "change")
    _wait_model(page, v)
    assert "block_mm=16" in page.url
