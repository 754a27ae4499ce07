"""A tile of each Archimedean tiling (``samples/tilings/*.toml``) cuts and prints cleanly.

Each sample design is built as it says and exported through :meth:`fabtiles.Tile.export`:
the DXF with the small holes filled (as the designs ask) has no findings under the
3 mm plywood profile, and the relief STL read back by trimesh is one watertight,
consistently wound body of the expected volume within the outline.
"""

from __future__ import annotations

import functools
from pathlib import Path

import ezdxf
import pytest
from mesh_helpers import assert_relief_stl, assert_style_sections

import fabtiles
from fabtiles.designs.design_file import load_design
from fabtiles.pattern.tilings import TILINGS

SAMPLES = Path(__file__).resolve().parents[2] / "samples" / "tilings"


def test_one_sample_per_tiling():
    assert sorted(p.stem for p in SAMPLES.glob("*.toml")) == sorted(TILINGS)


@functools.cache
def _tile(tiling):
    """The sample's design and tile, built once for its DXF and STL tests (the tile keeps its region)."""
    design = load_design(SAMPLES / f"{tiling}.toml")
    assert design.packing.kind == "archimedean" and design.packing.tiling == tiling
    assert design.output.fill_small_holes
    return design, design.build_tile(tile_cls=fabtiles.Tile)


@pytest.mark.parametrize("tiling", TILINGS)
def test_sample_dxf_is_clean(tiling, tmp_path):
    design, tile = _tile(tiling)
    report = tile.export(tmp_path / "t.dxf", profile=design.output.laser_profile, fill_small_holes=True)
    assert report.ok, report.summary()
    doc = ezdxf.readfile(tmp_path / "t.dxf")
    assert not doc.audit().has_errors and len(doc.modelspace()) > 100


@pytest.mark.parametrize("tiling", TILINGS)
def test_sample_stl_is_watertight(tiling, tmp_path):
    design, tile = _tile(tiling)
    mesh = assert_relief_stl(tile, tmp_path / "t.stl", design.output.printer_profile)
    assert_style_sections(mesh, "relief", tile.region(), tile.outline_shape())


def test_gallery_renders_are_reproducible(tmp_path):
    import importlib.util

    spec = importlib.util.spec_from_file_location("render_samples", SAMPLES.parent / "render.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for tiling in ("3.3.4.3.4", "4.6.12"):
        written = module.render(SAMPLES / f"{tiling}.toml", tmp_path)
        committed = SAMPLES.parent / "renders" / "tilings" / f"{tiling}.svg"
        assert written.read_bytes() == committed.read_bytes()
