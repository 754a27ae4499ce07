"""The ``filled_pattern`` finding: filling small holes must not leave a plain tile unsaid."""

from __future__ import annotations

from dataclasses import replace

import pytest
import shapely
from shapely.geometry import box

from fabtiles import FabricationError
from fabtiles.core.report import Report
from fabtiles.designs.design_file import build_tile, design_from_text
from fabtiles.geometry.cut_plan import CutOptions, plan_cut
from fabtiles.geometry.laser_checks import check_cut_pattern
from fabtiles.geometry.narrow import PATTERN_KEPT, check_pattern_kept
from fabtiles.geometry.print_checks import check_print_pattern, fill_print_holes
from fabtiles.machines.profiles import load_profile
from fabtiles.making.checks import check_design
from fabtiles.making.models import BuildOptions, Models

# every one of its 247 holes is narrower than laser-3mm-plywood's min_hole_mm = 1.2 mm (the widest 0.897 mm)
ALL_FILLED = """
[motif]
preset = "table3-2"
[packing]
kind = "archimedean"
tiling = "3.3.3.3.3.3"
edge = 10.14
[tile]
outline = "square"
size = [89.5, 89.5]
frame = 3.0
stroke = 2.0
[output]
formats = ["dxf"]
laser_profile = "laser-3mm-plywood"
fill_small_holes = true
"""


def codes(report):
    return [f.code for f in report.findings]


@pytest.fixture(scope="module")
def all_filled():
    design = design_from_text(ALL_FILLED, name="plain")
    return design, build_tile(design)


def test_a_laser_tile_with_every_hole_filled_says_so(all_filled):
    design, tile = all_filled
    report = Models(tile, BuildOptions.of_design(design)).cut.report
    assert codes(report) == ["filled_pattern"]
    f = report.findings[0]
    assert f.count == 247 and f.worst == 0 and f.limit == 100 * PATTERN_KEPT and f.unit == "%"
    assert len(f.locations) == 247
    # what to change, with figures the next two tests check
    assert "left none of the pattern (all 247 holes filled)" in f.message
    assert "the holes of 0.897 mm must be 1.2 mm wide or wider" in f.message
    assert "a stroke of at most 1.69 mm (it is 2 mm)" in f.message
    assert "a packing at least 1.11x larger (its edge or radius)" in f.message
    assert "a profile with min_hole_mm <= 0.89 mm" in f.message


@pytest.mark.parametrize("override", ["stroke = 1.69", "edge = 11.26"])
def test_the_advice_keeps_the_pattern(override):
    key = override.split(" =")[0]
    text = "\n".join(override if line.startswith(key + " =") else line for line in ALL_FILLED.splitlines())
    design = design_from_text(text, name="kept")
    report = Models(build_tile(design), BuildOptions.of_design(design)).cut.report
    assert report.stats["filled_holes"] > 50  # some holes are filled, and that is fine
    assert "filled_pattern" not in codes(report)


def test_strict_profile_refuses_the_plain_tile(all_filled):
    _, tile = all_filled
    strict = replace(load_profile("laser-3mm-plywood"), strict=True)
    with pytest.raises(FabricationError, match="filled_pattern: filling the holes narrower than min_hole_mm"):
        plan_cut(tile.region(), tile.outline_shape(), CutOptions.of(profile=strict, fill_small_holes=True, stroke=2.0))
    # kept holes: nothing filled, nothing to say (the small holes are reported instead)
    plan = plan_cut(
        tile.region(),
        tile.outline_shape(),
        CutOptions.of(profile="laser-3mm-plywood", fill_small_holes=False, stroke=2.0),
    )
    assert codes(plan.report) == ["small_hole"]


def test_fabtiles_check_reports_it_for_both_machines(all_filled):
    design, tile = all_filled
    design = replace(design, output=replace(design.output, printer_profile="fdm-0.6mm"))
    result = check_design(design, tile)
    assert [(where, f.code, f.count) for where, f in result.findings()] == [
        ("laser", "filled_pattern", 247),
        ("print", "filled_pattern", 247),
    ]
    # the 0.4 mm nozzle keeps holes of 0.8 mm: most of the pattern stays
    design = replace(design, output=replace(design.output, printer_profile="fdm-0.4mm"))
    assert [where for where, _ in check_design(design, tile).findings()] == ["laser"]


@pytest.mark.parametrize("style", ["relief", "pierced", "deboss", "mosaic"])
def test_a_print_with_every_opening_filled_says_so(all_filled, style):
    from fabtiles.solid.print_model import print_model

    _, tile = all_filled
    model = print_model(
        tile.region(), tile.outline_shape(), profile="fdm-0.6mm", style=style, stroke=2.0, fill_small_holes=True
    )
    (f,) = [f for f in model.report.findings if f.code == "filled_pattern"]
    assert f.worst == 0 and f.count == 247
    assert "a printer profile with min_hole_mm <= 0.89 mm (a finer nozzle)" in f.message
    strict = replace(load_profile("fdm-0.6mm"), strict=True)
    with pytest.raises(FabricationError, match="filled_pattern"):
        print_model(tile.region(), tile.outline_shape(), profile=strict, style=style, stroke=2.0, fill_small_holes=True)


def test_a_deboss_whose_grooves_are_mostly_filled():
    # grooves of 0.5 mm (too narrow for 0.8 mm, filled with plate) and one of 1 mm
    grooves = shapely.union_all([box(2 + 2 * k, 2, 2.5 + 2 * k, 38) for k in range(15)] + [box(33, 2, 34, 38)])
    outline = box(0, 0, 40, 40)
    filled, n = fill_print_holes(grooves, outline, "fdm-0.4mm", "deboss")
    assert n == 15
    report = Report(path="", format="")
    kept = check_print_pattern(grooves, filled, outline, "fdm-0.4mm", "deboss", stroke=0.5, report=report)
    assert kept == pytest.approx(1 / 8.5)
    (f,) = report.findings
    assert "left 12 % of its grooves' area (15 of 16 grooves filled)" in f.message
    assert "the grooves of 0.5 mm must be 0.8 mm wide or wider: a stroke of at least 0.8 mm (it is 0.5 mm)" in f.message
    assert "packing" not in f.message  # a larger packing does not widen a groove


def test_a_router_names_its_bit():
    plate = box(0, 0, 40, 40).difference(box(10, 10, 12, 12))  # a 2 mm hole: the 3.175 mm bit cannot enter
    report = Report(path="", format="")
    router = load_profile("router-3.175mm-plywood")
    assert check_cut_pattern(plate, box(0, 0, 40, 40), box(0, 0, 40, 40), router, stroke=3.0, report=report) == 0
    assert "narrower than the 3.175 mm bit (tool_diameter_mm of router profile" in report.findings[0].message
    assert "a bit of 2 mm or narrower" in report.findings[0].message


def test_half_the_pattern_is_enough():
    plate = box(0, 0, 40, 40).difference(box(5, 5, 6, 6)).difference(box(20, 20, 21, 21))
    after = box(0, 0, 40, 40).difference(box(20, 20, 21, 21))  # one of two equal holes filled: half kept
    report = Report(path="", format="")
    assert check_pattern_kept(report, plate, after, box(0, 0, 40, 40), limit_mm=1.2, limit="1.2 mm") == 0.5
    assert report.ok
