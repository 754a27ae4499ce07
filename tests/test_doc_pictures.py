"""The docs' drawn pictures are current: each ``samples/render_<name>.py`` draws exactly the files committed
in ``samples/pictures/<name>/``, and its page shows every one of them."""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

PICTURES = {"borders": "borders.md", "girih": "girih.md", "hankin": "hankin.md"}
"""The pictures' folder (and script) name -> the docs page that shows them."""


def script(name: str):
    """``samples/render_<name>.py`` as a module."""
    spec = importlib.util.spec_from_file_location(f"render_{name}", ROOT / "samples" / f"render_{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name", sorted(PICTURES))
def test_the_committed_pictures_are_current_and_shown(name, tmp_path):
    written = script(name).render(tmp_path)
    committed = ROOT / "samples" / "pictures" / name
    assert sorted(p.name for p in written) == sorted(p.name for p in committed.glob("*.svg"))
    stale = [p.name for p in written if p.read_bytes() != (committed / p.name).read_bytes()]
    assert stale == [], f"run python samples/render_{name}.py: {stale[:5]}"
    text = (ROOT / "docs" / PICTURES[name]).read_text(encoding="utf-8")
    assert [p.name for p in written if f"../samples/pictures/{name}/{p.name}" not in text] == []


def test_the_hankin_table_is_the_scripts():
    module = script("hankin")
    text = (ROOT / "docs" / "hankin.md").read_text(encoding="utf-8")
    assert module.table_markdown() in text
    assert len(module.table_markdown().splitlines()) == 2 + 11
