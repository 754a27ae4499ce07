"""``[surface]``: a design on a cylinder parsed, its defaults by style, its circumference fitted to whole
periods, its bad values refused with the key named."""

import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles.core import schema
from fabtiles.core.errors import DesignError
from fabtiles.designs.design_file import SurfaceSpec, design_from_text

ROLLER = """
[motif]
preset = "table3-3"
[packing]
radius = 10
[surface]
shape = "cylinder"
diameter = 60
length = 80
"""


def design(text=ROLLER, extra=""):
    return design_from_text(text + extra, name="roller", source="roller.toml")


def test_a_cylinder_design_is_its_unrolled_strip():
    d = design()
    assert d.surface.cylinder and d.surface.fit == "packing"
    t = d.tile_spec
    assert t.outline == "rectangle" and t.frame == 0 and t.corner_radius == 0
    assert t.size[0] == pytest.approx(math.pi * 60) and t.size[1] == 80
    tile = d.build_tile()
    assert tile.outline_shape().bounds == pytest.approx((0, 0, math.pi * 60, 80))
    # the strip's width is a whole number of the pattern's periods: its ends meet at the seam
    periods = t.size[0] / tile.pattern.period[0]
    assert periods == pytest.approx(round(periods)) and round(periods) == 9


def test_the_fit_says_what_it_changed():
    d = design()
    assert d.fitted == (
        "surface: cylinder D 60 mm x 80 mm, 9 periods around (packing radius 10.00 -> 10.47 mm, +4.7 %)",
    )
    assert d.packing.radius == pytest.approx(math.pi * 60 / 18)
    assert d.surface.diameter == 60


def test_the_diameter_fit_keeps_the_packing():
    d = design(ROLLER.replace("length = 80", 'length = 80\nfit = "diameter"'))
    assert d.packing.radius == 10
    assert d.surface.diameter == pytest.approx(9 * 20 / math.pi)
    assert d.tile_spec.size[0] == pytest.approx(180)
    assert d.fitted == (
        "surface: cylinder D 60 -> 57.30 mm (-4.5 %) x 80 mm, 9 periods around (packing radius 10 mm kept)",
    )


def test_an_archimedean_tiling_fits_its_edge():
    text = """
[packing]
kind = "archimedean"
tiling = "4.8.8"
edge = 12
[packing.motifs]
8 = "table3-3"
4 = { n = 8, radii = [1, 2] }
[surface]
shape = "cylinder"
diameter = 50
length = 40
"""
    d = design(text)
    period = d.build_tile().pattern.period[0]
    assert d.tile_spec.size[0] / period == pytest.approx(round(d.tile_spec.size[0] / period))
    assert d.fitted[0].startswith("surface: cylinder D 50 mm x 40 mm, ") and "packing edge 12.00 -> " in d.fitted[0]


def test_a_cylinders_tile_section_may_give_the_stroke():
    d = design(extra="[tile]\nstroke = 1.5\n")
    assert d.tile_spec.stroke == 1.5


def test_the_defaults_follow_the_style():
    s = SurfaceSpec(shape="cylinder", diameter=60, length=80)
    assert (s.mirror_for("relief"), s.mirror_for("deboss"), s.mirror_for("pierced")) == (True, True, False)
    assert s.bore_for("relief") == schema.ROLLER_BORE_MM and s.bore_for("pierced") == 0
    assert (s.rim_for("relief"), s.rim_for("pierced")) == (schema.ROLLER_RIM_MM, schema.SHADE_RIM_MM)
    given = SurfaceSpec(shape="cylinder", diameter=60, length=80, mirror=False, bore_mm=6, rim_mm=0)
    assert (given.mirror_for("relief"), given.bore_for("deboss"), given.rim_for("pierced")) == (False, 6, 0)


def test_a_flat_design_is_flat():
    d = design_from_text('[motif]\npreset = "table3-3"\n[tile]\nsize = 50\n')
    assert d.surface == SurfaceSpec() and not d.surface.cylinder


@pytest.mark.parametrize(
    ("change", "match", "param"),
    [
        (
            ("radius = 10", "radius = 100"),
            r"roller.toml: \[surface\] diameter = 60 mm is too small for one period of the pattern: its "
            r"circumference, 188\.50 mm, is less than the pattern's period along x, 200\.00 mm "
            r"\(packing radius 100 mm\); "
            r"the diameter must be at least 63\.66 mm",
            "surface.diameter",
        ),
        (
            ("[packing]\nradius = 10\n", ""),
            r'\[surface\] shape = "cylinder" needs a \[packing\]: a lone motif does not repeat',
            "surface.shape",
        ),
        (("length = 80\n", ""), r'\[surface\] shape = "cylinder" needs length \(mm, > 0\)', "surface.length"),
        (("diameter = 60", "diameter = -3"), r"\[surface\] diameter must be a number of mm > 0, got -3", None),
        (('shape = "cylinder"', 'shape = "cone"'), r"shape = 'cone' is not valid", None),
        (
            ('shape = "cylinder"', 'shape = "flat"'),
            r'\[surface\] diameter is a key of shape = "cylinder", not of shape = \'flat\'',
            "surface.diameter",
        ),
        (("length = 80", "length = 80\nbore = 8"), r"unknown key 'bore' in \[surface\]; did you mean 'bore_mm'", None),
        (
            ("[surface]", "[tile]\nsize = 100\n[surface]"),
            r"\[tile\] size is not a key of a cylinder's tile: .* remove size",
            "tile.size",
        ),
    ],
)
def test_bad_surfaces_are_refused(change, match, param):
    old, new = change
    assert old in ROLLER
    with pytest.raises(DesignError, match=match) as info:
        design(ROLLER.replace(old, new))
    if param is not None:
        assert info.value.param == param


def test_a_surface_must_be_a_table():
    from fabtiles.designs.design_file import design_from_dict

    with pytest.raises(DesignError, match=r"\[surface\] must be a table, got 3"):
        design_from_dict({"motif": {"preset": "table3-3"}, "tile": {"size": 50}, "surface": 3})


@settings(max_examples=examples(40), deadline=None)
@given(
    diameter=st.floats(20, 300),
    radius=st.floats(3, 30),
    fit=st.sampled_from(schema.SURFACE_FITS),
    kind=st.sampled_from(("hex", "square")),
)
def test_the_fit_makes_whole_periods_round_and_moves_the_least(diameter, radius, fit, kind):
    """Whatever the sizes, the strip holds a whole number of periods, and the value fitted moves by at most
    half a period's share of it (the nearest whole number is taken)."""
    around = math.pi * diameter
    assume(around >= 2 * radius)
    text = ROLLER.replace("radius = 10", f'kind = "{kind}"\nradius = {radius!r}').replace(
        "diameter = 60", f'diameter = {diameter!r}\nfit = "{fit}"'
    )
    d = design(text)
    period = 2 * d.packing.radius  # hex and square: 2R along x
    n = d.tile_spec.size[0] / period
    assert n == pytest.approx(round(n), abs=1e-9) and round(n) >= 1
    assert d.tile_spec.size[0] == pytest.approx(math.pi * d.surface.diameter)
    if fit == "packing":
        assert d.surface.diameter == diameter
        assert abs(d.packing.radius / radius - 1) <= 0.5 / round(n) + 1e-9 or round(n) == 1
    else:
        assert d.packing.radius == radius
        assert abs(d.surface.diameter - diameter) <= radius / math.pi + 1e-9


STAMP = """
[motif]
preset = "table3-3"
[packing]
radius = 10
[tile]
outline = "hexagon"
size = 60
[surface]
shape = "stamp"
"""


def test_a_stamp_keeps_its_tile_and_takes_the_block_defaults():
    d = design(STAMP)
    assert d.surface.stamp and not d.surface.cylinder
    assert d.tile_spec.outline == "hexagon" and d.tile_spec.size == (60.0, 60.0)
    assert (d.surface.block_mm, d.surface.grip_mm, d.surface.groove_mm) == (20.0, 3.0, 4.0)
    assert d.surface.mirror_for("relief") is True
    assert design(STAMP, "mirror = false\n").surface.mirror_for("relief") is False


@pytest.mark.parametrize(
    ("extra", "match", "param"),
    [
        ("diameter = 60\n", r'diameter is a key of shape = "cylinder", not of shape = \'stamp\'', "surface.diameter"),
        ("bore_mm = 8\n", r'bore_mm is a key of shape = "cylinder", not of shape = \'stamp\'', "surface.bore_mm"),
        ("grip_mm = 25\n", r"\[surface\] grip_mm must be a number of mm > 0 and <= 20, got 25", None),
        ("block_mm = 0\n", r"\[surface\] block_mm must be a number of mm > 0 and <= 200, got 0", None),
    ],
)
def test_bad_stamps_are_refused(extra, match, param):
    with pytest.raises(DesignError, match=match) as info:
        design(STAMP, extra)
    if param is not None:
        assert info.value.param == param


def test_a_cylinder_refuses_a_stamps_keys():
    with pytest.raises(DesignError, match=r'grip_mm is a key of shape = "stamp", not of shape = \'cylinder\'') as info:
        design(ROLLER, "grip_mm = 2\n")
    assert info.value.param == "surface.grip_mm"
