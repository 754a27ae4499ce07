"""docs/borders.md's pictures are current: samples/render_borders.py draws exactly the committed files."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_the_committed_border_pictures_are_current_and_shown(tmp_path):
    spec = importlib.util.spec_from_file_location("render_borders", ROOT / "samples" / "render_borders.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    written = module.render(tmp_path)
    committed = ROOT / "samples" / "pictures" / "borders"
    assert sorted(p.name for p in written) == sorted(p.name for p in committed.glob("*.svg"))
    stale = [p.name for p in written if p.read_bytes() != (committed / p.name).read_bytes()]
    assert stale == [], f"run python samples/render_borders.py: {stale}"
    text = (ROOT / "docs" / "borders.md").read_text(encoding="utf-8")
    assert all(f"../samples/pictures/borders/{p.name}" in text for p in written)
