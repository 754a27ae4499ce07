"""Design files (docs/design-files.md): loading, overrides and every error."""

from pathlib import Path

import pytest

from fabtiles import DesignError, Star
from fabtiles.designs.design_file import (
    Design,
    build_tile,
    design_from_text,
    load_design,
    parse_override,
)
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking, SquarePacking

SAMPLES = sorted((Path(__file__).resolve().parents[2] / "samples").glob("*.toml"))

BASE = """
[motif]
preset = "table3-3"

[packing]
kind = "hex"
radius = 12.5

[tile]
outline = "square"
size = [150, 150]
frame = 5.0
stroke = 1.0
"""


def write(tmp_path, text, name="demo.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("path", SAMPLES, ids=[p.stem for p in SAMPLES])
def test_samples_load_and_build(path):
    design = load_design(path)
    assert design.name == path.stem
    tile = build_tile(design)
    assert isinstance(tile, TileGeometry)


def test_spec_example_design(tmp_path):
    text = """
[motif]
n = 12
radii = [123, 85, 178]
alpha = 23
spr = -7
special = 2

[packing]
kind = "hex"
radius = 12.5
outline_circles = false
gap_motif = { n = 6, radii = [0.5, 1.0] }

[tile]
outline = "square"
size = [150, 150]
frame = 5.0
stroke = 1.0

[output]
formats = ["dxf", "svg", "stl", "3mf", "step"]
laser_profile = "laser-3mm-plywood"
printer_profile = "fdm-0.4mm"
"""
    d = load_design(write(tmp_path, text, "spec.toml"))
    assert isinstance(d, Design) and d.name == "spec"
    assert d.motif.star() == Star.preset("table3-3")
    assert d.output.formats == ("dxf", "svg", "stl", "3mf", "step")
    assert d.output.laser_mode is None and d.output.print_style is None  # the profiles decide
    tile = d.build_tile()
    assert tile.pattern == HexPacking(radius=12.5, motif=Star.preset("table3-3"))
    assert (tile.frame, tile.stroke, tile.size) == (5.0, 1.0, (150.0, 150.0))


def test_designs_are_frozen(tmp_path):
    d = load_design(write(tmp_path, BASE))
    with pytest.raises(AttributeError):
        d.name = "other"


def test_preset_with_overrides_and_gap_motif_as_preset():
    d = design_from_text(BASE.replace('preset = "table3-3"', 'preset = "table3-3"\nrotation = 15') + "\n", name="x")
    assert d.motif.star() == Star.preset("table3-3", rotation=15)
    d = design_from_text(
        BASE.replace("radius = 12.5", 'radius = 12.5\nkind = "square"\ngap_motif = "table1-part1"').replace(
            'kind = "hex"\n', ""
        )
    )
    tile = d.build_tile()
    assert isinstance(tile.pattern, SquarePacking)
    assert tile.pattern.gap_motif == Star.preset("table1-part1")


def test_single_motif_without_packing():
    d = design_from_text('[motif]\npreset = "table2-left"\n[tile]\noutline = "circle"\nsize = 80\n')
    assert d.packing is None
    assert d.build_tile().pattern == Star.preset("table2-left")


def test_output_name_and_seamless():
    d = design_from_text(
        BASE.replace("radius = 12.5", "radius = 14\nseamless = true")
        .replace('outline = "square"', 'outline = "rectangle"')
        .replace("size = [150, 150]", "size = [150, 100]")
        + '[output]\nname = "fitted"\n',
        name="ignored",
    )
    assert d.name == "fitted"
    assert d.packing.radius == pytest.approx(15.0)
    assert d.tile_spec.size == pytest.approx((150, 2 * 2 * 3**0.5 * 15))  # k = 2 periods up


def test_overrides_are_applied_before_validation(tmp_path):
    path = write(tmp_path, BASE)
    d = load_design(
        path,
        overrides=[
            "tile.size=[200, 100]",
            "tile.outline=rectangle",
            "packing.gap_motif={ n = 8, radii = [0.5, 1.0] }",
            "output.formats=['svg']",
        ],
    )
    assert d.tile_spec.size == (200.0, 100.0) and d.tile_spec.outline == "rectangle"
    assert d.build_tile().pattern.gap_motif.n == 8
    with pytest.raises(DesignError, match=r"unknown key 'sise' in \[tile\]; did you mean 'size'\?"):
        load_design(path, overrides=["tile.sise=3"])
    with pytest.raises(DesignError, match=r"stroke must be > 0 and <= 12.5 mm"):
        load_design(path, overrides=["tile.stroke=20"])


@pytest.mark.parametrize(
    "item, match",
    [
        ("tile.size", r"--set expects section.key=value, got 'tile.size'"),
        ("size=3", r"--set expects section.key=value \(like tile.size=\[200,200\]\), got 'size=3'"),
        ("tile.size=[1,", r"--set tile.size: '\[1,' is not a TOML value"),
    ],
)
def test_bad_overrides(item, match):
    with pytest.raises(DesignError, match=match):
        parse_override(item)


def test_override_into_a_value_is_an_error():
    with pytest.raises(DesignError, match=r"--set tile.size.x: tile.size is not a table"):
        design_from_text(BASE, overrides=["tile.size.x=1"])


def test_parse_override_values():
    assert parse_override("packing.outline_circles=true") == (["packing", "outline_circles"], True)
    assert parse_override("motif.radii = [1, 2.5]") == (["motif", "radii"], [1, 2.5])
    assert parse_override('output.name="a b"') == (["output", "name"], "a b")


def test_unreadable_and_invalid_files(tmp_path):
    missing = tmp_path / "nope.toml"
    with pytest.raises(DesignError, match=r"cannot read design file '.*nope.toml': No such file"):
        load_design(missing)
    with pytest.raises(DesignError, match=r"cannot read design file '.*': Is a directory"):
        load_design(tmp_path)
    bad = tmp_path / "bin.toml"
    bad.write_bytes(b"\xff\xfe\x00")
    with pytest.raises(DesignError, match=r"cannot read design file '.*bin.toml'"):
        load_design(bad)
    with pytest.raises(DesignError, match=r"broken.toml: not valid TOML"):
        load_design(write(tmp_path, "[motif\n", "broken.toml"))


@pytest.mark.parametrize(
    "change, match",
    [
        (
            ("[tile]", "[tyle]"),
            r"unknown section 'tyle' in the design; did you mean 'tile'\? "
            r"\(valid sections: motif, packing, tile, output, colour, surface\)",
        ),
        (
            ('preset = "table3-3"', 'preset = "table3-3"\nradius = 3'),
            r"unknown key 'radius' in \[motif\]; did you mean "
            r"'radii'\? \(valid keys: preset, n, radii, alpha, spr, special, rotation\)",
        ),
        (("radius = 12.5", "raduis = 12.5"), r"unknown key 'raduis' in \[packing\]; did you mean 'radius'\?"),
        (("stroke = 1.0", "strok = 1.0"), r"unknown key 'strok' in \[tile\]; did you mean 'stroke'\?"),
        (
            ("radius = 12.5", "radius = 12.5\ngap_motif = { n = 6, radis = [1, 2] }"),
            r"unknown key 'radis' in \[packing\] gap_motif; did you mean 'radii'\?",
        ),
        (("", "[output]\nformat = ['svg']"), r"unknown key 'format' in \[output\]; did you mean 'formats'\?"),
        (("", "[output]\nzzz = 1"), r"unknown key 'zzz' in \[output\] \(valid keys: formats, laser_profile"),
        (('preset = "table3-3"', 'preset = "table9"'), r"\[motif\] preset 'table9' is unknown"),
        (
            ('preset = "table3-3"', 'preset = "table3-33"'),
            r"\[motif\] preset 'table3-33' is unknown; did you mean 'table3-3'\? \(presets: table1-part1, ",
        ),
        (
            ("radius = 12.5", 'radius = 12.5\ngap_motif = "tabel1-part1"'),
            r"\[packing\] gap_motif preset 'tabel1-part1' is unknown; did you mean 'table1-part1'\?",
        ),
        (
            ('outline = "square"', 'outline = "sqare"'),
            r"\[tile\] outline = 'sqare' is not valid \(did you mean 'square'\?\), must be one of: square, ",
        ),
        (
            ("", "[output]\nlaser_mode = 'pirced'"),
            r"\[output\] laser_mode = 'pirced' is not valid \(did you mean 'pierced'\?\)",
        ),
        (
            ("", "[output]\nformats = ['dxff']"),
            r"\[output\] formats: 'dxff' is not a valid format \(did you mean 'dxf'\?\)",
        ),
        (('preset = "table3-3"', "n = 2\nradii = [1, 2]"), r"\[motif\] n must be an integer >= 3 and <= 120, got 2"),
        (
            ('preset = "table3-3"', "n = 6"),
            r"\[motif\] needs preset = \"...\" or the parameters n and radii \(missing: radii\)",
        ),
        (('preset = "table3-3"', "preset = 3"), r"\[motif\] preset must be a string, got 3"),
        (
            ('preset = "table3-3"', 'preset = "table3-3"\nspecial = 7'),
            r"\[motif\] special must be an integer >= 2 and <= 3, got 7",
        ),
        (
            ('kind = "hex"', 'kind = "triangle"'),
            r"\[packing\] kind = 'triangle' is not valid, must be one of: hex, square",
        ),
        (("radius = 12.5", "radius = -1"), r"\[packing\] radius must be a finite number > 0, got -1"),
        (("radius = 12.5", 'radius = "big"'), r"\[packing\] radius must be a number of mm > 0, got 'big'"),
        (("radius = 12.5", "radius = 12.5\nfill = 2"), r"\[packing\] fill must be a finite number > 0 and <= 1, got 2"),
        (
            ("radius = 12.5", "radius = 12.5\noutline_circles = 1"),
            r"\[packing\] outline_circles must be true or false, got 1",
        ),
        (
            ("radius = 12.5", "radius = 12.5\ngap_motif = 3"),
            r"\[packing\] gap_motif must be a table or a preset name, got 3",
        ),
        (
            ('outline = "square"', 'outline = "oval"'),
            r"\[tile\] outline = 'oval' is not valid, must be one of: square, rectangle, hexagon, circle",
        ),
        (("size = [150, 150]", "size = [150, 100]"), r"\[tile\] size of a square is one number"),
        (("size = [150, 150]", ""), r"\[tile\] needs size"),
        (("frame = 5.0", "frame = 80"), r"\[tile\] tile size \(150, 150\) mm is too small for frame 80 mm"),
        (("stroke = 1.0", "stroke = true"), r"\[tile\] stroke must be a number of mm > 0, got True"),
        (("stroke = 1.0", "stroke = 0"), r"\[tile\] stroke must be a finite number > 0, got 0"),
        (
            ("stroke = 1.0", 'join = "zigzag"'),
            r"\[tile\] join = 'zigzag' is not valid, must be one of: miter, round, bevel",
        ),
        (
            ("", "[output]\nformats = ['svg', 'png']"),
            r"\[output\] formats: 'png' is not a valid format, must be one of: dxf, svg, lbrn2, stl, 3mf, step",
        ),
        (("", "[output]\nformats = []"), r"\[output\] formats must be a non-empty list"),
        (
            ("", "[output]\nlaser_mode = 'etch'"),
            r"\[output\] laser_mode = 'etch' is not valid, must be one of: pierced, score, engrave",
        ),
        (
            ("", "[output]\nprint_style = 'flat'"),
            r"\[output\] print_style = 'flat' is not valid, must be one of: relief, pierced, deboss",
        ),
        (("", "[output]\nlaser_profile = 3"), r"\[output\] laser_profile must be a profile name or path, got 3"),
        (("", "[output]\nname = '../evil'"), r"\[output\] name must be a plain file name"),
        (("[motif]", "output = 3\n[motif]"), r"\[output\] must be a table, got 3"),
        (
            ("radius = 12.5", "radius = 12.5\nseamless = true"),
            r"\[tile\] a square tile cannot be seamless with the hex packing",
        ),
    ],
)
def test_design_errors(tmp_path, change, match):
    old, new = change
    text = BASE.replace(old, new) if old else BASE + new + "\n"
    path = write(tmp_path, text, "bad.toml")
    with pytest.raises(DesignError, match=match) as info:
        load_design(path)
    assert str(info.value).startswith(str(path))


@pytest.mark.parametrize(
    "key, name, match",
    [
        (
            "laser_profile",
            "laser-3mm-plywod",
            r"\[output\] laser_profile: profile 'laser-3mm-plywod' does not exist "
            r"\(did you mean 'laser-3mm-plywood'\?\)",
        ),
        (
            "printer_profile",
            "fdm-0.4mn",
            r"\[output\] printer_profile: profile 'fdm-0.4mn' does not exist "
            r"\(did you mean 'fdm-0.4mm'\?\)",
        ),
        (
            "printer_profile",
            "laser-3mm-plywood",
            r"\[output\] printer_profile: profile 'laser-3mm-plywood' is a laser "
            r"profile, but a printer profile is needed",
        ),
    ],
)
def test_an_unknown_profile_names_its_key(tmp_path, key, name, match):
    from fabtiles import ProfileError
    from fabtiles.designs.design_file import profile_of

    path = write(tmp_path, BASE + f"[output]\n{key} = {name!r}\n", "p.toml")
    with pytest.raises(ProfileError, match=match) as info:
        profile_of(load_design(path), key.split("_")[0])
    assert str(info.value).startswith(str(path)) and info.value.param == f"output.{key}"


def test_missing_sections():
    with pytest.raises(DesignError, match=r"the design needs a \[motif\] section"):
        design_from_text("[tile]\nsize = 10\n")
    with pytest.raises(DesignError, match=r"the design needs a \[tile\] section"):
        design_from_text('[motif]\npreset = "table3-3"\n')


def test_build_tile_with_a_subclass():
    class MyTile(TileGeometry):
        pass

    d = design_from_text(BASE)
    assert type(build_tile(d, tile_cls=MyTile)) is MyTile


def test_print_heights_override_the_profile():
    design = design_from_text(BASE + "[output]\nbase_mm = 3\nrelief_mm = 0.6\n")
    assert design.output.heights() == {"base_mm": 3.0, "relief_mm": 0.6}
    assert design_from_text(BASE).output.heights() == {}


@pytest.mark.parametrize("value", ["0", "-1", "1001", "nan", "inf", '"2"', "true"])
@pytest.mark.parametrize("key", ["base_mm", "relief_mm", "pierced_mm", "deboss_mm"])
def test_bad_print_heights(key, value):
    with pytest.raises(DesignError, match=rf"\[output\] {key} must be a number of mm > 0 and <= 1000, got"):
        design_from_text(BASE + f"[output]\n{key} = {value}\n")


def test_a_value_over_its_limit_shows_the_digits_that_tell_them_apart():
    """Rounding must not hide why a value is refused: 8.0004 mm is over the 8 mm radius, though both read 8."""
    from fabtiles import LimitError
    from fabtiles.machines.limits import CLI_LIMITS, check_size

    with pytest.raises(DesignError, match=r"stroke must be > 0 and <= 12\.5 mm \(the packing radius\), got 12\.50004$"):
        design_from_text(BASE.replace("stroke = 1.0", "stroke = 12.50004"))
    over = CLI_LIMITS.max_size_mm + 0.5
    with pytest.raises(
        LimitError,
        match=rf"the tile is {over:g} x 100 mm, larger than the limit of "
        rf"{CLI_LIMITS.max_size_mm:g} mm",
    ):
        check_size(over, 100, CLI_LIMITS)
