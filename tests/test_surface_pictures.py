"""docs/surfaces.md's pictures are committed and shown: samples/render_surfaces.py draws them.

The script is not run here (the roller takes about ten seconds to draw): it says how to draw the
pictures again; this checks that each of its pictures is a PNG of the size it draws, and that
the docs show every one of them.
"""

import importlib.util
import inspect
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
RENDERS = ROOT / "samples" / "renders"


def _script():
    spec = importlib.util.spec_from_file_location("render_surfaces", ROOT / "samples" / "render_surfaces.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


SCRIPT = _script()
DRAWN_BY = {
    "roller": SCRIPT.roller_picture,
    "imprint": SCRIPT.imprint_picture,
    "lampshade": SCRIPT.lampshade_picture,
}


@pytest.mark.parametrize("key", sorted(SCRIPT.PICTURES))
def test_each_picture_is_committed_at_the_size_the_script_draws(key):
    from PIL import Image

    params = inspect.signature(DRAWN_BY[key]).parameters
    size = (params["width"].default, params["height"].default)
    with Image.open(RENDERS / SCRIPT.PICTURES[key]) as image:
        assert (image.format, image.mode, image.size) == ("PNG", "RGB", size)
    assert max(size) <= 900


def test_the_surfaces_page_shows_every_picture_and_says_how_they_are_drawn():
    page = (ROOT / "docs" / "surfaces.md").read_text(encoding="utf-8")
    for name in SCRIPT.PICTURES.values():
        assert f"](../samples/renders/{name})" in page
    assert "python samples/render_surfaces.py" in page


def test_the_readme_shows_the_lampshade():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert f"](samples/renders/{SCRIPT.PICTURES['lampshade']})" in readme
