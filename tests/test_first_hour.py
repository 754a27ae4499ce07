"""docs/first-cut.md and docs/first-print.md: what the first hour needs, and enough to check.

Their commands, outputs and quoted figures run in tests/test_docs.py (tests/doc_pages.py runs
every page); here, that the parser still finds them, and the steps and words the pages must give.
"""

from __future__ import annotations

import re

import pytest
from doc_pages import BLOCK, ROOT, prose_figures, steps

PAGES = ["first-cut.md", "first-print.md"]


@pytest.mark.parametrize("page", PAGES)
def test_the_pages_have_commands_outputs_and_figures_to_check(page):
    """The parser still finds what it checks (a page rewritten in another layout fails here)."""
    found = [s for s in steps(ROOT / "docs" / page) if s.kind == "sh"]
    assert sum(len(s.commands) for s in found) >= 5
    assert sum(len(s.shown or ()) for s in found) >= 10
    assert len(prose_figures(ROOT / "docs" / page)) >= 2


def test_first_cut_gives_each_measured_key_and_each_step():
    text = (ROOT / "docs" / "first-cut.md").read_text(encoding="utf-8")
    for key in ("kerf_mm", "kerf_x_mm", "kerf_y_mm", "min_feature_mm", "min_hole_mm", "inlay_fit_mm"):
        assert f"`{key}`" in text, key
    for step in (
        "fabtiles profile copy laser-3mm-plywood my-laser.toml",
        "fabtiles calibrate --profile my-laser.toml",
        "laser-programs.md",
        "inlay.md",
    ):
        assert step in text, step


def test_first_print_names_each_style_and_slicer():
    text = (ROOT / "docs" / "first-print.md").read_text(encoding="utf-8")
    for word in (
        "fabtiles profile copy fdm-0.4mm",
        "`relief`",
        "`pierced`",
        "`deboss`",
        "PrusaSlicer",
        "Bambu Studio",
        "OrcaSlicer",
        "Cura",
        "slicers.md",
    ):
        assert word in text, word


def slug(heading: str) -> str:
    """A heading's anchor as GitHub makes it: lower case, punctuation dropped, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


@pytest.mark.parametrize("page", PAGES)
def test_the_pages_anchors_name_headings(page):
    """A link to a section (``page.md#section``) names a heading of that page."""
    text = (ROOT / "docs" / page).read_text(encoding="utf-8")
    broken = []
    for target, anchor in re.findall(r"\]\(([^)#\s]*)#([^)\s]+)\)", text):
        linked = (ROOT / "docs" / target) if target else ROOT / "docs" / page
        headings = re.findall(r"^#+ (.+)$", BLOCK.sub("", linked.read_text(encoding="utf-8")), re.M)
        if anchor not in {slug(h) for h in headings}:
            broken.append(f"{target}#{anchor}")
    assert broken == []
