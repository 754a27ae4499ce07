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

FIT_FRACTION = 0.05
"""The vertices of an arc lie on its circle within this fraction of ``tolerance_mm``
(0.5 micrometres at the laser's 0.01 mm): far above the contours' rounding to 1e-6 mm
(:data:`fabtiles.geometry.contours.ROUND_DECIMALS`), far below what a cutter can cut."""

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
    0.0005
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

    >>> from shapely.geometry import LineString
    >>> join = np.asarray(LineString([(0, 0), (10, 0), (10, 10)]).buffer(1.0, quad_segs=8).exterior.coords)[:-1]
    >>> runs = arc_runs(join, tolerance_mm=0.1)
    >>> sorted(np.round(runs.radius, 9).tolist()), runs.full
    ([1.0, 1.0, 1.0], False)
    """
    p = np.asarray(ring, dtype=float)
    n = len(p)
    if n < 4 or tolerance_mm <= 0:
        return _empty()
    eps = fit_distance(tolerance_mm)
    idx = np.arange(n)
    prev, nxt = idx - 1, idx + 1
    if closed:
        prev[0], nxt[-1] = n - 1, 0
    else:
        prev[0], nxt[-1] = 0, n - 1
    centre, radius, cross = _circumcircles(p, prev, nxt)
    chord = np.hypot(*(p[nxt] - p).T)
    # triple i: vertices prev[i], i, nxt[i]; it is an arc piece when it turns, and both
    # its chords stand within the tolerance off its circle
    with np.errstate(invalid="ignore"):
        sag_next = radius - np.sqrt(np.maximum(radius ** 2 - chord ** 2 / 4, 0.0))
        sag_prev = radius - np.sqrt(np.maximum(radius ** 2 - chord[prev] ** 2 / 4, 0.0))
        ok = np.isfinite(radius) & (np.abs(cross) > 0) & (sag_next <= tolerance_mm) & (sag_prev <= tolerance_mm)
        # and it is no straight line: the middle vertex stands off the chord prev-next by more than the fit
        span = np.hypot(*(p[nxt] - p[prev]).T)
        off = np.abs(cross) / np.where(span > 0, span, np.inf)
        ok &= off > eps
    if not closed:
        ok[0] = ok[-1] = False
    # link i: triples i and i+1 lie on one circle (the vertex after triple i's on its circle, same turn)
    n2 = nxt[nxt]
    with np.errstate(invalid="ignore"):
        on = np.abs(np.hypot(*(p[n2] - centre).T) - radius) <= eps
    link = ok & ok[nxt] & on & (np.sign(cross) == np.sign(cross[nxt]))
    if not closed:
        link[-2:] = False
    if closed and link.all():
        c, r = _full_fit(p)
        if np.abs(np.hypot(*(p - c).T) - r).max() <= eps:
            sweep = 2 * np.pi * np.sign(cross[0])
            return ArcRuns(np.array([0]), np.array([0]), c[None, :], np.array([r]), True, np.array([sweep]))
    # rotate a closed ring to start just after a break, so no run wraps in the arrays below
    start = 0
    if closed:
        breaks = np.flatnonzero(~link)
        start = int(breaks[0]) + 1 if len(breaks) else 0
    order = np.roll(idx, -start)
    lk = link[order].astype(np.int8)
    if closed and not len(np.flatnonzero(~link)):
        lk[-1] = 0
    # runs of links: links j..k (in rotated order) join triples j..k+1, vertices j-1..k+2
    edges = np.diff(np.r_[0, lk, 0])
    lo = np.flatnonzero(edges == 1)
    hi = np.flatnonzero(edges == -1) - 1
    out = []
    for a, b in zip(lo.tolist(), hi.tolist()):
        # two runs of links one triple apart would share a chord: it stays with the first
        v0 = max(a - 1, out[-1][1]) if out else a - 1
        out += _verified(p, order, v0, b + 2, eps, closed)
    if closed and len(out) > 1 and out[-1][1] > out[0][0] + n:
        v0, _, *rest = out.pop()
        out += _verified(p, order, v0, out[0][0] + n, eps, closed)
    if not out:
        return _empty()
    first = np.array([order[o[0] % n] for o in out])
    last = np.array([order[o[1] % n] for o in out])
    return ArcRuns(first, last, np.array([o[2] for o in out]), np.array([o[3] for o in out]), False,
                   np.array([o[4] for o in out]))


def _verified(p, order, v0: int, v1: int, eps: float, closed: bool) -> list:
    """The run of rotated vertex positions v0..v1 as arcs that fit: split where it does not (an ellipse)."""
    if v1 - v0 < 3:
        return []
    n = len(p)
    pts = p[order[np.arange(v0, v1 + 1) % n]]
    if not closed and (v0 < 0 or v1 >= n):
        return []
    c, r = _bisector_fit(pts)
    res = np.abs(np.hypot(*(pts - c).T) - r)
    if res.max() <= eps:
        return [(v0, v1, c, r, _sweep(pts, c))]
    k = int(np.argmax(res[1:-1])) + 1
    return _verified(p, order, v0, v0 + k, eps, closed) + _verified(p, order, v0 + k, v1, eps, closed)
