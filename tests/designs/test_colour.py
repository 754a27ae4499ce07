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


@pytest.mark.parametrize("bad, match", [
    ("#12345", r"colour must be #rrggbb or a CSS colour name \(like \"navy\"\), got '#12345'"),
    ("#ggggggg", r"colour must be #rrggbb"),
    (42, r"colour must be #rrggbb or a CSS colour name"),
    ("", r"colour must be #rrggbb or a CSS colour name"),
    ("nav", r"colour 'nav' is not a CSS colour name \(did you mean 'navy'\?\); give #rrggbb"),
    ("qqq", r"colour 'qqq' is not a CSS colour name; give #rrggbb or a CSS name like \"navy\""),
])
def test_bad_colours_are_refused(bad, match):
    with pytest.raises(ParameterError, match=match):
        parse_colour(bad)


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
    with pytest.raises(ParameterError, match=r"palette 'iznk' is not known \(did you mean 'iznik'\?\), must be one "
                                             r"of: zellige, iznik, mamluk, alhambra, haft-rangi"):
        colouring(palette_name="iznk")


def test_more_than_sixteen_materials_are_refused():
    many = [Colour(f"#0000{k:02x}", str(k)) for k in range(MAX_MATERIALS + 1)]
    check_materials(many[:MAX_MATERIALS])
    with pytest.raises(ParameterError, match=r"the print has 17 distinct colours, more than the 16 filaments a "
                                             r"slicer takes; give some face classes the same colour"):
        check_materials(many)


def test_the_palette_table_in_the_docs_is_the_codes():
    text = (DOCS / "colours.md").read_text(encoding="utf-8")
    block = re.search(r"<!-- palettes -->\n(.*?)<!-- /palettes -->", text, re.S).group(1)
    rows = block.strip().splitlines()[2:]
    assert len(rows) == len(PALETTES)
    for row, p in zip(rows, PALETTES.values()):
        faces = ", ".join(f"{c.name} `{c.hex}`" for c in p.faces)
        assert row == (f"| `{p.name}` | {p.band.name} `{p.band.hex}` | {p.base.name} `{p.base.hex}` | {faces} | "
                       f"{p.source} |")
    for p in PALETTES.values():  # names are file names: distinct within a palette, one per value
        names = {c.hex: c.name for c in (p.band, p.base, *p.faces)}
        assert len(set(names.values())) == len(names)


def test_a_design_reads_its_colour_section():
    d = design_from_text(BASE + '[colour]\nby = "shape"\npalette = "iznik"\nband_colour = "white"\n'
                                '[colour.faces]\nB = "#1e4fa0"\nA = "navy"\n')
    assert d.colour.given and d.colour.by == "shape" and d.colour.palette == "iznik"
    assert d.colour.band_colour == "white" and d.colour.faces == (("A", "navy"), ("B", "#1e4fa0"))
    c = d.colour.colouring(("A", "B", "C"))
    assert c.face("A").hex == "#000080" and c.band.hex == "#ffffff"
    plain = design_from_text(BASE)
    assert not plain.colour.given and plain.colour.by == "none"


@pytest.mark.parametrize("section, match", [
    ('[colour]\npalette = "azulejo"\n', r"\[colour\] palette = 'azulejo' is not valid, must be one of: zellige, "
                                       r"iznik, mamluk, alhambra, haft-rangi"),
    ('[colour]\nby = "colour"\n', r"\[colour\] by = 'colour' is not valid, must be one of: none, shape"),
    ('[colour]\nband_colour = "#12"\n', r"\[colour\] band_colour must be #rrggbb or a CSS colour name"),
    ('[colour]\nbase_colour = "blu"\n', r"\[colour\] base_colour 'blu' is not a CSS colour name \(did you mean "
                                        r"'blue'\?\)"),
    ('[colour]\nfaces = "red"\n', r"\[colour.faces\] must be a table of class letters to colours"),
    ('[colour.faces]\nstar = "red"\n', r"\[colour.faces\] key 'star' must be a class letter"),
    ('[colour.faces]\nA = "reddish"\n', r"\[colour.faces\] A 'reddish' is not a CSS colour name"),
    ('[colour]\nbands = "red"\n', r"unknown key 'bands' in \[colour\]"),
])
def test_bad_colour_sections_name_the_key(section, match):
    with pytest.raises(DesignError, match=match):
        design_from_text(BASE + section)


@pytest.mark.parametrize("inset, match", [
    (-0.1, r"mosaic_inset_mm must be a finite number >= 0 and <= 1000, got -0.1"),
    (1.2, r"mosaic_inset_mm must be smaller than relief_mm \(the bands stand 1.2 mm above the plate\), got 1.2"),
])
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
    assert parts["coloured"] == {"base": pal.base.linear, "pattern": pal.band.linear}
    assert parts["plain"]["pattern"] != pal.band.linear  # no [colour]: the parts' own display colours


def test_the_export_api_takes_colours(tmp_path):
    import fabtiles as ft
    from fabtiles.export.threemf import read_3mf

    tile = ft.Tile("square", 60, ft.HexPacking(radius=12.5, motif=ft.Star.preset("table3-3")), frame=3, stroke=1.2)
    tile.export(tmp_path / "a.3mf", style="mosaic", colours=ft.Colours(by="shape", palette="iznik", faces={"A": "navy"}))
    # CSS navy for A beside Iznik's own navy base: two colours, two names, two parts
    assert list(read_3mf(tmp_path / "a.3mf")) == ["navy (base)", "white (bands)", "navy-000080 (A)", "turquoise (B)"]
    tile.export(tmp_path / "b.3mf", style="mosaic", colours={"by": "shape", "palette": "mamluk"})
    assert list(read_3mf(tmp_path / "b.3mf"))[1] == "gold (bands)"
    report = tile.export(tmp_path / "k.dxf", mode="inlay", colours=ft.Colours(by="shape", palette="iznik"))
    assert [Path(p).name for p in report.stats["files"]] == ["k-lattice.dxf", "k-pieces-cobalt.dxf",
                                                             "k-pieces-turquoise.dxf"]
    with pytest.raises(ParameterError, match=r"colours must be a fabtiles.Colours \(or a dict of its keys: by, "
                                             r"palette, band_colour, base_colour, faces\), got \{'pallete': 'x'\}"):
        tile.export(tmp_path / "c.3mf", colours={"pallete": "x"})
    with pytest.raises(ParameterError, match=r"key 'a' must be a class letter"):
        ft.Colours(faces={"a": "red"})


def test_a_bad_face_colour_names_its_class():
    """A bad class colour names its key, ``colour.faces.<letter>`` (the web app's ``face_<letter>``)."""
    with pytest.raises(DesignError, match=r"\[colour.faces\] B 'reddish' is not a CSS colour name") as info:
        design_from_text(BASE + '[colour.faces]\nB = "reddish"\n')
    assert info.value.key == "colour.faces.B"
    with pytest.raises(DesignError, match=r"\[colour.faces\] key 'star' must be a class letter") as info:
        design_from_text(BASE + '[colour.faces]\nstar = "red"\n')
    assert info.value.key == "colour.faces"


def test_an_unknown_class_names_its_letter():
    with pytest.raises(ParameterError, match=r"face class 'E' is not one of this design's: A, B") as info:
        colouring(faces={"E": "red"}, classes=("A", "B"))
    assert info.value.param == "faces.E"
