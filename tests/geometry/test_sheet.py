"""Sheets: tiles laid out on the laser bed."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from dxf_helpers import read_checked, star_plate
from model_files import write_cut
from shapely.geometry import box

from fabtiles import FabricationError, ParameterError
from fabtiles.geometry.sheet import layout_sheet
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")


def test_rows_and_gap():
    tile = star_plate(size=100)
    sheet = layout_sheet([tile], PLY, copies=8)
    gap = PLY.kerf_mm + 2
    assert np.array(sheet.offsets[:6]) == pytest.approx(
        np.array(
            [(0, 0), (100 + gap, 0), (2 * (100 + gap), 0), (3 * (100 + gap), 0), (4 * (100 + gap), 0), (0, 100 + gap)]
        )
    )
    outlines = shapely.get_parts(sheet.outline)
    assert len(outlines) == 8
    d = shapely.distance(outlines[:, None], outlines[None, :])
    assert d[~np.eye(8, dtype=bool)].min() == pytest.approx(gap)
    assert sheet.region.is_valid and sheet.region.area == pytest.approx(8 * tile[0].area)
    xmin, ymin, xmax, ymax = sheet.outline.bounds
    assert (xmin, ymin) == (0, 0) and xmax <= 600 and ymax <= 400


def test_mixed_tiles_fill_and_centrelines():
    a = (box(0, 0, 150, 100), box(0, 0, 150, 100))
    b = (box(0, 0, 50, 50).difference(box(10, 10, 40, 40)), box(0, 0, 50, 50))
    seg = [np.array([[[0, 0], [150, 100]]], float), np.array([[[0, 0], [50, 50]]], float)]
    sheet = layout_sheet([a, b], PLY, fill=True, gap_mm=5, centrelines=seg)
    assert len(sheet.offsets) > 6
    assert sheet.centrelines.shape == (len(sheet.offsets), 2, 2)
    assert sheet.size[0] <= 600 and sheet.size[1] <= 400
    assert sheet.centrelines[1, 0].tolist() == list(sheet.offsets[1])


def test_too_many_copies():
    with pytest.raises(FabricationError, match="do not fit on the 600 x 400 mm bed"):
        layout_sheet([star_plate(size=100)], PLY, copies=40)
    with pytest.raises(ParameterError, match=r"gap_mm must be a finite number > 0.15"):
        layout_sheet([star_plate(size=100)], PLY, gap_mm=0.1)
    with pytest.raises(ParameterError, match="copies must be an integer"):
        layout_sheet([star_plate(size=100)], PLY, copies=0)


def test_sheet_dxf_has_no_loose_part_findings(tmp_path):
    sheet = layout_sheet([star_plate(size=100)], PLY, copies=6)
    path = tmp_path / "sheet.dxf"
    report = write_cut(path, region=sheet.region, outline=sheet.outline, profile=PLY)
    assert report.ok, report.summary()
    assert report.stats["outer_contours"] == 6 and report.stats["inner_contours"] == 54
    layers = [e.dxf.layer for e in read_checked(path).modelspace()]
    assert layers == ["INNER"] * 54 + ["OUTER"] * 6
