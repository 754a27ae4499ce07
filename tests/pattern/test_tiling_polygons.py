"""Every tiling checked from ``TilingPacking.polygons(window)`` alone (``docs/tilings.md``).

The polygons are regular with edges of the packing's length, overlap nowhere and cover the
window away from its edge; the angles round every vertex add up to 360 degrees; a tiling has
exactly the vertex types its name gives (one for the 11, two for the two-uniform ones). And
Hankin's rays: on a regular n-gon of edge a at contact angle t two rays meet after
L = (a/2) sin(A/2) / sin(t + A/2) (A the interior angle), so the centre-lines' length per unit
area is the sum over a cell's polygons of 2 n L_n over the cell's area.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiLineString, Polygon, box

from fabtiles.core.errors import ParameterError
from fabtiles.pattern.archimedean import TilingPacking
from fabtiles.pattern.tilings import ALL_TILINGS, TILINGS, unit_cell

EDGE = 10.0
HALF = 45.0  # the window: (-HALF, -HALF, HALF, HALF) mm


def _configurations(name: str) -> set[tuple[int, ...]]:
    """The vertex types a tiling's name gives, each as the least of its rotations and reflections."""
    out = set()
    for part in re.sub(r"#\d$", "", name).strip("[]").split(";"):
        sides: list[int] = []
        for term in part.strip().split("."):
            base, _, power = term.partition("^")
            sides += [int(base)] * int(power or 1)
        out.add(_least(tuple(sides)))
    return out


def _least(seq: tuple[int, ...]) -> tuple[int, ...]:
    rots = [seq[k:] + seq[:k] for k in range(len(seq))]
    return min(rots + [r[::-1] for r in rots])


@pytest.fixture(scope="module", params=ALL_TILINGS)
def tiling_polygons(request):
    polys = TilingPacking(request.param, edge=EDGE).polygons((-HALF, -HALF, HALF, HALF))
    return request.param, polys


def test_every_polygon_is_regular_with_the_edge(tiling_polygons):
    _, polys = tiling_polygons
    assert len(polys) > 10
    for corners in polys:
        n = len(corners)
        edges = np.hypot(*(np.roll(corners, -1, axis=0) - corners).T)
        centre = corners.mean(axis=0)
        assert n in (3, 4, 6, 8, 12)
        assert edges == pytest.approx(EDGE, abs=1e-9)
        assert np.hypot(*(corners - centre).T) == pytest.approx(EDGE / (2 * math.sin(math.pi / n)), abs=1e-9)
        assert Polygon(corners).area == pytest.approx(n * EDGE**2 / (4 * math.tan(math.pi / n)), rel=1e-9)


def test_polygons_overlap_nowhere_and_cover_the_window(tiling_polygons):
    _, polys = tiling_polygons
    # each shrunk by a micrometre: GEOS finds area in the intersection of some triangles that only share an edge
    shapes = [Polygon(c).buffer(-1e-3, join_style="mitre") for c in polys]
    tree = shapely.STRtree(shapes)
    left, right = tree.query(shapes, predicate="intersects")
    pairs = left < right
    overlap = sum(shapes[i].intersection(shapes[j]).area for i, j in zip(left[pairs], right[pairs], strict=True))
    assert overlap < 1e-6
    inner = box(-HALF + 2 * EDGE, -HALF + 2 * EDGE, HALF - 2 * EDGE, HALF - 2 * EDGE)
    union = shapely.union_all([Polygon(c) for c in polys])
    assert union.intersection(inner).area == pytest.approx(inner.area, rel=1e-9)
    window = box(-HALF, -HALF, HALF, HALF)
    assert all(Polygon(c).intersects(window) for c in polys)


def test_vertex_angles_and_types(tiling_polygons):
    name, polys = tiling_polygons
    around: dict[tuple, list] = {}
    for corners in polys:
        n = len(corners)
        centre = corners.mean(axis=0)
        for v in corners:
            around.setdefault(tuple(np.round(v, 6)), []).append((math.atan2(*(centre - v)[::-1]), n))
    inside = 2 * EDGE
    types = set()
    for v, polygons in around.items():
        if max(abs(v[0]), abs(v[1])) > HALF - inside:
            continue  # a polygon round it may lie outside the window
        assert sum(180 - 360 / n for _, n in polygons) == pytest.approx(360, abs=1e-9), (name, v)
        types.add(_least(tuple(n for _, n in sorted(polygons))))
    assert types == _configurations(name)
    assert len(types) == (1 if name in TILINGS else 2)


def test_polygons_meet_only_the_window():
    polys = TilingPacking("4.8.8", edge=EDGE).polygons((50, 50, 50.5, 50.5))
    assert len(polys) == 1 and len(polys[0]) in (4, 8)
    with pytest.raises(ParameterError, match="window"):
        TilingPacking("4.8.8", edge=EDGE).polygons((1, 1, 0, 0))


@pytest.mark.parametrize("tiling", ALL_TILINGS)
def test_hankin_length_per_area(tiling):
    angle = 55.0
    packing = TilingPacking(tiling, edge=EDGE, method="hankin", contact_angle=angle)
    t = math.radians(angle)
    per_cell = 0.0  # over one translational cell
    for n in unit_cell(tiling).sides.tolist():
        a_half = (n - 2) * math.pi / n / 2
        per_cell += 2 * n * (EDGE / 2) * math.sin(a_half) / math.sin(t + a_half)
    expected = per_cell / abs(np.linalg.det(packing.lattice))
    # a whole number of rectangular periods: the average over it is the tiling's own
    px, py = packing.period
    w, h = px * max(1, round(150 / px)), py * max(1, round(150 / py))
    segs = packing.segments((0, 0, w, h))
    measured = MultiLineString([s.tolist() for s in segs]).intersection(box(0, 0, w, h)).length / (w * h)
    assert measured == pytest.approx(expected, rel=1e-9)


def test_two_uniform_spellings():
    for spelling in ("[3^6; 3^4.6]#2", "3^6;3^4.6#2", "3.3.3.3.6, 3.3.3.3.3.3 2", "[6.3.3.3.3; 3^6] #2"):
        assert TilingPacking(spelling, edge=EDGE).tiling == "[3^6; 3^4.6]#2"
    assert TilingPacking("4.12.6; 4.6.4.3", edge=EDGE).tiling == "[4.6.12; 3.4.6.4]"


@pytest.mark.parametrize("bad", ["[3^6; 3^4.6]#3", "[3^6; 4.8.8]", "[3^6; 3^4.6; 6^3]"])
def test_unknown_two_uniform_tiling(bad):
    with pytest.raises(
        ParameterError,
        match=r"is unknown(; did you mean '[^']+'\?)? \(tilings: 3\.3\.3\.3\.3\.3, .*\[3\^6; 3\^4\.6\]#1",
    ):
        TilingPacking(bad, edge=EDGE)


def test_a_pair_without_its_number_names_both():
    with pytest.raises(ParameterError, match=r"did you mean '\[3\^6; 3\^4\.6\]#1' or '\[3\^6; 3\^4\.6\]#2'\?"):
        TilingPacking("3^6; 3^4.6", edge=EDGE)
