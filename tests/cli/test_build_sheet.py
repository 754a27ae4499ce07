"""``fabtiles build --sheet / --copies N``: tiles laid out on the laser profile's bed (issue 4)."""

from __future__ import annotations

import re
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "export"))
from dxf_helpers import check_laser_dxf, is_closed, read_checked, vertices
from test_build import SMALL as BUILD_SMALL
from test_build import run

import fabtiles
from fabtiles import FabtilesError
from fabtiles.designs.design_file import load_design
from fabtiles.export.formats import FORMATS
from fabtiles.geometry.narrow import fill_small_holes
from fabtiles.machines.profiles import load_profile
from fabtiles.making import BuildOptions, layout_tile_sheet

ROOT = Path(__file__).resolve().parents[2]
PLY = load_profile("laser-3mm-plywood")
INNER, OUTER, SCORE = PLY.layers.inner_cut.name, PLY.layers.outer_cut.name, PLY.layers.score.name

SMALL = BUILD_SMALL.replace('formats = ["svg"]', 'formats = ["dxf", "svg", "stl"]\nlaser_profile = "laser-3mm-plywood"')
assert SMALL != BUILD_SMALL


@pytest.fixture
def design(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL, encoding="utf-8")
    return path


def check_sheet_dxf(path, design_path, copies, kerf=PLY.kerf_mm, sheet=None):
    """The sheet DXF: the laser checks, ``copies`` outer contours, every one inside the bed.

    ``sheet``: the design's sheet of ``copies``, where the test has laid it out already."""
    design = load_design(design_path)
    options = BuildOptions.of_design(design)
    if sheet is None:
        sheet = layout_tile_sheet(design.build_tile(tile_cls=fabtiles.Tile), options, copies=copies)
    region = sheet.region
    if options.fill_small_holes:  # the design's default: the cut fills the holes the laser cannot cut
        region, _ = fill_small_holes(region, PLY.min_hole_mm, tolerance_mm=PLY.tolerance_mm)
    doc = check_laser_dxf(path, region, kerf=kerf, profile=PLY)  # layers, order, closed, area
    outer = [vertices(e) for e in doc.modelspace() if e.dxf.layer == OUTER]
    assert len(outer) == copies
    pts = np.vstack([vertices(e) for e in doc.modelspace()])
    assert pts.min(0).tolist() == [0.0, 0.0]  # the first tile's kerf, moved into the positive quadrant
    assert (pts.max(0) <= np.array(PLY.bed_mm)).all()
    return doc


def test_copies_writes_a_sheet_of_n_tiles(design, tmp_path):
    out = tmp_path / "out"
    result = run("build", design, "-o", out, "--copies", 7, "--format", "dxf", "--format", "svg")
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in out.iterdir()) == ["small-sheet.dxf", "small-sheet.svg"]
    wrote = [line.split(" (")[0] for line in result.stdout.splitlines() if line.startswith("wrote ")]
    assert wrote == [f"wrote {out / 'small-sheet.dxf'}", f"wrote {out / 'small-sheet.svg'}"]
    assert result.stdout.count("laser laser-3mm-plywood: ") == 1  # the sheet's checks, once for both files
    assert "  laid 7 tiles on the 600 x 400 mm bed of laser profile 'laser-3mm-plywood' (" in result.stdout
    assert result.stderr == ""
    check_sheet_dxf(out / "small-sheet.dxf", design, 7)
    svg = (out / "small-sheet.svg").read_text()
    assert 'id="INNER"' in svg and 'id="OUTER"' in svg
    width, height = (float(v) for v in re.search(r'width="([\d.]+)mm" height="([\d.]+)mm"', svg).groups())
    assert width <= PLY.bed_mm[0] and height <= PLY.bed_mm[1]


def test_sheet_fills_the_bed_and_skips_print_formats(tmp_path):
    design = tmp_path / "coaster.toml"  # one motif per tile: a small file for 54 tiles
    design.write_text(SMALL.replace("[packing]\nradius = 8\n", "").replace("table3-1", "table2-left"))
    out = tmp_path / "out"
    result = run("build", design, "-o", out, "--sheet", "--format", "dxf", "--format", "stl")
    assert result.exit_code == 0, result.output
    assert [p.name for p in out.iterdir()] == ["coaster-sheet.dxf"]
    assert result.stderr == "fabtiles: note: skipped stl: a sheet is laid out for the laser formats (dxf, svg) only\n"
    gap = PLY.kerf_mm + 2
    fit = [int((bed + gap) // (60 + gap)) for bed in PLY.bed_mm]  # 9 x 6 tiles of 60 mm
    assert fit == [9, 6]
    check_sheet_dxf(out / "coaster-sheet.dxf", design, fit[0] * fit[1])
    assert "  laid 54 tiles on the 600 x 400 mm bed of laser profile 'laser-3mm-plywood' (" in result.stdout


def test_score_mode_sheet_and_gap(design, tmp_path):
    out = tmp_path / "out"
    result = run(
        "build", design, "-o", out, "--copies", 2, "--gap", 10, "--format", "dxf", "--set", "output.laser_mode=score"
    )
    assert result.exit_code == 0, result.output
    ents = list(read_checked(out / "small-sheet.dxf").modelspace())
    outer = sorted((vertices(e) for e in ents if e.dxf.layer == OUTER), key=lambda v: v[:, 0].min())  # in cut order
    assert len(outer) == 2 and all(is_closed(e) for e in ents if e.dxf.layer == OUTER)
    assert {e.dxf.layer for e in ents} == {OUTER, SCORE}
    assert all(not is_closed(e) for e in ents if e.dxf.layer == SCORE)
    assert outer[1][:, 0].min() - outer[0][:, 0].max() == pytest.approx(10 - PLY.kerf_mm)


def test_a_bed_sized_tile_is_one_copy(tmp_path):
    big = tmp_path / "big.toml"
    big.write_text(
        '[motif]\npreset = "table2-left"\n[tile]\noutline = "rectangle"\nsize = [600, 400]\n'
        'frame = 5\nstroke = 1.5\n[output]\nformats = ["dxf"]\n'
    )
    result = run("build", big, "-o", tmp_path / "out", "--sheet")
    assert result.exit_code == 0, result.output
    doc = read_checked(tmp_path / "out" / "big-sheet.dxf")
    assert [e.dxf.layer for e in doc.modelspace()].count(OUTER) == 1


def test_the_large_pattern_sample_is_the_benchmark_sheet():
    design = load_design(ROOT / "samples" / "sheet-600x400.toml")
    profile = load_profile(design.output.laser_profile)
    t = design.tile_spec
    assert (t.outline, t.size, t.frame, t.stroke) == ("rectangle", tuple(profile.bed_mm), 5.0, 1.0)
    assert design.motif.preset == "table3-3" and design.packing.radius == 15
    assert design.output.formats == ("dxf", "svg")


def test_help_documents_sheets():
    text = " ".join(run("build", "--help").output.split())
    assert "--sheet" in text and "--copies N" in text
    assert "Print formats (stl, 3mf, step) have no sheet: they are skipped" in text
    assert "samples/sheet-600x400.toml" in text


@pytest.mark.parametrize(
    "extra, match",
    [
        (["--copies", 55], r"55 tiles do not fit on the 600 x 400 mm bed of laser profile 'laser-3mm-plywood'"),
        (["--copies", 0], r"copies must be an integer"),
        (["--sheet", "--gap", 0.1], r"gap_mm must be a finite number > 0.15"),
        (
            ["--sheet", "--format", "stl"],
            r"a sheet is laid out for the laser formats \(dxf, svg\) only, "
            r"but the formats asked for are: stl; add --format dxf",
        ),
        (["--sheet", "--set", "tile.size=700"], r"not even one tile fits on the 600 x 400 mm bed"),
        (["--copies", 2, "--set", 'output.laser_profile="fdm-0.4mm"'], r"printer profile, but a laser profile"),
    ],
)
def test_bad_sheet_exits_2_writes_nothing(design, tmp_path, extra, match):
    out = tmp_path / "out"
    result = run("build", design, "-o", out, *extra)
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    assert result.stderr.startswith("fabtiles: error: ") and result.stderr.count("\n") == 1
    assert re.search(match, result.stderr), result.stderr
    assert not out.exists()


def test_a_refused_sheet_format_keeps_its_existing_file(design, tmp_path, monkeypatch):
    """A sheet format whose writer fails is refused on its own (exit 3): its file of an earlier
    build is left as it was, the other format is written; every format refused is exit 2."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "small-sheet.svg").write_text("old")
    calls = []

    def boom(fmt):
        def write(model, options):
            calls.append(fmt)
            if fmt == "svg":
                raise FabtilesError("disk on fire")
            return b"new"

        return write

    for fmt in ("dxf", "svg"):
        monkeypatch.setitem(FORMATS, fmt, replace(FORMATS[fmt], write=boom(fmt)))
    result = run("build", design, "-o", out, "--copies", 2, "--format", "dxf", "--format", "svg")
    assert result.exit_code == 3
    assert result.stderr == (
        f"fabtiles: refused {out / 'small-sheet.svg'} (svg): disk on fire "
        f"({out / 'small-sheet.svg'}, from an earlier build, was left as it was)\n"
    )
    assert calls == ["dxf", "svg"]
    assert sorted(p.name for p in out.iterdir()) == ["small-sheet.dxf", "small-sheet.svg"]
    assert (out / "small-sheet.svg").read_text() == "old" and (out / "small-sheet.dxf").read_text() == "new"
    result = run("build", design, "-o", out, "--copies", 2, "--format", "svg")
    assert result.exit_code == 2 and result.stderr == "fabtiles: error: disk on fire\n"
    assert (out / "small-sheet.svg").read_text() == "old"


WOVEN = SMALL.replace("stroke = 1.0", "stroke = 1.0\ninterlace = true")
assert WOVEN != SMALL


def score_length(path):
    """Total length of the score lines of a DXF read back."""
    total = 0.0
    for e in read_checked(path).modelspace():
        if e.dxf.layer == SCORE:
            pts = vertices(e)
            total += float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    return total


def test_interlaced_score_sheet_holds_the_woven_score_lines(tmp_path):
    path = tmp_path / "woven.toml"
    path.write_text(WOVEN, encoding="utf-8")
    out = tmp_path / "out"
    for extra in ((), ("--copies", 2)):
        result = run("build", path, "-o", out, "--format", "dxf", "--set", "output.laser_mode=score", *extra)
        assert result.exit_code == 0, result.output
    one, sheet = score_length(out / "woven.dxf"), score_length(out / "woven-sheet.dxf")
    design = load_design(path)
    tile = design.build_tile(tile_cls=fabtiles.Tile)
    plain = float(np.linalg.norm(np.diff(tile.centrelines(), axis=1)[:, 0], axis=1).sum())
    assert one < plain - 1.0  # the woven tile's lines are broken under its crossings
    assert sheet == pytest.approx(2 * one, rel=1e-6)


def test_interlace_cut_sheet_cuts_every_copy(tmp_path):
    from fabtiles.geometry.machine_geometry import cut_geometry as laser_geometry

    path = tmp_path / "cut.toml"
    # a 30 mm tile: its crossings' cut still takes tens of mm^2 off the region (asserted below), so a sheet
    # of the uncut region would not be three times the cut's area
    text = WOVEN.replace("interlace = true", "interlace = true\ninterlace_cut = true").replace("size = 60", "size = 30")
    assert "size = 30" in text
    path.write_text(text, encoding="utf-8")
    design = load_design(path)
    tile = design.build_tile(tile_cls=fabtiles.Tile)
    cut, _ = laser_geometry(tile, profile=PLY, mode="pierced")
    assert cut.area < tile.region().area - 1.0
    sheet = layout_tile_sheet(tile, BuildOptions.of_design(design), copies=3)
    assert sheet.region.area == pytest.approx(3 * cut.area, rel=1e-9)
    out = tmp_path / "out"
    result = run("build", path, "-o", out, "--format", "dxf", "--copies", 3)
    assert result.exit_code == 0, result.output
    check_sheet_dxf(out / "cut-sheet.dxf", path, 3, sheet=sheet)
