"""The page in headless Chromium (Debian's package), driven by Playwright.

Needs /usr/bin/chromium and the playwright package (see browser_helpers.py).
"""

import pytest

pytestmark = pytest.mark.browser
READS_3D_CAPTION = True  # an invalid design says so in the 3D view too (conftest.py: page)


def _preview_version(page):
    return page.get_attribute("#preview", "data-version")


def _wait_new_preview(page, old):
    page.wait_for_function(
        "old => { const v = document.querySelector('#preview').dataset.version; return v && v !== old; }", arg=old
    )


def test_page_slider_preset_and_download(page, server, tmp_path):
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    first_src = page.get_attribute("#preview", "src")
    assert first_src.startswith("data:image/svg+xml")

    # Move a slider: the preview follows without a reload and the URL keeps the state.
    v = _preview_version(page)
    page.fill("#rotation", "15")
    page.dispatch_event("#rotation", "change")
    _wait_new_preview(page, v)
    assert page.get_attribute("#preview", "src") != first_src
    assert "rotation=15" in page.url
    page.screenshot(path=str(tmp_path / "page.png"))

    # Load a preset.
    v = _preview_version(page)
    page.select_option("#preset", "table1-part1")
    _wait_new_preview(page, v)
    assert "preset=table1-part1" in page.url
    assert page.input_value("#n") == "8"

    # A bad value shows the error beside the control that caused it.
    page.fill("#stroke", "0")
    page.dispatch_event("#stroke", "change")
    page.wait_for_function("() => document.querySelector('.err[data-for=stroke]').textContent.length > 0")
    assert "stroke" in page.text_content(".err[data-for=stroke]")
    page.fill("#stroke", "1")
    page.dispatch_event("#stroke", "change")
    page.wait_for_function("() => document.querySelector('.err[data-for=stroke]').textContent === ''")

    # Download a DXF and read it with ezdxf.
    with page.expect_download() as info:
        page.click("#downloads a[data-format=dxf]")
    path = tmp_path / "tile.dxf"
    info.value.save_as(path)
    import ezdxf

    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4
    assert not doc.audit().has_errors
    assert len(doc.modelspace()) > 0

    # The laser job shows beside the checks; the LightBurn button downloads a project.
    page.wait_for_function("() => document.querySelector('#job').textContent.includes(' m of cut, ')")
    assert "about" in page.text_content("#job")
    with page.expect_download() as info:
        page.click("#downloads a[data-format=lbrn2]")
    project = tmp_path / "tile.lbrn2"
    info.value.save_as(project)
    assert project.read_text().startswith('<?xml version="1.0" encoding="UTF-8"?>\n<LightBurnProject ')


def test_findings_marks_fill_and_heights_controls(page, server):
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3&fill_small_holes=false")
    page.wait_for_function("() => document.querySelector('#checks li[data-code]')")
    assert not page.is_checked("#fill_small_holes")  # the URL's state reaches the controls
    assert page.is_checked("#show_findings")
    holes = page.locator("#marks circle.finding.small_hole[data-where=laser]").count()
    assert holes > 0 and page.locator("#marks circle.finding.hl").count() == 0
    from urllib.parse import unquote

    assert 'class="finding small_hole"' in unquote(page.get_attribute("#preview", "src"))

    # Choosing a finding in the list highlights its marks (and only those); choosing it again clears.
    page.click("#checks li[data-code=small_hole][data-where=laser]")
    assert page.locator("#marks circle.finding.small_hole.hl").count() == holes
    assert page.locator("#marks circle.finding.hl").count() == holes
    assert "chosen" in page.get_attribute("#checks li[data-code=small_hole][data-where=laser]", "class")
    page.click("#checks li[data-code=small_hole][data-where=laser]")
    assert page.locator("#marks circle.finding.hl").count() == 0

    # Fill the small holes: the findings and their marks go, the URL says so.
    v = _preview_version(page)
    page.check("#fill_small_holes")
    _wait_new_preview(page, v)
    page.wait_for_function("() => document.querySelector('#checks li.ok')")
    assert "fill_small_holes=true" in page.url
    assert page.locator("#marks circle.finding").count() == 0

    # Print heights go into the URL and every download link.
    v = _preview_version(page)
    page.fill("#base_mm", "3")
    page.dispatch_event("#base_mm", "change")
    _wait_new_preview(page, v)
    assert "base_mm=3" in page.url
    assert "base_mm=3" in page.get_attribute("#downloads a[data-format=stl]", "href")
    assert "base_mm=3" in page.get_attribute("#download-design", "href")

    # The marks can be switched off: the preview is then the plain tile.
    v = _preview_version(page)
    page.uncheck("#show_findings")
    _wait_new_preview(page, v)
    assert "findings" not in page.get_attribute("#preview", "src")


def test_gap_motif_controls_reach_the_url_and_the_design(page, server):
    """The gap circles' motif: rotation, and as a rosette (special circle 2) with its alpha and spr."""
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert "gap_special" not in page.url and "gap_rotation" not in page.url  # the default gap motif
    v = _preview_version(page)
    page.check("#gap_rosette")
    _wait_new_preview(page, v)
    assert "gap_special=2" in page.url and "gap_alpha=20" in page.url and "gap_spr=0.2" in page.url
    v = _preview_version(page)
    page.fill("#gap_rotation", "30")
    page.dispatch_event("#gap_rotation", "change")
    _wait_new_preview(page, v)
    assert "gap_rotation=30" in page.url
    design = page.get_attribute("#download-design", "href")
    assert "gap_special=2" in design and "gap_rotation=30" in design
    import urllib.request

    import tomllib

    with urllib.request.urlopen(server + design if design.startswith("/") else design) as resp:
        gap = tomllib.loads(resp.read().decode())["packing"]["gap_motif"]
    assert gap["special"] == 2 and gap["alpha"] == 20 and gap["spr"] == 0.2 and gap["rotation"] == 30
    # the URL alone brings the controls back
    page.goto(page.url)
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.is_checked("#gap_rosette") and page.input_value("#gap_rotation") == "30"


def test_the_inlay_kit_mode_shows_the_kit(page, server):
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert page.is_hidden("#kit-box")
    v = _preview_version(page)
    page.select_option("#laser_mode", "inlay")
    _wait_new_preview(page, v)
    page.wait_for_function(
        "() => document.querySelector('#kit').complete && document.querySelector('#kit').naturalWidth > 0"
    )
    assert page.is_visible("#kit-box") and "laser_mode=inlay" in page.url
    with page.expect_download() as info:
        page.click("#downloads a[data-format=dxf]")
    assert info.value.suggested_filename == "custom-kit-dxf.zip"  # the laser mode changed: no preset's design


def _label(page):
    """The Preset menu's shown text."""
    return page.evaluate(
        "() => { const s = document.querySelector('#preset'); return s.options[s.selectedIndex].text; }"
    )


def _set(page, selector, value):
    """Type a value and leave the box (its change event, once: no late one when focus moves on)."""
    v = _preview_version(page)
    page.fill(selector, value)
    page.press(selector, "Tab")
    _wait_new_preview(page, v)


def test_the_preset_menu_says_custom_once_edited_and_downloads_are_named(page, server, tmp_path):
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert _label(page) == "table3-3"
    assert page.get_attribute("#downloads a[data-format=dxf]", "download") == "table3-3.dxf"
    assert page.get_attribute("#download-design", "download") == "table3-3.toml"

    # any edit, of the motif or not: "custom", and so are the files
    _set(page, "#stroke", "2")
    assert _label(page) == "custom" and page.input_value("#preset") == ""
    assert page.get_attribute("#downloads a[data-format=stl]", "download") == "custom.stl"
    assert "name=custom" in page.get_attribute("#downloads a[data-format=stl]", "href")
    with page.expect_download() as info:
        page.click("#downloads a[data-format=svg]")
    assert info.value.suggested_filename == "custom.svg"
    assert "name=" not in page.url  # the page's name for the files is no parameter of the design

    # the values set back: the preset's name again
    _set(page, "#stroke", "1")
    assert _label(page) == "table3-3"
    with page.expect_download() as info:
        page.click("#downloads a[data-format=dxf]")
    assert info.value.suggested_filename == "table3-3.dxf"

    # a preset chosen in the menu names the design; the user's file name wins over it
    v = _preview_version(page)
    page.select_option("#preset", "table1-part1")
    _wait_new_preview(page, v)
    assert _label(page) == "table1-part1"
    assert page.get_attribute('#downloads a[data-format="3mf"]', "download") == "table1-part1.3mf"
    _set(page, "#name", "my tile")
    assert _label(page) == "table1-part1"  # a file name is no edit of the design
    with page.expect_download() as info:
        page.click("#download-design")
    assert info.value.suggested_filename == "my tile.toml"


def test_downloads_are_disabled_while_the_design_is_invalid(page, server):
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    links = "#downloads a"
    assert page.locator(f"{links}[href]").count() == page.locator(links).count() == 7
    page.fill("#stroke", "0")
    page.press("#stroke", "Tab")
    page.wait_for_function("() => document.querySelector('.err[data-for=stroke]').textContent.length > 0")
    # the error in the form's words, beside its field and above the buttons
    error = page.text_content(".err[data-for=stroke]")
    assert error.startswith("stroke must be a finite number > 0, got 0"), error
    assert "query" not in page.text_content("#status") and "[tile]" not in page.text_content("#status")
    assert page.locator(f"{links}[href]").count() == 0
    assert page.locator(f"{links}[aria-disabled=true]").count() == 7
    assert page.locator(f"{links}.disabled").first.evaluate("a => getComputedStyle(a).pointerEvents") == "none"
    _set(page, "#stroke", "1")
    assert page.locator(f"{links}[href]").count() == 7 and page.locator(f"{links}.disabled").count() == 0


def test_a_page_opened_with_an_invalid_value_says_what_is_wrong_in_each_view(page, server):
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3&stroke=0")
    page.wait_for_function("() => !document.querySelector('#preview-error').hidden")
    wrong = "stroke must be a finite number > 0, got 0"
    # no broken picture, no "loading" 3D view, no "..." checks: the error in each place
    assert page.text_content("#preview-error").startswith(f"No picture: {wrong}")
    assert page.locator("#preview").is_hidden()
    page.wait_for_function("() => document.querySelector('#view3d-caption').textContent.includes('not shown')")
    assert page.text_content("#view3d-caption").startswith(f"The print in 3D: not shown, {wrong}")
    assert page.text_content("#checks").startswith(f"Not checked: {wrong}")
    _set(page, "#stroke", "1")  # fixed: the picture and the checks come back
    assert page.locator("#preview").is_visible() and page.locator("#preview-error").is_hidden()
    page.wait_for_function("() => !document.querySelector('#checks').textContent.startsWith('Not checked')")


def test_controls_show_only_where_they_apply(page, server):
    page.goto(f"{server}/?preset=table3-3&width=60&radius=10&frame=3")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")

    def hidden(sel):
        return page.locator(sel).is_hidden()

    # a square: no height; pierced: no kit; a relief: its base and relief heights only; miter: the limit
    assert hidden("#height-row") and hidden("#inlay_fit_mm") and hidden("#inlay_base")
    assert not hidden("#base_mm") and not hidden("#relief_mm") and hidden("#pierced_mm") and hidden("#deboss_mm")
    assert hidden("#interlace_gap_mm") and hidden("#inlay") and not hidden("#miter_limit-row")
    assert hidden("#gap_alpha-row") and not hidden("#gap_n-row") and hidden("#edge-row")
    page.select_option("#outline", "rectangle")
    page.select_option("#laser_mode", "inlay")
    page.select_option("#print_style", "deboss")
    page.select_option("#join", "round")
    page.check("#interlace")
    page.check("#gap_rosette")
    assert not hidden("#height-row") and not hidden("#inlay_fit_mm") and not hidden("#inlay_base")
    assert not hidden("#base_mm") and hidden("#relief_mm") and not hidden("#deboss_mm") and not hidden("#inlay")
    assert not hidden("#interlace_gap_mm") and hidden("#interlace_cut") and hidden("#miter_limit-row")
    assert not hidden("#gap_alpha-row") and not hidden("#gap_spr-row")
    page.select_option("#packing", "none")
    assert hidden("#gap_n-row") and hidden("#gap_inner-row") and hidden("#gap_rosette") and hidden("#radius-row")
    assert hidden("#seamless") and hidden("#outline_circles") and hidden("#gap_alpha-row")
    page.select_option("#packing", "archimedean")
    assert not hidden("#edge-row") and hidden("#radius-row") and not hidden("#gap_n-row")
