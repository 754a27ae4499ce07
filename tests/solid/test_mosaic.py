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
from fabtiles.solid import parts
from fabtiles.solid._mesh_build import QUANTUM, polygons_of, resolve_stack
from fabtiles.solid.parts import APART_MM, MosaicPart
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
        return (
            MosaicPart("white (base, bands, B)", True, True, tuple(faces_b), c.band),
            MosaicPart("cobalt (A)", False, False, tuple(faces_a), c.face("A")),
        )
    return (
        MosaicPart("black (base)", True, False, (), c.base),
        MosaicPart("white (bands)", False, True, (), c.band),
        MosaicPart("cobalt (A)", False, False, tuple(faces_a), c.face("A")),
        MosaicPart("green (B)", False, False, tuple(faces_b), c.face("B")),
    )


@settings(max_examples=examples(12), deadline=None)
@given(
    st.lists(st.tuples(st.floats(5, 35), st.floats(5, 25), st.floats(1.0, 3.0)), min_size=2, max_size=5),
    st.sampled_from([0.0, 0.4]),
    st.booleans(),
)
def test_the_parts_tile_the_outline_and_weigh_their_areas(holes, inset, shared):
    region, _faces = _tile(holes)
    parts_geom = shapely.get_parts(OUTLINE.difference(region))
    a, b = parts_geom[::2], parts_geom[1::2]
    model = print_model(
        region,
        OUTLINE,
        profile="fdm-0.4mm",
        style="mosaic",
        mosaic=_specs(a, b, shared=shared),
        colours=COLOURS,
        mosaic_inset_mm=inset,
        fill_small_holes=False,
    )
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


@settings(max_examples=examples(8), deadline=None)
@given(
    st.lists(st.tuples(st.floats(5, 35), st.floats(5, 25), st.floats(1.0, 3.0)), min_size=2, max_size=5),
    st.sampled_from([0.0, 0.4]),
    st.booleans(),
)
def test_the_step_holds_each_part_checked_against_its_own_mesh(tmp_path_factory, holes, inset, shared):
    from fabtiles.export.step import check_step_file, step_bytes

    region, _faces = _tile(holes)
    parts_geom = shapely.get_parts(OUTLINE.difference(region))
    model = print_model(
        region,
        OUTLINE,
        profile="fdm-0.4mm",
        style="mosaic",
        mosaic=_specs(parts_geom[::2], parts_geom[1::2], shared=shared),
        colours=COLOURS,
        mosaic_inset_mm=inset,
        fill_small_holes=False,
    )
    path = tmp_path_factory.mktemp("step") / "m.step"
    path.write_bytes(step_bytes(model, name="m"))  # each part's B-rep checked in memory against its mesh
    breps = model.breps
    assert [name for name, _ in breps] == list(model.parts)
    for (_, (_brep, volume, solids)), part in zip(breps, model.parts.values(), strict=True):
        assert (volume, solids) == (part.mesh.mesh_volume_mm3, part.mesh.bodies)
    # OCCT reads every part's solids, valid, as many as the parts' bodies, their volumes the whole print's
    solids = sum(p.mesh.bodies for p in model.parts.values())
    assert check_step_file(path, volume=model.fused.mesh_volume_mm3, parts=solids) == pytest.approx(
        model.fused.mesh_volume_mm3, rel=5e-4
    )


def test_a_faces_part_stands_on_the_plate_at_its_height():
    region, _ = _tile([(10, 10, 3), (30, 20, 3)])
    faces = shapely.get_parts(OUTLINE.difference(region))
    model = print_model(
        region,
        OUTLINE,
        profile="fdm-0.4mm",
        style="mosaic",
        mosaic=_specs(faces[:1], faces[1:]),
        colours=COLOURS,
        mosaic_inset_mm=0.4,
    )
    s = model.stack
    cobalt = model.parts["cobalt (A)"].mesh.vertices
    assert cobalt[:, 2].min() == pytest.approx(s.base) and cobalt[:, 2].max() == pytest.approx(s.base + s.relief - 0.4)
    bands = model.parts["white (bands)"].mesh.vertices
    assert bands[:, 2].max() == pytest.approx(s.base + s.relief)
    assert model.parts["black (base)"].mesh.vertices[:, 2].max() == pytest.approx(s.base)


def test_each_colour_is_its_own_stl_named_by_colour():
    region, _ = _tile([(10, 10, 3), (30, 20, 3)])
    faces = shapely.get_parts(OUTLINE.difference(region))
    model = print_model(
        region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=_specs(faces[:1], faces[1:]), colours=COLOURS
    )
    files = model.bodies()  # the STL row writes one file per body
    assert [s for s, _ in files] == ["-black", "-white", "-cobalt", "-green"]
    assert [m.fused_name for _, m in files] == list(model.parts)
    assert model.files() == [("", model)]


def test_a_colour_no_face_took_is_no_part():
    region, _ = _tile([(10, 10, 3)])
    faces = shapely.get_parts(OUTLINE.difference(region))
    model = print_model(region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=_specs(faces, []), colours=COLOURS)
    assert list(model.parts) == ["black (base)", "white (bands)", "cobalt (A)"]


def test_mosaic_parts_need_the_mosaic_style():
    region, _ = _tile([(10, 10, 3)])
    with pytest.raises(ParameterError, match=r"mosaic parts need style='mosaic', got style='relief'"):
        print_model(region, OUTLINE, profile="fdm-0.4mm", style="relief", mosaic=_specs([], []))


PINCH = [box(10, 10, 15, 15), box(15, 15, 20, 20)]
"""Two faces of one colour touching at the point (15, 15)."""


def _pinched(**kwargs):
    region = OUTLINE.difference(shapely.union_all(PINCH))
    specs = (
        MosaicPart("black (base, bands)", True, True, (), COLOURS.base),
        MosaicPart("cobalt (A)", False, False, tuple(PINCH), COLOURS.face("A")),
    )
    return print_model(
        region,
        OUTLINE,
        profile="fdm-0.4mm",
        style="mosaic",
        mosaic=specs,
        colours=COLOURS,
        fill_small_holes=False,
        **kwargs,
    )


@pytest.mark.parametrize("inset", [0.0, 0.4])
def test_two_faces_touching_at_a_point_are_cut_apart_there(inset):
    """A vertical edge of four walls at the point cannot be watertight: a speck of the faces is cut away there."""
    model = _pinched(mosaic_inset_mm=inset)
    s = model.stack
    height = s.relief - inset
    cobalt = model.parts["cobalt (A)"].mesh
    mesh = trimesh.Trimesh(cobalt.vertices, cobalt.faces, process=True)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.body_count == 2
    # the faces less a diamond of APART_MM about the point (a quarter of it from each face)
    cut = APART_MM**2  # two quarters of a diamond of area 2 * APART_MM ** 2
    assert mesh.volume == pytest.approx((50 - cut) * height, rel=1e-6)
    footprint = _footprint(model.parts["cobalt (A)"])
    assert footprint.distance(shapely.Point(15, 15)) == pytest.approx(APART_MM / 2**0.5, abs=2e-3)
    # the bands touch themselves at the point too (the faces' corners): cut there the same way
    black = model.parts["black (base, bands)"].mesh
    mesh = trimesh.Trimesh(black.vertices, black.faces, process=True)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.body_count == 1
    assert mesh.volume == pytest.approx(OUTLINE.area * s.base + (OUTLINE.area - 50 - cut) * s.relief, rel=1e-6)


def test_a_part_that_cannot_be_meshed_is_refused(monkeypatch):
    """Without the cut at the point of contact, the part is refused: an error, not a file."""
    monkeypatch.setattr(parts, "_apart", lambda layers, points: layers)
    model = _pinched()
    with pytest.raises(
        FabricationError,
        match=r"^the part '[a-z]+ \([a-zA-Z, ]+\)' mesh is not watertight as a "
        r"slicer reads it",
    ):
        _ = model.parts


def _cdt_failure(*args, **kwargs):
    exc = FabricationError("cannot triangulate the region near (15, 15) mm: GEOS stops there")
    exc.points = np.array([[15.0, 15.0]])
    raise exc


def _geos_failure(*args, **kwargs):
    raise shapely.errors.GEOSException("TopologyException: side location conflict at 15 15")


@pytest.mark.parametrize(
    "target, broken, match",
    [
        (
            "mesh_coverage",
            _cdt_failure,
            (
                r"could not be made: cannot triangulate the region near \(15, 15\) mm: GEOS "
                r"stops there; nothing was written$"
            ),
        ),
        (
            "coverage",
            _geos_failure,
            (
                r"could not be cut into cells \(TopologyException: side location conflict at 15 "
                r"15\); nothing was written$"
            ),
        ),
    ],
)
def test_a_part_whose_cut_fails_is_refused_by_name_after_moved_lines(monkeypatch, target, broken, match):
    calls = []

    def spy(*args, **kwargs):
        calls.append(kwargs.get("shift"))
        return broken(*args, **kwargs)

    model = _pinched()
    monkeypatch.setattr(parts, target, spy)
    with pytest.raises(FabricationError, match=r"^the part '[a-z]+ \([a-zA-Z, ]+\)' mesh " + match):
        _ = model.parts
    assert len(calls) == parts.GRID_SHIFTS  # every cut of lines tried, then refused


def test_bands_and_faces_that_do_not_join_are_refused(monkeypatch):
    region, _ = _tile([(10, 10, 3)])
    faces = shapely.get_parts(OUTLINE.difference(region))
    specs = (
        MosaicPart("black (base)", True, False, (), COLOURS.base),
        MosaicPart("white (bands, A)", False, True, tuple(faces), COLOURS.band),
    )
    model = print_model(
        region, OUTLINE, profile="fdm-0.4mm", style="mosaic", mosaic=specs, colours=COLOURS, mosaic_inset_mm=0.0
    )
    monkeypatch.setattr(shapely, "coverage_union_all", _geos_failure)
    with pytest.raises(
        FabricationError,
        match=r"^the part 'white \(bands, A\)' mesh could not be made: its bands and "
        r"faces do not join \(TopologyException",
    ):
        _ = model.parts


def test_faces_that_cannot_be_cut_from_the_outline_are_refused(monkeypatch):
    region, faces = _tile([(10, 10, 3)])
    stack = resolve_stack("fdm-0.4mm", "mosaic")
    monkeypatch.setattr(shapely, "difference", _geos_failure)
    with pytest.raises(
        FabricationError,
        match=r"^the mosaic's faces could not be cut from the outline "
        r"\(TopologyException",
    ):
        parts.mosaic_parts(region, OUTLINE, stack, _specs(faces, []))


def _slanted():
    """A mosaic along a slanted edge whose bands' ring runs a hair inside the outline between points on it."""
    outline = shapely.Polygon([(0, 0), (40, 0), (40, 20), (0, 40)])
    inner = shapely.Polygon([(3, 3), (37, 3), (37, 18), (3, 35)])
    # on the grid: every other point of the bands' edge on the slanted line, the others a grid step inside it
    x = np.arange(40 * 1024 - 64, 0, -64)
    y = 20 * 1024 + (40 * 1024 - x) // 2 - np.where(np.arange(len(x)) % 2, 1, 0)
    edge = np.stack([x, y], axis=1) * QUANTUM
    region = shapely.Polygon([(0, 0), (40, 0), (40, 20), *edge.tolist(), (0, 40)], [list(inner.exterior.coords)])
    specs = (
        MosaicPart("black (base, bands)", True, True, (), COLOURS.base),
        MosaicPart("cobalt (A)", False, False, (inner,), COLOURS.face("A")),
    )
    return region, outline, inner, specs


def test_slivers_along_a_slanted_outline_are_no_faces():
    """Where the bands run along a slanted edge, the outline less them on the grid leaves slivers thinner
    than a micron, touching one another at their ends: not faces (a part of them would not be watertight)."""
    region, outline, inner, specs = _slanted()
    faces = np.asarray(polygons_of(shapely.difference(outline, region, grid_size=QUANTUM)), dtype=object)
    slivers = parts._slivers(faces)
    assert slivers.sum() > 100 and list(shapely.area(faces[~slivers])) == [inner.area]
    model = print_model(
        region, outline, profile="fdm-0.4mm", style="mosaic", mosaic=specs, colours=COLOURS, fill_small_holes=False
    )
    cobalt = model.parts["cobalt (A)"].mesh
    mesh = trimesh.Trimesh(cobalt.vertices, cobalt.faces, process=True)
    assert mesh.is_watertight and mesh.body_count == 1
    assert mesh.volume == pytest.approx(inner.area * model.stack.relief, rel=1e-6)
