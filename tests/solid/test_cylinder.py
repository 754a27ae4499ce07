"""A flat print of the unrolled strip wrapped onto a cylinder, checked independently.

The STL is read back by trimesh and admesh and the 3MF by PrusaSlicer (the slicers slice a
roller and a shade built from design files in tests/making/test_cylinder_build.py); the
cylinder's sizes, its cross-section at mid-height against the flat strip's pattern on the
line y = L/2 (shapely), the seam, a mirrored strip and the volume against the prisms'
analytic volume.
"""

from __future__ import annotations

import functools
import io
import math
import re

import numpy as np
import pytest
import shapely
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from real_programs import program, run
from shapely import affinity

from fabtiles import FabricationError, ParameterError, Star
from fabtiles.export.formats import FORMATS, FileOptions
from fabtiles.export.threemf import read_3mf
from fabtiles.geometry.machine_geometry import print_geometry
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking
from fabtiles.solid.cylinder import (
    CHORD_MM,
    CylinderPrint,
    LampHolder,
    cylinder_print,
    glue_seam,
    slice_x,
    with_holder,
    wrap_part,
)
from fabtiles.solid.mesh_check import check_indexed
from fabtiles.solid.print_model import print_model

ROLLER = dict(diameter=30.0, length=20.0, periods=6)
SHADE = dict(diameter=40.0, length=24.0, periods=8)
RIM_MM = 3.0
SHIFT = 0.3
"""The roller's pattern moved round by this many periods: mirrored, it is another pattern."""
HOLDER = LampHolder(fitting_mm=16, ring_mm=3, spokes=3, thickness_mm=1.6)


def strip(diameter, length, periods, *, mirror=False, rims=False, shift=0.0):
    """The unrolled strip ``C x L`` of a hex pattern, ``periods`` packing periods round, moved round by
    ``shift`` periods (the pattern is its own mirror about its lattice points): region, outline, C."""
    c = math.pi * diameter
    tile = TileGeometry(
        "rectangle", (c, length), HexPacking(radius=c / (2 * periods), motif=Star.preset("table3-2")), stroke=1.0
    )
    region, outline = tile.region(), tile.outline_shape()
    if shift:
        dx = shift * c / periods
        twice = shapely.union(region, affinity.translate(region, c, 0))
        region = affinity.translate(twice, -dx, 0).intersection(outline)
    if mirror:
        region = affinity.scale(region, -1, 1, origin=(c / 2, 0))
    if rims:
        bands = [shapely.box(0, 0, c, RIM_MM), shapely.box(0, length - RIM_MM, c, length)]
        region = shapely.union_all([region, *bands]).intersection(outline)
    return region, outline, c


def wrapped(sizes, style, *, mirror=False, rims=False, holder=None, shift=0.0):
    region, outline, c = strip(**sizes, mirror=mirror, rims=rims, shift=shift)
    model = print_model(region, outline, profile="fdm-0.4mm", style=style)
    return cylinder_print(model, circumference_mm=c, outer_radius_mm=sizes["diameter"] / 2, holder=holder)


def read_stl(data: bytes) -> trimesh.Trimesh:
    return trimesh.load(io.BytesIO(data), file_type="stl")  # merged by position, as a slicer reads it


@pytest.fixture(scope="module")
def roller():
    cp = wrapped(ROLLER, "relief", shift=SHIFT)
    return cp, FORMATS["stl"].write(cp, FileOptions())


@pytest.fixture(scope="module")
def mirrored_roller():
    return wrapped(ROLLER, "relief", mirror=True, shift=SHIFT)


@pytest.fixture(scope="module")
def shade():
    cp = wrapped(SHADE, "pierced", rims=True, holder=HOLDER)
    return cp, FORMATS["stl"].write(cp, FileOptions())


def radii(mesh, outer):
    v = np.asarray(mesh.vertices)
    return np.hypot(v[:, 0] - outer, v[:, 1] - outer)


def section(mesh, z):
    """The mesh cut at height ``z``: a shapely (Multi)Polygon in the XY plane."""
    path = mesh.section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1])
    loops = [shapely.Polygon(d[:, :2]) for d in path.discrete]
    return functools.reduce(shapely.symmetric_difference, loops)


def angular_profile(sec, outer, r_lo, r_hi, n=1440):
    """Whether each of ``n`` radial segments ``r_lo .. r_hi`` (angles 0 .. 2 pi) meets material of ``sec``."""
    theta = (np.arange(n) + 0.5) * 2 * math.pi / n
    c, s = np.cos(theta), np.sin(theta)
    rays = shapely.linestrings(
        np.stack(
            [
                np.column_stack([outer + r_lo * c, outer + r_lo * s]),
                np.column_stack([outer + r_hi * c, outer + r_hi * s]),
            ],
            axis=1,
        )
    )
    return shapely.length(shapely.intersection(rays, sec)) > 1e-6


def flat_profile(region, c, y, n=1440):
    """The same of the flat strip on the line ``y``: ``x`` in the middle of each of ``n`` steps covered."""
    xs = (np.arange(n) + 0.5) * c / n
    return shapely.contains_xy(region, xs, np.full(n, y))


# --------------------------------------------------------------------------- the roller


def test_the_roller_reads_back_watertight_one_body_wound_outwards(roller):
    cp, data = roller
    mesh = read_stl(data)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert len(mesh.split(only_watertight=False)) == 1
    assert mesh.volume > 0
    assert mesh.volume == pytest.approx(cp.fused.mesh_volume_mm3, rel=1e-6)


def test_the_roller_has_the_outer_radius_the_bore_and_the_length(roller):
    cp, data = roller
    mesh = read_stl(data)
    outer, top = ROLLER["diameter"] / 2, cp.top_mm
    r = radii(mesh, outer)
    assert r.max() == pytest.approx(outer, abs=1e-5)
    assert r.min() == pytest.approx(outer - top, abs=1e-5)
    assert mesh.bounds[:, 2].tolist() == pytest.approx([0, ROLLER["length"]], abs=1e-6)
    assert mesh.bounds[0, :2].tolist() == pytest.approx([0, 0], abs=CHORD_MM)
    assert mesh.bounds[0, :2].min() >= 0
    # every edge on the outer surface or the bore: its middle within the chord tolerance of the circle
    e = mesh.edges_unique
    v = np.asarray(mesh.vertices)
    for radius in (outer, outer - top):
        on = np.abs(r - radius) < 1e-4
        both = on[e].all(axis=1)
        mid = v[e[both]].mean(axis=1)
        assert np.count_nonzero(both) > 100
        assert radius - np.hypot(mid[:, 0] - outer, mid[:, 1] - outer).max() < 1e-4
        assert radius - np.hypot(mid[:, 0] - outer, mid[:, 1] - outer).min() <= CHORD_MM * 1.001


def test_the_rollers_raised_fraction_at_mid_height_is_the_strips(roller):
    cp, data = roller
    outer, relief = ROLLER["diameter"] / 2, cp.stack.relief
    sec = section(read_stl(data), ROLLER["length"] / 2)
    ring = (
        shapely.Point(outer, outer).buffer(outer + 1).difference(shapely.Point(outer, outer).buffer(outer - relief / 2))
    )
    raised = shapely.intersection(sec, ring).area / (math.pi * (outer**2 - (outer - relief / 2) ** 2))
    line = shapely.LineString([(0, ROLLER["length"] / 2), (cp.circumference_mm, ROLLER["length"] / 2)])
    flat = shapely.intersection(cp.region, line).length / cp.circumference_mm
    assert 0.1 < flat < 0.9
    assert raised == pytest.approx(flat, abs=0.005)


def test_the_rollers_profile_is_the_strips_and_meets_itself_at_the_seam(roller):
    cp, data = roller
    outer, relief, y = ROLLER["diameter"] / 2, cp.stack.relief, ROLLER["length"] / 2
    sec = section(read_stl(data), y)
    # one ring round the bore: nothing is cut at theta = 0
    assert sec.geom_type == "Polygon" and len(sec.interiors) == 1
    profile = angular_profile(sec, outer, outer - relief / 2, outer + 1)
    flat = flat_profile(cp.region, cp.circumference_mm, y)
    assert np.mean(profile == flat) > 0.98
    # the first and last steps, either side of the seam, are the strip's
    assert profile[[0, -1]].tolist() == flat[[0, -1]].tolist()


def test_a_mirrored_strip_gives_the_reversed_profile(roller, mirrored_roller):
    cp, data = roller
    outer, relief, y = ROLLER["diameter"] / 2, cp.stack.relief, ROLLER["length"] / 2
    plain = angular_profile(section(read_stl(data), y), outer, outer - relief / 2, outer + 1)
    mirror_mesh = read_stl(FORMATS["stl"].write(mirrored_roller, FileOptions()))
    mirrored = angular_profile(section(mirror_mesh, y), outer, outer - relief / 2, outer + 1)
    assert np.mean(mirrored == plain[::-1]) > 0.98
    assert np.mean(mirrored == plain) < 0.9  # the pattern is not its own mirror here


def test_the_rollers_volume_is_the_prisms_wrapped(roller):
    cp, _ = roller
    outer, b, h = ROLLER["diameter"] / 2, cp.stack.base, cp.stack.relief
    r0 = outer - b - h
    # a prism of area A from radius r0 to r1 wrapped onto C: A (r1^2 - r0^2) pi / C
    exact = (
        math.pi
        / cp.circumference_mm
        * (cp.outline.area * ((r0 + b) ** 2 - r0**2) + cp.region.area * (outer**2 - (r0 + b) ** 2))
    )
    assert cp.fused.volume_mm3 == pytest.approx(exact, rel=1e-3)
    assert cp.fused.mesh_volume_mm3 == pytest.approx(exact, rel=2e-3)
    assert cp.fused.mesh_volume_mm3 < cp.fused.volume_mm3  # chords cut inside the circles


def test_the_rollers_3mf_holds_its_base_and_pattern_each_watertight(roller, tmp_path):
    cp, _ = roller
    path = tmp_path / "roller.3mf"
    path.write_bytes(FORMATS["3mf"].write(cp, FileOptions()))
    parts = read_3mf(str(path))
    assert list(parts) == ["base", "pattern"]
    volume = 0.0
    for p in parts.values():
        mesh = trimesh.Trimesh(p.vertices.astype(np.float64), p.faces)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
        volume += mesh.volume
    assert volume == pytest.approx(cp.fused.mesh_volume_mm3, rel=2e-3)


def test_the_glb_and_the_figures_read_the_wrapped_parts(roller):
    cp, _ = roller
    assert FORMATS["glb"].write(cp, FileOptions())[:4] == b"glTF"
    figures = FORMATS["stl"].figures(cp, FileOptions())
    assert figures["surface"]["diameter_mm"] == ROLLER["diameter"]
    assert figures["surface"]["length_mm"] == pytest.approx(ROLLER["length"])
    assert figures["surface"]["inner_diameter_mm"] == pytest.approx(2 * cp.inner_radius_mm)
    assert figures["volume_mm3"] == pytest.approx(cp.fused.mesh_volume_mm3)


def test_a_cylinders_step_is_refused_in_one_line(roller):
    cp, _ = roller
    with pytest.raises(FabricationError, match=r"^a cylinder's STEP is not made: [^\n]+; write STL or 3MF$"):
        FORMATS["step"].write(cp, FileOptions())


def test_deboss_and_mosaic_wrap_to_watertight_bodies():
    for style in ("deboss", "mosaic"):
        cp = wrapped(dict(diameter=24.0, length=12.0, periods=5), style)
        for p in cp.parts.values():
            mesh = trimesh.Trimesh(p.mesh.vertices, p.mesh.faces)
            assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
        assert len(read_stl(FORMATS["stl"].write(cp, FileOptions())).split(only_watertight=False)) == 1


@settings(max_examples=examples(10), deadline=None)
@given(
    c=st.floats(20, 100),
    length=st.floats(1, 20),
    top=st.floats(0.5, 5),
    inside=st.floats(0.5, 30),
)
def test_a_plain_strip_wraps_to_the_tube_of_its_sizes(c, length, top, inside):
    box = shapely.box(0, 0, c, length)
    model = print_model(box, box, profile="fdm-0.4mm", style="pierced", pierced_mm=top)
    outer = top + inside
    part = wrap_part(model.fused, circumference_mm=c, outer_radius_mm=outer, top_mm=top)
    _, y0, _, y1 = model.fused.outline.bounds  # as meshed: on the grid
    tube = math.pi * (outer**2 - inside**2) * (y1 - y0)
    assert part.volume_mm3 == pytest.approx(tube, rel=1e-6)  # the flat mesh's corners are float32
    assert part.mesh_volume_mm3 == pytest.approx(tube, rel=1e-3) and part.mesh_volume_mm3 < tube
    mesh = trimesh.Trimesh(part.vertices, part.faces)
    assert mesh.is_watertight and mesh.is_winding_consistent and part.bodies == 1
    r = radii(mesh, outer)
    assert r.max() == pytest.approx(outer, abs=1e-5) and r.min() == pytest.approx(inside, abs=1e-5)


@settings(max_examples=examples(25), deadline=None)
@given(
    rotation=st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=3),
    cuts=st.lists(st.floats(0.01, 0.99), min_size=1, max_size=12, unique=True),
)
def test_slicing_keeps_a_closed_mesh_closed_and_cuts_every_edge_at_the_planes(rotation, cuts):
    box = trimesh.creation.box(extents=(3, 2, 1))
    box.apply_transform(trimesh.transformations.euler_matrix(*rotation))
    v, f = np.asarray(box.vertices), np.asarray(box.faces)
    lo, hi = v[:, 0].min(), v[:, 0].max()
    planes = np.sort(lo + (hi - lo) * np.asarray(cuts))
    if np.abs(v[:, 0][:, None] - planes[None, :]).min() < 1e-3 or np.diff(planes).min(initial=1) < 1e-3:
        return  # a plane through a corner, or two planes as one: not what slice_x is given
    sv, sf = slice_x(v, f, planes)
    check_indexed(sv, sf, name="sliced box", volume=6.0, bodies=1)
    x = sv[:, 0][sf]
    inside = (x.min(axis=1)[:, None] < planes - 1e-9) & (planes + 1e-9 < x.max(axis=1)[:, None])
    assert not inside.any()  # no triangle crosses a plane


def test_an_interlaced_roller_wraps_with_its_dips():
    sizes = dict(diameter=24.0, length=10.0, periods=4)
    c = math.pi * sizes["diameter"]
    pack = HexPacking(radius=c / (2 * sizes["periods"]), motif=Star.preset("table3-2"))
    tile = TileGeometry("rectangle", (c, sizes["length"]), pack, stroke=1.2, interlace=True)
    region, dips = print_geometry(tile, profile="fdm-0.4mm", style="relief")
    assert dips is not None and not dips.is_empty
    model = print_model(region, tile.outline_shape(), profile="fdm-0.4mm", style="relief", dips=dips)
    cp = cylinder_print(model, circumference_mm=c, outer_radius_mm=sizes["diameter"] / 2)
    mesh = read_stl(FORMATS["stl"].write(cp, FileOptions()))
    assert mesh.is_watertight and mesh.is_winding_consistent and len(mesh.split(only_watertight=False)) == 1
    # the dips lower the strands: less than the plain relief of the same region
    plain = (
        math.pi
        / c
        * (
            cp.outline.area * ((cp.inner_radius_mm + cp.stack.base) ** 2 - cp.inner_radius_mm**2)
            + cp.region.area * (cp.outer_radius_mm**2 - (cp.inner_radius_mm + cp.stack.base) ** 2)
        )
    )
    assert mesh.volume < plain - 1


# --------------------------------------------------------------------------- the lampshade


def test_the_shade_with_its_holder_is_one_watertight_body(shade):
    cp, data = shade
    mesh = read_stl(data)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert len(mesh.split(only_watertight=False)) == 1
    outer = SHADE["diameter"] / 2
    assert radii(mesh, outer).max() == pytest.approx(outer, abs=1e-5)
    assert mesh.bounds[:, 2].tolist() == pytest.approx([0, SHADE["length"]], abs=1e-6)
    assert list(cp.parts) == ["pattern"] and cp.parts["pattern"].mesh is cp.fused


def test_the_shades_open_fraction_at_mid_height_is_the_strips(shade):
    cp, data = shade
    outer, y = SHADE["diameter"] / 2, SHADE["length"] / 2
    inner = cp.inner_radius_mm
    sec = section(read_stl(data), y)
    disc = shapely.Point(outer, outer)
    wall = math.pi * (outer**2 - inner**2)
    open_3d = 1 - shapely.intersection(sec, disc.buffer(outer + 1)).area / wall
    line = shapely.LineString([(0, y), (cp.circumference_mm, y)])
    open_flat = 1 - shapely.intersection(cp.region, line).length / cp.circumference_mm
    assert 0.1 < open_flat < 0.9
    assert open_3d == pytest.approx(open_flat, abs=0.005)
    profile = angular_profile(sec, outer, inner - 0.5, outer + 0.5)
    assert np.mean(profile == flat_profile(cp.region, cp.circumference_mm, y)) > 0.98


def test_the_holder_lies_on_the_bed_and_reaches_into_the_wall(shade):
    cp, data = shade
    outer = SHADE["diameter"] / 2
    sec = section(read_stl(data), HOLDER.thickness_mm / 2)
    inside = sec.intersection(shapely.Point(outer, outer).buffer(cp.inner_radius_mm - 0.01))
    ring = math.pi * ((HOLDER.fitting_mm / 2 + HOLDER.ring_mm) ** 2 - (HOLDER.fitting_mm / 2) ** 2)
    spoke = HOLDER.ring_mm * (cp.inner_radius_mm - HOLDER.fitting_mm / 2 - HOLDER.ring_mm)
    assert inside.area == pytest.approx(ring + HOLDER.spokes * spoke, rel=0.03)
    # the fitting's hole is open
    assert not sec.intersects(shapely.Point(outer, outer).buffer(HOLDER.fitting_mm / 2 - 0.01))
    # above the holder, only the shade's rim
    above = section(read_stl(data), HOLDER.thickness_mm + 0.5)
    assert not above.intersects(shapely.Point(outer, outer).buffer(cp.inner_radius_mm - 0.01))


# --------------------------------------------------------------------------- the programs


@pytest.fixture(scope="module")
def stl_files(roller, shade, tmp_path_factory):
    folder = tmp_path_factory.mktemp("cylinders")
    out = {}
    for name, (_, data) in (("roller", roller), ("shade", shade)):
        out[name] = folder / f"{name}.stl"
        out[name].write_bytes(data)
    return out


def test_admesh_finds_nothing_to_fix(stl_files):
    admesh = program("admesh", "apt-get install admesh")
    for path in stl_files.values():
        text = run([admesh, path], timeout=120).stdout
        figures = {k.strip(): v for k, v in re.findall(r"^([A-Za-z ]+?)\s*:\s*(\d+)\s*$", text, flags=re.M)}
        assert int(re.search(r"Number of parts\s*:\s*(\d+)", text).group(1)) == 1
        for key in ("Degenerate facets", "Edges fixed", "Facets removed", "Facets added", "Facets reversed",
                    "Backwards edges", "Normals fixed"):  # fmt: skip
            assert figures[key] == "0", (path.name, key, figures[key])
        assert int(re.search(r"Total disconnected facets\s*:\s*(\d+)", text).group(1)) == 0


def test_prusaslicer_reads_the_rollers_3mf_as_one_closed_object_of_two_parts(roller, tmp_path):
    prusa = program("prusa-slicer", "apt-get install prusa-slicer")
    cp, _ = roller
    path = tmp_path / "roller.3mf"
    path.write_bytes(FORMATS["3mf"].write(cp, FileOptions()))
    text = run([prusa, "--loglevel", "1", "--datadir", tmp_path / "data", "--info", path], cwd=tmp_path).stdout
    found = dict(re.findall(r"^(\w+) = +(\S+)$", text, flags=re.M))
    assert found["manifold"] == "yes" and int(found["number_of_parts"]) == 2
    assert float(found["size_x"]) == pytest.approx(ROLLER["diameter"], abs=CHORD_MM)
    assert float(found["size_z"]) == pytest.approx(ROLLER["length"], abs=1e-5)
    parts = sum(p.mesh.mesh_volume_mm3 for p in cp.parts.values())
    assert float(found["volume"]) == pytest.approx(parts, rel=1e-5)


# --------------------------------------------------------------------------- bad input


@pytest.fixture(scope="module")
def small():
    """A small relief strip's flat model and fused part, with its circumference."""
    region, outline, c = strip(diameter=20.0, length=8.0, periods=4)
    model = print_model(region, outline, profile="fdm-0.4mm", style="relief")
    return model, c


def test_wrap_part_refuses_sizes_that_do_not_fit_the_strip(small):
    model, c = small
    part = model.fused
    with pytest.raises(ParameterError, match=r"circumference_mm = 63 mm must be the strip's width, 62\.83"):
        wrap_part(part, circumference_mm=63, outer_radius_mm=10, top_mm=3.2)
    with pytest.raises(ParameterError, match=r"top_mm = 10 mm must be less than outer_radius_mm = 10 mm"):
        wrap_part(part, circumference_mm=c, outer_radius_mm=10, top_mm=10)
    with pytest.raises(ParameterError, match=r"top_mm = 2 mm is below the part's highest point, 3.2 mm"):
        wrap_part(part, circumference_mm=c, outer_radius_mm=10, top_mm=2)


def test_a_strip_whose_edges_do_not_meet_is_refused(small):
    model, c = small
    one_side = print_model(shapely.box(0, 2, 5, 6), model.outline, profile="fdm-0.4mm", style="relief")
    with pytest.raises(FabricationError, match=r"edges x = 0 and x = 62\.83\d* of the strip do not meet: \d+ vertices"):
        wrap_part(one_side.fused, circumference_mm=c, outer_radius_mm=10, top_mm=3.2)


@pytest.mark.parametrize("steps", [1, 2])
def test_a_crossing_a_grid_step_or_two_apart_on_the_two_edges_is_glued(small, steps):
    model, c = small
    q = 2.0**-10
    x1 = model.fused.outline.bounds[2]
    band = shapely.union(shapely.box(0, 2, 5, 4), shapely.box(x1 - 5, 2 + steps * q, x1, 4))
    one_band = print_model(band, model.outline, profile="fdm-0.4mm", style="relief")
    part = wrap_part(one_band.fused, circumference_mm=c, outer_radius_mm=10, top_mm=3.2)
    mesh = trimesh.Trimesh(part.vertices, part.faces)
    assert mesh.is_watertight and mesh.is_winding_consistent and part.bodies == 1


def test_a_crossing_further_apart_is_not_glued(small):
    model, c = small
    x1 = model.fused.outline.bounds[2]
    band = shapely.union(shapely.box(0, 2, 5, 4), shapely.box(x1 - 5, 2.005, x1, 4))
    one_band = print_model(band, model.outline, profile="fdm-0.4mm", style="relief")
    with pytest.raises(FabricationError, match=r"do not meet: 2 vertices have no twin"):
        wrap_part(one_band.fused, circumference_mm=c, outer_radius_mm=10, top_mm=3.2)


def test_a_part_with_other_bodies_than_it_says_is_refused(small):
    model, c = small
    with pytest.raises(FabricationError, match=r"cut for wrapping has 1 bodies where the flat part has 2"):
        wrap_part(model.fused._replace(bodies=2), circumference_mm=c, outer_radius_mm=10, top_mm=3.2)


def test_glue_seam_is_the_identity_on_a_mesh_off_the_seam():
    v = np.array([[1.0, 0, 0], [2, 0, 0], [1, 1, 0], [1, 0, 1]])
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    _, gf, twins = glue_seam(v, f, 0.0, 3.0)
    assert gf.tolist() == f.tolist() and twins.shape == (0, 2)


def test_cylinder_print_refuses_bad_sizes_and_holders(small):
    model, c = small
    with pytest.raises(ParameterError, match=r"circumference_mm = 60 mm must be the strip's width"):
        cylinder_print(model, circumference_mm=60, outer_radius_mm=10)
    with pytest.raises(ParameterError, match=r"outer_radius_mm = 3 mm must be more than the print's height, 3.2 mm"):
        cylinder_print(model, circumference_mm=c, outer_radius_mm=3)
    with pytest.raises(ParameterError, match=r"holder must be a LampHolder or None, got 40"):
        cylinder_print(model, circumference_mm=c, outer_radius_mm=10, holder=40)
    with pytest.raises(
        ParameterError,
        match=r"fitting_mm = 10 mm with ring_mm = 5 mm is too wide for the shade: .* inside diameter, 13.6 mm",
    ):
        cylinder_print(model, circumference_mm=c, outer_radius_mm=10, holder=LampHolder(fitting_mm=10))
    assert isinstance(cylinder_print(model, circumference_mm=c, outer_radius_mm=10), CylinderPrint)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        (dict(fitting_mm=0), r"fitting_mm must be a finite number > 0, got 0"),
        (dict(fitting_mm=30, ring_mm=-1), r"ring_mm must be a finite number > 0, got -1"),
        (dict(fitting_mm=30, spokes=25), r"spokes must be an integer >= 2 and <= 24, got 25"),
        (dict(fitting_mm=30, thickness_mm=float("nan")), r"thickness_mm must be a finite number > 0, got nan"),
    ],
)
def test_a_lamp_holder_out_of_range_is_refused(kwargs, message):
    with pytest.raises(ParameterError, match=message):
        LampHolder(**kwargs)


def test_a_holder_thicker_than_the_shade_is_long_is_refused(small):
    model, c = small
    part = wrap_part(model.fused, circumference_mm=c, outer_radius_mm=30, top_mm=3.2)
    with pytest.raises(ParameterError, match=r"thickness_mm = 9 mm of the lamp holder must be less than the shade's"):
        with_holder(
            part, LampHolder(fitting_mm=10, thickness_mm=9), outer_radius_mm=30, inner_radius_mm=26.8, wall_mm=2
        )


def test_an_open_mesh_is_not_fused_with_a_holder(small):
    model, _ = small
    part = model.fused._replace(faces=model.fused.faces[:-1])
    with pytest.raises(FabricationError, match=r"the part mesh could not be read by manifold3d"):
        with_holder(part, LampHolder(fitting_mm=10), outer_radius_mm=30, inner_radius_mm=26.8, wall_mm=2)


def test_a_wall_that_falls_apart_is_refused():
    c = 40.0
    outline = shapely.box(0, 0, c, 10)
    wall = shapely.union(shapely.box(0, 0, c, 3), shapely.box(10, 5, 14, 8))  # a square not joined to the band
    model = print_model(wall, outline, profile="fdm-0.4mm", style="pierced")
    cp = cylinder_print(model, circumference_mm=c, outer_radius_mm=c / (2 * math.pi))
    with pytest.raises(
        FabricationError, match=r"wrapped pattern falls apart into 2 bodies: 1 piece of material not joined"
    ):
        _ = cp.fused
