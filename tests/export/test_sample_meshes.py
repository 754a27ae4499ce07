"""Every sample design in every print style, as STL, 3MF and STEP (issue 5).

Each ``samples/*.toml`` (but the 600 x 400 mm benchmark sheet and the router panel) is built as its
design says and written as :meth:`fabtiles.Tile.export` writes it (STEP through it; STL and 3MF
through its pipeline from one print model shared by both) with the design's printer profile, in
each style (relief, pierced, deboss). The files are
read back (trimesh for STL and 3MF, OCP for STEP) and must be watertight (STEP: a
valid closed B-rep), of the volume of region area x heights within 0.5 %, within
the outline's bounds from z = 0 to the style's top, with the expected number of
bodies; a two-colour 3MF's ``base`` and ``pattern`` must not overlap.

STEP costs ~24 s and ~18 MB for one full 150 mm sample (about 1 s at 40 mm),
so STL and 3MF run at full size while STEP runs with each design shrunk to
``STEP_SIZE_MM`` (``--set tile.size=...``: same motif, packing, frame, stroke
and, for the seamless one, a refitted seamless radius), in every style; one
STEP (``STEP_FULL``, the 100 mm rosette coaster in relief) runs at full size.
"""

from __future__ import annotations

import functools
import zipfile
from pathlib import Path

import numpy as np
import pytest
import shapely
from designs import printed_only
from mesh_helpers import (
    STYLES,
    VOLUME_REL,
    assert_section,
    assert_solid,
    assert_step_solid,
    assert_style_sections,
    assert_touch_without_overlap,
    expected_volume,
    load_3mf_parts,
    load_stl,
    top,
)

import fabtiles
from fabtiles.designs.design_file import load_design
from fabtiles.export.formats import format_of
from fabtiles.geometry.stack import resolve_stack
from fabtiles.machines.profiles import DEFAULT_PRINTER_PROFILE
from fabtiles.making import write_files
from fabtiles.making.models import Models
from fabtiles.making.pipeline import _options_for

ROOT = Path(__file__).resolve().parents[2]
SKIP = {"sheet-600x400", "panel-2440x1220", "screen-1200x800", "relief-400x400"}
"""The benchmark sheet and the router's panel: far too big for a test of every format and style; the
samples larger than their machine's bed are made as pieces (tests/making/test_panel_pieces.py,
tests/making/test_print_pieces.py)."""
SAMPLES = [p for p in sorted((ROOT / "samples").glob("*.toml")) if p.stem not in SKIP and not printed_only(p)]
IDS = [p.stem for p in SAMPLES]

STEP_SIZE_MM = 40.0
"""Size the samples are shrunk to for STEP (longest side, mm)."""
STEP_FULL = ("rosette", "relief")
"""The one sample and style written as STEP at full size."""


@functools.cache
def sample_tile(path: Path, shrink: bool = False):
    """``(tile, printer profile)`` of a sample, optionally shrunk for STEP."""
    design = load_design(path)
    w, h = design.tile_spec.size
    if shrink and max(w, h) > STEP_SIZE_MM:
        f = STEP_SIZE_MM / max(w, h)
        value = f"{w * f:g}" if w == h else f"[{w * f:g}, {h * f:g}]"
        design = load_design(path, overrides=[f"tile.size={value}"])
    tile = design.build_tile(tile_cls=fabtiles.Tile)
    return tile, design.output.printer_profile or DEFAULT_PRINTER_PROFILE


@pytest.fixture(scope="module")
def print_export():
    """``export(path, sample, style)``: what ``tile.export(path, ...)`` writes, from one print model per
    sample and style shared by the STL and the 3MF.

    ``Tile.export`` makes a fresh :class:`~fabtiles.making.models.Models` on each call; the writers are
    pure functions of the print model, so both formats are written through the same pipeline
    (:func:`~fabtiles.making.write_files`) from one model, made with the options ``Tile.export`` makes
    for either suffix (asserted equal).
    """
    models: dict = {}

    def export(path: Path, sample: Path, style: str):
        tile, profile = sample_tile(sample)
        options = {"style": style, "fill_small_holes": False}
        built = {s: _options_for(format_of(f"t.{s}"), profile, options) for s in ("stl", "3mf")}
        assert built["stl"] == built["3mf"]
        key = (sample, style)
        if key not in models:
            models[key] = Models(tile, built["stl"])
        (report,) = write_files(models[key], (format_of(path).name,), path.parent, path.stem).reports
        return report

    return export


def expectations(tile, profile, style):
    """Region, outline, stack heights and the expected volume, top and body count.

    The files are written with ``fill_small_holes=False``: they are compared with the
    drawn ``tile.region()``, openings and all.
    """
    region, outline = tile.region(), tile.outline_shape()
    s = resolve_stack(profile, style)
    volume = expected_volume(style, region, outline, s.base, s.relief, s.pierced, s.deboss)
    parts = len(shapely.get_parts(region)) if style == "pierced" else len(shapely.get_parts(outline))
    return region, outline, s, volume, top(style, s.base, s.relief, s.pierced), parts


def triangles(mesh):
    """A mesh's triangles in an order of their own: each from its least vertex on (its winding kept), sorted;
    ordered on the mesh's 2^-10 mm grid, so that a float's last bit does not change the order."""
    t = mesh.vertices[mesh.faces]
    key = np.round(t * 1024)
    first = np.lexsort(key.transpose(2, 0, 1)[::-1], axis=-1)[:, 0]
    turn = (np.arange(3) + first[:, None]) % 3
    t, key = (np.take_along_axis(a, turn[:, :, None], axis=1) for a in (t, key))
    return t[np.lexsort(key.reshape(len(key), -1).T[::-1])]


def test_samples_found():
    assert len(SAMPLES) >= 5 and "rosette" in IDS


@pytest.mark.parametrize("style", STYLES)
@pytest.mark.parametrize("sample", SAMPLES, ids=IDS)
def test_sample_stl(tmp_path, print_export, sample, style):
    tile, profile = sample_tile(sample)
    region, outline, s, volume, zmax, parts = expectations(tile, profile, style)
    path = tmp_path / "t.stl"
    report = print_export(path, sample, style)
    assert report.format == "stl" and report.stats["style"] == style
    mesh = load_stl(path)
    assert_solid(mesh, volume, outline.bounds, zmax, bodies=parts)
    assert_style_sections(mesh, style, region, outline, s.base, s.relief, s.pierced, s.deboss)


@pytest.mark.parametrize("style", STYLES)
@pytest.mark.parametrize("sample", SAMPLES, ids=IDS)
def test_sample_3mf(tmp_path, print_export, sample, style):
    tile, profile = sample_tile(sample)
    region, outline, s, volume, zmax, parts = expectations(tile, profile, style)
    path = tmp_path / "t.3mf"
    report = print_export(path, sample, style)
    assert report.format == "3mf"
    assert 'unit="millimeter"' in zipfile.ZipFile(path).read("3D/3dmodel.model").decode()
    got = load_3mf_parts(path)
    if style != "relief":
        assert list(got) == [{"pierced": "pattern", "deboss": "plate"}[style]]
        (mesh,) = got.values()
        assert_solid(mesh, volume, outline.bounds, zmax, bodies=parts)
        # its sections are the STL's, which test_sample_stl cuts at every height of the style: the same triangles
        print_export(tmp_path / "t.stl", sample, style)
        np.testing.assert_allclose(triangles(mesh), triangles(load_stl(tmp_path / "t.stl")), atol=1e-5)
        return
    assert list(got) == ["base", "pattern"]
    base, pattern = got["base"], got["pattern"]
    assert_solid(base, outline.area * s.base, outline.bounds, s.base, bodies=parts)
    assert_solid(
        pattern, region.area * s.relief, outline.bounds, zmax, zmin=s.base, bodies=len(shapely.get_parts(region))
    )
    assert_section(base, s.base / 2, outline)
    assert_section(pattern, s.base + s.relief / 2, region)
    assert base.volume + pattern.volume == pytest.approx(volume, rel=VOLUME_REL)
    assert_touch_without_overlap(base, pattern)


@pytest.mark.parametrize("style", STYLES)
@pytest.mark.parametrize("sample", SAMPLES, ids=IDS)
def test_sample_step(tmp_path, sample, style):
    from fabtiles.export import step

    tile, profile = sample_tile(sample, shrink=(sample.stem, style) != STEP_FULL)
    _region, outline, _, volume, zmax, parts = expectations(tile, profile, style)
    path = tmp_path / "t.step"
    report = tile.export(path, profile=profile, style=style, fill_small_holes=False)
    assert report.format == "step" and report.stats["solids"] == parts
    assert_step_solid(step.read_step(path), volume, outline.bounds, zmax, solids=parts)
