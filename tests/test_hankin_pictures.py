"""docs/hankin.md's pictures are current: samples/render_hankin.py draws exactly the committed files."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _script():
    spec = importlib.util.spec_from_file_location("render_hankin", ROOT / "samples" / "render_hankin.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_committed_pictures_are_current(tmp_path):
    module = _script()
    written = module.render(tmp_path)
    committed = ROOT / "samples" / "pictures" / "hankin"
    assert sorted(p.name for p in written) == sorted(p.name for p in committed.glob("*.svg"))
    stale = [p.name for p in written if p.read_bytes() != (committed / p.name).read_bytes()]
    assert stale == [], f"run python samples/render_hankin.py: {stale[:5]}"


def test_the_docs_table_is_the_scripts():
    module = _script()
    text = (ROOT / "docs" / "hankin.md").read_text(encoding="utf-8")
    assert module.table_markdown() in text
    assert "../samples/pictures/hankin/construction.svg" in text
    assert "../samples/pictures/hankin/parquet.svg" in text
    assert len(module.table_markdown().splitlines()) == 2 + 11
