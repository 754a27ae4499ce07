"""The cut plan's refusals (fabtiles.geometry.cut_plan): modes it cannot plan on their own or without their input."""

from __future__ import annotations

import pytest
import shapely
from shapely.geometry import box

from fabtiles import ParameterError
from fabtiles.geometry.cut_plan import plan_cut, plan_kit

PLATE = box(0, 0, 40, 40)


def test_the_inlay_mode_is_a_kit_not_one_plan():
    with pytest.raises(ParameterError, match=r"^the inlay mode writes a kit of two files \(lattice and pieces\): "
                                             r"export it with fabtiles\.export\.kit\.write_kit") as err:
        plan_cut(PLATE.difference(box(10, 10, 30, 30)), PLATE, profile="laser-3mm-plywood", mode="inlay")
    assert err.value.param == "mode"


@pytest.mark.parametrize("centrelines", [None, []])
def test_the_score_mode_needs_centrelines(centrelines):
    with pytest.raises(ParameterError, match=r"^the score mode needs centrelines \(an array of shape \(k, 2, 2\)\), "
                                             r"got none$") as err:
        plan_cut(PLATE, PLATE, profile="laser-3mm-plywood", mode="score", centrelines=centrelines)
    assert err.value.param == "centrelines"


def test_a_pocket_kit_needs_a_hole_large_enough_for_a_piece():
    # holes of 0.5 mm: far under the profile's smallest piece (twice min_hole_mm, 2.4 mm)
    holes = [box(x, y, x + 0.5, y + 0.5) for x in range(5, 35, 5) for y in range(5, 35, 5)]
    region = PLATE.difference(shapely.union_all(holes))
    with pytest.raises(ParameterError, match="^the tile has no hole large enough for a piece; nothing to pocket$") as err:
        plan_kit(region, PLATE, profile="laser-3mm-plywood", inlay_base="pocket")
    assert err.value.param == "region"
