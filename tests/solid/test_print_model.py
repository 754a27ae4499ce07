"""The print model of any design: every mesh fabtiles makes passes its own check as a slicer reads it.

Random small designs (40-80 mm tiles, the hex packing and Archimedean tilings, presets and
drawn motifs, every stroke, join and interlace, colours) in every print style, with small
holes kept and filled: the print model's parts (the 3MF's) and its fused body (the STL's),
written as binary STL, read back as float32 and checked as a slicer merges them
(:func:`fabtiles.solid.mesh_check.check_triangles`). No traceback, and no refusal of a mesh
fabtiles made itself; a design may still be refused for what it is (no material at all).
Every failing case found is pinned as an ``@example``.
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, Phase, example, given, reject, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles import DesignError, FabricationError
from fabtiles.designs.design_file import design_from_dict
from fabtiles.export.stl import read_stl_triangles, stl_bytes
from fabtiles.machines.profiles import PRINT_STYLES
from fabtiles.making.models import BuildOptions, Models
from fabtiles.pattern.tilings import ALL_TILINGS, unit_cell
from fabtiles.solid.mesh_check import check_triangles

PRESETS = ("table1-part1", "table1-part2", "table2-left", "table2-right", "table3-1", "table3-2", "table3-3")

REFUSED = ("the tile holds no material", "every groove of this deboss is narrower than min_hole_mm")
"""What a design may be refused for: what it is, not a mesh fabtiles made of it."""


@st.composite
def motifs(draw):
    """A preset, or a motif drawn as design 2 of the issue was (``n`` and up to four radii)."""
    if draw(st.booleans()):
        return {"preset": draw(st.sampled_from(PRESETS))}
    radii = draw(st.lists(st.floats(20, 200).map(lambda r: round(r, 1)), min_size=2, max_size=4))
    return {"n": draw(st.integers(3, 12)), "radii": radii}


@st.composite
def designs(draw, styles=PRINT_STYLES):
    """A design as its TOML tables: a small tile, its packing, strokes, colours and a print of ``styles``."""
    data = {"motif": draw(motifs())}
    if draw(st.booleans()):
        data["packing"] = {
            "kind": "hex",
            "radius": draw(st.floats(6, 15).map(lambda r: round(r, 2))),
            "outline_circles": draw(st.booleans()),
        }
    else:
        tiling = draw(st.sampled_from(ALL_TILINGS))  # the 11 Archimedean and the 20 two-uniform
        packing = {
            "kind": "archimedean",
            "tiling": tiling,
            "edge": draw(st.floats(6, 15).map(lambda e: round(e, 2))),
            "outline_circles": draw(st.booleans()),
        }
        if draw(st.booleans()):  # one kind of polygon with a motif of its own
            sides = draw(st.sampled_from(sorted(set(unit_cell(tiling).sides.tolist()))))
            packing["motifs"] = {str(sides): draw(st.sampled_from(PRESETS))}
        data["packing"] = packing
    outline = draw(st.sampled_from(["square", "rectangle", "hexagon", "circle"]))
    w = round(draw(st.floats(40, 80)), 1)
    h = round(draw(st.floats(40, 80)), 1) if outline == "rectangle" else w
    data["tile"] = {
        "outline": outline,
        "size": [w, h],
        "frame": draw(st.sampled_from([0.0, 1.5, 3.0])),
        "stroke": round(draw(st.floats(0.6, 2.0)), 2),
        "join": draw(st.sampled_from(["miter", "round", "bevel"])),
        "interlace": draw(st.booleans()),
    }
    style = draw(st.sampled_from(styles))
    output = {
        "formats": ["stl", "3mf"],
        "printer_profile": draw(st.sampled_from(["fdm-0.4mm", "fdm-0.6mm"])),
        "print_style": style,
        "fill_small_holes": draw(st.booleans()),
    }
    if style == "mosaic":
        output["mosaic_inset_mm"] = draw(st.sampled_from([0.0, 0.4]))
    if style == "deboss":
        output["inlay"] = draw(st.booleans())
    data["output"] = output
    if draw(st.booleans()):
        data["colour"] = {
            "by": draw(st.sampled_from(["none", "shape"])),
            "palette": draw(st.sampled_from(["zellige", "iznik", "mamluk", "alhambra", "haft-rangi"])),
        }
    return data


def _read_back(vertices, faces, *, name, volume, bodies):
    """The mesh as its binary STL holds it, read back in float32 and checked as a slicer merges it."""
    tris = read_stl_triangles(stl_bytes(vertices, faces))
    check_triangles(tris, name=name, volume=volume, bodies=bodies)


def _design(motif, packing, tile, style, **output):
    """A design's tables as :func:`designs` draws them (the pinned cases below)."""
    return {
        "motif": motif,
        "packing": packing,
        "tile": tile,
        "output": {"formats": ["stl", "3mf"], "printer_profile": "fdm-0.4mm", "print_style": style, **output},
    }


EDGE_BAND_TIP = {"outline": "hexagon", "frame": 0.0, "join": "bevel", "interlace": True}
"""A hexagon without a frame, interlaced: bands end in tips on its edges."""


def _check(data):
    """Build a design's print model; every mesh it makes must pass its slicer check, read back."""
    try:
        design = design_from_dict(data, name="random")
    except DesignError:  # a stroke wider than the packing allows
        reject()
    models = Models(design.build_tile(), BuildOptions.of_design(design))
    try:
        model = models.print
        parts = model.parts  # the 3MF's parts (a mosaic's STL per colour)
        fused = model.fused  # the STL's body
    except FabricationError as exc:
        assert any(why in str(exc) for why in REFUSED), exc
        return
    for name, part in parts.items():
        _read_back(part.mesh.vertices, part.mesh.faces, name=name, volume=part.mesh.volume_mm3, bodies=part.mesh.bodies)
    _read_back(fused.vertices, fused.faces, name="fused", volume=fused.volume_mm3, bodies=fused.bodies)


@pytest.mark.parametrize("style", PRINT_STYLES)
@settings(max_examples=examples(3), suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_every_mesh_of_a_random_design_passes_its_slicer_check(style, data):
    _check(data.draw(designs((style,)), label="design"))


@settings(phases=[Phase.explicit])
@given(designs())
# two faces of a class meeting at a band's tip on the edge: a vertical edge of four walls in their part
@example(
    _design(
        {"n": 9, "radii": [150.0, 195.3]},
        {"kind": "hex", "radius": 10.41, "outline_circles": False},
        {"size": [59.5, 59.5], "stroke": 1.2, **EDGE_BAND_TIP},
        "mosaic",
        fill_small_holes=False,
        mosaic_inset_mm=0.0,
    )
)
@example(
    _design(
        {"n": 9, "radii": [119.7, 90.0, 199.0]},
        {
            "kind": "archimedean",
            "tiling": "3.4.6.4",
            "edge": 6.19,
            "outline_circles": False,
            "motifs": {"4": "table1-part1"},
        },
        {"size": [66.1, 66.1], "stroke": 1.32, **EDGE_BAND_TIP},
        "mosaic",
        fill_small_holes=False,
        mosaic_inset_mm=0.0,
    )
)
# the under strands dipping all round a small face: filled, the dip nested the face's hole in the region
@example(
    _design(
        {"preset": "table3-1"},
        {"kind": "hex", "radius": 10.92, "outline_circles": False},
        {"size": [57.0, 57.0], "stroke": 1.42, **EDGE_BAND_TIP},
        "relief",
        fill_small_holes=False,
    )
)
# two dips touching at a point: the full height's walls and theirs on one vertical edge
@example(
    _design(
        {"n": 7, "radii": [117.0, 43.4, 30.0, 150.0]},
        {"kind": "hex", "radius": 6.96, "outline_circles": False},
        {"outline": "rectangle", "size": [60.0, 67.1], "frame": 0.0, "stroke": 0.9, "join": "miter", "interlace": True},
        "relief",
        fill_small_holes=True,
    )
)
# two dips leaving their point at a small angle: cut back, they still touched on the grid (and others
# a third of a grid step apart touched once the STEP writer noded them)
@example(
    _design(
        {"preset": "table3-1"},
        {"kind": "archimedean", "tiling": "4.4.4.4", "edge": 14.89, "outline_circles": False},
        {"outline": "hexagon", "size": [58.6, 58.6], "frame": 3.0, "stroke": 1.43, "join": "miter", "interlace": True},
        "relief",
        fill_small_holes=True,
    )
)
def test_the_random_designs_that_broke_pass(data):
    _check(data)
