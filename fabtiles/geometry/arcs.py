"""Arcs recovered from flattened rings, so the cutter files write curves as curves.

Every curve fabtiles makes (circle outlines, outline circles, round joins and caps,
corner radii, the arcs a router bit leaves in every corner, the round ends of kerf
offsets) reaches the cut plan as a run of short chords, flattened by GEOS within the
profile's ``tolerance_mm``. :func:`arc_runs` finds those runs again: a run is three or
more consecutive chords whose vertices lie on one circle within
:data:`FIT_FRACTION` of the tolerance, each chord's sagitta ``r (1 - cos(theta / 2))``
within the tolerance and all turning one way. The last condition is what keeps
straight pattern edges straight: a hexagon's corners lie on a circle too, but its
chords stand 13 % of the radius off it, so it is no arc.

Why fit instead of carrying the arcs from the geometry: the curves of a cut plan are
made by GEOS (``buffer`` of the strokes, union, the kerf offset, clipping to the tile
and the sheet), and every one of those steps flattens and cuts them; carrying the
exact arcs through them would mean an arc-aware polygon library for each step. The
fit works on what the writers receive, whatever made it, in one vectorised pass (see
``benchmarks/bench_arcs.py`` and ``docs/speed.md`` for its time on the sheet).

Each arc passes exactly through its run's two end vertices (its centre is on the
perpendicular bisector of the end chord, placed there by least squares on the run's
vertices), so arcs and the straight pieces between them join without gaps.

>>> from shapely.geometry import Point
>>> ring = np.asarray(Point(3.0, 4.0).buffer(10.0, quad_segs=16).exterior.coords)[:-1]
>>> runs = arc_runs(ring, tolerance_mm=0.1)
>>> runs.full, np.round(runs.centre, 9).tolist(), np.round(runs.radius, 9).tolist()
(True, [[3.0, 4.0]], [10.0])
>>> hexagon = np.asarray(Point(0, 0).buffer(10.0, quad_segs=1).exterior.coords)[:-1]
>>> len(arc_runs(hexagon, tolerance_mm=0.1).first)
0
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

FIT_FRACTION = 0.1
"""The vertices of an arc lie on its circle within this fraction of ``tolerance_mm``
(1 micrometre at the laser's 0.01 mm): far above the contours' rounding to 1e-6 mm
(:data:`fabtiles.geometry.contours.ROUND_DECIMALS`), far below what a cutter can cut.
Not less: the kerf offset (mitred) of a round join puts the join's two end vertices
0.45 micrometres off the offset circle (0.075 / cos 3.6 deg - 0.075 mm at the 0.15 mm
kerf); at 0.05 those ends were left out of 634 arcs of the 100 mm circle tile, whose
DXF then kept 3,268 of its 6,184 vertices instead of 2,612."""

GRID_LINK_SLACK = 4.0
"""``link_slack`` for points rounded to a grid near the fit's distance (the print's B-rep, 2**-10 mm):
three points' circle extrapolates their noise about three times over one chord, and at 1 the quarter
circles of a 4 mm corner were cut in five arcs of radii 3.96 to 4.03 mm."""

RADIUS_MATCH = 0.02
"""How near a two-chord run's circle must come to one of the known radii (``radii``), as a
fraction of that radius. Three points on the print's 2**-10 mm grid fix the circle of a round
join's two chords (0.6 mm, 58 degrees) within about 0.7 % of its radius; the cutter files' points
(rounded to 1e-6 mm) far closer."""

RADIUS_RECURS = 3
"""A radius is known when at least this many arcs of three chords or more have it (within
:data:`RADIUS_MATCH`) among the rings searched together: the round joins of one stroke, offset by
one kerf, or a router bit's corners. Then its two-chord arcs are found too, with no radius given."""

MIN_FIT_MM = 1e-5
"""Floor of the fit's distance: ten times the contours' rounding, so a ring rounded to
1e-6 mm still fits its circle when the tolerance is very fine."""


class ArcRuns(NamedTuple):
    """The arcs found in one ring: run ``i`` goes from vertex ``first[i]`` to ``last[i]``.

    ``first``/``last`` index the ring's vertices; in a closed ring a run may wrap
    (``last < first``). ``full``: the whole closed ring is one circle (one run, with
    ``first == last``). ``centre`` (k, 2) and ``radius`` (k,) in mm; ``sweep`` (k,)
    the signed angle in radians from ``first`` to ``last`` (positive counter-clockwise;
    ``+-2 pi`` for a full circle).
    """

    first: np.ndarray
    last: np.ndarray
    centre: np.ndarray
    radius: np.ndarray
    full: bool
    sweep: np.ndarray


def _empty() -> ArcRuns:
    return ArcRuns(np.zeros(0, dtype=int), np.zeros(0, dtype=int), np.zeros((0, 2)), np.zeros(0), False, np.zeros(0))


def fit_distance(tolerance_mm: float) -> float:
    """How far a vertex of an arc may lie off its circle, in mm.

    >>> fit_distance(0.01)
    0.001
    """
    return max(float(tolerance_mm) * FIT_FRACTION, MIN_FIT_MM)


def _circumcircles(p: np.ndarray, prev: np.ndarray, nxt: np.ndarray):
    """Centre, radius and twice the signed area of each triangle (p[prev], p, p[nxt])."""
    a = p[prev] - p
    b = p[nxt] - p
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    a2 = (a * a).sum(axis=1)
    b2 = (b * b).sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (b[:, 1] * a2 - a[:, 1] * b2) / (2 * cross)
        uy = (a[:, 0] * b2 - b[:, 0] * a2) / (2 * cross)
    centre = p + np.column_stack([ux, uy])
    return centre, np.hypot(ux, uy), cross


def _bisector_fit(pts: np.ndarray):
    """Centre and radius of the circle through ``pts[0]`` and ``pts[-1]`` nearest the others.

    The centre is ``M + t u`` on the end chord's bisector; minimising the algebraic
    residuals ``|v - c|^2 - r^2`` over ``t`` is linear, so it has one closed form.
    """
    a, b = pts[0], pts[-1]
    mid = (a + b) / 2
    d = b - a
    h = np.hypot(*d) / 2
    u = np.array([-d[1], d[0]]) / (2 * h)
    w = pts - mid
    wu = w @ u
    t = float(((w * w).sum(axis=1) - h * h) @ wu / (2 * (wu @ wu)))
    return mid + t * u, float(np.hypot(h, t))


def _full_fit(pts: np.ndarray):
    """Least-squares (algebraic) circle through all of ``pts``."""
    m = pts.mean(axis=0)
    q = pts - m
    a = np.column_stack([2 * q, np.ones(len(q))])
    sol = np.linalg.lstsq(a, (q * q).sum(axis=1), rcond=None)[0]
    c = sol[:2]
    return m + c, float(np.sqrt(sol[2] + c @ c))


def _sweep(pts: np.ndarray, centre: np.ndarray) -> float:
    """Signed angle swept from ``pts[0]`` to ``pts[-1]`` around ``centre``, through the points."""
    v = pts - centre
    ang = np.arctan2(v[:-1, 0] * v[1:, 1] - v[:-1, 1] * v[1:, 0], (v[:-1] * v[1:]).sum(axis=1))
    return float(ang.sum())


def arc_runs(
    ring: np.ndarray, *, tolerance_mm: float, closed: bool = True, link_slack: float = 1.0, radii=()
) -> ArcRuns:
    """The arcs of a flattened ``ring``: runs of >= 3 chords on one circle.

    ``ring`` is (n, 2), as the cut plan keeps its paths: a closed ring WITHOUT its
    repeated closing vertex (:func:`fabtiles.geometry.contours.clean_rings` drops it),
    an open path (``closed=False``) from its first vertex to its last. A run's
    vertices lie on its circle within :func:`fit_distance` of ``tolerance_mm``, its
    chords' sagittas are at most ``tolerance_mm``, it turns one way, and its circle
    passes exactly through its two end vertices. Runs share at most an end vertex.
    :func:`arc_runs_many` does many rings in one pass.

    >>> from shapely.geometry import LineString
    >>> join = np.asarray(LineString([(0, 0), (10, 0), (10, 10)]).buffer(1.0, quad_segs=8).exterior.coords)[:-1]
    >>> runs = arc_runs(join, tolerance_mm=0.1)
    >>> sorted(np.round(runs.radius, 9).tolist()), runs.full
    ([1.0, 1.0, 1.0], False)
    """
    return arc_runs_many([ring], tolerance_mm=tolerance_mm, closed=closed, link_slack=link_slack, radii=radii)[0]


def arc_runs_many(rings, *, tolerance_mm: float, closed: bool = True, link_slack: float = 1.0, radii=()) -> list:
    """:func:`arc_runs` of each of ``rings`` (a list of (n, 2) arrays), in one vectorised pass.

    ``link_slack``: how much farther than :func:`fit_distance` the vertex after three may lie off
    their circle and still continue their run (each run is then fitted by least squares within
    :func:`fit_distance`, and split where it does not fit); see :data:`GRID_LINK_SLACK`.

    ``radii``: radii (mm) the rings' curves are known to have, such as a round join's (half the
    stroke), besides those of :data:`RADIUS_RECURS` arcs found in the rings. Two chords between
    corners whose circle has one of them (within :data:`RADIUS_MATCH`) are an arc too, on a
    radius given exactly that radius: a round join that meets other bands within 60 degrees is
    flattened within the printer's 0.02 mm in two chords, and three points on an arbitrary
    circle prove nothing, while three on the join's own radius do (on a 100 mm pierced circle
    tile every such join had its radius within 0.2 %). One chord is no arc
    whatever its length: a bevel's is the same chord.

    The sheets' and panels' cut plans hold thousands of rings: one pass over all their
    vertices instead of a pass per ring (``benchmarks/bench_arcs.py`` measures the pass).

    >>> from shapely.geometry import Point, box
    >>> rings = [np.asarray(g.exterior.coords)[:-1] for g in (Point(0, 0).buffer(5.0), box(0, 0, 1, 1))]
    >>> [(len(r.first), r.full) for r in arc_runs_many(rings, tolerance_mm=0.01)]
    [(1, True), (0, False)]
    """
    rings = [np.asarray(r, dtype=float).reshape(-1, 2) for r in rings]
    out = [_empty() for _ in rings]
    if tolerance_mm <= 0:
        return out
    counts = np.array([len(r) for r in rings], dtype=np.int64)
    use = np.flatnonzero(counts >= 4)
    if not len(use):
        return out
    p = np.concatenate([rings[i] for i in use])
    cnt = counts[use]
    start = np.concatenate([[0], np.cumsum(cnt)[:-1]])
    rid = np.repeat(np.arange(len(use)), cnt)
    local = np.arange(len(p)) - start[rid]
    n_of = cnt[rid]
    eps = fit_distance(tolerance_mm)
    prev, nxt = _ring_neighbours(len(p), start[rid], local, n_of, closed)
    centre, radius, cross = _circumcircles(p, prev, nxt)
    interior = None if closed else (local > 0) & (local < n_of - 1)  # an open ring's ends are no triple's middle
    ok, link = _arc_triples(p, prev, nxt, centre, radius, cross, tolerance_mm, link_slack * eps, interior)
    if not closed:
        link &= local < n_of - 2
    # each closed ring is rotated to start just after a break in its links, so no run wraps
    breaks = np.where(link, np.iinfo(np.int64).max, local)
    first_break = np.minimum.reduceat(breaks, start)
    unbroken = first_break == np.iinfo(np.int64).max
    results = _whole_circles(p, start, cnt, rid, ok, cross, unbroken, eps, closed)
    shift = np.where(unbroken, 0, first_break + 1)
    order = start[rid] + (local + shift[rid]) % n_of
    ring_of, v0, v1 = _candidate_runs(link[order], start, cnt, rid, closed)
    keep = (v1 - v0 >= 3) & ~np.isin(ring_of, list(results))
    runs = _fit_runs(p, order, start, cnt, ring_of[keep], v0[keep], v1[keep], eps)
    known = _known_radii(radii, runs[4])
    if len(known):
        # two chords of a known radius, a triple of their own (neither neighbour triple is a piece
        # of arc, so they overlap no run above)
        t = np.flatnonzero(ok & ~ok[prev] & ~ok[nxt] & ~np.isin(rid, list(results)))
        extra = _known_radius_arcs(p, t, prev, nxt, centre, radius, cross, known, radii, eps, link_slack)
        if extra is not None:
            t, cen, rad, turn = extra
            # positions in the rotated ring, as _fit_runs gives them
            rot = (local[t] - shift[rid[t]]) % n_of[t]
            j, a, b, c, r, sw = runs
            runs = (
                np.r_[j, rid[t]],
                np.r_[a, rot - 1],
                np.r_[b, rot + 1],
                np.vstack([c, cen]),
                np.r_[r, rad],
                np.r_[sw, turn],
            )
    results.update(_runs_by_ring(order, start, cnt, *runs))
    for k, res in results.items():
        out[use[k]] = res
    return out


def _ring_neighbours(n: int, base, local, n_of, closed: bool):
    """``(prev, nxt)``: each vertex's neighbours along its ring (all rings' vertices in one array, each
    ring from ``base``); an open ring's ends are their own neighbours on the side they have none."""
    if closed:
        return base + (local - 1) % n_of, base + (local + 1) % n_of
    at = np.arange(n)
    return np.where(local == 0, at, at - 1), np.where(local == n_of - 1, at, at + 1)


def _arc_triples(p, prev, nxt, centre, radius, cross, tolerance_mm: float, link_mm: float, interior):
    """``(ok, link)``: triple i (vertices prev[i], i, nxt[i]) is a piece of arc when it turns and both its
    chords stand within ``tolerance_mm`` off its circle (and its middle is ``interior``, if given);
    link i: triples i and i + 1 on one circle (the vertex after triple i's within ``link_mm`` of its
    circle, turning alike)."""
    chord = np.hypot(*(p[nxt] - p).T)
    with np.errstate(invalid="ignore"):
        r2 = radius**2
        sag_next = radius - np.sqrt(np.maximum(r2 - chord**2 / 4, 0.0))
        sag_prev = radius - np.sqrt(np.maximum(r2 - chord[prev] ** 2 / 4, 0.0))
        ok = np.isfinite(radius) & (cross != 0) & (sag_next <= tolerance_mm) & (sag_prev <= tolerance_mm)
        if interior is not None:
            ok &= interior
        n2 = nxt[nxt]
        link = (
            ok
            & ok[nxt]
            & (np.abs(np.hypot(*(p[n2] - centre).T) - radius) <= link_mm)
            & (np.sign(cross) == np.sign(cross[nxt]))
        )
    return ok, link


def _whole_circles(p, start, cnt, rid, ok, cross, unbroken, eps: float, closed: bool) -> dict:
    """``{ring: ArcRuns}`` of the rings that are whole circles: all their points within ``eps`` of one
    circle fitted to them, among the rings whose links never break or (closed) whose triples all turn
    alike within the tolerance: three points' circle is too unsure where the chords are short
    against the points' noise (a 100 mm circle outline on the print's 2**-10 mm grid: 1.3 mm
    chords, 0.0043 mm sagitta)."""
    turns = ok & (np.sign(cross) == np.sign(cross[start[rid]]))
    whole = np.minimum.reduceat(turns.view(np.int8), start).astype(bool) if closed else unbroken
    results = {}
    for j in np.flatnonzero(unbroken | whole).tolist():  # a circle (or an ellipse, split below)
        pts = p[start[j] : start[j] + cnt[j]]
        c, r = _full_fit(pts)
        if np.abs(np.hypot(*(pts - c).T) - r).max() <= eps:
            sweep = 2 * np.pi * np.sign(cross[start[j]])
            results[j] = ArcRuns(np.array([0]), np.array([0]), c[None, :], np.array([r]), True, np.array([sweep]))
    return results


def _candidate_runs(lk, start, cnt, rid, closed: bool):
    """``(ring, v0, v1)`` of the runs of links ``lk`` (in each ring's rotated order): vertices v0..v1.

    Two runs one triple apart share a chord (triples on two circles meet there, or a
    straight edge's three-chord ghost run): the shorter run gives it up, so the runs
    share a vertex only.
    """
    lk[start + cnt - 1] = False  # the break (or, for an unbroken ring that is no circle, a cut)
    edges = np.diff(np.r_[0, lk.view(np.int8), 0])
    lo = np.flatnonzero(edges == 1)
    hi = np.flatnonzero(edges == -1) - 1
    # links lo..hi join triples lo..hi+1: vertices lo-1 .. hi+2, in rotated positions within the ring
    ring_of = rid[lo]
    v0 = lo - 1 - start[ring_of]
    v1 = hi + 2 - start[ring_of]
    same = np.zeros(len(lo), dtype=bool)
    same[1:] = ring_of[1:] == ring_of[:-1]
    pairs = [(i - 1, i) for i in np.flatnonzero(same & (np.r_[0, v1[:-1]] > v0)).tolist()]
    if closed and len(lo):
        # the last run of a ring may reach round to the first's start
        first_of = np.flatnonzero(np.r_[True, ring_of[1:] != ring_of[:-1]])
        last_of = np.r_[first_of[1:], len(lo)] - 1
        wraps = (last_of != first_of) & (v1[last_of] > v0[first_of] + cnt[ring_of[first_of]])
        pairs += list(zip(last_of[wraps].tolist(), first_of[wraps].tolist(), strict=True))
    for a, b in pairs:
        nb = cnt[ring_of[b]] if b < a else 0  # the first run, seen from the last one, is a ring further on
        if v1[a] - v0[a] < v1[b] - v0[b]:
            v1[a] = v0[b] + nb
        else:
            v0[b] = v1[a] - nb
    return ring_of, v0, v1


def _known_radii(radii, found) -> np.ndarray:
    """The radii given and those that recur (:data:`RADIUS_RECURS` times within :data:`RADIUS_MATCH`)
    among the radii ``found``, sorted."""
    known = np.sort(np.r_[np.asarray(radii, dtype=float), found])
    lo_k = np.searchsorted(known, known * (1 - RADIUS_MATCH), side="left")
    hi_k = np.searchsorted(known, known * (1 + RADIUS_MATCH), side="right")
    given = np.isin(known, np.asarray(radii, dtype=float))
    return known[given | (hi_k - lo_k >= RADIUS_RECURS)]


def _known_radius_arcs(p, t, prev, nxt, centre, radius, cross, known, radii, eps: float, link_slack: float):
    """``(triples, centres, radii, sweeps)`` of the lone triples ``t`` whose circle has a ``known`` radius
    (within :data:`RADIUS_MATCH`) and whose middle vertex is off the straight line: two chords that
    are an arc; or None. A given radius whose circle through the two ends passes the middle vertex
    within the fit's distance is taken exactly."""
    # |radius - k| <= RADIUS_MATCH k for some known k: the least k >= radius / (1 + RADIUS_MATCH) tells
    at = np.minimum(np.searchsorted(known, radius[t] / (1 + RADIUS_MATCH)), len(known) - 1)
    near = np.abs(radius[t] - known[at]) <= RADIUS_MATCH * known[at]
    # the middle vertex off the chord between the ends by more than the fit's distance: no straight line
    mid_off = np.abs(cross[t]) / np.maximum(np.hypot(*(p[nxt[t]] - p[prev[t]]).T), 1e-300)
    t, rho = t[near & (mid_off > eps)], known[at][near & (mid_off > eps)]
    if not len(t):
        return None
    # the circle of the known radius through the two ends, when the middle vertex lies on it within the
    # fit's distance: a 0.6 mm join on the print's 2**-10 mm grid read 0.5989 mm by its three points
    a0, a2 = p[prev[t]], p[nxt[t]]
    mid, d = (a0 + a2) / 2, a2 - a0
    h = np.hypot(*d.T) / 2
    u = np.column_stack([-d[:, 1], d[:, 0]]) / (2 * h)[:, None]
    side = np.sign(((centre[t] - mid) * u).sum(axis=1))
    c_rho = mid + (side * np.sqrt(np.maximum(rho**2 - h**2, 0.0)))[:, None] * u
    # (a radius given; one that recurs among the arcs found is itself a fit, the triple's as good)
    fits = (
        np.isin(rho, np.asarray(radii, dtype=float))
        & (rho > h)
        & (np.abs(np.hypot(*(p[t] - c_rho).T) - rho) <= link_slack * eps)
    )
    cen = np.where(fits[:, None], c_rho, centre[t])
    rad = np.where(fits, rho, radius[t])
    va, vb = p[prev[t]] - cen, p[t] - cen
    vc = p[nxt[t]] - cen
    turn = np.arctan2(va[:, 0] * vb[:, 1] - va[:, 1] * vb[:, 0], (va * vb).sum(axis=1)) + np.arctan2(
        vb[:, 0] * vc[:, 1] - vb[:, 1] * vc[:, 0], (vb * vc).sum(axis=1)
    )
    return t, cen, rad, turn


def _runs_by_ring(order, start, cnt, j, a, b, c, r, sw) -> dict:
    """``{ring: ArcRuns}`` of the arcs (ring ``j``, rotated positions ``a..b``), their ends as the
    ring's own vertex numbers, in order along each ring."""
    results: dict = {}
    if not len(j):
        return results
    srt = np.lexsort((a, j))
    j, a, b, c, r, sw = j[srt], a[srt], b[srt], c[srt], r[srt], sw[srt]
    first = order[start[j] + a % cnt[j]] - start[j]
    last = order[start[j] + b % cnt[j]] - start[j]
    cut = np.flatnonzero(np.r_[True, j[1:] != j[:-1], True])
    for s0, s1 in zip(cut[:-1].tolist(), cut[1:].tolist(), strict=True):
        results[int(j[s0])] = ArcRuns(first[s0:s1], last[s0:s1], c[s0:s1], r[s0:s1], False, sw[s0:s1])
    return results


def _fit_runs(p, order, start, cnt, ring_of, v0, v1, eps) -> tuple:
    """Fit each candidate run (ring ``ring_of``, rotated vertex positions ``v0..v1``), all at once.

    Returns the arrays ``(ring, v0, v1, centre, radius, sweep)`` of the runs that fit; a run that
    does not (an ellipse's points pass the neighbour test but drift off any one circle)
    is split at its worst vertex, by :func:`_verified`.
    """
    if not len(v0):
        return (np.zeros(0, dtype=np.int64),) * 3 + (np.zeros((0, 2)), np.zeros(0), np.zeros(0))
    m = v1 - v0 + 1
    run = np.repeat(np.arange(len(v0)), m)
    at = np.arange(m.sum()) - np.repeat(np.cumsum(m) - m, m)
    pos = (v0[run] + at) % cnt[ring_of[run]]
    pts = p[order[start[ring_of[run]] + pos]]
    offs = np.cumsum(m) - m
    a, b = pts[offs], pts[offs + m - 1]
    mid = (a + b) / 2
    d = b - a
    h = np.hypot(*d.T) / 2
    chord = h > 0  # a run whose ends meet (round a whole ring) has no chord to fit on: it is no arc
    u = np.column_stack([-d[:, 1], d[:, 0]]) / np.where(chord, 2 * h, 1.0)[:, None]
    w = pts - mid[run]
    wu = (w * u[run]).sum(axis=1)
    num = np.add.reduceat(((w * w).sum(axis=1) - h[run] ** 2) * wu, offs)
    den = 2 * np.add.reduceat(wu * wu, offs)
    t = num / np.where(chord, den, 1.0)
    c = mid + t[:, None] * u
    r = np.hypot(h, t)
    res = np.maximum.reduceat(np.abs(np.hypot(*(pts - c[run]).T) - r[run]), offs)
    # a straight edge cut in pieces (collinear vertices, rounded to 1e-6 mm) fits a circle of huge
    # radius: a run whose vertices all lie within the fit's distance of its end chord is no arc
    off = np.maximum.reduceat(np.abs(wu), offs)
    straight = off <= eps
    v = pts - c[run]
    ang = np.arctan2(v[:-1, 0] * v[1:, 1] - v[:-1, 1] * v[1:, 0], (v[:-1] * v[1:]).sum(axis=1))
    ang = np.r_[ang, 0.0]
    ang[offs + m - 1] = 0.0  # the step from one run's last vertex to the next run's first
    sweep = np.add.reduceat(ang, offs)
    good = chord & ~straight & (res <= eps)
    cols = [ring_of[good], v0[good], v1[good], c[good], r[good], sweep[good]]
    extra = []
    for i in np.flatnonzero(chord & ~straight & (res > eps)).tolist():  # rare: an ellipse (an anisotropic kerf)
        j = int(ring_of[i])
        ring_pts = p[order[start[j] : start[j] + cnt[j]]]
        extra += [(j, *piece) for piece in _verified(ring_pts, int(v0[i]), int(v1[i]), eps)]
    if extra:
        more = list(zip(*extra, strict=True))
        cols = [
            np.concatenate([col, np.array(m, dtype=col.dtype).reshape(-1, *col.shape[1:])])
            for col, m in zip(cols, more, strict=True)
        ]
    return tuple(cols)


def _verified(pts_ring, v0: int, v1: int, eps: float) -> list:
    """The run v0..v1 of a (rotated) ring as arcs that fit: split at the worst vertex where it does not."""
    if v1 - v0 < 3:
        return []
    n = len(pts_ring)
    pts = pts_ring[np.arange(v0, v1 + 1) % n]
    a, b = pts[0], pts[-1]
    d = b - a
    off = np.abs(d[0] * (pts[:, 1] - a[1]) - d[1] * (pts[:, 0] - a[0])) / max(np.hypot(*d), 1e-300)
    if off.max() <= eps:
        return []
    c, r = _bisector_fit(pts)
    res = np.abs(np.hypot(*(pts - c).T) - r)
    if res.max() <= eps:
        return [(v0, v1, c, r, _sweep(pts, c))]
    k = int(np.argmax(res[1:-1])) + 1
    return _verified(pts_ring, v0, v0 + k, eps) + _verified(pts_ring, v0 + k, v1, eps)


class Curve(NamedTuple):
    """A path with arcs: vertices (m, 2) and the bulge of the piece leaving each vertex.

    ``bulge[i]`` is ``tan(sweep / 4)`` of the piece from ``xy[i]`` to ``xy[i + 1]``
    (for a closed path, the last one back to ``xy[0]``), positive counter-clockwise,
    0 for a straight piece: DXF's LWPOLYLINE bulge (group code 42).
    """

    xy: np.ndarray
    bulge: np.ndarray


def bulge_path(ring: np.ndarray, runs: ArcRuns, *, closed: bool = True, max_sweep: float = np.pi) -> Curve:
    """``ring`` with each arc of ``runs`` as one bulged piece (or several of at most ``max_sweep``).

    The arcs' interior vertices are dropped; the ring keeps its first vertex (an arc round
    it is cut there in two), so a path starts where its flattened one did. A piece longer
    than ``max_sweep`` is cut at points on the arc's circle: ``pi`` keeps every bulge
    within [-1, 1] (some CAM reads no more), ``pi / 2`` gives the quarter arcs a cubic
    Bezier draws within 0.03 % of the radius (LightBurn's curves, :mod:`fabtiles.export.lbrn2`).

    >>> from shapely.geometry import Point
    >>> ring = np.asarray(Point(0, 0).buffer(2.0, quad_segs=16).exterior.coords)[:-1]
    >>> curve = bulge_path(ring, arc_runs(ring, tolerance_mm=0.01))
    >>> np.round(curve.xy, 9).tolist(), np.round(curve.bulge, 9).tolist()
    ([[2.0, 0.0], [-2.0, 0.0]], [1.0, 1.0])
    """
    p = np.asarray(ring, dtype=float)
    n = len(p)
    k = len(runs.first)
    if k == 0:
        return Curve(p, np.zeros(n))
    if runs.full:
        c, r, sweep = runs.centre[0], float(runs.radius[0]), float(runs.sweep[0])
        m = max(2, int(np.ceil(abs(sweep) / max_sweep - 1e-9)))
        a0 = np.arctan2(*(p[0] - c)[::-1])
        ang = a0 + sweep * np.arange(1, m) / m
        xy = np.vstack([p[:1], c + r * np.column_stack([np.cos(ang), np.sin(ang)])])
        return Curve(xy, np.full(m, np.tan(sweep / m / 4)))
    first, last = runs.first.astype(np.int64), runs.last.astype(np.int64)
    centre, radius, sweep = runs.centre, runs.radius, runs.sweep
    wrap = last < first
    if closed and wrap.any():
        # an arc round the ring's first vertex: cut in two there, the ring starts where it did
        w = np.flatnonzero(wrap)
        v = p[0] - centre[w]
        u = p[first[w]] - centre[w]
        turn = np.arctan2(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0], (u * v).sum(axis=1))
        turn = np.where(np.sign(turn) != np.sign(sweep[w]), turn + 2 * np.pi * np.sign(sweep[w]), turn)
        turn = np.where(last[w] == 0, sweep[w], turn)  # ends at vertex 0: no second piece
        at_zero = first[w] == 0
        turn = np.where(at_zero, 0.0, turn)
        first = np.r_[first[~wrap], first[w], np.zeros(len(w), dtype=np.int64)]
        last = np.r_[last[~wrap], np.full(len(w), n, dtype=np.int64), last[w]]
        centre = np.vstack([centre[~wrap], centre[w], centre[w]])
        radius = np.r_[radius[~wrap], radius[w], radius[w]]
        sweep = np.r_[sweep[~wrap], turn, sweep[w] - turn]
        good = (last - first >= 1) & (sweep != 0)
        first, last, centre, radius, sweep = first[good], last[good], centre[good], radius[good], sweep[good]
        order = np.argsort(first, kind="stable")
        first, last, centre, radius, sweep = first[order], last[order], centre[order], radius[order], sweep[order]
    drop = np.zeros(n + 2, dtype=np.int64)
    np.add.at(drop, first + 1, 1)
    np.add.at(drop, last, -1)
    keep = np.cumsum(drop)[:n] == 0
    pieces = np.maximum(1, np.ceil(np.abs(sweep) / max_sweep - 1e-9)).astype(np.int64)
    bulge = np.zeros(n)
    bulge[first] = np.tan(sweep / pieces / 4)
    xy, b = p[keep], bulge[keep]
    split = np.flatnonzero(pieces > 1)
    if len(split):
        # the points that cut a long arc, on its circle, after its first vertex
        reps = pieces[split] - 1
        which = np.repeat(split, reps)
        j = np.arange(reps.sum()) - np.repeat(np.cumsum(reps) - reps, reps) + 1
        a0 = np.arctan2(*(p[first[which]] - centre[which]).T[::-1])
        ang = a0 + sweep[which] * j / pieces[which]
        pts = centre[which] + radius[which][:, None] * np.column_stack([np.cos(ang), np.sin(ang)])
        at = np.cumsum(keep)[first[which]]  # the position after the arc's first vertex among the kept ones
        xy = np.insert(xy, at, pts, axis=0)
        b = np.insert(b, at, np.tan(sweep[which] / pieces[which] / 4))
    return Curve(xy, b)


def curves(rings, *, tolerance_mm: float, closed: bool = True, max_sweep: float = np.pi, radii=()) -> list:
    """The :class:`Curve` of each of ``rings``: :func:`arc_runs_many` (with the known ``radii``) then
    :func:`bulge_path`.

    >>> from shapely.geometry import box
    >>> [len(c.xy) for c in curves([np.asarray(box(0, 0, 1, 1).buffer(0.5).exterior.coords)[:-1]], tolerance_mm=0.01)]
    [8]
    """
    return [
        bulge_path(r, runs, closed=closed, max_sweep=max_sweep)
        for r, runs in zip(
            rings, arc_runs_many(rings, tolerance_mm=tolerance_mm, closed=closed, radii=radii), strict=True
        )
    ]


def piece_lengths(curve: Curve, closed: bool = True) -> np.ndarray:
    """The length of each piece of ``curve``: its chord, or its arc's ``r * sweep``.

    >>> piece_lengths(Curve(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 1.0]))).round(9).tolist()
    [3.141592654, 3.141592654]
    """
    xy = np.asarray(curve.xy, dtype=float)
    nxt = np.roll(xy, -1, axis=0) if closed else xy[1:]
    b = np.asarray(curve.bulge, dtype=float)[: len(nxt)]
    chord = np.hypot(*(nxt - xy[: len(nxt)]).T)
    half = 2 * np.arctan(np.abs(b))  # half the sweep
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(b != 0, chord * half / np.sin(half), chord)


def _pieces(curves_, closed: bool):
    """All pieces of ``curves_`` at once: start points, end points, bulges and the curve of each."""
    curves_ = list(curves_)
    sizes = np.array([len(c.xy) for c in curves_], dtype=np.int64)
    if not len(curves_) or not sizes.sum():
        z = np.zeros((0, 2))
        return z, z, np.zeros(0), np.zeros(0, dtype=np.int64), sizes
    xy = np.concatenate([np.asarray(c.xy, dtype=float).reshape(-1, 2) for c in curves_])
    b = np.concatenate([np.asarray(c.bulge, dtype=float) for c in curves_])
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    which = np.repeat(np.arange(len(curves_)), sizes)
    nxt = np.arange(len(xy)) + 1
    last = starts + sizes - 1
    if closed:
        nxt[last] = starts
        keep = np.ones(len(xy), dtype=bool)
    else:
        keep = np.ones(len(xy), dtype=bool)
        keep[last] = False
        nxt[last] = last
    return xy[keep], xy[nxt[keep]], b[keep], which[keep], sizes


def curve_lengths(curves_, *, closed: bool = True) -> np.ndarray:
    """The length of each of ``curves_`` (:class:`Curve`), arcs as arcs, in one pass.

    >>> half = Curve(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 0.0]))
    >>> curve_lengths([half], closed=True).round(9).tolist(), curve_lengths([half], closed=False).round(9).tolist()
    ([5.141592654], [3.141592654])
    """
    a, z, b, which, sizes = _pieces(curves_, closed)
    chord = np.hypot(*(z - a).T)
    half = 2 * np.arctan(np.abs(b))
    with np.errstate(invalid="ignore", divide="ignore"):
        length = np.where(b != 0, chord * half / np.sin(half), chord)
    return np.bincount(which, weights=length, minlength=len(sizes))


def arc_geometry(a: np.ndarray, z: np.ndarray, b: np.ndarray):
    """Centre, radius, start angle and signed sweep of bulged pieces from ``a`` to ``z`` (bulge ``b`` != 0).

    >>> c, r, a0, sweep = arc_geometry(np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]), np.array([np.tan(np.pi / 8)]))
    >>> np.round(c, 9).tolist(), np.round(r, 9).tolist(), np.round(a0, 9).tolist(), np.round(sweep, 9).tolist()
    ([[0.0, 0.0]], [1.0], [0.0], [1.570796327])
    """
    d = z - a
    perp = np.column_stack([-d[:, 1], d[:, 0]])
    c = (a + z) / 2 + perp * ((1 - b * b) / (4 * b))[:, None]
    r = np.hypot(*d.T) * (1 + b * b) / (4 * np.abs(b))
    a0 = np.arctan2(a[:, 1] - c[:, 1], a[:, 0] - c[:, 0])
    return c, r, a0, 4 * np.arctan(b)


def curve_bounds(curves_, *, closed: bool = True):
    """``(xmin, ymin, xmax, ymax)`` of ``curves_``, arcs as arcs (an arc may reach past its end vertices).

    >>> curve_bounds([Curve(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 1.0]))])
    (-1.0, -1.0, 1.0, 1.0)
    """
    a, z, b, _, _ = _pieces(curves_, closed)
    pts = [a, z]
    arc = b != 0
    if arc.any():
        c, r, a0, sweep = arc_geometry(a[arc], z[arc], b[arc])
        for k, (dx, dy) in enumerate(((1, 0), (0, 1), (-1, 0), (0, -1))):
            # the arc passes the axis direction k * 90 degrees when it sweeps that far from its start
            ahead = np.mod((k * np.pi / 2 - a0) * np.sign(sweep), 2 * np.pi)
            hit = ahead <= np.abs(sweep)
            pts.append(c[hit] + r[hit][:, None] * np.array([dx, dy]))
    allp = np.concatenate(pts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def bezier_error(sweep, r):
    """How far the cubic Bezier with handles ``4/3 tan(sweep/4) r`` strays from its arc, at most (mm).

    The cubic meets the arc at its ends and its middle and lies outside it between, by no more
    than ``r 2/27 sin^6(sweep/4) / cos^2(sweep/4)`` (the largest distance itself to within 0.1 %
    up to a quarter turn, 1 % up to a half): 2.73e-4 of the radius on a quarter turn, with the
    sixth power of the sweep below that.

    >>> round(float(bezier_error(np.pi / 2, 1.0)), 7), round(float(bezier_error(np.pi / 2, 70.0)), 4)
    (0.0002726, 0.0191)
    """
    q = np.abs(np.asarray(sweep, dtype=float)) / 4
    return np.asarray(r, dtype=float) * (2 / 27) * np.sin(q) ** 6 / np.cos(q) ** 2


class Beziers(NamedTuple):
    """A path of straight lines and cubic Beziers: vertices, and per piece leaving vertex ``i``
    whether it is a Bezier, its outgoing handle ``c0[i]`` and the incoming handle ``c1[i]`` of its
    end vertex (NaN where a piece is straight)."""

    xy: np.ndarray
    bezier: np.ndarray
    c0: np.ndarray
    c1: np.ndarray


def beziers(curve: Curve, *, tolerance_mm: float, closed: bool = True) -> Beziers:
    """``curve``'s arcs as cubic Beziers within a tenth of ``tolerance_mm`` of them.

    Each arc is cut into equal pieces of at most a quarter turn, fewer degrees on a large
    radius, so that each piece's :func:`bezier_error` stays within a tenth of the tolerance
    (a quarter circle of 75 mm as one Bezier strays 0.02 mm: cut in two, 3e-4 mm).

    >>> half = Curve(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 0.0]))
    >>> b = beziers(half, tolerance_mm=0.01)
    >>> np.round(b.xy, 9).tolist(), b.bezier.tolist()
    ([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]], [True, True, False])
    >>> np.round(b.c0[0], 6).tolist(), np.round(b.c1[0], 6).tolist()
    ([1.0, 0.552285], [0.552285, 1.0])
    """
    return beziers_many([curve], tolerance_mm=tolerance_mm, closed=closed)[0]


def beziers_many(curves_, *, tolerance_mm: float, closed: bool = True) -> list:
    """:func:`beziers` of every curve of ``curves_`` in one vectorised pass (a call per curve was
    most of a LightBurn project's time).

    >>> half = Curve(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 0.0]))
    >>> [b.bezier.tolist() for b in beziers_many([half, half], tolerance_mm=0.01, closed=False)]
    [[True, True, False], [True, True, False]]
    """
    if not len(curves_):
        return []
    sizes = np.array([len(c.xy) for c in curves_], dtype=np.int64)
    xy = np.concatenate([np.asarray(c.xy, dtype=float) for c in curves_])
    bulge = np.concatenate([np.asarray(c.bulge, dtype=float) for c in curves_])
    n = len(xy)
    first = np.repeat(np.cumsum(sizes) - sizes, sizes)
    pos = np.arange(n) - first
    last = pos == np.repeat(sizes - 1, sizes)
    nxt = np.where(last, first, np.arange(n) + 1)  # each vertex's next one on its own path
    has_piece = ~last if not closed else np.ones(n, dtype=bool)
    arc = np.flatnonzero((bulge != 0) & has_piece)
    count = np.ones(n, dtype=np.int64)
    out_sizes = sizes.copy()
    if len(arc):
        a, z = xy[arc], xy[nxt[arc]]
        c, r, a0, sweep = arc_geometry(a, z, bulge[arc])
        # pieces of at most a quarter turn, as many as the sixth-power rule asks, then one more
        # wherever the exact error of a piece still exceeds a tenth of the tolerance
        target = 0.1 * tolerance_mm
        limit = np.pi / 2 * np.minimum(1.0, (target / (bezier_error(np.pi / 2, 1.0) * r)) ** (1 / 6))
        m = np.maximum(1, np.ceil(np.abs(sweep) / limit - 1e-9)).astype(np.int64)
        while (short := bezier_error(sweep / m, r) > target).any():
            m[short] += 1
        count[arc] = m
        out_sizes = np.bincount(np.repeat(np.arange(len(sizes)), sizes), weights=count, minlength=len(sizes)).astype(
            np.int64
        )
    at = np.concatenate([[0], np.cumsum(count)[:-1]])  # where each old vertex lands
    total = int(count.sum())
    out = np.empty((total, 2))
    out[at] = xy
    bez = np.zeros(total, dtype=bool)
    c0 = np.full((total, 2), np.nan)
    c1 = np.full((total, 2), np.nan)
    if len(arc):
        # the pieces of each arc: angles a0 + sweep * k / m, k = 0..m
        which = np.repeat(np.arange(len(arc)), m)
        k = np.arange(m.sum()) - np.repeat(np.cumsum(m) - m, m)
        step = sweep[which] / m[which]
        alpha0 = a0[which] + step * k
        alpha1 = alpha0 + step
        idx = at[arc][which] + k  # the piece's start vertex in the output
        inner = k > 0
        out[idx[inner]] = c[which][inner] + r[which][inner, None] * np.column_stack(
            [np.cos(alpha0[inner]), np.sin(alpha0[inner])]
        )
        h = (4 / 3) * np.tan(step / 4) * r[which]
        bez[idx] = True
        c0[idx] = out[idx] + h[:, None] * np.column_stack([-np.sin(alpha0), np.cos(alpha0)])
        end_pt = np.where(
            (k == m[which] - 1)[:, None],
            z[which],
            c[which] + r[which][:, None] * np.column_stack([np.cos(alpha1), np.sin(alpha1)]),
        )
        c1[idx] = end_pt - h[:, None] * np.column_stack([-np.sin(alpha1), np.cos(alpha1)])
    cuts = np.cumsum(out_sizes)[:-1]
    return [
        Beziers(*parts)
        for parts in zip(np.split(out, cuts), np.split(bez, cuts), np.split(c0, cuts), np.split(c1, cuts), strict=True)
    ]


def subdivide(curve: Curve, *, max_sweep: float, closed: bool = True) -> Curve:
    """``curve`` with each arc longer than ``max_sweep`` cut into equal arcs, at points on its circle.

    For files that print few decimals: an SVG arc gives its radius, and a half turn's centre
    moves by ``sqrt(2 r e)`` when its radius is printed ``e`` too long (0.01 mm for a 1.125 mm
    radius at 4 decimals); a quarter turn's by ``1.4 e``.

    >>> half = Curve(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 0.0]))
    >>> q = subdivide(half, max_sweep=np.pi / 2, closed=False)
    >>> np.round(q.xy, 9).tolist(), np.round(q.bulge, 9).tolist()
    ([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]], [0.414213562, 0.414213562, 0.0])
    """
    xy = np.asarray(curve.xy, dtype=float)
    bulge = np.asarray(curve.bulge, dtype=float)
    n = len(xy)
    pieces = n if closed else n - 1
    arc = np.flatnonzero(bulge[:pieces] != 0)
    if not len(arc):
        return Curve(xy, bulge)
    c, r, a0, sweep = arc_geometry(xy[arc], xy[(arc + 1) % n], bulge[arc])
    m = np.maximum(1, np.ceil(np.abs(sweep) / max_sweep - 1e-9)).astype(np.int64)
    if (m == 1).all():
        return Curve(xy, bulge)
    b = bulge.copy()
    b[arc] = np.tan(sweep / m / 4)
    split = np.flatnonzero(m > 1)
    reps = m[split] - 1
    which = np.repeat(split, reps)
    k = np.arange(reps.sum()) - np.repeat(np.cumsum(reps) - reps, reps) + 1
    ang = a0[which] + sweep[which] * k / m[which]
    pts = c[which] + r[which][:, None] * np.column_stack([np.cos(ang), np.sin(ang)])
    at = arc[which] + 1
    return Curve(np.insert(xy, at, pts, axis=0), np.insert(b, at, b[arc[which]]))
