"""Interlace: strands through the centre-lines and an alternating over/under (``docs/tile-operation.md``, "Interlace").

Pure numpy. From centre-line segments ``(k, 2, 2)``:

1. **Node.** Endpoints closer than :data:`MERGE` are one vertex. Crossings are
   found with a uniform grid (each segment is entered in the cells its bounding
   box covers; only segments sharing a cell are tested), so the search is linear
   in the segments for a pattern of bounded density, not quadratic. Two segments
   crossing in their interiors get a new vertex there; an endpoint lying on
   another segment's interior splits that segment (a T).
2. **Pair the ends at each vertex.** Two ends: the strand goes on (a tip or bend
   turns it, a straight joint continues it). Four ends as two straight lines
   (an interior crossing, or four segment ends meeting that way): a
   **crossing**, each strand goes straight through. Any other vertex (a T, three
   or more lines through one point, two tips touching) is a **knot**: ends that
   continue each other in a straight line are paired, starting with the
   straightest, the others end there. A knot is never over or under: the bands
   meeting there stay joined at full height, and the alternation along each
   strand counts the two-strand crossings only, so it holds across a knot.
3. **Walk every strand once** (open strands from an end, then the closed loops),
   numbering its crossings along the way: linear in the pieces.
4. **Assign over/under.** Along a strand the crossings alternate, so each
   strand has one free bit (is its first crossing over or under?). Each
   crossing ties the bits of its two strands; a breadth-first search over the
   strands sets them. A planar arrangement of closed curves always admits an
   alternating weave; a tie that cannot hold (possible only with strands that
   end inside the pattern) is counted in :attr:`Weave.conflicts` and that one
   crossing keeps its first strand's choice.

>>> import numpy as np
>>> x = np.array([[[-1, 0], [1, 0]], [[0, -1], [0, 1]]], float)   # a plus sign
>>> w = weave(x)
>>> w.points.tolist(), w.over.tolist(), w.under.tolist(), w.conflicts
([[0.0, 0.0]], [0], [1], 0)
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np

MERGE = 1e-6
"""Endpoints closer than this (in the segments' units) are one vertex."""

STRAIGHT = 1e-6
"""Segments whose directions differ by a sine below this are parallel: they never cross."""

BEND_DEG = 30.0
"""Two ends at a vertex of three or more continue each other when they bend by less than this.

The plain 8-pointed star of the paper (table1-part1, radii 51, 70, 172) meets
at each inner point as two lines bent by 3.9 degrees: a crossing, not a knot.
"""

_COS_BEND = float(np.cos(np.radians(BEND_DEG)))


@dataclass(frozen=True)
class Weave:
    """The crossings of a set of centre-lines, each with its over and under strand.

    Attributes
    ----------
    points : ndarray (c, 2)
        Crossing points.
    over, under : ndarray (c,)
        Index (into the input segments) of a segment of the over / under strand
        that passes through the crossing.
    over_dir, under_dir : ndarray (c, 2)
        Unit directions of the over and under strands there.
    sin : ndarray (c,)
        ``|sin|`` of the angle between the two strands (> 0).
    strand : ndarray (k,)
        Strand id of every input segment (-1 for a degenerate one).
    knots : ndarray (m, 2)
        Points where three or more lines (or a T) meet: no over/under there.
    ends : ndarray (e, 2)
        Points where a strand ends (a free tip, a T's stem, an unpaired end at a knot).
    conflicts : int
        Crossings where the alternation could not hold. 0 when no strand ends
        (closed strands always alternate); strands that end inside the pattern
        can make it impossible, and then along the second strand of each such
        crossing the alternation breaks there.
    pieces : ndarray (p, 2, 2)
        The segments cut at every crossing and knot, each oriented along its strand.
    piece_strand, piece_segment, piece_start : ndarray (p,)
        Strand of each piece, the input segment it is part of, and the arc
        length along the strand where it starts.
    strand_length : ndarray (s,)
        Length of each strand; ``strand_closed`` (s,) says whether it is a loop.
    visit_strand, visit_pos, visit_crossing, visit_over : ndarray (2c,)
        The crossings along the strands: strand, arc length, crossing, and
        whether the strand is over there.
    """

    points: np.ndarray
    over: np.ndarray
    under: np.ndarray
    over_dir: np.ndarray
    under_dir: np.ndarray
    sin: np.ndarray
    strand: np.ndarray
    knots: np.ndarray
    ends: np.ndarray
    conflicts: int
    pieces: np.ndarray
    piece_strand: np.ndarray
    piece_segment: np.ndarray
    piece_start: np.ndarray
    strand_length: np.ndarray
    strand_closed: np.ndarray
    visit_strand: np.ndarray
    visit_pos: np.ndarray
    visit_crossing: np.ndarray
    visit_over: np.ndarray

    def __len__(self) -> int:
        return len(self.points)

    def under_gaps(self, half_width, gap) -> np.ndarray:
        """Intervals ``(c, 2)`` of arc length along each under strand that a crossing hides.

        The over band (``half_width`` each side of its centre-line) plus ``gap``
        each side, measured along the under strand: half length
        ``(half_width + gap) / sin``. Rows follow :attr:`points`.
        """
        sel = ~self.visit_over
        order = np.argsort(self.visit_crossing[sel])
        pos = self.visit_pos[sel][order]
        half = (half_width + gap) / self.sin
        return np.stack([pos - half, pos + half], axis=1)

    def max_gap(self, half_width) -> float:
        """Largest gap before the gaps along some strand add up to its whole length.

        A strand's gaps (one per crossing where it is under, ``2 (half_width + gap) /
        sin`` long each) swallow it when their total reaches its length; this is the
        largest ``gap`` below that for every strand (negative when the over bands
        alone swallow a strand; ``inf`` without crossings).

        >>> w = weave(np.array([[[0, 0], [4, 0]], [[1, -1], [1, 1]], [[3, -1], [3, 1]]], float))
        >>> round(w.max_gap(0.25), 6)
        0.75
        """
        sel = ~self.visit_over
        if not sel.any():
            return float("inf")
        strand = self.visit_strand[sel]
        inv_sin = 1.0 / self.sin[self.visit_crossing[sel]]
        n = len(self.strand_length)
        total_inv = np.bincount(strand, weights=inv_sin, minlength=n)
        has = total_inv > 0
        # sum over gaps 2 (h + g) / sin_i < L  <=>  g < (L / 2 - h S) / S, S = sum 1 / sin_i
        limit = (self.strand_length[has] / 2 - half_width * total_inv[has]) / total_inv[has]
        return float(limit.min())

    def straight_reach(self) -> np.ndarray:
        """How far each under strand runs straight on from its crossing: ``(c, 2)``, back and forward.

        Arc length along the under strand (in the direction it is walked, that of
        :attr:`under_dir`) from the crossing to where the strand bends, ends or
        reaches its start (a loop's run is not followed round its start; a knot
        does not stop a straight run). Rows follow :attr:`points`; both 0 where
        the strand bends at the crossing itself (by more than 1e-9 in sine: a
        crossing may bend each strand by up to :data:`BEND_DEG`).

        >>> x = np.array([[[-1, 0], [3, 0]], [[0, -1], [0, 1]], [[0, 1], [1, 2]]], float)
        >>> w = weave(x)   # the vertical strand is under, and bends at (0, 1)
        >>> w.under.tolist(), w.straight_reach().round(6).tolist()
        ([1], [[1.0, 1.0]])
        """
        c = len(self.points)
        if not c:
            return np.zeros((0, 2))
        order = np.lexsort((self.piece_start, self.piece_strand))
        seg = self.pieces[order]
        strand, start = self.piece_strand[order], self.piece_start[order]
        d = seg[:, 1] - seg[:, 0]
        length = np.linalg.norm(d, axis=1)
        d = d / length[:, None]
        end = start + length
        turn = (np.abs(_cross(d[1:], d[:-1])) > 1e-9) | (np.sum(d[1:] * d[:-1], axis=1) <= 0)
        gap = np.abs(start[1:] - end[:-1]) > MERGE
        new_run = np.r_[True, (strand[1:] != strand[:-1]) | turn | gap]
        head = np.flatnonzero(new_run)
        run_lo = start[head]
        run_hi = np.maximum.reduceat(end, head)
        run = np.cumsum(new_run) - 1
        # every strand on one axis (as in broken_pieces): the piece leaving each crossing
        offset = np.concatenate([[0.0], np.cumsum(self.strand_length + 1.0)])[:-1]
        sel = ~self.visit_over
        crossing = self.visit_crossing[sel]
        s, pos = self.visit_strand[sel], self.visit_pos[sel]
        k = np.clip(np.searchsorted(offset[strand] + start, offset[s] + pos + MERGE, side="right") - 1, 0, None)
        r = run[k]
        through = (k > 0) & (run[np.maximum(k - 1, 0)] == r)  # the piece ending there is in the run too
        out = np.zeros((c, 2))
        out[crossing, 0] = np.where(through, np.maximum(pos - run_lo[r], 0.0), 0.0)
        out[crossing, 1] = np.where(through, np.maximum(run_hi[r] - pos, 0.0), 0.0)
        return out

    def broken_pieces(self, half_width, gap) -> np.ndarray:
        """The pieces with each under strand's gap removed: ``(q, 2, 2)`` segments.

        The score lines of a woven tile: a strand's centre-line stops ``gap``
        before the over band and starts again ``gap`` after it.

        >>> x = np.array([[[-1, 0], [1, 0]], [[0, -1], [0, 1]]], float)
        >>> weave(x).broken_pieces(0.1, 0.05).round(3).tolist()
        [[[-1.0, 0.0], [1.0, 0.0]], [[0.0, -1.0], [0.0, -0.15]], [[0.0, 0.15], [0.0, 1.0]]]
        """
        if not len(self.pieces):
            return self.pieces.copy()
        # every strand on one axis: offset by the lengths before it (plus a spacer)
        offset = np.concatenate([[0.0], np.cumsum(self.strand_length + 1.0)])[:-1]
        gaps = self.under_gaps(half_width, gap)
        ustrand = self.visit_strand[~self.visit_over][np.argsort(self.visit_crossing[~self.visit_over])]
        lo = gaps[:, 0]
        hi = gaps[:, 1]
        total = self.strand_length[ustrand]
        closed = self.strand_closed[ustrand]
        # a loop's gap may wrap round its start
        extra_lo = np.where(lo < 0, lo + total, np.where(hi > total, 0.0, np.nan))
        extra_hi = np.where(lo < 0, total, np.where(hi > total, hi - total, np.nan))
        wrap = closed & np.isfinite(extra_lo)
        g_lo = np.concatenate([np.clip(lo, 0, total), extra_lo[wrap]]) + np.concatenate(
            [offset[ustrand], offset[ustrand[wrap]]]
        )
        g_hi = np.concatenate([np.clip(hi, 0, total), extra_hi[wrap]]) + np.concatenate(
            [offset[ustrand], offset[ustrand[wrap]]]
        )
        order = np.argsort(g_lo)
        g_lo, g_hi = g_lo[order], np.maximum.accumulate(g_hi[order])
        # merge overlapping gaps into disjoint intervals
        start = np.r_[np.ones(min(len(g_lo), 1), bool), g_lo[1:] > g_hi[:-1]]  # none without crossings
        m_lo = g_lo[start]
        m_hi = np.maximum.reduceat(g_hi, np.flatnonzero(start)) if len(g_hi) else g_hi
        # kept intervals: the complement of the gaps
        k_lo = np.concatenate([[-np.inf], m_hi])
        k_hi = np.concatenate([m_lo, [np.inf]])
        length = np.linalg.norm(self.pieces[:, 1] - self.pieces[:, 0], axis=1)
        a = offset[self.piece_strand] + self.piece_start
        b = a + length
        first = np.searchsorted(k_hi, a, side="right")  # first kept interval ending after a
        last = np.searchsorted(k_lo, b, side="left") - 1  # last kept interval starting before b
        cnt = np.maximum(last - first + 1, 0)
        pid = np.repeat(np.arange(len(a)), cnt)
        kid = np.repeat(first, cnt) + (np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt))
        s0 = np.maximum(a[pid], k_lo[kid])
        s1 = np.minimum(b[pid], k_hi[kid])
        keep = s1 - s0 > MERGE
        pid, s0, s1 = pid[keep], s0[keep], s1[keep]
        # join the pieces of one input segment that no gap separates (fewer score lines)
        order = np.argsort(s0, kind="stable")
        pid, s0, s1 = pid[order], s0[order], s1[order]
        seg = self.piece_segment[pid]
        join = (seg[1:] == seg[:-1]) & (np.abs(s0[1:] - s1[:-1]) <= MERGE)
        head = np.flatnonzero(np.r_[True, ~join])
        tail = np.r_[head[1:], len(pid)] - 1
        start = self.pieces[pid[head], 0] + ((s0[head] - a[pid[head]]) / length[pid[head]])[:, None] * (
            self.pieces[pid[head], 1] - self.pieces[pid[head], 0]
        )
        end = self.pieces[pid[tail], 0] + ((s1[tail] - a[pid[tail]]) / length[pid[tail]])[:, None] * (
            self.pieces[pid[tail], 1] - self.pieces[pid[tail], 0]
        )
        return np.stack([start, end], axis=1)


# --------------------------------------------------------------------------- noding


def _candidate_pairs(seg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (i < j) of segments whose bounding boxes share a grid cell."""
    k = len(seg)
    lo = seg.min(axis=1)
    hi = seg.max(axis=1)
    span = np.maximum(hi.max(axis=0) - lo.min(axis=0), MERGE)
    length = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1)
    # a cell about the typical segment length: each segment in a few cells, a few segments a cell
    cell = max(float(np.median(length)), float(np.sqrt(span[0] * span[1] / max(k, 1))), MERGE * 10)
    origin = lo.min(axis=0)
    i0 = np.floor((lo - origin) / cell).astype(np.int64)
    i1 = np.floor((hi - origin) / cell).astype(np.int64)
    nx = np.maximum(i1[:, 0] - i0[:, 0] + 1, 1)
    ny = np.maximum(i1[:, 1] - i0[:, 1] + 1, 1)
    cnt = nx * ny
    sid = np.repeat(np.arange(k), cnt)
    r = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    cx = i0[sid, 0] + r % nx[sid]
    cy = i0[sid, 1] + r // nx[sid]
    key = cx * (int(i1[:, 1].max()) + 2) + cy
    order = np.lexsort((sid, key))
    key, sid = key[order], sid[order]
    start = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
    end = np.r_[start[1:], len(key)]
    group_end = np.repeat(end, end - start)
    pos = np.arange(len(key))
    n_after = group_end - pos - 1
    a = np.repeat(pos, n_after)
    b = a + 1 + (np.arange(n_after.sum()) - np.repeat(np.cumsum(n_after) - n_after, n_after))
    i, j = sid[a], sid[b]  # i < j: sorted by segment within a cell
    # each pair once, in the first cell both boxes share (no np.unique over the pairs, which a
    # sheet has by the hundred thousand), and only if the boxes themselves overlap
    c = key[a]
    first = (c // (int(i1[:, 1].max()) + 2) == np.maximum(i0[i, 0], i0[j, 0])) & (
        c % (int(i1[:, 1].max()) + 2) == np.maximum(i0[i, 1], i0[j, 1])
    )
    i, j = i[first], j[first]
    meet = np.all((lo[i] <= hi[j]) & (lo[j] <= hi[i]), axis=1)
    return i[meet], j[meet]


def _point_keys(pts) -> np.ndarray:
    """One key per point rounded to :data:`MERGE`: equal keys for equal rounded points.

    An int64 made of the two rounded coordinates when they fit (a pattern a few
    metres across; ``np.unique`` over int64 keys is several times quicker than over
    rows), else the rows themselves as a void view.
    """
    key = np.round(np.asarray(pts) / MERGE).astype(np.int64)
    if not len(key):
        return np.zeros(0, np.int64)
    key -= key.min(axis=0)
    span = int(key[:, 1].max()) + 1
    if (int(key[:, 0].max()) + 1) * span < (1 << 62):
        return key[:, 0] * span + key[:, 1]
    key = np.ascontiguousarray(key)
    return key.view(np.dtype((np.void, key.dtype.itemsize * 2))).ravel()


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _node(seg: np.ndarray):
    """Merge endpoints, find crossings and T's; return the pieces and their vertices.

    Returns ``(verts, piece_v (p, 2), piece_seg (p,))``.
    """
    pts = seg.reshape(-1, 2)
    _, first, inv = np.unique(_point_keys(pts), return_index=True, return_inverse=True)
    inv = inv.ravel()
    verts = pts[first]
    sv = inv.reshape(-1, 2)
    k = len(seg)
    # split points: (segment, t, vertex)
    sp_seg = [np.arange(k), np.arange(k)]
    sp_t = [np.zeros(k), np.ones(k)]
    sp_v = [sv[:, 0], sv[:, 1]]
    n_verts = len(verts)
    new_pts = []
    if k >= 2:
        i, j = _candidate_pairs(seg)
        share = (sv[i, 0] == sv[j, 0]) | (sv[i, 0] == sv[j, 1]) | (sv[i, 1] == sv[j, 0]) | (sv[i, 1] == sv[j, 1])
        i, j = i[~share], j[~share]
        p, r = seg[i, 0], seg[i, 1] - seg[i, 0]
        q, s = seg[j, 0], seg[j, 1] - seg[j, 0]
        den = _cross(r, s)
        lr, ls = np.linalg.norm(r, axis=1), np.linalg.norm(s, axis=1)
        ok = np.abs(den) > STRAIGHT * lr * ls
        i, j, p, r, q, s, den, lr, ls = (x[ok] for x in (i, j, p, r, q, s, den, lr, ls))
        t = _cross(q - p, s) / den
        u = _cross(q - p, r) / den
        et, eu = MERGE / lr, MERGE / ls
        t_in = (t > et) & (t < 1 - et)
        u_in = (u > eu) & (u < 1 - eu)
        t_end = (np.abs(t) <= et) | (np.abs(t - 1) <= et)
        u_end = (np.abs(u) <= eu) | (np.abs(u - 1) <= eu)
        x = t_in & u_in
        nx = int(x.sum())
        new_v = n_verts + np.arange(nx)
        new_pts.append(p[x] + t[x, None] * r[x])
        sp_seg += [i[x], j[x]]
        sp_t += [t[x], u[x]]
        sp_v += [new_v, new_v]
        n_verts += nx
        # T: an end of one segment on the interior of the other
        tj = u_end & t_in  # j's end on i
        sp_seg.append(i[tj])
        sp_t.append(t[tj])
        sp_v.append(np.where(np.abs(u[tj]) <= eu[tj], sv[j[tj], 0], sv[j[tj], 1]))
        ti = t_end & u_in  # i's end on j
        sp_seg.append(j[ti])
        sp_t.append(u[ti])
        sp_v.append(np.where(np.abs(t[ti]) <= et[ti], sv[i[ti], 0], sv[i[ti], 1]))
    sp_seg, sp_t, sp_v = np.concatenate(sp_seg), np.concatenate(sp_t), np.concatenate(sp_v)
    if new_pts:
        # three or more lines crossing at one point: their crossings are one vertex
        verts = np.concatenate([verts] + new_pts)
        _, first, inv = np.unique(_point_keys(verts), return_index=True, return_inverse=True)
        verts, sp_v = verts[first], inv.ravel()[sp_v]
    order = np.lexsort((sp_t, sp_seg))
    sp_seg, sp_v = sp_seg[order], sp_v[order]
    nxt = np.r_[sp_seg[1:] == sp_seg[:-1], False]
    a = np.flatnonzero(nxt)
    piece_v = np.stack([sp_v[a], sp_v[a + 1]], axis=1)
    piece_seg = sp_seg[a]
    good = piece_v[:, 0] != piece_v[:, 1]
    return verts, piece_v[good], piece_seg[good]


def _pair_ends(verts, piece_v):
    """Partner end of every piece end (-1: the strand ends), and the crossing and knot vertices.

    End ``2p`` is piece ``p``'s first vertex, ``2p + 1`` its second.
    """
    n_end = 2 * len(piece_v)
    end_v = piece_v.ravel()
    other = piece_v[:, ::-1].ravel()
    d = verts[other] - verts[end_v]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    ang = np.arctan2(d[:, 1], d[:, 0])
    order = np.lexsort((ang, end_v))
    vs = end_v[order]
    start = np.flatnonzero(np.r_[True, vs[1:] != vs[:-1]])
    deg = np.diff(np.r_[start, len(vs)])
    partner = np.full(n_end, -1)
    # two ends: the strand goes on
    s2 = start[deg == 2]
    partner[order[s2]] = order[s2 + 1]
    partner[order[s2 + 1]] = order[s2]
    # four ends sorted by angle, as two straight lines: ends 0-2 and 1-3 are opposite
    s4 = start[deg == 4]
    e = order[s4[:, None] + np.arange(4)]
    straight = (np.sum(d[e[:, 0]] * d[e[:, 2]], 1) < -_COS_BEND) & (np.sum(d[e[:, 1]] * d[e[:, 3]], 1) < -_COS_BEND)
    ex = e[straight]
    for a, b in ((0, 2), (1, 3)):
        partner[ex[:, a]] = ex[:, b]
        partner[ex[:, b]] = ex[:, a]
    crossings = vs[s4[straight]]
    # knots: pair straight continuations, straightest first; the rest end here
    knot_starts = start[(deg == 3) | (deg > 4)]
    knot_starts = np.concatenate([knot_starts, s4[~straight]])
    for g in np.unique(deg[np.searchsorted(start, knot_starts)]).tolist():
        at = knot_starts[deg[np.searchsorted(start, knot_starts)] == g]
        _pair_knots(partner, order[at[:, None] + np.arange(g)], d)
    knots = vs[knot_starts] if len(knot_starts) else np.empty(0, np.int64)
    return partner, crossings, knots


def _pair_knots(partner, ends, d) -> None:
    """Pair the ends ``(m, g)`` at knots of ``g`` ends (directions ``d``) in ``partner``:
    greedily, the straightest pair first (ties by end number), only pairs within
    :data:`BEND_DEG` of straight, each end at most once.

    Three or four ends (every knot of the samples, thousands on a sheet) hold at most
    the best pair and its complement: numpy, all knots at once; more, a loop.
    """
    g = ends.shape[1]
    xs, ys = np.triu_indices(g, 1)
    ea, eb = ends[:, xs], ends[:, ys]
    dot = np.sum(d[ea] * d[eb], axis=2)
    if g > 4:
        for row in range(len(ends)):
            for k in np.lexsort((eb[row], ea[row], dot[row])).tolist():
                a, b = ea[row, k], eb[row, k]
                if dot[row, k] < -_COS_BEND and partner[a] < 0 and partner[b] < 0:
                    partner[a], partner[b] = b, a
        return
    m = len(ends)
    rows = np.repeat(np.arange(m), len(xs))
    best = np.lexsort((eb.ravel(), ea.ravel(), dot.ravel(), rows)).reshape(m, -1)[:, 0] - np.arange(m) * len(xs)
    picks = [best]
    if g == 4:  # the one pair left disjoint from the best: the other two ends
        picks.append(len(xs) - 1 - best)  # (0,1)-(2,3), (0,2)-(1,3), (0,3)-(1,2) in triu order
    ok = np.ones(m, bool)
    for k in picks:
        r = np.arange(m)
        ok = ok & (dot[r, k] < -_COS_BEND)
        a, b = ea[r[ok], k[ok]], eb[r[ok], k[ok]]
        partner[a], partner[b] = b, a


def weave(segments) -> Weave:
    """The strands of ``segments`` (k, 2, 2) and an alternating over/under at their crossings.

    See the module docstring for the rule.

    >>> import numpy as np
    >>> hash_sign = np.array([[[0, 1], [4, 1]], [[0, 2], [4, 2]], [[1, 0], [1, 3]], [[2, 0], [2, 3]]], float)
    >>> w = weave(hash_sign)
    >>> len(w), w.conflicts, sorted(w.over.tolist() + w.under.tolist()) == [0, 0, 1, 1, 2, 2, 3, 3]
    (4, 0, True)
    """
    seg = np.asarray(segments, dtype=float).reshape(-1, 2, 2)
    k = len(seg)
    verts, piece_v, piece_seg = _node(seg)
    partner, cross_v, knot_v = _pair_ends(verts, piece_v)
    is_cross = np.zeros(len(verts), bool)
    is_cross[cross_v] = True
    plen = np.linalg.norm(verts[piece_v[:, 1]] - verts[piece_v[:, 0]], axis=1)

    strand_of, flip, start_pos, strand_len, strand_closed, v_strand, v_pos, v_vertex, v_piece = _walk(
        partner, piece_v, plen, is_cross
    )
    # index of each visit along its strand (visits are in walk order)
    first_visit = np.r_[True, v_strand[1:] != v_strand[:-1]] if len(v_strand) else np.zeros(0, bool)
    idx = np.arange(len(v_strand)) - np.maximum.accumulate(np.where(first_visit, np.arange(len(v_strand)), 0))
    # the two visits of each crossing
    order = np.argsort(v_vertex, kind="stable")
    va, vb = order[0::2], order[1::2]
    cvert = v_vertex[va]
    n_strand = len(strand_len)
    bit = _assign(n_strand, v_strand[va], v_strand[vb], idx[va], idx[vb])
    a_over = (bit[v_strand[va]] + idx[va]) % 2 == 0
    b_over = (bit[v_strand[vb]] + idx[vb]) % 2 == 0
    conflicts = int(np.count_nonzero(a_over == b_over))
    visit_over = np.zeros(len(v_strand), bool)
    visit_over[va] = a_over
    visit_over[vb] = ~a_over
    over_visit = np.where(a_over, va, vb)
    under_visit = np.where(a_over, vb, va)
    visit_crossing = np.empty(len(v_strand), np.int64)
    visit_crossing[va] = np.arange(len(va))
    visit_crossing[vb] = np.arange(len(va))

    oriented = np.where(flip[:, None], piece_v[:, ::-1], piece_v)
    pieces = verts[oriented]
    pdir = pieces[:, 1] - pieces[:, 0]
    pdir /= np.linalg.norm(pdir, axis=1, keepdims=True)
    odir, udir = pdir[v_piece[over_visit]], pdir[v_piece[under_visit]]
    # Where both strands bend at a crossing, the pieces arriving there can be the two halves of one line (a flat V
    # touching a line with its tip): parallel, they would give the crossing no angle. There each strand's
    # direction is the mean of its pieces arriving and leaving.
    flat = np.abs(_cross(odir, udir)) < STRAIGHT
    if flat.any():
        arriving = v_piece[np.concatenate([over_visit[flat], under_visit[flat]])]
        leaving = partner[(2 * arriving + flip[arriving]) ^ 1] >> 1
        through = pdir[arriving] + pdir[leaving]
        through /= np.linalg.norm(through, axis=1, keepdims=True)
        odir[flat], udir[flat] = np.split(through, 2)
    seg_strand = np.full(k, -1)
    seg_strand[piece_seg] = strand_of
    return Weave(
        points=verts[cvert],
        over=piece_seg[v_piece[over_visit]],
        under=piece_seg[v_piece[under_visit]],
        over_dir=odir,
        under_dir=udir,
        sin=np.abs(_cross(odir, udir)),
        strand=seg_strand,
        knots=verts[knot_v],
        ends=verts[piece_v.ravel()[partner < 0]],
        conflicts=conflicts,
        pieces=pieces,
        piece_strand=strand_of,
        piece_segment=piece_seg,
        piece_start=start_pos,
        strand_length=np.array(strand_len),
        strand_closed=np.array(strand_closed, bool),
        visit_strand=v_strand,
        visit_pos=v_pos,
        visit_crossing=visit_crossing,
        visit_over=visit_over,
    )


def _walk(partner, piece_v, plen, is_cross):
    """Every strand walked once: the pieces in order along it, where it crosses.

    A strand is walked from its lowest open end (a loop: from the first vertex of
    its lowest piece); strands are numbered open ones first, by that end, then
    loops, by that piece. Returns, per piece, its strand, whether it is walked from
    its second vertex, and how far along the strand it starts; per strand, its
    length and whether it is a loop; per visit of a crossing (in walk order), the
    strand, how far along, the vertex and the piece arriving there.

    In numpy (:func:`fabtiles.core.graph.chain_ranks`), not a Python walk over a sheet's
    tens of thousands of pieces. Positions are summed along each strand one piece after
    the other, as a walk would.
    """
    from ..core.graph import chain_ranks, components

    n = len(piece_v)
    m = 2 * n
    linked = np.flatnonzero(partner >= 0)
    label = components(n, linked >> 1, partner[linked] >> 1)  # each strand's lowest piece
    # entry end e of a piece leads to the entry end partner[e ^ 1] of the next: so the
    # entry before e is partner[e] ^ 1. Each strand is two chains, one each way.
    pred = np.where(partner >= 0, partner ^ 1, -1)
    open_end = np.flatnonzero(partner < 0)
    lowest_open = np.full(n, m)
    np.minimum.at(lowest_open, label[open_end >> 1], open_end)
    roots = np.flatnonzero(label == np.arange(n))
    loops = roots[lowest_open[roots] == m]
    pred[2 * loops] = -1  # a loop is cut before its lowest piece, both ways
    pred[partner[2 * loops]] = -1
    head, rank = chain_ranks(pred)
    start = np.where(lowest_open[roots] < m, lowest_open[roots], 2 * roots)  # each strand's first end
    is_open = lowest_open[roots] < m
    order = np.lexsort((np.where(is_open, start, roots), ~is_open))  # open strands by end, then loops
    sid_of_start = np.full(m, -1)
    sid_of_start[start[order]] = np.arange(len(order))
    entry = np.flatnonzero(sid_of_start[head] >= 0)  # the ends a piece is entered by, walking forward
    piece = entry >> 1
    sid = sid_of_start[head[entry]]
    walk = np.lexsort((rank[entry], sid))
    piece, sid, entry = piece[walk], sid[walk], entry[walk]
    n_strand = len(order)
    count = np.bincount(sid, minlength=n_strand)
    reach = _cumulative(plen[piece], count)  # along its strand, where each piece ends
    begin = np.empty(n)
    begin[1:] = reach[:-1]
    first = np.cumsum(count) - count
    begin[first[count > 0]] = 0.0
    strand_of = np.empty(n, np.int64)
    strand_of[piece] = sid
    flip = np.empty(n, bool)
    flip[piece] = (entry & 1).astype(bool)
    start_pos = np.empty(n)
    start_pos[piece] = begin
    strand_len = np.zeros(n_strand)
    ends = count > 0
    strand_len[ends] = reach[(first + count - 1)[ends]]
    vertex = piece_v[piece, 1 - (entry & 1)]  # where each piece is left
    visit = np.flatnonzero(is_cross[vertex])
    return (
        strand_of,
        flip,
        start_pos,
        strand_len,
        ~is_open[order],
        sid[visit],
        reach[visit],
        vertex[visit],
        piece[visit],
    )


def _cumulative(values, count) -> np.ndarray:
    """Running sums of ``values`` restarting every ``count[i]`` values, each one added
    after the other (``np.cumsum`` row by row: the same floats as a loop).

    >>> _cumulative(np.array([1.0, 2, 3, 4, 5]), np.array([2, 0, 3])).tolist()
    [1.0, 3.0, 3.0, 7.0, 12.0]
    """
    out = np.empty(len(values))
    first = np.cumsum(count) - count
    # rows of similar length together: padded no more than twice over
    size = np.maximum(count, 1)
    bucket = np.floor(np.log2(size)).astype(np.int64)
    for b in np.unique(bucket[count > 0]).tolist():
        rows = np.flatnonzero((bucket == b) & (count > 0))
        width = int(count[rows].max())
        col = np.arange(width)
        mask = col < count[rows, None]
        idx = first[rows, None] + col
        grid = np.zeros((len(rows), width))
        grid[mask] = values[idx[mask]]
        out[idx[mask]] = np.cumsum(grid, axis=1)[mask]
    return out


def _assign(n_strand, sa, sb, ia, ib) -> np.ndarray:
    """One bit per strand so that at each crossing one visit is over and one under.

    Visit ``i`` of strand ``s`` is over when ``(bit[s] + i)`` is even; crossing
    ``c`` needs ``bit[sa] + ia`` and ``bit[sb] + ib`` of different parity, i.e.
    ``bit[sa] ^ bit[sb] == (1 + ia + ib) % 2``. Breadth-first over the strands.
    """
    need = ((1 + ia + ib) % 2).tolist()
    adj: list[list[tuple[int, int]]] = [[] for _ in range(n_strand)]
    for a, b, w in zip(sa.tolist(), sb.tolist(), need, strict=True):
        adj[a].append((b, w))
        adj[b].append((a, w))
    bit = [-1] * n_strand
    for root in range(n_strand):
        if bit[root] >= 0:
            continue
        bit[root] = 0
        queue = deque([root])
        while queue:
            s = queue.popleft()
            for t, w in adj[s]:
                if bit[t] < 0:
                    bit[t] = bit[s] ^ w
                    queue.append(t)
    return np.array(bit, dtype=np.int64)
