"""A bordered design's files: a clean DXF that LibreCAD draws, a watertight STL; the CLI's refusals."""

from __future__ import annotations

import ezdxf
from click.testing import CliRunner
from mesh_helpers import assert_relief_stl
from test_dxf_librecad import drawn_and_cut_edges

import fabtiles
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import design_from_text, design_notes

DESIGN = """
[motif]
preset = "table3-3"
[packing]
radius = 8
[tile]
outline = "square"
size = 60
frame = 2
stroke = 1
border_mm = 8
border_motif = "{motif}"
"""


def _tile(motif="hankin"):
    return design_from_text(DESIGN.format(motif=motif)).build_tile(tile_cls=fabtiles.Tile)


def test_the_build_reports_the_fit():
    notes = design_notes(design_from_text(DESIGN.format(motif="hankin")))
    assert notes == [
        "tile.border_mm: 5 x 5 repeats of 8 x 8 mm, a 8 mm square cell at each corner "
        "(band 8 mm, hankin at 67.5 degrees)"
    ]


def test_a_bordered_dxf_audits_clean(tmp_path):
    tile = _tile("stars")
    report = tile.export(tmp_path / "t.dxf", profile="laser-3mm-plywood", fill_small_holes=True)
    assert report.ok, report.summary()
    doc = ezdxf.readfile(tmp_path / "t.dxf")
    assert not doc.audit().has_errors and len(doc.modelspace()) > 50


def test_a_bordered_stl_is_watertight(tmp_path):
    assert_relief_stl(_tile(), tmp_path / "t.stl")


def test_librecad_draws_the_bordered_dxf(tmp_path):
    dxf = tmp_path / "border.dxf"
    _tile().export(dxf, profile="laser-3mm-plywood", fill_small_holes=True)
    drawn, edges = drawn_and_cut_edges(dxf, tmp_path)
    assert drawn == edges > 50


def test_the_cli_refuses_a_bad_border_with_exit_2_and_no_file(tmp_path):
    design = tmp_path / "b.toml"
    design.write_text(DESIGN.format(motif="hankin"))
    for setting, words in (
        ("tile.border_mm=30", "border_mm must be >= 0 and <= 18.67 mm"),
        ("tile.border_mm=2", "border_mm must be >= "),
        ("tile.border_motif=hankn", "did you mean 'hankin'?"),
    ):
        result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out"), "--set", setting])
        assert result.exit_code == 2, result.output
        assert words in result.output and len(result.output.strip().splitlines()) == 1
        assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())
