"""STEP export (issue 5): one valid closed solid, read back, volume within 0.5 % of area x height."""

from __future__ import annotations

import pytest
import shapely
from mesh_helpers import B, D, H, T, solids_of, step_bounds
from shapely.geometry import box

from fabtiles import FabricationError, ParameterError, ProfileError, Star
from fabtiles.geometry.tile import Tile
from fabtiles.pattern.packing import HexPacking

pytest.importorskip("OCP")
step = pytest.importorskip("fabtiles.export.step")


@pytest.mark.parametrize("outline", ["square", "hexagon"])
@pytest.mark.parametrize("style", ["relief", "pierced", "deboss"])
def test_step_styles(tmp_path, outline, style):
    from OCP.BRepCheck import BRepCheck_Analyzer

    tile = Tile(outline, 30, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0)
    region, shape = tile.region(), tile.outline_shape()
    path = tmp_path / "t.step"
    report = step.write_step(path, region=region, outline=shape, profile="fdm-0.4mm", style=style, stroke=1.0)
    assert report.stats["solids"] == 1
    back = step.read_step(path)
    assert solids_of(back) == 1
    assert BRepCheck_Analyzer(back).IsValid()
    expected = {"relief": shape.area * B + region.area * H, "pierced": region.area * T,
                "deboss": shape.area * B - region.area * D}[style]
    assert step._volume(back) == pytest.approx(expected, rel=0.005)
    top = {"relief": B + H, "pierced": T, "deboss": B}[style]
    x0, y0, z0, x1, y1, z1 = step_bounds(back)
    assert z0 == pytest.approx(0, abs=1e-3) and z1 == pytest.approx(top, abs=1e-3)
    assert x0 >= -1e-3 and y0 >= -1e-3
    assert x1 <= shape.bounds[2] + 1e-3 and y1 <= shape.bounds[3] + 1e-3
    assert "SI_UNIT(.MILLI.,.METRE.)" in path.read_text().replace(" ", "")


@pytest.mark.parametrize("preset", Star.presets())
def test_step_every_preset_relief(tmp_path, preset):
    tile = Tile("square", 24, HexPacking(8, Star.preset(preset)), frame=2, stroke=1.0)
    region, outline = tile.region(), tile.outline_shape()
    step.write_step(tmp_path / "t.step", region=region, outline=outline, profile="fdm-0.4mm")
    back = step.read_step(tmp_path / "t.step")
    assert solids_of(back) == 1
    assert step._volume(back) == pytest.approx(outline.area * B + region.area * H, rel=0.005)


def test_step_pierced_in_pieces_gives_one_solid_each(tmp_path):
    region = shapely.MultiPolygon([box(1, 1, 4, 4), box(6, 6, 9, 9)])
    report = step.write_step(tmp_path / "t.step", region=region, outline=box(0, 0, 10, 10),
                             profile="fdm-0.4mm", style="pierced")
    assert report.stats["solids"] == 2
    assert [f.code for f in report.findings] == ["loose_part"]
    assert solids_of(step.read_step(tmp_path / "t.step")) == 2


def test_prism_volume_matches_occt_gauss_kronrod():
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    from fabtiles.export.mesh import _snapped
    from fabtiles.geometry.stack import resolve_stack

    region = box(0, 0, 20, 10).difference(box(2, 2, 18, 8)).union(box(5, 2, 6, 8))
    r, o = _snapped(region, box(0, 0, 20, 10))
    cov = step._stack_coverage("deboss", r, o, resolve_stack("fdm-0.4mm", style="deboss"))
    solid, _ = step.solid_from_coverage(cov)
    props = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(solid, props, 1e-9)
    assert step._prism_volume(solid) == pytest.approx(props.Mass(), rel=1e-6)
    assert step._prism_volume(solid) == pytest.approx(200 * B - region.area * D, rel=1e-9)


@pytest.mark.parametrize("kwargs,exc,msg", [
    (dict(base_mm=0), ParameterError, "base_mm must be a finite number > 0"),
    (dict(style="deboss", deboss_mm=2.5), ParameterError, "deboss_mm must be smaller than base_mm"),
    (dict(profile="no-such-printer"), ProfileError, "does not exist"),
])
def test_step_bad_input_no_file(tmp_path, kwargs, exc, msg):
    tile = Tile("square", 24, HexPacking(8, Star.preset("table3-3")), frame=2, stroke=1.0)
    kwargs = {"profile": "fdm-0.4mm", **kwargs}
    with pytest.raises(exc, match=msg):
        step.write_step(tmp_path / "t.step", region=tile.region(), outline=tile.outline_shape(), **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_step_strict_findings_no_file(tmp_path):
    strict = tmp_path / "strict.toml"
    strict.write_text('kind = "printer"\n[printer]\nstrict = true\nbed_mm = [10, 10]\n')
    with pytest.raises(FabricationError, match="bed_size"):
        step.write_step(tmp_path / "t.step", region=box(1, 1, 19, 19), outline=box(0, 0, 20, 20), profile=strict)
    assert [p.name for p in tmp_path.iterdir()] == ["strict.toml"]
