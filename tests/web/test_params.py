import pytest

from fabtiles.web.params import QueryError, design_from_query


def test_full_query_maps_to_design_sections():
    d = design_from_query({
        "n": "12", "radii": "123,85,178", "alpha": "23", "spr": "-7", "special": "2", "rotation": "0",
        "packing": "hex", "radius": "15", "gap_n": "6", "gap_radii": "0.5,1", "outline_circles": "true",
        "fill": "0.9", "outline": "rectangle", "width": "200", "height": "100", "frame": "5", "stroke": "1",
        "join": "round", "corner_radius": "2", "laser_profile": "laser-3mm-acrylic",
        "printer_profile": "fdm-0.6mm", "laser_mode": "score", "print_style": "deboss",
    })
    assert d["motif"] == {"n": 12, "radii": [123.0, 85.0, 178.0], "alpha": 23.0, "spr": -7.0, "special": 2, "rotation": 0.0}
    assert d["packing"] == {"kind": "hex", "radius": 15.0, "outline_circles": True, "fill": 0.9,
                            "gap_motif": {"n": 6, "radii": [0.5, 1.0]}}
    assert d["tile"] == {"outline": "rectangle", "size": [200.0, 100.0], "frame": 5.0, "stroke": 1.0,
                         "join": "round", "corner_radius": 2.0}
    assert d["output"] == {"laser_profile": "laser-3mm-acrylic", "printer_profile": "fdm-0.6mm",
                           "laser_mode": "score", "print_style": "deboss"}


def test_packing_none_drops_the_packing_section():
    d = design_from_query({"preset": "table1-part1", "packing": "none", "width": "80"})
    assert "packing" not in d and d["tile"]["size"] == [80.0, 80.0]
    assert design_from_query({"preset": "x", "special": "none"})["motif"] == {"preset": "x"}


@pytest.mark.parametrize(
    "query, field, match",
    [
        ({"n": "eight"}, "n", r"n must be an integer, got 'eight'"),
        ({"n": "8.5"}, "n", r"n must be an integer, got '8.5'"),
        ({"radii": "1,x"}, "radii", r"radii must be a number, got 'x'"),
        ({"radii": ","}, "radii", r"radii must be comma-separated numbers"),
        ({"alpha": "nan"}, "alpha", r"alpha must be a finite number, got 'nan'"),
        ({"spr": "inf"}, "spr", r"spr must be a finite number"),
        ({"special": "two"}, "special", r"special must be an integer"),
        ({"rotation": ""}, "rotation", r"rotation must be a number, got ''"),
        ({"radius": "big"}, "radius", r"radius must be a number"),
        ({"fill": "x"}, "fill", r"fill must be a number"),
        ({"gap_n": "1.5"}, "gap_n", r"gap_n must be an integer"),
        ({"gap_radii": "a"}, "gap_radii", r"gap_radii must be a number"),
        ({"outline_circles": "maybe"}, "outline_circles", r"outline_circles must be true or false, got 'maybe'"),
        ({"width": "-"}, "width", r"width must be a number"),
        ({"height": "x"}, "height", r"height must be a number"),
        ({"height": "100"}, "width", r"width is missing"),
        ({"frame": "x"}, "frame", r"frame must be a number"),
        ({"stroke": "x"}, "stroke", r"stroke must be a number"),
        ({"corner_radius": "x"}, "corner_radius", r"corner_radius must be a number"),
        ({"colour": "red"}, "colour", r"'colour' is not a valid parameter, must be one of: preset, n, radii"),
        ({"packing": "none", "radius": "5"}, "radius", r"radius has no meaning with packing=none"),
    ],
)
def test_bad_query_names_the_field(query, field, match):
    with pytest.raises(QueryError, match=match) as info:
        design_from_query(query)
    assert info.value.field == field
