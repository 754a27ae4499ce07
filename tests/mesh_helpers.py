"""Checks shared by the 3D export tests: STL, 3MF (trimesh, manifold3d) and STEP (OCP).

Heights are those of the ``fdm-0.4mm`` printer profile unless given.
"""

from __future__ import annotations

import numpy as np
import pytest

B, H, T, D = 2.0, 1.2, 3.0, 0.8
"""Base, relief, pierced and deboss heights of ``fdm-0.4mm`` (mm)."""

STYLES = ("relief", "pierced", "deboss")

GRID = 2.0**-10
"""The grid the meshes' vertices lie on (mm)."""

TOLERANCE = 0.02
"""The printer profiles' ``tolerance_mm``: the print region's holes are simplified within it."""

VOLUME_REL = 2e-3
"""Volume allowed off the region's area times the heights, relative. The holes' rings simplified
within :data:`TOLERANCE` move the volume: measured 1.35e-3 on the 150 mm seamless-hexagon sample
pierced (1,381 holes), 4.6e-4 on the 40 mm test tiles, 1e-5 to 1e-4 on most samples. A hole
filled or missing shows in the sections (:func:`assert_section`), not here."""

SECTION_AREA_REL = 4e-3
"""Symmetric difference allowed between a mid-height section and its region, relative to the
region's area (measured at most 2.3e-3, the seamless-hexagon sample's 1,381 simplified holes)."""

SECTION_WIDTH = TOLERANCE + 2 * GRID
"""Widest difference allowed between a mid-height section and its region (mm): the simplification's
tolerance and the grid (measured at most 0.01997 mm, over every mesh test)."""


def expected_volume(style, region, outline, b=B, h=H, t=T, d=D):
    """Volume of a printed part from the areas of the region and the outline (mm^3).

    Parameters
    ----------
    style : {"relief", "pierced", "deboss"}
    region, outline : shapely geometry
        The material region and the tile outline.
    b, h, t, d : float, optional
        Base, relief, pierced and deboss heights (mm).
    """
    return {
        "relief": outline.area * b + region.area * h,
        "pierced": region.area * t,
        "deboss": outline.area * b - region.area * d,
    }[style]


def top(style, b=B, h=H, t=T):
    """Height of the top of a part of ``style`` (mm)."""
    return {"relief": b + h, "pierced": t, "deboss": b}[style]


def load_stl(path):
    """An STL read by trimesh, vertices merged by position as a slicer does."""
    import trimesh

    return trimesh.load(path, file_type="stl")


def assert_relief_stl(tile, path, profile: str = "fdm-0.4mm"):
    """Export ``tile`` as a relief STL to ``path`` (small holes kept) and assert it is one solid of the
    region's volume within the tile (:func:`assert_solid`); returns the mesh. ``profile`` must have the
    ``fdm-0.4mm`` heights (:data:`B`, :data:`H`)."""
    tile.export(path, profile=profile, style="relief", fill_small_holes=False)
    mesh = load_stl(path)
    volume = expected_volume("relief", tile.region(), tile.outline_shape())
    assert_solid(mesh, volume, (0, 0, tile.width_mm, tile.height_mm), top("relief"))
    return mesh


def assert_solid(m, volume, bounds_xy, zmax, bodies=1, zmin=0.0):
    """Assert that a trimesh body is watertight, wound consistently, of the right volume and size.

    Parameters
    ----------
    m : trimesh.Trimesh
    volume : float
        Expected volume; :data:`VOLUME_REL` allowed.
    bounds_xy : tuple of 4 floats
        ``(xmin, ymin, xmax, ymax)`` the mesh must lie within (1 micron allowed).
    zmax, zmin : float
        Expected top and bottom heights.
    bodies : int
        Expected number of connected bodies.
    """
    assert m.is_watertight
    assert m.is_winding_consistent
    assert m.volume > 0
    assert m.volume == pytest.approx(volume, rel=VOLUME_REL)
    assert m.body_count == bodies
    lo, hi = m.bounds
    assert lo[0] >= bounds_xy[0] - 1e-3 and lo[1] >= bounds_xy[1] - 1e-3
    assert hi[0] <= bounds_xy[2] + 1e-3 and hi[1] <= bounds_xy[3] + 1e-3
    assert lo[2] == pytest.approx(zmin, abs=1e-5)
    assert hi[2] == pytest.approx(zmax, abs=1e-5)


def manifold_of(m):
    """A trimesh body as a manifold3d Manifold (for boolean checks)."""
    import manifold3d as m3

    return m3.Manifold(
        m3.Mesh(vert_properties=np.asarray(m.vertices, np.float32), tri_verts=np.asarray(m.faces, np.uint32))
    )


def assert_touch_without_overlap(base, pattern):
    """Assert that two bodies overlap by no volume (they may share faces)."""
    a, b = manifold_of(base), manifold_of(pattern)  # each made once, for both operations
    overlap = (a ^ b).volume()
    assert overlap == pytest.approx(0.0, abs=1e-6 * base.volume)
    union = (a + b).volume()
    assert union == pytest.approx(base.volume + pattern.volume, rel=1e-6)


def solids_of(shape):
    """Number of solids in an OCP shape."""
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    n, exp = 0, TopExp_Explorer(shape, TopAbs_SOLID)
    while exp.More():
        n += 1
        exp.Next()
    return n


def occt_volume(shape) -> float:
    """OCCT's volume of a shape (``BRepGProp``, default integration: what FreeCAD shows)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


def step_bounds(shape):
    """``(xmin, ymin, zmin, xmax, ymax, zmax)`` of an OCP shape, without OCCT's gap."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    bb = Bnd_Box()
    BRepBndLib.Add_s(shape, bb)
    bb.SetGap(0.0)
    lo, hi = bb.CornerMin(), bb.CornerMax()
    return lo.X(), lo.Y(), lo.Z(), hi.X(), hi.Y(), hi.Z()


def assert_step_solid(shape, volume, bounds_xy, zmax, solids=1):
    """Assert that a STEP shape read back is valid and closed, with the right solids, volume and size.

    The volume is OCCT's own (:func:`occt_volume`, what CAD programs report).
    """
    from OCP.BRep import BRep_Tool
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    assert solids_of(shape) == solids
    assert BRepCheck_Analyzer(shape).IsValid()
    exp = TopExp_Explorer(shape, TopAbs_SHELL)
    while exp.More():
        assert BRep_Tool.IsClosed_s(TopoDS.Shell(exp.Current()))
        exp.Next()
    assert occt_volume(shape) == pytest.approx(volume, rel=VOLUME_REL)
    x0, y0, z0, x1, y1, z1 = step_bounds(shape)
    assert z0 == pytest.approx(0, abs=1e-3) and z1 == pytest.approx(zmax, abs=1e-3)
    assert x0 >= bounds_xy[0] - 1e-3 and y0 >= bounds_xy[1] - 1e-3
    assert x1 <= bounds_xy[2] + 1e-3 and y1 <= bounds_xy[3] + 1e-3


def load_3mf_parts(path):
    """The parts of a fabtiles 3MF as trimesh bodies, split as PrusaSlicer splits them.

    Each part's vertices are merged by position within the part only (slicers keep
    parts apart: a part's face may lie on another's).
    """
    import trimesh

    from fabtiles.export.threemf import read_3mf

    return {
        name: trimesh.Trimesh(vertices=p.vertices.astype(np.float64), faces=p.faces, process=True)
        for name, p in read_3mf(path).items()
    }


def section_region(mesh, z):
    """The cross-section of a trimesh body at height ``z`` as a shapely (Multi)Polygon (trimesh cuts,
    GEOS assembles the rings by nesting: a ring inside an odd number of others is a hole).

    trimesh's segments with their ends merged as ``Trimesh.section`` merges them, handed to GEOS as
    segments: ``section`` chains them into paths one connected piece at a time, each piece a search
    of the whole graph (seconds for a tile's thousands of holes), and GEOS finds the rings anyway.
    """
    import shapely
    from trimesh import grouping, intersections
    from trimesh.constants import tol_path

    lines = intersections.mesh_plane(mesh, plane_normal=[0, 0, 1], plane_origin=[0, 0, z])
    if not len(lines):
        return shapely.Polygon()
    points = np.asarray(lines, dtype=np.float64).reshape(-1, 3)
    unique, inverse = grouping.unique_rows(points, digits=tol_path.merge_digits)
    edges = np.sort(inverse.reshape(-1, 2), axis=1)
    edges = np.unique(edges[edges[:, 0] != edges[:, 1]], axis=0)
    segments = shapely.linestrings(points[unique][:, :2][edges])
    return shapely.build_area(shapely.multilinestrings(segments))


def mid_heights(style, b=B, h=H, t=T, d=D):
    """The height in the middle of the layers where a style's openings are (mm): a relief's raised
    pattern, a pierced tile, a deboss's grooves."""
    return {"relief": b + h / 2, "pierced": t / 2, "deboss": b - d / 2}[style]


def widths(polygons):
    """Each polygon's width: the diameter of the largest disc inside it (GEOS, within 0.1 micron)."""
    import shapely

    polygons = np.asarray(polygons, dtype=object)
    if not len(polygons):
        return np.zeros(0)
    return 2 * shapely.length(shapely.maximum_inscribed_circle(polygons, 1e-4))


def section_difference(mesh, z, expected):
    """The symmetric difference between the mesh's section at ``z`` and the ``expected`` region."""
    import shapely

    return shapely.symmetric_difference(section_region(mesh, z), expected)


def assert_section(mesh, z, expected, *, area=SECTION_AREA_REL, width=SECTION_WIDTH):
    """Assert that the mesh cut at height ``z`` is the ``expected`` shapely region: their symmetric
    difference under ``area`` of the region's area, and nowhere wider than ``width`` mm.

    The width of the difference is what tells a slip: a filled or missing hole, or a missing piece,
    is as wide as itself, a hole's ring simplified within the printer's tolerance only the sagitta
    of each chord. (A Hausdorff distance would count the slivers 0.0003 mm wide that a deboss's
    plate leaves along the outline, which the mesh's 2^-10 mm grid closes, by their length.)
    A piece is wider than ``width`` where it keeps anything once shrunk by half of it (GEOS's
    inward buffer: a second on the 150 mm seamless sample's 8,700 slivers, against minutes for
    each piece's largest inscribed disc). Each piece is shrunk on its own: the pieces of a valid
    region meet at points at most, so a disc inside their union is inside one of them, and GEOS
    buffers the pieces one by one faster than their union at once.
    """
    import shapely

    diff = section_difference(mesh, z, expected)
    rel = diff.area / expected.area
    assert rel <= area, f"the section at z = {z} differs from the region by {rel:.3g} of its area"
    pieces = shapely.get_parts(diff)
    wide = ~shapely.is_empty(shapely.buffer(pieces, -width / 2, quad_segs=2))
    if wide.any():
        pieces = pieces[wide]
        k = int(np.argmax(widths(pieces)))
        raise AssertionError(
            f"the section at z = {z} differs from the region by {widths(pieces)[k]:.4g} mm "
            f"around {pieces[k].representative_point().wkt}"
        )


def style_sections(style, region, outline, b=B, h=H, t=T, d=D):
    """``[(z, expected region), ...]``: the middle of each layer of a part of ``style`` and what its
    section there is (a relief's plate and raised pattern, a pierced tile, a deboss's plate under and
    between its grooves)."""
    return {
        "relief": [(b / 2, outline), (b + h / 2, region)],
        "pierced": [(t / 2, region)],
        "deboss": [((b - d) / 2, outline), (b - d / 2, outline.difference(region))],
    }[style]


def assert_style_sections(mesh, style, region, outline, b=B, h=H, t=T, d=D, **tolerances):
    """:func:`assert_section` at every height of :func:`style_sections`."""
    for z, expected in style_sections(style, region, outline, b, h, t, d):
        assert_section(mesh, z, expected, **tolerances)
