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

LINK_SLACK = 4.0
"""How much farther than :func:`fit_distance` the vertex after a triple may lie off the triple's circle and
still link it to the run (each run is then fitted by least squares within :func:`fit_distance`, and split
where it does not fit). Three points' circle extrapolates their noise about three times over one chord:
on the print's 2**-10 mm grid (0.0007 mm of rounding) the quarter circles of a 4 mm corner were cut in
five arcs of radii 3.96 to 4.03 mm."""

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
    sweep: np.ndarray | None = None


def _empty() -> ArcRuns:
    return ArcRuns(np.zeros(0, dtype=int), np.zeros(0, dtype=int), np.zeros((0, 2)), np.zeros(0), False,
                   np.zeros(0))


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


def arc_runs(ring: np.ndarray, *, tolerance_mm: float, closed: bool = True) -> ArcRuns:
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
    return arc_runs_many([ring], tolerance_mm=tolerance_mm, closed=closed)[0]


def arc_runs_many(rings, *, tolerance_mm: float, closed: bool = True) -> list:
    """:func:`arc_runs` of each of ``rings`` (a list of (n, 2) arrays), in one vectorised pass.

    The sheets' and panels' cut plans hold thousands of rings: one pass over all their
    vertices instead of a pass per ring (the 2440 x 1220 mm panel's 2,812 rings and
    238,772 vertices: 1.1 s ring by ring, see ``benchmarks/bench_arcs.py`` for the pass).

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
    base = start[rid]
    n_of = cnt[rid]
    eps = fit_distance(tolerance_mm)
    if closed:
        prev = base + (local - 1) % n_of
        nxt = base + (local + 1) % n_of
    else:
        prev = np.where(local == 0, np.arange(len(p)), np.arange(len(p)) - 1)
        nxt = np.where(local == n_of - 1, np.arange(len(p)), np.arange(len(p)) + 1)
    centre, radius, cross = _circumcircles(p, prev, nxt)
    chord = np.hypot(*(p[nxt] - p).T)
    # triple i (vertices prev[i], i, nxt[i]) is a piece of arc when it turns and both its
    # chords stand within the tolerance off its circle
    with np.errstate(invalid="ignore"):
        r2 = radius ** 2
        sag_next = radius - np.sqrt(np.maximum(r2 - chord ** 2 / 4, 0.0))
        sag_prev = radius - np.sqrt(np.maximum(r2 - chord[prev] ** 2 / 4, 0.0))
        ok = np.isfinite(radius) & (cross != 0) & (sag_next <= tolerance_mm) & (sag_prev <= tolerance_mm)
        if not closed:
            ok &= (local > 0) & (local < n_of - 1)
        # link i: triples i and i + 1 on one circle (the vertex after triple i's on its circle, turning alike)
        n2 = nxt[nxt]
        link = ok & ok[nxt] & (np.abs(np.hypot(*(p[n2] - centre).T) - radius) <= LINK_SLACK * eps) & \
            (np.sign(cross) == np.sign(cross[nxt]))
    if not closed:
        link &= local < n_of - 2
    # each closed ring is rotated to start just after a break in its links, so no run wraps
    breaks = np.where(link, np.iinfo(np.int64).max, local)
    first_break = np.minimum.reduceat(breaks, start)
    unbroken = first_break == np.iinfo(np.int64).max
    # a closed ring whose triples all turn alike within the tolerance may be a circle though some links
    # fail: three points' circle is too unsure where the chords are short against the points' noise
    # (a 100 mm circle outline on the print's 2**-10 mm grid: 1.3 mm chords, 0.0043 mm sagitta)
    turns = ok & (np.sign(cross) == np.sign(cross[start[rid]]))
    whole = np.minimum.reduceat(turns.view(np.int8), start).astype(bool) if closed else unbroken
    results = {}
    for j in np.flatnonzero(unbroken | whole).tolist():  # a circle (or an ellipse, split below)
        pts = p[start[j]:start[j] + cnt[j]]
        c, r = _full_fit(pts)
        if np.abs(np.hypot(*(pts - c).T) - r).max() <= eps:
            sweep = -2 * np.pi * np.sign(cross[start[j]])  # cross < 0 where a ring turns left
            results[j] = ArcRuns(np.array([0]), np.array([0]), c[None, :], np.array([r]), True, np.array([sweep]))
    shift = np.where(unbroken, 0, first_break + 1)
    order = base + (local + shift[rid]) % n_of
    lk = link[order]
    ends_of_ring = start + cnt - 1
    lk[ends_of_ring] = False  # the break (or, for an unbroken ring that is no circle, a cut)
    edges = np.diff(np.r_[0, lk.view(np.int8), 0])
    lo = np.flatnonzero(edges == 1)
    hi = np.flatnonzero(edges == -1) - 1
    # links lo..hi join triples lo..hi+1: vertices lo-1 .. hi+2, in rotated positions within the ring
    ring_of = rid[lo]
    v0 = lo - 1 - start[ring_of]
    v1 = hi + 2 - start[ring_of]
    # two runs one triple apart would share a chord: it stays with the first
    same = np.zeros(len(lo), dtype=bool)
    same[1:] = ring_of[1:] == ring_of[:-1]
    v0[same] = np.maximum(v0[same], v1[np.flatnonzero(same) - 1])
    if closed and len(lo):
        # the last run of a ring may reach round to the first's start
        last_of = np.r_[ring_of[1:] != ring_of[:-1], True]
        first_of = np.r_[True, ring_of[1:] != ring_of[:-1]]
        fi = np.flatnonzero(first_of)
        li = np.flatnonzero(last_of)
        lim = v0[fi] + cnt[ring_of[fi]]
        clash = (li != fi) & (v1[li] > lim)
        v1[li[clash]] = lim[clash]
    keep = (v1 - v0 >= 3) & ~np.isin(ring_of, list(results))
    ring_of, v0, v1 = ring_of[keep], v0[keep], v1[keep]
    runs = _fit_runs(p, order, start, cnt, ring_of, v0, v1, eps)
    # gather per ring
    groups = {}
    for j, a, b, c, r, sw in runs:
        groups.setdefault(j, []).append((a, b, c, r, sw))
    for j, items in groups.items():
        items.sort(key=lambda t: t[0])
        nj = cnt[j]
        o = order[start[j]:start[j] + nj] - start[j]
        results[j] = ArcRuns(np.array([o[a % nj] for a, *_ in items]), np.array([o[b % nj] for _, b, *_ in items]),
                             np.array([t[2] for t in items]).reshape(-1, 2), np.array([t[3] for t in items]), False,
                             np.array([t[4] for t in items]))
    for j, res in results.items():
        out[use[j]] = res
    return out


def _fit_runs(p, order, start, cnt, ring_of, v0, v1, eps) -> list:
    """Fit each candidate run (ring ``ring_of``, rotated vertex positions ``v0..v1``), all at once.

    Returns ``(ring, v0, v1, centre, radius, sweep)`` of the runs that fit; a run that
    does not (an ellipse's points pass the neighbour test but drift off any one circle)
    is split at its worst vertex, by :func:`_verified`.
    """
    if not len(v0):
        return []
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
    u = np.column_stack([-d[:, 1], d[:, 0]]) / (2 * h)[:, None]
    w = pts - mid[run]
    wu = (w * u[run]).sum(axis=1)
    num = np.add.reduceat(((w * w).sum(axis=1) - h[run] ** 2) * wu, offs)
    den = 2 * np.add.reduceat(wu * wu, offs)
    t = num / den
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
    out = []
    for i in np.flatnonzero(~straight).tolist():
        j = int(ring_of[i])
        if res[i] <= eps:
            out.append((j, int(v0[i]), int(v1[i]), c[i], float(r[i]), float(sweep[i])))
        else:
            ring_pts = p[order[start[j]:start[j] + cnt[j]]]
            out += [(j, *piece) for piece in _verified(ring_pts, int(v0[i]), int(v1[i]), eps)]
    return out


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
