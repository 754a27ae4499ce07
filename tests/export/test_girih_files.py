"""A girih design's files: a clean DXF that LibreCAD draws, a watertight STL that PrusaSlicer slices."""

from __future__ import annotations

import re

import ezdxf
import pytest
from mesh_helpers import assert_relief_stl
from test_3mf_multicolour import slice_gcode
from test_dxf_librecad import drawn_and_cut_edges

import fabtiles
from fabtiles.designs.design_file import design_from_text
from fabtiles.pattern.girih import PATTERNS

DESIGN = """
[packing]
kind = "girih"
girih_pattern = "{pattern}"
girih_level = {level}
edge = {edge}
[tile]
outline = "square"
size = 50
frame = 3
stroke = 1.2
"""


def _tile(pattern="decagon-bowtie", level=0):
    edge = 9 if level == 0 else 7.5  # stroke 1.2 takes an edge of 7.2 mm at least
    return design_from_text(DESIGN.format(pattern=pattern, level=level, edge=edge)).build_tile(tile_cls=fabtiles.Tile)


@pytest.mark.parametrize(("pattern", "level"), [(p, 0) for p in PATTERNS] + [("decagon-bowtie", 2)])
def test_girih_dxf_audits_clean(pattern, level, tmp_path):
    tile = _tile(pattern, level)
    report = tile.export(tmp_path / "t.dxf", profile="laser-3mm-plywood", fill_small_holes=True)
    assert report.ok, report.summary()
    doc = ezdxf.readfile(tmp_path / "t.dxf")
    assert not doc.audit().has_errors and len(doc.modelspace()) > 10


@pytest.mark.parametrize("level", [0, 2])
def test_girih_stl_is_watertight(level, tmp_path):
    assert_relief_stl(_tile(level=level), tmp_path / "t.stl")


def test_librecad_draws_the_girih_dxf(tmp_path):
    dxf = tmp_path / "girih.dxf"
    _tile().export(dxf, profile="laser-3mm-plywood", fill_small_holes=True)
    drawn, edges = drawn_and_cut_edges(dxf, tmp_path)
    assert drawn == edges > 50


def test_prusaslicer_slices_the_girih_stl(tmp_path):
    stl = tmp_path / "girih.stl"
    _tile().export(stl, profile="fdm-0.4mm", style="relief", fill_small_holes=False)
    gcode = slice_gcode(tmp_path, stl, 1)
    layers = re.findall(r"^;LAYER_CHANGE", gcode, flags=re.M)
    assert len(layers) > 5 and re.search(r"^G1 X[\d.]+ Y[\d.]+ E[\d.]+", gcode, flags=re.M)
