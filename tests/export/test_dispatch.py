import pytest

import fabtiles as ft
from fabtiles.export.formats import format_of
from fabtiles.making import export_region


def _empty_tile():
    # A 6 mm tile whose only motif's strokes all lie outside it (a hexagon of radius 5.2).
    return ft.Tile("square", 6, ft.HexPacking(radius=6, motif=ft.Star(n=3, radii=(1, 1))), stroke=1)


@pytest.mark.parametrize("fmt", ["dxf", "svg", "stl", "3mf", "step"])
def test_a_tile_without_material_is_an_error_not_a_file(tmp_path, fmt):
    tile = _empty_tile()
    assert tile.region().is_empty
    with pytest.raises(ft.FabricationError, match=r"the tile holds no material: .* add a frame"):
        tile.export(tmp_path / f"t.{fmt}")
    assert list(tmp_path.iterdir()) == []


def test_unknown_suffix_and_option(tmp_path):
    tile = ft.Tile("square", 30, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-3")), frame=2)
    with pytest.raises(
        ft.ParameterError,
        match=r"'png' is not a valid output format .* must be one of: dxf, svg, lbrn2, stl, 3mf, step",
    ):
        tile.export(tmp_path / "t.png")
    with pytest.raises(
        ft.ParameterError, match=r"'style' is not a valid option for .dxf files, must be one of: mode, dxf_version"
    ):
        tile.export(tmp_path / "t.dxf", style="relief")
    with pytest.raises(
        ft.ParameterError, match=r"'kerf_mm' is not a valid option for .stl files, must be one of: style"
    ):
        tile.export(tmp_path / "t.stl", kerf_mm=0.1)
    with pytest.raises(ft.ProfileError, match=r"'fdm-0.4mm' is a printer profile, but a laser profile is needed"):
        tile.export(tmp_path / "t.dxf", profile="fdm-0.4mm")
    assert list(tmp_path.iterdir()) == []


def test_format_of_is_case_insensitive():
    assert format_of("A.STEP").name == "step" and format_of("x.3MF").name == "3mf"


def test_export_region_defaults_to_bundled_profiles(tmp_path):
    from shapely.geometry import box

    plate = box(0, 0, 40, 40).difference(box(10, 10, 30, 30))
    report = export_region(tmp_path / "p.dxf", region=plate, outline=box(0, 0, 40, 40), stroke=10)
    assert report.format == "dxf" and (tmp_path / "p.dxf").exists()
