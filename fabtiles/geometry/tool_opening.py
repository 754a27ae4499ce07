"""The part as a spinning bit or a jet makes it: every hole opened by the tool's radius.

A router bit of radius ``r`` cannot cut a hole corner sharper than ``r``, and cannot
enter any part of a hole narrower than ``2 r``. The hole it does cut is the hole's
morphological *opening* by a disc of radius ``r``: the hole eroded by ``r`` (where
the bit's centre can go) and grown back by ``r`` (what the bit sweeps). In GEOS
terms ``hole.buffer(-r).buffer(r)``, round joins. So

* every convex corner of a hole (a star tip) comes out as an arc of radius ``r``;
* a hole, or a star tip, narrower than ``2 r`` vanishes: it stays material;
* a hole with a neck narrower than ``2 r`` comes out as two holes.

The outline is cut by the outside of the bit: its convex corners stay sharp, its
concave ones (a notch, the gap between two bands that reach the edge of a
frameless tile) come out rounded, and a notch narrower than ``2 r`` is not cut. That
is the *closing* of each part's outer ring, ``shell.buffer(r).buffer(-r)``, done
only for the outer rings that are not convex (the default square, rectangle and
hexagon outlines are left exactly as they are).

A waterjet is the same with the jet's radius (half its kerf); its kerf is then
compensated as a laser's (:func:`~fabtiles.geometry.contours.laser_contours`).

:func:`open_region` does it for every hole at once, with shapely 2's array
functions (one ``shapely.buffer`` call each way over the array of holes), and rebuilds the
part from its outer rings
and the opened holes without a boolean overlay. :func:`check_tool` turns what changed
into findings: ``small_hole`` for the holes that vanish (the tool the reason),
``rounded_corner`` at every corner that moves by more than :data:`VISIBLE_MM`.

>>> import shapely
>>> plate = shapely.box(0, 0, 30, 30).difference(shapely.box(10, 10, 20, 20))
>>> made = open_region(plate, radius_mm=2, tolerance_mm=0.01)
>>> round(made.region.area - plate.area, 3)  # four corners of 4 - pi mm^2 (3.434) stay, and the chords' 0.02
3.454
>>> made.vanished, made.moved.round(3).tolist()[:2]
(0, [0.828, 0.828])
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import shapely

from ..core.errors import ParameterError
from ..core.report import Report, distinct
from .narrow import MAX_LOCATIONS, add_small_holes, hole_widths, locations

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry

VISIBLE_MM = 0.1
"""A corner that moves more than this (mm) is reported as ``rounded_corner``.

A tenth of a millimetre is about what a person sees on a cut part and what a
caliper reads; with a 6 mm bit every corner sharper than 151 degrees moves more
(a corner of angle ``a`` moves ``r / sin(a / 2) - r``: a right angle by 1.24 mm).
"""


def quad_segs_for(radius_mm: float, tolerance_mm: float) -> int:
    """Segments per quarter circle so that an arc of ``radius_mm`` is flattened within a quarter of ``tolerance_mm``.

    A chord of an arc of radius ``r`` spanning ``pi / (2 q)`` lies at most
    ``r (1 - cos(pi / (4 q)))`` inside it. The opening flattens twice (the erosion's arcs
    at the material's corners, the growth's at the hole's), and the errors add up: at half
    the tolerance a hole of a 3.175 mm bit was 0.0106 mm (Hausdorff) from GEOS's opening at
    64 segments a quarter; at a quarter, within 0.006 mm, and the symmetric difference
    within 0.01 % of the area.

    >>> quad_segs_for(3.0, 0.01), quad_segs_for(1.5875, 0.01), quad_segs_for(0.5, 0.01)
    (20, 14, 8)
    """
    r, tol = float(radius_mm), float(tolerance_mm) / 4
    if r <= tol:
        return 1
    return max(2, math.ceil(math.pi / (4 * math.acos(1 - tol / r))))


@dataclass
class OpenedRegion:
    """What :func:`open_region` made of a region.

    ``region`` is the part as the tool makes it; ``vanished`` the count of holes
    the tool cannot enter (``vanished_holes`` their nominal polygons);
    ``corners`` the corners that moved more than :data:`VISIBLE_MM` (shapely
    Points on the nominal boundary) and ``moved`` how far each moved (mm).
    """

    region: BaseGeometry
    radius_mm: float
    holes: int = 0
    vanished: int = 0
    vanished_holes: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=object))
    corners: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=object))
    moved: np.ndarray = field(default_factory=lambda: np.empty(0))
    closed_shells: int = 0


def _holes(parts: np.ndarray):
    nholes = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), nholes)
    idx = np.concatenate([np.arange(k) for k in nholes]) if len(parts) else np.empty(0, int)
    return shapely.polygons(shapely.get_interior_ring(parts[owner], idx)), owner


def _opening(polys: np.ndarray, r: float, q: int) -> np.ndarray:
    """``polys`` opened by ``r`` (round joins), empty where a disc of radius ``r`` does not fit.

    Polygons whose bounding box is narrower than ``2 r`` cannot hold the disc: they
    are not buffered at all (most of the small holes of a panel).
    """
    out = np.full(len(polys), shapely.Polygon(), dtype=object)
    if not len(polys):
        return out
    b = shapely.bounds(polys)
    fits = np.minimum(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]) > 2 * r
    if fits.any():
        eroded = shapely.buffer(polys[fits], -r, quad_segs=q)
        # (the eroded arcs' chords let the bit reach past a corner of material by at most the chord
        # error, tolerance_mm / 4: clipping that off would leave notches of a few micrometres)
        out[fits] = shapely.buffer(eroded, r, quad_segs=q)
    return out


def _moved(points: np.ndarray, targets: np.ndarray, boundary: bool) -> np.ndarray:
    """How far each point is from its target geometry (its boundary when ``boundary``)."""
    if not len(points):
        return np.empty(0)
    return shapely.distance(points, shapely.boundary(targets) if boundary else targets)


def open_region(region, *, radius_mm: float, tolerance_mm: float = 0.01) -> OpenedRegion:
    """``region`` (the material) as a tool of radius ``radius_mm`` cuts it (see the module text).

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The nominal material (mm).
    radius_mm : float
        The tool's radius, > 0.
    tolerance_mm : float
        Chord error of the rounded corners (the arcs are flattened within a quarter of it,
        :func:`quad_segs_for`); holes with less area than its square are noise.

    Returns
    -------
    OpenedRegion
    """
    r = float(radius_mm)
    if not math.isfinite(r) or r <= 0:
        raise ParameterError(f"the tool radius must be > 0 mm, got {radius_mm!r}", param="tool_diameter_mm")
    q = quad_segs_for(r, tolerance_mm)
    parts = shapely.get_parts(region)
    parts = parts[~shapely.is_empty(parts)]
    shells = shapely.polygons(shapely.get_exterior_ring(parts))
    nested = _nested(shells)
    if nested.any():
        return _open_general(region, parts, r, q, tolerance_mm)
    holes, owner = _holes(parts)
    real = shapely.area(holes) > float(tolerance_mm) ** 2
    holes, owner = holes[real], owner[real]
    opened = _opening(holes, r, q)
    gone = shapely.is_empty(opened)
    # the outer rings: convex ones stay as they are; the others are closed (concave corners filled)
    concave = shapely.area(shapely.convex_hull(shells)) - shapely.area(shells) > float(tolerance_mm) ** 2
    made_shells = shells.copy()
    if concave.any():
        closed = shapely.buffer(shapely.buffer(shells[concave], r, quad_segs=q), -r, quad_segs=q)
        # a closing only adds material; the union keeps convex corners exactly where they were
        made_shells[concave] = shapely.union(shells[concave], closed)
    pieces, which = shapely.get_parts(opened, return_index=True)
    real_piece = (shapely.get_type_id(pieces) == 3) & ~shapely.is_empty(pieces)
    pieces, which = pieces[real_piece], which[real_piece]
    if len(pieces) and (shapely.get_num_interior_rings(pieces) > 0).any():
        return _open_general(region, parts, r, q, tolerance_mm)
    if concave.any() and _overlap(made_shells):  # closed outer rings that now meet: overlay
        return _open_general(region, parts, r, q, tolerance_mm)
    rings = np.concatenate([shapely.get_exterior_ring(made_shells), shapely.get_exterior_ring(pieces)])
    index = np.concatenate([np.arange(len(parts)), owner[which]])
    order = np.argsort(index, kind="stable")  # each part's outer ring first, then its holes
    made = shapely.polygons(rings[order], indices=index[order])
    out = made[0] if len(made) == 1 and region.geom_type == "Polygon" else shapely.multipolygons(made)
    # where the design changes: the corners of the holes kept, and of the closed outer rings
    kept = np.flatnonzero(~gone)
    coords, at = shapely.get_coordinates(holes[kept], return_index=True)
    points = shapely.points(coords)
    moved = _moved(points, opened[kept][at], boundary=False)
    if concave.any():
        scoords, sat = shapely.get_coordinates(shapely.get_exterior_ring(shells[concave]), return_index=True)
        spoints = shapely.points(scoords)
        points = np.concatenate([points, spoints])
        moved = np.concatenate([moved, _moved(spoints, made_shells[concave][sat], boundary=True)])
    corners, moved = _corners(points, moved)
    return OpenedRegion(out, r, len(holes), int(gone.sum()), holes[gone], corners, moved, int(concave.sum()))


def _corners(points: np.ndarray, moved: np.ndarray):
    """The points that moved more than :data:`VISIBLE_MM`, one per place (rings repeat their first point)."""
    far = moved > VISIBLE_MM
    points, moved = points[far], moved[far]
    if not len(points):
        return points, moved
    xy = np.round(shapely.get_coordinates(points), 6)
    _, first = np.unique(xy, axis=0, return_index=True)
    first.sort()
    return points[first], moved[first]


def _overlap(shells: np.ndarray) -> bool:
    """Whether any of ``shells`` is not one simple polygon, or two of them intersect."""
    if (shapely.get_type_id(shells) != 3).any() or (shapely.get_num_interior_rings(shells) > 0).any():
        return True
    a, b = shapely.STRtree(shells).query(shells, predicate="intersects")
    return bool((a != b).any())


def _nested(shells: np.ndarray) -> np.ndarray:
    """True for each part lying inside another part's outer ring (an island in a hole)."""
    if len(shells) < 2:
        return np.zeros(len(shells), dtype=bool)
    a, b = shapely.STRtree(shells).query(shells, predicate="within")
    out = np.zeros(len(shells), dtype=bool)
    out[a[a != b]] = True
    return out


def _open_general(region, parts, r, q, tolerance_mm) -> OpenedRegion:
    """The same by overlay, for regions with islands in holes (or holes whose opening has holes).

    The free space around the material (a frame ``2 r`` wider than the region, less the
    material) is opened as a whole: islands, the holes around them and the outer
    rings all come out right. Slower (one overlay of every hole), so used only then.
    """
    xmin, ymin, xmax, ymax = region.bounds
    pad = 2 * r + 1.0
    frame = shapely.box(xmin - pad, ymin - pad, xmax + pad, ymax + pad)
    free = shapely.difference(frame, region)
    opened_free = shapely.buffer(shapely.buffer(free, -r, quad_segs=q), r, quad_segs=q)
    # what is left of the frame, inside the region's hull (the closing of an outer ring stays in it)
    made = shapely.intersection(shapely.difference(frame, opened_free), shapely.convex_hull(region))
    made = shapely.union_all([g for g in shapely.get_parts(made) if g.geom_type == "Polygon"])
    holes, _ = _holes(parts)
    holes = holes[shapely.area(holes) > float(tolerance_mm) ** 2]
    gone = ~shapely.intersects(holes, opened_free) if len(holes) else np.zeros(0, bool)
    rings = shapely.get_rings(parts)
    coords, _ = shapely.get_coordinates(rings, return_index=True)
    points = shapely.points(coords)
    moved = shapely.distance(points, shapely.boundary(made)) if len(points) else np.empty(0)
    corners, moved = _corners(points, moved)
    return OpenedRegion(made, r, len(holes), int(gone.sum()), holes[gone], corners, moved, 0)


def check_tool(region, profile, *, fill_small_holes: bool = False, report: Report | None = None):
    """Open ``region`` by the profile's tool and report where the design changes: ``(made region, report, filled)``.

    ``small_hole``: the holes the tool cannot enter, at their widest point with their
    width (with ``fill_small_holes`` they are counted in ``filled`` instead: they are
    material in the file either way). ``rounded_corner``: every corner that moves by
    more than :data:`VISIBLE_MM`, with how far it moves. A tool that can enter no hole
    of a design that has holes is a :class:`~fabtiles.ParameterError`: the file
    would be a blank.
    """
    cutter = profile.cutter
    cutter.check_profile(profile)
    report = report if report is not None else Report(path="", format="laser")
    r = profile.tool_radius_mm
    made = open_region(region, radius_mm=r, tolerance_mm=profile.tolerance_mm)
    key = cutter.tool_key
    if made.holes and made.vanished == made.holes:
        _, widths = hole_widths(made.vanished_holes, tolerance_mm=profile.tolerance_mm)
        raise ParameterError(
            f"{key} = {2 * r:g} mm of {profile.kind} profile {profile.name!r} is wider than every hole of the "
            f"design (the widest is {distinct(widths.max(), 2 * r)} mm): the tool can cut none of its {made.holes:,} "
            f"holes; use a tool narrower than {distinct(widths.max(), 2 * r)} mm, or a larger packing radius or "
            "thinner stroke",
            param=key,
        )
    filled = 0
    if made.vanished:
        if fill_small_holes:
            filled = made.vanished
        else:
            add_small_holes(
                report,
                made.vanished_holes,
                tolerance_mm=profile.tolerance_mm,
                message=lambda n, w: (
                    f"{n:,} hole{'s' if n > 1 else ''} narrower than {cutter.tool_name(profile)} (narrowest "
                    f"{distinct(w, 2 * r)} mm): the tool cannot enter them, so they stay material; "
                    "fill_small_holes = true counts them as filled"
                ),
                limit_mm=2 * r,
            )
    if len(made.corners):
        n = len(made.corners)
        report.add(
            "rounded_corner",
            f"{n:,} corner{'s' if n > 1 else ''} rounded to the tool's radius r = {r:g} mm by "
            f"{cutter.tool_name(profile)}, moved by more than {VISIBLE_MM:g} mm "
            f"(up to {distinct(made.moved.max(), VISIBLE_MM)} "
            "mm); the file holds the rounded part",
            count=n,
            locations=locations(made.corners),
            sizes=made.moved[:MAX_LOCATIONS].round(3),
            worst=round(float(made.moved.max()), 3),
            limit=VISIBLE_MM,
        )
    report.stats["tool_radius_mm"] = r
    report.stats["tool_removed_holes"] = made.vanished
    return made.region, report, filled
