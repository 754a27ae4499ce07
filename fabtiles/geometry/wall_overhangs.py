"""Overhangs of the openings in a wall printed upright, and pointed tops that need no support.

A cylinder (a lampshade, a texture roller) prints standing on its end, so the pattern's unrolled
strip is a vertical wall: x around the circumference, y up the axis, the first layer at the
bottom. Every opening in that wall (a hole through a pierced shade, a deboss's groove) has a
*ceiling*: the stretches of its edge with material above and the opening below. A layer laid
there rests on the one below only where the edge is steep; where the edge leans further from
vertical than the printer's ``max_overhang_deg``, it is laid over air.

What :func:`check_wall_overhangs` promises, for the material ``region`` of a strip with y up:
every edge of an opening with material above it either leans at most ``max_overhang_deg`` from
vertical (within :data:`ANGLE_TOLERANCE_DEG`), or belongs to a *ceiling stretch* (a run of such
flatter edges along the opening's edge, see :func:`wall_ceilings`) no wider than the printer's
``max_bridge_mm``: the printer bridges that stretch from its two ends, as it bridges the top of a
small round hole. Every wider stretch is one place of the ``overhang`` finding, located at its
middle, with its width. The check is of the 2D strip, edge by edge: it does not slice, and a
stretch counts as bridged by its width alone (a stretch held at one end only, a star point's upper
edge, is judged as if held at both).

A deboss's groove is backed by the plate: its ceiling steps out by the groove's depth in one
layer, held at the back and at both ends. A groove no deeper than one layer's step at the limit
(``layer_height_mm * tan(max_overhang_deg)``) is no overhang at all; a deeper one is judged as a
hole's. A relief (a texture roller) is the same with the gaps between its raised bands as the
openings: the underside of a band steps out by the relief's height over the plate.

:func:`pointed_tops` raises every ceiling stretch into a peak whose two sides lean
:data:`PEAK_MARGIN_DEG` inside ``max_overhang_deg`` from vertical, as makers draw a teardrop over a
round hole: after it, the check finds only the peaks it had to clip to keep ``min_wall_mm`` of
material, which it lists.

>>> import shapely
>>> wall = shapely.box(0, 0, 30, 30).difference(shapely.Point(15, 15).buffer(5, quad_segs=16))
>>> found = wall_ceilings(wall, overhang_deg=45)
>>> len(found), round(float(found.span_mm[0]), 2)
(1, 7.07)
>>> raised = pointed_tops(wall, overhang_deg=45, min_wall_mm=0.8)
>>> raised.raised, raised.clipped, len(wall_ceilings(raised.region, overhang_deg=45))
(1, 0, 0)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from ..core.errors import ParameterError
from ..core.report import Report, distinct
from ..machines.profiles import load_profile
from .narrow import MAX_LOCATIONS

ANGLE_TOLERANCE_DEG = 0.5
"""An edge leaning at most this much beyond the limit counts as at the limit: the peaks' own sides
lie exactly on it, and a polygon's rounding moves them by less."""

POINT_TOLERANCE_MM = 1e-4
"""Points of an opening's edge closer than this are one: an overlay's hairs have no direction."""

OVERLAP_MM = 1e-5
"""The peaks are taken this much larger than drawn (:func:`pointed_tops`): far below
:data:`POINT_TOLERANCE_MM`, far above a rounding."""

AREA_TOLERANCE_MM2 = 1e-4
"""Openings, and pieces of the material left by the peaks, of less area than this are slivers of
the geometry."""

PEAK_MARGIN_DEG = 1.0
"""The peaks' sides lean this much less than the printer's limit, and every edge beyond the limit
less this is raised: a slicer given the same limit as its support threshold supports a face that
leans at exactly it (docs/surfaces.md gives the slicer's figures)."""

QUAD_SEGS = 8
"""Segments of a quarter circle in the room kept around the other openings."""

BUFFER_SIMPLIFY = 0.011
"""GEOS thins a geometry within 1 % of the buffer's distance before it buffers it (its
``simplify_factor``), so a buffer may come that much closer: the room is grown by a little more."""


@dataclass(frozen=True)
class Ceilings:
    """The ceiling stretches of a wall's openings flatter than the limit (:func:`wall_ceilings`).

    One entry per stretch, in the strip's coordinates (y up): the line along the opening's edge
    (shapely LineString, from its right end to its left), its width along x (mm), and the opening it
    belongs to (an index into ``openings``, the strip's openings as polygons; a periodic strip's
    opening across the seam is whole, in the copy that starts inside the strip).
    """

    lines: np.ndarray
    span_mm: np.ndarray
    owner: np.ndarray
    openings: np.ndarray

    def __len__(self) -> int:
        return len(self.lines)

    def middles(self, period_mm: float | None = None, x0: float = 0.0) -> np.ndarray:
        """Each stretch's middle point along its edge, as ``(n, 2)`` coordinates; with ``period_mm``,
        x brought into ``[x0, x0 + period_mm)``."""
        if not len(self.lines):
            return np.empty((0, 2))
        xy = shapely.get_coordinates(shapely.line_interpolate_point(self.lines, 0.5, normalized=True))
        if period_mm is not None:
            xy[:, 0] = x0 + np.mod(xy[:, 0] - x0, period_mm)
        return xy


@dataclass(frozen=True)
class PointedTops:
    """The result of :func:`pointed_tops`."""

    region: object
    """The material with every raised peak taken out of it (shapely Polygon or MultiPolygon)."""
    raised: int
    """How many ceiling stretches were raised into a peak (clipped ones included)."""
    clipped: int
    """How many peaks were cut short to keep ``min_wall_mm`` of material from another opening, a peak
    raised before or the strip's edge; their tops may still overhang (the check says where)."""
    clipped_at: tuple[tuple[float, float], ...]
    """The middle of each clipped peak's ceiling stretch."""
    removed_mm2: float
    """The material the peaks took (mm^2)."""


def _check_angle(overhang_deg: float) -> float:
    if isinstance(overhang_deg, bool) or not isinstance(overhang_deg, (int, float)) or not 0 < overhang_deg < 90:
        raise ParameterError(
            f"overhang_deg must be a number of degrees from vertical, > 0 and < 90, got {overhang_deg!r}"
        )
    return float(overhang_deg)


def _check_length(name: str, value: float, *, allow_zero: bool = True) -> float:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or value < 0 or (value == 0 and not allow_zero):
        raise ParameterError(f"{name} must be a finite number of mm {'>= 0' if allow_zero else '> 0'}, got {value!r}")
    return float(value)


def _strip(region, outline, period_mm):
    """The openings, the domain they were cut from, and which of them to judge.

    A periodic strip's openings are laid three times side by side, those at the seam joined to
    their copies a turn on, so an opening across the seam is whole; the openings judged are those
    whose leftmost point lies in ``(x0, x0 + period]``, one copy of each (the others are neighbours).
    """
    if outline is None:
        outline = shapely.box(*region.bounds)
    x0, y0, x1, y1 = outline.bounds
    openings = shapely.get_parts(shapely.difference(outline, region))
    openings = openings[(shapely.get_type_id(openings) == 3) & (shapely.area(openings) > AREA_TOLERANCE_MM2)]
    if period_mm is None:
        return openings, outline, np.ones(len(openings), bool)
    p = _check_length("period_mm", period_mm, allow_zero=False)
    if abs((x1 - x0) - p) > 1e-6 * max(1.0, p):
        raise ParameterError(
            f"period_mm = {p:g} mm must be the strip's width along x ({x1 - x0:g} mm): the strip is one turn"
        )
    eps = 1e-9 * max(1.0, p)
    b = shapely.bounds(openings)
    seam = (b[:, 0] <= x0 + eps) | (b[:, 2] >= x1 - eps)
    copies = [shapely.transform(openings, lambda xy, k=k: xy + [k * p, 0.0]) for k in (-1, 0, 1)]
    # only the openings at the seam are joined to their copies a turn on; the others stay as they are
    across = shapely.get_parts(shapely.union_all(np.concatenate([c[seam] for c in copies])))
    joined = np.concatenate([*(c[~seam] for c in copies), across])
    joined = joined[(shapely.get_type_id(joined) == 3) & (shapely.area(joined) > AREA_TOLERANCE_MM2)]
    domain = shapely.box(x0 - p, y0, x1 + p, y1)
    left = shapely.bounds(joined)[:, 0]
    return joined, domain, (left > x0 + eps) & (left <= x0 + p + eps)


def _stretches(polygon, domain_edge, flat_below: float):
    """The ceiling stretches of one opening: lists of ``(n, 2)`` points from right to left."""
    polygon = shapely.orient_polygons(polygon)  # the opening on the left of every ring
    out = []
    for ring in shapely.get_rings(polygon):
        xy = shapely.get_coordinates(shapely.remove_repeated_points(ring, POINT_TOLERANCE_MM))
        if len(xy) < 4:
            continue
        d = np.diff(xy, axis=0)
        # material on the right, so above when the edge runs towards -x; how far it leans from vertical
        lean = np.degrees(np.arctan2(np.abs(d[:, 0]), np.abs(d[:, 1])))
        over = (d[:, 0] < 0) & (lean > flat_below)
        if over.any():
            mids = shapely.points((xy[:-1] + xy[1:]) / 2)
            on_edge = shapely.dwithin(mids, domain_edge, POINT_TOLERANCE_MM)
            over &= ~on_edge
        if not over.any():
            continue
        # runs of consecutive flat edges, the ring read from an edge that is not one
        start = int(np.flatnonzero(~over)[0]) + 1
        order = (np.arange(len(over)) + start) % len(over)
        flags = over[order]
        k = 0
        while k < len(flags):
            if not flags[k]:
                k += 1
                continue
            j = k
            while j < len(flags) and flags[j]:
                j += 1
            edges = order[k:j]
            pts = np.vstack([xy[edges], xy[edges[-1] + 1]])
            out.append(pts)
            k = j
    return out


def wall_ceilings(region, *, overhang_deg: float = 45.0, outline=None, period_mm: float | None = None) -> Ceilings:
    """Every ceiling stretch of the openings in a wall printed upright that leans beyond ``overhang_deg``.

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The wall's material in the strip's coordinates, y up (the first layer at the lowest y): a
        pierced wall's material, a debossed wall's plate less its grooves, or a relief's raised
        pattern.
    overhang_deg : float
        The printer's limit, degrees from vertical, > 0 and < 90.
    outline : shapely Polygon, optional
        The strip; its edges are no opening's ceiling. Default: the region's bounding box.
    period_mm : float, optional
        The strip is one turn of a cylinder, its pattern periodic in x with this period (the
        outline's width): an opening across the seam is judged whole, once.

    Returns
    -------
    Ceilings
        A stretch is a maximal run of an opening's edges, along its ring, each with material above
        and leaning more than ``overhang_deg + ANGLE_TOLERANCE_DEG`` from vertical; each runs in x
        one way, so its width is its x extent.

    Raises
    ------
    ParameterError
        ``overhang_deg`` outside (0, 90), ``period_mm`` not a positive length or not the outline's width.
    """
    limit = _check_angle(overhang_deg)
    openings, domain, kept = _strip(region, outline, period_mm)
    edge = shapely.boundary(domain)
    lines, owner = [], []
    for i in np.flatnonzero(kept):
        for pts in _stretches(openings[i], edge, limit + ANGLE_TOLERANCE_DEG):
            lines.append(shapely.linestrings(pts))
            owner.append(i)
    lines_a = np.array(lines, dtype=object)
    span = np.array([np.ptp(shapely.get_coordinates(g)[:, 0]) for g in lines], dtype=float)
    return Ceilings(lines_a, span, np.array(owner, dtype=int), openings)


WALL_OPENINGS = {
    "pierced": ("a hole through the wall", "holes through the wall"),
    "deboss": ("a groove", "grooves"),
    "relief": ("a gap in the raised pattern", "gaps in the raised pattern"),
}
"""What a wall's openings are, by print style (a pierced wall's go through it; the others' are backed)."""


def check_wall_overhangs(
    region,
    profile,
    *,
    style: str = "pierced",
    depth_mm: float | None = None,
    outline=None,
    period_mm: float | None = None,
    report: Report | None = None,
) -> Report:
    """Report the ``overhang`` finding: ceiling stretches a printer neither prints nor bridges.

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The wall's material, y up (see :func:`wall_ceilings`).
    profile : str, Path or PrinterProfile
        Its ``max_overhang_deg`` is the limit, its ``max_bridge_mm`` the widest stretch bridged.
    style : {"pierced", "deboss", "relief"}
        What the openings are: holes through the wall, grooves, or gaps between raised bands.
    depth_mm : float, optional
        A deboss's or a relief's openings: how deep they go into the wall, backed by it (mm, > 0);
        default the profile's ``deboss_mm`` or ``relief_mm``. Openings no deeper than
        ``layer_height_mm * tan(max_overhang_deg)`` have no overhang.
    outline, period_mm : optional
        As for :func:`wall_ceilings`.
    report : Report, optional
        Added to and returned; a new one (path ``""``) otherwise.

    Returns
    -------
    Report
        With one ``overhang`` finding when a stretch is wider than ``max_bridge_mm``: its count,
        the stretches' middles as locations (x within the period), their widths as sizes, the widest
        as ``worst`` and ``max_bridge_mm`` as the limit.

    Raises
    ------
    ParameterError
        A style that is none of these, a depth for a pierced wall, a depth not > 0.

    >>> import shapely
    >>> wall = shapely.box(0, 0, 40, 30).difference(shapely.box(10, 10, 30, 14))
    >>> print(check_wall_overhangs(wall, "fdm-0.4mm").findings[0].message)  # doctest: +NORMALIZE_WHITESPACE
    1 ceiling of a hole through the wall leans more than max_overhang_deg = 45 degrees from vertical
    over 20 mm, wider than max_bridge_mm = 5 mm: the printer lays it over air, where it sags or
    fails without support; pointed tops, a peak at the limit over each, print without it
    """
    profile = load_profile(profile, kind="printer")
    if style not in WALL_OPENINGS:
        raise ParameterError(f"style must be one of: {', '.join(WALL_OPENINGS)}, got {style!r}")
    if style == "pierced" and depth_mm is not None:
        raise ParameterError(
            f"depth_mm = {depth_mm!r} is for a deboss or a relief: a pierced wall's holes go through it"
        )
    report = report if report is not None else Report(path="", format="print")
    limit = profile.max_overhang_deg
    if style != "pierced":
        given = depth_mm if depth_mm is not None else getattr(profile, f"{style}_mm")
        depth = _check_length("depth_mm", given, allow_zero=False)
        if depth <= profile.layer_height_mm * math.tan(math.radians(limit)) * (1 + 1e-9):
            return report
    found = wall_ceilings(region, overhang_deg=limit, outline=outline, period_mm=period_mm)
    wide = found.span_mm > profile.max_bridge_mm * (1 + 1e-9)
    n = int(wide.sum())
    if not n:
        return report
    x0 = (outline if outline is not None else shapely.box(*region.bounds)).bounds[0]
    where = found.middles(period_mm, x0)[wide]
    spans = found.span_mm[wide]
    order = np.argsort(-spans, kind="stable")
    one, many = WALL_OPENINGS[style]
    bridge = profile.max_bridge_mm
    widest = float(spans.max())
    lean = f"more than max_overhang_deg = {limit:g} degrees from vertical"
    wider = f"wider than max_bridge_mm = {bridge:g} mm"
    head = (
        f"1 ceiling of {one} leans {lean} over {distinct(widest, bridge)} mm, {wider}: the printer lays it over "
        "air, where it sags or fails"
        if n == 1
        else f"{n:,} ceilings of {many} lean {lean} over up to {distinct(widest, bridge)} mm, {wider}: the "
        "printer lays them over air, where they sag or fail"
    )
    report.add(
        "overhang",
        f"{head} without support; pointed tops, a peak at the limit over each, print without it",
        count=n,
        locations=np.round(where[order][:MAX_LOCATIONS], 3),
        sizes=spans[order][:MAX_LOCATIONS].round(3),
        worst=round(widest, 3),
        limit=bridge,
    )
    return report


def _peak(pts: np.ndarray, slope: float):
    """The triangle over a stretch (right to left) under the two lines at the limit from its ends."""
    (xr, yr), (xl, yl) = pts[0], pts[-1]
    xa = (yr - yl + slope * (xr + xl)) / (2 * slope)
    ya = yl + slope * (xa - xl)
    return shapely.polygons(np.vstack([pts, [[xa, ya]], pts[:1]]))


def _shadow(block, top: float):
    """``block`` swept straight up to ``top``: what lies above it is cut off from below by it."""
    polys = shapely.get_parts(block)
    polys = polys[shapely.get_type_id(polys) == 3]
    if not len(polys):
        return block
    xy = shapely.get_coordinates(shapely.get_rings(polys), return_index=False)
    idx = shapely.get_coordinates(shapely.get_rings(polys), return_index=True)[1]
    a, b = xy[:-1], xy[1:]
    same = idx[:-1] == idx[1:]  # edges within a ring, not from one ring's end to the next's start
    a, b = a[same], b[same]
    a, b = a[np.abs(b[:, 0] - a[:, 0]) > 1e-12], b[np.abs(b[:, 0] - a[:, 0]) > 1e-12]
    quads = np.stack([a, b, np.c_[b[:, 0], np.full(len(b), top)], np.c_[a[:, 0], np.full(len(a), top)]], axis=1)
    quads = shapely.polygons(quads)
    return shapely.union_all(np.concatenate([polys, quads[shapely.area(quads) > 0]]))


def pointed_tops(
    region,
    *,
    overhang_deg: float = 45.0,
    min_wall_mm: float = 0.8,
    max_bridge_mm: float = 0.0,
    outline=None,
    period_mm: float | None = None,
) -> PointedTops:
    """The wall's material with every overhanging ceiling of its openings raised into a peak.

    Each ceiling stretch (:func:`wall_ceilings`, of the limit less :data:`PEAK_MARGIN_DEG`) wider
    than ``max_bridge_mm`` becomes the floor of a peak: the triangle between the stretch and the two
    lines that rise from its ends, leaning that much from vertical towards each other. A round hole
    becomes the classic teardrop (the lines are tangent to it where its edge leans at that angle); a
    star's opening gains a peak over each point's upper edge, which trims the material wedge
    between two points. Every new edge leans inside the limit by the margin or is an edge of the
    opening already printable.

    A peak keeps ``min_wall_mm`` of material from every other opening, from the peaks already
    raised (the lowest stretches first, as they print) and from the strip's edge (a periodic
    strip's top and bottom; else the outline's). Where a full peak would come closer, it is cut
    back to that distance, and nothing of it above the cut is taken either, so a peak never goes
    round another opening (which would leave that opening in a loose ring); such a peak is counted
    in ``clipped``, and its cut top may still overhang (the check says where). A peak may come
    closer than ``min_wall_mm`` to its own opening's other edges: that leaves a sharp tip of
    material, as a star's points do; a piece that two peaks cut off a part of the material,
    narrower than ``min_wall_mm``, goes with them (loose, it would fall out of a pierced wall).

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The wall's material, y up (see :func:`wall_ceilings`).
    overhang_deg : float
        The printer's limit, degrees from vertical (> 0, < 90): a profile's ``max_overhang_deg``.
    min_wall_mm : float
        Material left between a peak and another opening (mm, >= 0): a profile's ``min_wall_mm``.
    max_bridge_mm : float
        Stretches no wider than this are left flat, for the printer to bridge (mm, >= 0; default 0:
        every stretch is raised).
    outline, period_mm : optional
        As for :func:`wall_ceilings`; with ``period_mm`` a peak across the seam is taken from both
        ends of the strip.

    Raises
    ------
    ParameterError
        A limit, wall or bridge out of its range (the message names it), or a bad ``period_mm``.
    """
    # the peaks lean a little inside the limit: a slicer given the same limit supports a face at it
    limit = _check_angle(overhang_deg)
    limit -= min(PEAK_MARGIN_DEG, limit / 2)
    wall = _check_length("min_wall_mm", min_wall_mm)
    bridge = _check_length("max_bridge_mm", max_bridge_mm)
    found = wall_ceilings(region, overhang_deg=limit, outline=outline, period_mm=period_mm)
    strip = outline if outline is not None else shapely.box(*region.bounds)
    todo = np.flatnonzero(found.span_mm > bridge * (1 + 1e-9))
    if not len(todo):
        return PointedTops(region, 0, 0, (), 0.0)
    slope = 1 / math.tan(math.radians(limit))
    room = _Room(found.openings, strip, wall, period_mm, capacity=len(todo))
    kept: list = []
    clipped = np.zeros(len(todo), bool)
    low = shapely.bounds(found.lines[todo])[:, 1]
    for k in np.argsort(low, kind="stable"):  # the lowest first, as they print
        stretch, own = found.lines[todo[k]], int(found.owner[todo[k]])
        peak = _peak(shapely.get_coordinates(stretch), slope)
        base = shapely.difference(peak, found.openings[own])
        pieces = room.cut(base, peak, stretch, own)
        # cut back by any real area
        clipped[k] = float(shapely.area(pieces).sum()) < float(shapely.area(base)) * (1 - 1e-9) - 1e-9
        if len(pieces):
            kept.extend(pieces)
            room.add(pieces, own)
    out = _without(region, shapely.union_all(kept) if kept else shapely.Polygon(), strip, period_mm, wall)
    where = found.middles(period_mm, strip.bounds[0])[todo][clipped]
    return PointedTops(
        out,
        len(todo),
        int(clipped.sum()),
        tuple((float(round(x, 3)), float(round(y, 3))) for x, y in where),
        float(shapely.area(region) - shapely.area(out)),
    )


class _Room:
    """The room a peak keeps: ``wall`` from the other openings, from the peaks raised so far and from
    the strip's edge (a periodic strip's top and bottom)."""

    def __init__(self, openings, strip, wall: float, period_mm, *, capacity: int):
        x0, y0, x1, y1 = strip.bounds
        if period_mm is None:
            self.inner = shapely.buffer(strip, -wall, join_style="mitre") if wall else strip
        else:  # the strip goes on in x: only its top and bottom are edges
            self.inner = shapely.box(x0 - 3 * period_mm, y0 + wall, x1 + 3 * period_mm, y1 - wall)
        # the buffer's polygon circumscribes the true offset, so no chord of it comes closer than
        # ``wall``, and GEOS simplifies the input by 1 % of the distance before it offsets it
        self.grow = wall * (1 / math.cos(math.pi / 4 / QUAD_SEGS) + BUFFER_SIMPLIFY)
        self.grown = shapely.buffer(openings, self.grow, quad_segs=QUAD_SEGS) if wall else openings
        self.tree = shapely.STRtree(self.grown)
        # the peaks raised so far, a periodic strip's also a turn either way, their bounds grown
        self.turns = (0.0,) if period_mm is None else (-period_mm, 0.0, period_mm)
        size = capacity * len(self.turns)
        self.peaks = np.empty(size, dtype=object)
        self.owner = np.empty(size, dtype=int)
        self.bounds = np.empty((size, 4))
        self.n = 0
        self.wall = wall

    def blocks(self, peak, own: int) -> list:
        """What of the room lies in ``peak``'s way: the others' grown openings and peaks, the edge."""
        out = [self.grown[o] for o in self.tree.query(peak, predicate="intersects") if o != own]
        if self.n:
            b, (px0, py0, px1, py1) = self.bounds[: self.n], peak.bounds
            near = (b[:, 0] <= px1) & (b[:, 2] >= px0) & (b[:, 1] <= py1) & (b[:, 3] >= py0)
            for i in np.flatnonzero(near & (self.owner[: self.n] != own)):
                if shapely.dwithin(self.peaks[i], peak, self.grow):  # grown only when it is that near
                    out.append(shapely.buffer(self.peaks[i], self.grow, quad_segs=QUAD_SEGS))
        if not shapely.contains_properly(self.inner, peak):
            out.append(shapely.difference(peak, self.inner))
        return out

    def cut(self, base, peak, stretch, own: int) -> np.ndarray:
        """The pieces of ``base`` (the peak less its opening) over ``stretch`` clear of the room,
        nothing above a block taken."""
        cut = base
        blocks = self.blocks(peak, own)
        if blocks:
            # a hair beyond the peak, so that no edge of the cut runs along the stretch a rounding off it
            block = shapely.intersection(
                shapely.union_all(blocks), shapely.buffer(peak, OVERLAP_MM, join_style="mitre")
            )
            if not block.is_empty:
                cut = shapely.difference(base, _shadow(block, max(peak.bounds[3], block.bounds[3])))
        pieces = shapely.get_parts(cut)
        pieces = pieces[(shapely.get_type_id(pieces) == 3) & (shapely.area(pieces) > 0)]
        return pieces[shapely.dwithin(pieces, stretch, 1e-6)]

    def add(self, pieces: np.ndarray, own: int) -> None:
        """Keep later peaks of other openings clear of these pieces of ``own``'s peak."""
        if not self.wall:
            return
        g = pieces[0] if len(pieces) == 1 else shapely.union_all(pieces)
        for t in self.turns:
            moved = g if t == 0 else shapely.transform(g, lambda xy, t=t: xy + [t, 0.0])
            mx0, my0, mx1, my1 = moved.bounds
            self.peaks[self.n], self.owner[self.n] = moved, own if t == 0 else -1
            self.bounds[self.n] = (mx0 - self.grow, my0 - self.grow, mx1 + self.grow, my1 + self.grow)
            self.n += 1


def _without(region, taken, strip, period_mm, wall: float = 0.0):
    """``region`` less the peaks ``taken`` (a periodic strip's brought back into it from a turn on), and less
    the pieces the peaks cut off a part of it narrower than ``wall`` (a star's tip between two peaks of its
    opening: loose, it would fall out of a pierced wall, and no disc of ``wall`` fits in it to print)."""
    # grown by a hair: where a peak's computed corner lies a rounding off its opening's edge, the
    # difference would leave a sliver of material there with a ceiling of its own (grown before a periodic
    # strip's are brought back into it, so that what the hair reaches beyond one end is taken at the other)
    taken = shapely.buffer(taken, OVERLAP_MM, join_style="mitre")
    if period_mm is not None:
        x0, y0, x1, y1 = strip.bounds
        pieces = [shapely.intersection(taken, shapely.box(x0, y0, x1, y1))]
        for lo, shift in ((x1, -period_mm), (x0 - period_mm, period_mm)):
            on = shapely.transform(
                shapely.intersection(taken, shapely.box(lo, y0, lo + period_mm, y1)), lambda xy, d=shift: xy + [d, 0.0]
            )
            if not on.is_empty:
                # a turn back moves a point by a rounding: its edges meet the strip's again when snapped to
                # them (only the strip's material near them, for speed)
                near = shapely.intersection(region, shapely.box(*shapely.buffer(on, 1.0).bounds))
                pieces.append(shapely.snap(on, near, POINT_TOLERANCE_MM))
        taken = shapely.union_all(pieces)
    out = shapely.difference(region, taken)
    parts = shapely.get_parts(out)
    # a part at a periodic strip's end may go on across the seam: never dropped, so that both ends meet
    ends = np.zeros(len(parts), bool)
    if period_mm is not None and len(parts):
        x0, _, x1, _ = strip.bounds
        b = shapely.bounds(parts)
        ends = (b[:, 0] <= x0 + POINT_TOLERANCE_MM) | (b[:, 2] >= x1 - POINT_TOLERANCE_MM)
    if len(parts) > 1:  # an overlay's slivers along the peaks' floors
        keep = ends | (shapely.area(parts) > AREA_TOLERANCE_MM2)
        parts, ends = parts[keep], ends[keep]
    parts = parts[ends | ~_cut_off(parts, shapely.get_parts(region), wall)]
    return parts[0] if len(parts) == 1 else shapely.multipolygons(parts)


def _cut_off(parts, before, wall: float):
    """Which ``parts`` are pieces the peaks cut off a part of ``before`` narrower than ``wall``: all but its
    largest piece, and that one too where the part was not so narrow (the peaks left crumbs of it)."""
    if wall <= 0:
        return np.zeros(len(parts), bool)
    owner = np.full(len(parts), -1)
    inside, of = shapely.STRtree(before).query(shapely.point_on_surface(parts), predicate="intersects")
    owner[inside] = of
    area = shapely.area(parts)
    largest = np.zeros(len(parts), bool)
    for k in np.unique(owner[owner >= 0]).tolist():
        mine = np.flatnonzero(owner == k)
        largest[mine[np.argmax(area[mine])]] = True
    narrow = shapely.is_empty(shapely.buffer(parts, -wall / 2, quad_segs=2))
    was_narrow = np.ones(len(parts), bool)
    if (narrow & largest).any():
        was_narrow[owner >= 0] = shapely.is_empty(shapely.buffer(before, -wall / 2, quad_segs=2))[owner[owner >= 0]]
    return (owner >= 0) & narrow & (~largest | ~was_narrow)
