"""making/nesting.py's plan and bytes (the web's nest): the same sheets as the files nest_designs writes."""

from __future__ import annotations

import io
import zipfile

import pytest

from fabtiles import LimitError
from fabtiles.designs.design_file import design_from_text
from fabtiles.machines.limits import CLI_LIMITS, WEB_LIMITS, check_nest
from fabtiles.making.nesting import nest_bytes, nest_designs, plan_nest

DESIGN = """
[motif]
preset = "table3-1"
[packing]
radius = 8
[tile]
size = 40
frame = 3
"""


@pytest.fixture(scope="module")
def design():
    return design_from_text(DESIGN, name="square")


def test_nest_bytes_are_the_files_nest_designs_writes(design, tmp_path):
    made = nest_bytes([(design, 2)], ("dxf", "svg"), sheet_mm=(100, 60), rotations="none", time_s=1, name="n")
    assert [n for n, _ in made.files] == ["n-sheet-1.dxf", "n-sheet-1.svg"]
    written = nest_designs([(design, 2)], tmp_path, ("svg",), sheet_mm=(100, 60), rotations="none", time_s=1, name="n")
    # the packer's placements may differ between two runs; the sheets' count and parts do not
    assert len(written.sheets) == len(made.job.sheets()) == 1
    assert written.sheets[0]["designs"] == made.job.sheets()[0]["designs"] == {"square": 2}
    with zipfile.ZipFile(io.BytesIO(made.zip_bytes())) as zf:
        assert zf.namelist() == ["n-sheet-1.dxf", "n-sheet-1.svg"]
        assert zf.read("n-sheet-1.svg") == dict(made.files)["n-sheet-1.svg"]


def test_the_picture_names_each_part_on_its_sheet(design):
    # two sheets show each picture is its own sheet's (the packer takes a second a sheet)
    job = plan_nest([(design, 2)], sheet_mm=(60, 60), time_s=1)
    assert job.nesting.sheets == 2  # one 40 mm tile per 60 mm sheet
    for k in range(2):
        svg = job.picture(k)
        assert svg.count('data-part="square"') == 1 and 'viewBox="0 0 60 60"' in svg
        assert f"<title>sheet {k + 1}: 1 part, material use" in svg


def test_the_limits_on_parts_and_time(design):
    check_nest(60, 10, WEB_LIMITS)
    check_nest(5_000, 3600, CLI_LIMITS)
    with pytest.raises(LimitError, match=r"the nest has 61 parts, more than the limit of 60; nest fewer copies"):
        check_nest(61, 1, WEB_LIMITS)
    with pytest.raises(LimitError, match=r"time_s must be at most 10 s here, got 10\.5"):
        check_nest(1, 10.5, WEB_LIMITS)
    with pytest.raises(LimitError, match=r"the nest has 61 parts"):
        plan_nest([(design, 61)], limits=WEB_LIMITS)
    with pytest.raises(ValueError, match=r"time_s must be a finite number > 0, got 0"):
        plan_nest([(design, 1)], time_s=0)
