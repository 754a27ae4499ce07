"""The shapes of a woven tile (``docs/tile-operation.md``): where the under strands dip, break or are cut.

The strands and their over/under come from :func:`fabtiles.pattern.interlace.weave`.
At each crossing the under strand is hidden over the over band's width plus the
clearance ``gap`` on each side. Since the over band itself stays whole, what
changes is two thin **slivers** of the under band, one each side of the over
band, ``gap`` wide (in the 2.5D relief, the under strand's dip is seen only
there):

- the woven drawing (preview, :func:`woven_region`): the region without the
  slivers, so every under band stops ``gap`` short of the band it passes under;
- the relief (:func:`dips`): the slivers lowered to the dip level;
- the laser score lines (:func:`score_lines`): the under centre-line broken over
  the whole hidden length;
- ``interlace_cut`` (:func:`cut_region`): the slivers cut through, each leaving
  a tab across the middle (along the under centre-line) so that no piece falls
  out: a strand cut at every crossing where it is under would otherwise leave
  loose pieces between its crossings.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..pattern.interlace import Weave
from .containment import quads_inside
from .stack import QUANTUM

INSET_MM = 0.02
"""The relief's dips stop this far (20 microns, far below a nozzle's width) inside the bands' edges.

A dip that reached a band's edge would share it with the band's outline; cut on the
2**-10 mm meshing grid, near-collinear edges there leave spikes a grid step thin
that break the mesh (every rosette preset failed so). Strictly inside the
material, a dip is a hole in the full-height level, vertex for vertex.
"""


def _parallelograms(w: Weave, a0, a1, b0, b1) -> np.ndarray:
    """Shapely polygons ``p + a d_u / sin + b d_o / sin`` for a in [a0, a1], b in [b0, b1].

    ``a`` is the distance from the over centre-line, ``b`` from the under one
    (both measured square to those lines); one polygon per crossing.
    """
    q = _corners(w, a0, a1, b0, b1)
    return shapely.polygons(np.concatenate([q, q[:, :1]], axis=1))


def _corners(w: Weave, a0, a1, b0, b1) -> np.ndarray:
    """The corners ``(k, 4, 2)`` of :func:`_parallelograms`."""
    p, du, do, s = w.points, w.under_dir, w.over_dir, w.sin[:, None]
    return np.stack([p + (a * du + b * do) / s for a, b in ((a0, b0), (a1, b0), (a1, b1), (a0, b1))], axis=1)


def dip_quads(w: Weave, half: float, gap: float) -> np.ndarray:
    """Every candidate dip ``(2k, 4, 2)``: each crossing's forward sliver, then each one's
    backward sliver, inset by :data:`INSET_MM`, corners on the meshes' 2**-10 mm grid
    (the dips are meshed as they are tested).
    """
    e = INSET_MM
    band = (-half + e, half - e)  # across the under band, off its edges
    q = np.concatenate([_corners(w, half + e, half + gap - e, *band), _corners(w, -half - gap + e, -half - e, *band)])
    return np.round(q / QUANTUM) * QUANTUM


def slivers(w: Weave, half: float, gap: float, *, tab: float = 0.0, reach=None) -> np.ndarray:
    """The under band's hidden slivers beside each over band, as shapely polygons.

    ``half`` is half the stroke, ``gap`` the clearance. Each sliver reaches
    ``reach`` (default ``half + gap``) across the under centre-line, so it cuts
    the under band through; a ``tab`` > 0 leaves that width uncut along the under
    centre-line.

    >>> import numpy as np
    >>> from fabtiles.pattern.interlace import weave
    >>> w = weave(np.array([[[-2, 0], [2, 0]], [[0, -2], [0, 2]]], float))
    >>> [round(p.area, 4) for p in slivers(w, 0.5, 0.25)]
    [0.375, 0.375]
    >>> len(slivers(w, 0.5, 0.25, tab=0.2))
    4
    """
    if not len(w) or gap <= 0:
        return np.empty(0, dtype=object)
    reach = half + gap if reach is None else reach
    parts = []
    for a0, a1 in ((half, half + gap), (-half - gap, -half)):
        if tab > 0:
            parts.append(_parallelograms(w, a0, a1, tab / 2, reach))
            parts.append(_parallelograms(w, a0, a1, -reach, -tab / 2))
        else:
            parts.append(_parallelograms(w, a0, a1, -reach, reach))
    return np.concatenate(parts)


def _hidden(w, half, gap, within, tab=0.0):
    """The union of the slivers, clipped to ``within`` (the patterned area: never the frame)."""
    s = slivers(w, half, gap, tab=tab)
    if not len(s):
        return None
    u = shapely.union_all(s)
    return u if within is None else _overlay(shapely.intersection, u, within)


def _overlay(op, a, b):
    """``op(a, b)``; when GEOS meets a robustness failure, again on a 2**-20 mm grid (about 1 nm)."""
    try:
        return op(a, b)
    except shapely.errors.GEOSException:
        return op(a, b, grid_size=2.0**-20)


def dips(region, w: Weave, half: float, gap: float, within=None):
    """Where the relief's under strands dip: each under band's two slivers, inset by :data:`INSET_MM`.

    A sliver is kept only where it lies inside the material (and inside
    ``within``): one whose under band ends or merges into other material within
    the gap (a strand's tip just past the crossing) gets no dip. Exactly GEOS's
    ``contains_properly``, built from the crossings alone: slivers along a straight
    run of their under strand lie in its band; the others are tested by
    :func:`~fabtiles.geometry.containment.quads_inside` (no edge of the region
    meets the sliver, its centre inside). Corner probes and region vertices through
    GEOS passed a gap crossing a sliver whole; GEOS's containment test of each polygon
    and an overlay of the region with the slivers are slower (``docs/speed.md``). Only
    slivers that overlap another (crossings closer than a gap) are merged.
    """
    e = INSET_MM
    if not len(w) or gap <= 2 * e or half <= e:
        return shapely.Polygon()
    probes = dip_quads(w, half, gap)
    keep = np.ones(len(probes), bool)
    if within is not None:
        shapely.prepare(within)
        keep &= shapely.contains_xy(within, probes[..., 0], probes[..., 1]).all(axis=1)
    # A sliver along a straight run of its under strand lies in that strand's band,
    # so in the material (inside ``within``, which the region fills but for the
    # bands' gaps): only the others are tested (12,696 of the sheet's 14,736).
    no = np.zeros(len(probes), bool)
    straight, centre = _straight(w, half, gap) if within is not None else (no, no)
    probe = keep & ~straight
    if probe.any():
        # the centre lies on the under centre-line: in its band where the run reaches it
        keep[probe] = quads_inside(region, probes[probe], centre_inside=centre[probe])
    q = probes[keep]
    if not len(q):
        return shapely.Polygon()
    parts = shapely.polygons(np.concatenate([q, q[:, :1]], axis=1))
    a, b = shapely.STRtree(parts).query(parts, predicate="intersects")
    touching = np.zeros(len(parts), bool)
    touching[a[a != b]] = True
    if not touching.any():
        return shapely.multipolygons(parts)
    # overlapping slivers merged, back on the grid
    merged = polygonal(shapely.set_precision(shapely.union_all(parts[touching]), QUANTUM))
    out = shapely.multipolygons(np.concatenate([parts[~touching], shapely.get_parts(merged)]))
    if shapely.is_valid(out):
        return out
    # put on the grid, a merged sliver may have moved onto a lone one: all merged, an overlay needs them valid
    return polygonal(shapely.set_precision(shapely.union_all(parts), QUANTUM))


def _straight(w: Weave, half: float, gap: float):
    """Which slivers (the forward ones, then the backward ones, as :func:`dips` makes them)
    lie along a straight run of their under strand from the crossing, and which
    have their centre on one: two masks.

    Along the under strand, measured from the crossing, the forward sliver's
    corners lie between ``(half - half |cos|) / sin >= 0`` and ``(half + gap +
    half |cos|) / sin`` (``sin``, ``cos`` of the angle between the strands; the
    inset only shrinks it), its centre at ``(half + gap / 2) / sin``, the backward
    one's mirrored: the run must reach that far on its side
    (:meth:`Weave.straight_reach` is 0 both ways where the strand bends at the
    crossing).
    """
    cos = np.abs(np.sum(w.over_dir * w.under_dir, axis=1))
    back, fwd = w.straight_reach().T
    far = (half + gap + half * cos) / w.sin
    mid = (half + gap / 2) / w.sin
    return np.concatenate([fwd >= far, back >= far]), np.concatenate([fwd >= mid, back >= mid])


def polygonal(geom):
    """The polygons of an overlay result (dropping the lines and points it may hold)."""
    parts = shapely.get_parts(geom)
    parts = parts[(shapely.get_type_id(parts) == 3) & (shapely.area(parts) > 0)] if len(parts) else parts
    return shapely.multipolygons(parts) if len(parts) else shapely.Polygon()


def woven_region(region, w: Weave, half: float, gap: float, within=None):
    """The material with the slivers taken out: the classic woven drawing, filled."""
    u = _hidden(w, half, gap, within)
    return region if u is None else polygonal(_overlay(shapely.difference, region, u))


def cut_region(region, w: Weave, half: float, gap: float, tab: float, within=None):
    """The material of a pierced ``interlace_cut`` tile: the slivers cut, tabs left across.

    Only across the under band (``half`` each side of its centre-line). A sliver
    whose cut would still free a piece (a band running close beside the over band,
    cut too) is left uncut, a few rounds, so every piece stays joined: the number
    of parts never grows.
    """
    cuts = slivers(w, half, gap, tab=tab, reach=half)
    if not len(cuts):
        return region
    if within is not None:
        cuts = cuts[shapely.intersects(cuts, within)]
    n_parts = len(shapely.get_parts(region))
    keep = np.ones(len(cuts), bool)
    out = region
    for _ in range(CUT_ROUNDS):
        u = shapely.union_all(cuts[keep])
        if within is not None:
            u = _overlay(shapely.intersection, u, within)
        # on a 2**-16 mm grid: the kerf offset of holes this close failed in GEOS without it
        out = polygonal(shapely.difference(region, u, grid_size=2.0**-16))
        parts = shapely.get_parts(out)
        if len(parts) <= n_parts:
            return out
        main = np.argsort(shapely.area(parts))[::-1][:n_parts]
        loose = np.delete(parts, main)
        tree = shapely.STRtree(cuts)
        hit = tree.query(loose, predicate="intersects")[1]
        if not keep[hit].any():
            break
        keep[hit] = False
    return region if len(shapely.get_parts(out)) > n_parts else out


CUT_ROUNDS = 4
"""Rounds of leaving uncut the slivers that would free a piece (``interlace_cut``)."""


def score_lines(w: Weave, half: float, gap: float, clip) -> np.ndarray:
    """The score centre-lines ``(k, 2, 2)``: under strands broken, clipped by ``clip(segments)``."""
    return clip(w.broken_pieces(half, gap))


# --------------------------------------------------------------------------- tiles


def woven_segments(tile) -> np.ndarray:
    """The centre-lines a tile weaves, file coordinates: its motifs (not its outline circles)."""
    return tile.motif_segments()


def checked_weave(tile) -> Weave:
    """The weave of a tile, its gap checked against :meth:`Weave.max_gap`.

    Raises :class:`~fabtiles.ParameterError` when the given ``interlace_gap_mm`` is
    so large that the gaps swallow a strand.
    """
    from ..core.errors import ParameterError
    from ..pattern.interlace import weave

    w = weave(woven_segments(tile))
    given = tile.params()["interlace_gap_mm"]
    if given is not None and len(w):
        limit = max(w.max_gap(tile.stroke / 2), 0.0)
        if given > limit:
            raise ParameterError(
                f"interlace_gap_mm must be >= 0 and <= {limit:.3g} mm for this pattern and stroke "
                f"(a larger gap hides a whole strand under its crossings), got {given:g}; "
                "make it smaller, or leave it out for the default",
                param="interlace_gap_mm",
            )
    return w


def tile_gap(tile) -> float:
    """The clearance a tile uses, mm: ``interlace_gap_mm``; by default a third of the
    stroke, lowered where needed so that no strand is swallowed (never below 0)."""
    w = tile.weave()
    if tile.params()["interlace_gap_mm"] is not None or not len(w):
        return tile.interlace_gap_mm
    return min(tile.interlace_gap_mm, max(w.max_gap(tile.stroke / 2), 0.0))


def tile_dips(tile):
    """The relief dips of an interlaced tile (empty when it is not interlaced)."""
    if not tile.interlace:
        return shapely.Polygon()
    within = _within(tile)
    return dips(
        tile.region(), tile.weave(), tile.stroke / 2, tile_gap(tile), tile.outline_shape() if within is None else within
    )


def tile_drawing(tile):
    """The filled woven drawing of a tile: its region, under bands stopped short (if interlaced)."""
    if not tile.interlace:
        return tile.region()
    return woven_region(tile.region(), tile.weave(), tile.stroke / 2, tile_gap(tile), _within(tile))


def tile_score_lines(tile) -> np.ndarray:
    """The laser score lines of a tile: centre-lines, under strands broken if interlaced."""
    if not tile.interlace:
        return tile.centrelines()
    from .stroke import clip_segments

    w = tile.weave()
    seg = w.broken_pieces(tile.stroke / 2, tile_gap(tile))
    all_seg = tile.segments()
    if len(all_seg) > len(w.strand):  # the outline circles follow the motifs: scored whole
        seg = np.concatenate([seg, all_seg[len(w.strand) :]])
    return clip_segments(seg, tile.outline_shape())


def tile_cut_region(tile, tab: float):
    """The pierced material of a tile with ``interlace_cut``: slivers cut, ``tab`` wide tabs left."""
    if not (tile.interlace and tile.interlace_cut):
        return tile.region()
    return cut_region(tile.region(), tile.weave(), tile.stroke / 2, tile_gap(tile), tab, _within(tile))


def _within(tile):
    """Where a tile's weave may hide bands: inside its frame (the frame stays whole)."""
    return tile.inner_shape() if tile.frame > 0 else None
