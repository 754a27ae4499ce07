"""docs/first-cut.md and docs/first-print.md cannot drift: their commands run and print what they quote.

Every ``fabtiles ...`` line of the pages' ```sh blocks runs, in the page's order, in one temporary
folder (holding copies of the samples it names), and exits 0, or the status its comment gives
(``# exits 1``). Every line of the plain ``` block right after a ```sh block appears in what that
block's commands printed (stdout and stderr), and every figure the page's prose quotes from an
output (`about 9 min`, `73 g of filament`, ...) appears in what one of its commands printed.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = ["first-cut.md", "first-print.md"]

BLOCK = re.compile(r"^```(\w*)\n(.*?)^```\n", re.M | re.S)
# A figure quoted from a command's output: a job time, a length of cut, pierces, filament, a
# count of holes, a card's size.
FIGURE = re.compile(r"about \d+ min|[\d.,]+ m of cut|[\d,]+ pierces|[\d.]+ g of filament"
                    r"|[\d,]+ (?:small )?holes|\d+ x \d+ mm")


def steps(page: str) -> list[tuple[list[tuple[list[str], int]], list[str]]]:
    """The page's ```sh blocks in order: each block's commands (argv, expected exit status) and
    the lines of the plain ``` block that follows it (none if there is none)."""
    text = (ROOT / "docs" / page).read_text(encoding="utf-8")
    blocks = [(m.group(1), m.group(2), m.end()) for m in BLOCK.finditer(text)]
    out = []
    for i, (lang, body, end) in enumerate(blocks):
        if lang != "sh":
            continue
        cmds = []
        for line in body.replace("\\\n", " ").splitlines():
            comment = line.partition("#")[2]
            exits = re.search(r"exits (\d)", comment)
            argv = shlex.split(line, comments=True)
            if argv and argv[0] == "fabtiles":
                cmds.append((argv[1:], int(exits.group(1)) if exits else 0))
        following = blocks[i + 1] if i + 1 < len(blocks) else None
        shown = []
        if following and following[0] == "" and text[end:following[2]].lstrip().startswith("```\n"):
            shown = [ln.strip() for ln in following[1].splitlines() if ln.strip()]
        out.append((cmds, shown))
    return out


def prose_figures(page: str) -> list[str]:
    """The figures quoted in backticks outside the code blocks."""
    text = BLOCK.sub("", (ROOT / "docs" / page).read_text(encoding="utf-8"))
    return [span for span in re.findall(r"`([^`\n]+)`", text) if FIGURE.search(span)]


def run(argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
    for arg in argv:  # copy the samples the command names
        if arg.startswith("samples/") and (ROOT / arg).is_file():
            (cwd / arg).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(ROOT / arg, cwd / arg)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "fabtiles", *argv], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("page", PAGES)
def test_the_pages_commands_run_and_print_what_the_page_says(page, tmp_path):
    outputs = []
    for cmds, shown in steps(page):
        printed = ""
        for argv, status in cmds:
            done = run(argv, tmp_path)
            assert done.returncode == status, (argv, done.stdout, done.stderr)
            printed += done.stdout + done.stderr
        lines = {ln.strip() for ln in printed.splitlines()}
        assert [ln for ln in shown if ln not in lines] == [], printed
        outputs.append(printed)
    everything = "\n".join(outputs)
    assert [f for f in prose_figures(page) if f not in everything] == []


@pytest.mark.parametrize("page", PAGES)
def test_the_pages_have_commands_outputs_and_figures_to_check(page):
    """The parser still finds what it checks (a page rewritten in another layout fails here)."""
    found = steps(page)
    assert sum(len(cmds) for cmds, _ in found) >= 5
    assert sum(len(shown) for _, shown in found) >= 10
    assert len(prose_figures(page)) >= 2


def test_first_cut_gives_each_measured_key_and_each_step():
    text = (ROOT / "docs" / "first-cut.md").read_text(encoding="utf-8")
    for key in ("kerf_mm", "kerf_x_mm", "kerf_y_mm", "min_feature_mm", "min_hole_mm", "inlay_fit_mm"):
        assert f"`{key}`" in text, key
    for step in ("fabtiles profile copy laser-3mm-plywood my-laser.toml",
                 "fabtiles calibrate --profile my-laser.toml", "laser-programs.md", "inlay.md"):
        assert step in text, step


def test_first_print_names_each_style_and_slicer():
    text = (ROOT / "docs" / "first-print.md").read_text(encoding="utf-8")
    for word in ("fabtiles profile copy fdm-0.4mm", "`relief`", "`pierced`", "`deboss`",
                 "PrusaSlicer", "Bambu Studio", "OrcaSlicer", "Cura", "slicers.md"):
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
