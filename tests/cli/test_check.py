"""``fabtiles check``: findings printed, overlay written, exit 0 / 1 / 2."""

import re

import pytest
from click.testing import CliRunner
from designs import design_toml

from fabtiles.cli.main import cli


def design_text(fill: bool) -> str:
    return design_toml(output={"laser_profile": "laser-3mm-plywood", "fill_small_holes": fill})


def run(*args):
    return CliRunner().invoke(cli, ["check", *map(str, args)], catch_exceptions=False)


@pytest.fixture
def designs(tmp_path):
    paths = {}
    for fill in ("true", "false"):
        p = tmp_path / f"fill-{fill}.toml"
        p.write_text(design_text(fill == "true"))
        paths[fill] = p
    return paths


def test_clean_design_exits_0_and_its_overlay_has_no_marks(designs, tmp_path):
    out = tmp_path / "clean.svg"
    res = run(designs["true"], "-o", out)
    assert res.exit_code == 0, res.output
    assert "small holes filled" in res.output and res.output.rstrip().endswith("ok: nothing found")
    text = out.read_text()
    assert text.startswith("<?xml") and 'class="findings"' in text and 'class="finding ' not in text


def test_findings_are_printed_and_marked(designs, tmp_path):
    out = tmp_path / "overlay.svg"
    res = run(designs["false"], "-o", out)
    assert res.exit_code == 1, res.output
    line = next(x for x in res.output.splitlines() if "small_hole" in x)
    m = re.fullmatch(
        r"\s+laser small_hole: ([\d,]+), worst ([\d.]+) mm \(limit 1\.2 mm\), at \([\d., -]+\).* and ([\d,]+) more",
        line,
    )
    assert m, line
    count = int(m[1].replace(",", ""))
    assert 0 < float(m[2]) < 1.2
    marks = re.findall(
        r'<circle class="finding small_hole" data-where="laser" cx="([\d.]+)" cy="([\d.]+)"', out.read_text()
    )
    assert len(marks) == count
    assert all(0 <= float(x) <= 60 and 0 <= float(y) <= 60 for x, y in marks)
    assert run(designs["false"]).exit_code == 1  # without -o: same status, no file
    assert run(designs["false"], "--set", "output.fill_small_holes=true").exit_code == 0


@pytest.mark.parametrize(
    "args, message",
    [
        (["missing.toml"], "cannot read design file"),
        (["{false}", "-o", "{tmp}/overlay.png"], "the overlay (-o) must be an .svg file"),
        (["{bad}", "-o", "{tmp}/overlay.svg"], "unknown key 'strok' in [tile]"),
    ],
)
def test_bad_input_exits_2_and_writes_nothing(designs, tmp_path, args, message):
    bad = tmp_path / "bad.toml"
    bad.write_text(design_text(True).replace("stroke", "strok"))
    args = [a.format(false=designs["false"], bad=bad, tmp=tmp_path) for a in args]
    res = CliRunner().invoke(cli, ["check", *args])
    assert res.exit_code == 2, res.output
    assert message in res.output
    assert not list(tmp_path.glob("overlay*"))


def test_check_judges_the_interlace_cut_region(tmp_path):
    """With ``interlace_cut`` the laser file holds the cut gaps and their tabs: so does the check."""
    from fabtiles.core.report import Report
    from fabtiles.designs.design_file import load_design
    from fabtiles.geometry.laser_checks import check_laser
    from fabtiles.geometry.machine_geometry import cut_geometry as laser_geometry
    from fabtiles.machines.profiles import load_profile
    from fabtiles.making.checks import check_design

    woven = design_text(False).replace("stroke = 1.0", "stroke = 1.0\ninterlace = true")
    p = tmp_path / "woven.toml"
    p.write_text(woven)
    q = tmp_path / "cut.toml"
    q.write_text(woven.replace("interlace = true", "interlace = true\ninterlace_cut = true"))
    laser = load_profile("laser-3mm-plywood")
    results = {}
    for path in (p, q):
        design = load_design(path)
        tile = design.build_tile()
        region, _ = laser_geometry(tile, profile=laser, mode="pierced")
        expected = check_laser(
            region,
            tile.outline_shape(),
            laser,
            stroke=tile.stroke,
            report=Report(path="", format="laser"),
            validate=False,
        )
        got = check_design(design, tile).laser
        assert [(f.code, f.count) for f in got.findings] == [(f.code, f.count) for f in expected.findings]
        results[path.stem] = got
    # the cut leaves tabs thinner than the plain bands: more (or worse) thin bridges than the woven drawing
    assert [(f.code, f.count) for f in results["cut"].findings] != [
        (f.code, f.count) for f in results["woven"].findings
    ]
    # and the command reports them (exit 1 with findings)
    result = run(q)
    assert result.exit_code == 1, result.output
