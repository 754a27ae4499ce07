"""Where material is narrower than a width: two boundaries of one piece closer than it.

Shared by the laser checks (thin bridges) and the print checks (thin walls). A
boundary is a ring (the outer ring of a piece or one of its holes); a thin dead-end
spike, such as a star tip, belongs to one ring and is not reported.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import shapely

MAX_LOCATIONS = 100_000
"""At most this many locations are listed per finding (a 1,200 x 600 mm sheet has about 20,000 holes)."""


class NarrowPlaces(NamedTuple):
    """What :func:`narrow_places` found: one entry per pair of boundaries closer than the width."""

    count: int
    narrowest: float
    points: np.ndarray
    """The narrowest point of each pair (the midpoint of its shortest line), shapely Points."""
    widths: np.ndarray
    """The material's width there (mm)."""


def locations(points, limit: int = MAX_LOCATIONS) -> list[tuple[float, float]]:
    """The first ``limit`` points as rounded ``(x, y)`` tuples, for a report.

    >>> locations([shapely.Point(1.23456, 2)])
    [(1.235, 2.0)]
    """
    pts = shapely.get_coordinates(np.asarray(points, dtype=object)[:limit])
    return [(float(round(x, 3)), float(round(y, 3))) for x, y in pts]


def hole_widths(holes: np.ndarray, *, tolerance_mm: float = 0.01):
    """The widest point of each hole polygon and its width (the largest disc inside it).

    Returns ``(centres, widths)``: shapely Points and their diameters (mm), from
    GEOS's maximum inscribed circle within ``tolerance_mm``.

    >>> from shapely.geometry import box
    >>> centres, widths = hole_widths(np.array([box(0, 0, 2, 1)]))
    >>> shapely.get_coordinates(centres).round(2).tolist(), widths.round(2).tolist()
    ([[0.5, 0.5]], [1.0])
    """
    holes = np.asarray(holes, dtype=object)
    # GEOS's maximum inscribed circle: about 20 us a hole at 0.01 mm (680 holes of the
    # default web tile in 14 ms).
    lines = shapely.maximum_inscribed_circle(holes, max(tolerance_mm, 1e-4))
    return shapely.get_point(lines, 0), 2 * shapely.length(lines)


def add_small_holes(report, holes: np.ndarray, *, tolerance_mm: float, message) -> None:
    """Report ``holes`` as one ``small_hole`` finding, each at its widest point with its width.

    ``message(count, narrowest_mm)`` says why they are too small and what to do (a laser
    burns them away; a router's bit cannot enter them).
    """
    centres, widths = hole_widths(holes, tolerance_mm=tolerance_mm)
    n = len(widths)
    report.add("small_hole", message(n, float(widths.min())), count=n, locations=locations(centres),
               sizes=widths[:MAX_LOCATIONS].round(3), worst=round(float(widths.min()), 3))


def split_long_rings(rings: np.ndarray, max_points: int = 64, *, min_size: float = 0.0):
    """Rings with more than ``max_points`` points cut into 2-point segments (for a spatial index).

    Only rings whose bounding box is larger than ``min_size`` (width plus height) are cut:
    a small ring with many points (a hole with rounded corners) is one item already, and
    cut into segments each would overlap dozens of its neighbours' boxes (the router panel's
    1,613 rounded holes, 176,000 points, made 570 MB of candidate pairs and took 2.9 s; kept
    whole, 2 MB and 0.17 s).

    Returns the pieces and, for each, the index of its ring.
    """
    npts = shapely.get_num_coordinates(rings)
    b = shapely.bounds(rings)
    long = (npts > max_points) & ((b[:, 2] - b[:, 0]) + (b[:, 3] - b[:, 1]) > min_size)
    big = np.flatnonzero(long)
    small = np.flatnonzero(~long)
    if not len(big):
        return rings, np.arange(len(rings))
    coords, idx = shapely.get_coordinates(rings[big], return_index=True)
    same = idx[1:] == idx[:-1]
    segs = shapely.linestrings(np.stack([coords[:-1][same], coords[1:][same]], axis=1))
    return np.concatenate([rings[small], segs]), np.concatenate([small, big[idx[:-1][same]]])


def narrow_places(region, width: float, *, tolerance: float = 0.0) -> NarrowPlaces:
    """Pairs of boundaries of the same piece of ``region`` closer than ``width - tolerance``.

    ``tolerance`` keeps material exactly ``width`` wide from being reported (after
    Clipper2's integer rounding it measures a hair less). Returns a
    :class:`NarrowPlaces`: one entry per pair of rings, at the narrowest point
    between the two rings, with the width there.

    >>> from shapely.geometry import box
    >>> found = narrow_places(box(0, 0, 10, 10).difference(box(1, 1, 9.5, 9)), 0.8)
    >>> found.count, found.narrowest, shapely.get_coordinates(found.points).tolist()
    (1, 0.5, [[9.75, 9.0]])
    """
    none = NarrowPlaces(0, float("inf"), np.empty(0, object), np.empty(0))
    parts = shapely.get_parts(region)
    parts = parts[shapely.area(parts) > 0]
    if not len(parts):
        return none
    n_int = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), n_int)
    idx = np.concatenate([np.arange(k) for k in n_int]) if len(owner) else np.zeros(0, int)
    holes = shapely.get_interior_ring(parts[owner], idx) if len(owner) else np.zeros(0, object)
    rings = np.concatenate([shapely.get_exterior_ring(parts), holes])
    part_of = np.concatenate([np.arange(len(parts)), owner])
    items, ring_of = split_long_rings(rings, min_size=64 * width)
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
        return none
    # per pair of rings, the closest pair of pieces (long rings are cut into segments)
    dist = shapely.distance(items[a], items[b])
    key = ring_of[a] * len(rings) + ring_of[b]
    order = np.lexsort((dist, key))
    _, first = np.unique(key[order], return_index=True)
    pick = order[first]
    a, b, dist = a[pick], b[pick], dist[pick]
    lines = shapely.shortest_line(items[a], items[b])
    points = shapely.line_interpolate_point(lines, 0.5, normalized=True)
    return NarrowPlaces(len(a), float(dist.min()), points, dist)
