"""``fabtiles nest``: tiles of several designs nested onto sheets (issue 34), checked on the files read back."""

from __future__ import annotations

import sys
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "export"))
from dxf_helpers import bulges, raw_vertices, vertices
from test_laser_programs import burns, meerk40t

from fabtiles import FabtilesError, ParameterError
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import load_design
from fabtiles.machines.profiles import load_profile
from fabtiles.making import BuildOptions, Models, prepare_tile
from fabtiles.making.nesting import nest_designs, part_outline

PLY = load_profile("laser-3mm-plywood")
OUTER = PLY.layers.outer_cut.name

DESIGN = """
[motif]
preset = "{preset}"
[packing]
radius = 8
[tile]
outline = "{outline}"
size = 40
frame = 3
stroke = 1.0
[output]
formats = ["dxf"]
laser_profile = "laser-3mm-plywood"
"""


def run(*args):
    return CliRunner().invoke(cli, list(map(str, args)), catch_exceptions=False)


def write_designs(folder):
    paths = []
    for preset, outline in (("table3-1", "square"), ("table3-3", "circle")):
        path = folder / f"{outline}.toml"
        path.write_text(DESIGN.format(preset=preset, outline=outline), encoding="utf-8")
        paths.append(path)
    return paths


@pytest.fixture
def designs(tmp_path):
    return write_designs(tmp_path)


GAP = 1.15


@pytest.fixture(scope="module")
def nested(tmp_path_factory):
    """Five squares and four circles nested onto 150 x 100 mm sheets once for the module's tests:
    (the designs, the output folder, the result)."""
    folder = tmp_path_factory.mktemp("nested")
    paths = write_designs(folder)
    out = folder / "out"
    result = nest_designs(
        [(load_design(paths[0]), 5), (load_design(paths[1]), None)],
        out,
        ("dxf", "svg"),
        count=4,
        sheet_mm=(150, 100),
        gap_mm=GAP,
        time_s=1,
    )
    return paths, out, result


def rings(path, layer=None):
    """Every polyline of the DXF (of ``layer``), as (n, 2) arrays: its arcs drawn by ezdxf."""
    return [vertices(e) for e in ezdxf.readfile(path).modelspace() if layer is None or e.dxf.layer == layer]


def bulged(path, layer):
    """Every polyline of ``layer`` as written: its vertices and bulges."""
    return [(raw_vertices(e), bulges(e)) for e in ezdxf.readfile(path).modelspace() if e.dxf.layer == layer]


def test_nested_files_hold_every_part_once_moved_rigidly_inside_and_apart(nested):
    designs, out, result = nested
    gap = GAP
    n = result.nesting
    assert len(n.placements) == 9 and len({p.id for p in n.placements}) == 9
    assert n.sheets >= 2  # 9 tiles of 40 mm do not go on one 150 x 100 mm sheet
    plans = {}
    for path in designs:
        d = load_design(path)
        plans[d.name] = Models(prepare_tile(d), BuildOptions.of_design(d)).cut
    for k in range(n.sheets):
        dxf = out / f"nest-sheet-{k + 1}.dxf"  # several designs: the files are named after none of them
        assert (out / f"nest-sheet-{k + 1}.svg").is_file()
        outer = [shapely.Polygon(r) for r in rings(dxf, OUTER)]
        every = np.concatenate(rings(dxf))
        assert every.min() >= 0 and (every <= (150, 100)).all()  # every cut inside the sheet, kerf included
        on = n.on_sheet(k)
        assert len(outer) == len(on)
        for i, a in enumerate(outer):  # no two parts' cut paths closer than the gap (nor overlapping)
            for b in outer[i + 1 :]:
                assert shapely.distance(a, b) >= gap - 1e-6
        # each placed part is its source tile's cut moved rigidly: its outer path in the file (vertices and
        # arcs as written), turned and moved back, is the tile's own (vertices within 1 um, the same arcs);
        # every path of the file belongs to one part
        written = bulged(dxf, OUTER)
        arcs = 0
        for i in on:
            p = n.placements[i]
            source = next(layer for layer in plans[p.id.split("#")[0]].layers if layer.role == "outer").curves[0]
            placed = p.move(source.xy)
            xy, bulge = min(written, key=lambda w: np.linalg.norm(w[0].mean(axis=0) - placed.mean(axis=0)))
            a = np.radians(p.rotation)
            back = (xy - p.translation) @ np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
            assert back.shape == source.xy.shape and np.abs(back - source.xy).max() < 1e-3
            assert bulge == pytest.approx(source.bulge, abs=1e-6)
            arcs += np.count_nonzero(bulge)
        assert shapely.covers(shapely.union_all(outer).buffer(1e-6), shapely.points(every)).all()
        assert arcs > 0 or not any(n.placements[i].id.startswith("circle") for i in on)  # a circle's outline: arcs
    assert [s["parts"] for s in result.sheets] == [len(n.on_sheet(k)) for k in range(n.sheets)]
    assert sum(s["designs"].get("square", 0) for s in result.sheets) == 5
    assert sum(s["designs"].get("circle", 0) for s in result.sheets) == 4


def test_the_command_writes_a_file_per_sheet_and_reports_each(designs, tmp_path):
    out = tmp_path / "out"
    result = run(
        "nest",
        f"{designs[0]}:3",
        designs[1],
        "--count",
        "2",
        "-o",
        out,
        "--sheet",
        "100x100",
        "--time",
        "1",
        "--format",
        "lbrn2",
        "--format",
        "dxf",
        "--name",
        "kit",
        "--rotate",
        "180",
    )
    assert result.exit_code == 0, result.output
    files = sorted(p.name for p in out.iterdir())
    sheets = len(files) // 2
    assert files == sorted(f"kit-sheet-{k}.{f}" for k in range(1, sheets + 1) for f in ("dxf", "lbrn2"))
    assert f"5 parts on {sheets} sheet" in result.output and "100 x 100 mm, gap 1.15 mm, rotate 180" in result.output
    assert "sheet 1: " in result.output and "material use " in result.output and " of cut" in result.output


def test_the_files_are_named_after_the_one_design_or_nest_and_no_bar_off_a_terminal(designs, tmp_path):
    """Sheets of one design are named after it, of several ``nest-sheet-<k>`` (not after the first);
    off a terminal the progress bar prints nothing (its label would be a stray line)."""
    result = run("nest", f"{designs[0]}:1", f"{designs[1]}:1", "-o", tmp_path / "two", "--time", "1")
    assert result.exit_code == 0, result.output
    assert [p.name for p in (tmp_path / "two").iterdir()] == ["nest-sheet-1.dxf"]
    assert result.output.splitlines()[0] == f"wrote {tmp_path / 'two' / 'nest-sheet-1.dxf'}"
    # the name a nest of one design takes (the command passes no --name on): square-sheet-1.dxf in
    # test_a_quarter_turn_is_refused_when_the_kerf_differs_along_x_and_y, and default_stem's example


@pytest.mark.parametrize(
    "args, match",
    [
        (["--count", "0"], r"count must be an integer >= 1 and <= 10000, got 0"),
        (["--gap", "0.1"], r"gap_mm must be >= the cut's width \(0.15 mm.*got 0.1; use --gap 1.15"),
        (["--time", "0"], r"time_s must be .*> 0, got 0"),
        (["--sheet", "700x400"], r"the sheet 700 x 400 mm is larger than the 600 x 400 mm bed.*--sheet 600x400"),
        (["--sheet", "30x30"], r"part 'square#0:1' \(40.15 x 40.15 mm\) does not fit on the 30 x 30 mm sheet"),
        (["--sheet", "big"], r"expected WIDTHxHEIGHT in mm like 600x400, got 'big'"),
        (["--rotate", "45"], r"'45' is not one of '90', '180', 'free', 'none'|Invalid value for '--rotate'"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_no_file(designs, tmp_path, args, match):
    import re

    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["nest", str(designs[0]), "-o", str(out), "--time", "1", *args])
    assert result.exit_code == 2
    assert re.search(match, result.output), result.output
    assert not out.exists()


def test_a_count_below_one_in_the_per_design_form_and_the_api_errors(designs, tmp_path):
    result = run("nest", f"{designs[0]}:0", "-o", tmp_path / "out")
    assert result.exit_code == 2 and "count of square must be an integer >= 1 and <= 10000, got 0" in result.output
    with pytest.raises(ParameterError, match="give at least one design to nest"):
        nest_designs([], tmp_path / "out")
    d = load_design(designs[0])
    with pytest.raises(ParameterError, match=r"cutter formats \(dxf, svg, lbrn2\) only, got stl"):
        nest_designs([(d, 1)], tmp_path / "out", ("stl",))
    with pytest.raises(ParameterError, match=r"sheet_mm must be \(width, height\) in mm, got 600"):
        nest_designs([(d, 1)], tmp_path / "out", sheet_mm=600)
    assert not (tmp_path / "out").exists()


def test_designs_of_two_profiles_or_an_inlay_kit_are_refused(designs, tmp_path):
    d = load_design(designs[0])
    router = load_design(designs[1], overrides=['output.laser_profile="router-6mm-mdf"'])
    with pytest.raises(FabtilesError, match=r"one cutter profile.*square uses 'laser-3mm-plywood', circle uses"):
        nest_designs([(d, 1), (router, 1)], tmp_path / "out")
    kit = load_design(designs[0], overrides=['output.laser_mode="inlay"'])
    with pytest.raises(ParameterError, match=r"square is an inlay kit .*not nested"):
        nest_designs([(kit, 1)], tmp_path / "out")


def test_a_quarter_turn_is_refused_when_the_kerf_differs_along_x_and_y(designs, tmp_path):
    text = (Path(__file__).resolve().parents[2] / "profiles" / "laser-3mm-plywood.toml").read_text()
    profile = tmp_path / "aniso.toml"
    profile.write_text(text.replace("kerf_mm = 0.15 ", "kerf_mm = 0.15\nkerf_y_mm = 0.2 "), encoding="utf-8")
    d = load_design(designs[0], overrides=[f'output.laser_profile="{profile}"'])
    with pytest.raises(
        ParameterError, match=r"kerf along Y unlike along X.*use --rotate 180 or --rotate none, got '90'"
    ):
        nest_designs([(d, 1)], tmp_path / "out")
    nest_designs([(d, 2)], tmp_path / "out", rotations="180", time_s=1)
    assert (tmp_path / "out" / "square-sheet-1.dxf").is_file()


def test_part_outline_of_loose_parts_is_their_convex_hull():
    from shapely.geometry import box

    from fabtiles.geometry.cut_plan import CutOptions, plan_cut

    two = shapely.union_all([box(0, 0, 10, 10), box(20, 0, 30, 10)])
    plan = plan_cut(two, box(0, 0, 30, 10), CutOptions.of(profile=PLY))
    assert part_outline(plan).area == pytest.approx(30.15 * 10.15, rel=1e-3)


def test_meerk40t_loads_a_nested_sheet_where_it_lies(nested, tmp_path):
    _, out, _ = nested
    dxf = out / "nest-sheet-1.dxf"
    job = meerk40t(dxf, tmp_path)
    every = np.concatenate(rings(dxf))
    assert job["added"] == len(rings(dxf))
    allp = np.concatenate(burns(job["gcode"]))
    # the burns span the file's paths at their own size (not scaled to MeerK40t's 235 mm bed)
    assert allp.max(axis=0) - allp.min(axis=0) == pytest.approx(every.max(axis=0) - every.min(axis=0), abs=0.05)


def test_the_commands_choices_are_the_nestings():
    from fabtiles.cli import nest as cli_nest
    from fabtiles.geometry import nest

    assert cli_nest.ROTATIONS == tuple(nest.ROTATIONS) and cli_nest.DEFAULT_TIME_S == nest.DEFAULT_TIME_S


def test_the_public_nest_takes_files_and_designs(tmp_path):
    import fabtiles as ft
    from fabtiles.designs.design_file import design_from_text

    small = tmp_path / "a.toml"
    small.write_text('[motif]\npreset = "table3-3"\n[tile]\noutline = "circle"\nsize = 40\nframe = 3\n')
    other = design_from_text(
        '[motif]\npreset = "table3-1"\n[tile]\noutline = "square"\nsize = 40\nframe = 3\n', name="b"
    )
    result = ft.nest([small, (other, 2)], tmp_path / "out", sheet_mm=(200, 150), time_s=1)
    files = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert files == ["nest-sheet-1.dxf"]  # several designs: named after none of them
    assert len(result.nesting.placements) == 3  # one of a, two of b
