"""The meshing core (fabtiles.solid._mesh_build): its refusals (bad shapes, coverages it cannot mesh) and its cells."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, box

from fabtiles import FabricationError, ParameterError
from fabtiles.solid import _mesh_build as mb
from fabtiles.solid._mesh_build import (
    QUANTUM,
    Coverage,
    cells_for,
    check_shapes,
    coverage,
    coverage_from_cells,
    mesh_coverage,
    topology,
)
from fabtiles.solid._triangulate import cdt
from fabtiles.solid.mesh_check import check_indexed

OUTLINE = box(0, 0, 10, 10)


def _triangle_with_corner(x: float):
    """A triangle with a corner at ``(x, 0)``, NaN or infinite on purpose: GEOS's arithmetic on it sets the
    floating-point invalid flag, which numpy would report as a RuntimeWarning."""
    with np.errstate(invalid="ignore"):
        return shapely.Polygon([(0, 0), (x, 0), (1, 1)])


@pytest.mark.parametrize("name", ["region", "outline"])
@pytest.mark.parametrize(
    "bad,match",
    [
        ("square", "must be a shapely Polygon or MultiPolygon, got str"),
        (box(0, 0, 1, 1).boundary, "must be a shapely Polygon or MultiPolygon, got LineString"),
        (shapely.Polygon(), "must have an area > 0, got an empty Polygon"),
        (shapely.Polygon([(0, 0), (1, 0), (2, 0)]), "must have an area > 0, got an empty Polygon"),
        (_triangle_with_corner(math.nan), "must have finite coordinates, got NaN or infinite values"),
        (_triangle_with_corner(math.inf), "must have finite coordinates, got NaN or infinite values"),
        (box(0, 0, 16001, 1), r"must lie within 16 m of the origin \(coordinates in mm\), got 16001"),
        (box(-20000, 0, -19990, 1), r"must lie within 16 m of the origin \(coordinates in mm\), got 20000"),
        (shapely.Polygon([(0, 0), (4, 4), (4, 0), (0, 1)]), r"is not a valid polygon \(Self-intersection"),
    ],
)
def test_check_shapes_refuses(name, bad, match):
    shapes = {"region": box(1, 1, 9, 9), "outline": OUTLINE, name: bad}
    with pytest.raises(ParameterError, match=f"^{name} {match}"):
        check_shapes(shapes["region"], shapes["outline"])


def test_check_shapes_passes_good_shapes_through():
    region = MultiPolygon([box(1, 1, 4, 4), box(6, 6, 9, 9)])
    assert check_shapes(region, OUTLINE) == (region, OUTLINE)


def test_topology_of_no_pieces_is_refused():
    with pytest.raises(FabricationError, match=r"^nothing to mesh: the material region is empty$"):
        topology(Coverage(pieces=[], levels=np.array([0.0, 1.0])))


def test_topology_refuses_overlapping_pieces():
    square = MultiPolygon([box(0, 0, 1, 1)])
    with pytest.raises(
        FabricationError,
        match=r"^cannot mesh the region: two pieces overlap \(the region is not a "
        r"clean coverage\)$",
    ):
        topology(Coverage(pieces=[(square, 1), (square, 1)], levels=np.array([0.0, 1.0])), triangulate=False)


def test_topology_refuses_an_edge_of_three_pieces():
    # three pieces along the edge x = 1, 0 <= y <= 1: the left square twice over would also overlap,
    # so the third is a triangle on the other side sharing the edge
    left, right = MultiPolygon([box(0, 0, 1, 1)]), MultiPolygon([box(1, 0, 2, 1)])
    third = MultiPolygon([shapely.Polygon([(1, 0), (1, 1), (3, 0.5)])])
    with pytest.raises(FabricationError, match=r"^cannot mesh the region: an edge is shared by more than two pieces$"):
        topology(Coverage(pieces=[(left, 1), (right, 1), (third, 1)], levels=np.array([0.0, 1.0])), triangulate=False)


LOBES = shapely.Polygon([(0, 0), (4, 0), (4, 2), (2, 0), (0, 2)])
"""A ring touching itself at (2, 0): two lobes, as a piece cut at a line through a vertex of its ring was."""


def test_a_piece_geos_cannot_triangulate_is_a_fabrication_error_at_its_place():
    cov = coverage_from_cells([(LOBES, 1)], [0.0, 1.0])
    with pytest.raises(
        FabricationError,
        match=r"^cannot triangulate the region near \(2, 0\) mm: GEOS stops there "
        r"\(IllegalStateException: .*; its ring touches itself\)$",
    ) as info:
        mesh_coverage(cov)
    assert info.value.points.tolist() == [[2.0, 0.0]]


def test_a_valid_piece_geos_cannot_triangulate_is_refused_at_a_point_of_it(monkeypatch):
    def broken(geom, **kwargs):
        raise shapely.errors.GEOSException("IllegalStateException: Unable to find a convex corner")

    monkeypatch.setattr(shapely, "constrained_delaunay_triangles", broken)
    ij = np.array([[0, 0], [4, 0], [4, 2]]) * 1024
    with pytest.raises(
        FabricationError,
        match=r"^cannot triangulate the region near \(3, 1\) mm: "
        r"GEOS stops \(IllegalStateException: Unable to find a convex corner\)$",
    ):
        cdt(shapely.Polygon([(0, 0), (4, 0), (4, 2)]), ij)


def test_a_triangle_corner_off_the_rings_is_refused(monkeypatch):
    monkeypatch.setattr(
        shapely, "constrained_delaunay_triangles", lambda geom, **kwargs: shapely.Polygon([(0, 0), (4, 0), (3, 1)])
    )
    ij = np.array([[0, 0], [4, 0], [4, 2]]) * 1024
    with pytest.raises(
        FabricationError,
        match=r"^cannot triangulate the region near \(3, 1\) mm: GEOS gives a point "
        r"not on its rings$",
    ):
        cdt(shapely.Polygon([(0, 0), (4, 0), (4, 2)]), ij)


def test_no_cell_line_passes_through_a_vertex():
    """A notch whose tip touches a cell line: the line moves off it, and the cut pieces mesh watertight."""
    square = box(0, 0, 40, 40)
    xs, ys, _ = cells_for([square], 1)
    x, y = float(xs[1]) - 5, float(ys[1])
    # a notch from the top edge down to the line y = ys[1], its tip on it: the bounds stay the square's
    notch = shapely.Polygon([(x - 3, 40), (x, y), (x + 3, 40)])
    shape = square.difference(notch)
    assert [x, y] in shapely.get_coordinates(shape).tolist()
    xs2, ys2, _ = cells_for([shape], 1)
    # moved forward a little, clear of the tip
    assert len(xs2) == len(xs) and len(ys2) == len(ys)
    assert np.all((ys2 >= ys) & (ys2 <= ys + mb.LINE_SEARCH * QUANTUM))
    assert np.abs(ys2 - y).min() >= mb.LINE_CLEARANCE * QUANTUM
    verts, faces = mesh_coverage(coverage([(shape, 1.0)], bottom=0.0, cell_vertices=1))
    check_indexed(verts, faces, volume=shape.area, bodies=1)


def test_the_lines_kept_off_a_vertex_are_what_kept_the_notch_triangulable(monkeypatch):
    square = box(0, 0, 40, 40)
    xs, ys, _ = cells_for([square], 1)
    shape = square.difference(shapely.Polygon([(xs[1] - 8, 40), (xs[1] - 5, ys[1]), (xs[1] - 2, 40)]))
    monkeypatch.setattr(mb, "_off_vertices", lambda lines, values: lines)
    with pytest.raises(FabricationError, match=r"^cannot triangulate the region near"):
        check_indexed(*mesh_coverage(coverage([(shape, 1.0)], bottom=0.0, cell_vertices=1)))
