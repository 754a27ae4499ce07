"""STEP round walls (issue 35): the arcs of a print's boundary as circle edges and cylinder faces.

Read back as CAD programs read them (build123d's ``import_step``, OCCT with its shape
healing) and as the writer's own check does (OCCT's translator without healing): one
valid solid per body, its round walls cylinders of the right radius, the volume of the
true shape (the region at a high resolution times its heights) within 0.05 %.
"""

from __future__ import annotations

import math

import pytest
import shapely
from mesh_helpers import B, H, T, occt_volume
from model_files import write_print
from shapely.geometry import Point, box

from fabtiles import ProfileError, Star, Tile
from fabtiles.export import step
from fabtiles.pattern.packing import HexPacking

FINE = 1024
"""quad_segs of the high-resolution shapes the volumes are measured against."""


def _write(tmp_path, region, outline, style="pierced", profile="fdm-0.4mm", name="t.step"):
    path = tmp_path / name
    report = write_print(path, region=region, outline=outline, profile=profile, style=style, name="t")
    return path, report


def _read(path):
    from build123d import import_step

    part = import_step(str(path))
    assert part.is_valid
    return part


def _cylinders(part):
    from build123d import GeomType

    kinds = {f.geom_type for f in part.faces()}
    assert kinds <= {GeomType.PLANE, GeomType.CYLINDER}, kinds
    return [f for f in part.faces() if f.geom_type == GeomType.CYLINDER]


def _radius(face) -> float:
    from OCP.BRepAdaptor import BRepAdaptor_Surface

    return BRepAdaptor_Surface(face.wrapped).Cylinder().Radius()


def _check_unhealed(path, report):
    """The writer's own independent check: OCCT's translator without healing, face by face."""
    return step.check_step_file(path, volume=report.stats["volume_mm3"], parts=report.stats["solids"])


def test_a_round_hole_is_one_cylinder_in_two_halves(tmp_path):
    plate, hole = box(0, 0, 40, 40), Point(20, 20).buffer(5.0, quad_segs=64)
    path, report = _write(tmp_path, plate.difference(hole), plate)
    part = _read(path)
    cyl = _cylinders(part)
    assert len(cyl) == 2 and len(part.faces()) == 8  # 4 sides, top, bottom and the hole's halves
    assert [_radius(f) for f in cyl] == pytest.approx([5.0, 5.0], abs=1e-3)
    true = plate.difference(Point(20, 20).buffer(5.0, quad_segs=FINE)).area * T
    assert part.volume == pytest.approx(true, rel=0.0005)
    assert report.stats["cylinders"] == 2
    assert _check_unhealed(path, report) == pytest.approx(part.volume, rel=1e-6)


def test_arcs_between_straight_walls_at_one_height(tmp_path):
    """A rounded plate with a rounded slot: a quarter cylinder at each corner between the straight walls."""
    outline = box(4, 4, 46, 26).buffer(4.0, quad_segs=32)
    slot = box(15, 12, 35, 18).buffer(2.0, quad_segs=32)
    path, report = _write(tmp_path, outline.difference(slot), outline)
    part = _read(path)
    cyl = _cylinders(part)
    assert sorted(_radius(f) for f in cyl) == pytest.approx([2.0] * 4 + [4.0] * 4, abs=0.005)
    assert len(part.faces()) == 8 + 8 + 2
    fine = box(4, 4, 46, 26).buffer(4.0, quad_segs=FINE).difference(box(15, 12, 35, 18).buffer(2.0, quad_segs=FINE))
    assert part.volume == pytest.approx(fine.area * T, rel=0.0005)
    _check_unhealed(path, report)


def test_a_relief_whose_outline_wall_steps_between_levels(tmp_path):
    """A band across a round relief: the outline's wall rises to the band's top where the band meets it."""
    outline = Point(0, 0).buffer(20.0, quad_segs=64)
    band = box(-25, -3, 25, 3).intersection(outline)
    path, report = _write(tmp_path, band, outline, style="relief")
    part = _read(path)
    radii = sorted(_radius(f) for f in _cylinders(part))
    # a face for each stretch at one height: the band's ends, short arcs (17 degrees) whose radius their
    # grid points fix only within 0.2 mm (their vertices within 0.002 mm of it), and the rest, 20 mm
    assert len(radii) == 4 and radii == pytest.approx([20.0] * 4, abs=0.2)
    assert radii[2:] == pytest.approx([20.0] * 2, abs=0.002)
    fine = Point(0, 0).buffer(20.0, quad_segs=FINE)
    true = fine.area * B + box(-25, -3, 25, 3).intersection(fine).area * H
    assert part.volume == pytest.approx(true, rel=0.0005)
    _check_unhealed(path, report)


def test_a_pierced_circle_tile_with_outline_circles_and_round_joins(tmp_path):
    tile = Tile(
        "circle", 40, HexPacking(8, Star.preset("table3-3"), outline_circles=True), frame=2.0, stroke=1.2, join="round"
    )
    path = tmp_path / "t.step"
    report = tile.export(path, profile="fdm-0.4mm", style="pierced")
    part = _read(path)
    cyl = _cylinders(part)
    assert sum(abs(_radius(f) - 20.0) < 1e-3 for f in cyl) == 2  # the outline: one circle
    assert len(cyl) > 20
    assert occt_volume(part.wrapped) == pytest.approx(report.stats["volume_mm3"], rel=0.0005)
    _check_unhealed(path, report)


def test_narrow_round_joins_in_two_chords_are_cylinders_of_half_the_stroke(tmp_path):
    """A band turning 58 degrees twice: each join flattened in two chords (within the profile's
    0.02 mm). Given the stroke, the STEP knows their radius and makes each a cylinder; without it,
    two chords prove no circle and the walls stay planar. Either way OCCT reads one valid solid of
    the true shape's volume (the joins' chords against their arcs: 0.002 mm^2 each)."""
    t = math.radians(58)
    path = [(2, 10), (12, 10), (12 + 6 * math.cos(t), 10 + 6 * math.sin(t))]
    path.append((path[-1][0] + 10, path[-1][1]))
    outline = box(0, 0, 40, 25)
    band = shapely.LineString(path).buffer(0.6, quad_segs=3).intersection(outline)
    fine = shapely.LineString(path).buffer(0.6, quad_segs=FINE).intersection(outline)
    joins = {}
    for stroke in (None, 1.2):
        out = tmp_path / f"{stroke}.step"
        report = write_print(
            out, region=band, outline=outline, profile="fdm-0.4mm", style="relief", stroke=stroke, name="t"
        )
        part = _read(out)
        joins[stroke] = sorted(round(_radius(f), 4) for f in _cylinders(part) if _radius(f) < 1)
        assert part.volume == pytest.approx(outline.area * B + fine.area * H, rel=0.0005)
        _check_unhealed(out, report)
    # the caps (180 degrees in six chords of 30: 0.0204 mm off the arc) are no arcs at 0.02 mm
    assert joins == {None: [], 1.2: [0.6, 0.6]}


def test_the_file_is_the_same_bytes_every_time(tmp_path):
    plate, hole = box(0, 0, 30, 30), Point(15, 15).buffer(4.0, quad_segs=64)
    a, _ = _write(tmp_path, plate.difference(hole), plate, name="a.step")
    b, _ = _write(tmp_path, plate.difference(hole), plate, name="b.step")
    text = a.read_bytes()
    assert text == b.read_bytes()
    assert text.count(b"CYLINDRICAL_SURFACE(") == 2 and text.count(b"CIRCLE(") == 4


def test_a_round_edge_takes_a_fillet(tmp_path):
    """A CAD user's first move: a 1 mm fillet on the top edge of a hole."""
    from build123d import GeomType, fillet

    plate, hole = box(0, 0, 40, 40), Point(20, 20).buffer(6.0, quad_segs=64)
    path, _ = _write(tmp_path, plate.difference(hole), plate)
    part = _read(path)
    rim = [e for e in part.edges() if e.geom_type == GeomType.CIRCLE and abs(e.center().Z - T) < 1e-6]
    assert len(rim) == 2 and all(abs(e.radius - 6.0) < 1e-3 for e in rim)
    rounded = fillet(rim, radius=1.0)
    assert rounded.is_valid
    # a fillet of radius 1 cuts (1 - pi / 4) mm^2 of section, its centroid 0.22 mm from the rim
    removed = (1 - math.pi / 4) * 2 * math.pi * (6.0 + (10 - 3 * math.pi) / (12 - 3 * math.pi))  # Pappus
    assert part.volume - rounded.volume == pytest.approx(removed, rel=0.01)


def test_a_tolerance_of_zero_keeps_the_walls_planar(tmp_path):
    profile = tmp_path / "exact.toml"
    profile.write_text('kind = "printer"\n[printer]\ntolerance_mm = 0\n')
    plate, hole = box(0, 0, 40, 40), Point(20, 20).buffer(5.0, quad_segs=16)
    path, report = _write(tmp_path, plate.difference(hole), plate, profile=profile)
    assert _cylinders(_read(path)) == [] and report.stats["cylinders"] == 0


def test_a_tolerance_too_coarse_for_the_arcs_is_refused_with_no_file(tmp_path):
    """At 5 mm the hexagonal holes pass for circles: the solid would lose its shape."""
    profile = tmp_path / "coarse.toml"
    profile.write_text('kind = "printer"\n[printer]\ntolerance_mm = 5\n')
    hexagons = [
        shapely.Polygon([(x + 4 * math.cos(k * math.pi / 3), y + 4 * math.sin(k * math.pi / 3)) for k in range(6)])
        for x in (10, 30)
        for y in (10, 30)
    ]
    plate = box(0, 0, 40, 40)
    with pytest.raises(ProfileError, match=r"tolerance_mm = 5 mm is too coarse .* set printer.tolerance_mm"):
        _write(tmp_path, plate.difference(shapely.union_all(hexagons)), plate, profile=profile)
    assert not (tmp_path / "t.step").exists()


def test_gmsh_reads_the_cylinders_and_meshes_the_solid(tmp_path):
    """gmsh (its own OCCT build, as FEM users open a part): one volume, the hole's two cylinder faces,
    the file's volume, and a surface mesh of it."""
    import gmsh

    plate, hole = box(0, 0, 30, 20), Point(15, 10).buffer(4.0, quad_segs=64)
    path, report = _write(tmp_path, plate.difference(hole), plate)
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        volumes = gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        assert [dim for dim, _ in volumes] == [3]
        kinds = sorted(gmsh.model.getType(2, tag) for _, tag in gmsh.model.getEntities(2))
        assert kinds == ["Cylinder"] * 2 + ["Plane"] * 6
        assert gmsh.model.occ.getMass(3, volumes[0][1]) == pytest.approx(report.stats["volume_mm3"], rel=1e-6)
        gmsh.option.setNumber("Mesh.MeshSizeMax", 2.0)
        gmsh.model.mesh.generate(2)
        _, nodes, _ = gmsh.model.mesh.getNodes()
        assert len(nodes) > 100
    finally:
        gmsh.finalize()


def _perforated(n: int, pitch: float = 2.0, r: float = 0.5):
    """A square plate with n x n round holes."""
    side = n * pitch
    holes = [Point(pitch * (i + 0.5), pitch * (j + 0.5)).buffer(r, quad_segs=16) for i in range(n) for j in range(n)]
    return box(0, 0, side, side).difference(shapely.union_all(holes)), box(0, 0, side, side)


def _flat_faces(part):
    from build123d import GeomType

    return [f for f in part.faces() if f.geom_type == GeomType.PLANE and abs(f.normal_at().Z) > 0.5]


@pytest.mark.parametrize("style", ["pierced", "relief"])
def test_a_face_of_many_holes_is_cut_into_cells_that_opencascade_reads_fast(tmp_path, style, monkeypatch):
    """More holes than MAX_FACE_HOLES (20 here, for a small test: 64 holes) in one face, so the flat
    faces are cut by a grid (a pierced plate's bottom too); one valid solid of the true volume, every
    hole's wall still cylinders, where a seam cuts it too."""
    from fabtiles.solid import brep

    monkeypatch.setattr(brep, "MAX_FACE_HOLES", 20)
    n = 8
    # holes 6 mm apart: their edges thinned for the slicers within 0.02 mm (16 chords) hold 0.24 % more
    # plastic than their arcs (the STEP refuses arcs that change the volume by more than 0.5 %)
    region, outline = _perforated(n, pitch=6.0, r=1.0)
    clip = box(0.5, 0.5, 47.5, 47.5)
    if style == "relief":  # the holes in the pattern's top, the base whole beneath (no hole touching its edge)
        region = region.intersection(clip)
    path, report = _write(tmp_path, region, outline, style=style)
    part = _read(path)
    assert len(part.solids()) == 1
    flat = _flat_faces(part)
    tops = [f for f in flat if f.normal_at().Z > 0]
    bottoms = [f for f in flat if f.normal_at().Z < 0]
    assert len(tops) >= 4 and all(len(f.inner_wires()) <= 20 for f in flat)
    assert len(bottoms) == (len(tops) if style == "pierced" else 1)  # a relief's bottom is the whole outline
    radii = [_radius(f) for f in _cylinders(part)]
    assert len(radii) >= 2 * n * n and radii == pytest.approx([1.0] * len(radii), rel=0.01)
    fine = outline.difference(
        shapely.union_all(
            [Point(6 * (i + 0.5), 6 * (j + 0.5)).buffer(1.0, quad_segs=FINE) for i in range(n) for j in range(n)]
        )
    )
    true = fine.area * T if style == "pierced" else outline.area * B + fine.intersection(clip).area * H
    assert part.volume == pytest.approx(true, rel=0.0005)
    _check_unhealed(path, report)


def test_holes_so_dense_that_their_thinning_moves_the_volume_ask_for_a_finer_tolerance(tmp_path):
    """64 holes of 1 mm 4 mm apart, thinned within the default 0.02 mm (16 chords each): 0.6 % more
    plastic than their arcs, more than the STEP allows; the error names a finer tolerance to give."""
    region, outline = _perforated(8, pitch=4.0, r=1.0)
    with pytest.raises(ProfileError, match=r"tolerance_mm = 0.02 mm is too coarse .* to 0.005 or finer"):
        _write(tmp_path, region, outline)
    assert not (tmp_path / "t.step").exists()


def test_up_to_max_face_holes_keep_one_face():
    import shapely as shp

    from fabtiles.solid.brep import MAX_FACE_HOLES, SINGLE_CELL, _cells_for_faces

    plate = box(0, 0, 100, 100)
    holes = [box(i * 3 + 1, j * 3 + 1, i * 3 + 2, j * 3 + 2) for i in range(33) for j in range(33)]
    many = plate.difference(shp.union_all(holes[: MAX_FACE_HOLES + 1]))
    few = plate.difference(shp.union_all(holes[:MAX_FACE_HOLES]))
    assert _cells_for_faces([(few, 3.0)]) == SINGLE_CELL
    assert _cells_for_faces([(many, 3.0)]) < SINGLE_CELL
