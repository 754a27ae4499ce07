"""Errors about one parameter carry its name (``err.param``), for front ends to point at the field."""

from __future__ import annotations

import pytest
from shapely.geometry import box

from fabtiles import ParameterError


def _param(make):
    with pytest.raises(ParameterError) as info:
        make()
    return info.value.param


def test_laser_options():
    from fabtiles.geometry.cut_plan import CutOptions, plan_cut

    plate = box(0, 0, 40, 40)

    def laser(**kw):
        return lambda: plan_cut(plate, plate, CutOptions.of(profile="laser-3mm-plywood", **kw))

    assert _param(laser(stroke=0.5)) == "stroke"
    assert _param(laser(stroke=1.5, kerf_mm=2)) == "kerf_mm"
    assert _param(laser(fill_small_holes=1)) == "fill_small_holes"
    assert _param(laser(mode="score")) == "centrelines"
    assert _param(laser(mode="etch")) == "mode"
    assert _param(lambda: plan_cut("plate", plate, CutOptions.of(profile="laser-3mm-plywood"))) == "region"


def test_export_and_sheet_options():
    from fabtiles.export.formats import format_of
    from fabtiles.geometry.sheet import layout_sheet
    from fabtiles.geometry.stack import resolve_stack
    from fabtiles.making import export_region

    plate = box(0, 0, 40, 40)
    assert _param(lambda: format_of("t.png")) == "path"
    assert _param(lambda: export_region("t.dxf", region=plate, outline=plate, style="relief")) == "style"
    assert _param(lambda: layout_sheet([], "laser-3mm-plywood")) == "tiles"
    assert _param(lambda: layout_sheet([(plate, plate)], "laser-3mm-plywood", centrelines=[])) == "centrelines"
    assert _param(lambda: resolve_stack("fdm-0.4mm", style="deboss", deboss_mm=5)) == "deboss_mm"


def test_seamless_and_tile():
    from fabtiles import HexPacking, Star, Tile, seamless_fit

    assert _param(lambda: seamless_fit("circle", 100, 10)) == "outline"
    assert _param(lambda: seamless_fit("square", 100, 10, packing="hex")) == "outline"
    assert _param(lambda: seamless_fit("square", 100, 10, packing="triangle")) == "packing"
    pack = HexPacking(radius=10, motif=Star.preset("table3-3"))
    assert _param(lambda: Tile("square", 20, pack, frame=10)) == "frame"
    assert _param(lambda: Tile("square", 100, pack, stroke=11)) == "stroke"
    assert _param(lambda: Tile("rectangle", 100, pack)) == "size"
    assert _param(lambda: Tile("circle", 100, pack, corner_radius=2)) == "corner_radius"
    assert _param(lambda: Tile("oval", 100, pack)) == "outline"
