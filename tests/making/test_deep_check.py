"""``fabtiles check --deep`` (fabtiles/making/deep.py): the print files read back by OCCT and trimesh."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner
from designs import design_toml

from fabtiles import FabricationError
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import design_from_text
from fabtiles.export.formats import FORMATS
from fabtiles.export.stl import stl_bytes
from fabtiles.making.deep import ReadBack, read_back

SMALL = design_toml(
    preset="table3-1", radius=8, size=40, output={"formats": ["dxf", "stl", "3mf", "step"], "fill_small_holes": False}
)
# fill_small_holes = false: the holes kept (the filled case is its own test below)


def test_check_deep_reads_every_print_file_back(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    result = CliRunner().invoke(cli, ["check", str(path), "--deep"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    lines = [line.strip() for line in result.output.splitlines() if " read back by " in line]
    assert [line.split(" read back by ")[0] for line in lines] == ["stl", "3mf", "step"]
    assert lines[2].startswith("step read back by OCCT: 1 solid, ")
    volumes = {float(line.split(", ")[1].split(" mm^3")[0].replace(",", "")) for line in lines}
    assert len(volumes) == 1  # the three files hold the same print
    assert list(tmp_path.iterdir()) == [path]  # nothing left behind


def test_the_deep_check_reads_the_formats_the_design_names():
    design = design_from_text(SMALL.replace('"stl", "3mf", "step"', '"step"'), name="s")
    (back,) = read_back(design)
    assert back.fmt == "step" and back.reader == "OCCT" and back.bodies == 1 and back.volume_mm3 > 1000
    laser_only = design_from_text(SMALL.replace(', "stl", "3mf", "step"', ""), name="s")
    assert [b.fmt for b in read_back(laser_only)] == ["stl", "3mf", "step"]


def _tetrahedron(flip=False, drop=False):
    v = np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]], float)
    f = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    f = [t[::-1] for t in f] if flip else f
    return stl_bytes(v, f[:-1] if drop else f)


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(drop=True), r"the STL file read back by trimesh has a body that is not watertight"),
        (dict(flip=True), r"the STL file read back by trimesh has a body turned inside out"),
        (
            dict(),
            r"the STL file read back by trimesh holds 166\.667 mm\^3, not the [0-9.e+]+ mm\^3 it was written with",
        ),
    ],
)
def test_a_mesh_file_the_reader_disagrees_with_is_a_bug_reported(monkeypatch, kw, match):
    monkeypatch.setitem(FORMATS, "stl", replace(FORMATS["stl"], write=lambda model, options: _tetrahedron(**kw)))
    design = design_from_text(SMALL.replace('"stl", "3mf", "step"', '"stl"'), name="s")
    with pytest.raises(FabricationError, match=r"^the deep check found a file the writer's checks passed: " + match):
        read_back(design)


def test_a_step_file_occt_cannot_read_is_a_bug_reported(monkeypatch):
    monkeypatch.setitem(FORMATS, "step", replace(FORMATS["step"], write=lambda model, options: b"ISO-10303-21;\n"))
    design = design_from_text(SMALL.replace('"stl", "3mf", "step"', '"step"'), name="s")
    with pytest.raises(FabricationError, match=r"cannot read back the STEP file .*\(a bug in fabtiles, please report"):
        read_back(design)


def test_a_read_back_line_says_what_was_read():
    assert (
        ReadBack("3mf", "trimesh", 2, 1000.0).line() == "3mf read back by trimesh: 2 meshes, 1,000.0 mm^3, as written"
    )


def test_a_relief_whose_pattern_meets_the_outline_reads_back_part_by_part():
    """Filled, the pattern's outer ring is the outline's: the 3MF's plate and pattern meet along it in
    edges of four faces, and each part must be checked on its own."""
    design = design_from_text(
        SMALL.replace('"stl", "3mf", "step"', '"3mf"').replace("fill_small_holes = false", "")
        + 'fill_small_holes = true\nprint_style = "relief"\n',
        name="s",
    )
    (back,) = read_back(design)
    assert back.fmt == "3mf" and back.bodies == 2
