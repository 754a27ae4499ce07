"""Pieces of a panel larger than the bed: seams chosen on the pattern, and joints that lock.

A tile larger than its machine's bed is made as pieces that assemble into exactly the
designed panel. :func:`split_panel` takes the panel's material (the region a cutter
keeps, in panel millimetres) and the bed, and returns a :class:`PanelSplit`:

- **How many pieces.** The fewest columns x rows whose cells, with the joints' tabs
  sticking out on two sides, fit the bed less its margin either way round
  (:func:`grid_for`); more than :data:`MAX_PIECES` is an error.
- **Where the seams run.** Each seam may move within the slack the bed leaves. Along
  it, candidates are scored in order by: the joints it can hold (every pair of pieces
  it separates needs one: a seam that crosses only thin bands cannot be joined), the
  slivers it leaves (material narrower than the minimum feature: the wedge a band
  crossing the seam at a slant leaves, a corner just beside the seam), then a place
  on the pattern's period (pieces in the same place of the
  grid are then congruent: interchangeable, one file fits several places), then the
  even division.
- **Islands.** A bit of band cut off on the wrong side of a seam, touching its piece
  nowhere, would fall out: it joins the neighbour it touches, so the seam steps
  round it along the pattern.
- **Joints.** Where a piece meets its neighbour across a seam over a stretch of
  material wide enough (the tab's widest part and the minimum feature each side), a
  tab of the left (lower) piece locks into a socket of the right (upper) one (several
  along a long stretch, one per :data:`TAB_SPACING_MM`):
  a ``"dovetail"`` (a trapezoid whose head is wider than its neck) or a ``"jigsaw"``
  knob (a disc on a neck). Tabs always stick out to the right and up, so pieces in
  the same place of the grid get the same joints. ``fit_mm`` grows the tab like an
  inlay's fit: positive presses in, negative leaves play. Laid flat, two joined
  pieces cannot be pulled apart in the plane.
- **Seam bars.** Where a pair of pieces meets only across bands too thin for any joint
  (a fine lattice), a bar of material is laid along the seam between them, as wide as
  the joint and its neck either side (:func:`seam_bar_mm`), and the joints go into the
  bar: the panel gains a mullion there (:attr:`PanelSplit.bars`; ``bars=False`` refuses
  such a panel instead).

The pieces are the nominal shapes: the cut plan offsets each by the kerf as any part.

>>> import shapely
>>> frame = shapely.box(0, 0, 300, 100).difference(shapely.box(10, 10, 290, 90))
>>> split = split_panel(frame, bed_mm=(200, 200), margin_mm=5, joint=joint_for("dovetail", thickness_mm=3))
>>> split.grid, len(split.pieces), len(split.joints)
((2, 1), 2, 2)
>>> [round(x, 1) for x in split.seams_x]
[150.0]
>>> round(sum(p.region.area for p in split.pieces) - frame.area, 6)
0.0
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
import shapely
import shapely.affinity
from shapely.geometry import box

from ..core.errors import FabricationError, ParameterError
from ..core.validate import check_choice, check_float

JOINT_KINDS = ("dovetail", "jigsaw")
"""The joints a seam may carry: a dovetail (trapezoid) or a jigsaw knob (a disc on a neck)."""

MAX_PIECES = 100
"""The most pieces a panel is split into: beyond, the bed is too small for the panel to be worth it."""

DOVETAIL_FLARE = 1.0 / 3.0
"""How much wider a dovetail's head is than its neck, per unit of depth each side (a steep
dovetail locks better in the plane than a woodworker's 1:6, and needs no glue to hold)."""

_COARSE_STEP_MM = 4.0
"""The spacing of the positions a seam is tried at first within its slack (besides the period's)."""

_GRID_STEP_MM = 1.0
"""The spacing of the positions tried around the best of the first, coarse round."""

_ALIKE_SLIVER_MM2 = 2.0
"""How much more sliver (mm^2 over all seams of an axis) seams a whole number of periods apart may
leave than the best seams found one by one, and still be chosen for their alike pieces."""

_ROUNDS = 2

_SHORT_EDGE_MM = 50.0
"""Edges of the material longer than this along a seam's axis are few (a frame's sides): a seam's
crossings test them all, and only the short edges that start within this of it."""

TAB_SPACING_MM = 150.0
"""The length of a stretch of shared material per tab: a long stretch (a frame, a seam bar) gets
several tabs evenly along it, so that a long seam cannot hinge about one."""
"""Rounds of choosing the columns' seams then the rows': each choice depends on the other's segments."""


@dataclass(frozen=True, slots=True)
class Joint:
    """A joint's shape, in mm: its kind, the neck at the seam, the widest part, the depth into
    the neighbour, the fit (positive presses in, negative leaves play) and the radius its
    corners are rounded to (a router's bit cannot cut a socket's inner corner sharper than its
    own radius: the tab is rounded to it, and its neck meets the seam in fillets of it, so
    both pieces are as the bit makes them)."""

    kind: str
    neck_mm: float
    head_mm: float
    depth_mm: float
    fit_mm: float = 0.0
    corner_mm: float = 0.0

    def figures(self) -> dict:
        """The joint's shape for the reports and the assembly manifest (mm, to the micron)."""
        return dict(
            kind=self.kind,
            neck_mm=round(self.neck_mm, 3),
            head_mm=round(self.head_mm, 3),
            depth_mm=round(self.depth_mm, 3),
            fit_mm=self.fit_mm,
            corner_mm=round(self.corner_mm, 3),
        )

    def tab(self, centre, direction) -> shapely.Polygon:
        """The tab at ``centre`` on the seam, sticking out along the unit vector ``direction``.

        >>> t = joint_for("dovetail", thickness_mm=3).tab((0, 0), (1, 0))
        >>> [round(v, 3) for v in t.bounds]
        [0.0, -3.5, 6.0, 3.5]
        """
        d = np.asarray(direction, float)
        n = np.array([-d[1], d[0]])
        c = np.asarray(centre, float)
        if self.kind == "dovetail":
            local = [(0, -self.neck_mm / 2), (self.depth_mm, -self.head_mm / 2),
                     (self.depth_mm, self.head_mm / 2), (0, self.neck_mm / 2)]  # fmt: skip
            shape = shapely.Polygon(local)
        else:
            r = self.head_mm / 2
            knob = shapely.Point(self.depth_mm - r, 0).buffer(r, quad_segs=16)
            neck = box(0, -self.neck_mm / 2, self.depth_mm - r, self.neck_mm / 2)
            shape = shapely.union(knob, neck)
        if self.corner_mm > 0:
            shape = _rounded(shape, self.corner_mm, self.neck_mm, self.fit_mm)
        coords = np.asarray(shape.exterior.coords)
        placed = c + coords[:, :1] * d + coords[:, 1:] * n
        return shapely.Polygon(placed)

    def grown(self, tab: shapely.Polygon, by_mm: float) -> shapely.Polygon:
        """``tab`` grown by ``by_mm``: mitred, its corners kept sharp; a rounded tab (``corner_mm``)
        with round joins, as its fillets meet the seam at a cusp that a mitre would draw out to a spike."""
        if self.corner_mm:
            return tab.buffer(by_mm, quad_segs=8)
        return tab.buffer(by_mm, join_style="mitre")

    @property
    def extent_mm(self) -> float:
        """How far a tab sticks out of its piece beyond the seam."""
        return self.depth_mm


def _rounded(shape, r: float, neck_mm: float, fit_mm: float) -> shapely.Polygon:
    """A tab (sticking out along +x from the seam x = 0) with its corners rounded to ``r`` and its
    neck meeting the seam in fillets a little wider (by the fit: grown by it, a fillet of ``r``
    alone would be tighter than the tool): the opening of the tab, then the closing of it with the
    seam's side."""
    q = 16
    fillet = r + abs(fit_mm) + 0.01
    opened = shape.buffer(-r, quad_segs=q).buffer(r, quad_segs=q)
    side = box(-2 * fillet, -neck_mm / 2 - 3 * fillet, 0, neck_mm / 2 + 3 * fillet)
    closed = shapely.union(opened, side).buffer(fillet, quad_segs=q).buffer(-fillet, quad_segs=q)
    _, y0, x1, y1 = shape.bounds
    tab = shapely.intersection(closed, box(0, y0 - 2 * fillet, x1 + 1, y1 + 2 * fillet))
    return max(_parts(tab), key=lambda g: g.area)


def joint_for(
    kind: str = "dovetail", *, thickness_mm: float, kerf_mm: float = 0.0, fit_mm: float = 0.0, corner_mm: float = 0.0
) -> Joint:
    """The joint sized from the material: the neck as wide as one thickness (never under 2 mm), a
    dovetail as deep as two, its head wider by :data:`DOVETAIL_FLARE` of the depth each side; a
    jigsaw knob as wide as that head, on a neck half the neck's width long.

    The kerf only sets a floor: a neck narrower than four kerfs would burn away. ``corner_mm``
    rounds the tab's corners (a router's bit radius, see :class:`Joint`).

    >>> joint_for("dovetail", thickness_mm=3)
    Joint(kind='dovetail', neck_mm=3.0, head_mm=7.0, depth_mm=6.0, fit_mm=0.0, corner_mm=0.0)
    >>> joint_for("jigsaw", thickness_mm=3).depth_mm
    8.5
    >>> joint_for("knot", thickness_mm=3)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: 'knot' is not a valid joint, must be one of: dovetail, jigsaw
    """
    check_choice("joint", kind, JOINT_KINDS)
    t = check_float("thickness_mm", thickness_mm, low=0.1, high=100.0)
    kerf = check_float("kerf_mm", kerf_mm, low=0.0, high=10.0)
    fit = check_float("fit_mm", fit_mm, low=-0.5, high=0.5)
    corner = check_float("corner_mm", corner_mm, low=0.0, high=50.0)
    neck = max(t, 2.0, 4 * kerf)
    depth = 2 * neck
    head = neck + 2 * DOVETAIL_FLARE * depth
    if kind == "jigsaw":  # the knob (as wide as the dovetail's head) on a neck half its width long
        depth = head + neck / 2
    return Joint(kind, neck, head, depth, fit, corner)


@dataclass(frozen=True, slots=True)
class Piece:
    """One piece: its number (1 at the top left, along the rows), its place in the grid
    (column, row from the bottom) and its nominal region in panel mm."""

    number: int
    cell: tuple[int, int]
    region: shapely.Geometry


@dataclass(frozen=True, slots=True)
class PlacedJoint:
    """A joint between two pieces (numbers): the tab's piece first, where on the seam, the tab."""

    pieces: tuple[int, int]
    at: tuple[float, float]
    tab: shapely.Polygon


@dataclass(frozen=True, slots=True)
class PanelSplit:
    """A panel split into pieces: the grid (columns, rows), the seams, the pieces and joints."""

    grid: tuple[int, int]
    seams_x: tuple[float, ...]
    seams_y: tuple[float, ...]
    pieces: tuple[Piece, ...]
    joints: tuple[PlacedJoint, ...]
    joint: Joint
    bars: tuple[shapely.Geometry, ...] = ()
    """The material added as seam bars (with the slits beside them filled) where a pair of pieces
    met only across bands too thin for a joint: the pieces' union is the panel's material and these."""


def grid_for(width_mm: float, height_mm: float, bed_mm, *, margin_mm: float, extent_mm: float) -> tuple[int, int]:
    """The fewest columns x rows whose cells, grown by a tab's ``extent_mm`` on two sides, fit
    the bed less ``margin_mm`` all round, either way round.

    >>> grid_for(1200, 800, (600, 400), margin_mm=5, extent_mm=6)
    (4, 2)
    >>> grid_for(1200, 800, (16, 16), margin_mm=5, extent_mm=6)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: bed_mm (16, 16) less the margin of 5 mm all round leaves no room for a piece with its joints (6 mm); use a larger bed, a smaller margin or a smaller joint
    """  # noqa: E501 - a doctest's lines are as Python prints them
    bw, bh = (b - 2 * margin_mm for b in bed_mm)
    if min(bw, bh) <= extent_mm:
        raise ParameterError(
            f"bed_mm {tuple(bed_mm)!r} less the margin of {margin_mm:g} mm all round leaves no room for a piece "
            f"with its joints ({extent_mm:g} mm); use a larger bed, a smaller margin or a smaller joint",
            param="bed_mm",
        )
    best = None
    for cw, ch in ((bw, bh), (bh, bw)):  # cells laid on the bed as they are or turned
        nx = 1 if width_mm <= cw else math.ceil(width_mm / (cw - extent_mm))
        ny = 1 if height_mm <= ch else math.ceil(height_mm / (ch - extent_mm))
        if best is None or nx * ny < best[0] * best[1]:
            best = (nx, ny)
    assert best is not None
    if best[0] * best[1] > MAX_PIECES:
        raise ParameterError(
            f"the {width_mm:g} x {height_mm:g} mm panel needs {best[0] * best[1]} pieces on the "
            f"{bed_mm[0]:g} x {bed_mm[1]:g} mm bed, more than the {MAX_PIECES} allowed; use a larger bed or a "
            "smaller panel",
            param="bed_mm",
        )
    return best


def split_panel(
    material,
    *,
    bed_mm,
    margin_mm: float,
    joint: Joint,
    min_feature_mm: float = 1.0,
    period_mm: tuple[float, float] | None = None,
    origin=(0.0, 0.0),
    bars: bool = True,
) -> PanelSplit:
    """Split ``material`` (a panel's region, mm) into pieces that fit ``bed_mm``, joined by ``joint``.

    ``period_mm`` is the pattern's period along x and y (translations that map the pattern
    onto itself) and ``origin`` a point of that lattice: seams on it make congruent pieces.
    Where a pair of neighbouring pieces can be joined nowhere (every seam position crosses only
    material too thin for the joint), a seam bar is added between them; with ``bars=False``
    that is a :class:`~fabtiles.FabricationError` instead.
    """
    x0, y0, x1, y1 = material.bounds
    nx, ny = grid_for(x1 - x0, y1 - y0, bed_mm, margin_mm=margin_mm, extent_mm=joint.extent_mm)
    cell_max = _cell_max(bed_mm, margin_mm, joint.extent_mm, x1 - x0, y1 - y0, nx, ny)
    xs = _even(x0, x1, nx)
    ys = _even(y0, y1, ny)
    ctx = _Context(material, joint, min_feature_mm)
    for _ in range(_ROUNDS):
        xs = _choose(ctx, 0, xs, ys, x0, x1, cell_max[0], None if period_mm is None else (period_mm[0], origin[0]))
        ys = _choose(ctx, 1, ys, xs, y0, y1, cell_max[1], None if period_mm is None else (period_mm[1], origin[1]))
    cells = _cell_boxes(xs, ys, (x0, y0, x1, y1))
    regions = {cell: _clip(material, bounds) for cell, bounds in cells.items()}
    added: list = []
    if bars:  # where a pair would meet only across bands too thin for a joint, before the islands move
        added = _lay_bars(ctx, regions, cells, _bar_boxes(ctx, xs, ys))
    regions = _islands_to_neighbours(regions, nx, ny)
    joints = _joints(ctx, regions, xs, ys, nx, ny)
    pieces = tuple(
        Piece(_number(i, j, nx, ny), (i, j), regions[i, j]) for j in range(ny - 1, -1, -1) for i in range(nx)
    )
    return PanelSplit((nx, ny), tuple(xs[1:-1]), tuple(ys[1:-1]), pieces, tuple(joints), joint, tuple(added))


def seam_bar_mm(joint: Joint) -> float:
    """How wide a seam bar is across its seam: a neck's width behind the seam, the tab's depth
    and a neck's width round the socket beyond it.

    >>> seam_bar_mm(joint_for("dovetail", thickness_mm=3))
    12.0
    """
    return joint.depth_mm + 2 * joint.neck_mm


def laid_on_bed(region, bed_mm, *, margin_mm: float) -> tuple[shapely.Geometry, np.ndarray]:
    """A piece as its file holds it: its lower left corner at the margin, turned a quarter if it
    fits the bed only turned; and the 3 x 3 matrix (mm) that carries the file's piece to its
    place in the panel.

    >>> laid, m = laid_on_bed(box(300, 0, 500, 300), (400, 250), margin_mm=5)
    >>> [round(v, 6) for v in laid.bounds], (m.round(6) + 0.0).tolist()
    ([5.0, 5.0, 305.0, 205.0], [[0.0, -1.0, 505.0], [1.0, 0.0, -5.0], [0.0, 0.0, 1.0]])
    >>> (m @ [5, 5, 1]).round(6).tolist()  # the file's corner at the margin is the panel's (500, 0)
    [500.0, 0.0, 1.0]
    """
    x0, y0, x1, y1 = region.bounds
    bw, bh = (b - 2 * margin_mm for b in bed_mm)
    turn = not (x1 - x0 <= bw + 1e-9 and y1 - y0 <= bh + 1e-9)
    # panel -> file: turn a quarter clockwise (x, y) -> (y, -x) if needed, then shift to the margin
    rot = np.array([[0.0, 1.0], [-1.0, 0.0]]) if turn else np.eye(2)
    corners = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]]) @ rot.T
    shift = margin_mm - corners.min(axis=0)
    to_file = np.eye(3)
    to_file[:2, :2] = rot
    to_file[:2, 2] = shift
    laid = shapely.transform(region, lambda xy: xy @ rot.T + shift)
    return laid, np.linalg.inv(to_file)


def congruent_groups(pieces, *, tolerance_mm: float = 1e-3) -> list[list[int]]:
    """The pieces' numbers grouped by shape: pieces of one group are the same up to a shift, so
    one file makes any of them (and they are interchangeable in the panel).

    >>> ps = [Piece(1, (0, 0), box(0, 0, 10, 10)), Piece(2, (1, 0), box(10, 0, 20, 10)),
    ...       Piece(3, (2, 0), box(20, 0, 31, 10))]
    >>> congruent_groups(ps)
    [[1, 2], [3]]
    """
    groups: list[tuple[shapely.Geometry, list[int]]] = []
    for piece in pieces:
        x0, y0 = piece.region.bounds[:2]
        shape = shapely.affinity.translate(piece.region, -x0, -y0)
        for ref, members in groups:
            if (
                abs(ref.area - shape.area) <= tolerance_mm * max(1.0, shape.length)
                and np.allclose(ref.bounds, shape.bounds, atol=tolerance_mm)
                and shapely.symmetric_difference(ref, shape).area <= tolerance_mm * max(1.0, shape.length)
            ):
                members.append(piece.number)
                break
        else:
            groups.append((shape, [piece.number]))
    return [members for _, members in groups]


class _Context:
    """The material and the joint's rules."""

    def __init__(self, material, joint: Joint, min_feature_mm: float):
        self.material = material
        self.joint = joint
        self.min_mm = min_feature_mm
        self.reach = joint.depth_mm + 2 * min_feature_mm + joint.head_mm
        # a tab grown by the minimum feature, at the origin sticking out along +x and +y: placed by a shift
        self.probes = [
            np.asarray(joint.grown(joint.tab((0, 0), d), min_feature_mm).exterior.coords)
            for d in ((1.0, 0.0), (0.0, 1.0))
        ]

    def near(self, axis: int, lo: float, hi: float) -> _Window:
        """The material within reach of a seam of ``axis`` placed anywhere from ``lo`` to ``hi``."""
        x0, y0, x1, y1 = self.material.bounds
        r = self.reach
        window = (lo - r, y0 - 1, hi + r, y1 + 1) if axis == 0 else (x0 - 1, lo - r, x1 + 1, hi + r)
        return _Window(shapely.clip_by_rect(self.material, *window), axis)


class _Window:
    """The material near a seam's slack, with its edges as arrays: a seam's crossings by arithmetic."""

    def __init__(self, local, axis: int):
        self.local = local
        shapely.prepare(local)
        rings = shapely.get_rings(shapely.get_parts(local))
        starts, ends = [], []
        for ring in rings:
            xy = shapely.get_coordinates(ring)
            starts.append(xy[:-1])
            ends.append(xy[1:])
        p = np.concatenate(starts) if starts else np.zeros((0, 2))
        q = np.concatenate(ends) if ends else np.zeros((0, 2))
        self.axis = axis
        self.bounds = local.bounds
        # edges sorted by where they start along the axis; the few long ones (a frame's sides) apart,
        # so that a seam's crossings look only at the short edges that can reach it
        lo = np.minimum(p[:, axis], q[:, axis])
        long = np.maximum(p[:, axis], q[:, axis]) - lo > _SHORT_EDGE_MM
        order = np.argsort(np.where(long, -np.inf, lo), kind="stable")
        self.p, self.q, self.lo = p[order], q[order], lo[order]
        self.n_long = int(long.sum())
        self.corners = np.sort(p[:, axis])

    def _near(self, pos: float) -> slice:
        """The short edges that may cross ``pos`` (after the long ones, which always might)."""
        i0 = self.n_long + int(np.searchsorted(self.lo[self.n_long :], pos - _SHORT_EDGE_MM))
        i1 = self.n_long + int(np.searchsorted(self.lo[self.n_long :], pos, side="right"))
        return slice(i0, i1)

    def crossings(self, pos: float) -> tuple[list[tuple[float, float]], np.ndarray]:
        """The stretches where a seam at ``pos`` runs through material (from, to along it), and the
        crossing edges' slopes (along the seam per unit across: the wedge each leaves)."""
        near = self._near(pos)
        p = np.concatenate([self.p[: self.n_long], self.p[near]])
        q = np.concatenate([self.q[: self.n_long], self.q[near]])
        a = p[:, self.axis] - pos
        b = q[:, self.axis] - pos
        hit = (a < 0) != (b < 0)  # half-open, as a point-in-polygon test counts: even-odd holds at vertices
        t = a[hit] / (a[hit] - b[hit])
        o = 1 - self.axis
        along = p[hit, o] + t * (q[hit, o] - p[hit, o])
        slope = np.abs(q[hit, o] - p[hit, o]) / np.abs(q[hit, self.axis] - p[hit, self.axis])
        order = np.sort(along)
        return [(float(order[k]), float(order[k + 1])) for k in range(0, len(order) - 1, 2)], slope

    def corners_within(self, pos: float, m: float) -> np.ndarray:
        """How far each corner of the material within ``m`` of ``pos`` (not on it) lies from it."""
        i0, i1 = np.searchsorted(self.corners, [pos - m, pos + m])
        d = np.abs(self.corners[i0:i1] - pos)
        return d[(d > 1e-9) & (d < m)]


def _number(i: int, j: int, nx: int, ny: int) -> int:
    """Pieces numbered from 1 at the top left, along each row, as a drawing is read."""
    return (ny - 1 - j) * nx + i + 1


def _even(lo: float, hi: float, n: int) -> list[float]:
    return [lo + (hi - lo) * k / n for k in range(n + 1)]


def _cell_max(bed_mm, margin_mm, extent, w, h, nx, ny) -> tuple[float, float]:
    """The widest and tallest a cell may be (the tabs apart), in the bed's orientation that needs the grid."""
    bw, bh = (b - 2 * margin_mm for b in bed_mm)
    for cw, ch in ((bw, bh), (bh, bw)):
        if w / nx <= cw - (extent if nx > 1 else 0) + 1e-9 and h / ny <= ch - (extent if ny > 1 else 0) + 1e-9:
            return cw - (extent if nx > 1 else 0), ch - (extent if ny > 1 else 0)
    raise AssertionError("grid_for chose a grid whose cells do not fit")  # pragma: no cover


def _candidates(ideal: float, lo: float, hi: float, period, step: float) -> list[tuple[float, bool]]:
    """Seam positions to try between ``lo`` and ``hi``: the period's (flagged), the ideal and a grid."""
    out = [(ideal, False)]
    n = int((hi - lo) / step)
    out += [(lo + k * step, False) for k in range(n + 1)]
    if period is not None and period[0] > 0:
        p, o = period
        k0, k1 = math.ceil((lo - o) / p), math.floor((hi - o) / p)
        out += [(o + k * p, True) for k in range(k0, k1 + 1)]
    return out


def _choose(ctx: _Context, axis: int, seams, others, lo_end, hi_end, cell_max, period) -> list[float]:
    """The inner seams of one axis at their best positions within the slack the bed leaves.

    Each seam is tried on a coarse grid (and the period's), then finely around its best. With
    a period, seams a whole number of periods apart are tried too, and kept where they join as
    many pairs with as few slivers: their inner pieces are then alike.
    """
    n = len(seams) - 1
    if n <= 1:
        return list(seams)
    slack = max(0.0, cell_max - (hi_end - lo_end) / n)
    ideal = _even(lo_end, hi_end, n)
    chosen = [lo_end]
    scores = []
    for k in range(1, n):
        lo, hi = ideal[k] - slack / 2, ideal[k] + slack / 2
        best = _best_seam(ctx, ctx.near(axis, lo, hi), axis, others, ideal[k], lo, hi, period)
        chosen.append(best[1])
        scores.append(best[0])
    chosen.append(hi_end)
    if period is not None:
        regular = _regular_seams(ctx, axis, others, lo_end, hi_end, n, cell_max, period)
        if regular is not None:
            unjoined = sum(s[0] for s in scores)
            slivers = sum(s[1] for s in scores)
            if regular[0][0] <= unjoined and regular[0][1] <= slivers + _ALIKE_SLIVER_MM2:
                return regular[1]
    return chosen


def _best_seam(ctx: _Context, win: _Window, axis: int, others, ideal: float, lo: float, hi: float, period):
    """The best (key, position) of one seam between ``lo`` and ``hi``."""
    best = None
    coarse = _candidates(ideal, lo, hi, period, _COARSE_STEP_MM)
    for round_ in (coarse, None):
        if round_ is None:
            assert best is not None
            c = best[1]
            round_ = _candidates(c, max(lo, c - _COARSE_STEP_MM), min(hi, c + _COARSE_STEP_MM), None, _GRID_STEP_MM)
        for pos, on_period in round_:
            key = _score(ctx, win, axis, pos, others, on_period, abs(pos - ideal), best)
            if key is not None and (best is None or key < best[0]):
                best = (key, pos)
    assert best is not None
    return best


def _regular_seams(ctx: _Context, axis: int, others, lo_end, hi_end, n, cell_max, period):
    """The best seams on the period a whole number of periods apart: ((unjoined, slivers, uneven), seams),
    or None when no such spacing fits the bed; of seams alike in the rest, those nearest the even division
    (the most even pieces)."""
    p, o = period
    best = None
    even = (hi_end - lo_end) / n
    win = ctx.near(axis, lo_end, hi_end)
    for steps in range(1, int(cell_max / p) + 1):
        spacing = steps * p
        k0 = math.ceil((hi_end - (n - 1) * spacing - cell_max - o) / p)
        k1 = math.floor((lo_end + cell_max - o) / p)
        for k in range(k0, k1 + 1):
            inner = [o + k * p + i * spacing for i in range(n - 1)]
            cuts = [lo_end, *inner, hi_end]
            if any(b - a > cell_max + 1e-9 or b - a <= 0 for a, b in itertools.pairwise(cuts)):
                continue
            keys = [_score(ctx, win, axis, x, others, True, 0.0, None) for x in inner]
            uneven = round(max(abs(b - a - even) for a, b in itertools.pairwise(cuts)), 3)
            total = (sum(key[0] for key in keys), sum(key[1] for key in keys), uneven)
            if best is None or total < best[0]:
                best = (total, cuts)
    return best


def _score(ctx: _Context, win: _Window, axis: int, pos: float, others, on_period: bool, off: float, best):
    """A seam position's key, smaller is better: pairs it cannot join, slivers, off the period, off
    even; None when it cannot beat ``best`` on the pairs it joins."""
    stretches, slopes = win.crossings(pos)
    unjoined = sum(not _sites(ctx, win, pos, stretches, a, b) for a, b in _pairs(others))
    if best is not None and unjoined > best[0][0]:
        return None
    return (unjoined, round(_sliver_area(ctx, win, pos, slopes), 2), not on_period, round(off, 3))


def _pairs(others) -> list[tuple[float, float]]:
    """The stretches of a seam between the other axis's seams, open at the panel's edges (a tab
    near an edge crosses no seam)."""
    return list(itertools.pairwise([-math.inf, *others[1:-1], math.inf]))


def _sites(ctx: _Context, win: _Window, pos: float, stretches, a: float, b: float) -> list[float]:
    """Where on the seam ``pos`` between ``a`` and ``b`` a tab fits: the middles of its stretches
    long enough, where the tab grown by the minimum feature lies in the material."""
    need = ctx.joint.head_mm + 2 * ctx.min_mm
    lo, hi = a + need / 2, b - need / 2
    probe = ctx.probes[win.axis]
    out = []
    for p, q in stretches:
        p, q = max(p, lo), min(q, hi)
        if q - p < ctx.joint.neck_mm + 2 * ctx.min_mm:
            continue
        mid = (p + q) / 2
        centre = (pos, mid) if win.axis == 0 else (mid, pos)
        if shapely.contains(win.local, shapely.Polygon(probe + centre)):
            out.append(mid)
    return out


def _sliver_area(ctx: _Context, win: _Window, pos: float, slopes: np.ndarray) -> float:
    """The material a seam at ``pos`` leaves narrower than the minimum feature, estimated.

    An edge crossing the seam at an angle leaves a wedge, thinner than ``m`` over ``m`` times
    its slope: ``m**2 * slope / 2``, capped at the edge's own reach; a corner of the material
    within ``m`` of the seam without crossing it leaves a strip as thin as its distance.
    """
    m = ctx.min_mm
    wedges = float(np.minimum(slopes, 50.0).sum()) * m * m / 2
    near = win.corners_within(pos, m)
    return wedges + float(((m - near) * m).sum())


def _cell_boxes(xs, ys, bounds) -> dict[tuple[int, int], tuple[float, float, float, float]]:
    """Each cell's rectangle between the seams (the outermost moved out beyond ``bounds``)."""
    x0, y0, x1, y1 = bounds
    xs = [x0 - 1, *xs[1:-1], x1 + 1]
    ys = [y0 - 1, *ys[1:-1], y1 + 1]
    return {(i, j): (xs[i], ys[j], xs[i + 1], ys[j + 1]) for i in range(len(xs) - 1) for j in range(len(ys) - 1)}


def _clip(geom, bounds):
    """``geom`` within the rectangle ``bounds``: GEOS's rectangle clip (tens of times faster than
    an overlay on a lattice of many holes), the overlay where the clip's result is not valid."""
    out = shapely.clip_by_rect(geom, *bounds)
    return out if shapely.is_valid(out) else shapely.intersection(geom, box(*bounds))


def _parts(region) -> list:
    return [g for g in getattr(region, "geoms", [region]) if not g.is_empty]


def _islands_to_neighbours(regions: dict, nx: int, ny: int) -> dict:
    """Give each bit of a piece that touches the piece's largest part nowhere to a neighbour it touches."""
    changed = True
    while changed:
        changed = False
        for cell, region in list(regions.items()):
            parts = _parts(region)
            if len(parts) < 2:
                continue
            main = max(parts, key=lambda g: g.area)
            for part in parts:
                if part is main:
                    continue
                home = _neighbour_touching(regions, cell, part, nx, ny)
                if home is None:
                    continue  # an island of the design itself, not of the seam
                regions[cell] = shapely.difference(regions[cell], part)
                regions[home] = shapely.union(regions[home], part)
                changed = True
    return regions


def _neighbour_touching(regions: dict, cell, part, nx: int, ny: int):
    i, j = cell
    best = None
    for di, dj in ((-1, 0), (1, 0), (0, -1), (0, 1)):
        other = (i + di, j + dj)
        if other not in regions:
            continue
        shared = shapely.intersection(shapely.boundary(part), shapely.boundary(regions[other])).length
        if shared > 1e-9 and (best is None or shared > best[0]):
            best = (shared, other)
    return None if best is None else best[1]


def _bar_boxes(ctx: _Context, xs, ys) -> list:
    """Where each inner seam's pairs of pieces can hold no joint: a seam bar's box there (a neck's
    width behind the seam, the tab's depth and a neck beyond)."""
    joint = ctx.joint
    out = []
    for axis, seams, others in ((0, xs, ys), (1, ys, xs)):
        for pos in seams[1:-1]:
            win = ctx.near(axis, pos, pos)
            stretches, _ = win.crossings(pos)
            lo, hi = pos - joint.neck_mm, pos + joint.depth_mm + joint.neck_mm
            for a, b in _pairs(others):
                if b - a >= joint.head_mm + 2 * ctx.min_mm and not _sites(ctx, win, pos, stretches, a, b):
                    a, b = max(a, others[0] - 1), min(b, others[-1] + 1)
                    out.append(box(lo, a, hi, b) if axis == 0 else box(a, lo, b, hi))
    return out


def _lay_bars(ctx: _Context, regions: dict, cells: dict, boxes: list) -> list:
    """Add the seam bars of ``boxes`` (within the panel's footprint) to the regions of the cells
    they cross, in place, filling the holes they leave narrower than the minimum feature; the
    material each bar added (disjoint: together, all that was added)."""
    if not boxes:
        return []
    footprint = _footprint(ctx.material)
    bars: list = []
    for b in boxes:  # disjoint where an x and a y seam's bars cross
        bar = shapely.intersection(b, footprint)
        bar = shapely.difference(bar, shapely.union_all(bars)) if bars else bar
        if not bar.is_empty:
            bars.append(bar)
    every = shapely.union_all(bars)
    near = every.buffer(ctx.min_mm)
    filled = []
    for cell, bounds in cells.items():  # one overlay per region: each costs the whole region
        part = _clip(every, bounds)
        if not part.is_empty:
            regions[cell], holes = _fill_slits(shapely.union(regions[cell], part), near, ctx.min_mm)
            filled.append(holes)
    new = [shapely.difference(bar, _clip(ctx.material, bar.bounds)) for bar in bars]
    parts = shapely.get_parts(shapely.union_all(new + filled))
    taken = np.zeros(len(parts), bool)
    added = []
    for bar in bars:  # each bit added counted with the first bar it lies by
        mine = shapely.intersects(bar.buffer(ctx.min_mm), parts) & ~taken
        taken |= mine
        added.append(shapely.union_all(parts[mine]))
    return added


def _footprint(material):
    """The material with its holes filled: where a seam bar may lie (never beyond the panel's edge)."""
    return shapely.union_all([shapely.Polygon(p.exterior) for p in _parts(material) if p.geom_type == "Polygon"])


def _fill_slits(region, near, min_mm: float):
    """``region`` with the holes by ``near`` (a seam bar) narrower than ``min_mm`` filled; and those holes."""
    shapely.prepare(near)
    out, filled = [], []
    for part in _parts(region):
        if part.geom_type != "Polygon":
            continue
        rings = shapely.get_interior_ring(part, np.arange(shapely.get_num_interior_rings(part)))
        holes = shapely.polygons(rings)
        thin = np.zeros(len(holes), bool)
        close = np.flatnonzero(shapely.intersects(near, holes))
        thin[close] = shapely.is_empty(shapely.buffer(holes[close], -min_mm / 2))
        out.append(shapely.polygons(shapely.get_exterior_ring(part), holes=rings[~thin]) if thin.any() else part)
        filled.extend(holes[thin])
    # the parts stay apart (a hole filled joins nothing): a collection of them, not an overlay
    return (out[0] if len(out) == 1 else shapely.MultiPolygon(out)), shapely.union_all(filled)


def _joints(ctx: _Context, regions: dict, xs, ys, nx: int, ny: int) -> list:
    """A joint on every stretch where two neighbours meet wide enough (the regions changed in
    place); an error where a pair has none."""
    joints: list[PlacedJoint] = []
    sockets: dict = {cell: [] for cell in regions}
    tabs: dict = {cell: [] for cell in regions}
    for i, j in sorted(regions):
        for axis, other in ((0, (i + 1, j)), (1, (i, j + 1))):
            if other not in regions:
                continue
            pos = xs[i + 1] if axis == 0 else ys[j + 1]
            pair = (_number(i, j, nx, ny), _number(*other, nx, ny))
            stretches = _stretches(regions[(i, j)], regions[other])
            if not stretches:
                continue  # neighbours that touch nowhere (a corner of the grid)
            placed = _tabs_on_seam(ctx, regions, (i, j), other, axis, pos, stretches, joints)
            if not placed:
                joint = ctx.joint
                raise FabricationError(
                    f"pieces {pair[0]} and {pair[1]} meet across the seam at {'x' if axis == 0 else 'y'} = "
                    f"{pos:.1f} mm only where the material is narrower than a {joint.kind} joint needs "
                    f"({joint.neck_mm + 2 * ctx.min_mm:g} mm at the seam, {joint.head_mm + 2 * ctx.min_mm:g} mm "
                    "across its head); use a wider stroke or frame, a smaller joint, or a larger bed"
                )
            for at, tab in placed:
                joints.append(PlacedJoint(pair, at, tab))
                sockets[other].append(tab)
                tabs[(i, j)].append(ctx.joint.grown(tab, ctx.joint.fit_mm) if ctx.joint.fit_mm else tab)
    # each region changed once for all its tabs and sockets: an overlay costs the whole region
    for cell in regions:
        if sockets[cell]:
            regions[cell] = shapely.difference(regions[cell], shapely.union_all(sockets[cell]))
        if tabs[cell]:
            regions[cell] = shapely.union(regions[cell], shapely.union_all(tabs[cell]))
    return joints


def _stretches(region, other) -> list:
    """Where two pieces meet: the shared boundary's line pieces, longest first."""
    shared = shapely.intersection(shapely.boundary(region), shapely.boundary(other))
    return sorted((s for s in _segments(shared) if s.length > 1e-9), key=lambda s: -s.length)


def _tabs_on_seam(ctx: _Context, regions: dict, cell, other, axis: int, pos: float, stretches, joints) -> list:
    """Tabs of ``cell`` into ``other`` on each stretch of the seam where they fit: one per
    :data:`TAB_SPACING_MM` of it, each at the middle of its share of the stretch, else at the
    nearest place in that share that holds the tab (a stretch may run on from a frame into a
    band), clear of the tabs of ``joints`` placed before; the new tabs as ``[((x, y), tab), ...]``
    (the regions are not changed: :func:`_joints` applies every tab at the end)."""
    joint = ctx.joint
    direction = (1.0, 0.0) if axis == 0 else (0.0, 1.0)
    along = 1 - axis
    taken = [joint.grown(j.tab, ctx.min_mm) for j in joints]
    placed: list = []
    for s in stretches:
        c = np.asarray(s.centroid.coords[0])
        if s.length < joint.neck_mm + 2 * ctx.min_mm or abs(c[axis] - pos) > 1e-6:
            continue
        start, end = sorted((s.coords[0][along], s.coords[-1][along]))
        n = max(1, round(s.length / TAB_SPACING_MM))
        for k in range(n):
            share = (start + (end - start) * k / n, start + (end - start) * (k + 1) / n)
            at = np.array(c, float)
            at[axis] = pos  # on the seam exactly: a tab a rounding off it would not touch its piece
            at[along] = (share[0] + share[1]) / 2
            found = _fitting_tab(ctx, regions, cell, other, share, at, direction, along, taken)
            if found is not None:
                tab, where = found
                taken.append(joint.grown(tab, ctx.min_mm))
                placed.append(((float(where[0]), float(where[1])), tab))
    return placed


def _fitting_tab(ctx: _Context, regions: dict, cell, other, share, c, direction, along: int, taken):
    """``(tab, where)``: the tab at ``c``, or moved along the seam within ``share`` (by a tenth of
    the neck, nearest first) to where the tab grown by the minimum feature lies in the two pieces'
    material, clear of the ``taken`` tabs (grown likewise); None where none does."""
    joint = ctx.joint
    r = ctx.reach
    lo, hi = share
    x0, y0, x1, y1 = (c[0] - r, lo - r, c[0] + r, hi + r) if along else (lo - r, c[1] - r, hi + r, c[1] + r)
    mine = _clip(regions[cell], (x0, y0, x1, y1))
    theirs = _clip(regions[other], (x0, y0, x1, y1))
    shapely.prepare(theirs)
    lo, hi = lo + joint.neck_mm / 2 + ctx.min_mm, hi - joint.neck_mm / 2 - ctx.min_mm
    step = max(0.1, joint.neck_mm / 10)
    mid = float(c[along])
    n = int((hi - lo) / step) if hi > lo else 0
    tries = sorted({mid, *(lo + k * step for k in range(n + 1))}, key=lambda v: abs(v - mid))
    for v in tries:
        if not lo - 1e-9 <= v <= hi + 1e-9 and v != mid:
            continue
        at = np.array(c, float)
        at[along] = v
        tab = joint.tab(at, direction)
        grown = joint.grown(tab, ctx.min_mm)
        if shapely.contains(theirs, grown.difference(mine)) and not any(shapely.intersects(grown, t) for t in taken):
            return tab, at
    return None


def _segments(geom) -> list:
    """The line pieces of a shared boundary, merged where they continue each other."""
    lines = [g for g in getattr(geom, "geoms", [geom]) if g.geom_type in ("LineString", "MultiLineString")]
    if not lines:
        return []
    merged = shapely.line_merge(shapely.union_all(lines))
    return list(getattr(merged, "geoms", [merged]))
