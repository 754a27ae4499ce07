"""[tile] border_mm, border_motif and border_angle in a design: the tile built, the hankin frieze's
default angle, the fit noted, a cylinder refusing a border."""

import pytest

from fabtiles.core.errors import DesignError
from fabtiles.designs.design_file import border_angle, design_from_dict, design_notes

TILE = {"outline": "square", "size": 60, "frame": 2, "stroke": 1, "border_mm": 8}


def test_a_design_builds_its_border():
    d = design_from_dict({"motif": {"preset": "table3-3"}, "packing": {"radius": 8}, "tile": TILE})
    tile = d.build_tile()
    assert tile.border_mm == 8 and tile.border_motif == "stars" and tile.border().fit.repeats == (5, 5)
    assert design_notes(d) == [tile.border().fit.line("stars")]


def test_the_hankin_frieze_takes_the_packings_contact_angle_unless_given():
    packing = {"kind": "archimedean", "tiling": "4.8.8", "edge": 8, "method": "hankin", "contact_angle": 60}
    tile = {**TILE, "border_motif": "hankin"}
    d = design_from_dict({"packing": packing, "tile": tile})
    assert border_angle(d) == 60 and d.build_tile().border_angle == 60
    assert "hankin at 60 degrees" in design_notes(d)[-1]
    d = design_from_dict({"packing": packing, "tile": {**tile, "border_angle": 45}})
    assert d.build_tile().border_angle == 45
    d = design_from_dict({"motif": {"preset": "table3-3"}, "packing": {"radius": 8}, "tile": tile})
    assert d.build_tile().border_angle == 67.5


def test_a_bad_border_angle_names_the_key():
    with pytest.raises(DesignError, match="border_angle"):
        design_from_dict(
            {"motif": {"preset": "table3-3"}, "packing": {"radius": 8}, "tile": {**TILE, "border_angle": 95}}
        ).build_tile()


def test_a_cylinder_takes_no_border():
    with pytest.raises(DesignError, match=r"\[tile\] border_mm is not a key of a cylinder's tile"):
        design_from_dict(
            {
                "motif": {"preset": "table3-3"},
                "packing": {"radius": 8},
                "tile": {"stroke": 1, "border_mm": 5},
                "surface": {"shape": "cylinder", "diameter": 60, "length": 80},
            }
        )
