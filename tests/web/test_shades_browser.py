"""A shaded engraving on the page, in headless Chromium: the 'Shaded on a laser' box draws the classes burnt."""

import pytest
from test_colours_browser import SMALL, _changed, _fills

from fabtiles.geometry.shades import WOOD

pytestmark = pytest.mark.browser


def test_the_shaded_box_draws_the_classes_burnt_on_wood(page, server):
    page.goto(f"{server}/?{SMALL}&colour_by=shape&laser_mode=pierced")
    page.wait_for_function("() => document.querySelector('#preview').dataset.version")
    assert set(_fills(page)) == set("ABCD")  # the palette's colours

    def shade():
        page.fill("#shaded", "B D")
        page.press("#shaded", "Enter")
        page.dispatch_event("#shaded", "change")

    _changed(page, shade)
    fills = _fills(page)
    # the pierced cut keeps B and D, burnt, and cuts A and C out: no face of theirs drawn
    assert set(fills) == {"B", "D"} and WOOD not in fills.values()
    assert "shaded=B+D" in page.url or "shaded=B%20D" in page.url
