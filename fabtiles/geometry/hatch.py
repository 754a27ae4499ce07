"""Hatch fills: faces filled with parallel pen strokes, the ink kept inside each face.

A plotter colours an area by drawing parallel lines across it close enough to touch.
:func:`hatch` fills polygons with straight strokes at ``spacing_mm`` from each other
and ``angle_deg`` from the x axis (``cross``: a second set at right angles). The
strokes are clipped inside each polygon shrunk by ``inset_mm`` (half the pen's width),
so the ink's edge, a disc of the pen's radius swept along the stroke, stays inside
the face: no ink crosses the strapwork around it.

The clipping is a scanline fill in numpy rather than one GEOS intersection per line: in a
frame turned by the angle the lines are horizontal, each ring edge yields its crossings
with the lines it spans (half-open, so a vertex on a line counts once), and the crossings
of each polygon and line, sorted along the line, pair up into the strokes inside it
(even-odd: holes come out by themselves). GEOS only shrinks the faces. The lines lie on
one grid for every polygon (line ``k`` at ``k * spacing_mm`` from the origin across the
hatch direction), so the strokes of neighbouring faces line up.

:func:`hatch_order` orders the strokes for a short pen-up travel: each face's strokes as a
boustrophedon (line after line, every other one drawn backwards), the faces then ordered as
paths by :mod:`.cut_order` (a face's chain may be drawn from either end); up to
:data:`~.cut_order.POLISH_MAX` strokes :func:`~.cut_order.order_strokes` then keeps the
shortest of that order and the greedy tours, each improved by 2-opt and the polish.

>>> square = shapely.box(0, 0, 10, 10)
>>> h = hatch([square], spacing_mm=2.5, angle_deg=0, inset_mm=1)
>>> h.segments[:, :, 1].min(), h.segments[:, :, 1].max(), len(h.segments)
(np.float64(2.5), np.float64(7.5), 3)
>>> h.segments[0].tolist()
[[1.0, 2.5], [9.0, 2.5]]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

MIN_STROKE_MM = 1e-6
"""Crossings closer than this along a line (a line touching a vertex) make no stroke."""


@dataclass(frozen=True)
class Hatch:
    """Hatch strokes: ``segments`` ``(k, 2, 2)`` (mm), and for each the polygon it fills (an index into
    the polygons given), the part of it (a face the inset splits in two has two), its set (0, or 1 for
    the cross-hatching) and its line (along the grid)."""

    segments: np.ndarray
    face: np.ndarray
    part: np.ndarray
    pass_: np.ndarray
    line: np.ndarray


def hatch(polygons, *, spacing_mm: float, angle_deg: float, inset_mm: float = 0.0, cross: bool = False) -> Hatch:
    """The strokes filling ``polygons`` (shapely Polygons or MultiPolygons); see the module's text.

    Parameters
    ----------
    polygons : sequence of shapely geometries
        The areas to fill (the faces of one class).
    spacing_mm : float
        The distance between neighbouring lines, across them (> 0).
    angle_deg : float
        The lines' direction, degrees anticlockwise from the x axis.
    inset_mm : float
        How far the strokes stay inside each polygon's edge (half the pen's width).
    cross : bool
        A second set of lines at ``angle_deg + 90``.
    """
    polys = np.asarray(polygons, dtype=object).reshape(-1)
    if inset_mm > 0 and len(polys):
        # a mitred corner would reach past the pen's disc at a reflex corner: round joins are its exact erosion
        polys = shapely.buffer(polys, -inset_mm, quad_segs=8)
    parts, face = shapely.get_parts(polys, return_index=True)
    rings, ring_part = shapely.get_rings(parts, return_index=True)
    xy, xy_ring = shapely.get_coordinates(rings, return_index=True)
    same = xy_ring[1:] == xy_ring[:-1]  # consecutive points of one ring: an edge
    a, b = xy[:-1][same], xy[1:][same]
    edge_part = ring_part[xy_ring[:-1][same]]
    out = [_lines(a, b, edge_part, face, spacing_mm, angle_deg, 0)]
    if cross:
        out.append(_lines(a, b, edge_part, face, spacing_mm, angle_deg + 90.0, 1))
    return Hatch(*(np.concatenate(col) for col in zip(*out, strict=True)))


def _lines(a, b, edge_part, part_face, spacing: float, angle_deg: float, which: int) -> tuple:
    """``(segments, face, part, pass, line)`` of one set of lines at ``angle_deg``: the scanline fill of the
    edges ``a -> b`` (each of polygon part ``edge_part``) in the frame where the lines are horizontal."""
    t = math.radians(angle_deg)
    c, s = math.cos(t), math.sin(t)
    # u along the lines, v across them
    ua, va = a @ (c, s), a @ (-s, c)
    ub, vb = b @ (c, s), b @ (-s, c)
    lo, hi = np.minimum(va, vb), np.maximum(va, vb)
    k0 = np.ceil(lo / spacing).astype(np.int64)
    k1 = np.ceil(hi / spacing).astype(np.int64)  # lines lo <= k s < hi: a vertex on a line counted once
    n = np.maximum(k1 - k0, 0)
    e = np.repeat(np.arange(len(n)), n)
    k = k0[e] + np.arange(len(e)) - np.repeat(np.cumsum(n) - n, n)
    v = k * spacing
    u = ua[e] + (v - va[e]) * (ub[e] - ua[e]) / (vb[e] - va[e])
    part = edge_part[e]
    o = np.lexsort((u, k, part))
    u, k, part = u[o], k[o], part[o]
    # the crossings of one part and line alternate out -> in -> out along the line (even-odd)
    start = np.r_[True, (k[1:] != k[:-1]) | (part[1:] != part[:-1])]
    rank = np.arange(len(u)) - np.maximum.accumulate(np.where(start, np.arange(len(u)), 0))
    enter = np.flatnonzero(rank % 2 == 0)
    enter = enter[enter + 1 < len(u)]
    enter = enter[(k[enter + 1] == k[enter]) & (part[enter + 1] == part[enter])]
    u0, u1, kk = u[enter], u[enter + 1], k[enter]
    keep = u1 - u0 > MIN_STROKE_MM
    u0, u1, kk, pp = u0[keep], u1[keep], kk[keep], part[enter][keep]
    vv = kk * spacing
    p0 = np.column_stack([u0 * c - vv * s, u0 * s + vv * c])
    p1 = np.column_stack([u1 * c - vv * s, u1 * s + vv * c])
    segs = np.stack([p0, p1], axis=1)
    return segs, part_face[pp], pp, np.full(len(kk), which, np.int64), kk


def hatch_order(h: Hatch, *, start=(0.0, 0.0)) -> list:
    """The strokes of ``h`` as polylines (two points each) in drawing order, for a short pen-up travel.

    Each face part's strokes (each set's) are chained as a boustrophedon, the chains ordered by
    :func:`~.cut_order.path_orders` (either end first); that order is a start of
    :func:`~.cut_order.order_strokes`, which keeps the shortest of it and its greedy tours.
    """
    from .cut_order import order_strokes

    if not len(h.segments):
        return []
    seg = _boustrophedon(h, start)
    order, flipped = order_strokes(
        seg[:, 0], seg[:, 1], start=start, given=(np.arange(len(seg)), np.zeros(len(seg), bool))
    )
    return [s[::-1] if f else s for s, f in zip(seg[order], flipped.tolist(), strict=True)]


def _boustrophedon(h: Hatch, start) -> np.ndarray:
    """The segments of ``h`` chained: per part and set, line by line, every other line drawn
    backwards (its strokes in reverse order too); the chains in :func:`~.cut_order.path_orders`' order."""
    from .cut_order import path_orders

    o = np.lexsort((_along(h), h.line, h.pass_, h.part))
    seg, row = h.segments[o], h.line[o]
    chain = h.part[o] * 2 + h.pass_[o]
    starts = np.r_[0, np.flatnonzero(chain[1:] != chain[:-1]) + 1]
    new_row = np.r_[True, (row[1:] != row[:-1]) | (chain[1:] != chain[:-1])]
    row_no = np.cumsum(new_row) - 1
    of_chain = np.searchsorted(starts, np.arange(len(seg)), side="right") - 1
    back = (row_no - row_no[starts][of_chain]) % 2 == 1
    seg = np.where(back[:, None, None], seg[:, ::-1], seg)
    seg = seg[np.lexsort((np.where(back, -np.arange(len(seg)), np.arange(len(seg))), row_no))]
    chains = np.split(seg, starts[1:])
    ends = [np.array([c[0, 0], c[-1, 1]]) for c in chains]
    order, flipped = path_orders({"score": ends}, start=start, thorough=True)["score"]
    return np.concatenate(
        [chains[i][::-1, ::-1] if f else chains[i] for i, f in zip(order.tolist(), flipped.tolist(), strict=True)]
    )


def _along(h: Hatch) -> np.ndarray:
    """Each stroke's position along its line (its first point's projection on the line's direction)."""
    d = h.segments[:, 1] - h.segments[:, 0]
    return np.einsum("ij,ij->i", h.segments[:, 0], d / np.hypot(*d.T)[:, None])
