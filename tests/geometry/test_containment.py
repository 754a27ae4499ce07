"""Quads inside a polygon (geometry/containment.py) against GEOS's exact contains_properly."""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles.geometry.containment import edges_meet_quads, quads_inside


def random_region(rng):
    """A union of thick random segments on an integer grid, with holes, touching corners and long edges."""
    pts = rng.integers(0, 40, size=(int(rng.integers(3, 12)), 2, 2)).astype(float)
    lines = shapely.linestrings(pts)
    region = shapely.union_all(shapely.buffer(lines, rng.uniform(0.5, 3), cap_style="flat", join_style="mitre"))
    return shapely.union(region, shapely.box(0, 0, 40, 2))  # a long straight edge, cut into grid pieces


def random_quads(rng, region, k):
    """Convex quads: random parallelograms and squares, some snapped onto the region's vertices and edges."""
    c = rng.uniform(-2, 42, size=(k, 2))
    verts = shapely.get_coordinates(region)
    snap = rng.random(k) < 0.3
    c[snap] = verts[rng.integers(0, len(verts), snap.sum())]  # a corner on a boundary vertex
    u = rng.normal(size=(k, 2))
    v = np.stack([-u[:, 1], u[:, 0]], axis=1) + rng.normal(scale=0.5, size=(k, 2))
    size = rng.uniform(0.1, 2.5, size=(k, 1))
    q = np.stack([c, c + size * u, c + size * (u + v), c + size * v], axis=1)
    flip = rng.random(k) < 0.5
    q[flip] = q[flip, ::-1]  # either orientation
    return q


@settings(max_examples=examples(60), deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_quads_inside_is_geos_contains_properly(seed):
    rng = np.random.default_rng(seed)
    region = random_region(rng)
    q = random_quads(rng, region, 300)
    polys = shapely.polygons(np.concatenate([q, q[:, :1]], axis=1))
    want = shapely.contains_properly(region, polys)
    assert quads_inside(region, q).tolist() == want.tolist()


def test_a_quad_sharing_an_edge_or_a_corner_with_the_boundary_is_not_inside():
    square = shapely.box(0, 0, 10, 10)
    q = np.array(
        [
            [[0, 4], [2, 4], [2, 6], [0, 6]],  # an edge on the boundary
            [[8, 8], [10, 10], [8, 9.5], [7, 8.5]],  # a corner on the boundary's corner
            [[1, 1], [9, 1], [9, 9], [1, 9]],
        ],
        float,
    )  # inside, far from it
    assert quads_inside(square, q).tolist() == [False, False, True]
    assert quads_inside(shapely.Polygon(), q).tolist() == [False] * 3
    assert quads_inside(square, np.empty((0, 4, 2))).tolist() == []


def test_a_long_edge_is_found_in_every_cell_it_crosses():
    """A boundary edge far longer than the quads crosses a quad far from its ends."""
    a, b = np.array([[-100.0, 0.5]]), np.array([[100.0, 0.5]])
    quads = np.array([[[x, 0], [x + 1, 0], [x + 1, 1], [x, 1]] for x in (-60, 3, 47)], float)
    assert edges_meet_quads(a, b, quads).tolist() == [True, True, True]
    # slanted, y = 0.5 + (x + 100) / 100: through the first quad, above the others
    assert edges_meet_quads(a, b + [[0, 2]], quads).tolist() == [True, False, False]


@pytest.mark.parametrize("seed", range(3))
def test_holes_of_the_region_are_outside(seed):
    rng = np.random.default_rng(seed)
    outer = shapely.box(0, 0, 30, 30)
    holes = [shapely.box(x, y, x + 3, y + 3) for x, y in rng.uniform(2, 25, size=(6, 2))]
    region = shapely.difference(outer, shapely.union_all(holes))
    q = random_quads(rng, region, 400)
    polys = shapely.polygons(np.concatenate([q, q[:, :1]], axis=1))
    assert quads_inside(region, q).tolist() == shapely.contains_properly(region, polys).tolist()
