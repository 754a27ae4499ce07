"""The CLI and the Archimedean tilings: presets lists them, build makes them, bad input exits 2."""

import pytest
from click.testing import CliRunner

from fabtiles.cli.main import cli
from fabtiles.pattern.tilings import TILINGS

DESIGN = """
[packing]
kind = "archimedean"
tiling = "3.4.6.4"
edge = 8

[packing.motifs]
6 = "table3-3"

[tile]
outline = "square"
size = 50
frame = 2
stroke = 1.0
"""


def run(*args):
    return CliRunner().invoke(cli, list(map(str, args)), catch_exceptions=False)


def test_presets_lists_the_tilings():
    res = run("presets")
    assert res.exit_code == 0
    for name in TILINGS:
        assert f"\n{name} " in res.output
    assert "snub hexagonal" in res.output and "polygons 3,4,6" in res.output


def test_build_an_archimedean_design(tmp_path):
    path = tmp_path / "t.toml"
    path.write_text(DESIGN, encoding="utf-8")
    res = run("build", path, "-o", tmp_path / "out")
    assert res.exit_code == 0, res.output
    assert (tmp_path / "out" / "t.svg").stat().st_size > 1000


@pytest.mark.parametrize(
    "override, match",
    [
        (
            'packing.tiling="3.3.3"',
            "[packing] tiling '3.3.3' is unknown; did you mean '3.3.4.3.4'? (tilings: 3.3.3.3.3.3, 4.4.4.4",
        ),
        ("packing.edge=-1", "edge must be a finite number > 0, got -1"),
        ("packing.motifs.8=table3-3", "motifs key 8 is not a polygon of the tiling 3.4.6.4, must be one of: 3, 4, 6"),
        ("packing.edge=0.05", "stroke must be > 0 and <= 0.0144338 mm (the packing radius), got 1"),
    ],
)
def test_bad_tiling_input_exits_2_and_writes_nothing(tmp_path, override, match):
    path = tmp_path / "t.toml"
    path.write_text(DESIGN, encoding="utf-8")
    out = tmp_path / "out"
    res = run("build", path, "-o", out, "--set", override)
    assert res.exit_code == 2
    assert res.output.startswith("fabtiles: error: ") and res.output.count("\n") == 1
    assert match in res.output
    assert not out.exists()


def test_too_many_circles_exits_2(tmp_path):
    path = tmp_path / "t.toml"
    path.write_text(DESIGN, encoding="utf-8")
    res = run("build", path, "-o", tmp_path / "out", "--set", "packing.edge=4", "--set", "tile.size=2500")
    assert res.exit_code == 2 and "more than the limit of 400,000" in res.output
    assert not (tmp_path / "out").exists()


def test_bare_tiling_names_in_set_and_vary(tmp_path):
    path = tmp_path / "t.toml"
    path.write_text(DESIGN, encoding="utf-8")
    res = run("build", path, "-o", tmp_path / "out", "--set", "packing.tiling=3^4.6")
    assert res.exit_code == 0, res.output
    res = run("sweep", path, "--vary", "packing.tiling=3.6.3.6,6^3", "-o", tmp_path / "sweep")
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in (tmp_path / "sweep").glob("t-00?.svg")) == ["t-001.svg", "t-002.svg"]
