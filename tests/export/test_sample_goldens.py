"""Golden DXFs of the samples (issue 4), compared entity by entity.

Every ``samples/*.toml`` design is built into its pierced laser DXF, with its
laser profile, through ``fabtiles build``'s own code; the file is checked as the
issue asks (:func:`dxf_helpers.check_laser_dxf`) and compared with
``tests/export/golden/sample-<name>.json``. One sample is also built in score mode
and as R12. Samples too large for a full golden (the 600 x 400 mm sheet) are
compared by counts and a spread sample of their entities.

Regenerate after an intended change of the geometry or the writer::

    FABTILES_UPDATE_GOLDEN=1 python -m pytest tests/export/test_sample_goldens.py
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from designs import printed_only
from dxf_helpers import (
    GOLDEN,
    assert_golden,
    assert_golden_summary,
    check_laser_dxf,
    check_router_dxf,
    edge_problems,
    golden_text,
    is_closed,
    read_checked,
    star_plate,
    vertices,
)
from model_files import write_cut

import fabtiles
from fabtiles.designs.design_file import load_design
from fabtiles.geometry.narrow import fill_small_holes
from fabtiles.machines.profiles import DEFAULT_LASER_PROFILE, load_profile
from fabtiles.making import build_design, export_tile

ROOT = Path(__file__).resolve().parents[2]
PIECES = {"screen-1200x800"}
"""Samples larger than their cutter's bed, cut as pieces: checked in tests/making/test_panel_pieces.py."""
SAMPLES = sorted(p for p in (ROOT / "samples").glob("*.toml") if p.stem not in PIECES and not printed_only(p))
LARGE = {"sheet-600x400", "panel-2440x1220", "relief-400x400"}
"""Samples whose full golden would be megabytes: counts and a sample of entities only."""
ONE = ROOT / "samples" / "rosette.toml"
"""The sample also built in score mode and as R12 (small: one rosette in a circle)."""


def build(sample: Path, out: Path, mode: str = "pierced"):
    """Build ``sample``'s DXF in ``mode`` as ``fabtiles build`` does: (path, tile, profile)."""
    design = load_design(sample, overrides=[f"output.laser_mode={mode}"])
    [report] = build_design(design, out, ["dxf"]).reports
    path = Path(report.path)
    tile = design.build_tile(tile_cls=fabtiles.Tile)
    return path, tile, load_profile(design.output.laser_profile or DEFAULT_LASER_PROFILE)


def laser_region(tile, profile, fill=True):
    """The region a laser DXF of a design cuts: the tile's, its holes too small for the laser filled
    (``fill_small_holes``, the default)."""
    if not fill:
        return tile.region()
    region, _ = fill_small_holes(tile.region(), profile.min_hole_mm, tolerance_mm=profile.tolerance_mm)
    return region


@pytest.mark.parametrize("sample", SAMPLES, ids=[p.stem for p in SAMPLES])
def test_sample_dxf_is_golden(sample, tmp_path):
    path, tile, profile = build(sample, tmp_path)
    assert path.name == f"{sample.stem}.dxf"
    if profile.kind == "router":  # the part as the bit makes it, no kerf (see tests/export/test_router.py)
        doc = check_router_dxf(path, tile.region(), profile)
    else:
        fill = load_design(sample).output.fill_small_holes
        doc = check_laser_dxf(
            path, laser_region(tile, profile, fill), kerf=profile.kerf_mm, version=profile.dxf_version, profile=profile
        )
    if sample.stem in LARGE:  # the panel's entities are long (rounded corners): fewer of them sampled
        assert_golden_summary(path, f"sample-{sample.stem}", samples=10 if profile.kind == "router" else 40, doc=doc)
    else:
        assert_golden(path, f"sample-{sample.stem}", doc=doc)


def test_sample_score_dxf_is_golden(tmp_path):
    path, tile, profile = build(ONE, tmp_path, mode="score")
    doc = read_checked(path)
    assert doc.header["$INSUNITS"] == 4
    layers = profile.layers
    ents = list(doc.modelspace())
    cut = [e for e in ents if e.dxf.layer != layers.score.name]
    score = [e for e in ents if e.dxf.layer == layers.score.name]
    # The outline alone on the cut layer, closed and last; the centre-lines open, scored first.
    assert [e.dxf.layer for e in cut] == [layers.outer_cut.name] and is_closed(cut[0])
    assert ents[-1].dxf.handle == cut[0].dxf.handle
    assert score and all(e.dxftype() == "LWPOLYLINE" and not is_closed(e) for e in score)
    assert all(edge_problems(vertices(e), closed=False)[0] == 0 for e in score)
    outline = vertices(cut[0])
    # the outline grown by half the kerf, moved into the positive quadrant: its corner at (0, 0)
    kerf = profile.kerf_mm
    # (the circle's outline is arcs: ezdxf's drawing of them comes within its 0.001 mm of the extremes)
    assert outline.min(0) == pytest.approx([0.0, 0.0], abs=0.001) and outline.min() >= -1e-9
    assert outline.max(0) == pytest.approx([tile.width_mm + kerf, tile.height_mm + kerf], abs=profile.tolerance_mm)
    assert_golden(path, f"sample-{ONE.stem}-score")


def test_sample_r12_dxf_is_golden(tmp_path):
    design = load_design(ONE)
    tile = design.build_tile(tile_cls=fabtiles.Tile)
    profile = load_profile(design.output.laser_profile or DEFAULT_LASER_PROFILE)
    path = tmp_path / f"{ONE.stem}-r12.dxf"
    report = export_tile(tile, path, profile=profile, mode="pierced", dxf_version="R12")
    assert report.stats["dxf_version"] == "R12"
    check_laser_dxf(path, laser_region(tile, profile), kerf=profile.kerf_mm, version="R12", profile=profile)
    assert_golden(path, f"sample-{ONE.stem}-r12")


def test_every_sample_golden_is_present_and_canonical():
    """One golden per sample (none left over), each exactly as the helpers write it."""
    names = {f"sample-{p.stem}.json" for p in SAMPLES} | {f"sample-{ONE.stem}-{x}.json" for x in ("score", "r12")}
    assert {p.name for p in GOLDEN.glob("sample-*.json")} == names
    for name in sorted(names):
        text = (GOLDEN / name).read_text()
        assert golden_text(json.loads(text)) == text, f"{name} was not written by golden_text"
        assert len(text) < 2_000_000, f"{name} is {len(text):,} bytes; store a summary instead"


def test_summary_golden_catches_a_changed_entity(tmp_path, monkeypatch):
    """A summary golden is not just counts: a moved vertex in a sampled entity fails."""
    import dxf_helpers

    region, outline = star_plate(grid=4)
    path = tmp_path / "p.dxf"
    write_cut(path, region=region, outline=outline, profile="laser-3mm-plywood")
    monkeypatch.setattr(dxf_helpers, "GOLDEN", tmp_path / "golden")
    monkeypatch.setenv("FABTILES_UPDATE_GOLDEN", "1")
    assert_golden_summary(path, "plate", samples=5)
    first = (tmp_path / "golden" / "plate.json").read_bytes()
    assert_golden_summary(path, "plate", samples=5)
    assert (tmp_path / "golden" / "plate.json").read_bytes() == first  # reproducible
    monkeypatch.delenv("FABTILES_UPDATE_GOLDEN")
    assert_golden_summary(path, "plate", samples=5)
    data = json.loads(first)
    assert data["entities"] == 17 and data["sample_every"] == 3
    data["sample"][1][4][0][0] += 0.01
    (tmp_path / "golden" / "plate.json").write_text(golden_text(data))
    with pytest.raises(AssertionError, match=r"entity 3: vertices differ by 0\.0(1|099)"):
        assert_golden_summary(path, "plate", samples=5)
    with pytest.raises(AssertionError, match=r"no golden file .*missing\.json"):
        assert_golden_summary(path, "missing")
