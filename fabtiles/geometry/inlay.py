"""Inlay kits: the lattice with its holes, and the pieces that fit into them.

A star pattern in wood is made as inlay: a lattice of one material with the stars and
polygons of another pressed into its holes. :func:`inlay_kit` splits a tile's
material into the two sheets of such a kit:

- the **lattice**: the material with its holes, cut as any pierced tile (the kerf
  into each hole, so the hole comes out at its nominal shape); holes too small to
  become pieces (no disc of ``min_piece_mm`` fits) are filled and counted;
- the **pieces**: every other hole as a part, its nominal shape the hole grown by
  ``fit_mm`` (mitred, so star tips stay sharp; positive presses in, negative leaves
  play), cut with the kerf outward so it comes out at that size. Each piece keeps
  its hole's place (the same origin), so the pieces drop out of the second sheet
  where they belong.

Where a hole has a neck narrower than the kerf, the lattice's cut of it (the hole
shrunk by half the kerf) would fall into several holes under one piece: the neck is
widened so the hole is cut as one opening (:func:`_cut_whole`).

Cut the same two files from the two materials swapped and they make the reverse
tile. A piece grown by the fit and by half the kerf must not touch its neighbour on
the pieces sheet: pieces no more than the kerf apart (bands narrower than
``kerf + 2 x fit``) are an error naming the narrowest gap.

>>> import shapely
>>> plate = shapely.box(0, 0, 30, 30).difference(shapely.box(5, 5, 12, 12)).difference(shapely.box(15, 15, 25, 25))
>>> kit = inlay_kit(plate, shapely.box(0, 0, 30, 30), fit_mm=0.1, min_piece_mm=2.4, kerf_mm=0.15)
>>> len(kit.pieces), kit.filled_holes, kit.kinds
(2, 0, 2)
>>> round(float(shapely.area(kit.pieces[0])), 2)  # the 7 mm hole grown by 0.1 mm, corners rounded by 0.175 mm
51.81
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from ..core.errors import FabricationError
from ..core.report import distinct
from ..core.schema import key
from .contours import MITRE_LIMIT, polygon_parts

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry

_FIT = key("output.inlay_fit_mm")
FIT_RANGE_MM = (_FIT.bounds.min, _FIT.bounds.max)
"""The fits accepted (the schema's range of ``inlay_fit_mm``): beyond half a millimetre a piece no longer fits."""


@dataclass(frozen=True)
class InlayKit:
    """The two sheets of a kit (nominal shapes, file coordinates in mm) and what they hold."""

    lattice: BaseGeometry
    """The lattice's material: the tile's material with the holes too small for pieces filled."""
    pieces: np.ndarray
    """The pieces' nominal polygons, each in its hole's place."""
    holes: np.ndarray
    """The hole each piece fills (nominal), in the same order."""
    filled_holes: int
    kinds: int
    """Distinct piece shapes: pieces congruent under rotation and reflection count once."""
    necks: tuple = ()
    """``(x, y, width)`` of each neck narrower than the kerf widened so its hole is cut whole."""
    split: tuple = ()
    """``(x, y)`` of each neck left uncut: its hole is cut as several openings (see :func:`_cut_whole`)."""

    def stats(self) -> dict:
        area = float(shapely.area(self.pieces).sum()) if len(self.pieces) else 0.0
        return {
            "pieces": len(self.pieces),
            "filled_holes": self.filled_holes,
            "piece_kinds": self.kinds,
            "lattice_area_mm2": round(float(self.lattice.area), 3),
            "pieces_area_mm2": round(area, 3),
        }


def check_fit(fit_mm) -> float:
    """``fit_mm`` as a float, or a :class:`~fabtiles.ParameterError` naming the range.

    >>> check_fit(0.6)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: inlay_fit_mm must be a number of mm from -0.5 to 0.5 (positive: a press fit, negative: play), got 0.6
    """  # noqa: E501 - a doctest's lines are as Python prints them
    return _FIT.check(fit_mm, required=True)


def inlay_kit(
    region, outline, *, fit_mm: float, min_piece_mm: float, kerf_mm: float, tolerance_mm: float = 0.01
) -> InlayKit:
    """Split ``region`` (the tile's material) into an inlay kit; see the module text.

    Raises :class:`~fabtiles.FabricationError` when two pieces stand no more than the
    kerf apart (their cut paths, each half a kerf outside its piece, would touch on the
    pieces sheet), naming the narrowest gap and where it is.
    """
    from .narrow import fill_small_holes, small_hole_mask

    fit = check_fit(fit_mm)
    parts = polygon_parts(region)
    nholes = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), nholes)
    index = np.concatenate([np.arange(k) for k in nholes]) if len(parts) else np.empty(0, int)
    holes = shapely.polygons(shapely.get_interior_ring(parts[owner], index))
    holes = holes[shapely.area(holes) > tolerance_mm**2]
    keep = holes[~small_hole_mask(holes, min_piece_mm)] if len(holes) else holes
    # the lattice: the material with the holes too small for a piece filled
    lattice, filled = fill_small_holes(region, min_piece_mm, tolerance_mm=tolerance_mm)
    d = kerf_mm / 2
    keep, corridors, fills, necks, split = _cut_whole(keep, d, tolerance_mm)
    if len(fills):
        lattice = shapely.union_all([lattice, *fills])
    if len(corridors):
        lattice = shapely.difference(lattice, shapely.union_all(corridors))
    # the material lying in a hole (an island of the lattice) is cut out of the hole's cut path
    cut = _cut_paths(keep, _islands(keep, parts), d)
    opening = shapely.buffer(cut, d) if d else cut
    pieces = shapely.buffer(opening, fit) if fit else opening
    _check_apart(pieces, keep, fit, kerf_mm)
    # the kinds counted on the holes: each piece is made from its hole alone, so congruent holes give
    # congruent pieces, and a hole's few vertices compare fast (a round-grown piece has hundreds)
    return InlayKit(
        lattice, np.asarray(pieces, dtype=object), keep, int(filled), distinct_shapes(cut), tuple(necks), tuple(split)
    )


def _islands(holes, parts) -> np.ndarray:
    """The lattice's material lying in each hole (its islands, the union of those parts), or None."""
    islands = np.full(len(holes), None, dtype=object)
    if len(holes) and len(parts) > 1:
        a, b = shapely.STRtree(holes).query(shapely.point_on_surface(parts), predicate="within")
        for k in np.unique(b).tolist():
            islands[k] = shapely.union_all(parts[a[b == k]])
    return islands


def _cut_paths(holes, islands: np.ndarray, d: float) -> np.ndarray:
    """The lattice's cut path of each hole: the hole shrunk by ``d`` (half the kerf), mitred, its islands
    (grown likewise) cut out.

    Each piece is its hole as the lattice's cut opens it, grown by the fit: this cut path
    swept by the round beam. The beam rounds every tip of a hole (radius kerf/2), so a
    piece grown from the designed hole would overhang its opening at sharp tips, over
    uncut lattice, and two pieces' cuts could meet; grown round from the opening, a piece
    reaches the fit past its opening everywhere (never more than the fit past its hole)
    and its tips are rounded with radius kerf/2 + fit like the hole's.
    """
    cut = shapely.buffer(holes, -d, join_style="mitre", mitre_limit=MITRE_LIMIT) if d else holes.copy()
    for k in np.flatnonzero(islands != None).tolist():  # noqa: E711  (an object array)
        grown = shapely.buffer(islands[k], d, join_style="mitre", mitre_limit=MITRE_LIMIT) if d else islands[k]
        cut[k] = shapely.difference(cut[k], grown)
    return cut


def piece_of_hole(hole, *, fit_mm: float, kerf_mm: float):
    """The piece of one simple ``hole``, as :func:`inlay_kit` grows it: the opening the lattice's cut
    leaves (the hole shrunk by half the kerf, mitred, swept by the round beam), grown round by the fit.

    The calibration card's inlay gauge cuts its pieces this way, so a fit measured on
    the card is the fit the kits get (corners rounded by half the kerf plus the fit).

    >>> from shapely.geometry import box
    >>> p = piece_of_hole(box(0, 0, 6, 6), fit_mm=0.1, kerf_mm=0.15)
    >>> [round(v, 6) for v in p.bounds], round(p.area, 3)  # its box 6.2 mm; its corners rounded by 0.175 mm
    ([-0.1, -0.1, 6.1, 6.1], 38.413)
    """
    d = kerf_mm / 2
    opening = shapely.buffer(shapely.buffer(hole, -d, join_style="mitre", mitre_limit=MITRE_LIMIT), d) if d else hole
    return shapely.buffer(opening, fit_mm) if fit_mm else opening


def _cut_whole(holes, d: float, tolerance_mm: float):
    """The holes the lattice's cut makes whole: each neck narrower than the kerf widened.

    The lattice's cut path of a hole is the hole shrunk by ``d`` (half the kerf); where
    the hole has a neck narrower than the kerf the shrunk hole falls into several parts,
    the laser cuts several holes and leaves a sliver of lattice at the neck under the
    one piece (slivers of about 0.45 x 0.35 mm; 8 pieces over 24 openings on a 4.6.12
    tile). Each neck is widened instead: the parts are joined by the shortest lines
    between them (a spanning tree, each line through its neck), and the hole grows by
    the corridor the beam sweeps along each line (``d`` plus ``tolerance_mm`` each side,
    so the shrunk hole keeps a corridor of twice ``tolerance_mm`` and stays whole). The
    lattice loses at most ``d + tolerance_mm`` beside each neck (0.085 mm on the
    plywood profile); a piece still fills its hole with the fit. Filling the necks
    instead (a piece per part) left parts of one hole closer than the kerf on the
    pieces sheet. A part no straight line inside the hole reaches (beyond a curved slit,
    as at the horns of the 4.6.12 tile's 12-gon motif) is filled with the slit leading to
    it: the lattice keeps that material, the piece loses it, and its place is returned
    in ``split`` for a finding.

    Returns ``(holes, corridors, fills, necks, split)``: the holes (widened or filled
    where needed), the corridors cut out of the lattice, the regions filled in it,
    ``(x, y, width)`` of each neck widened, and ``(x, y)`` of each part filled.
    """
    corridors: list = []
    fills: list = []
    necks: list = []
    split: list = []
    if not d or not len(holes):
        return holes, np.empty(0, dtype=object), np.empty(0, dtype=object), necks, split
    shrunk = shapely.buffer(holes, -d, join_style="mitre", mitre_limit=MITRE_LIMIT)
    holes = holes.copy()
    for k in np.flatnonzero(shapely.get_num_geometries(shrunk) > 1).tolist():
        parts = [p for p in shapely.get_parts(shrunk[k]) if p.area > tolerance_mm**2]
        parts.sort(key=lambda p: -p.area)
        joined, rest, mine = _join_parts(holes[k], parts, d, tolerance_mm, necks)
        if rest:
            # parts no straight line reaches (past a curved neck): left as lattice, with the
            # slit leading to them, so the lattice cuts one opening and the piece follows it
            reach = shapely.difference(holes[k], shapely.buffer(joined, d + tolerance_mm))
            lost = [z for z in shapely.get_parts(reach) if shapely.intersects(z, shapely.union_all(rest))]
            fills.extend(lost)
            split.extend((p.x, p.y) for p in shapely.point_on_surface(rest))
            holes[k] = shapely.difference(holes[k], shapely.union_all(lost))
        if mine:
            corridors.extend(mine)
            holes[k] = shapely.union_all([holes[k], *mine])
    return holes, np.asarray(corridors, dtype=object), np.asarray(fills, dtype=object), necks, split


def _join_parts(hole, parts: list, d: float, tolerance_mm: float, necks: list) -> tuple:
    """The parts of a hole's shrunk cut path (largest first) joined by a spanning tree of the shortest lines
    inside the hole (Prim's: the nearest part first): ``(joined, parts left unreached, corridors)``; each
    neck crossed is appended to ``necks`` as ``(x, y, width)``."""
    joined, rest, mine = parts[0] if parts else None, parts[1:], []
    inside = shapely.buffer(hole, tolerance_mm)
    while rest:
        lines = shapely.shortest_line(joined, rest)
        ok = np.flatnonzero(shapely.within(lines, inside))
        if not len(ok):
            break
        j = int(ok[np.argmin(shapely.length(lines[ok]))])
        mid = shapely.line_interpolate_point(lines[j], 0.5, normalized=True)
        mine.append(shapely.buffer(lines[j], d + tolerance_mm))
        necks.append((mid.x, mid.y, 2 * shapely.distance(mid, hole.exterior)))
        joined = shapely.union_all([joined, rest.pop(j), mine[-1]])
    return joined, rest, mine


def _check_apart(pieces, holes, fit: float, kerf: float) -> None:
    """Refuse a kit whose pieces stand no more than the kerf apart (see the module text).

    The pieces' own distance decides: each piece is cut half a kerf outside it, so two
    cuts touch where two pieces stand ``kerf`` apart; the message gives that distance,
    and the band of lattice between the two holes there for the design's side of it.
    """
    if len(pieces) < 2:
        return
    a, b = shapely.STRtree(pieces).query(pieces, predicate="dwithin", distance=kerf)
    pair = a < b
    if pair.any():
        a, b = a[pair], b[pair]
        gaps = shapely.distance(pieces[a], pieces[b])
        k = int(np.argmin(gaps))
        where = shapely.get_coordinates(shapely.shortest_line(pieces[a[k]], pieces[b[k]])).mean(axis=0)
        band = float(shapely.distance(holes[a[k]], holes[b[k]]))
        raise FabricationError(
            f"{len(a)} pair{'s' if len(a) != 1 else ''} of inlay pieces would touch on the pieces sheet: the "
            f"narrowest gap between two pieces is {distinct(gaps[k], kerf)} mm (at ({where[0]:.4g}, "
            f"{where[1]:.4g}), where the band of lattice between their holes is {band:.3g} mm), and pieces must "
            f"stand more than the kerf = {kerf:g} mm apart, so bands must be wider than kerf + 2 x fit = "
            f"{kerf + 2 * fit:g} mm; make the stroke wider or inlay_fit_mm smaller"
        )


def shape_key(poly, decimals: int = 3) -> tuple:
    """A key equal for congruent polygons (rotated, moved or mirrored), from the outer ring.

    The ring's sequence of (edge length, turn at the next vertex), rounded, read from
    every start and in both directions; the smallest reading is the key. Holes are
    counted by number and area.

    >>> import shapely.affinity
    >>> sq = shapely.box(0, 0, 2, 2)
    >>> shape_key(sq) == shape_key(shapely.affinity.rotate(shapely.affinity.translate(sq, 5, 1), 30))
    True
    >>> shape_key(sq) == shape_key(shapely.box(0, 0, 2, 3))
    False
    """
    ring = shapely.get_coordinates(shapely.orient_polygons(poly).exterior)[:-1]
    readings = []
    for pts in (ring, ring[::-1] * [1, -1]):  # the mirror image, still counter-clockwise
        edges = np.roll(pts, -1, axis=0) - pts
        length = np.hypot(edges[:, 0], edges[:, 1])
        heading = np.arctan2(edges[:, 1], edges[:, 0])
        turn = (np.roll(heading, -1) - heading + math.pi) % (2 * math.pi) - math.pi
        seq = np.round(np.c_[length, turn], decimals) + 0.0
        readings.append(tuple(map(tuple, np.roll(seq, -_least_start(np.asarray(seq)), axis=0))))
    holes = (len(poly.interiors), round(poly.area, decimals))
    return min(readings), holes


def _least_start(seq: np.ndarray) -> int:
    """The row to start at for the smallest reading of ``seq``'s rows read cyclically (compared as
    tuples, row by row): the starts still tied are narrowed a row at a time, instead of every reading
    made as tuples (a ring of n vertices: n readings of n rows each)."""
    n = len(seq)
    starts = np.arange(n)
    for j in range(n):
        if len(starts) == 1:
            break
        for column in range(seq.shape[1]):
            values = seq[(starts + j) % n, column]
            starts = starts[values == values.min()]
    return int(starts[0])


def distinct_shapes(pieces) -> int:
    """How many different shapes ``pieces`` are, congruent ones counting once."""
    seen = set()
    for p in np.asarray(pieces, dtype=object):
        for q in shapely.get_parts(p):
            seen.add(shape_key(q))
    return len(seen)
