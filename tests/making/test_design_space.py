"""Any design a user can write builds its files or is refused with a FabtilesError, across the whole design
space at once: every packing (hex, square, the 31 tilings by motifs or Hankin's rays, parquet deformations,
girih patterns subdivided or not), interlace, borders, colours and shades, every laser mode and print style,
routers and waterjets, cylinders and stamps.

The features are tested one by one elsewhere; what breaks is where they meet (a border with a mosaic's
colours, a woven tile with no crossing scored, a parquet deformation's deboss in STEP: each found so).
``FABTILES_HYPOTHESIS=long`` draws ten times as many designs.
"""

from pathlib import Path

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

import fabtiles as ft
from fabtiles.designs.design_file import design_from_dict
from fabtiles.making.pipeline import build_design
from fabtiles.pattern.girih import PATTERNS
from fabtiles.pattern.presets import PRESETS
from fabtiles.pattern.tilings import ALL_TILINGS

CUTTERS = ("laser-3mm-plywood", "laser-3mm-plywood", "router-6mm-mdf", "waterjet-1mm-aluminium")
PALETTES = ("zellige", "iznik", "mamluk", "alhambra", "haft-rangi")


def _num(lo, hi):
    return st.floats(lo, hi).map(lambda x: round(x, 2))


@st.composite
def motifs(draw):
    if draw(st.booleans()):
        return {"preset": draw(st.sampled_from(sorted(PRESETS)))}
    n = draw(st.integers(3, 16))
    motif = {"n": n, "radii": draw(st.lists(_num(0.1, 10), min_size=2, max_size=4))}
    if draw(st.booleans()):
        motif["special"] = draw(st.integers(2, len(motif["radii"])))
        motif["alpha"] = draw(_num(-180 / n, 180 / n))
        motif["spr"] = draw(_num(-3, 3))
    return motif


@st.composite
def packings(draw):
    kind = draw(st.sampled_from(["hex", "square", "archimedean", "archimedean", "girih"]))
    packing, motif, unit = {"kind": kind}, None, 0.0
    if kind in ("hex", "square"):
        motif = draw(motifs())
        packing["radius"] = unit = draw(_num(4, 30))
    elif kind == "archimedean":
        packing["tiling"] = draw(st.sampled_from(ALL_TILINGS))
        packing["edge"] = unit = draw(_num(6, 30))
        if draw(st.booleans()):
            packing.update(method="hankin", contact_angle=draw(_num(20, 85)))
            if draw(st.integers(0, 3)) == 0:
                packing.update(
                    contact_angle_to=draw(_num(20, 85)),
                    parquet_direction=draw(st.sampled_from(["x", "y", "radial"])),
                    parquet_curve=draw(st.sampled_from(["linear", "smooth"])),
                )
        else:
            motif = draw(motifs())
    else:
        packing["girih_pattern"] = draw(st.sampled_from(PATTERNS))
        packing["edge"] = unit = draw(_num(6, 20))
        if packing["girih_pattern"] != "rhombi" and draw(st.integers(0, 2)) == 0:
            packing["girih_level"] = 1
    if kind != "girih" and draw(st.integers(0, 7)) == 0:
        packing["seamless"] = True
    return packing, motif, unit


@st.composite
def designs(draw):
    packing, motif, unit = draw(packings())
    outline = draw(st.sampled_from(["square", "rectangle", "hexagon", "circle"]))
    size = draw(_num(20, 70))
    tile = {
        "outline": outline,
        "size": [size, draw(_num(20, 70))] if outline == "rectangle" else size,
        "frame": draw(st.sampled_from([0, 0, 2, 4])),
        "stroke": draw(_num(1.0, max(1.01, min(3.0, unit / 5)))),
        "join": draw(st.sampled_from(["miter", "round", "bevel"])),
    }
    if draw(st.integers(0, 3)) == 0:
        tile["interlace"] = True
        tile["interlace_cut"] = draw(st.booleans())
    if draw(st.integers(0, 6)) == 0:
        tile.update(border_mm=draw(_num(3, size / 4)), border_motif=draw(st.sampled_from(["stars", "hankin"])))
    cutter = draw(st.sampled_from(CUTTERS))
    if not cutter.startswith("laser"):
        tile["stroke"] = max(tile["stroke"], 6.5 if cutter.startswith("router") else 1.6)
    output = {
        "laser_profile": cutter,
        "laser_mode": draw(st.sampled_from(["pierced", "pierced", "score", "engrave", "inlay"]))
        if cutter.startswith("laser")
        else "pierced",
        "print_style": draw(st.sampled_from(["relief", "relief", "pierced", "deboss", "mosaic"])),
    }
    design = {"packing": packing, "tile": tile, "output": output}
    if motif is not None:
        design["motif"] = motif
    if draw(st.integers(0, 6)) == 0 and packing["kind"] != "girih":
        shape = draw(st.sampled_from(["cylinder", "stamp"]))
        if shape == "cylinder":
            design["surface"] = {"shape": shape, "diameter": draw(_num(20, 60)), "length": draw(_num(20, 60))}
            design["tile"] = {k: v for k, v in tile.items() if k in ("stroke", "join", "interlace")}
            output["print_style"] = draw(st.sampled_from(["relief", "deboss", "pierced"]))
            packing.pop("seamless", None)
        else:
            design["surface"] = {"shape": shape}
            output["print_style"] = "relief"
    if output["print_style"] == "mosaic" or draw(st.booleans()):
        design["colour"] = {"by": "shape", "palette": draw(st.sampled_from(PALETTES))}
        if output["laser_mode"] != "inlay" and draw(st.booleans()):
            design["colour"]["shaded"] = "B"
    formats = ["dxf", "svg", "stl", "3mf"] + (["lbrn2"] if cutter.startswith("laser") else [])
    return design, draw(st.lists(st.sampled_from(formats), min_size=1, max_size=2, unique=True))


@pytest.mark.slow
@settings(max_examples=examples(12), deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(drawn=designs())
def test_any_design_builds_or_is_refused_with_a_fabtiles_error(tmp_path_factory, drawn):
    data, formats = drawn
    out = tmp_path_factory.mktemp("design")
    try:
        design = design_from_dict(data, name="drawn")
        result = build_design(design, out, formats)
    except ft.FabtilesError as exc:
        event("refused")
        assert isinstance(exc, ValueError) and str(exc)
        assert not any(out.iterdir())  # a refused build writes nothing
        return
    event("built, a format refused" if result.refused else "built")
    assert result.paths and all(Path(p).stat().st_size > 0 for p in result.paths)
    assert {r.format for r in result.refused} | {r.format for r in result.reports} >= set(formats)
