"""Where material is narrower than a width: two boundaries of one piece closer than it.

Shared by the laser checks (thin bridges) and the print checks (thin walls). A
boundary is a ring (the outer ring of a piece or one of its holes); a thin dead-end
spike, such as a star tip, belongs to one ring and is not reported.
"""

from __future__ import annotations

import numpy as np
import shapely

MAX_LOCATIONS = 20
"""At most this many locations are listed per finding."""


def locations(points, limit: int = MAX_LOCATIONS) -> list[tuple[float, float]]:
    """The first ``limit`` points as rounded ``(x, y)`` tuples, for a report.

    >>> locations([shapely.Point(1.23456, 2)])
    [(1.235, 2.0)]
    """
    pts = shapely.get_coordinates(np.asarray(points, dtype=object)[:limit])
    return [(float(round(x, 3)), float(round(y, 3))) for x, y in pts]


def split_long_rings(rings: np.ndarray, max_points: int = 64):
    """Rings with more than ``max_points`` points cut into 2-point segments (for a spatial index).

    Returns the pieces and, for each, the index of its ring.
    """
    npts = shapely.get_num_coordinates(rings)
    big = np.flatnonzero(npts > max_points)
    small = np.flatnonzero(npts <= max_points)
    if not len(big):
        return rings, np.arange(len(rings))
    coords, idx = shapely.get_coordinates(rings[big], return_index=True)
    same = idx[1:] == idx[:-1]
    segs = shapely.linestrings(np.stack([coords[:-1][same], coords[1:][same]], axis=1))
    return np.concatenate([rings[small], segs]), np.concatenate([small, big[idx[:-1][same]]])


def narrow_places(region, width: float, *, tolerance: float = 0.0):
    """Pairs of boundaries of the same piece of ``region`` closer than ``width - tolerance``.

    ``tolerance`` keeps material exactly ``width`` wide from being reported (after
    Clipper2's integer rounding it measures a hair less). Returns ``(count,
    narrowest, midpoints)``: one count per pair of rings, the smallest distance, and
    the midpoints of the shortest lines of the first :data:`MAX_LOCATIONS` pairs.

    >>> from shapely.geometry import box
    >>> narrow_places(box(0, 0, 10, 10).difference(box(1, 1, 9.5, 9)), 0.8)[:2]
    (1, 0.5)
    """
    parts = shapely.get_parts(region)
    parts = parts[shapely.area(parts) > 0]
    if not len(parts):
        return 0, float("inf"), []
    n_int = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), n_int)
    idx = np.concatenate([np.arange(k) for k in n_int]) if len(owner) else np.zeros(0, int)
    holes = shapely.get_interior_ring(parts[owner], idx) if len(owner) else np.zeros(0, object)
    rings = np.concatenate([shapely.get_exterior_ring(parts), holes])
    part_of = np.concatenate([np.arange(len(parts)), owner])
    items, ring_of = split_long_rings(rings)
    # candidate pairs: bounding boxes grown by width/2 overlap; then an exact distance test
    grow = np.array([-width / 2, -width / 2, width / 2, width / 2])
    env = shapely.box(*(shapely.bounds(items) + grow).T)
    a, b = shapely.STRtree(env).query(env)
    ra, rb = ring_of[a], ring_of[b]
    sel = (ra < rb) & (part_of[ra] == part_of[rb])
    a, b = a[sel], b[sel]
    near = shapely.dwithin(items[a], items[b], width - tolerance)
    a, b = a[near], b[near]
    if not len(a):
        return 0, float("inf"), []
    _, first = np.unique(ring_of[a] * len(rings) + ring_of[b], return_index=True)
    a, b = a[first], b[first]
    narrowest = float(shapely.distance(items[a], items[b]).min())
    lines = shapely.shortest_line(items[a[:MAX_LOCATIONS]], items[b[:MAX_LOCATIONS]])
    return len(a), narrowest, shapely.line_interpolate_point(lines, 0.5, normalized=True)
