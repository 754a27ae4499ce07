"""Face classes (issue 33): checked with GEOS and numpy, not with the module's own helpers.

The faces and the material partition the outline; every uncut face of a class is
congruent to the class's first uncut face (areas, and a point-set match after the best
rotation or reflection found here); faces a packing's translation maps onto each other
share a class, pieces cut by the frame included; letters follow the total area.
"""

import functools
import math
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest
import shapely
import shapely.affinity as aff
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles import ParameterError
from fabtiles.designs.design_file import load_design
from fabtiles.geometry.faces import FaceClass, FaceClasses, face_classes
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking, SquarePacking
from fabtiles.pattern.star import Star

SAMPLES = Path(__file__).resolve().parents[2] / "samples"
DESIGNS = ["table3-3.toml", "seamless-hexagon.toml", "tilings/4.8.8.toml", "tilings/3.12.12.toml"]


def _sample(name):
    return load_design(SAMPLES / name).build_tile()


@pytest.fixture(scope="module")
def sample_classes():
    """A sample's tile and its face classes by the sample's name, each built once for the module's
    tests (the designs' are ``classed``'s and ``test_translates_share_a_class``'s)."""

    @functools.cache
    def of(name):
        tile = _sample(name)
        return tile, face_classes(tile)

    return of


# a border's band of stars round Hankin's rays: the frieze's faces are classed by their own shapes, the field's
# by the packing's
@pytest.fixture(scope="module", params=DESIGNS + ["classical/border-4.8.8.toml", "motif"])
def classed(request, sample_classes):
    if request.param != "motif":
        return sample_classes(request.param)
    tile = TileGeometry("circle", 100, Star.preset("table3-1"), frame=2, stroke=0.6)
    return tile, face_classes(tile)


# -- what the test measures, with GEOS -----------------------------------------------
def _cut(tile, faces):
    """True for faces touching the frame's inner edge (or the outline with no frame), or a border's line round
    the field (its centre-line half a stroke away): pieces."""
    edge = shapely.get_exterior_ring(tile.inner_shape())
    cut = shapely.distance(faces, edge) < 1e-6
    if tile.border_mm > 0:
        cut |= shapely.distance(faces, shapely.get_exterior_ring(tile.field_shape())) < tile.stroke / 2 + 1e-6
    return cut


def _point_match(p, q, tol=1e-3):
    """Smallest Hausdorff distance between ``p`` and ``q`` over the rotations and reflections
    that put ``p``'s farthest vertex from its centroid onto a vertex of ``q`` as far out."""
    pc, qc = p.centroid, q.centroid
    p0 = aff.translate(p, -pc.x, -pc.y)
    best = math.inf
    for mirror in (1, -1):
        q0 = aff.scale(aff.translate(q, -qc.x, -qc.y), mirror, 1, origin=(0, 0))
        pv = shapely.get_coordinates(p0.exterior)
        qv = shapely.get_coordinates(q0.exterior)
        far = pv[np.argmax(np.hypot(*pv.T))]
        rp = math.hypot(*far)
        for v in qv[np.abs(np.hypot(*qv.T) - rp) < 10 * tol]:
            angle = math.atan2(v[1], v[0]) - math.atan2(far[1], far[0])
            moved = aff.rotate(p0, angle, origin=(0, 0), use_radians=True)
            best = min(best, shapely.hausdorff_distance(moved, q0))
            if best < tol:
                return best
    return best


# -- the faces ----------------------------------------------------------------------
def test_faces_and_region_partition_the_outline(classed):
    tile, fc = classed
    outline, region = tile.outline_shape(), tile.region()
    union = shapely.union_all(fc.faces)
    total = shapely.area(fc.faces).sum()
    assert union.area == pytest.approx(total, rel=1e-9)  # the faces do not overlap each other
    assert union.intersection(region).area < 1e-4 * outline.area * 1e-2  # nor the material
    assert total + region.area == pytest.approx(outline.area, rel=1e-4)
    assert union.union(region).symmetric_difference(outline).area < 1e-4 * outline.area
    assert all(shapely.get_type_id(fc.faces) == 3) and shapely.is_valid(fc.faces).all()


def test_counts_areas_and_letters(classed):
    _tile, fc = classed
    cls = fc.classes
    assert [c.letter for c in cls] == [chr(ord("A") + k) for k in range(len(cls))]
    areas = [c.area_mm2 for c in cls]
    assert all(a >= b * (1 - 1e-9) for a, b in pairwise(areas))  # ties within float noise
    assert sum(c.count for c in cls) == len(fc.faces) == len(fc.labels)
    np.testing.assert_allclose(np.bincount(fc.labels, weights=shapely.area(fc.faces)), areas, rtol=1e-12)
    for c in cls:
        assert fc.of(c.letter).area == pytest.approx(c.area_mm2, rel=1e-9)
        assert len(shapely.get_parts(fc.of(c.letter))) == c.count
    assert fc.stats()[0] == {
        "letter": "A",
        "count": cls[0].count,
        "description": cls[0].description,
        "area_mm2": round(cls[0].area_mm2, 3),
    }


def test_every_uncut_face_is_congruent_to_its_class_first(classed):
    tile, fc = classed
    cut = _cut(tile, fc.faces)
    areas = shapely.area(fc.faces)
    for k, c in enumerate(fc.classes):
        mine = np.flatnonzero(fc.labels == k)
        whole = mine[~cut[mine]]
        if not len(whole):
            continue
        first = fc.faces[whole[0]]
        np.testing.assert_allclose(areas[whole], first.area, rtol=1e-3, err_msg=c.letter)
        # a piece cut by the edge is no larger than its whole face
        assert (areas[mine[cut[mine]]] <= first.area * (1 + 1e-6)).all()
        for i in whole[1:]:
            assert _point_match(first, fc.faces[i]) < 1e-3, (c.letter, i)


def test_faces_of_different_classes_differ(classed):
    """Uncut faces of two classes are not congruent (the classes are not split needlessly)."""
    tile, fc = classed
    cut = _cut(tile, fc.faces)
    firsts = []
    for k in range(len(fc.classes)):
        whole = np.flatnonzero((fc.labels == k) & ~cut)
        if len(whole):
            firsts.append(fc.faces[whole[0]])
    for a in range(len(firsts)):
        for b in range(a + 1, len(firsts)):
            p, q = firsts[a], firsts[b]
            if abs(p.area - q.area) < 1e-3 * p.area and len(p.exterior.coords) == len(q.exterior.coords):
                assert _point_match(p, q) > 1e-3


TILINGS = sorted(f"tilings/{p.name}" for p in (SAMPLES / "tilings").glob("*.toml"))


@pytest.mark.parametrize("name", sorted(set(DESIGNS + TILINGS)))
def test_translates_share_a_class(name, sample_classes):
    """A face moved by a period of the packing onto another face (its whole or a piece of it
    cut by the frame) is in that face's class."""
    tile, fc = sample_classes(name)
    pattern = tile.pattern
    px, py = pattern.period
    moves = [(px, 0.0), (0.0, py), (-px, 0.0), (0.0, -py)]
    if hasattr(pattern, "lattice"):
        moves += [tuple(v) for v in pattern.lattice]
    areas = shapely.area(fc.faces)
    inside = shapely.point_on_surface(fc.faces)
    tree = shapely.STRtree(fc.faces)
    checked = 0
    for dx, dy in moves:
        moved = shapely.transform(inside, lambda c, dx=dx, dy=dy: c + (dx, dy))
        i, j = tree.query(moved, predicate="within")
        # face i moved lies in face j (when i is the smaller: i is a piece of j's translate, or equal)
        keep = areas[i] <= areas[j] * (1 + 1e-6)
        assert (fc.labels[i[keep]] == fc.labels[j[keep]]).all()
        checked += int(keep.sum())
    assert checked > len(fc.faces)


def test_pieces_cut_by_the_frame_keep_their_whole_face_class():
    tile = _sample("table3-3.toml")
    fc = face_classes(tile)
    cut = _cut(tile, fc.faces)
    # the 150 mm tile's frame cuts faces of the large classes: they have uncut members
    assert cut.sum() > 20
    assert all((fc.labels[~cut] == fc.labels[i]).any() for i in np.flatnonzero(cut) if shapely.area(fc.faces[i]) > 1.0)


def test_stable_letters_across_calls_and_tiles():
    a = face_classes(_sample("table3-3.toml"))
    b = face_classes(_sample("table3-3.toml"))
    assert a.classes == b.classes
    np.testing.assert_array_equal(a.labels, b.labels)
    assert shapely.equals_exact(a.faces, b.faces, tolerance=0).all()


def test_by_none_is_one_class_of_every_face():
    tile = _sample("tilings/4.8.8.toml")
    fc = face_classes(tile, by="none")
    assert len(fc.classes) == 1 and (fc.labels == 0).all()
    c = fc.classes[0]
    assert (c.letter, c.count, c.description) == ("A", len(fc.faces), "faces")
    assert c.area_mm2 == pytest.approx(tile.outline_shape().area - tile.region().area, rel=1e-6)


def test_region_override_fills_holes():
    tile = _sample("table3-3.toml")
    from fabtiles.geometry.narrow import fill_small_holes

    filled, n = fill_small_holes(tile.region(), 1.2)
    full, less = face_classes(tile), face_classes(tile, region=filled)
    assert len(less.faces) == len(full.faces) - n
    # each face left keeps its class: its shape's description and its place in the order
    i, j = shapely.STRtree(full.faces).query(shapely.point_on_surface(less.faces), predicate="within")
    assert len(i) == len(less.faces)

    def desc(fc, k):
        return fc.classes[fc.labels[k]].description

    assert [desc(less, a) for a in i] == [desc(full, b) for b in j]
    assert less.classes[0].description == full.classes[0].description
    assert shapely.area(less.faces).sum() < shapely.area(full.faces).sum()


# -- descriptions, by shape alone (a region with holes of known shapes) ----------------
def _regular(n, r=4.0, angle=0.0):
    t = np.radians(angle) + 2 * np.pi * np.arange(n) / n
    return shapely.Polygon(np.c_[r * np.cos(t), r * np.sin(t)])


def _star(k, r=5.0, inner=2.5, angle=0.0):
    t = np.radians(angle) + np.pi * np.arange(2 * k) / k
    rad = np.where(np.arange(2 * k) % 2 == 0, r, inner)
    return shapely.Polygon(np.c_[rad * np.cos(t), rad * np.sin(t)])


SHAPES = [
    (_regular(3), "equilateral triangle"),
    (_regular(4), "square"),
    (_regular(5), "regular pentagon"),
    (_regular(6), "regular hexagon"),
    (_regular(8), "regular octagon"),
    (_regular(12), "regular dodecagon"),
    (_star(12), "12-point star"),
    (_star(5, inner=2.0), "5-point star"),
    (shapely.Polygon([(0, 0), (3, -2), (8, 0), (3, 2)]), "kite"),
    (shapely.Polygon([(0, 0), (4, 0), (6, 3), (2, 3)]), "quadrilateral"),
    (shapely.Polygon([(0, 0), (5, 0), (8, 4), (3, 4)]), "rhombus"),
    (shapely.box(0, 0, 7, 3), "rectangle"),
    (shapely.Polygon([(0, 0), (6, 0), (1, 4)]), "triangle"),
    (shapely.Polygon([(0, 0), (6, 0), (7, 3), (3, 6), (-1, 3)]), "pentagon"),
    (shapely.Polygon([(0, 0), (6, 0), (8, 3), (6, 6), (0, 6), (-1, 3)]), "hexagon"),
    (shapely.Polygon([(0, 0), (6, 0), (6, 6), (3, 2), (0, 6)]), "concave pentagon"),
    (shapely.Polygon([(0, 0), (6, 0), (6, 6), (4, 6), (3, 2), (2, 6), (0, 6)]), "concave heptagon"),
    (shapely.Polygon([(0, 0), (3, -1), (1, 0), (3, 1)]), "dart"),
    (shapely.Polygon([(0, 0), (4, 0), (6, 2), (4, 4), (0, 4), (1, 3), (-1, 2), (1, 1)]), "concave octagon"),
    (_regular(40), ""),
]

MOTIF_TILE = TileGeometry("square", 100, Star.preset("table3-1"), frame=2, stroke=0.6)


def _material(*holes):
    """A 100 mm plate of the motif tile's outline with ``holes`` cut, laid apart."""
    placed = [aff.translate(h, 15 + 17 * (i % 5), 15 + 17 * (i // 5)) for i, h in enumerate(holes)]
    return MOTIF_TILE.outline_shape().difference(shapely.union_all(placed)), placed


@pytest.mark.parametrize("shape, description", SHAPES, ids=[d or "nothing plain" for _, d in SHAPES])
def test_description(shape, description):
    # the same shape moved, turned, mirrored and with an extra vertex mid-edge is one class
    coords = shapely.get_coordinates(shape.exterior)
    extra = shapely.Polygon(np.insert(coords, 1, (coords[0] + coords[1]) / 2, axis=0))
    copies = [shape, aff.rotate(shape, 37.3, origin="centroid"), aff.scale(shape, -1, 1), extra]
    region, _ = _material(*copies)
    fc = face_classes(MOTIF_TILE, region=region)
    assert [(c.count, c.description) for c in fc.classes] == [(4, description)]
    assert fc.classes[0].area_mm2 == pytest.approx(4 * shape.area, rel=1e-9)


def test_a_12_point_star_preset():
    tile = TileGeometry("circle", 100, Star.preset("table3-1"), frame=2, stroke=0.6)
    descriptions = {c.description: c.count for c in face_classes(tile).classes}
    assert descriptions["12-point star"] == 1


def test_close_shapes_are_told_apart_and_congruent_ones_not():
    sq = shapely.box(0, 0, 6, 6)
    bigger = shapely.box(0, 0, 6.01, 6.01)  # 10 microns larger: another shape
    tiny = shapely.box(0, 0, 6 + 1e-7, 6)  # within the tolerance: the same
    fc = face_classes(MOTIF_TILE, region=_material(sq, aff.rotate(sq, 0.1), bigger, tiny)[0])
    assert sorted(c.count for c in fc.classes) == [1, 3]
    assert [(c.count, c.description) for c in fc.classes] == [(3, "square"), (1, "square")]
    assert fc.classes[1].area_mm2 == pytest.approx(6.01**2)


def test_a_face_round_an_island():
    plate = shapely.box(0, 0, 50, 50)
    hole = shapely.box(10, 10, 40, 40)
    island = shapely.box(20, 20, 30, 30).difference(shapely.box(24, 24, 26, 26))
    region = plate.difference(hole).union(island)
    tile = TileGeometry("square", 50, Star.preset("table3-1"), frame=2)
    fc = face_classes(tile, region=region)
    assert sorted(shapely.area(fc.faces).tolist()) == pytest.approx([4.0, 800.0])
    assert {c.description for c in fc.classes} == {"square", ""}


# -- property: random motifs on a packing ------------------------------------------------
@given(
    n=st.integers(5, 12),
    r1=st.floats(0.3, 0.9),
    r2=st.floats(0.3, 1.0),
    stroke=st.floats(0.4, 1.2),
    frame=st.sampled_from([0.0, 3.0]),
    join=st.sampled_from(["miter", "bevel", "round"]),
    outline=st.sampled_from(["square", "hexagon", "circle"]),
    packing=st.sampled_from([HexPacking, SquarePacking]),
    circles=st.booleans(),
)
@settings(max_examples=examples(8), deadline=None)
def test_random_motifs_on_a_packing(n, r1, r2, stroke, frame, join, outline, packing, circles):
    tile = TileGeometry(
        outline,
        70,
        packing(radius=10, motif=Star(n=n, radii=(r1, r2, 1.0)), outline_circles=circles),
        frame=frame,
        stroke=stroke,
        join=join,
    )
    fc = face_classes(tile)
    outline, region = tile.outline_shape(), tile.region()
    total = shapely.area(fc.faces).sum()
    assert total + region.area == pytest.approx(outline.area, rel=1e-4)
    areas = [c.area_mm2 for c in fc.classes]
    assert all(a >= b * (1 - 1e-9) for a, b in pairwise(areas))
    cut = _cut(tile, fc.faces)
    areas = shapely.area(fc.faces)
    for k in range(len(fc.classes)):
        whole = np.flatnonzero((fc.labels == k) & ~cut)
        if len(whole) > 1:
            np.testing.assert_allclose(areas[whole], areas[whole[0]], rtol=1e-3)
            assert _point_match(fc.faces[whole[0]], fc.faces[whole[-1]]) < 1e-3
    # translates by the packing's period share a class
    px, _ = tile.pattern.period
    moved = shapely.transform(shapely.point_on_surface(fc.faces), lambda c: c + (px, 0.0))
    i, j = shapely.STRtree(fc.faces).query(moved, predicate="within")
    keep = areas[i] <= areas[j] * (1 + 1e-6)
    assert (fc.labels[i[keep]] == fc.labels[j[keep]]).all()


# -- errors ----------------------------------------------------------------------------
def test_by_must_be_shape_or_none():
    with pytest.raises(ParameterError, match=r"'colour' is not a valid by, must be one of: shape, none"):
        face_classes(MOTIF_TILE, by="colour")


def test_tile_must_be_a_tile():
    with pytest.raises(ParameterError, match=r"tile must be a TileGeometry .*got Polygon"):
        face_classes(shapely.box(0, 0, 1, 1))


def test_of_an_unknown_letter():
    fc = FaceClasses(np.empty(0, object), np.empty(0, int), (FaceClass("A", 0, "", 0.0),))
    with pytest.raises(ParameterError, match=r"face class 'Q' is not one of this tile's classes \(A\)"):
        fc.of("Q")


def test_region_must_be_polygons():
    with pytest.raises(ParameterError, match=r"region must be a shapely Polygon or MultiPolygon, got LineString"):
        face_classes(MOTIF_TILE, region=shapely.LineString([(0, 0), (1, 1)]))


def test_no_faces():
    fc = face_classes(MOTIF_TILE, region=MOTIF_TILE.outline_shape())
    assert len(fc.faces) == 0 and fc.classes == () and fc.stats() == []


def test_a_tile_with_no_material_is_one_face_its_outline():
    # a 20 mm circle in a hex packing of radius 40: every stroke falls outside it (the build refuses the tile
    # saying so; its faces must not fail first)
    tile = TileGeometry("circle", 20, HexPacking(radius=40, motif=Star.preset("table3-3")), frame=0, stroke=1)
    assert tile.region().is_empty
    classes = face_classes(tile, by="shape")
    assert len(classes.faces) == 1 and [c.count for c in classes.classes] == [1]
    assert classes.faces[0].area == pytest.approx(tile.outline_shape().area)


def test_a_border_wider_than_a_third_of_the_packings_period_is_classed():
    # the whole faces are found in a window a few periods wide, which once carried the tile's border: a border
    # the tile takes (at most a third of it) was refused there as wider than a third of the window
    from fabtiles.pattern.archimedean import ArchimedeanPacking

    packing = ArchimedeanPacking("3.3.3.3.3.3", edge=10, method="hankin", contact_angle=30)
    tile = TileGeometry("square", 120, packing, frame=0, stroke=1, border_mm=35)
    fc = face_classes(tile, by="shape")
    assert len(fc.classes) > 1 and shapely.union_all(fc.faces).area + tile.region().area == pytest.approx(120 * 120)
