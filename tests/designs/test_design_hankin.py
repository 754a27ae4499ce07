"""Design files with method = "hankin": the contact angle and gap, the motifs kept, the errors."""

import pytest
from click.testing import CliRunner
from designs import assert_cli_refused

from fabtiles import ArchimedeanPacking, DesignError, Star
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import build_tile, design_from_text

BASE = """
[packing]
kind = "archimedean"
tiling = "4.8.8"
edge = 20
method = "hankin"
contact_angle = 67.5
[tile]
outline = "square"
size = 100
stroke = 1
[output]
formats = ["svg"]
"""


def test_hankin_design_builds_the_packing():
    d = design_from_text(BASE)
    assert d.packing.method == "hankin" and d.packing.contact_angle == 67.5 and d.packing.contact_gap == 0
    assert build_tile(d).pattern == ArchimedeanPacking("4.8.8", 20, method="hankin", contact_angle=67.5)


def test_motif_section_fills_no_kind_packing_motifs_keep_theirs():
    d = design_from_text(BASE + '[motif]\npreset = "table1-part1"\n[packing.motifs]\n8 = "table3-3"\n')
    pack = build_tile(d).pattern
    assert dict(pack.motifs) == {8: Star.preset("table3-3")} and pack.contact_angle == 67.5


def test_the_default_method_is_the_papers():
    d = design_from_text(
        BASE.replace('method = "hankin"\ncontact_angle = 67.5\n', '[packing.motifs]\n8 = "table3-3"\n')
    )
    assert d.packing.method == "motifs" and build_tile(d).pattern.method == "motifs"


@pytest.mark.parametrize(
    "change, match, key",
    [
        (
            ("contact_angle = 67.5", "contact_angle = 90"),
            r"\[packing\] contact_angle must be a finite number > 0 and < 90, "
            r"got 90",
            "packing.contact_angle",
        ),
        (
            ("contact_angle = 67.5", "contact_angle = 0"),
            r"contact_angle must be a finite number > 0 and < 90, got 0",
            "packing.contact_angle",
        ),
        (
            ("contact_angle = 67.5", "contact_angle = 'steep'"),
            r"contact_angle must be a number > 0 and < 90 \(degrees\)|"
            r"contact_angle must be a number > 0 and < 90, got 'steep'",
            "packing.contact_angle",
        ),
        (
            ("contact_angle = 67.5", "contact_gap = -0.5"),
            r"\[packing\] contact_gap must be a finite number >= 0, got -0\.5",
            "packing.contact_gap",
        ),
        (
            ("contact_angle = 67.5", "contact_gap = 20"),
            r"contact_gap must be >= 0 and < the edge \(20 mm\)",
            "packing.contact_gap",
        ),
        (
            ("contact_angle = 67.5", "contact_angle = 85\ncontact_gap = 6"),
            r"contact_angle 85 has no pattern on the tiling 4\.8\.8 with contact_gap 6 mm: .* must be > 0 and <= 73\.3",
            "packing.contact_angle",
        ),
        (
            ('method = "hankin"', 'method = "kaplan"'),
            r"\[packing\] method = 'kaplan' is not valid, must be one of: "
            r"motifs, hankin",
            "packing.method",
        ),
        (
            ('method = "hankin"', 'method = "hankn"'),
            r"method = 'hankn' is not valid \(did you mean 'hankin'\?\)",
            "packing.method",
        ),
        (
            ('method = "hankin"\n', ""),
            r"contact_angle is a key of method = \"hankin\", not of method = 'motifs'",
            "packing.contact_angle",
        ),
        (
            ('kind = "archimedean"\ntiling = "4.8.8"\nedge = 20\n', 'kind = "hex"\nradius = 10\n'),
            r"method = 'hankin' is not valid with kind = 'hex': method \(one of: motifs, hankin\) is a key of "
            r"kind = \"archimedean\"",
            "packing.method",
        ),
        (
            (
                'kind = "archimedean"\ntiling = "4.8.8"\nedge = 20\nmethod = "hankin"\n',
                'kind = "square"\nradius = 10\n',
            ),
            r"contact_angle is a key of kind = \"archimedean\", not of kind = 'square'",
            "packing.contact_angle",
        ),
    ],
)
def test_bad_hankin_keys_name_the_key_and_the_valid_values(change, match, key):
    assert change[0] in BASE
    with pytest.raises(DesignError, match=match) as err:
        design_from_text(BASE.replace(*change))
    assert err.value.param == key


@pytest.mark.parametrize(
    "setting, match",
    [
        ("packing.contact_angle=95", r"contact_angle must be a finite number > 0 and < 90, got 95"),
        ("packing.contact_gap=-1", r"contact_gap must be a finite number >= 0, got -1"),
        ("packing.contact_gap=20", r"contact_gap must be >= 0 and < the edge"),
        ('packing.method="circles"', r"method = 'circles' is not valid, must be one of: motifs, hankin"),
    ],
)
def test_cli_exits_2_and_writes_nothing(tmp_path, setting, match):
    path = tmp_path / "h.toml"
    path.write_text(BASE, encoding="utf-8")
    assert_cli_refused(["build", path, "-o", tmp_path / "out", "--set", setting], tmp_path / "out", match)


def test_cli_method_on_a_hex_packing_exits_2(tmp_path):
    path = tmp_path / "hex.toml"
    path.write_text('[motif]\npreset = "table3-1"\n[packing]\nradius = 8\n[tile]\nsize = 60\n', encoding="utf-8")
    out = tmp_path / "out"
    result = CliRunner().invoke(
        cli, ["build", str(path), "-o", str(out), "--set", 'packing.method="hankin"'], catch_exceptions=False
    )
    assert result.exit_code == 2 and 'is a key of kind = "archimedean"' in result.output and not out.exists()


@pytest.mark.parametrize("motif", [False, True])
def test_cli_builds_a_hankin_design(tmp_path, motif):
    """A [motif] section is drawn nowhere with Hankin's method: the build says so, and still builds."""
    path = tmp_path / "h.toml"
    path.write_text(BASE + ('[motif]\npreset = "table1-part1"\n' if motif else ""), encoding="utf-8")
    result = CliRunner().invoke(cli, ["build", str(path), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert 'width="100.15mm"' in (tmp_path / "out" / "h.svg").read_text()
    assert ('note: [motif] is not drawn: with method = "hankin"' in result.output) == motif


def test_seamless_keeps_the_method():
    d = design_from_text(BASE.replace("edge = 20", "edge = 20\nseamless = true"))
    pack = build_tile(d).pattern
    assert d.packing.edge != 20 and pack.method == "hankin" and pack.edge == d.packing.edge
