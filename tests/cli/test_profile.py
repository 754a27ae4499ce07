"""``fabtiles profile list | show | copy``: the bundled profiles, and a copy to edit and pass by path."""

from pathlib import Path

import pytest
from click.testing import CliRunner

import fabtiles as ft
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import design_from_text, profile_of
from fabtiles.machines.profiles import bundled_profiles, kind_of

ROOT = Path(__file__).resolve().parents[2]


def run(*args):
    return CliRunner().invoke(cli, list(map(str, args)), catch_exceptions=False)


def test_list_groups_every_bundled_profile_by_kind_with_its_description():
    result = run("profile", "list")
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    heads = [line for line in lines if line.endswith(":") and not line.startswith(" ")]
    assert heads == ["laser:", "router:", "waterjet:", "printer:"]
    for name in bundled_profiles():
        (line,) = [line for line in lines if line.split()[:1] == [name]]
        assert ft.load_profile(name).description in line
        # listed under its kind's heading
        head = [h for h in lines[: lines.index(line)] if h in heads][-1]
        assert head == f"{kind_of(name)}:"
    assert "fabtiles profile copy NAME" in result.output


@pytest.mark.parametrize("name", ["fdm-0.4mm", "router-6mm-mdf"])
def test_show_prints_the_bundled_toml(name):
    result = run("profile", "show", name)
    assert result.exit_code == 0, result.output
    assert result.output == (ROOT / "profiles" / f"{name}.toml").read_text(encoding="utf-8")


def test_show_a_file_by_path_and_an_unknown_name(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text('kind = "printer"\n[printer]\nnozzle_mm = 0.6\n', encoding="utf-8")
    assert run("profile", "show", path).output == path.read_text(encoding="utf-8")
    result = run("profile", "show", "fdm-0.4")
    assert result.exit_code == 2
    assert "profile 'fdm-0.4' does not exist (did you mean 'fdm-0.4mm'?)" in result.output
    path.write_text('kind = "printer"\n[printer]\nnozle_mm = 0.6\n', encoding="utf-8")
    result = run("profile", "show", path)
    assert result.exit_code == 2 and "unknown key printer.'nozle_mm' (did you mean 'nozzle_mm'?)" in result.output


def test_copy_writes_a_profile_that_loads_and_says_how_to_use_it(tmp_path):
    path = tmp_path / "my-laser.toml"
    result = run("profile", "copy", "laser-3mm-plywood", path)
    assert result.exit_code == 0, result.output
    assert f"wrote {path}: a copy of laser profile laser-3mm-plywood" in result.output
    assert f'laser_profile = "{path.as_posix()}"' in result.output
    assert f"fabtiles calibrate --profile {path.as_posix()}" in result.output
    copy, original = ft.load_profile(path), ft.load_profile("laser-3mm-plywood")
    assert copy.name == "my-laser" and copy.kerf_mm == original.kerf_mm and copy.layers == original.layers
    assert (ROOT / "profiles" / "laser-3mm-plywood.toml").read_text(encoding="utf-8") in path.read_text()
    # the user edits the copy and a design uses it by path
    path.write_text(path.read_text().replace("kerf_mm = 0.15", "kerf_mm = 0.21"), encoding="utf-8")
    design = design_from_text(
        f'[motif]\npreset = "table3-1"\n[tile]\nsize = 40\n[output]\nlaser_profile = "{path.as_posix()}"\n'
    )
    assert profile_of(design, "laser").kerf_mm == pytest.approx(0.21)


def test_copy_of_a_printer_names_the_printer_key(tmp_path):
    result = run("profile", "copy", "fdm-0.6mm", tmp_path / "p.toml")
    assert result.exit_code == 0, result.output
    assert "printer_profile = " in result.output and "--set output.printer_profile=" in result.output
    assert "calibrate" not in result.output
    assert ft.load_profile(tmp_path / "p.toml").nozzle_mm == pytest.approx(0.6)


def test_copy_refuses_to_overwrite_unless_forced(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text("# my settings\n", encoding="utf-8")
    result = run("profile", "copy", "fdm-0.4mm", path)
    assert result.exit_code == 2
    assert f"fabtiles: error: {path} exists; pass --force to overwrite it" in result.output
    assert path.read_text() == "# my settings\n"
    result = run("profile", "copy", "fdm-0.4mm", path, "--force")
    assert result.exit_code == 0, result.output
    assert ft.load_profile(path).kind == "printer"


@pytest.mark.parametrize(
    "args, match",
    [
        (["laser-3mm-plywood", "{tmp}/my-laser"], "the copy must be a .toml file"),
        (
            ["laser-3mm-plywod", "{tmp}/x.toml"],
            "profile 'laser-3mm-plywod' does not exist (did you mean 'laser-3mm-plywood'?)",
        ),
        (["laser-3mm-plywood", "{tmp}/no-folder/x.toml/y.toml"], "cannot write"),
    ],
)
def test_copy_errors_write_nothing(tmp_path, args, match):
    (tmp_path / "no-folder").write_text("a file, not a folder")
    result = run("profile", "copy", *(a.format(tmp=tmp_path) for a in args))
    assert result.exit_code == 2 and match in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["no-folder"]
