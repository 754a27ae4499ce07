"""The laser job's length and time, where users read it: build, check, sweep's index.csv, the web app."""

from __future__ import annotations

import csv
import re

import pytest
from click.testing import CliRunner
from designs import design_toml

from fabtiles.cli.main import cli

DESIGN = design_toml(stroke=None, output={"formats": ["dxf", "lbrn2"], "fill_small_holes": True})
JOB = re.compile(
    r"^  laser job: ([0-9.]+) m of cut, ([0-9,]+) pierces?, (?:([0-9.]+) cm\^2 engraved, )?about ([0-9,]+) min$", re.M
)


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args], catch_exceptions=False)


def test_build_and_check_print_the_same_job_line(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN)
    built = run("build", design, "-o", tmp_path / "out")
    assert built.exit_code == 0, built.output
    lines = JOB.findall(built.output)
    assert len(lines) == 1  # the DXF and the LightBurn project: one job, one cut plan, printed once
    checked = run("check", design)
    assert JOB.findall(checked.output) == lines[:1]
    metres, pierces, _, minutes = lines[0]
    assert float(metres) > 1 and int(pierces.replace(",", "")) > 10 and int(minutes) >= 1


def test_engrave_mode_prints_the_engraved_area(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.replace('formats = ["dxf", "lbrn2"]', 'formats = ["svg"]\nlaser_mode = "engrave"'))
    built = run("build", design, "-o", tmp_path / "out")
    ((_metres, pierces, area, _),) = JOB.findall(built.output)
    assert pierces == "1" and float(area) > 10  # the outline is the only cut


def test_a_sheet_is_the_sum_of_its_tiles(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.replace('formats = ["dxf", "lbrn2"]', 'formats = ["dxf"]'))
    one = JOB.findall(run("build", design, "-o", tmp_path / "one").output)[0]
    four = JOB.findall(run("build", design, "-o", tmp_path / "four", "--copies", 4).output)[0]
    assert int(four[1].replace(",", "")) == 4 * int(one[1].replace(",", ""))
    assert float(four[0]) == pytest.approx(4 * float(one[0]), rel=0.05)


def test_sweep_index_has_the_job_columns(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.replace('formats = ["dxf", "lbrn2"]', 'formats = ["dxf"]'))
    result = run("sweep", design, "--vary", "packing.radius=8,12", "-o", tmp_path / "sweep", "--jobs", 1)
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader((tmp_path / "sweep" / "index.csv").open()))
    assert len(rows) == 2
    for row in rows:
        assert float(row["cut_length_mm"]) > 1000 and int(row["pierces"]) > 10 and float(row["laser_time_s"]) > 60
        assert float(row["engrave_area_mm2"]) == 0 and float(row["travel_mm"]) > 0
    assert int(rows[0]["pierces"]) != int(rows[1]["pierces"])  # a smaller radius, more holes
