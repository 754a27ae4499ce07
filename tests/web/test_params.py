import pytest

from fabtiles.web.params import QueryError, design_from_query


def test_full_query_maps_to_design_sections():
    d = design_from_query(
        {
            "n": "12",
            "radii": "123,85,178",
            "alpha": "23",
            "spr": "-7",
            "special": "2",
            "rotation": "0",
            "packing": "hex",
            "radius": "15",
            "gap_n": "6",
            "gap_radii": "0.5,1",
            "outline_circles": "true",
            "fill": "0.9",
            "outline": "rectangle",
            "width": "200",
            "height": "100",
            "frame": "5",
            "stroke": "1",
            "join": "round",
            "corner_radius": "2",
            "laser_profile": "laser-3mm-acrylic",
            "printer_profile": "fdm-0.6mm",
            "laser_mode": "score",
            "print_style": "deboss",
        }
    )
    assert d["motif"] == {
        "n": 12,
        "radii": [123.0, 85.0, 178.0],
        "alpha": 23.0,
        "spr": -7.0,
        "special": 2,
        "rotation": 0.0,
    }
    assert d["packing"] == {
        "kind": "hex",
        "radius": 15.0,
        "outline_circles": True,
        "fill": 0.9,
        "gap_motif": {"n": 6, "radii": [0.5, 1.0]},
    }
    assert d["tile"] == {
        "outline": "rectangle",
        "size": [200.0, 100.0],
        "frame": 5.0,
        "stroke": 1.0,
        "join": "round",
        "corner_radius": 2.0,
    }
    assert d["output"] == {
        "laser_profile": "laser-3mm-acrylic",
        "printer_profile": "fdm-0.6mm",
        "laser_mode": "score",
        "print_style": "deboss",
    }


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


# Query parameters that carry a design key under another name (or two).
QUERY_NAMES = {
    ("tile", "width"): ("tile", "size"),
    ("tile", "height"): ("tile", "size"),
    **{("motifs", str(p)): ("packing", "motifs") for p in (3, 4, 6, 8, 12)},  # motif_<sides>
    **{("faces", chr(ord("A") + i)): ("colour", "faces") for i in range(26)},  # face_<letter>
    **{("shades", chr(ord("A") + i)): ("colour", "shades") for i in range(26)},  # shade_<letter>
}


def test_every_design_key_is_a_query_parameter():
    """The web app says everything a design file says (and nothing else)."""
    from fabtiles.designs import design_file as design
    from fabtiles.web.params import FIELDS, NOT_WEB_PARAMS

    keys = {("motif", k) for k in design.MOTIF_KEYS}
    keys |= {("packing", k) for k in design.PACKING_KEYS if k != "gap_motif"}
    keys |= {("gap_motif", k) for k in design.MOTIF_KEYS}  # [packing] gap_motif = { ... }
    keys |= {("tile", k) for k in design.TILE_KEYS} | {("output", k) for k in design.OUTPUT_KEYS}
    keys |= {("colour", k) for k in design.COLOUR_KEYS} | {("surface", k) for k in design.SURFACE_KEYS}
    web = {QUERY_NAMES.get((section, name), (section, name)) for section, name, _ in FIELDS.values()}
    assert NOT_WEB_PARAMS <= keys
    assert web == keys - NOT_WEB_PARAMS, (keys - NOT_WEB_PARAMS - web, web - keys)


def test_new_keys_map_to_the_design_and_validate():
    from fabtiles.designs.design_file import design_from_dict

    d = design_from_query(
        {
            "preset": "table3-3",
            "radius": "10",
            "seamless": "true",
            "gap_alpha": "10",
            "gap_spr": "-0.1",
            "gap_special": "2",
            "gap_rotation": "30",
            "outline": "hexagon",
            "width": "60",
            "miter_limit": "2.5",
            "fill_small_holes": "false",
            "base_mm": "2.5",
            "relief_mm": "1",
            "pierced_mm": "3",
            "deboss_mm": "0.6",
            "name": "my-tile",
        }
    )
    assert d["packing"] == {
        "radius": 10.0,
        "seamless": True,
        "gap_motif": {"n": 6, "radii": [0.5, 1.0], "alpha": 10.0, "spr": -0.1, "special": 2, "rotation": 30.0},
    }
    assert d["tile"] == {"outline": "hexagon", "size": [60.0, 60.0], "miter_limit": 2.5}
    assert d["output"] == {
        "fill_small_holes": False,
        "base_mm": 2.5,
        "relief_mm": 1.0,
        "pierced_mm": 3.0,
        "deboss_mm": 0.6,
        "name": "my-tile",
    }
    spec = design_from_dict(d, source="query")
    assert spec.name == "my-tile" and spec.output.heights()["base_mm"] == 2.5
    assert design_from_query({"gap_special": "none"}).get("packing") is None


@pytest.mark.parametrize(
    "query, field, match",
    [
        ({"fill_small_holes": "sometimes"}, "fill_small_holes", r"fill_small_holes must be true or false"),
        ({"seamless": "2"}, "seamless", r"seamless must be true or false"),
        ({"base_mm": "thick"}, "base_mm", r"base_mm must be a number, got 'thick'"),
        ({"miter_limit": "inf"}, "miter_limit", r"miter_limit must be a finite number"),
        ({"gap_special": "x"}, "gap_special", r"gap_special must be an integer"),
    ],
)
def test_bad_new_keys_name_the_field(query, field, match):
    with pytest.raises(QueryError, match=match) as info:
        design_from_query(query)
    assert info.value.field == field


def test_a_parquet_deformation_is_three_query_parameters():
    from fabtiles import DesignError
    from fabtiles.designs.design_file import design_from_dict

    query = {"packing": "archimedean", "tiling": "4.8.8", "edge": "10", "method": "hankin", "width": "80"}
    query |= {"contact_angle": "30", "contact_angle_to": "70", "parquet_direction": "y", "parquet_curve": "smooth"}
    packing = design_from_dict(design_from_query(query)).packing
    assert (packing.contact_angle_to, packing.parquet_direction, packing.parquet_curve) == (70.0, "y", "smooth")
    with pytest.raises(DesignError, match=r"parquet_curve = 'cubic' is not valid, must be one of: linear, smooth"):
        design_from_dict(design_from_query({**query, "parquet_curve": "cubic"}))
