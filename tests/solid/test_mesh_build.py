"""The meshing core's refusals (fabtiles.solid._mesh_build): bad shapes, and coverages it cannot mesh."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, box

from fabtiles import FabricationError, ParameterError
from fabtiles.solid._mesh_build import Coverage, check_shapes, topology

OUTLINE = box(0, 0, 10, 10)


def _triangle_with_corner(x: float):
    """A triangle with a corner at ``(x, 0)``, NaN or infinite on purpose: GEOS's arithmetic on it sets the
    floating-point invalid flag, which numpy would report as a RuntimeWarning."""
    with np.errstate(invalid="ignore"):
        return shapely.Polygon([(0, 0), (x, 0), (1, 1)])


@pytest.mark.parametrize("name", ["region", "outline"])
@pytest.mark.parametrize("bad,match", [
    ("square", "must be a shapely Polygon or MultiPolygon, got str"),
    (box(0, 0, 1, 1).boundary, "must be a shapely Polygon or MultiPolygon, got LineString"),
    (shapely.Polygon(), "must have an area > 0, got an empty Polygon"),
    (shapely.Polygon([(0, 0), (1, 0), (2, 0)]), "must have an area > 0, got an empty Polygon"),
    (_triangle_with_corner(math.nan), "must have finite coordinates, got NaN or infinite values"),
    (_triangle_with_corner(math.inf), "must have finite coordinates, got NaN or infinite values"),
    (box(0, 0, 16001, 1), r"must lie within 16 m of the origin \(coordinates in mm\), got 16001"),
    (box(-20000, 0, -19990, 1), r"must lie within 16 m of the origin \(coordinates in mm\), got 20000"),
    (shapely.Polygon([(0, 0), (4, 4), (4, 0), (0, 1)]), r"is not a valid polygon \(Self-intersection"),
])
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
    with pytest.raises(FabricationError, match=r"^cannot mesh the region: two pieces overlap \(the region is not a "
                                               r"clean coverage\)$"):
        topology(Coverage(pieces=[(square, 1), (square, 1)], levels=np.array([0.0, 1.0])), triangulate=False)


def test_topology_refuses_an_edge_of_three_pieces():
    # three pieces along the edge x = 1, 0 <= y <= 1: the left square twice over would also overlap,
    # so the third is a triangle on the other side sharing the edge
    left, right = MultiPolygon([box(0, 0, 1, 1)]), MultiPolygon([box(1, 0, 2, 1)])
    third = MultiPolygon([shapely.Polygon([(1, 0), (1, 1), (3, 0.5)])])
    with pytest.raises(FabricationError, match=r"^cannot mesh the region: an edge is shared by more than two pieces$"):
        topology(Coverage(pieces=[(left, 1), (right, 1), (third, 1)], levels=np.array([0.0, 1.0])),
                 triangulate=False)
