"""A mosaic print (issue 33): a part per colour, the plate, the bands and the faces, checked with GEOS and trimesh."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely.geometry import box

from fabtiles import FabricationError, ParameterError
from fabtiles.designs.colour import colouring
from fabtiles.solid.parts import MosaicPart
from fabtiles.solid.print_model import print_model

OUTLINE = box(0, 0, 40, 30)
COLOURS = colouring(palette_name="zellige", classes=("A", "B"))


def _tile(holes):
    faces = [shapely.Point(x, y).buffer(r, quad_segs=8) for x, y, r in holes]
    return OUTLINE.difference(shapely.union_all(faces)), faces


def _footprint(part):
    """The part's footprint by GEOS: the union of its triangles seen from above."""
    tris = part.mesh.vertices[part.mesh.faces][:, :, :2]
    polys = shapely.polygons(np.concatenate([tris, tris[:, :1]], axis=1))
    return shapely.union_all(polys[shapely.area(polys) > 1e-12])


def _specs(faces_a, faces_b, *, shared=False):
    c = COLOURS
    if shared:  # the plate, the bands and class B in one colour
        return (MosaicPart("white (base, bands, B)", True, True, tuple(faces_b), c.band),
                MosaicPart("cobalt (A)", False, False, tuple(faces_a), c.face("A")))
    return (MosaicPart("black (base)", True, False, (), c.base),
            MosaicPart("white (bands)", False, True, (), c.band),
            MosaicPart("cobalt (A)", False, False, tuple(faces_a), c.face("A")),
            MosaicPart("green (B)", False, False, tuple(faces_b), c.face("B")))


@settings(max_examples=examples(12), deadline=None)
@given(st.lists(st.tuples(st.floats(5, 35), st.floats(5, 25), st.floats(1.0, 3.0)), min_size=2, max_size=5),
       st.sampled_from([0.0, 0.4]), st.booleans())
def test_the_parts_tile_the_outline_and_weigh_their_areas(holes, inset, shared):
    region, _faces = _tile(holes)
    parts_geom = shapely.get_parts(OUTLINE.difference(region))
    a, b = parts_geom[::2], parts_geom[1::2]
    model = print_model(region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=_specs(a, b, shared=shared),
                        colours=COLOURS, mosaic_inset_mm=inset, fill_small_holes=False)
    s = model.stack
    top = s.base + s.relief
    parts = model.parts
    assert [p.material for p in parts.values()] == list(range(1, len(parts) + 1))
    # the parts above the plate: their footprints do not overlap, and with the plate's cover the outline
    above = [_footprint(p) for p in parts.values() if p.mesh.vertices[:, 2].min() >= s.base - 1e-6]
    for i in range(len(above)):
        for j in range(i + 1, len(above)):
            assert shapely.intersection(above[i], above[j]).area < 1e-6 * OUTLINE.area
    cover = shapely.union_all([_footprint(p) for p in parts.values()])
    assert cover.symmetric_difference(OUTLINE).area < 1e-4 * OUTLINE.area
    # each part's volume (trimesh, from its own mesh) is its area x height within 0.1 %
    face_area = OUTLINE.area - region.area
    expected = OUTLINE.area * top - face_area * inset
    total = 0.0
    for name, part in parts.items():
        mesh = trimesh.Trimesh(part.mesh.vertices, part.mesh.faces, process=True)
        assert mesh.is_watertight and mesh.is_winding_consistent, name
        assert mesh.volume == pytest.approx(part.mesh.volume_mm3, rel=1e-3), name
        total += mesh.volume
    assert total == pytest.approx(expected, rel=1e-3)
    # and the model's fused body (the STEP's solid) is the whole of it
    assert model.fused.mesh_volume_mm3 == pytest.approx(expected, rel=1e-3)


def test_a_faces_part_stands_on_the_plate_at_its_height():
    region, _ = _tile([(10, 10, 3), (30, 20, 3)])
    faces = shapely.get_parts(OUTLINE.difference(region))
    model = print_model(region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=_specs(faces[:1], faces[1:]),
                        colours=COLOURS, mosaic_inset_mm=0.4)
    s = model.stack
    cobalt = model.parts["cobalt (A)"].mesh.vertices
    assert cobalt[:, 2].min() == pytest.approx(s.base) and cobalt[:, 2].max() == pytest.approx(s.base + s.relief - 0.4)
    bands = model.parts["white (bands)"].mesh.vertices
    assert bands[:, 2].max() == pytest.approx(s.base + s.relief)
    assert model.parts["black (base)"].mesh.vertices[:, 2].max() == pytest.approx(s.base)


def test_each_colour_is_its_own_stl_named_by_colour():
    region, _ = _tile([(10, 10, 3), (30, 20, 3)])
    faces = shapely.get_parts(OUTLINE.difference(region))
    model = print_model(region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=_specs(faces[:1], faces[1:]),
                        colours=COLOURS)
    files = model.files_of("stl")
    assert [s for s, _ in files] == ["-black", "-white", "-cobalt", "-green"]
    assert [m.fused_name for _, m in files] == list(model.parts)
    assert model.files_of("3mf") == [("", model)]


def test_a_colour_no_face_took_is_no_part():
    region, _ = _tile([(10, 10, 3)])
    faces = shapely.get_parts(OUTLINE.difference(region))
    model = print_model(region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=_specs(faces, []),
                        colours=COLOURS)
    assert list(model.parts) == ["black (base)", "white (bands)", "cobalt (A)"]


def test_mosaic_parts_need_the_mosaic_style():
    region, _ = _tile([(10, 10, 3)])
    with pytest.raises(ParameterError, match=r"mosaic parts need style='mosaic', got style='relief'"):
        print_model(region, OUTLINE, profile="fdm-0.4mm", style="relief", mosaic=_specs([], []))


def test_a_part_that_cannot_be_meshed_is_refused():
    """Two faces of one colour touching at a point cannot be one watertight body: an error, not a file."""
    pinch = [box(10, 10, 15, 15), box(15, 15, 20, 20)]
    region = OUTLINE.difference(shapely.union_all(pinch))
    specs = (MosaicPart("black (base, bands)", True, True, (), COLOURS.base),
             MosaicPart("cobalt (A)", False, False, tuple(pinch), COLOURS.face("A")))
    model = print_model(region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=specs, colours=COLOURS,
                        fill_small_holes=False)
    with pytest.raises(FabricationError, match=r"the part '[a-z]+ \([a-zA-Z, ]+\)' mesh is not watertight as a "
                                               r"slicer reads it"):
        _ = model.parts
