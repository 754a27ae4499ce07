"""``fabtiles build D.toml -o tile.dxf``: an output named with a format's suffix is that one file."""

from __future__ import annotations

import pytest
from test_build import SMALL, run


@pytest.fixture
def design(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL, encoding="utf-8")
    return path


@pytest.mark.parametrize(
    "name, magic",
    [("tile.dxf", b"  0\nSECTION"), ("tile.SVG", b"<?xml"), ("tile.Stl", b"fabtiles"), ("tile.3mf", b"PK")],
)
def test_output_file_is_written_in_its_format(design, tmp_path, name, magic):
    out = tmp_path / "sub" / name
    result = run("build", design, "-o", out)
    assert result.exit_code == 0, result.output
    assert out.is_file() and out.read_bytes().startswith(magic)
    assert sorted(p.name for p in out.parent.iterdir()) == [name]  # no staging left over
    assert f"wrote {out}" in result.output


def test_output_file_replaces_an_existing_file(design, tmp_path):
    out = tmp_path / "tile.dxf"
    out.write_text("old")
    result = run("build", design, "-o", out, "--format", "dxf")  # the same format: fine
    assert result.exit_code == 0, result.output
    assert out.read_text().startswith("  0\nSECTION")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["small.toml", "tile.dxf"]


def test_sheet_to_one_file(design, tmp_path):
    import ezdxf

    out = tmp_path / "sheet.dxf"
    result = run("build", design, "-o", out, "--copies", 3)
    assert result.exit_code == 0, result.output
    assert sum(e.dxf.layer == "OUTER" for e in ezdxf.readfile(out).modelspace()) == 3


@pytest.mark.parametrize(
    "formats, match",
    [
        (["--format", "svg"], r"-o .*tile\.dxf writes one \.dxf file, but --format asks for svg"),
        (["--format", "dxf", "--format", "svg"], r"--format asks for dxf, svg"),
    ],
)
def test_output_file_with_other_formats_is_an_error(design, tmp_path, formats, match):
    import re

    out = tmp_path / "tile.dxf"
    result = run("build", design, "-o", out, *formats)
    assert result.exit_code == 2
    assert re.search(match, result.output), result.output
    assert not out.exists()


def test_failing_output_file_writes_nothing(design, tmp_path):
    out = tmp_path / "new" / "tile.dxf"
    result = run("build", design, "-o", out, "--set", "tile.stroke=50")
    assert result.exit_code == 2 and "stroke must be" in result.output
    assert not (tmp_path / "new").exists()


def test_print_file_as_sheet_is_an_error(design, tmp_path):
    out = tmp_path / "tile.stl"
    result = run("build", design, "-o", out, "--sheet")
    assert result.exit_code == 2 and "a sheet is laid out for the laser formats" in result.output
    assert not out.exists()


def test_unknown_suffix_is_a_folder(design, tmp_path):
    out = tmp_path / "tiles.v2"
    result = run("build", design, "-o", out)
    assert result.exit_code == 0, result.output
    assert (out / "small.svg").is_file()


@pytest.mark.parametrize("name", ["tile.png", "t.PDF", "tile.gcode", "tile.stp"])
def test_a_file_type_fabtiles_does_not_write_is_an_error(design, tmp_path, name):
    out = tmp_path / name
    result = run("build", design, "-o", out)
    assert result.exit_code == 2 and result.output.count("\n") == 1, result.output
    suffix = name.rsplit(".", 1)[1]
    assert (
        f"fabtiles does not write .{suffix.lower()} files; name the file with a format's suffix (.dxf, .svg, "
        f".lbrn2, .stl, .3mf, .step) or give a folder" in result.output
    )
    assert list(tmp_path.iterdir()) == [design]


def test_an_existing_folder_or_a_trailing_slash_is_a_folder_whatever_its_suffix(design, tmp_path):
    (tmp_path / "pics.png").mkdir()
    assert run("build", design, "-o", tmp_path / "pics.png").exit_code == 0
    assert (tmp_path / "pics.png" / "small.svg").is_file()
    result = run("build", design, "-o", f"{tmp_path / 'new.png'}/")
    assert result.exit_code == 0, result.output
    assert (tmp_path / "new.png" / "small.svg").is_file()
