"""The manual cannot drift from the code: every key, command and option documented, every link alive."""

from __future__ import annotations

import re
from dataclasses import fields
from pathlib import Path

import click
import numpy as np
import pytest

from fabtiles.machines import profiles as _profiles
from fabtiles.designs import design_file as design
from fabtiles.cli.main import cli

ROOT = Path(__file__).resolve().parents[1]
DOCS = sorted((ROOT / "docs").glob("*.md"))
PAGES = [ROOT / "README.md", *DOCS]


def text_of(*names) -> str:
    return "\n".join((ROOT / "docs" / n).read_text(encoding="utf-8") for n in names)


def documented(key: str, text: str) -> bool:
    """``key`` appears as code (`key`) or as a TOML key (``key =``) in ``text``."""
    k = re.escape(key)
    return bool(re.search(rf"`{k}`|^\s*{k}\s*=|[{{,]\s*{k}\s*=|^\[{k}\]", text, re.M))


@pytest.mark.parametrize("section,keys", [
    ("motif", design.MOTIF_KEYS), ("packing", design.PACKING_KEYS), ("tile", design.TILE_KEYS),
    ("output", design.OUTPUT_KEYS)])
def test_every_design_key_is_in_design_files_md(section, keys):
    text = text_of("design-files.md")
    assert f"[{section}]" in text
    assert [k for k in keys if not documented(k, text)] == []


def profile_keys() -> list[str]:
    keys = ["kind", "description", "laser", "printer", "layers", "name", "color"]
    for cls in (_profiles.CutterProfile, _profiles.PrinterProfile, _profiles.LaserLayers):
        keys += [f.name for f in fields(cls) if f.name not in ("name", "description", "layers")]
    return list(dict.fromkeys(keys))


def test_every_profile_key_is_in_profiles_md():
    text = text_of("profiles.md")
    assert [k for k in profile_keys() if not documented(k, text)] == []


def commands(group, prefix=()):
    for name, cmd in sorted(group.commands.items()):
        yield (*prefix, name), cmd
        if hasattr(cmd, "commands"):
            yield from commands(cmd, (*prefix, name))


def test_every_cli_command_and_option_is_in_cli_md():
    text = text_of("cli.md")
    sections = dict(re.findall(r"^## `fabtiles ([a-z -]+)`\n(.*?)(?=^## |\Z)", text, re.M | re.S))
    missing = []
    for path, cmd in commands(cli):
        name = " ".join(path)
        if name not in sections:
            missing.append(name)
            continue
        for param in cmd.params:
            for opt in param.opts if isinstance(param, click.Option) else ():
                if opt != "--help" and f"`{opt}`" not in sections[name]:
                    missing.append(f"{name} {opt}")
    assert missing == []


LINK = re.compile(r"\]\(([^)\s]+)\)")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_relative_link_points_to_a_file(page):
    broken = []
    for target in LINK.findall(page.read_text(encoding="utf-8")):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        if not (page.parent / target.split("#")[0]).exists():
            broken.append(target)
    assert broken == []


def test_the_readme_is_a_landing_page():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme.encode()) <= 15_000
    ci = (ROOT / ".ci" / "run").read_text()
    test_command = ci.split("# --- the README's test command (keep the two in step) ---\n", 1)[1].strip()
    assert test_command in readme  # the README's test command is CI's
    assert "fabtiles build samples/table3-3.toml -o out" in readme


def test_the_card_size_in_laser_cutting_md_is_the_cards():
    """The calibration card's size, as the docs state it, is the bundled laser profiles' cards' (to the mm)."""
    from fabtiles.geometry.calibration import calibration_card

    m = re.search(r"The card \(about (\d+) x (\d+) mm for the bundled profiles", text_of("laser-cutting.md"))
    assert m, "laser-cutting.md no longer states the card's size"
    stated = np.array([float(m.group(1)), float(m.group(2))])
    for name in _profiles.bundled_profiles("laser"):
        profile = _profiles.load_profile(name)
        if profile.cutter.card:
            card = calibration_card(profile)
            assert np.abs(np.array([card.width_mm, card.height_mm]) - stated).max() <= 1.0, name


def test_design_files_md_example_names_every_output_key():
    """The example design of design-files.md shows every [output] key of the schema (the inlay ones too)."""
    from fabtiles.core import schema as _schema

    text = text_of("design-files.md")
    example = text[text.index("[output]"):text.index("```", text.index("[output]"))]
    keys = [k.name for k in _schema.KEYS if k.section == "output"]
    assert keys and [k for k in keys if not re.search(rf"^{k} = ", example, re.M)] == []


def test_a_copy_of_a_profile_comes_with_the_command_that_makes_it():
    """Wherever the manual says to write values into a copy of a profile, it gives `fabtiles profile copy`."""
    missing = []
    for page in PAGES:
        text = " ".join(page.read_text(encoding="utf-8").split())
        for m in re.finditer(r"copy of (the|a|your) profile", text, re.I):
            if "fabtiles profile copy" not in text[m.start():m.end() + 200]:
                missing.append(f"{page.name}: {text[m.start():m.end() + 60]}")
    assert missing == []
    assert "fabtiles profile copy laser-3mm-plywood my-laser.toml" in text_of("profiles.md")


def test_the_readme_tour_prints_the_figures_it_quotes(tmp_path, monkeypatch, capsys):
    """The README's Python tour runs as shown (in an empty folder), and what its ``print`` lines print
    holds the figures their comments quote (the laser job of the default export, its small holes
    filled)."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    tour = readme[readme.index("## A tour"):]
    block = tour[tour.index("```python\n") + len("```python\n"):]
    block = block[:block.index("```")]
    quoted = [q for line in block.splitlines() if line.lstrip().startswith("print(") and "#" in line
              for q in re.findall(r'"([^"]+)"', line.split("#", 1)[1])]
    assert quoted, "the tour's print lines quote no figures"
    monkeypatch.chdir(tmp_path)
    exec(compile(block, "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert [q for q in quoted if q not in printed] == [], printed
