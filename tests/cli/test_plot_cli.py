"""``fabtiles plot`` (issue 37): the pen's SVG and HPGL, one-line errors."""

from __future__ import annotations

import sys
from pathlib import Path

from click.testing import CliRunner

from fabtiles.cli.main import cli

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "table3-3.toml"


def run(*args):
    return CliRunner().invoke(cli, ["plot", *map(str, args)], catch_exceptions=False)


def test_svg_and_hpgl(tmp_path):
    res = run(SAMPLE, "-o", tmp_path / "t.svg", "--pen", 0.5)
    assert res.exit_code == 0, res.output
    assert "strands" in res.output and "pen up" in res.output
    text = (tmp_path / "t.svg").read_text()
    assert 'width="150mm"' in text and 'stroke-width="0.5"' in text and 'inkscape:label="strands"' in text
    res = run(SAMPLE, "-o", tmp_path / "t.hpgl")
    assert res.exit_code == 0, res.output
    assert (tmp_path / "t.hpgl").read_bytes().startswith(b"IN;")


def test_bad_output_and_bad_key(tmp_path):
    res = CliRunner().invoke(cli, ["plot", str(SAMPLE), "-o", str(tmp_path / "t.png")])
    assert res.exit_code == 2 and res.output.count("\n") == 1
    assert "must end in .svg or .hpgl" in res.output
    res = CliRunner().invoke(cli, ["plot", str(SAMPLE), "-o", str(tmp_path / "t.svg"), "--set", "tile.size=-1"])
    assert res.exit_code == 2 and "size must be" in res.output and not (tmp_path / "t.svg").exists()


def test_a_bad_pen_is_refused_naming_the_option(tmp_path):
    res = CliRunner().invoke(cli, ["plot", str(SAMPLE), "-o", str(tmp_path / "t.svg"), "--pen", "-1"])
    assert res.exit_code == 2 and res.output.count("\n") == 1, res.output
    assert "fabtiles: error: --pen must be a finite number > 0 and <= 10, got -1" in res.output
    assert not (tmp_path / "t.svg").exists()


def test_hpgl_without_vpype_says_how_to_install(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "vpype", None)  # import vpype fails as when it is not installed
    res = CliRunner().invoke(cli, ["plot", str(SAMPLE), "-o", str(tmp_path / "t.hpgl")])
    assert res.exit_code == 2
    assert "HPGL needs vpype, which is not installed: pip install 'fabtiles[vpype]'" in res.output
