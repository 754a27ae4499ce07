"""Where material is narrower than a width, and holes too small for a machine.

Shared by the laser checks (thin bridges, small holes) and the print checks (thin
walls, small holes). A boundary is a ring (the outer ring of a piece or one of its
holes); a thin dead-end spike, such as a star tip, belongs to one ring and is not
reported. A hole is too small when no disc of the machine's ``min_hole_mm`` fits in
it (:func:`small_hole_mask`); :func:`fill_small_holes` fills such holes.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import shapely

from .contours import polygon_parts

MAX_LOCATIONS = 100_000
"""At most this many locations are listed per finding (a 1,200 x 600 mm sheet has about 20,000 holes)."""


class NarrowPlaces(NamedTuple):
    """What :func:`narrow_places` found: one entry per pair of boundaries closer than the width."""

    count: int  # type: ignore[assignment]  # the field is the count of places; tuple.count is not used
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
    # GEOS's maximum inscribed circle, each hole at once: quick enough for the web's preview
    lines = shapely.maximum_inscribed_circle(holes, max(tolerance_mm, 1e-4))
    return shapely.get_point(lines, 0), 2 * shapely.length(lines)


def add_small_holes(report, holes: np.ndarray, *, tolerance_mm: float, message, limit_mm: float) -> None:
    """Report ``holes`` as one ``small_hole`` finding, each at its widest point with its width.

    ``message(count, narrowest_mm)`` says why they are too small and what to do (a laser
    burns them away; a router's bit cannot enter them); ``limit_mm`` the width they are under.
    """
    centres, widths = hole_widths(holes, tolerance_mm=tolerance_mm)
    n = len(widths)
    report.add(
        "small_hole",
        message(n, float(widths.min())),
        count=n,
        locations=locations(centres),
        sizes=widths[:MAX_LOCATIONS].round(3),
        worst=round(float(widths.min()), 3),
        limit=limit_mm,
    )


def hole_polygons(parts: np.ndarray):
    """Interior rings of ``parts`` as polygons, with the index of their part."""
    nholes = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), nholes)
    idx = np.concatenate([np.arange(k) for k in nholes]) if len(parts) else np.empty(0, int)
    return shapely.polygons(shapely.get_interior_ring(parts[owner], idx)), owner


def small_hole_mask(holes: np.ndarray, min_hole_mm: float) -> np.ndarray:
    """True for each hole polygon that no disc of diameter ``min_hole_mm`` fits in.

    Cheap tests first (bounding box, area, a disc at the centroid), a negative buffer
    only for the undecided ones, by a little more than ``min_hole_mm / 2`` (with 4
    segments a quarter and no margin, its polygonal arcs passed holes 0.391 mm wide for
    0.4 mm).

    >>> from shapely.geometry import box
    >>> small_hole_mask(np.array([box(0, 0, 1, 1), box(0, 0, 5, 5), box(0, 0, 1, 9)]), 1.2).tolist()
    [True, False, True]
    """
    holes = np.asarray(holes, dtype=object)
    if min_hole_mm <= 0:  # a machine with no smallest hole (a printer profile's min_hole_mm = 0)
        return np.zeros(len(holes), bool)
    r = min_hole_mm / 2
    b = shapely.bounds(holes)
    small = (np.minimum(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]) < min_hole_mm) | (shapely.area(holes) < math.pi * r * r)
    todo = np.flatnonzero(~small)
    if len(todo):
        c = shapely.centroid(holes[todo])
        roomy = shapely.contains_properly(holes[todo], c) & (
            shapely.distance(c, shapely.get_exterior_ring(holes[todo])) >= r
        )
        todo = todo[~roomy]
    if len(todo):
        # eroded by 0.2 % more than r: the offset's arcs of 16 chords a quarter lie up to 0.12 %
        # inside the true circle, so no hole narrower than the limit survives (a hole up to
        # 0.2 % wider may count as small); far quicker than GEOS's largest inscribed circle
        small[todo] = shapely.is_empty(shapely.buffer(holes[todo], -r * 1.002, quad_segs=16))
    return small


def fill_small_holes(region, min_hole_mm: float, *, tolerance_mm: float = 0.0):
    """``region`` with its holes narrower than ``min_hole_mm`` filled: ``(region, count)``.

    Degenerate holes (area <= ``tolerance_mm**2``) are filled too but not counted.

    >>> from shapely.geometry import box
    >>> plate = box(0, 0, 9, 9).difference(box(1, 1, 1.5, 1.5)).difference(box(4, 4, 8, 8))
    >>> filled, n = fill_small_holes(plate, 1.2)
    >>> n, len(filled.interiors)
    (1, 1)
    """
    parts = polygon_parts(region)
    holes, owner = hole_polygons(parts)
    if not len(holes):
        return region, 0
    small = small_hole_mask(holes, min_hole_mm)
    degenerate = shapely.area(holes) <= tolerance_mm**2
    drop = small | degenerate
    if not drop.any():
        return region, 0
    return without_holes(region, parts, holes, owner, drop), int((small & ~degenerate).sum())


def without_holes(region, parts, holes, owner, drop):
    """``region`` (its polygons ``parts``) rebuilt without the holes marked in ``drop``.

    ``holes, owner`` are :func:`hole_polygons` of ``parts``. Rebuilding the polygons
    from their rings is exact and costs no overlay.
    """
    keep = ~drop
    rings = shapely.get_exterior_ring(holes[keep])
    shells = shapely.get_exterior_ring(parts)
    allr = np.concatenate([shells, rings])
    index = np.concatenate([np.arange(len(parts)), owner[keep]])
    order = np.argsort(index, kind="stable")  # each part's shell first, then its holes
    new = shapely.polygons(allr[order], indices=index[order])
    return new[0] if len(new) == 1 and region.geom_type == "Polygon" else shapely.multipolygons(new)


PATTERN_KEPT = 0.5
"""The share of a pattern's open area a file must keep once its small holes are filled, else a
``filled_pattern`` finding: below half, what is cut or printed no longer reads as the design.
Measured as area, not as a count of holes: a pattern often has many small holes (where its bands
cross the outline, the points of its stars) that hold little of its open area, and filling them
changes little of what one sees (the samples keep 84 % to 100 % of their open area on the bundled
profiles while keeping 14 % to 97 % of their holes)."""


def check_pattern_kept(
    report,
    before,
    after,
    outline,
    *,
    limit_mm: float,
    limit: str,
    openings: str = "holes",
    stroke=None,
    min_stroke_mm: float = 0.0,
    scale: bool = True,
    tool: str = "",
    deboss: bool = False,
    tolerance_mm: float = 0.01,
) -> float:
    """Report ``filled_pattern`` when filling small openings left less than :data:`PATTERN_KEPT` of the pattern.

    The pattern's open area is the tile's area without material (``outline`` less
    ``before``); the share kept is that area in ``after`` over that area in ``before``.
    A ``deboss`` (``before`` and ``after`` are its grooves) loses pattern both ways: its
    islands of plate too small become groove (the open area above), and its grooves too
    narrow become plate (the grooves' area); the share is the smaller of the two. The
    message tells how wide the openings that must stay open are (the narrowest of the
    widest filled openings that, kept, bring the share back to :data:`PATTERN_KEPT`) and
    what makes them as wide as ``limit_mm``: a stroke that much thinner (wider, for
    grooves), kept at ``min_stroke_mm`` or more; the packing scaled up (``scale``: the
    openings of a stroke ``s`` grow from ``w`` to ``k (w + s) - s``); ``tool`` (a format
    with ``{w}``), a machine whose limit they meet.

    Returns the share kept (1.0 when the pattern had no open area).

    >>> from shapely.geometry import box
    >>> from fabtiles.core.report import Report
    >>> plate = box(0, 0, 20, 20).difference(box(4, 4, 5, 5)).difference(box(10, 10, 11, 11))
    >>> filled, n = fill_small_holes(plate, 1.2)
    >>> r = Report(path="", format="")
    >>> check_pattern_kept(r, plate, filled, box(0, 0, 20, 20), limit_mm=1.2, limit="min_hole_mm = 1.2 mm",
    ...                    stroke=2.0, min_stroke_mm=1.0, tool="a profile with min_hole_mm <= {w} mm")
    0.0
    >>> print(r.findings[0].message)
    filling the holes narrower than min_hole_mm = 1.2 mm left none of the pattern (all 2 holes filled): to keep at least 50 % of the pattern's open area, the holes of 1 mm must be 1.2 mm wide or wider: a stroke of at most 1.8 mm (it is 2 mm), a packing at least 1.07x larger (its edge or radius), or a profile with min_hole_mm <= 1 mm
    """  # noqa: E501 - a doctest's lines are as Python prints them
    least = _least_share(before, after, outline, deboss=deboss, tolerance_mm=tolerance_mm)
    if least is None:
        return 1.0
    kept, open_before, grooves = least
    if kept >= PATTERN_KEPT:
        return kept
    if kept < 1e-9:
        kept = 0.0
    openings = "grooves" if grooves else openings
    filled, total = _filled_openings(before, after, outline, grooves=grooves, tolerance_mm=tolerance_mm)
    n = len(filled)
    centres, widths = hole_widths(filled, tolerance_mm=tolerance_mm) if n else (np.empty(0, object), np.empty(0))
    what = f"all {total:,} {openings}" if n == total else f"{n:,} of {total:,} {openings}"
    area_of = "its grooves' area" if grooves else "the pattern's open area"
    share = "none of the pattern" if kept == 0 else f"{100 * kept:.0f} % of {area_of}"
    message = f"filling the {openings} narrower than {limit} left {share} ({what} filled)"
    if n:
        # the widest filled openings first, until they bring back enough area
        order = np.argsort(-widths, kind="stable")
        need = PATTERN_KEPT * open_before - kept * open_before
        reach = int(np.searchsorted(np.cumsum(shapely.area(filled)[order]), need))
        w = float(widths[order[min(reach, n - 1)]])
        ways = _ways_to_width(w, limit_mm, stroke, min_stroke_mm, scale=scale, tool=tool, grooves=grooves)
        message += (
            f": to keep at least {100 * PATTERN_KEPT:.0f} % of {area_of}, the {openings} of {w:.3g} mm "
            f"must be {limit_mm:g} mm wide or wider: {ways}"
        )
    report.add(
        "filled_pattern",
        message,
        count=n,
        locations=locations(centres),
        worst=round(100 * kept, 1),
        unit="%",
        limit=100 * PATTERN_KEPT,
    )
    return kept


def _least_share(before, after, outline, *, deboss: bool, tolerance_mm: float):
    """``(share kept, open area before, grooves)`` of the phase that kept least, or None when nothing was open.

    The open area is the outline less ``before``; a ``deboss`` also loses its grooves'
    area where the filling took groove away (``grooves`` True for that phase).
    """
    o_area, b_area = float(shapely.area(outline)), float(shapely.area(before))
    # only a deboss's filling takes material (groove) away; elsewhere it only adds
    gone = float(shapely.area(shapely.difference(before, after))) if deboss else 0.0
    phases = [(o_area - b_area, float(shapely.area(after)) - b_area + gone, False)]
    if deboss:
        phases.append((b_area, gone, True))
    shares = [(max(0.0, 1.0 - lost / area), area, grooves) for area, lost, grooves in phases if area > tolerance_mm**2]
    if not shares:
        return None
    kept, open_before, grooves = min(shares, key=lambda x: x[0])
    return min(kept, 1.0), open_before, grooves


def _filled_openings(before, after, outline, *, grooves: bool, tolerance_mm: float):
    """``(filled, total)``: the openings before that the filling closed (their inside is material now;
    plate, for ``grooves``), and how many openings there were."""
    pieces = shapely.get_parts(before if grooves else shapely.difference(outline, before))
    pieces = pieces[shapely.area(pieces) > tolerance_mm**2]
    shapely.prepare(after)
    inside = shapely.contains(after, shapely.point_on_surface(pieces))
    return pieces[inside != grooves], len(pieces)


def _ways_to_width(w: float, m: float, stroke, min_stroke_mm: float, *, scale: bool, tool: str, grooves: bool) -> str:
    """What makes openings ``w`` wide ``m`` wide, as a list in words: a thinner stroke (thicker, for
    grooves) kept at ``min_stroke_mm`` or more, a larger packing (``scale``), or ``tool``."""
    ways = []
    if stroke is not None:
        if grooves:
            ways.append(f"a stroke of at least {_up(stroke + m - w):g} mm (it is {stroke:g} mm)")
        elif stroke - (m - w) >= min_stroke_mm:
            ways.append(f"a stroke of at most {_down(stroke - (m - w)):g} mm (it is {stroke:g} mm)")
    if scale and not grooves:
        s = stroke if stroke is not None else 0.0
        ways.append(f"a packing at least {_up((m + s) / max(w + s, 1e-9)):g}x larger (its edge or radius)")
    if tool:
        ways.append(tool.format(w=f"{_down(w):g}"))
    return ", ".join(ways[:-1]) + ", or " + ways[-1] if len(ways) > 1 else "".join(ways)


def _up(x: float) -> float:
    """``x`` rounded up to 0.01 (a float's last bit does not make 1.07 read 1.08)."""
    return math.ceil(x * 100 - 1e-6) / 100


def _down(x: float) -> float:
    """``x`` rounded down to 0.01."""
    return math.floor(x * 100 + 1e-6) / 100


def neck_pieces(polygons: np.ndarray, neck_mm: float):
    """Each polygon cut where it narrows below ``neck_mm`` or touches itself at a point: ``(pieces, owner)``.

    A polygon without such a neck is its own one piece (the same object); the pieces
    of one with necks are its parts once shrunk by ``neck_mm / 2``, grown back and
    kept inside it (they overlap by a hair at the neck).

    >>> from shapely.geometry import box
    >>> neck = shapely.union_all([box(0, 0, 2, 2), box(2, 1, 2.5, 1.004), box(2.5, 0.5, 2.8, 1.5)])
    >>> pieces, owner = neck_pieces(np.array([box(5, 5, 6, 6), neck]), 0.01)
    >>> shapely.area(pieces).round(2).tolist(), owner.tolist()
    ([1.0, 4.0, 0.3], [0, 1, 1])
    """
    polygons = np.asarray(polygons, dtype=object)
    # an erosion by a hair splits at every neck, all holes in one call
    inner = shapely.buffer(polygons, -neck_mm / 2, quad_segs=2)
    split = np.flatnonzero(shapely.get_num_geometries(inner) > 1)
    if not len(split):
        return polygons, np.arange(len(polygons))
    subs, idx = shapely.get_parts(inner[split], return_index=True)
    subs = shapely.intersection(shapely.buffer(subs, neck_mm / 2, quad_segs=2), polygons[split[idx]])
    whole = np.setdiff1d(np.arange(len(polygons)), split)
    return np.concatenate([polygons[whole], subs]), np.concatenate([whole, split[idx]])


def split_long_rings(rings: np.ndarray, max_points: int = 64, *, min_size: float = 0.0):
    """Rings with more than ``max_points`` points cut into 2-point segments (for a spatial index).

    Only rings whose bounding box is larger than ``min_size`` (width plus height) are cut:
    a small ring with many points (a hole with rounded corners) is one item already, and
    cut into segments each would overlap dozens of its neighbours' boxes, and the candidate
    pairs of a panel's rounded holes would fill the memory (``docs/speed.md``).

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
