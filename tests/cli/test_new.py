"""``fabtiles new NAME.toml``: a commented starter design that builds as written, and its refusals."""

from __future__ import annotations

import re

import pytest
from click.testing import CliRunner

from fabtiles.cli.main import cli
from fabtiles.designs.design_file import load_design


def run(*args):
    return CliRunner().invoke(cli, list(map(str, args)))


def test_the_starter_builds_as_written_with_no_warning(tmp_path):
    design = tmp_path / "my-tile.toml"
    result = run("new", design)
    assert result.exit_code == 0, result.output
    assert result.output == f"wrote {design}: build it with fabtiles build {design} -o out/\n"
    text = design.read_text()
    for section in ("[motif]", "[packing]", "[tile]", "[output]", "laser_profile", "printer_profile", "# [colour]"):
        assert section in text
    result = run("build", design, "-o", tmp_path / "out")
    assert result.exit_code == 0, result.output
    assert result.stderr == "" and "warning" not in result.output and "- " not in result.output
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["my-tile.3mf", "my-tile.dxf", "my-tile.svg"]


def test_the_starters_colour_section_builds_once_uncommented(tmp_path):
    design = tmp_path / "c.toml"
    run("new", design)
    text = re.sub(r"^# (?=\[colour|by |palette |A )", "", design.read_text(), flags=re.MULTILINE)
    text = text.replace('# print_style = "mosaic"', 'print_style = "mosaic"')
    design.write_text(text)
    d = load_design(design)
    assert d.colour.given and d.colour.palette == "iznik" and d.output.print_style == "mosaic"
    result = run("check", design)
    assert result.exit_code == 0, result.output
    assert "face class A: " in result.output and ", cobalt" in result.output


def test_an_existing_file_is_kept_unless_force(tmp_path):
    design = tmp_path / "t.toml"
    design.write_text("mine")
    result = run("new", design)
    assert result.exit_code == 2 and result.output.count("\n") == 1
    assert f"{design} exists; give another name, or --force to replace it" in result.output
    assert design.read_text() == "mine"
    result = run("new", design, "--force")
    assert result.exit_code == 0 and result.output.startswith(f"replaced {design}")
    assert "[motif]" in design.read_text()


@pytest.mark.parametrize(
    "name, match",
    [
        ("t.txt", "the design must be a .toml file, got '{tmp}/t.txt'"),
        ("missing/t.toml", "the folder '{tmp}/missing' of '{tmp}/missing/t.toml' does not exist"),
        ("d.toml", "'{tmp}/d.toml' is a folder; give the design's file name"),
    ],
)
def test_a_bad_path_is_one_line_exit_2(tmp_path, name, match):
    (tmp_path / "d.toml").mkdir()
    result = run("new", f"{tmp_path}/{name}")
    assert result.exit_code == 2 and result.output.count("\n") == 1, result.output
    assert match.format(tmp=tmp_path) in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.toml"]
