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

Cut the same two files from the two materials swapped and they make the reverse
tile. A piece grown by the fit and by half the kerf must not touch its neighbour on
the pieces sheet: bands narrower than ``kerf + 2 x fit`` are an error naming the
narrowest.

>>> import shapely
>>> plate = shapely.box(0, 0, 30, 30).difference(shapely.box(5, 5, 12, 12)).difference(shapely.box(15, 15, 25, 25))
>>> kit = inlay_kit(plate, shapely.box(0, 0, 30, 30), fit_mm=0.1, min_piece_mm=2.4, kerf_mm=0.15)
>>> len(kit.pieces), kit.filled_holes, kit.kinds
(2, 0, 2)
>>> round(float(shapely.area(kit.pieces[0])), 2)  # the 7 mm hole grown by 0.1 mm each way
51.84
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from .._errors import FabricationError, ParameterError
from .._report import distinct
from .._schema import key
from .contours import MITRE_LIMIT, polygon_parts

_FIT = key("output.inlay_fit_mm")
FIT_RANGE_MM = (_FIT.range.min, _FIT.range.max)
"""The fits accepted (the schema's range of ``inlay_fit_mm``): beyond half a millimetre a piece no longer fits."""


@dataclass(frozen=True)
class InlayKit:
    """The two sheets of a kit (nominal shapes, file coordinates in mm) and what they hold."""

    lattice: object
    """The lattice's material: the tile's material with the holes too small for pieces filled."""
    pieces: np.ndarray
    """The pieces' nominal polygons, each in its hole's place."""
    holes: np.ndarray
    """The hole each piece fills (nominal), in the same order."""
    filled_holes: int
    kinds: int
    """Distinct piece shapes: pieces congruent under rotation and reflection count once."""

    def stats(self) -> dict:
        area = float(shapely.area(self.pieces).sum()) if len(self.pieces) else 0.0
        return {"pieces": len(self.pieces), "filled_holes": self.filled_holes, "piece_kinds": self.kinds,
                "lattice_area_mm2": round(float(self.lattice.area), 3), "pieces_area_mm2": round(area, 3)}


def check_fit(fit_mm) -> float:
    """``fit_mm`` as a float, or a :class:`~fabtiles.ParameterError` naming the range.

    >>> check_fit(0.6)
    Traceback (most recent call last):
    ...
    fabtiles._errors.ParameterError: inlay_fit_mm must be a number of mm from -0.5 to 0.5 (positive: a press fit, negative: play), got 0.6
    """
    return _FIT.check(fit_mm, required=True)


def inlay_kit(region, outline, *, fit_mm: float, min_piece_mm: float, kerf_mm: float,
              tolerance_mm: float = 0.01) -> InlayKit:
    """Split ``region`` (the tile's material) into an inlay kit; see the module text.

    Raises :class:`~fabtiles.FabricationError` when two pieces' cut paths (grown by
    the fit and half the kerf) would touch on the pieces sheet, naming the narrowest band.
    """
    from .narrow import fill_small_holes, small_hole_mask

    fit = check_fit(fit_mm)
    parts = polygon_parts(region)
    nholes = shapely.get_num_interior_rings(parts)
    owner = np.repeat(np.arange(len(parts)), nholes)
    index = np.concatenate([np.arange(k) for k in nholes]) if len(parts) else np.empty(0, int)
    holes = shapely.polygons(shapely.get_interior_ring(parts[owner], index))
    holes = holes[shapely.area(holes) > tolerance_mm ** 2]
    keep = holes[~small_hole_mask(holes, min_piece_mm)] if len(holes) else holes
    # the lattice: the material with the holes too small for a piece filled
    lattice, filled = fill_small_holes(region, min_piece_mm, tolerance_mm=tolerance_mm)
    # a piece goes round the material lying in its hole (an island of the lattice)
    nominal = keep.copy()
    if len(keep) and len(parts) > 1:
        a, b = shapely.STRtree(keep).query(shapely.point_on_surface(parts), predicate="within")
        for k in np.unique(b).tolist():
            nominal[k] = shapely.difference(keep[k], shapely.union_all(parts[a[b == k]]))
    pieces = shapely.buffer(nominal, fit, join_style="mitre", mitre_limit=MITRE_LIMIT) if fit else nominal
    _check_apart(pieces, keep, fit, kerf_mm)
    return InlayKit(lattice, np.asarray(pieces, dtype=object), keep, int(filled), distinct_shapes(pieces))


def _check_apart(pieces, holes, fit: float, kerf: float) -> None:
    """Refuse a kit whose pieces' cut paths touch on the pieces sheet (see the module text)."""
    if len(pieces) < 2:
        return
    cut = shapely.buffer(pieces, kerf / 2, join_style="mitre", mitre_limit=MITRE_LIMIT) if kerf else pieces
    a, b = shapely.STRtree(cut).query(cut, predicate="intersects")
    pair = a < b
    if pair.any():
        gaps = shapely.distance(holes[a[pair]], holes[b[pair]])
        k = int(np.argmin(gaps))
        where = shapely.get_coordinates(shapely.shortest_line(holes[a[pair][k]], holes[b[pair][k]])).mean(axis=0)
        raise FabricationError(
            f"{int(pair.sum())} pairs of inlay pieces would touch on the pieces sheet: the narrowest band between "
            f"two pieces is {distinct(gaps[k], kerf + 2 * fit)} mm (at ({where[0]:.4g}, {where[1]:.4g})), and bands "
            f"must be wider than kerf + 2 x fit = {kerf + 2 * fit:g} mm; make the stroke wider or inlay_fit_mm smaller")


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
        n = len(seq)
        rows = [tuple(map(tuple, np.roll(seq, -k, axis=0))) for k in range(n)]
        readings.append(min(rows))
    holes = (len(poly.interiors), round(poly.area, decimals))
    return min(readings), holes


def distinct_shapes(pieces) -> int:
    """How many different shapes ``pieces`` are, congruent ones counting once."""
    seen = set()
    for p in np.asarray(pieces, dtype=object):
        for q in shapely.get_parts(p):
            seen.add(shape_key(q))
    return len(seen)
