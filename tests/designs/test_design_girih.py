"""Design files with kind = "girih": pattern and edge; bad input named, exit 2 and no file from the CLI."""

import pytest
from click.testing import CliRunner
from designs import assert_cli_refused

from fabtiles import DesignError, GirihPacking, LimitError
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import build_tile, design_from_text

BASE = """
[packing]
kind = "girih"
girih_pattern = "decagon-bowtie"
edge = 8
[tile]
outline = "square"
size = 60
stroke = 1
"""


def test_girih_design_builds_the_packing():
    d = design_from_text(BASE)
    assert d.motif is None and d.packing.girih_pattern == "decagon-bowtie" and d.packing.edge == 8
    tile = build_tile(d)
    assert tile.pattern == GirihPacking("decagon-bowtie", edge=8)
    assert tile.region().is_valid and tile.region().area > 0.2 * 60 * 60


def test_girih_level_subdivides_the_pattern():
    d = design_from_text(BASE.replace("edge = 8", "edge = 6\ngirih_level = 2"))
    assert d.packing.girih_level == 2
    assert build_tile(d).pattern == GirihPacking("decagon-bowtie", edge=6, level=2)
    assert design_from_text(BASE).packing.girih_level == 0


def test_a_motif_is_noted_as_not_drawn():
    from fabtiles.designs.design_file import design_notes

    assert design_notes(design_from_text(BASE)) == []
    with_motif = design_from_text(BASE + '[motif]\npreset = "table3-3"\n')
    assert design_notes(with_motif) == [
        '[motif] is not drawn: kind = "girih" draws the girih tiles\' strapwork (remove [motif])'
    ]
    assert build_tile(with_motif).pattern == GirihPacking("decagon-bowtie", edge=8)


def test_seamless_fits_the_edge_and_the_height():
    d = design_from_text(
        BASE.replace("edge = 8", "edge = 8\nseamless = true")
        .replace('"square"', '"rectangle"')
        .replace("60", "[60, 50]")
    )
    pack = build_tile(d).pattern
    px, py = pack.period
    w, h = d.tile_spec.size
    assert w == 60 and w / px == pytest.approx(round(w / px)) and h / py == pytest.approx(round(h / py))
    assert any(line.startswith("packing.seamless: edge 8 mm fitted to") for line in d.fitted)


def test_seamless_fits_a_subdivided_pattern_by_its_larger_period():
    d = design_from_text(
        BASE.replace("edge = 8", "edge = 6\ngirih_level = 1\nseamless = true")
        .replace('"square"', '"rectangle"')
        .replace("size = 60", "size = [200, 150]")
        .replace("stroke = 1", "stroke = 0.8")
    )
    pack = build_tile(d).pattern
    px, py = pack.period
    assert pack.level == 1 and px == pytest.approx(pack.replace(level=0).period[0] * 2.618034, rel=1e-6)
    assert 200 / px == pytest.approx(3) and d.tile_spec.size[1] / py == pytest.approx(round(d.tile_spec.size[1] / py))


@pytest.mark.parametrize(
    ("change", "match", "param"),
    [
        (('"decagon-bowtie"', '"decagon-bowties"'), r"did you mean 'decagon-bowtie'\?", "packing.girih_pattern"),
        (
            ('girih_pattern = "decagon-bowtie"\n', ""),
            r'kind = "girih" needs girih_pattern = one of: decagon-bowtie,',
            "packing.girih_pattern",
        ),
        (("edge = 8", "edge = -3"), r"\[packing\] edge must be a finite number > 0, got -3", "packing.edge"),
        (("edge = 8", "radius = 8"), r'kind = "girih" has no radius', "packing.radius"),
        (("edge = 8", 'edge = 8\ntiling = "4.8.8"'), r'tiling is a key of kind = "archimedean"', "packing.tiling"),
        (
            ('kind = "girih"', 'kind = "hex"'),
            r'edge is a key of kind = "archimedean" or "girih", not of kind = \'hex\'; '
            r'set kind = "archimedean" \(or "girih"\) or remove it',
            "packing.edge",
        ),
        (
            ('kind = "girih"', 'kind = "archimedean"\ntiling = "4.8.8"'),
            r'girih_pattern is a key of kind = "girih", not of kind = \'archimedean\'; set kind = "girih" or remove',
            "packing.girih_pattern",
        ),
        (
            ("edge = 8", "edge = 8\nseamless = true"),
            r"a square tile cannot be seamless with the girih pattern decagon-bowtie",
            "tile.outline",
        ),
        (
            ("edge = 8", "edge = 8\ngirih_level = -1"),
            r"\[packing\] girih_level must be an integer >= 0, got -1",
            "packing.girih_level",
        ),
        (
            ("edge = 8", "edge = 8\ngirih_level = 1.5"),
            r"girih_level must be an integer >= 0, got 1.5",
            "packing.girih_level",
        ),
        (
            ('"decagon-bowtie"', '"rhombi"\ngirih_level = 1'),
            r"\[packing\] girih_level = 1 subdivides decagons, hexagons and bowties; the girih pattern rhombi has",
            "packing.girih_level",
        ),
        (
            ('kind = "girih"\ngirih_pattern = "decagon-bowtie"\nedge = 8', 'kind = "hex"\ngirih_level = 1'),
            r'girih_level is a key of kind = "girih", not of kind = \'hex\'',
            "packing.girih_level",
        ),
    ],
)
def test_bad_input_names_the_key_and_value(change, match, param):
    with pytest.raises(DesignError, match=match) as info:
        design_from_text(BASE.replace(*change))
    assert info.value.param == param


def test_cli_exits_2_and_writes_nothing(tmp_path):
    path = tmp_path / "g.toml"
    path.write_text(BASE.replace('"decagon-bowtie"', '"decagon-bowties"'), encoding="utf-8")
    assert_cli_refused(["build", path, "-o", tmp_path / "out"], tmp_path / "out", "did you mean 'decagon-bowtie'\\?")


def test_a_level_too_deep_is_refused_exit_2_and_no_file(tmp_path):
    text = BASE.replace("edge = 8", "edge = 8\ngirih_level = 6")
    with pytest.raises(
        LimitError, match=r"girih_level = 6 would make 4,749,436 strapwork segments .* limit of 500,000"
    ) as info:
        design_from_text(text)
    assert info.value.param == "packing.girih_level"
    path = tmp_path / "deep.toml"
    path.write_text(text, encoding="utf-8")
    assert_cli_refused(
        ["build", path, "-o", tmp_path / "out"],
        tmp_path / "out",
        "girih_level = 6 would make 4,749,436 strapwork segments",
    )


def test_cli_builds_a_girih_svg(tmp_path):
    path = tmp_path / "g.toml"
    path.write_text(BASE, encoding="utf-8")
    result = CliRunner().invoke(cli, ["build", str(path), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "g.svg").stat().st_size > 1000
