"""docs/girih.md's subdivision pictures are current: samples/render_girih.py draws exactly the committed files."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_the_committed_girih_pictures_are_current_and_shown(tmp_path):
    spec = importlib.util.spec_from_file_location("render_girih", ROOT / "samples" / "render_girih.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    written = module.render(tmp_path)
    committed = ROOT / "samples" / "pictures" / "girih"
    assert sorted(p.name for p in written) == sorted(p.name for p in committed.glob("*.svg"))
    stale = [p.name for p in written if p.read_bytes() != (committed / p.name).read_bytes()]
    assert stale == [], f"run python samples/render_girih.py: {stale}"
    text = (ROOT / "docs" / "girih.md").read_text(encoding="utf-8")
    assert all(f"../samples/pictures/girih/{p.name}" in text for p in written)
