"""STEP export (issue 12): a solid as a CAD user would model it, checked by OCCT as CAD reads it.

Every file here is read back the way OCCT-based CAD (FreeCAD, CadQuery, build123d)
reads it: OCCT's STEP reader with its shape healing (``step.read_step``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from mesh_helpers import B, D, H, T, occt_volume, solids_of, step_bounds
from model_files import write_print
from shapely.geometry import box

from fabtiles import FabricationError, ParameterError, ProfileError, Star
from fabtiles.export import step
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking


def _faces(shape):
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    out = []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face(exp.Current())
        out.append((face, BRepAdaptor_Surface(face, True)))
        exp.Next()
    return out


def _planes(shape, cylinders=False):
    """(normal (x, y, z), a point) of every plane face; every face must be a plane (or, with
    ``cylinders``, a cylinder: a round wall, which is left out)."""
    from OCP.GeomAbs import GeomAbs_Cylinder, GeomAbs_Plane
    from OCP.TopAbs import TopAbs_REVERSED

    out = []
    for face, surf in _faces(shape):
        if cylinders and surf.GetType() == GeomAbs_Cylinder:
            continue
        assert surf.GetType() == GeomAbs_Plane
        ax = surf.Plane().Axis()
        n = ax.Direction()
        sign = -1.0 if face.Orientation() == TopAbs_REVERSED else 1.0
        p = ax.Location()
        out.append(((sign * n.X(), sign * n.Y(), sign * n.Z()), (p.X(), p.Y(), p.Z()), face))
    return out


def _edges(shape):
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    out = []
    exp = TopExp_Explorer(shape, TopAbs_EDGE)
    while exp.More():
        c = BRepAdaptor_Curve(TopoDS.Edge(exp.Current()))
        a, b = c.Value(c.FirstParameter()), c.Value(c.LastParameter())
        out.append((c.GetType(), (a.X(), a.Y(), a.Z()), (b.X(), b.Y(), b.Z())))
        exp.Next()
    return out


def assert_no_coplanar_neighbours(shape):
    """Every edge joins two faces in different planes: each flat region is one face (cylinders: see
    tests/export/test_step_cylinders.py).

    The faces of each edge are gathered as OCCT's ``TopExp.MapShapesAndAncestors`` gathers them
    (every face, every edge of it), by one walk over the faces: reading that map's lists back edge by
    edge took seconds on a sample's tile. Each face's plane is read once."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as ShapeMap
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    faces, edges = ShapeMap(), ShapeMap()
    edge_of, face_of = [], []
    walk = TopExp_Explorer(shape, TopAbs_FACE)
    while walk.More():
        face = walk.Current()
        k = faces.Add(face)
        inner = TopExp_Explorer(face, TopAbs_EDGE)
        while inner.More():
            edge_of.append(edges.Add(inner.Current()))
            face_of.append(k)
            inner.Next()
        walk.Next()
    planes = np.full((faces.Extent() + 1, 4), np.nan)  # (normal, offset) by face index; NaN: not a plane
    for k in range(1, faces.Extent() + 1):
        surf = BRepAdaptor_Surface(TopoDS.Face(faces.FindKey(k)), False)
        if surf.GetType() == GeomAbs_Plane:
            pl = surf.Plane()
            n, p = pl.Axis().Direction(), pl.Location()
            planes[k] = (n.X(), n.Y(), n.Z(), n.X() * p.X() + n.Y() * p.Y() + n.Z() * p.Z())
    edge_of, face_of = np.asarray(edge_of), np.asarray(face_of)
    assert (np.bincount(edge_of)[1:] == 2).all()  # every edge of a face bounds two faces
    pair = face_of[np.argsort(edge_of, kind="stable")].reshape(-1, 2)
    one, two = planes[pair[:, 0]], planes[pair[:, 1]]
    dot = (one[:, :3] * two[:, :3]).sum(axis=1)
    same = (np.abs(np.abs(dot) - 1) < 1e-9) & (np.abs(one[:, 3] - np.where(dot > 0, two[:, 3], -two[:, 3])) < 1e-6)
    assert not same.any(), [one[same][0].tolist(), two[same][0].tolist()]


def _write(tmp_path, tile, style="relief", **kw):
    path = tmp_path / "t.step"
    path.unlink(missing_ok=True)
    report = write_print(
        path,
        region=tile.region(),
        outline=tile.outline_shape(),
        profile="fdm-0.4mm",
        style=style,
        stroke=tile.stroke,
        **kw,
    )
    return path, report


def _tile(outline="square", size=40, frame=5.0, radius=10, preset="table3-3"):
    return TileGeometry(outline, size, HexPacking(radius, Star.preset(preset)), frame=frame, stroke=1.0)


@pytest.mark.parametrize("outline,sides", [("square", 4), ("hexagon", 6)])
@pytest.mark.parametrize("frame", [5.0, 0.0])
def test_relief_is_modelled_with_planar_faces_one_per_flat_region(tmp_path, outline, sides, frame):
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.GeomAbs import GeomAbs_Line

    tile = _tile(outline, frame=frame)
    path, report = _write(tmp_path, tile)
    back = step.read_step(path)
    assert solids_of(back) == 1 and BRepCheck_Analyzer(back).IsValid()
    planes = _planes(back)  # asserts every face is a plane
    edges = _edges(back)
    assert all(kind == GeomAbs_Line for kind, _, _ in edges)
    bottom = [f for n, p, f in planes if n[2] < -0.999]
    assert len(bottom) == 1
    assert all(abs(p[2]) < 1e-9 for n, p, _ in planes if n[2] < -0.999)
    # each straight side of the outline is one face (corners are snapped to the 2**-10 mm grid)
    ring = shapely.get_coordinates(tile.outline_shape().exterior)[:-1]
    for a, b in zip(ring, [*ring[1:], ring[0]], strict=True):
        d = (b - a) / math.hypot(*(b - a))
        on_side = [
            f
            for n, p, f in planes
            if abs(n[2]) < 1e-9
            and abs(n[0] * d[0] + n[1] * d[1]) < 1e-4
            and abs((p[0] - a[0]) * d[1] - (p[1] - a[1]) * d[0]) < 2e-3
            and (n[0] * d[1] - n[1] * d[0]) > 0
        ]
        assert len(on_side) == 1, (a, b)
    # one face per flat region: no two faces that meet along an edge lie in one plane
    assert_no_coplanar_neighbours(back)
    tops = [f for n, p, f in planes if n[2] > 0.999 and abs(p[2] - (B + H)) < 1e-9]
    assert len(tops) == len(shapely.get_parts(tile.region()))
    assert report.stats["faces"] == len(planes)
    # vertical edges at the outline's corners, from the bottom to the top of the side there
    vertical = [
        a for kind, a, b in edges if abs(a[0] - b[0]) < 1e-9 and abs(a[1] - b[1]) < 1e-9 and abs(a[2] - b[2]) > 1e-3
    ]
    for x, y in ring:
        assert any(math.hypot(x - v[0], y - v[1]) < 1e-3 for v in vertical), (x, y)


@pytest.mark.parametrize(
    "style,preset,outline",
    [
        ("relief", "table3-3", "square"),
        ("pierced", "table3-1", "hexagon"),
        ("deboss", "table2-left", "square"),
        ("pierced", "table3-3", "hexagon"),
        ("relief", "table1-part1", "circle"),
    ],
)
def test_occt_volume_is_the_mesh_volume_within_005_percent(tmp_path, style, preset, outline):
    """OCCT's own volume (what FreeCAD shows): was up to 16.5 % off on a pierced hexagon."""
    tile = _tile(outline, size=60, frame=3.0, radius=12, preset=preset)
    path, report = _write(tmp_path, tile, style)
    back = step.read_step(path)
    volume = occt_volume(back)
    assert volume == pytest.approx(report.stats["volume_mm3"], rel=0.0005)
    expected = {
        "relief": tile.outline_shape().area * B + tile.region().area * H,
        "pierced": tile.region().area * T,
        "deboss": tile.outline_shape().area * B - tile.region().area * D,
    }[style]
    assert volume == pytest.approx(expected, rel=0.005)
    _x0, _y0, z0, _x1, _y1, z1 = step_bounds(back)
    assert z0 == pytest.approx(0, abs=1e-3) and z1 == pytest.approx(
        {"relief": B + H, "pierced": T, "deboss": B}[style], abs=1e-3
    )


def test_cad_fillets_the_corners_and_drills_a_hole(tmp_path):
    """What a CAD user does next: 2 mm fillets on the corners, a 3 mm hole through the frame."""
    import build123d as bd

    tile = _tile("square", size=40, frame=5.0)
    path, _ = _write(tmp_path, tile)
    part = bd.import_step(str(path))
    solid = part.solids()[0]
    corners = [
        e
        for e in solid.edges().filter_by(bd.Axis.Z)
        if min(abs(e.center().X), abs(e.center().X - 40)) < 1e-6
        and min(abs(e.center().Y), abs(e.center().Y - 40)) < 1e-6
    ]
    assert len(corners) == 4
    filleted = solid.fillet(2.0, corners)
    assert filleted.is_valid and len(filleted.solids()) == 1
    # a fillet takes (1 - pi / 4) r^2 off each of the 4 corners over the full height
    assert filleted.volume == pytest.approx(solid.volume - 4 * (1 - math.pi / 4) * 2.0**2 * (B + H), rel=1e-6)
    drilled = filleted - bd.Pos(2.5, 20, 0) * bd.Cylinder(1.5, 20)
    assert drilled.is_valid and len(drilled.solids()) == 1
    assert drilled.volume == pytest.approx(filleted.volume - math.pi * 1.5**2 * (B + H), rel=1e-3)


def test_interlaced_relief_dips_in_the_step_too(tmp_path):
    """A woven relief on a seamless hexagon: valid, planes and cylinders, the dips' level present, the mesh's
    volume (its round parts as arcs, within 0.05 %)."""
    import fabtiles as ft
    from fabtiles.geometry.stack import resolve_stack
    from fabtiles.solid.levels import dip_z

    tile = ft.Tile("hexagon", 50, HexPacking(12, Star.preset("table3-3")), frame=0.0, stroke=1.5, interlace=True)
    path = tmp_path / "t.step"
    report = tile.export(path, profile="fdm-0.4mm")
    back = step.read_step(path)
    planes = _planes(back, cylinders=True)
    assert_no_coplanar_neighbours(back)
    dip = dip_z(resolve_stack("fdm-0.4mm"))
    assert any(n[2] > 0.999 and abs(p[2] - dip) < 1e-9 for n, p, _ in planes)
    assert occt_volume(back) == pytest.approx(report.stats["volume_mm3"], rel=0.0005)
    stl = tile.export(tmp_path / "t.stl", profile="fdm-0.4mm")
    assert report.stats["volume_mm3"] == pytest.approx(stl.stats["volume_mm3"], rel=0.0005)


def test_pierced_in_pieces_gives_one_solid_each(tmp_path):
    region = shapely.MultiPolygon([box(1, 1, 4, 4), box(6, 6, 9, 9)])
    path = tmp_path / "t.step"
    report = write_print(path, region=region, outline=box(0, 0, 10, 10), profile="fdm-0.4mm", style="pierced")
    assert report.stats["solids"] == 2
    assert [f.code for f in report.findings] == ["loose_part"]
    back = step.read_step(path)
    assert solids_of(back) == 2
    assert occt_volume(back) == pytest.approx(18 * T, rel=1e-9)
    assert len(_planes(back)) == 12  # two boxes


def test_a_mosaic_of_one_colour_is_one_solid_not_an_assembly(tmp_path):
    plate = box(0, 0, 40, 40).difference(box(10, 10, 30, 30))
    path = tmp_path / "m.step"
    report = write_print(path, region=plate, outline=box(0, 0, 40, 40), profile="fdm-0.4mm", style="mosaic")
    assert report.stats["solids"] == 1
    text = path.read_text()
    assert text.count("MANIFOLD_SOLID_BREP(") == 1 and "NEXT_ASSEMBLY_USAGE_OCCURRENCE" not in text
    assert occt_volume(step.read_step(path)) == pytest.approx(report.stats["volume_mm3"], rel=1e-9)


@pytest.mark.parametrize("preset", Star.presets())
def test_every_preset_relief(tmp_path, preset):
    tile = TileGeometry("square", 24, HexPacking(8, Star.preset(preset)), frame=2, stroke=1.0)
    path, report = _write(tmp_path, tile)
    back = step.read_step(path)
    assert solids_of(back) == 1
    assert occt_volume(back) == pytest.approx(report.stats["volume_mm3"], rel=0.0005)


def test_file_is_byte_identical_on_every_run(tmp_path):
    tile = _tile(size=30)
    a, _ = _write(tmp_path, tile)
    first = a.read_bytes()
    b, _ = _write(tmp_path, tile)
    assert b.read_bytes() == first
    assert b"SI_UNIT(.MILLI.,.METRE.)" in first and b"AUTOMOTIVE_DESIGN" in first
    assert b"B_SPLINE" not in first and b"SURFACE_OF_LINEAR_EXTRUSION" not in first
    # the header's time stamp is fixed, as ISO 8601 (the standard's form), not the time of writing
    assert b"FILE_NAME('t.step','2000-01-01T00:00:00',(''),(''),'fabtiles','fabtiles','');" in first


def test_check_solids_refuses_a_wrong_volume_or_count(tmp_path):
    tile = _tile(size=30)
    path, report = _write(tmp_path, tile)
    solids = step.read_step_solids(path)
    v = report.stats["volume_mm3"]
    assert step.check_solids(solids, volume=v, parts=1) == pytest.approx(v, rel=0.0005)
    with pytest.raises(FabricationError, match=r"has a volume of .* not the mesh's .* \(0.05% allowed\)"):
        step.check_solids(solids, volume=v * 1.01, parts=1)
    with pytest.raises(FabricationError, match="holds 1 solids, not 2; nothing was written"):
        step.check_solids(solids, volume=v, parts=2)


def _refused_when_edited(tmp_path, edit, match):
    """A good file of a 30 mm tile, ``edit`` applied to its text by hand: check_solids refuses it."""
    path, report = _write(tmp_path, _tile(size=30))
    bad = tmp_path / "bad.step"
    bad.write_text(edit(path.read_text()))
    with pytest.raises(FabricationError, match=match):
        step.check_solids(step.read_step_solids(bad), volume=report.stats["volume_mm3"], parts=1)


def test_check_solids_refuses_an_open_shell(tmp_path):
    """A file with a face missing is refused (written by hand from a good one)."""
    import re

    def drop_a_face(text):
        shell = re.search(r"CLOSED_SHELL\('',\((#\d+),", text)
        return text.replace(shell.group(0), "CLOSED_SHELL('',(", 1)

    _refused_when_edited(tmp_path, drop_a_face, "open shell")


def test_check_solids_refuses_a_face_turned_inside_out(tmp_path):
    """One face's loop reversed by hand in a good file: its edges run the wrong way round."""
    import re

    def reverse_a_loop(text):
        bound = re.search(r"ADVANCED_FACE\('',\(#(\d+)\),#\d+,\.T\.\)", text).group(1)  # a face of one loop
        line = re.search(rf"^#{bound}=FACE_OUTER_BOUND\('',#\d+,\.T\.\);$", text, re.M).group(0)
        return text.replace(line, line.replace(".T.)", ".F.)"), 1)

    _refused_when_edited(tmp_path, reverse_a_loop, "oriented both ways")


def test_check_solids_refuses_a_face_whose_loop_disagrees_with_its_plane(tmp_path):
    """A face's same_sense flipped by hand: OCCT builds it on the reversed plane, and BRepCheck refuses it."""
    import re

    def flip_a_face(text):
        face = re.search(r"ADVANCED_FACE\('',\(#\d+\),#\d+,\.T\.\)", text).group(0)
        return text.replace(face, face[:-4] + ".F.)", 1)

    _refused_when_edited(tmp_path, flip_a_face, r"has an invalid face \(solid 1, BRepCheck_Analyzer\)")


def test_a_file_that_is_not_step_cannot_be_read_back(tmp_path):
    junk = tmp_path / "junk.step"
    junk.write_text("this is not a STEP file\n")
    with pytest.raises(FabricationError, match="cannot read back the STEP file"):
        step.read_step_solids(junk)
    with pytest.raises(FabricationError, match="cannot read back the STEP file"):
        step.read_step(junk)


def test_big_faces_are_checked_wire_by_wire(tmp_path, monkeypatch):
    """The per-wire check of faces with many holes agrees with BRepCheck on a valid and a broken face."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
    from OCP.gp import gp_Pln, gp_Pnt

    tile = _tile(size=40)
    path, report = _write(tmp_path, tile)
    monkeypatch.setattr(step, "BIG_FACE_WIRES", 2)  # every face with holes goes the per-wire way
    step.check_solids(step.read_step_solids(path), volume=report.stats["volume_mm3"], parts=1)

    def poly(pts):
        mk = BRepBuilderAPI_MakePolygon()
        for x, y in pts:
            mk.Add(gp_Pnt(x, y, 0))
        mk.Close()
        return mk.Wire()

    from OCP.TopoDS import TopoDS

    outer = poly([(0, 0), (10, 0), (10, 10), (0, 10)])
    mk = BRepBuilderAPI_MakeFace(gp_Pln(), outer)
    for hole in ([(1, 1), (1, 3), (3, 3), (3, 1)], [(2, 2), (2, 4), (4, 4), (4, 2)]):  # overlapping holes
        mk.Add(poly(hole))
    assert not step._big_face_valid(TopoDS.Face(mk.Face()))
    mk = BRepBuilderAPI_MakeFace(gp_Pln(), outer)
    for hole in ([(1, 1), (1, 3), (3, 3), (3, 1)], [(5, 5), (5, 7), (7, 7), (7, 5)]):
        mk.Add(poly(hole))
    assert step._big_face_valid(TopoDS.Face(mk.Face()))


@pytest.mark.slow
@settings(max_examples=examples(6), suppress_health_check=[HealthCheck.function_scoped_fixture], deadline=None)
@given(
    size=st.floats(20, 50),
    radius=st.floats(4, 15),
    preset=st.sampled_from(Star.presets()),
    style=st.sampled_from(["relief", "pierced", "deboss"]),
    outline=st.sampled_from(["square", "hexagon", "circle"]),
    frame=st.sampled_from([0.0, 2.0]),
)
def test_any_design_step_volume_is_occts(tmp_path, size, radius, preset, style, outline, frame):
    tile = TileGeometry(
        outline, size, HexPacking(radius, Star.preset(preset), outline_circles=True), frame=frame, stroke=1.0
    )
    path, report = _write(tmp_path, tile, style)
    back = step.read_step(path)
    assert solids_of(back) == report.stats["solids"]
    assert occt_volume(back) == pytest.approx(report.stats["volume_mm3"], rel=0.0005)
    _planes(back, cylinders=True)
    assert_no_coplanar_neighbours(back)


@pytest.mark.parametrize(
    "kwargs,exc,msg",
    [
        (dict(base_mm=0), ParameterError, "base_mm must be a finite number > 0"),
        (dict(style="deboss", deboss_mm=2.5), ParameterError, "deboss_mm must be smaller than base_mm"),
        (dict(profile="no-such-printer"), ProfileError, "does not exist"),
    ],
)
def test_step_bad_input_no_file(tmp_path, kwargs, exc, msg):
    tile = TileGeometry("square", 24, HexPacking(8, Star.preset("table3-3")), frame=2, stroke=1.0)
    kwargs = {"profile": "fdm-0.4mm", **kwargs}
    with pytest.raises(exc, match=msg):
        write_print(tmp_path / "t.step", region=tile.region(), outline=tile.outline_shape(), **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_step_strict_findings_no_file(tmp_path):
    strict = tmp_path / "strict.toml"
    strict.write_text('kind = "printer"\n[printer]\nstrict = true\nbed_mm = [10, 10]\n')
    with pytest.raises(FabricationError, match="bed_size"):
        write_print(tmp_path / "t.step", region=box(1, 1, 19, 19), outline=box(0, 0, 20, 20), profile=strict)
    assert [p.name for p in tmp_path.iterdir()] == ["strict.toml"]


def test_a_brep_the_check_refuses_is_never_written(tmp_path, monkeypatch):
    """When the in-memory B-rep check fails, nothing takes the file's name, and a good older file stays."""
    tile = _tile(size=30)
    path, _ = _write(tmp_path, tile)
    good = path.read_bytes()

    def refuse(*a, **k):
        raise FabricationError(
            "the STEP solid has an open shell or an edge joining more than two faces; nothing was written"
        )

    monkeypatch.setattr(step, "check_brep", refuse)
    with pytest.raises(FabricationError, match="open shell"):
        write_print(path, region=tile.region(), outline=tile.outline_shape(), profile="fdm-0.4mm")
    assert path.read_bytes() == good
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.step"]


def test_the_written_file_read_back_by_occt_has_the_checked_volume(tmp_path):
    """The independent check (``check_step_file``, for ``fabtiles check --deep``): OCCT reads the file's
    solids back with the volume the writer's in-memory check measured."""
    tile = _tile(size=30)
    path, report = _write(tmp_path, tile)
    volume = report.stats["volume_mm3"]
    assert step.check_step_file(path, volume=volume, parts=report.stats["solids"]) == pytest.approx(volume, rel=1e-6)
    with pytest.raises(FabricationError, match=r"STEP file '.*t\.step' holds 1 solids, not 2"):
        step.check_step_file(path, volume=volume, parts=2)


def test_check_solids_refuses_an_empty_solid_a_hollow_one_and_one_inside_out():
    """The guards only a broken writer could trip, on solids made by hand in OCCT."""
    from build123d import Box, Pos
    from OCP.TopoDS import TopoDS, TopoDS_Solid

    with pytest.raises(FabricationError, match=r"has an empty solid \(1\); nothing was written"):
        step.check_solids([TopoDS_Solid()], volume=1.0, parts=1)
    hollow = (Box(10, 10, 10) - Pos(0, 0, 0) * Box(4, 4, 4)).solids()[0].wrapped  # a void inside: 2 shells
    with pytest.raises(FabricationError, match="has 2 shells in solid 1, not 1; nothing was written"):
        step.check_solids([hollow], volume=1000 - 64, parts=1)
    cube = Box(10, 10, 10).solids()[0].wrapped
    assert step.check_solids([cube], volume=1000, parts=1) == pytest.approx(1000)
    with pytest.raises(FabricationError, match=r"has a solid of volume -1000 mm\^3 \(solid 1\): inside out"):
        step.check_solids([TopoDS.Solid(cube.Reversed())], volume=1000, parts=1)


@settings(max_examples=examples(60), deadline=None)
@given(
    st.lists(st.tuples(*[st.floats(-3000, 3000, allow_subnormal=False)] * 3), min_size=1, max_size=100),
    st.sampled_from([9, 12]),
    st.integers(0, 100),
)
def test_the_rows_formatted_at_once_are_each_number_as_real_writes_it(rows, decimals, repeats):
    """The writer formats points and directions an array at a time (each distinct row once, past 64
    rows); each number must read as the one STEP REAL that _real gives it (a point shared by text is
    then the same point), and as its value."""
    import numpy as np

    from fabtiles.export.step_file import _real, _rows

    rows = rows + rows[:repeats]  # rows again, as a wall's top and bottom edges share a direction

    got = _rows(rows, decimals)
    assert got == ["(" + ",".join(_real(x, decimals) for x in row) + ")" for row in rows]
    back = np.array([[float(t.replace("E", "e")) for t in text[1:-1].split(",")] for text in got])
    given = np.array(rows)  # within half the last decimal, and the doubles' own spacing
    assert (np.abs(back - given) <= 0.5 * 10.0**-decimals + 4 * np.spacing(np.abs(given))).all()
    assert all("." in t for text in got for t in text[1:-1].split(","))  # every number a REAL


def test_the_file_writes_each_point_direction_and_placement_once(tmp_path):
    """Entities shared, not repeated: a vertex's point is its wall's plane origin and its line's start."""
    plate = box(0, 0, 30, 30).difference(shapely.Point(15, 15).buffer(4.0, quad_segs=64))
    path = tmp_path / "p.step"
    write_print(path, region=plate, outline=box(0, 0, 30, 30), profile="fdm-0.4mm", style="pierced")
    lines = path.read_text().splitlines()
    for kind in ("CARTESIAN_POINT(", "DIRECTION(", "AXIS2_PLACEMENT_3D(", "VECTOR("):
        bodies = [line.split("=", 1)[1] for line in lines if kind in line]
        assert bodies and len(bodies) == len(set(bodies)), kind
