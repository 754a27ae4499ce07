"""Colours (issue 33): parsing, the palettes, a design's [colour] section and its errors."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from designs import design_toml

from fabtiles import DesignError, ParameterError
from fabtiles.designs.colour import MAX_MATERIALS, PALETTES, Colour, check_materials, colouring, letters, parse_colour
from fabtiles.designs.design_file import design_from_text
from fabtiles.geometry.stack import resolve_stack

DOCS = Path(__file__).resolve().parents[2] / "docs"

BASE = design_toml(radius=12.5, stroke=None)


def test_colours_parse_by_hex_and_css_name():
    assert parse_colour("#1F3B73") == Colour("#1f3b73", "1f3b73")
    assert parse_colour("navy") == Colour("#000080", "navy")
    assert parse_colour("#000080").name == "navy"  # a CSS colour's hex takes its name
    assert parse_colour("  Teal ") == Colour("#008080", "teal")
    white = parse_colour("white")
    assert white.srgb == (1.0, 1.0, 1.0) and white.linear == pytest.approx((1.0, 1.0, 1.0))


@pytest.mark.parametrize(
    "bad, match",
    [
        ("#12345", r"colour must be #rrggbb or a CSS colour name \(like \"navy\"\), got '#12345'"),
        ("#ggggggg", r"colour must be #rrggbb"),
        (42, r"colour must be #rrggbb or a CSS colour name"),
        ("", r"colour must be #rrggbb or a CSS colour name"),
        ("nav", r"colour 'nav' is not a CSS or palette colour name \(did you mean 'navy'\?\); give #rrggbb"),
        (
            "qqq",
            r"colour 'qqq' is not a CSS or palette colour name; give #rrggbb, a CSS name like \"navy\" or a "
            r"palette's like \"cobalt\"",
        ),
        ("lapiz", r"colour 'lapiz' is not a CSS or palette colour name \(did you mean 'lapis'\?\)"),
        ("band", r"colour 'band' names a part's colour, which only a face class takes"),
        (
            "iznik.lapis",
            r"colour 'iznik.lapis': palette 'iznik' has no colour 'lapis'; its colours: white, navy, "
            r"cobalt, turquoise, bole, green, black, sky",
        ),
    ],
)
def test_bad_colours_are_refused(bad, match):
    with pytest.raises(ParameterError, match=match):
        parse_colour(bad)


def test_palette_names_read_in_the_design_palette_first():
    iznik = PALETTES["iznik"]
    assert parse_colour("cobalt", palette="iznik") == iznik.faces[0]
    assert parse_colour("white", palette=iznik) == iznik.band  # the palette's white, not CSS #ffffff
    assert parse_colour("white", palette="mamluk").hex == "#ffffff"  # mamluk has no white: CSS
    assert parse_colour("#1e4fa0", palette="iznik").name == "cobalt"  # a hex takes the palette's name
    assert parse_colour("lapis", palette="iznik") == PALETTES["mamluk"].faces[0]  # one palette's: no doubt
    assert parse_colour("zellige.cobalt", palette="iznik") == PALETTES["zellige"].faces[0]
    assert parse_colour("cobalt").name == "cobalt"  # no palette given: accepted, settled by the design's


def test_a_name_of_several_palettes_not_the_designs_is_asked_by_palette():
    with pytest.raises(
        ParameterError,
        match=r"faces.C 'cobalt' is a colour of several palettes, not of this "
        r"design's \(mamluk\); name one: zellige.cobalt, iznik.cobalt, "
        r"haft-rangi.cobalt",
    ):
        colouring(palette_name="mamluk", faces={"C": "cobalt"}, classes=("A", "B", "C"))


def test_band_and_base_give_a_class_the_part_colour():
    c = colouring(palette_name="iznik", band="#ffeedd", faces={"A": "band", "B": "Base"}, classes=("A", "B", "C"))
    assert c.face("A") == c.band and c.band.hex == "#ffeedd"
    assert c.face("B") == c.base == PALETTES["iznik"].base
    assert [m.hex for m in c.materials()] == [c.base.hex, c.band.hex, PALETTES["iznik"].faces[2].hex]


def test_one_value_has_one_name():
    # C given the base's value in hex digits is named as the base is: the class line and the part agree
    c = colouring(palette_name="zellige", faces={"C": "#2B2B2B", "B": "#1d4e89"}, classes=("A", "B", "C"))
    assert c.face("C").name == c.base.name == "black" and c.face("B").name == "cobalt"


def test_letters_run_past_z():
    assert letters(0) == ()
    assert letters(27)[:3] == ("A", "B", "C") and letters(27)[25:] == ("Z", "AA")


def test_colouring_takes_the_palette_then_the_given_colours():
    c = colouring(palette_name="mamluk", classes=("A", "B", "C"))
    pal = PALETTES["mamluk"]
    assert c.band == pal.band and c.base == pal.base
    assert [v for _, v in c.faces] == list(pal.faces[:3])
    c = colouring(palette_name="mamluk", band="white", faces={"B": "#26428b"}, classes=("A", "B", "C"))
    assert c.band.hex == "#ffffff"
    # B given A's colour by value: one material for both
    assert c.face("B").hex == c.face("A").hex
    # C takes the palette's third colour, black: the base's, so one material again
    assert pal.faces[2].hex == pal.base.hex
    assert [m.hex for m in c.materials()] == [pal.base.hex, "#ffffff", pal.faces[0].hex]
    assert [m.hex for m in c.materials(base=False)] == ["#ffffff", pal.faces[0].hex, pal.faces[2].hex]


def test_more_classes_than_colours_reuse_the_palette():
    c = colouring(palette_name="zellige", classes=letters(8))
    assert c.face("G") == c.face("A") and c.face("H") == c.face("B")


def test_colouring_refuses_a_letter_the_design_lacks():
    with pytest.raises(ParameterError, match=r"face class 'D' is not one of this design's: A, B, C"):
        colouring(faces={"D": "red"}, classes=("A", "B", "C"))


def test_colouring_refuses_an_unknown_palette():
    with pytest.raises(
        ParameterError,
        match=r"palette 'iznk' is not known \(did you mean 'iznik'\?\), must be one "
        r"of: zellige, iznik, mamluk, alhambra, haft-rangi",
    ):
        colouring(palette_name="iznk")


def test_more_than_sixteen_materials_are_refused():
    many = [Colour(f"#0000{k:02x}", str(k)) for k in range(MAX_MATERIALS + 1)]
    check_materials(many[:MAX_MATERIALS])
    with pytest.raises(
        ParameterError,
        match=r"the print has 17 distinct colours, more than the 16 filaments a "
        r"slicer takes; give some face classes the same colour",
    ):
        check_materials(many)


def test_the_palette_table_in_the_docs_is_the_codes():
    text = (DOCS / "colours.md").read_text(encoding="utf-8")
    block = re.search(r"<!-- palettes -->\n(.*?)<!-- /palettes -->", text, re.S).group(1)
    rows = block.strip().splitlines()[2:]
    assert len(rows) == len(PALETTES)
    for row, p in zip(rows, PALETTES.values(), strict=True):
        faces = ", ".join(f"{c.name} `{c.hex}`" for c in p.faces)
        assert row == (
            f"| `{p.name}` | {p.band.name} `{p.band.hex}` | {p.base.name} `{p.base.hex}` | {faces} | {p.source} |"
        )
    for p in PALETTES.values():  # names are file names: distinct within a palette, one per value
        names = {c.hex: c.name for c in (p.band, p.base, *p.faces)}
        assert len(set(names.values())) == len(names)


def test_a_design_reads_its_colour_section():
    d = design_from_text(
        BASE + '[colour]\nby = "shape"\npalette = "iznik"\nband_colour = "white"\n'
        '[colour.faces]\nB = "#1e4fa0"\nA = "navy"\n'
    )
    assert d.colour.given and d.colour.by == "shape" and d.colour.palette == "iznik"
    assert d.colour.band_colour == "white" and d.colour.faces == (("A", "navy"), ("B", "#1e4fa0"))
    c = d.colour.colouring(("A", "B", "C"))
    # navy and white are Iznik's own (the base's and the bands'): the names the summary prints
    assert c.face("A") == PALETTES["iznik"].base and c.band == PALETTES["iznik"].band
    plain = design_from_text(BASE)
    assert not plain.colour.given and plain.colour.by == "none"


@pytest.mark.parametrize(
    "section, match",
    [
        (
            '[colour]\npalette = "azulejo"\n',
            r"\[colour\] palette = 'azulejo' is not valid, must be one of: zellige, "
            r"iznik, mamluk, alhambra, haft-rangi",
        ),
        ('[colour]\nby = "colour"\n', r"\[colour\] by = 'colour' is not valid, must be one of: none, shape"),
        ('[colour]\nband_colour = "#12"\n', r"\[colour\] band_colour must be #rrggbb or a CSS colour name"),
        (
            '[colour]\nbase_colour = "blu"\n',
            r"\[colour\] base_colour 'blu' is not a CSS or palette colour name \(did you mean "
            r"'blue'\?\)",
        ),
        ('[colour]\nfaces = "red"\n', r"\[colour.faces\] must be a table of class letters to colours"),
        ('[colour.faces]\nstar = "red"\n', r"\[colour.faces\] key 'star' must be a class letter"),
        ('[colour.faces]\nA = "reddish"\n', r"\[colour.faces\] A 'reddish' is not a CSS or palette colour name"),
        ('[colour]\nbands = "red"\n', r"unknown key 'bands' in \[colour\]"),
    ],
)
def test_bad_colour_sections_name_the_key(section, match):
    with pytest.raises(DesignError, match=match):
        design_from_text(BASE + section)


@pytest.mark.parametrize(
    "inset, match",
    [
        (-0.1, r"mosaic_inset_mm must be a finite number >= 0 and <= 1000, got -0.1"),
        (1.2, r"mosaic_inset_mm must be smaller than relief_mm \(the bands stand 1.2 mm above the plate\), got 1.2"),
    ],
)
def test_the_mosaic_inset_stays_under_the_relief(inset, match):
    with pytest.raises(ParameterError, match=match):
        resolve_stack("fdm-0.4mm", style="mosaic", relief_mm=1.2, mosaic_inset_mm=inset)


def test_the_inset_is_a_mosaics_alone():
    assert resolve_stack("fdm-0.4mm", style="mosaic", mosaic_inset_mm=0.4).inset == 0.4
    assert resolve_stack("fdm-0.4mm", style="relief", mosaic_inset_mm=0.4).inset == 0.0


def test_a_coloured_relief_takes_the_base_and_band_colours():
    """Face colours are the mosaic's alone; a relief's plate and bands take the base and band colours."""
    from fabtiles.making.models import BuildOptions, Models

    plain = design_from_text(BASE)
    coloured = design_from_text(BASE + '[colour]\npalette = "mamluk"\n')
    parts = {}
    for name, d in (("plain", plain), ("coloured", coloured)):
        model = Models(d.build_tile(), BuildOptions.of_design(d)).print
        parts[name] = {n: p.colour for n, p in model.parts.items()}
    pal = PALETTES["mamluk"]
    # named as a mosaic's parts are, by colour and what each holds
    assert parts["coloured"] == {
        f"{pal.base.name} (base)": pal.base.linear,
        f"{pal.band.name} (bands)": pal.band.linear,
    }
    assert parts["plain"]["pattern"] != pal.band.linear  # no [colour]: the parts' own display colours


@pytest.mark.parametrize("style, inlay", [("relief", False), ("deboss", True)])
def test_a_coloured_relief_3mf_carries_its_colours_as_a_mosaic_does(tmp_path, style, inlay):
    """In the 3MF: one part per colour, named by it, on extruders 1 and 2 (no display colours: docs/slicers.md)."""
    from fabtiles.export.threemf import read_3mf
    from fabtiles.making import build_design

    output = f'[output]\nformats = ["3mf"]\nprint_style = "{style}"\ninlay = {str(inlay).lower()}\n'
    design = design_from_text(BASE + output + '[colour]\nbase_colour = "navy"\nband_colour = "white"\n', name="c")
    build_design(design, tmp_path)
    parts = read_3mf(tmp_path / "c.3mf")
    assert [(name, p.extruder) for name, p in parts.items()] == [("navy (base)", 1), ("white (bands)", 2)]
    assert b"basematerials" not in (tmp_path / "c.3mf").read_bytes()


def test_the_export_api_takes_colours(tmp_path):
    import fabtiles as ft
    from fabtiles.export.threemf import read_3mf

    tile = ft.Tile("square", 60, ft.HexPacking(radius=12.5, motif=ft.Star.preset("table3-3")), frame=3, stroke=1.2)
    tile.export(
        tmp_path / "a.3mf", style="mosaic", colours=ft.Colours(by="shape", palette="iznik", faces={"A": "#000080"})
    )
    # CSS navy (#000080) for A beside Iznik's own navy base: two colours, two names, two parts
    assert list(read_3mf(tmp_path / "a.3mf")) == ["navy (base)", "white (bands)", "navy-000080 (A)", "turquoise (B)"]
    tile.export(tmp_path / "b.3mf", style="mosaic", colours={"by": "shape", "palette": "mamluk"})
    assert list(read_3mf(tmp_path / "b.3mf"))[1] == "gold (bands)"
    report = tile.export(tmp_path / "k.dxf", mode="inlay", colours=ft.Colours(by="shape", palette="iznik"))
    assert [Path(p).name for p in report.stats["files"]] == [
        "k-lattice.dxf",
        "k-pieces-cobalt.dxf",
        "k-pieces-turquoise.dxf",
    ]
    with pytest.raises(
        ParameterError,
        match=r"colours must be a fabtiles.Colours \(or a dict of its keys: by, "
        r"palette, band_colour, base_colour, faces, shaded, shades\), got \{'pallete': 'x'\}",
    ):
        tile.export(tmp_path / "c.3mf", colours={"pallete": "x"})
    with pytest.raises(ParameterError, match=r"key 'a' must be a class letter"):
        ft.Colours(faces={"a": "red"})


def test_a_bad_face_colour_names_its_class():
    """A bad class colour names its key, ``colour.faces.<letter>`` (the web app's ``face_<letter>``)."""
    with pytest.raises(DesignError, match=r"\[colour.faces\] B 'reddish' is not a CSS or palette colour name") as info:
        design_from_text(BASE + '[colour.faces]\nB = "reddish"\n')
    assert info.value.key == "colour.faces.B"
    with pytest.raises(DesignError, match=r"\[colour.faces\] key 'star' must be a class letter") as info:
        design_from_text(BASE + '[colour.faces]\nstar = "red"\n')
    assert info.value.key == "colour.faces"


def test_an_unknown_class_names_its_letter():
    with pytest.raises(ParameterError, match=r"face class 'E' is not one of this design's: A, B") as info:
        colouring(faces={"E": "red"}, classes=("A", "B"))
    assert info.value.param == "faces.E"
