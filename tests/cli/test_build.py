"""``fabtiles build``: outputs, overrides, errors (exit 2, nothing written), refused formats (exit 3),
golden renders."""

from dataclasses import replace
from pathlib import Path

import pytest
from click.testing import CliRunner
from designs import design_toml, printed_only

from fabtiles import FabtilesError
from fabtiles.cli.main import cli
from fabtiles.export.formats import FORMATS

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = sorted(p for p in (ROOT / "samples").glob("*.toml") if not printed_only(p))
RENDERS = ROOT / "samples" / "renders"

SMALL = design_toml(preset="table3-1", radius=8, output={"formats": ["svg"]})


def run(*args):
    return CliRunner().invoke(cli, list(map(str, args)), catch_exceptions=False)


@pytest.fixture
def design(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL, encoding="utf-8")
    return path


def test_build_writes_the_svg(design, tmp_path):
    out = tmp_path / "out"
    result = run("build", design, "-o", out)
    assert result.exit_code == 0, result.output
    svg = (out / "small.svg").read_text()
    # The laser SVG: true mm size, grown by the plywood profile's kerf (0.15 mm).
    assert 'width="60.15mm" height="60.15mm"' in svg and 'viewBox="' in svg
    assert 'id="INNER"' in svg and 'id="OUTER"' in svg
    assert sorted(p.name for p in out.iterdir()) == ["small.svg"]  # no staging left over
    assert f"wrote {out / 'small.svg'}" in result.output


def test_set_overrides_and_output_name(design, tmp_path):
    out = tmp_path / "out"
    result = run(
        "build",
        design,
        "-o",
        out,
        "--set",
        "tile.size=[80, 40]",
        "--set",
        "tile.outline=rectangle",
        "--set",
        'output.name="wide"',
    )
    assert result.exit_code == 0, result.output
    assert 'width="80.15mm" height="40.15mm"' in (out / "wide.svg").read_text()


@pytest.mark.parametrize(
    "extra, match",
    [
        (["--set", "tile.sise=3"], r"unknown key 'sise' in \[tile\]; did you mean 'size'\?"),
        (["--set", "tile.stroke=50"], r"stroke must be > 0 and <= 8 mm \(the packing radius\), got 50"),
        (["--set", "tile.frame=40"], r"too small for frame 40 mm"),
        (["--set", "motif.n=2"], r"\[motif\] n must be an integer >= 3"),
        (["--set", "oops"], r"--set expects section.key=value, got 'oops'"),
        (["--set", "output.tab_mm=-0.5"], r"\[output\] tab_mm must be a number of mm from 0 to 5 "),
        (["--set", "output.tabs_per_part=0"], r"\[output\] tabs_per_part must be an integer >= 1 and <= 64, got 0"),
        (["--set", "output.tab_mm=0.1"], r"tab_mm must be 0 \(no tabs\) or more than the kerf \(0\.15 mm\), got 0\.1"),
        (
            [
                "--set",
                "output.tab_mm=0.5",
                "--set",
                'output.laser_profile="router-6mm-mdf"',
                "--set",
                "tile.stroke=5",
                "--set",
                "packing.radius=12",
            ],
            r"tab_mm must be 0 for router profile 'router-6mm-mdf', got 0\.5: a router file holds the part whole and "
            r"CAM adds the holding tabs",
        ),
    ],
)
def test_bad_input_exits_2_and_writes_nothing(design, tmp_path, extra, match):
    import re

    out = tmp_path / "out"
    result = run("build", design, "-o", out, *extra)
    assert result.exit_code == 2
    assert re.search(match, result.output), result.output
    assert result.output.startswith("fabtiles: error: ") and result.output.count("\n") == 1
    assert not out.exists()


def test_holding_tabs_are_reported(design, tmp_path):
    result = run(
        "build", design, "-o", tmp_path / "out", "--set", "output.tab_mm=0.5", "--set", "output.tabs_per_part=3"
    )
    assert result.exit_code == 0, result.output
    assert "holding tabs: 3 tabs of 0.5 mm in 1 part (3 per part) at (" in result.output
    import xml.etree.ElementTree as ET

    ns = "{http://www.w3.org/2000/svg}"
    root = ET.parse(tmp_path / "out" / "small.svg").getroot()
    outer = next(g for g in root.iter(f"{ns}g") if g.get("id") == "OUTER")
    assert [p.get("d").endswith("Z") for p in outer.iter(f"{ns}path")] == [False] * 3


def test_unreadable_design_exits_2(tmp_path):
    result = run("build", tmp_path / "missing.toml", "-o", tmp_path / "out")
    assert result.exit_code == 2
    assert "cannot read design file" in result.output and "missing.toml" in result.output
    assert not (tmp_path / "out").exists()


def test_output_folder_is_a_file(design, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("keep")
    result = run("build", design, "-o", blocker / "sub")
    assert result.exit_code == 2 and "fabtiles: error:" in result.output
    assert blocker.read_text() == "keep"


def test_unknown_format_option_is_a_usage_error(design, tmp_path):
    result = run("build", design, "-o", tmp_path / "out", "--format", "png")
    assert result.exit_code == 2 and "'png' is not one of" in result.output


def test_a_refused_format_is_named_and_the_others_written_exit_3(design, tmp_path, monkeypatch):
    """A format whose writer fails is refused on its own: one line naming it and why, its earlier
    file left as it was; the other formats are written, and the exit status is 3."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "small.svg").write_text("old")
    (out / "small.stl").write_text("old")

    def boom(model, options):
        raise FabtilesError("mesh is not watertight")

    monkeypatch.setitem(FORMATS, "stl", replace(FORMATS["stl"], write=boom))
    result = run("build", design, "-o", out, "--format", "svg", "--format", "stl")
    assert result.exit_code == 3, result.output
    assert f"replaced {out / 'small.svg'} (svg)" in result.output
    assert (
        f"fabtiles: refused {out / 'small.stl'} (stl): mesh is not watertight ({out / 'small.stl'}, from an "
        f"earlier build, was left as it was)"
    ) in result.output
    assert "add --format stl" not in result.output  # rebuilding would not help: it was refused
    assert (out / "small.svg").read_text() != "old" and (out / "small.stl").read_text() == "old"
    assert sorted(p.name for p in out.iterdir()) == ["small.stl", "small.svg"]
    # every format refused: bad input's exit status 2, nothing written or changed
    result = run("build", design, "-o", out, "--format", "stl")
    assert result.exit_code == 2 and "fabtiles: error: mesh is not watertight" in result.output
    assert (out / "small.stl").read_text() == "old"


@pytest.mark.parametrize("sample", SAMPLES, ids=[p.stem for p in SAMPLES])
def test_sample_renders_are_golden(sample, tmp_path):
    import runpy

    render = runpy.run_path(str(ROOT / "samples" / "render.py"))["render"]
    got = render(sample, tmp_path).read_bytes()
    expected = (RENDERS / f"{sample.stem}.svg").read_bytes()
    assert got == expected, f"re-render with: python samples/render.py ({sample.name} changed)"


def test_custom_sizes_example(tmp_path):
    import runpy

    mod = runpy.run_path(str(ROOT / "samples" / "custom_sizes.py"))
    mod["main"](str(tmp_path))
    names = sorted(p.name for p in tmp_path.iterdir())
    assert len(names) == 6 and "rectangle-200x120.svg" in names
    assert any(n.startswith("seamless-200x129.90") for n in names)


def test_build_prints_findings_and_fills_small_holes_on_request(tmp_path):
    sample = ROOT / "samples" / "table3-3.toml"
    plain = run("build", sample, "-o", tmp_path / "a", "--format", "dxf", "--set", "output.fill_small_holes=false")
    assert plain.exit_code == 0, plain.output
    assert "laser laser-3mm-plywood: 1 warning" in plain.output and "small_hole:" in plain.output
    assert "fill_small_holes = true in a design's [output]" in plain.output
    filled = run("build", sample, "-o", tmp_path / "b", "--format", "dxf")  # the sample fills them
    assert filled.exit_code == 0, filled.output
    assert "laser laser-3mm-plywood: ok" in filled.output
    # Filling removes the holes from the cut: fewer inner contours.
    import ezdxf

    count = {k: sum(1 for e in ezdxf.readfile(tmp_path / k / "table3-3.dxf").modelspace()) for k in "ab"}
    assert count["b"] < count["a"]
    bad = run("build", sample, "-o", tmp_path / "c", "--set", "output.fill_small_holes=1")
    assert bad.exit_code == 2 and "[output] fill_small_holes must be true or false, got 1" in bad.output


def test_design_heights_reach_the_mesh(design, tmp_path):
    import numpy as np

    from fabtiles.export.stl import read_stl_triangles

    res = run(
        "build", design, "-o", tmp_path, "--format", "stl", "--set", "output.base_mm=3", "--set", "output.relief_mm=0.6"
    )
    assert res.exit_code == 0, res.output
    z = read_stl_triangles((tmp_path / "small.stl").read_bytes())[..., 2]
    assert np.unique(z).tolist() == pytest.approx([0.0, 3.0, 3.6])
    # a deboss deeper than the plate: refused, nothing written
    res = run(
        "build",
        design,
        "-o",
        tmp_path / "d",
        "--format",
        "stl",
        "--set",
        'output.print_style="deboss"',
        "--set",
        "output.deboss_mm=2.5",
    )
    assert res.exit_code == 2
    assert "deboss_mm must be smaller than base_mm (the plate is 2 mm thick), got 2.5" in res.output
    assert not (tmp_path / "d").exists()


def test_a_build_says_which_files_it_replaced(design, tmp_path):
    out = tmp_path / "out"
    first = run("build", design, "-o", out, "--format", "svg")
    assert first.exit_code == 0, first.output
    assert f"wrote {out / 'small.svg'} (svg)" in first.stdout and "replaced" not in first.stdout
    second = run("build", design, "-o", out, "--format", "svg", "--format", "dxf")
    assert second.exit_code == 0, second.output
    lines = second.stdout.splitlines()
    assert f"replaced {out / 'small.svg'} (svg)" in lines and f"wrote {out / 'small.dxf'} (dxf)" in lines


def test_set_says_what_it_changed(design, tmp_path):
    result = run(
        "build",
        design,
        "-o",
        tmp_path / "out",
        "--set",
        "tile.size=[80,80]",
        "--set",
        "tile.stroke=1.0",
        "--set",
        "tile.join=round",
        "--set",
        "packing.radius=9",
    )
    assert result.exit_code == 0, result.output
    notes = [line for line in result.stderr.splitlines() if line.startswith("fabtiles: note: --set ")]
    assert notes == [
        "fabtiles: note: --set tile.size=[80,80] (was 60)",
        "fabtiles: note: --set tile.stroke=1.0 (as the file has it)",
        'fabtiles: note: --set tile.join=round (not in the file: the default was "miter")',
        "fabtiles: note: --set packing.radius=9 (was 8)",
    ]
    plain = run("build", design, "-o", tmp_path / "plain")
    assert plain.exit_code == 0 and "--set" not in plain.stderr


def test_files_of_other_formats_left_from_an_earlier_build_are_named(tmp_path):
    """The issue's case: a 200 mm DXF built beside the 150 mm STL and 3MF of the same name."""
    sample = ROOT / "samples" / "table3-3.toml"
    out = tmp_path / "out"
    out.mkdir()
    for name in ("table3-3.stl", "table3-3.3mf", "table3-3-lattice.svg", "other.stl"):
        (out / name).write_text("from an earlier build")
    result = run("build", sample, "-o", out, "--set", "tile.size=[200,200]", "--format", "dxf")
    assert result.exit_code == 0, result.output
    assert "fabtiles: note: --set tile.size=[200,200] (was [150, 150])" in result.stderr
    earlier = ", ".join(str(out / n) for n in ("table3-3-lattice.svg", "table3-3.stl", "table3-3.3mf"))
    assert (
        f"fabtiles: note: {earlier} are from an earlier build and were not rewritten (this build wrote dxf); "
        f"add --format svg --format stl --format 3mf to rebuild them, or delete them"
    ) in result.stderr
    assert (out / "table3-3.stl").read_text() == "from an earlier build"
    # one file left, and a build of every format it has: no note
    (out / "table3-3.3mf").unlink()
    (out / "table3-3-lattice.svg").unlink()
    result = run("build", sample, "-o", out, "--format", "dxf")
    assert "is from an earlier build and was not rewritten" in result.stderr and "add --format stl" in result.stderr
    result = run("build", sample, "-o", out, "--format", "dxf", "--format", "stl")
    assert "earlier build" not in result.stderr
    assert f"replaced {out / 'table3-3.stl'} (stl)" in result.stdout


def test_build_result_lists_replaced_and_earlier_files(tmp_path):
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making import build_design

    d = design_from_text(SMALL, name="small")
    first = build_design(d, tmp_path, ["svg", "dxf"])
    assert first.replaced == [] and first.earlier == []
    again = build_design(d, tmp_path, ["svg"])
    assert again.replaced == [str(tmp_path / "small.svg")] and again.earlier == [str(tmp_path / "small.dxf")]
    one = build_design(d, tmp_path, ["svg"], file_name="small.svg")
    assert one.replaced == [str(tmp_path / "small.svg")] and one.earlier == []


def test_a_seamless_fit_says_what_it_changed(tmp_path):
    design = tmp_path / "seam.toml"
    design.write_text(
        '[motif]\npreset = "table3-3"\n[packing]\nkind = "hex"\nradius = 14\nseamless = true\n'
        '[tile]\noutline = "rectangle"\nsize = [120, 120]\nframe = 0.0\n[output]\nformats = ["svg"]\n'
    )
    notes = [
        "fabtiles: note: packing.seamless: radius 14 mm fitted to 15 mm (4 periods across the 120 mm width)",
        "fabtiles: note: packing.seamless: tile height 120 mm moved to 103.923 mm (-16.077 mm, 2 whole periods up)",
    ]
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert result.stderr.splitlines() == notes
    result = CliRunner().invoke(cli, ["check", str(design)])
    assert result.stderr.splitlines() == notes
