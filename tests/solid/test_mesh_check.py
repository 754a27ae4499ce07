"""The slicer-exact mesh check and the triangulation behind every 3D file (solid/mesh_check.py,
solid/_triangulate.py), against slow references.

``check_indexed`` merges a mesh from its vertices, ``check_triangles`` from an STL's
corners: both must see the same mesh and refuse the same defects. ``edges_pair_up``
and ``count_bodies`` are checked against plain Python and networkx, and the earcut
triangulation against its own guard (a bad triangulation falls back to manifold3d).
"""

from __future__ import annotations

import networkx as nx
import numpy as np
import pytest
import shapely
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely.geometry import box

from fabtiles import FabricationError
from fabtiles.export import stl
from fabtiles.solid import _mesh_build as mb
from fabtiles.solid import _triangulate as tr
from fabtiles.solid import mesh_check as sc


def corners32(v, f):
    return np.asarray(v, float)[np.asarray(f)].astype(np.float32)


@settings(max_examples=examples(60), deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(4, 40), st.integers(1, 60))
def test_merging_the_vertices_is_merging_the_corners(seed, n, m):
    rng = np.random.default_rng(seed)
    v = rng.choice([0.0, 1.0, 600.0, 600.00001, -0.0, 2.0**-10], size=(n, 3))  # float32 ties and -0.0
    v[: n // 2] += rng.integers(0, 3, size=(n // 2, 3))
    f = rng.integers(0, n, size=(m, 3))
    a = sc.merge_indexed32(v, f)
    b = sc._merge_float32(corners32(v, f))
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


def defects():
    cube = trimesh.creation.box()
    two = trimesh.util.concatenate([cube, cube.copy().apply_translation((5, 0, 0))])
    twice = np.concatenate([cube.faces, cube.faces[:1]])
    return [
        ("open", cube.vertices, cube.faces[:-1], {}, "not watertight as a slicer reads it.*3 open edges"),
        ("twice", cube.vertices, twice, {}, "edges wound the same way twice or shared by more than two faces"),
        ("inward", cube.vertices, cube.faces[:, ::-1], {}, "volume of -1 mm.3 .it must be positive"),
        ("volume", cube.vertices, cube.faces, {"volume": 2.0}, "not the 2 mm.3 of area x height"),
        ("bodies", two.vertices, two.faces, {"bodies": 1}, "2 separate bodies where 1 was expected"),
        (
            "flat",
            np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 0, 1.0]]),
            np.array([[0, 1, 2], [0, 1, 3]]),
            {},
            "zero-area faces in float32",
        ),
    ]


@pytest.mark.parametrize("name,v,f,kw,match", defects(), ids=[d[0] for d in defects()])
def test_both_checks_refuse_the_same_defects(name, v, f, kw, match):
    with pytest.raises(FabricationError, match=match) as by_vertices:
        sc.check_indexed(v, f, **kw)
    with pytest.raises(FabricationError, match=match) as by_corners:
        sc.check_triangles(corners32(v, f), **kw)
    assert str(by_vertices.value) == str(by_corners.value)
    merged = by_vertices.value.mesh
    assert merged is not None and len(merged[1]) == len(f)  # the merged mesh, for the repairs


def test_empty_and_non_finite_meshes_are_refused():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    with pytest.raises(FabricationError, match="the mesh mesh is empty"):
        sc.check_indexed(v, np.zeros((0, 3), int))
    with pytest.raises(FabricationError, match="the mesh mesh is empty"):
        sc.check_triangles(np.zeros((0, 3, 3), np.float32))
    v[1, 0] = np.nan
    with pytest.raises(FabricationError, match="has non-finite coordinates"):
        sc.check_indexed(v, [[0, 1, 2]])
    with pytest.raises(FabricationError, match="has non-finite coordinates"):
        sc.check_triangles(corners32(v, [[0, 1, 2]]))


def test_a_good_mesh_passes_both_checks_alike():
    cube = trimesh.creation.box()
    a = sc.check_indexed(cube.vertices, cube.faces, volume=1.0, bodies=1)
    b = sc.check_triangles(corners32(cube.vertices, cube.faces), volume=1.0, bodies=1)
    assert all(np.array_equal(x, y) for x, y in zip(a, b, strict=True))


@settings(max_examples=examples(80), deadline=None)
@given(st.lists(st.tuples(st.integers(0, 5), st.integers(0, 5)), max_size=14))
def test_edges_pair_up_as_counted_one_by_one(edges):
    edges = [(a, b) for a, b in edges if a != b]
    u = np.array([a for a, _ in edges], dtype=np.int64)
    v = np.array([b for _, b in edges], dtype=np.int64)
    expected = all(edges.count(e) == 1 and edges.count(e[::-1]) == 1 for e in edges)
    assert tr.edges_pair_up(u, v, 6) == expected


@settings(max_examples=examples(60), deadline=None)
@given(st.integers(2, 30), st.lists(st.tuples(st.integers(0, 29), st.integers(0, 29)), min_size=1, max_size=40))
def test_count_bodies_as_networkx(n, edges):
    edges = [(a % n, b % n) for a, b in edges]
    graph = nx.Graph(edges)
    assert sc.count_bodies(n, np.array(edges)) == nx.number_connected_components(graph)


def mesh_of(pieces):
    cov = mb.coverage_from_cells([(p, lvl) for p, lvl in pieces], np.array([0.0, 1.0, 2.0]))
    v, f = mb.mesh_coverage(cov)
    return sc.check_indexed(v, f)


def test_convex_pieces_are_fanned_and_the_rest_ear_clipped(monkeypatch):
    import mapbox_earcut

    sizes = []
    real = mapbox_earcut.triangulate_float64
    monkeypatch.setattr(mapbox_earcut, "triangulate_float64", lambda xy, ends: sizes.append(len(xy)) or real(xy, ends))
    ring = box(0, 0, 4, 4).difference(box(1, 1, 2, 2))  # one hole: ear clipped
    quad = shapely.Polygon([(5, 0), (7, 0.5), (7.5, 2), (5.5, 1.5)])  # convex: fanned
    v, f = mesh_of([(ring, 2), (quad, 1)])
    z = v[f][:, :, 2]
    flat_top = (z.min(axis=1) == z.max(axis=1)) & (z[:, 0] > 0)
    assert flat_top.sum() == (8 + 2 * 1 - 2) + (4 - 2)  # n + 2h - 2 triangles each
    assert sizes == [8]  # earcut saw the ring, not the quad


def test_a_bad_ear_clipping_falls_back_to_manifold3d(monkeypatch):
    """Earcut's answer is used only when it tiles the piece; here it is made to lie."""
    import mapbox_earcut

    calls = []

    def fan(xy, ends):  # a fan over a non-convex ring: triangles outside the piece
        calls.append(len(xy))
        k = np.arange(1, int(ends[0]) - 1)
        return np.stack([np.zeros_like(k), k, k + 1], axis=1).ravel().astype(np.uint32)

    monkeypatch.setattr(mapbox_earcut, "triangulate_float64", fan)
    notched = shapely.Polygon([(0, 0), (4, 0), (4, 4), (2, 1), (0, 4)])  # fanned from (0, 0): a triangle outside
    ij = np.round(np.asarray(notched.exterior.coords)[:-1] / mb.QUANTUM).astype(np.int64)
    nxt = np.r_[np.arange(1, len(ij)), 0]
    assert tr.ear_clip(ij, np.array([0, len(ij)]), np.array([0, 1]), nxt) is None
    _v, f = mesh_of([(notched, 2)])  # meshed all the same, by manifold3d: watertight
    assert calls and len(f) == 2 * (len(ij) - 2) + 2 * 2 * len(ij)  # top, bottom, walls over two levels


def test_earcut_refuses_an_edge_through_a_ring_point():
    """Two triangles of the right area and orientation whose shared edge passes a ring point."""
    square = np.array([[0, 0], [4, 0], [4, 4], [2, 4], [0, 4]], np.int64)  # (2, 4) on the top edge
    nxt = np.r_[np.arange(1, 5), 0]
    tris = np.array([[0, 1, 2], [0, 2, 4]])  # the edge 2 -> 4 runs through point 3
    u = np.concatenate([tris.ravel(), nxt])
    v = np.concatenate([tris[:, [1, 2, 0]].ravel(), np.arange(5)])
    assert int(tr.twice_areas(square, tris).sum()) == 2 * 16
    assert not tr.edges_pair_up(u, v, 5)

    fixed = tr.restore_collinear(square, tris, nxt)  # the edge split at the point it runs through
    assert tr.tiles_exactly(square, fixed, nxt) and len(fixed) == 3


@settings(max_examples=examples(40), deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_holes_along_one_line_are_ear_clipped_exactly(seed):
    """Holes with edges on one straight line (as cells cut the region): earcut runs a
    triangle edge along the line from hole to hole; split at the holes' corners, its
    triangles tile the piece with no fallback."""
    rng = np.random.default_rng(seed)
    k = int(rng.integers(2, 7))
    xs = np.sort(rng.choice(np.arange(2, 98), size=2 * k, replace=False))
    rings = [np.array([[0, 0], [100, 0], [100, 100], [0, 100]])]
    for i in range(k):
        h = int(rng.integers(2, 20))
        y0 = 50 if rng.random() < 0.8 else 50 - h  # above or below the line y = 50
        x0, x1 = xs[2 * i], xs[2 * i + 1]
        rings.append(np.array([[x0, y0], [x0, y0 + h], [x1, y0 + h], [x1, y0]]))  # clockwise: a hole
    ij = np.concatenate(rings).astype(np.int64)
    starts = np.cumsum([0] + [len(r) for r in rings])
    nxt = np.arange(len(ij)) + 1
    nxt[starts[1:] - 1] = starts[:-1]
    tris = tr.ear_clip(ij, starts, np.array([0, len(rings)]), nxt)
    assert tris is not None and tr.tiles_exactly(ij, tris, nxt)


def bottom_faces(v, f):
    z = v[f][:, :, 2]
    return int(np.count_nonzero(z.max(axis=1) == 0))


@pytest.mark.parametrize("style", ["relief", "deboss"])
def test_the_bottom_of_a_relief_or_plate_is_its_outline_alone(tmp_path, style):
    from fabtiles import HexPacking, Star, Tile

    tile = Tile("hexagon", 60, HexPacking(radius=8, motif=Star.preset("table3-3")), frame=3)
    tile.export(tmp_path / "t.stl", style=style)
    tris = stl.read_stl_triangles((tmp_path / "t.stl").read_bytes())
    v, f = sc.check_triangles(tris, bodies=1)
    top = int(np.count_nonzero(v[f][:, :, 2].min(axis=1) == v[:, 2].max()))
    # the hexagon's outline with the points where cell lines and walls meet it: a few dozen triangles
    assert 4 <= bottom_faces(v, f) < 200 < top


def test_a_pierced_bottom_is_the_top_turned_over(tmp_path):
    from fabtiles import HexPacking, Star, Tile

    tile = Tile("square", 40, HexPacking(radius=8, motif=Star.preset("table3-3")), frame=3)
    tile.export(tmp_path / "t.stl", style="pierced")
    v, f = sc.check_triangles(stl.read_stl_triangles((tmp_path / "t.stl").read_bytes()))
    top = int(np.count_nonzero(v[f][:, :, 2].min(axis=1) == v[:, 2].max()))
    assert bottom_faces(v, f) == top > 200


def test_a_bottom_through_one_point_twice_takes_the_top_turned_over():
    two = [(box(0, 0, 1, 1), 1), (box(1, 1, 2, 2), 1)]  # the outline passes (1, 1) twice
    cov = mb.coverage_from_cells(two, np.array([0.0, 1.0]))
    topo = mb.topology(cov)
    assert tr.bottom_triangles(topo.vid, topo.vid[topo.nxt], topo.out_level, topo.xy) is None
    v, f = mb.mesh_coverage(cov)
    assert bottom_faces(v, f) == 4  # each square's two top triangles, turned over
