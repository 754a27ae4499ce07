"""Hankin designs (``samples/hankin/*.toml``) into every output, as the paper's motifs go.

Each tiling's sample cuts cleanly (its DXF has no findings under the 3 mm plywood profile)
and prints as one watertight body; one design goes through every laser mode, the router,
every print style, interlace and the colour classes; LibreCAD draws its DXF and
PrusaSlicer slices its four-colour 3MF.
"""

from __future__ import annotations

import re
from pathlib import Path

import ezdxf
import pytest
from mesh_helpers import assert_relief_stl, expected_volume
from test_3mf_multicolour import extrusions_by_tool, slice_gcode
from test_dxf_librecad import drawn_and_cut_edges
from test_tiling_samples import SAMPLES as TILING_SAMPLES

import fabtiles
from fabtiles.designs.design_file import load_design
from fabtiles.making import build_design
from fabtiles.pattern.tilings import TILINGS

SAMPLES = Path(__file__).resolve().parents[2] / "samples" / "hankin"
SAMPLE = SAMPLES / "4.8.8.toml"


def test_one_hankin_sample_per_tiling():
    assert sorted(p.stem for p in SAMPLES.glob("*.toml")) == sorted(TILINGS)
    assert {p.stem for p in TILING_SAMPLES.glob("*.toml")} == {p.stem for p in SAMPLES.glob("*.toml")}


def _tile(tiling):
    design = load_design(SAMPLES / f"{tiling}.toml")
    assert design.packing.method == "hankin" and design.packing.tiling == tiling
    return design, design.build_tile(tile_cls=fabtiles.Tile)


@pytest.mark.parametrize("tiling", TILINGS)
def test_hankin_sample_dxf_is_clean(tiling, tmp_path):
    design, tile = _tile(tiling)
    report = tile.export(tmp_path / "t.dxf", profile=design.output.laser_profile, fill_small_holes=True)
    assert report.ok, report.summary()
    doc = ezdxf.readfile(tmp_path / "t.dxf")
    assert not doc.audit().has_errors and len(doc.modelspace()) > 50


@pytest.mark.parametrize("tiling", ["4.8.8", "6.6.6", "3.3.4.3.4"])
def test_hankin_sample_stl_is_watertight(tiling, tmp_path):
    design, tile = _tile(tiling)
    assert_relief_stl(tile, tmp_path / "t.stl", design.output.printer_profile)


def test_hankin_renders_are_reproducible(tmp_path):
    import importlib.util

    spec = importlib.util.spec_from_file_location("render_samples", SAMPLES.parent / "render.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for tiling in ("4.8.8", "6.6.6"):
        written = module.render(SAMPLES / f"{tiling}.toml", tmp_path)
        assert written.read_bytes() == (SAMPLES.parent / "renders" / "hankin" / f"{tiling}.svg").read_bytes()


def _build(tmp_path, formats, *overrides):
    design = load_design(SAMPLE, overrides=list(overrides))
    result = build_design(design, tmp_path / "out", formats)
    return design, result


@pytest.mark.parametrize("mode", ["pierced", "score", "engrave", "inlay"])
def test_every_laser_mode(tmp_path, mode):
    _, result = _build(tmp_path, ("dxf", "svg", "lbrn2"), f'output.laser_mode="{mode}"')
    assert result.paths and all(Path(p).stat().st_size > 1000 for p in result.paths)
    if mode == "score":  # each ray scored once: no centre-line twice
        doc = ezdxf.readfile(next(p for p in result.paths if p.endswith(".dxf")))
        layers = {e.dxf.layer for e in doc.modelspace()}
        assert any("SCORE" in name.upper() for name in layers), layers


def test_the_router(tmp_path):
    _, result = _build(tmp_path, ("dxf",), 'output.laser_profile="router-6mm-mdf"', "tile.stroke=7", "packing.edge=40")
    assert len(result.paths) == 1 and ezdxf.readfile(result.paths[0]).modelspace()


@pytest.mark.parametrize("style", ["relief", "pierced", "deboss", "mosaic"])
def test_every_print_style(tmp_path, style):
    extra = ("output.inlay=true",) if style == "deboss" else ()
    _, result = _build(tmp_path, ("stl", "3mf"), f'output.print_style="{style}"', 'colour.by="shape"', *extra)
    assert len(result.paths) >= 2


def test_the_step(tmp_path):
    from fabtiles.export.step import check_step_file

    design, result = _build(tmp_path, ("step",), "tile.size=60", "output.fill_small_holes=false")
    tile = design.build_tile()
    volume = expected_volume("relief", tile.region(), tile.outline_shape())
    assert check_step_file(result.paths[0], volume=volume, parts=1) == pytest.approx(volume, rel=1e-3)


def test_interlace_weaves_and_builds(tmp_path):
    design = load_design(SAMPLE, overrides=["tile.interlace=true"])
    tile = design.build_tile(tile_cls=fabtiles.Tile)
    assert tile.weave().conflicts == 0 and len(tile.weave()) > 10
    result = build_design(design, tmp_path / "out", ("svg", "stl"))
    assert len(result.paths) == 2


def test_librecad_draws_the_hankin_dxf(tmp_path):
    _, result = _build(tmp_path, ("dxf",))
    dxf = Path(result.paths[0])
    drawn, edges = drawn_and_cut_edges(dxf, dxf.parent)
    assert drawn == edges > 100


def test_prusaslicer_slices_the_hankin_mosaic_by_colour(tmp_path):
    _, result = _build(tmp_path, ("3mf",), 'output.print_style="mosaic"', 'colour.by="shape"')
    path = Path(result.paths[0])
    gcode = slice_gcode(tmp_path, path, 4)
    tools = sorted({int(t) for t in re.findall(r"^T(\d+)\s*$", gcode, flags=re.M)})
    assert len(tools) >= 3 and sorted(k for k in extrusions_by_tool(gcode) if k is not None) == tools
