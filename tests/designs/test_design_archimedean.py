"""Design files with kind = "archimedean": tiling, edge, [packing.motifs] keyed by sides."""

import pytest

from fabtiles import ArchimedeanPacking, DesignError, Star
from fabtiles.designs.design_file import build_tile, design_from_text

BASE = """
[packing]
kind = "archimedean"
tiling = "4.8.8"
edge = 20
[packing.motifs]
8 = "table3-3"
4 = { n = 8, radii = [1, 2] }
[tile]
outline = "square"
size = 120
"""


def test_archimedean_design_builds_the_packing():
    d = design_from_text(BASE)
    assert d.motif is None and d.packing.tiling == "4.8.8" and d.packing.edge == 20
    pack = build_tile(d).pattern
    assert pack == ArchimedeanPacking("4.8.8", 20, {8: "table3-3", 4: Star(n=8, radii=(1, 2))})


def test_motif_section_fills_the_kinds_not_listed():
    d = design_from_text(BASE.replace('8 = "table3-3"\n', "") + '[motif]\npreset = "table1-part1"\n')
    pack = build_tile(d).pattern
    assert pack.motifs[8] == Star.preset("table1-part1") and pack.motifs[4] == Star(n=8, radii=(1, 2))


def test_exponent_form_gap_motif_and_seamless():
    text = BASE.replace('"4.8.8"', '"4.8^2"').replace(
        "edge = 20", 'edge = 20\nseamless = true\ngap_motif = "table1-part1"'
    )
    d = design_from_text(text)
    fit_edge = d.packing.edge
    assert fit_edge != 20 and 120 / (fit_edge * (1 + 2**0.5)) == pytest.approx(round(120 / (fit_edge * (1 + 2**0.5))))
    assert build_tile(d).pattern.gap_motif == Star.preset("table1-part1")


@pytest.mark.parametrize(
    "change, match",
    [
        (
            ('tiling = "4.8.8"', 'tiling = "5.5.5"'),
            r"\[packing\] tiling '5\.5\.5' is unknown \(tilings: 3\.3\.3\.3\.3\.3",
        ),
        (('tiling = "4.8.8"\n', ""), r"kind = \"archimedean\" needs tiling = one of: 3\.3\.3\.3\.3\.3, 4\.4\.4\.4"),
        (('tiling = "4.8.8"', "tiling = 488"), r"\[packing\] tiling must be one of: 3\.3\.3\.3\.3\.3"),
        (("edge = 20", "edge = 0"), r"\[packing\] edge must be a finite number > 0, got 0"),
        (("edge = 20", "edge = -3"), r"\[packing\] edge must be a finite number > 0, got -3"),
        (("edge = 20", "edge = 'x'"), r"\[packing\] edge must be a number of mm > 0, got 'x'"),
        (("edge = 20", "radius = 20"), r"has no radius: give the tiling's edge \(mm\) instead, like edge = 20"),
        (
            ('8 = "table3-3"', '6 = "table3-3"'),
            r"\[packing\] motifs key 6 is not a polygon of the tiling 4\.8\.8, must be one of: 4, 8",
        ),
        (
            ('8 = "table3-3"', 'eight = "table3-3"'),
            r"\[packing\.motifs\] key 'eight' must be a polygon's number of sides",
        ),
        (('8 = "table3-3"', '8 = "nope"'), r"\[packing\.motifs\] 8 preset 'nope' is unknown"),
        (('8 = "table3-3"', "8 = { n = 2, radii = [1, 2] }"), r"\[packing\.motifs\] 8 n must be an integer >= 3"),
        (("[packing.motifs]", "motifs = 3\n[unused]"), r"unknown section 'unused'|\[packing\.motifs\] must be a table"),
    ],
)
def test_bad_archimedean_designs(change, match):
    with pytest.raises(DesignError, match=match):
        design_from_text(BASE.replace(*change))


def test_motifs_table_must_be_a_table():
    text = BASE.replace('[packing.motifs]\n8 = "table3-3"\n4 = { n = 8, radii = [1, 2] }\n', "motifs = 3\n")
    with pytest.raises(DesignError, match=r"\[packing\.motifs\] must be a table keyed by polygon sides"):
        design_from_text(text)


def test_archimedean_keys_refused_with_other_kinds():
    text = '[motif]\npreset = "table3-3"\n[packing]\nkind = "hex"\ntiling = "4.8.8"\n[tile]\nsize = 100\n'
    with pytest.raises(DesignError, match=r"tiling is a key of kind = \"archimedean\", not of kind = 'hex'"):
        design_from_text(text)


def test_motif_still_required_without_archimedean():
    with pytest.raises(DesignError, match=r"the design needs a \[motif\] section"):
        design_from_text('[packing]\nkind = "hex"\n[tile]\nsize = 100\n')


def test_design_errors_name_their_key():
    with pytest.raises(DesignError) as info:
        design_from_text(BASE.replace("edge = 20", "radius = 20"))
    assert info.value.param == "packing.radius"
    with pytest.raises(DesignError) as info:
        design_from_text(BASE.replace('tiling = "4.8.8"', 'tiling = "5.5.5"'))
    assert info.value.param == "packing.tiling"
    with pytest.raises(DesignError) as info:
        design_from_text(BASE.replace('8 = "table3-3"', '6 = "table3-3"'))
    assert info.value.param == "packing.motifs"
