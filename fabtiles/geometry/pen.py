"""A pen plotter's drawing: the strands as single strokes, merged into long polylines, ordered.

A pen draws a line once, as wide as its tip: the pattern is its centre-lines, not the
two outlines of each stroked band a cutter follows. :func:`strokes` joins the
centre-line segments into polylines that run straight on through every crossing (at
a vertex where several segments meet, the two nearest to a straight line are joined,
then the next two), so a star's strands come out as a few long strokes and the pen
lifts seldom. :func:`pen_drawing` orders each layer's strokes for the shortest
pen-up travel (:mod:`.cut_order`, a stroke may be drawn backwards).

>>> seg = np.array([[[0, 0], [1, 0]], [[1, 0], [2, 0]], [[1, -1], [1, 0]], [[1, 0], [1, 1]]], float)
>>> [p.tolist() for p in strokes(seg)]
[[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], [[1.0, -1.0], [1.0, 0.0], [1.0, 1.0]]]
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .contours import unique_segments
from .cut_order import order_paths


@dataclass(frozen=True)
class PenLayer:
    """One pen's strokes: the layer's name, its colour (``#rrggbb``) and its polylines (mm)."""

    name: str
    colour: str
    paths: tuple = ()

    @property
    def length_mm(self) -> float:
        """The pen-down length: every stroke's length (the job time's path lengths, open paths)."""
        from .job_time import path_lengths

        return float(path_lengths(self.paths, closed=False).sum())


@dataclass(frozen=True)
class PenDrawing:
    """A plotter's drawing: its layers in drawing order, its bounds (mm, y up), the pen's width."""

    layers: tuple
    bounds: tuple
    pen_mm: float
    stats: dict = field(default_factory=dict)

    @property
    def length_mm(self) -> float:
        return float(sum(layer.length_mm for layer in self.layers))

    @property
    def travel_mm(self) -> float:
        """The pen-up travel, each layer from the origin (a pen change re-homes on most plotters)."""
        from .cut_order import travel

        return float(sum(travel(layer.paths, closed=False) for layer in self.layers))


def strokes(segments) -> list:
    """Segments ``(k, 2, 2)`` joined into polylines that run straight on through crossings.

    Repeated and zero-length segments are dropped. A closed strand comes out closed
    (its last point equal to its first).
    """
    seg = unique_segments(segments)
    if not len(seg):
        return []
    k = len(seg)
    ends = seg.reshape(-1, 2)  # end e of segment e // 2; its other end is e ^ 1
    verts, node = np.unique(ends, axis=0, return_inverse=True)
    node = node.ravel()
    out_dir = ends[np.arange(2 * k) ^ 1] - ends
    out_dir /= np.hypot(*out_dir.T)[:, None]
    mate = np.full(2 * k, -1, np.int64)
    by_node = np.argsort(node, kind="stable")
    counts = np.bincount(node, minlength=len(verts))
    first = np.cumsum(counts) - counts
    two = np.flatnonzero(counts == 2)  # most vertices: a strand's bend, its two segments joined
    a, b = by_node[first[two]], by_node[first[two] + 1]
    mate[a], mate[b] = b, a
    _mate_crossings(mate, np.flatnonzero(counts > 2).tolist(), by_node, first, counts, out_dir)
    done = np.zeros(k, bool)
    out = []
    mate_l, node_l = mate.tolist(), node.tolist()

    def walk(e):  # from end e into its segment, on through the mates
        pts = [e]
        while True:
            s = e >> 1
            done[s] = True
            e = e ^ 1
            pts.append(e)
            nxt = mate_l[e]
            if nxt < 0 or done[nxt >> 1]:
                return pts
            e = nxt

    # open strands from their free ends, then the closed loops left
    for e in np.flatnonzero(mate < 0).tolist():
        if not done[e >> 1]:
            out.append(walk(e))
    for s in np.flatnonzero(~done).tolist():
        if not done[s]:
            out.append(walk(2 * s))
    return [verts[np.array([node_l[e] for e in chain])] for chain in out]


def _mate_crossings(mate: np.ndarray, crossings: list, by_node, first, counts, out_dir: np.ndarray) -> None:
    """At each crossing or knot, the ends that go straight on paired in ``mate`` (in place), the straightest first.

    Two ends turning sharper than 120 degrees are not one strand: they stay unpaired.
    """
    # the index pairs of each degree, made once (np.triu_indices per vertex was half of the time, profiled)
    pairs_of: dict = {}
    for v in crossings:
        es = by_node[first[v] : first[v] + counts[v]]
        d = out_dir[es]
        cos = d @ d.T  # -1: opposite, the strand going straight on
        i, j = pairs_of.get(len(es)) or pairs_of.setdefault(len(es), np.triu_indices(len(es), 1))
        free = np.ones(len(es), bool)
        for p in np.argsort(cos[i, j], kind="stable").tolist():
            if cos[i[p], j[p]] > -0.5:  # sharper than 120 degrees: not one strand
                break
            if free[i[p]] and free[j[p]]:
                free[i[p]] = free[j[p]] = False
                mate[es[i[p]]], mate[es[j[p]]] = es[j[p]], es[i[p]]


def join_ordered(groups, *, start=(0.0, 0.0)) -> list:
    """One pen's groups of strokes (lists of polylines, each in its own drawing order: the strands,
    a class's hatching) as one layer's strokes in drawing order: the groups one after the other are
    the start of :func:`~.cut_order.order_strokes`, which may interleave them where that is shorter."""
    from .cut_order import order_strokes

    paths = [np.asarray(p, float) for group in groups for p in group if len(p) >= 2]
    if len(paths) < 2 or sum(1 for g in groups if len(g)) < 2:
        return paths  # one group: in its order already
    first = np.array([p[0] for p in paths])
    last = np.array([p[-1] for p in paths])
    order, flipped = order_strokes(first, last, start=start, given=(np.arange(len(paths)), np.zeros(len(paths), bool)))
    return [paths[i][::-1] if f else paths[i] for i, f in zip(order.tolist(), flipped.tolist(), strict=True)]


def pen_drawing(layers, *, bounds, pen_mm: float, stats=None, order: bool = True) -> PenDrawing:
    """A :class:`PenDrawing` of ``layers`` (``(name, colour, paths)``), each layer's strokes ordered
    for the shortest pen-up travel from the origin (``order=False``: kept in the order given)."""
    out = []
    for name, colour, paths in layers:
        paths = [np.asarray(p, float) for p in paths if len(p) >= 2]
        if not paths:
            continue
        ordered = order_paths({"score": paths}, thorough=True)["score"] if order else paths
        out.append(PenLayer(name, colour, tuple(ordered)))
    return PenDrawing(tuple(out), tuple(float(v) for v in bounds), float(pen_mm), dict(stats or {}))
