"""The cut order: the head's travel between paths made short, holes still before what holds them.

A cutter's file lists its layers in cut order (engrave, score, inner, outer); within
a layer, the order of the paths is the head's travel. :func:`order_paths` reorders
each layer's paths from the machine's origin: a greedy nearest neighbour over
GEOS's R-tree (:class:`shapely.STRtree`), then 2-opt over each path's nearest
neighbours until no exchange shortens the travel (as vpype's ``linesort --two-opt``
does, but with neighbour lists and a queue of the paths whose neighbours changed
instead of every pair each pass: O(n k) a sweep instead of O(n^2)).

The rule of a cutter holds throughout: a contour inside another is cut before it
(a piece cut free drops or shifts, and what lies inside it would be cut on a
moving piece). Only the inner layer can hold nested contours (an island in a hole
and the hole around it: the outer layer is the top-level parts, cut last); a move
that would put a contour after one enclosing it is never made. Closed contours
keep their start and direction (the writers' kerf side and the tabs' places rely
on them); open score lines may be reversed; open pieces between holding tabs keep
their direction and are only chained by the nearest neighbour.

On the samples the travel is about a quarter shorter than in the Hilbert-curve order of
:mod:`.contours`, and a little shorter than vpype's ``linesort --two-opt`` in a third of its
time; ``benchmarks/bench_cut_order.py`` measures it, ``docs/speed.md`` keeps the figures.

>>> square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
>>> rings = [square + 30, square + 10, square + 20]
>>> order_rings(rings).tolist()
[1, 2, 0]
>>> travel(rings[1:] + rings[:1]) < travel(rings)
True
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np
import shapely

NEIGHBOURS = 8
"""Paths each path tries 2-opt exchanges with (its nearest by start point): fewer leave travel,
more cost time and are not always shorter (other exchanges are made first); ``docs/speed.md``
has the figures."""


def travel(paths, *, start=(0.0, 0.0), closed: bool = True) -> float:
    """The head's travel through ``paths`` in the given order, from ``start`` (mm).

    A closed path ends where it starts; an open one at its last point.

    >>> travel([np.array([[3.0, 4.0], [9, 9]]), np.array([[9.0, 12], [0, 0]])], closed=False)
    8.0
    """
    if not len(paths):
        return 0.0
    first = np.array([p[0] for p in paths], float)
    last = first if closed else np.array([p[-1] for p in paths], float)
    before = np.vstack([np.asarray(start, float)[None], last[:-1]])
    return float(np.hypot(*(first - before).T).sum())


def enclosing_pairs(rings) -> np.ndarray:
    """``(m, 2)`` index pairs ``(inside, around)``: ring ``around`` encloses ring ``inside``.

    Only direct or indirect enclosure matters for the order (any enclosing ring must
    come after); the rings of a cut never cross, so one point of a ring tells.
    Boxes first (an STRtree of the rings' boxes), GEOS's point in polygon only for
    the pairs whose boxes nest.

    >>> square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    >>> enclosing_pairs([square * 10, square + 4, square + 20]).tolist()
    [[1, 0]]
    """
    n = len(rings)
    if n < 2:
        return np.zeros((0, 2), np.int64)
    flat = np.concatenate(rings)
    starts = np.cumsum([0] + [len(r) for r in rings[:-1]])
    lo, hi = np.minimum.reduceat(flat, starts), np.maximum.reduceat(flat, starts)
    boxes = shapely.box(lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1])
    # a ring's box inside another's: the only candidates (a pierced sheet's 9,947 holes: none)
    a, b = shapely.STRtree(boxes).query(boxes, predicate="within")
    keep = a != b
    a, b = a[keep], b[keep]
    if not len(a):
        return np.zeros((0, 2), np.int64)
    ids = np.unique(b)
    polys = np.empty(n, dtype=object)
    polys[ids] = [shapely.Polygon(rings[i]) for i in ids.tolist()]
    polys = polys[b]
    probe = flat[starts[a]]
    inside = shapely.contains_xy(polys, probe[:, 0], probe[:, 1])
    return np.stack([a[inside], b[inside]], axis=1).astype(np.int64)


def order_rings(rings, *, start=(0.0, 0.0), end=None, nested: bool = True) -> np.ndarray:
    """The order to cut closed ``rings`` in: short travel from ``start`` (to ``end``, when given),
    enclosed rings first.

    ``nested=False`` skips the enclosure test (rings known to lie side by side). Never
    longer than the order given, when that one keeps the nesting.
    """
    pairs = enclosing_pairs(rings) if nested else np.zeros((0, 2), np.int64)
    first = np.array([r[0] for r in rings], float).reshape(-1, 2)
    return _order(first, first, start=start, end=end, flip=False, pairs=pairs)[0]


def order_paths(paths: dict, *, outer_closed: bool = True, start=(0.0, 0.0), thorough: bool = False) -> dict:
    """A plan's paths (role -> list of arrays, in cut order of roles) with each role's paths reordered.

    Each role starts where the one before it ended (from ``start``); the engrave
    layer's rings keep their order (its fill is swept line by line, not path by path).
    Open score lines may come out reversed. ``thorough``: the score lines' order is then
    polished by :func:`_polish` (a pen's strokes, see :mod:`.pen`).
    """
    out = dict(paths)
    for role, (order, flipped) in path_orders(paths, outer_closed=outer_closed, start=start, thorough=thorough).items():
        rings = [np.asarray(r, float) for r in paths[role]]
        out[role] = [rings[i][::-1] if f else rings[i] for i, f in zip(order.tolist(), flipped.tolist(), strict=True)]
    return out


def path_orders(paths: dict, *, outer_closed: bool = True, start=(0.0, 0.0), thorough: bool = False) -> dict:
    """:func:`order_paths`' orders: role -> ``(order, flipped)``, the paths' indices in cut order and
    whether each runs backwards (so a plan can reorder what it carries along with the paths: their arcs)."""
    out, here = {}, np.asarray(start, float)
    for k, role in enumerate(_ROLES):
        rings = [np.asarray(r, float) for r in paths.get(role, ())]
        if not rings:
            continue
        if role == "engrave":
            out[role] = (np.arange(len(rings)), np.zeros(len(rings), bool))
            here = rings[-1][0]
            continue
        closed, first, last, pairs = _role_ends(role, rings, outer_closed)
        end = _next_start(paths, _ROLES[k + 1 :], outer_closed)
        order, flipped = _order(
            first,
            last,
            start=here,
            end=end,
            flip=role == "score",
            pairs=pairs,
            two_opt=closed or role == "score",
            thorough=thorough and role == "score",
        )
        out[role] = (order, flipped)
        end = rings[order[-1]][::-1] if flipped[-1] else rings[order[-1]]
        here = end[0] if closed else end[-1]
    return out


def order_strokes(first, last, *, start=(0.0, 0.0), given=None) -> tuple:
    """``(order, flipped)`` of open strokes that may run backwards (a pen's), from ``start``, ``first``
    and ``last`` their end points ``(n, 2)``.

    Up to :data:`POLISH_MAX` strokes: the greedy tours from ``start`` and (with an order
    ``given``, ``(order, flipped)``, e.g. a hatch's boustrophedon) from the given order's first
    stroke, as vpype's ``linesort`` starts, and the given order itself, each improved by
    neighbour-list 2-opt and polished by :func:`_polish`; the shortest is returned. More strokes,
    up to :data:`TWO_OPT_MAX`: the order given improved by full 2-opt alone (the or-opt moves
    are the polish's time). More still keep the order given, which is then made by a method
    that scales (the greedy tour's and 2-opt's Python loops would be the whole time of a large
    plot); without one, the greedy tour.
    """
    first, last = np.asarray(first, float), np.asarray(last, float)
    n = len(first)
    if given is not None and n > POLISH_MAX:
        order, flipped = np.asarray(given[0], np.int64), np.asarray(given[1], bool)
        if n > TWO_OPT_MAX:
            return order, flipped
        return _polish(first, last, order, flipped, start, or_opt=())
    if n < 2:
        return np.zeros(n, np.int64), np.zeros(n, bool)
    pairs = np.zeros((0, 2), np.int64)
    ends, exits = np.concatenate([first, last]), np.concatenate([last, first])
    near = _near(ends, exits, NEIGHBOURS // 2 + 1)
    origins = [] if given is not None else [np.asarray(start, float)]
    tours = []
    if given is not None:
        tours.append((np.asarray(given[0], np.int64).copy(), np.asarray(given[1], bool).copy()))
        g, f = int(tours[0][0][0]), bool(tours[0][1][0])
        origins.append(last[g] if f else first[g])
    tours += [_nearest_neighbour(ends, exits, near, n, o, pairs) for o in origins]
    if n > 2:
        nodes = _neighbour_paths(near, n, True)
        for o, f in tours:
            _two_opt(first, last, o, f, nodes, start, None, True, pairs)
    if _polishable(n, True, None, pairs):
        tours = [_polish(first, last, *t, start) for t in tours]
    return min(tours, key=lambda t: _cost(first, last, t[0], t[1], start))


_ROLES = ("engrave", "score", "inner", "outer")
"""The roles in the order they are cut."""


def _role_ends(role: str, rings: list, outer_closed: bool):
    """``(closed, first, last, pairs)`` of a layer's paths: whether they are closed, each one's first and
    last point, and the nesting (``(inside, around)``: the inner rings only) the order must keep."""
    closed = role in ("inner", "outer") and (role == "inner" or outer_closed)
    first = np.array([r[0] for r in rings], float)
    last = first if closed else np.array([r[-1] for r in rings], float)
    pairs = enclosing_pairs(rings) if role == "inner" else np.zeros((0, 2), np.int64)
    return closed, first, last, pairs


def _next_start(paths: dict, after: tuple, outer_closed: bool):
    """Where the next layer's cut starts when it is one closed contour (a tile's outline), else None:
    the layer before ends its travel there."""
    after = [r for r in after if len(paths.get(r, ()))]
    fixed = after and len(paths[after[0]]) == 1 and (after[0] == "inner" or (after[0] == "outer" and outer_closed))
    return np.asarray(paths[after[0]][0][0], float) if fixed else None


def _order(first, last, *, start, end=None, flip: bool, pairs, two_opt: bool = True, thorough: bool = False):
    """``(order, flipped)`` of paths from ``first`` to ``last`` points: nearest neighbour, then 2-opt.

    ``flip``: a path may be run backwards. ``pairs``: ``(inside, around)``, ``inside``
    must come before ``around``. ``end``: where the head goes after the last path (counted).
    ``thorough``: open paths that may run backwards, with no nesting and no ``end``, are
    then polished by :func:`_polish` (up to :data:`POLISH_MAX` paths).
    """
    n = len(first)
    if n < 2:
        return np.zeros(n, np.int64), np.zeros(n, bool)
    # entering at ends[q] leaves at exits[q]: path q % n, run backwards when q >= n
    ends = np.concatenate([first, last]) if flip else first
    exits = np.concatenate([last, first]) if flip else last
    near = _near(ends, exits, NEIGHBOURS // 2 + 1 if flip else NEIGHBOURS + 1)
    order, flipped = _nearest_neighbour(ends, exits, near, n, np.asarray(start, float), pairs)
    tours = [(order, flipped)]
    if not flip and _keeps_nesting(pairs):
        # the order given, when it keeps the nesting, is a start too: the greedy tour is not always
        # shorter (two rows of holes and the Hilbert curve's order: 716 mm against 770 mm)
        tours.append((np.arange(n), np.zeros(n, bool)))
    if two_opt and n > 2:
        nodes = _neighbour_paths(near, n, flip)
        for o, f in tours:
            _two_opt(first, last, o, f, nodes, start, end, flip, pairs)
    best = min(tours, key=lambda t: _cost(first, last, t[0], t[1], start, end))
    if thorough and _polishable(n, flip, end, pairs):
        best = _polish(first, last, *best, start)
    return best


def _keeps_nesting(pairs) -> bool:
    """Whether the order given (path 0 first) cuts each path inside another before it."""
    return not len(pairs) or bool(np.all(pairs[:, 0] < pairs[:, 1]))


def _neighbour_paths(near: list, n: int, flip: bool) -> list:
    """Per path, the other paths among its neighbours (either end's, when paths may run backwards)."""
    return [sorted({c % n for c in near[q] + (near[q + n] if flip else [])} - {q}) for q in range(n)]


def _polishable(n: int, flip: bool, end, pairs) -> bool:
    """Whether :func:`_polish` takes these paths on: open ones that may run backwards, to a free end,
    with no nesting, at most :data:`POLISH_MAX` of them."""
    return flip and end is None and not len(pairs) and 2 < n <= POLISH_MAX


POLISH_MAX = 1500
"""The most paths :func:`_polish` takes on: its rounds are O(n^2) (in numpy), quick for a 150 mm
tile's few hundred strokes and too long for a sheet's thousands (``docs/speed.md``): larger drawings
keep the neighbour-list 2-opt."""


TWO_OPT_MAX = 10000
"""The most strokes :func:`order_strokes` improves by full 2-opt (a round is O(n^2) in numpy):
a hatch layer of a few thousand strokes, the size where its boustrophedon order is left a few
percent longer than vpype's ``linesort --two-opt`` makes it (``docs/speed.md``)."""


def _polish(first, last, order, flipped, start, max_rounds: int = 50, or_opt=(1, 2, 3)):
    """``(order, flipped)`` improved by full 2-opt and or-opt until neither shortens the travel.

    For open paths that may run backwards, from ``start`` to a free end (a pen's strokes).
    2-opt reverses a stretch of the order (each path in it run backwards), trying every
    stretch from each position, as vpype's ``linesort --two-opt`` does; or-opt moves a run of
    one, two or three paths to the best place elsewhere, either way round. Neighbour-list
    2-opt (:func:`_two_opt`) leaves chains of strokes that meet end to end apart, which a move
    of one path joins; a pen's plot has many (its strands end at the outline and at each other).
    """
    entry = np.where(flipped[:, None], last[order], first[order])
    leave = np.where(flipped[:, None], first[order], last[order])
    e = entry[:, 0] + 1j * entry[:, 1]
    x = leave[:, 0] + 1j * leave[:, 1]
    s = complex(float(start[0]), float(start[1]))
    idx, fl = np.asarray(order, np.int64).copy(), np.asarray(flipped, bool).copy()
    for _ in range(max_rounds):
        improved = _two_opt_round(e, x, idx, fl, s)
        for size in or_opt:
            e, x, idx, fl, moved = _or_opt_round(e, x, idx, fl, s, size)
            improved |= moved
        if not improved:
            break
    return idx, fl


def _two_opt_round(e, x, idx, fl, s) -> bool:
    """One round of full 2-opt (:func:`_polish`), in place: from each position, the stretch whose
    reversal shortens the travel most is reversed. Returns whether any was.

    ``e``, ``x``: each path's entry and exit (complex), in order; ``idx``, ``fl``: the paths
    and whether each runs backwards; ``s``: the start.
    """
    improved = False
    for lo in range(len(e)):  # 2-opt: the stretch lo..hi reversed
        p = s if lo == 0 else x[lo - 1]
        gain = np.abs(e[lo] - p) - np.abs(x[lo:] - p)
        gain[:-1] += np.abs(e[lo + 1 :] - x[lo:-1]) - np.abs(e[lo + 1 :] - e[lo])
        k = int(np.argmax(gain))
        if gain[k] > 1e-9:
            r = slice(lo, lo + k + 1)
            e[r], x[r] = x[r][::-1].copy(), e[r][::-1].copy()
            idx[r], fl[r] = idx[r][::-1].copy(), ~fl[r][::-1]
            improved = True
    return improved


def _or_opt_round(e, x, idx, fl, s, size: int):
    """One round of or-opt (:func:`_polish`): each run of ``size`` paths moved to the place, either way
    round, that shortens the travel most. Returns ``(e, x, idx, fl, whether any moved)``, as
    :func:`_two_opt_round` takes them."""
    n = len(e)
    improved = False
    # place k puts the run after position k - 1 (k = 0: first): between before[k] and after[k]
    before, after, link, tail = _places(e, x, s)
    i = 0
    while i + size <= n:
        j = i + size - 1
        p = s if i == 0 else x[i - 1]
        a, b = e[i], x[j]
        saved = abs(a - p) + (abs(e[j + 1] - b) - abs(e[j + 1] - p) if j + 1 < n else 0.0)
        ahead = np.abs(a - before) + np.abs(after - b) * tail - link
        back = np.abs(b - before) + np.abs(after - a) * tail - link
        ahead[i : j + 2] = back[i : j + 2] = np.inf  # its own place, and inside the run
        fa, fb = int(np.argmin(ahead)), int(np.argmin(back))
        cost, at, rev = (ahead[fa], fa, False) if ahead[fa] <= back[fb] else (back[fb], fb, True)
        if saved - cost > 1e-9:
            e, x, idx, fl = _moved_run(e, x, idx, fl, i, j, at, rev)
            before, after, link, tail = _places(e, x, s)
            improved = True
        i += 1
    return e, x, idx, fl, improved


def _moved_run(e, x, idx, fl, i: int, j: int, at: int, rev: bool):
    """``(e, x, idx, fl)`` with the run of paths i..j moved to place ``at`` (see :func:`_places`),
    run backwards if ``rev``."""
    run = slice(i, j + 1)
    re, rx, ri, rf = e[run].copy(), x[run].copy(), idx[run].copy(), fl[run].copy()
    if rev:
        re, rx, ri, rf = rx[::-1], re[::-1], ri[::-1], ~rf[::-1]
    rest = np.r_[0:i, j + 1 : len(e)]
    cut = at if at < i else at - (j + 1 - i)  # the place among the paths left
    e = np.concatenate([e[rest[:cut]], re, e[rest[cut:]]])
    x = np.concatenate([x[rest[:cut]], rx, x[rest[cut:]]])
    idx = np.concatenate([idx[rest[:cut]], ri, idx[rest[cut:]]])
    fl = np.concatenate([fl[rest[:cut]], rf, fl[rest[cut:]]])
    return e, x, idx, fl


def _places(e, x, s):
    """The places between paths (:func:`_polish`): the point before each (``s``, then every exit),
    the point after (every entry; the last place has none: ``tail`` 0) and the link they make."""
    before = np.concatenate([[s], x])
    after = np.concatenate([e, [0]])
    tail = np.ones(len(before))
    tail[-1] = 0.0
    return before, after, np.abs(after - before) * tail, tail


def _cost(first, last, order, flipped, start, end=None) -> float:
    """The travel of ``order`` (paths ``flipped`` run backwards) from ``start`` (to ``end``)."""
    entry = np.where(flipped[:, None], last[order], first[order])
    leave = np.where(flipped[:, None], first[order], last[order])
    before = np.vstack([np.asarray(start, float)[None], leave[:-1]])
    tail = 0.0 if end is None else float(np.hypot(*(np.asarray(end, float) - leave[-1])))
    return float(np.hypot(*(entry - before).T).sum()) + tail


def _near(ends, exits, k: int) -> list:
    """For each exit point, the indices of the ``k`` nearest ``ends`` (fewer where the points are sparse).

    GEOS's R-tree and its ``dwithin`` query within the radius that holds about ``2 k`` points at the
    points' mean density, then the ``k`` nearest of those found. (scipy's cKDTree does it in one call,
    but importing scipy.spatial costs more than the whole order.) The tree is asked first with a
    64th of that radius, then for the exits that found fewer than ``k`` twice that, up to the whole
    radius: where the points crowd far above their mean density (score lines meeting by the thousand
    at one point, or crossing at a shallow angle in pieces hundredths of a millimetre long) no exit
    gathers thousands of them. The tree returns what a smaller radius finds in the same order, so the
    lists are the one query's.
    """
    m = len(ends)
    lo, hi = ends.min(axis=0), ends.max(axis=0)
    area = max(float(np.prod(np.maximum(hi - lo, 1e-6))), 1e-12)
    reach = float(np.sqrt(2 * k * area / (np.pi * m)))
    tree = shapely.STRtree(shapely.points(ends))
    found_a, found_b = [], []
    todo, r = np.arange(len(exits)), reach / 64
    while len(todo):
        a, b = tree.query(shapely.points(exits[todo]), predicate="dwithin", distance=r)
        done = (np.bincount(a, minlength=len(todo)) >= k) | (r >= reach)
        keep = done[a]
        found_a.append(todo[a[keep]])
        found_b.append(b[keep])
        todo, r = todo[~done], min(2 * r, reach)
    a, b = np.concatenate(found_a), np.concatenate(found_b)
    d = np.hypot(*(exits[a] - ends[b]).T)
    o = np.lexsort((d, a))
    a, b = a[o], b[o]
    starts = np.searchsorted(a, np.arange(len(exits)))
    rank = np.arange(len(a)) - starts[a]
    keep = rank < k
    a, b = a[keep], b[keep]
    return [x.tolist() for x in np.split(b, np.searchsorted(a, np.arange(1, len(exits))))]


def _nearest_neighbour(ends, exits, near, n, start, pairs):
    """The greedy order: from where the head is, the nearest path not cut whose enclosed paths are cut.

    The path's neighbour list answers most steps; the rest ask an R-tree of the paths
    left, rebuilt whenever half of those it holds are cut, with a radius doubled until
    a path is found.
    """
    waiting, around = _nesting_lists(pairs, n)
    done = [False] * n
    order, entered = [], []
    m = len(ends)
    live, live_tree, cut_since = np.arange(m), shapely.STRtree(shapely.points(ends)), 0
    reach = float(np.hypot(*(ends.max(axis=0) - ends.min(axis=0)))) + 1.0
    step = reach / np.sqrt(m)
    q = -1
    for _ in range(n):
        pick = _first_free(near[q], done, waiting, n) if q >= 0 else -1
        if pick < 0:
            point = start if q < 0 else exits[q]
            pick = _nearest_free(ends, point, live, live_tree, step, reach, done, waiting, n)
        node = pick % n
        done[node] = True
        order.append(node)
        entered.append(pick)
        for b in around[node]:
            waiting[b] -= 1
        cut_since += m // n
        if 2 * cut_since > len(live) and len(order) < n:
            live = np.array([i for i in range(m) if not done[i % n]])
            live_tree, cut_since = shapely.STRtree(shapely.points(ends[live])), 0
        q = pick
    order = np.array(order, np.int64)
    return order, np.array(entered, np.int64) >= n


def _nesting_lists(pairs, n: int) -> tuple[list, list]:
    """``(waiting, around)``: per path, how many paths inside it are still to be cut, and the paths around it."""
    waiting = np.bincount(pairs[:, 1], minlength=n).tolist() if len(pairs) else [0] * n
    around: list[list] = [[] for _ in range(n)]
    for a, b in pairs.tolist():
        around[a].append(b)
    return waiting, around


def _first_free(near: list, done: list, waiting: list, n: int) -> int:
    """The first of the neighbours ``near`` whose path is not cut and waits for none, or -1."""
    for c in near:
        if not done[c % n] and not waiting[c % n]:
            return c
    return -1


def _nearest_free(ends, point, live, live_tree, step: float, reach: float, done: list, waiting: list, n: int) -> int:
    """The end nearest ``point`` whose path is not cut and waits for none, asking the R-tree of the
    ``live`` ends with a radius doubled from ``step`` until one is found (past ``reach``: all ends)."""
    where, r = shapely.Point(point), step
    far = 2 * reach + float(np.hypot(*(np.asarray(point) - ends.min(axis=0))))
    while True:
        found = live[live_tree.query(where, predicate="dwithin", distance=r)] if r < far else np.arange(len(ends))
        ok = [c for c in found.tolist() if not done[c % n] and not waiting[c % n]]
        if ok:
            d = np.hypot(*(ends[ok] - point).T)
            return ok[int(np.argmin(d))]
        r *= 2


def _two_opt(first, last, order, flipped, nodes, start, end, flip, pairs):
    """2-opt in place on ``order`` (and ``flipped``): reverse a stretch of the order while that
    shortens the travel, trying each path against its neighbours (``nodes``), the paths
    next to a change tried again. A stretch run backwards runs each of its paths backwards:
    the same length for a closed path (it ends where it starts), the right one for an open path
    that may be reversed. A stretch holding a path and one around it is never reversed.
    """
    n = len(order)
    fx, fy, lx, ly, (sx, sy), (ex, ey) = _scalar_points(first, last, start, end)
    pos = np.empty(n, np.int64)
    pos[order] = np.arange(n)
    fl = flipped  # by position in the order: kept aligned with it
    hyp = math.hypot

    def entry(node, f):
        return (lx[node], ly[node]) if f else (fx[node], fy[node])

    def exit_(node, f):
        return (fx[node], fy[node]) if f else (lx[node], ly[node])

    queue = deque(order.tolist())
    queued = [True] * n
    while queue:
        a = queue.popleft()
        queued[a] = False
        for c in nodes[a]:
            i, j = int(pos[a]), int(pos[c])
            moves = ((i + 1, j), (i, j - 1)) if j > i else ((j + 1, i), (j, i - 1))
            best = None
            for lo, hi in moves:
                if hi <= lo:
                    continue
                tl, th = int(order[lo]), int(order[hi])
                px, py = (sx, sy) if lo == 0 else exit_(int(order[lo - 1]), fl[lo - 1])
                ax, ay = entry(tl, fl[lo])
                bx, by = exit_(th, fl[hi])
                gain = hyp(ax - px, ay - py) - hyp(bx - px, by - py)
                if hi < n - 1 or end is not None:
                    nx, ny = entry(int(order[hi + 1]), fl[hi + 1]) if hi < n - 1 else (ex, ey)
                    gain += hyp(nx - bx, ny - by) - hyp(nx - ax, ny - ay)
                if gain > 1e-9:
                    best = (lo, hi)
                    break
            if best is not None and _reverse_stretch(order, fl, pos, *best, flip, pairs):
                _requeue(queue, queued, order, *best, a)
                break


def _scalar_points(first, last, start, end):
    """``(fx, fy, lx, ly, (sx, sy), (ex, ey))``: the paths' first and last points, the start and the end
    (none: the origin, not counted) as Python floats, for :func:`_two_opt`'s scalar loop."""
    ends = (0.0, 0.0) if end is None else (float(end[0]), float(end[1]))
    xy = (first[:, 0].tolist(), first[:, 1].tolist(), last[:, 0].tolist(), last[:, 1].tolist())
    return (*xy, (float(start[0]), float(start[1])), ends)


def _reverse_stretch(order, fl, pos, lo: int, hi: int, flip: bool, pairs) -> bool:
    """Reverse the stretch lo..hi of ``order`` in place (its paths run backwards if ``flip``), unless it
    holds a path and one around it (``pairs``). Returns whether it was reversed."""
    if len(pairs):
        pi, pa = pos[pairs[:, 0]], pos[pairs[:, 1]]
        if np.any((np.minimum(pi, pa) >= lo) & (np.maximum(pi, pa) <= hi)):
            return False
    order[lo : hi + 1] = order[lo : hi + 1][::-1].copy()
    if flip:
        fl[lo : hi + 1] = ~fl[lo : hi + 1][::-1]
    pos[order[lo : hi + 1]] = np.arange(lo, hi + 1)
    return True


def _requeue(queue, queued: list, order, lo: int, hi: int, a: int) -> None:
    """Queue again the paths next to the ends of a reversed stretch lo..hi, and path ``a``."""
    for p in (lo - 1, lo, hi, hi + 1):
        if 0 <= p < len(order):
            node = int(order[p])
            if not queued[node]:
                queued[node] = True
                queue.append(node)
    if not queued[a]:
        queued[a] = True
        queue.append(a)
