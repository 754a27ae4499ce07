"""A design made as a clay stamp end to end: its face mirrored on the block in the STL and 3MF, the check, and
its bad values refused before any file (CLI exit 2)."""

from __future__ import annotations

from pathlib import Path

import pytest
import shapely
import trimesh
from click.testing import CliRunner
from mesh_helpers import load_3mf_parts, section_region

from fabtiles.cli.main import cli
from fabtiles.designs.design_file import design_from_text
from fabtiles.geometry.mirror import mirrored
from fabtiles.making.pipeline import prepare_tile

ROOT = Path(__file__).resolve().parents[2]

STAMP = """
[motif]
preset = "table3-1"
rotation = 10
[packing]
radius = 10
[tile]
outline = "hexagon"
size = 40
frame = 2
stroke = 1.6
[surface]
shape = "stamp"
block_mm = 16
[output]
formats = ["stl", "3mf"]
print_style = "relief"
"""
"""A small stamp: a 40 mm hexagon of table3-1 stars, on a 16 mm block; the stars turned 10 degrees, so the
pattern is not its own mirror image."""


def _cli(*args):
    return CliRunner().invoke(cli, [str(a) for a in args], catch_exceptions=False)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The stamp's design file and its build's folder (STL and 3MF)."""
    folder = tmp_path_factory.mktemp("stamp")
    path = folder / "stamp.toml"
    path.write_text(STAMP)
    result = _cli("build", path, "-o", folder / "out")
    assert result.exit_code == 0, result.output
    return path, folder / "out", result.output


def _face(mesh: trimesh.Trimesh) -> shapely.Geometry:
    """The relief's section just under its top (mm, as a shapely region)."""
    return section_region(mesh, mesh.bounds[1][2] - 0.3)


def test_the_build_says_what_it_made(built):
    _path, out, output = built
    assert sorted(p.name for p in out.iterdir()) == ["stamp.3mf", "stamp.stl"]
    assert "stamp's face mirrored: its imprint reads as designed" in output
    assert "clay stamp: a block 16 mm high with a finger groove 3 mm deep" in output


def test_the_stl_is_one_watertight_stamp_whose_face_is_the_mirrored_pattern(built):
    _path, out, _ = built
    mesh = trimesh.load(out / "stamp.stl")
    assert mesh.is_watertight and mesh.body_count == 1
    assert mesh.bounds[1][2] == pytest.approx(16 + 2.0 + 1.2, abs=0.01)  # block, the profile's plate and relief
    tile = prepare_tile(design_from_text(STAMP, name="stamp"))
    region, outline = tile.region(), tile.outline_shape()
    face = _face(mesh)
    as_drawn = shapely.symmetric_difference(face, region).area
    as_mirrored = shapely.symmetric_difference(face, mirrored(region, outline)).area
    assert as_mirrored < 0.05 * region.area  # the small openings filled: a few per cent
    assert as_drawn > 0.2 * region.area  # the pattern is not its own mirror image


def test_mirror_false_keeps_the_face_as_drawn(tmp_path):
    path = tmp_path / "plain.toml"
    path.write_text(STAMP.replace("block_mm = 16", "block_mm = 16\nmirror = false").replace('"3mf"', '"3mf"'))
    result = _cli("build", path, "-o", tmp_path / "out", "--format", "stl")
    assert result.exit_code == 0, result.output
    assert "mirrored" not in result.output
    tile = prepare_tile(design_from_text(STAMP, name="stamp"))
    region, outline = tile.region(), tile.outline_shape()
    face = _face(trimesh.load(tmp_path / "out" / "plain.stl"))
    assert shapely.symmetric_difference(face, region).area < 0.05 * region.area
    assert shapely.symmetric_difference(face, mirrored(region, outline)).area > 0.2 * region.area


def test_the_3mf_holds_the_block_and_the_pattern(built):
    _path, out, _ = built
    parts = load_3mf_parts(out / "stamp.3mf")
    assert sorted(parts) == ["block", "pattern"]
    assert all(p.is_watertight and p.body_count >= 1 for p in parts.values())
    assert parts["pattern"].bounds[0][2] == pytest.approx(parts["block"].bounds[1][2], abs=1e-3)  # on the plate


def test_the_check_names_the_printer_and_the_stamp(built):
    path, _out, _ = built
    result = _cli("check", path)
    assert result.exit_code == 0, result.output
    first = result.output.splitlines()[0]
    assert first.endswith("printer profile fdm-0.4mm") and "laser" not in first
    assert "clay stamp: a block 16 mm high" in result.output


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (("--format", "dxf"), '[surface] shape = "stamp" is printed, not cut: formats dxf make none of it'),
        (("--set", "output.print_style=pierced"), "print_style = 'pierced' does not make a clay stamp"),
        (("--set", "surface.grip_mm=12"), "block_mm must be at least"),
        (("--sheet",), '[surface] shape = "stamp" is printed whole, pattern up'),
        (("--set", "tile.outline=circle", "--set", "surface.diameter=50"), 'diameter is a key of shape = "cylinder"'),
    ],
)
def test_a_stamp_it_cannot_make_is_refused_in_one_line_with_no_file(tmp_path, args, says):
    path = tmp_path / "stamp.toml"
    path.write_text(STAMP)
    result = _cli("build", path, "-o", tmp_path / "out", *args)
    assert result.exit_code == 2, result.output
    assert says in result.output and len(result.output.strip().splitlines()) == 1
    assert not (tmp_path / "out").exists()


def test_the_sample_stamp_builds(tmp_path):
    result = _cli("build", ROOT / "samples" / "stamp-60.toml", "-o", tmp_path, "--format", "stl")
    assert result.exit_code == 0, result.output
    mesh = trimesh.load(tmp_path / "stamp-60.stl")
    assert mesh.is_watertight and mesh.body_count == 1
