"""One model per build (issue 31): the work a build does is counted, not timed.

A build makes the cut plan and the print model once each, whatever formats it
writes, and each finding is printed once. The calls are counted with
:mod:`cProfile` (which sees every call of a function, however it was imported),
during real builds of small designs.
"""

from __future__ import annotations

import cProfile
import pstats
from pathlib import Path

import pytest
from click.testing import CliRunner
from designs import design_toml

import fabtiles
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import design_from_text
from fabtiles.making import build_design

PACKAGE = Path(fabtiles.__file__).resolve().parent

LASER = design_toml(
    output={"laser_profile": "laser-3mm-plywood", "printer_profile": "fdm-0.4mm", "fill_small_holes": False}
)

ROUTER = design_toml(
    radius=40,
    size=200,
    frame=12,
    stroke=8.0,
    output={"laser_profile": "router-6mm-mdf", "printer_profile": "fdm-0.4mm", "fill_small_holes": False},
)


def calls(run) -> dict[str, int]:
    """``{"module.py:function": calls}`` of the package's functions during ``run()``."""
    prof = cProfile.Profile()
    prof.runcall(run)
    counts: dict[str, int] = {}
    for (filename, _line, func), (_cc, ncalls, *_rest) in pstats.Stats(prof).stats.items():
        path = Path(filename)
        if PACKAGE in path.parents:
            key = f"{path.relative_to(PACKAGE).as_posix()}:{func}"
            counts[key] = counts.get(key, 0) + ncalls
    return counts


def test_a_five_format_build_plans_the_cut_and_checks_the_print_once(tmp_path):
    design = design_from_text(LASER, name="five")
    formats = ["dxf", "svg", "lbrn2", "stl", "3mf"]
    counted = calls(lambda: build_design(design, tmp_path, formats))
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(f"five.{f}" for f in formats)
    assert counted["geometry/machine_geometry.py:cut_geometry"] == 1
    assert counted["geometry/cut_plan.py:plan_cut"] == 1  # the laser preparation: checks and contours
    assert counted["geometry/laser_checks.py:check_laser"] == 1
    assert counted["solid/parts.py:prepare_print"] == 1  # the print checks
    assert counted["geometry/print_checks.py:check_print"] == 1
    assert counted["solid/print_model.py:print_model"] == 1
    # each profile's TOML parsed once: the laser's and the printer's
    assert counted["machines/profiles.py:_parse"] == 2


def test_a_router_build_with_its_picture_opens_the_holes_once(tmp_path):
    design = design_from_text(ROUTER, name="router")
    counted = calls(lambda: build_design(design, tmp_path, ["dxf", "svg"], preview=True))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["router.dxf", "router.preview.svg", "router.svg"]
    assert counted["geometry/tool_opening.py:open_region"] == 1  # the bit's round corners, made once
    assert counted["geometry/machine_geometry.py:cut_geometry"] == 1
    assert counted["geometry/cut_plan.py:plan_cut"] == 1
    assert counted["machines/profiles.py:_parse"] == 2


def test_each_finding_is_printed_once_whatever_the_formats(tmp_path):
    path = tmp_path / "d.toml"
    path.write_text(LASER)
    one = CliRunner().invoke(
        cli,
        ["build", str(path), "-o", str(tmp_path / "a"), "--format", "dxf", "--format", "stl"],
        catch_exceptions=False,
    )
    five = CliRunner().invoke(
        cli,
        [
            "build",
            str(path),
            "-o",
            str(tmp_path / "b"),
            "--format",
            "dxf",
            "--format",
            "svg",
            "--format",
            "lbrn2",
            "--format",
            "stl",
            "--format",
            "3mf",
        ],
        catch_exceptions=False,
    )
    assert one.exit_code == 0 and five.exit_code == 0, one.output + five.output

    def findings(output):
        return [line for line in output.splitlines() if line.startswith("  - ")]

    assert findings(five.output) == findings(one.output)
    assert len(findings(five.output)) == len(set(findings(five.output))) > 0
    assert any("small_hole" in line for line in findings(five.output))
    heads = [line for line in five.output.splitlines() if not line.startswith((" ", "wrote "))]
    assert heads == [line for line in heads if line.startswith(("laser laser-3mm-plywood: ", "printer fdm-0.4mm: "))]
    assert len(heads) == 2


@pytest.mark.parametrize("fmt", ["dxf", "svg", "lbrn2"])
def test_every_cutter_file_of_a_build_is_written_from_one_plan(tmp_path, fmt):
    """The file a build writes beside others is the file it writes alone (a writer is a function of the plan)."""
    design = design_from_text(LASER, name="t")
    build_design(design, tmp_path / "alone", [fmt])
    build_design(design, tmp_path / "all", ["dxf", "svg", "lbrn2"])
    alone, together = (tmp_path / "alone" / f"t.{fmt}").read_bytes(), (tmp_path / "all" / f"t.{fmt}").read_bytes()
    if fmt == "dxf":  # the geometry: the ENTITIES section (tests/making/test_reproducible.py compares whole files)
        alone, together = (d.split(b"ENTITIES", 1)[1].split(b"ENDSEC", 1)[0] for d in (alone, together))
    assert alone == together
