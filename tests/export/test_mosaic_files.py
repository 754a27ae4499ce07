"""A mosaic print's files (issue 33), opened by the programs users load them into.

``samples/mosaic-iznik.toml``: table3-3 on the hex packing, faces classed by shape in the
Iznik palette, printed as a mosaic of four colours (the base, the bands, classes A and B;
classes C and D are under the printer's 0.8 mm and filled with the bands). The 3MF's N
parts are read back and sliced by PrusaSlicer with an N-extruder printer, read by Cura's
parser and lib3mf's strict reader; the STL per colour by trimesh; the STEP by OCCT.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import shapely
import trimesh
from test_3mf_multicolour import extrusions_by_tool, slice_gcode
from test_3mf_readers import lib3mf_read, savitar

from fabtiles.designs.design_file import design_from_text, load_design
from fabtiles.export import threemf
from fabtiles.export.step import check_step_file
from fabtiles.machines.profiles import load_profile
from fabtiles.making import build_design
from fabtiles.making.models import BuildOptions, Models

SAMPLE = Path(__file__).resolve().parents[2] / "samples" / "mosaic-iznik.toml"
PARTS = ["navy (base)", "white (bands)", "cobalt (A)", "turquoise (B)"]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("mosaic")
    design = load_design(SAMPLE)
    result = build_design(design, out, formats=("3mf", "stl", "step"))
    models = Models(design.build_tile(), BuildOptions.of_design(design))
    components = tmp_path_factory.mktemp("components")
    build_design(load_design(SAMPLE, overrides=('output.threemf_layout="components"',)), components, formats=("3mf",))
    return out, result, models, components / "mosaic-iznik.3mf"


def test_the_3mf_holds_a_part_per_colour_on_extruders_1_to_n(built):
    out, _, models, _ = built
    parts = threemf.read_3mf(out / "mosaic-iznik.3mf")
    assert list(parts) == PARTS
    assert [p.extruder for p in parts.values()] == [1, 2, 3, 4]
    # each part's volume, read back, is its footprint's area times its height (GEOS areas)
    model = models.print
    s = model.stack
    region = shapely.intersection(model.region, model.outline)
    faces = model.outline.difference(region)
    volumes = {n: trimesh.Trimesh(p.vertices, p.faces).volume for n, p in parts.items()}
    assert volumes["navy (base)"] == pytest.approx(model.outline.area * s.base, rel=1e-3)
    assert volumes["white (bands)"] == pytest.approx(region.area * s.relief, rel=1e-3)
    assert volumes["cobalt (A)"] + volumes["turquoise (B)"] == pytest.approx(
        faces.area * (s.relief - s.inset), rel=1e-3
    )
    classes = models.face_classes
    for name, letter in (("cobalt (A)", "A"), ("turquoise (B)", "B")):
        # the class's faces, as printed (a face the fill closed is no longer one)
        printed = shapely.intersection(classes.of(letter), faces).area
        assert volumes[name] == pytest.approx(printed * (s.relief - s.inset), rel=2e-3)


def test_prusaslicer_with_four_extruders_changes_tool_for_each_colour(built, tmp_path):
    out, *_ = built
    gcode = slice_gcode(tmp_path, out / "mosaic-iznik.3mf", 4)
    tools = sorted({int(t) for t in re.findall(r"^T(\d+)\s*$", gcode, flags=re.M)})
    assert tools == [0, 1, 2, 3]
    assert sorted(k for k in extrusions_by_tool(gcode) if k is not None) == [0, 1, 2, 3]


def test_prusaslicer_with_one_extruder_prints_one_filament_silently(built, tmp_path):
    """What docs/slicers.md warns of: choose a printer of N extruders (or an MMU) in the slicer."""
    out, *_ = built
    gcode = slice_gcode(tmp_path, out / "mosaic-iznik.3mf", 1)
    assert re.findall(r"^T\d+", gcode, flags=re.M) == []
    assert list(extrusions_by_tool(gcode)) == [None]


def test_cura_and_lib3mf_read_the_four_parts(built):
    *_, components = built
    (group,) = savitar(components)["nodes"]
    assert [(c["name"], c["settings"]) for c in group["children"]] == [
        (n, {"extruder_nr": str(k)}) for k, n in enumerate(PARTS)
    ]
    got = lib3mf_read(components)
    assert got["warnings"] == [] and len(got["components"]) == 1
    assert all(manifold for _, _, manifold, _ in got["meshes"].values())


def test_an_stl_per_colour_in_one_frame(built):
    out, result, _models, _ = built
    names = ["navy", "white", "cobalt", "turquoise"]
    files = [out / f"mosaic-iznik-{n}.stl" for n in names]
    assert all(f.exists() for f in files) and not (out / "mosaic-iznik.stl").exists()
    meshes = [trimesh.load(f) for f in files]
    assert all(m.is_watertight and m.is_winding_consistent for m in meshes)
    parts = threemf.read_3mf(out / "mosaic-iznik.3mf")
    for mesh, part in zip(meshes, parts.values(), strict=True):
        # the same body as the 3MF's part, in the same frame
        np.testing.assert_allclose(mesh.bounds, [part.vertices.min(axis=0), part.vertices.max(axis=0)], atol=1e-5)
        assert mesh.volume == pytest.approx(trimesh.Trimesh(part.vertices, part.faces).volume, rel=1e-9)
    report = next(r for r in result.reports if r.format == "stl")
    assert report.stats["files"] == [str(f) for f in files]
    assert list(report.stats["material"]["parts"]) == PARTS


def test_the_step_holds_the_whole_mosaic_by_its_parts(built):
    out, _, models, _ = built
    model = models.print
    s = model.stack
    faces = model.outline.difference(shapely.intersection(model.region, model.outline))
    expected = model.outline.area * (s.base + s.relief) - faces.area * s.inset
    solids = sum(p.mesh.bodies for p in model.parts.values())
    volume = check_step_file(out / "mosaic-iznik.step", volume=model.fused.mesh_volume_mm3, parts=solids)
    assert volume == pytest.approx(expected, rel=1e-3)


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """The sample as a 60 mm tile: its 3MF, its STEP read by build123d (OCCT's XCAF reader), its model."""
    import build123d

    out = tmp_path_factory.mktemp("small")
    design = load_design(SAMPLE, overrides=["tile.size=60"])
    build_design(design, out, formats=("3mf", "step"))
    model = Models(design.build_tile(), BuildOptions.of_design(design)).print
    return threemf.read_3mf(out / "mosaic-iznik.3mf"), build123d.import_step(out / "mosaic-iznik.step"), model


def test_the_step_is_a_named_part_per_colour_each_its_3mf_parts_volume(small):
    parts, shape, model = small
    assert list(parts) == PARTS
    # one component per 3MF part, in its order, named as it is (build123d writes " .()" as "_")
    assert [c.label for c in shape.children] == [n.translate(str.maketrans(" .()", "____")) for n in PARTS]
    for child, (name, part) in zip(shape.children, parts.items(), strict=True):
        # its solids are the part's bodies (the faces of a class are pieces apart), valid by OCCT
        assert len(child.solids()) == model.parts[name].mesh.bodies
        assert all(solid.is_valid for solid in child.solids())
        assert child.volume == pytest.approx(trimesh.Trimesh(part.vertices, part.faces).volume, rel=5e-4)
    assert shape.volume == pytest.approx(model.fused.mesh_volume_mm3, rel=5e-4)
    assert len(shape.solids()) == sum(c.mesh.bodies for c in model.parts.values()) > len(PARTS)


def test_the_step_parts_touch_without_overlapping(small):
    _, shape, model = small
    children = shape.children
    for k, a in enumerate(children):
        for b in children[k + 1 :]:
            za, zb = a.bounding_box(), b.bounding_box()
            if za.max.Z <= zb.min.Z + 1e-9 or zb.max.Z <= za.min.Z + 1e-9:
                continue  # one lies on the other (the plate and what stands on it): no volume in common
            common = a.intersect(b)
            assert (common.volume if common is not None else 0.0) == pytest.approx(0.0, abs=1e-6 * a.volume)
    # each where it prints: the plate on the bed, the bands and the faces on the plate up to their tops
    s = model.stack
    heights = [(c.bounding_box().min.Z, c.bounding_box().max.Z) for c in children]
    top, faces_top = s.base + s.relief, s.base + s.relief - s.inset
    expected = [(0.0, s.base), (s.base, top), (s.base, faces_top), (s.base, faces_top)]
    np.testing.assert_allclose(heights, expected, atol=1e-6)


# -- a 150 mm hexagon of the 6.6.6 tiling, interlaced: a mosaic that was refused, or ended in a traceback --

HEXAGON = """
[motif]
n = 5
radii = [96.0, 151.0, 161.7, 164.2]
[packing]
kind = "archimedean"
tiling = "6.6.6"
edge = 12.89
outline_circles = false
[packing.motifs]
6 = "table3-2"
[tile]
outline = "hexagon"
size = [149.8, 149.8]
frame = 3.0
stroke = 1.2
join = "round"
interlace = true
[output]
formats = ["3mf", "stl"]
printer_profile = "fdm-0.6mm"
print_style = "mosaic"
fill_small_holes = {fill}
"""
"""Its bands run along the hexagon's slanted edges, where the outline less the bands left slivers
touching end to end; kept open (``fill_small_holes = false``) its faces cut at a cell line through a
vertex made a ring GEOS could not triangulate."""

HEXAGON_PARTS = ["black (base)", "white (bands)", "cobalt (A)"]


@pytest.fixture(scope="module", params=[True, False], ids=["filled", "kept"])
def hexagon(request, tmp_path_factory):
    fill = request.param
    out = tmp_path_factory.mktemp(f"hexagon-{'filled' if fill else 'kept'}")
    design = design_from_text(HEXAGON.format(fill=str(fill).lower()), name="hexagon")
    build_design(design, out)
    return out, fill


def test_the_hexagon_mosaic_writes_every_part_watertight(hexagon):
    out, _ = hexagon
    parts = threemf.read_3mf(out / "hexagon.3mf")
    assert list(parts) == HEXAGON_PARTS and [p.extruder for p in parts.values()] == [1, 2, 3]
    for name, part in parts.items():
        mesh = trimesh.Trimesh(part.vertices, part.faces, process=True)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0, name
    for colour in ("black", "white", "cobalt"):
        mesh = trimesh.load(out / f"hexagon-{colour}.stl")
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0, colour
    # the faces and the bands share the hexagon's top: their footprints' areas add up to the outline's
    volumes = {n: trimesh.Trimesh(p.vertices, p.faces).volume for n, p in parts.items()}
    side = 149.8 / 3**0.5  # a pointy-top hexagon 149.8 mm across its flats
    area = 3 * 3**0.5 / 2 * side**2
    relief = load_profile("fdm-0.6mm").relief_mm  # the faces flush with the bands (no inset)
    assert volumes["white (bands)"] + volumes["cobalt (A)"] == pytest.approx(area * relief, rel=1e-3)


# sliced as filled, the default: the kept file has the same three parts on the same extruders, and its parts'
# soundness (what broke) is test_the_hexagon_mosaic_writes_every_part_watertight's
@pytest.mark.parametrize("hexagon", [True], ids=["filled"], indirect=True)
def test_prusaslicer_prints_each_hexagon_part_with_its_own_tool(hexagon, tmp_path):
    out, _ = hexagon
    gcode = slice_gcode(tmp_path, out / "hexagon.3mf", len(HEXAGON_PARTS))
    assert sorted({int(t) for t in re.findall(r"^T(\d+)\s*$", gcode, flags=re.M)}) == [0, 1, 2]
    assert sorted(k for k in extrusions_by_tool(gcode) if k is not None) == [0, 1, 2]
