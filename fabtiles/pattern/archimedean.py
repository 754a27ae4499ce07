"""The tile operation on the 11 Archimedean and the two-uniform tilings (``docs/tile-operation.md``).

Pure numpy. In an edge-to-edge tiling by regular polygons of edge ``a`` the
incircle of each p-gon (radius ``a / (2 tan(pi/p))``) touches the incircles of
its p neighbours at the shared edges' midpoints, so the incircles are a packing
of tangent circles; around every tiling vertex they leave a gap, filled by its
gap circle (the largest circle in the gap, see :mod:`fabtiles.pattern.tilings`).
Each incircle holds the motif of its polygon kind, each gap circle the gap motif,
scaled to the circle as in :class:`~fabtiles.pattern.packing.HexPacking`.
"""

from __future__ import annotations

import functools
import math
import numbers
from collections.abc import Mapping
from dataclasses import KW_ONLY, dataclass, field
from types import MappingProxyType
from typing import Any, cast

import numpy as np

from ..core.errors import LimitError, ParameterError
from ..core.schema import register_check
from ..core.validate import check_float
from .hankin import check_contact, check_method, check_parquet, parquet_angles, polygon_rays, polygons_rays
from .packing import MAX_CIRCLES_IN_WINDOW, check_window, chord_count, circle_segments, default_gap_motif
from .star import Star
from .tilings import ALL_TILINGS, NAMES, UnitCell, circumradius, inradius, unit_cell

DEFAULT_MOTIFS: Mapping[int, dict[str, Any]] = MappingProxyType(
    {
        3: dict(n=6, radii=(0.5, 1.0)),
        4: dict(n=8, radii=(0.55, 1.0)),
        6: dict(n=12, radii=(123, 85, 178), alpha=23, spr=-7, special=2),  # preset table3-3
        8: dict(n=8, radii=(51, 70, 172)),  # preset table1-part1
        12: dict(n=12, radii=(123, 85, 178), alpha=23, spr=-7, special=2),
    }
)
"""Polygon sides -> Star parameters of the motif used when ``motifs`` names no motif for that kind."""


def _turn(star: Star) -> float:
    """Direction (radians) of the points on the motif's largest circle before its own
    ``rotation``: circle ``w`` (0-based) holds points at ``rotation + w * 180 / n``. These are
    turned to the tangency points; the motif's ``rotation`` then turns it further."""
    w = int(np.argmax(star.radii))
    return math.radians(w * 180.0 / star.n)


def _rotated(seg: np.ndarray, angle: float, step: float) -> np.ndarray:
    """``seg`` turned by ``angle`` modulo the motif's symmetry ``step`` (no turn when that is 0,
    so 6.6.6 and 4.4.4.4 place motifs exactly as HexPacking and SquarePacking do)."""
    angle = angle % step
    if min(angle, step - angle) < 1e-12:
        return seg
    c, s = math.cos(angle), math.sin(angle)
    return seg @ np.array([[c, s], [-s, c]])


@dataclass(frozen=True, slots=True, repr=False)
class TilingPacking:
    """A tiling's incircles and gap circles, a motif in each (immutable); the tiling one of the
    11 Archimedean or the two-uniform ones (``ArchimedeanPacking`` is the same class).

    Parameters
    ----------
    tiling : str
        One of :meth:`tilings` (``"4.8.8"``, ``"[3^6; 3^4.6]#1"``), or another spelling
        :func:`~fabtiles.pattern.tilings.canonical` takes (``"3^4.6"``).
    edge : float
        Edge length ``a`` of the tiling's polygons, mm (> 0).
    motifs : mapping of int to Star or str, optional
        Motif (a :class:`~fabtiles.pattern.star.Star` or a preset name) per polygon
        kind, keyed by its number of sides; kinds not given get
        :data:`DEFAULT_MOTIFS`. Each motif is turned so the points of its largest
        circle face the polygon's edge midpoints (with ``n`` a multiple of ``p``
        they land on the tangency points, so neighbouring motifs meet); its own
        ``rotation`` turns it further.
    gap_motif : Star or str, optional
        Motif of the gap circles (default ``Star(n=6, radii=(0.5, 1.0))``), turned
        so its largest circle's points face the largest polygon it touches.
    outline_circles : bool, keyword-only
        Also stroke the circles themselves.
    fill : float, keyword-only
        Motif extent as a fraction of its circle's radius, in (0, 1].
    method : str, keyword-only
        ``"motifs"`` (default): the paper's motifs in the incircles and gap circles, as above.
        ``"hankin"``: Hankin's polygons in contact (:mod:`fabtiles.pattern.hankin`): two rays
        leave each edge at ``contact_angle`` and meet their neighbours' on the corners'
        bisectors; the kinds named in ``motifs`` keep their motif in the incircle (the others
        take the rays, and ``DEFAULT_MOTIFS`` fills none); there are no gap circles.
    contact_angle : float, keyword-only
        ``method="hankin"``: the rays' angle to their edge, degrees, in (0, 90).
    contact_gap : float, keyword-only
        ``method="hankin"``: the distance along the edge between the two rays' starts, mm,
        >= 0 and < ``edge``. With no gap (or one under 1e-9 of the edge) a ray and its straight
        continuation across the edge (the neighbour's ray) are one segment.
    contact_angle_to : float, optional, keyword-only
        ``method="hankin"``: a *parquet deformation*: the contact angle at the far side of the
        window :meth:`segments` draws (a tile's bounding box), ``contact_angle`` being the near
        side's; each polygon's rays take the angle at its centre (:func:`~fabtiles.pattern.hankin.parquet_angles`).
        Both polygons of an edge start their rays at the same points on it, so the strands stay
        continuous, bending there by the two polygons' difference in angle. None (default): one angle.
    parquet_direction : str, keyword-only
        Across which the angle changes: ``"x"`` (left to right, default), ``"y"`` (bottom to top) or
        ``"radial"`` (from the centre out to the circle inscribed in the window).
    parquet_curve : str, keyword-only
        ``"linear"`` (default) or ``"smooth"`` (smoothstep: flat at both sides).

    Examples
    --------
    >>> p = TilingPacking("4.8.8", edge=20, motifs={8: "table3-3"})
    >>> p.tiling, p.kinds, round(p.incircle_radius(8), 4), tuple(round(v, 4) for v in p.period)
    ('4.8.8', (4, 8), 24.1421, (48.2843, 48.2843))
    >>> c, r = p.circles((-5, -5, 5, 5))
    >>> len(r), p.circle_sides((-5, -5, 5, 5)).tolist()
    (1, [8])
    >>> TilingPacking("4.8.8", edge=20, motifs={6: "table3-3"})
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: motifs key 6 is not a polygon of the tiling 4.8.8, must be one of: 4, 8
    >>> h = TilingPacking("4.8.8", edge=20, method="hankin", contact_angle=67.5)
    >>> h.motifs, h.segments((-1, -1, 1, 1)).shape  # the octagon's: 2 per edge it keeps (4 of 8)
    (mappingproxy({}), (8, 2, 2))
    """

    tiling: str
    """Vertex configuration, as in :meth:`tilings`."""
    edge: float
    """Edge length of the polygons, mm."""
    motifs: Mapping[int, Star] | Mapping[int | str, Star | str] | None = field(default=None, compare=False)
    """Polygon sides -> motif, for every kind of the tiling (``method="hankin"``: the kinds
    that keep a motif) (read-only mapping)."""
    gap_motif: Star | str | None = None
    """Motif of the gap circles (a Star once the packing is made)."""
    _: KW_ONLY
    outline_circles: bool = False
    """Whether the circles are stroked."""
    fill: float = 1.0
    """Motif extent / circle radius."""
    method: str = "motifs"
    """``"motifs"`` (the paper's) or ``"hankin"`` (polygons in contact)."""
    contact_angle: float = 60.0
    """Hankin's rays' angle to their edge, degrees."""
    contact_gap: float = 0.0
    """Between the two rays' starts on an edge, mm."""
    contact_angle_to: float | None = None
    """A parquet deformation's angle at the far side, degrees (None: one angle throughout)."""
    parquet_direction: str = "x"
    """Across which a parquet deformation's angle changes: ``"x"``, ``"y"`` or ``"radial"``."""
    parquet_curve: str = "linear"
    """How a parquet deformation's angle changes: ``"linear"`` or ``"smooth"``."""
    _motifs: tuple[tuple[int, Star], ...] = field(init=False, repr=False)
    """``motifs`` as ``(sides, Star)`` pairs: what equality and the hash compare (a mapping has no hash)."""

    def __post_init__(self) -> None:
        cell = unit_cell(self.tiling)
        kinds = tuple(sorted(set(cell.sides.tolist())))
        given = _given_motifs(self.motifs, kinds, cell.name)
        method = check_method(self.method)
        if method == "hankin":  # only the kinds named keep a motif; the rest take Hankin's rays
            full = tuple((p, given[p]) for p in kinds if p in given)
        else:
            full = tuple((p, given.get(p) or Star(**DEFAULT_MOTIFS[p])) for p in kinds)
        gap = default_gap_motif() if self.gap_motif is None else _motif("gap_motif", self.gap_motif)
        if not isinstance(self.outline_circles, bool):
            raise ParameterError(
                f"outline_circles must be true or false, got {self.outline_circles!r}", param="outline_circles"
            )
        init = object.__setattr__  # the frozen dataclass's own way to set a field in __post_init__
        init(self, "tiling", cell.name)
        edge = check_float("edge", self.edge, low=0, low_open=True)
        init(self, "edge", edge)
        contact = self._checked_contact(method, edge, [p for p in kinds if p not in given], cell.name)
        init(self, "method", method)
        init(self, "contact_angle", contact[0])
        init(self, "contact_gap", contact[1])
        init(
            self,
            "contact_angle_to",
            self._checked_parquet(method, edge, [p for p in kinds if p not in given], cell.name),
        )
        init(self, "_motifs", full)
        init(self, "motifs", MappingProxyType(dict(full)))
        init(self, "gap_motif", gap)
        init(self, "fill", check_float("fill", self.fill, low=0, high=1, low_open=True))

    def _checked_contact(self, method: str, edge: float, rays: list, tiling: str) -> tuple:
        """``(contact_angle, contact_gap)`` checked: against the tiling's polygons that take Hankin's
        ``rays``, or, with the motifs' method, each alone (unused, but kept and checked so that
        ``replace(method="hankin")`` takes them)."""
        if method == "hankin":
            return check_contact(self.contact_angle, self.contact_gap, edge, rays, tiling)
        return (
            check_float("contact_angle", self.contact_angle, low=0, high=90, low_open=True, high_open=True),
            check_float("contact_gap", self.contact_gap, low=0),
        )

    def _checked_parquet(self, method: str, edge: float, rays: list, tiling: str) -> float | None:
        """``contact_angle_to`` checked like ``contact_angle`` (every angle between the two then has
        a pattern too: the limit is one bound), and the direction and curve against their choices."""
        check_parquet(self.parquet_direction, self.parquet_curve)
        if method != "hankin":
            for name, value, default in (
                ("parquet_direction", self.parquet_direction, "x"),
                ("parquet_curve", self.parquet_curve, "linear"),
            ):
                if value != default:  # a parquet deformation's, which the motifs have not
                    raise ParameterError(
                        f"{name} = {value!r} shapes a parquet deformation of Hankin's rays, not of "
                        f"method = {method!r}; set method = 'hankin' (and contact_angle_to) or leave {name} out",
                        param=name,
                    )
        if self.contact_angle_to is None:
            return None
        if method != "hankin":
            raise ParameterError(
                f"contact_angle_to = {self.contact_angle_to!r} is a parquet deformation of Hankin's rays, "
                f"not of method = {method!r}; set method = 'hankin' or leave contact_angle_to out",
                param="contact_angle_to",
            )
        return check_contact(self.contact_angle_to, self.contact_gap, edge, rays, tiling, name="contact_angle_to")[0]

    def __reduce__(self):
        # ``motifs`` is a mappingproxy, which does not pickle: pickle and copy rebuild from the parameters.
        return (_rebuild, ({**self.params(), "motifs": dict(self._motifs)},))

    # -- parameters ---------------------------------------------------------
    @property
    def _cell(self) -> UnitCell:
        return unit_cell(self.tiling)

    @property
    def kinds(self) -> tuple[int, ...]:
        """The polygon kinds of the tiling (numbers of sides), ascending."""
        return tuple(sorted(set(self._cell.sides.tolist())))

    @property
    def radius(self) -> float:
        """The smallest incircle radius, mm: the largest stroke a tile of this packing takes."""
        return inradius(self.kinds[0], self.edge)

    def incircle_radius(self, sides: int) -> float:
        """Incircle radius of the tiling's ``sides``-gons, ``edge / (2 tan(pi / sides))``, mm."""
        return inradius(_kind(sides, self.kinds, self.tiling), self.edge)

    @staticmethod
    def tilings() -> tuple[str, ...]:
        """The tilings: the 11 vertex configurations, then the two-uniform tilings.

        >>> len(TilingPacking.tilings()), TilingPacking.tilings()[:3], TilingPacking.tilings()[11]
        (31, ('3.3.3.3.3.3', '4.4.4.4', '6.6.6'), '[3^6; 3^2.4.3.4]')
        """
        return ALL_TILINGS

    @staticmethod
    def tiling_name(tiling) -> str:
        """Common name of a tiling.

        >>> TilingPacking.tiling_name("3^4.6")
        'snub hexagonal'
        """
        return NAMES[unit_cell(tiling).name]

    @property
    def lattice(self) -> np.ndarray:
        """The two lattice vectors (rows), mm."""
        return self._cell.lattice * self.edge

    @property
    def period(self) -> tuple[float, float]:
        """Smallest rectangular period ``(px, py)`` of the packing, mm (see :func:`rectangular_period`)."""
        px, py = rectangular_period(self.tiling)
        return (px * self.edge, py * self.edge)

    def params(self) -> dict:
        """The constructor arguments."""
        return dict(
            tiling=self.tiling,
            edge=self.edge,
            motifs=self.motifs,
            gap_motif=self.gap_motif,
            outline_circles=self.outline_circles,
            fill=self.fill,
            method=self.method,
            contact_angle=self.contact_angle,
            contact_gap=self.contact_gap,
            contact_angle_to=self.contact_angle_to,
            parquet_direction=self.parquet_direction,
            parquet_curve=self.parquet_curve,
        )

    def replace(self, **changes) -> TilingPacking:
        """A copy with some parameters changed (validated again).

        >>> TilingPacking("3.6.3.6", 10).replace(edge=5).edge
        5.0
        """
        return type(self)(**{**self.params(), **changes})

    def __repr__(self) -> str:
        motifs = ", ".join(f"{p}: {s!r}" for p, s in self._motifs)
        extra = ", outline_circles=True" if self.outline_circles else ""
        extra += f", fill={self.fill:g}" if self.fill != 1.0 else ""
        if self.method == "hankin":
            extra += f", method='hankin', contact_angle={self.contact_angle:g}, contact_gap={self.contact_gap:g}"
        if self.contact_angle_to is not None:
            extra += (
                f", contact_angle_to={self.contact_angle_to:g}, parquet_direction={self.parquet_direction!r}, "
                f"parquet_curve={self.parquet_curve!r}"
            )
        return (
            f"{type(self).__name__}({self.tiling!r}, edge={self.edge:g}, motifs={{{motifs}}}, "
            f"gap_motif={self.gap_motif!r}{extra})"
        )

    # -- circles --------------------------------------------------------------
    def _entries(self):
        """Per unit-cell circle: offset (mm), radius (mm), sides (0: gap); Hankin's method has no gap circles."""
        cell, a = self._cell, self.edge
        if self.method == "hankin":
            return cell.centres * a, cell.radii() * a, np.asarray(cell.sides)
        offsets = np.concatenate([cell.centres, cell.gap_centres]) * a
        radii = np.concatenate([cell.radii(), cell.gap_radii]) * a
        sides = np.concatenate([cell.sides, np.zeros(len(cell.gap_radii), dtype=int)])
        return offsets, radii, sides

    def _translates(self, offsets, margins, window) -> tuple[np.ndarray, np.ndarray]:
        """``(points, entry index)``: every lattice translate of each offset (mm) within its margin
        (mm) of ``window``, unsorted; a LimitError when the window holds too many."""
        x0, y0, x1, y1 = check_window(window)
        basis = self.lattice
        inv = np.linalg.inv(basis.T)
        lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
        for off, m in zip(offsets, margins, strict=True):
            corners = np.array([[x0 - m, y0 - m], [x1 + m, y0 - m], [x0 - m, y1 + m], [x1 + m, y1 + m]])
            ij = (corners - off) @ inv.T
            lo, hi = np.minimum(lo, np.floor(ij.min(axis=0))), np.maximum(hi, np.ceil(ij.max(axis=0)))
        count = float(np.prod(hi - lo + 1)) * len(offsets)
        if count > MAX_CIRCLES_IN_WINDOW:
            raise LimitError(
                f"the window holds about {count:.3g} circles, more than the limit of "
                f"{MAX_CIRCLES_IN_WINDOW}; use a larger edge (got {self.edge:g} mm) or a smaller tile",
                param="edge",
            )
        jj, ii = np.meshgrid(np.arange(lo[1], hi[1] + 1), np.arange(lo[0], hi[0] + 1), indexing="ij")
        lattice = ii.reshape(-1, 1) * basis[0] + jj.reshape(-1, 1) * basis[1]
        pts, idx = [], []
        for e, (off, m) in enumerate(zip(offsets, margins, strict=True)):
            p = lattice + off
            keep = (p[:, 0] >= x0 - m) & (p[:, 0] <= x1 + m) & (p[:, 1] >= y0 - m) & (p[:, 1] <= y1 + m)
            pts.append(p[keep])
            idx.append(np.full(int(keep.sum()), e))
        return np.concatenate(pts), np.concatenate(idx)

    def _placed(self, window):
        """``(centres, entry index)`` of every circle whose bounding box meets ``window``,
        incircles first then gap circles, each group rows bottom to top, left to right."""
        offsets, radii, sides = self._entries()
        pts, idx = self._translates(offsets, self._reach(radii) * (1 + 1e-9), window)
        order = np.lexsort((np.round(pts[:, 0], 9), np.round(pts[:, 1], 9), sides[idx] == 0))
        return pts[order], idx[order]

    def polygons(self, window) -> list[np.ndarray]:
        """Every polygon of the tiling that meets ``window``, as its corners.

        The tiling under the pattern, for a picture or a check: the polygons of edge
        :attr:`edge` whose centres are the incircles' (:meth:`circles`), in the same frame.

        Parameters
        ----------
        window : (float, float, float, float)
            ``(xmin, ymin, xmax, ymax)`` in the packing's frame, mm (as :meth:`circles`).

        Returns
        -------
        list of ndarray, shape (k, 2)
            Each polygon's ``k`` corners, mm, counter-clockwise; rows of polygons bottom to
            top, left to right.

        Examples
        --------
        >>> square = TilingPacking("4.4.4.4", edge=10).polygons((1, 1, 2, 2))
        >>> [p.round(3).tolist() for p in square]
        [[[5.0, 5.0], [-5.0, 5.0], [-5.0, -5.0], [5.0, -5.0]]]
        >>> len(TilingPacking("[3^6; 3^4.6]#1", edge=10).polygons((0, 0, 30, 30)))
        25
        """
        cell, a = self._cell, self.edge
        out: list[np.ndarray] = []
        for centre, e in zip(*self._frames(window), strict=True):
            p = int(cell.sides[e])
            turns = cell.angles[e] + 2 * np.pi * np.arange(p) / p + np.pi / p
            out.append(centre + circumradius(p, a) * np.stack([np.cos(turns), np.sin(turns)], axis=1))
        return out

    def _frames(self, window) -> tuple[np.ndarray, np.ndarray]:
        """``(centres, entry index)`` of every polygon of the tiling that meets ``window``, in the
        order of :meth:`polygons`; a polygon's sides and turn are its unit-cell entry's."""
        x0, y0, x1, y1 = check_window(window)
        cell, a = self._cell, self.edge
        outer = np.array([circumradius(int(p), a) for p in cell.sides])
        pts, idx = self._translates(cell.centres * a, outer * (1 + 1e-9), window)
        order = np.lexsort((np.round(pts[:, 0], 9), np.round(pts[:, 1], 9)))
        pts, idx = pts[order], idx[order]
        rect = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
        keep = np.zeros(len(pts), dtype=bool)
        for e in np.unique(idx).tolist():
            p, at = int(cell.sides[e]), np.flatnonzero(idx == e)
            turns = cell.angles[e] + 2 * np.pi * np.arange(p) / p
            normals = np.stack([np.cos(turns), np.sin(turns)], axis=1)
            centres = pts[at]
            # separating axes of two convex shapes: the rectangle's (its bounding box) and the polygon's edge normals
            apart = ((rect[None] - centres[:, None]) @ normals.T).min(axis=1).max(axis=1) > inradius(p, a) * (1 + 1e-12)
            corners = centres[:, None] + outer[e] * np.stack(
                [np.cos(turns + np.pi / p), np.sin(turns + np.pi / p)], axis=1
            )
            outside = (
                (corners[..., 0].max(axis=1) < x0)
                | (corners[..., 0].min(axis=1) > x1)
                | (corners[..., 1].max(axis=1) < y0)
                | (corners[..., 1].min(axis=1) > y1)
            )
            keep[at] = ~(apart | outside)
        return pts[keep], idx[keep]

    def circles(self, window) -> tuple[np.ndarray, np.ndarray]:
        """Centres ``(m, 2)`` and radii ``(m,)`` of every circle that may meet ``window``.

        A circle is kept when its bounding box meets the window, so every circle a tile can
        show is there and the caller clips. Incircles first, then gap circles, each rows
        bottom to top, left to right.

        Parameters
        ----------
        window : (float, float, float, float)
            ``(xmin, ymin, xmax, ymax)`` in the packing's frame (a polygon centred on the
            origin), mm.

        Returns
        -------
        centres : ndarray, shape (m, 2)
            mm.
        radii : ndarray, shape (m,)
            mm.

        Examples
        --------
        >>> c, r = TilingPacking("6.6.6", edge=10).circles((0, 0, 8, 6))
        >>> c.round(3).tolist(), r.round(3).tolist()
        ([[0.0, 0.0], [8.66, 5.0]], [8.66, 1.34])
        """
        pts, idx = self._placed(window)
        return pts, self._entries()[1][idx]

    def circle_sides(self, window) -> np.ndarray:
        """For each circle of :meth:`circles` (same order), the sides of its polygon; 0 for a gap circle.

        >>> TilingPacking("3.4.6.4", edge=10).circle_sides((-1, -1, 1, 1)).tolist()
        [6]
        """
        return self._entries()[2][self._placed(window)[1]]

    def segment_count(self, window) -> int:
        """Centre-line segments :meth:`segments` returns for ``window``, counted without placing them.

        >>> TilingPacking("4.4.4.4", edge=10).segment_count((0, 0, 6, 6))  # 4 squares, 1 gap
        76
        """
        per = np.array([len(u) for u in self._unit_motifs()])
        if self.contact_angle_to is None:
            count = int(per[self._placed(window)[1]].sum())
        else:
            rays, motifs = self._parquet_entries()
            idx = self._placed(window)[1]
            count = int(per[idx[motifs[idx]]].sum())
            e = self._frames(window)[1]
            count += int((2 * self._cell.sides[e])[rays[e]].sum())
        if self.outline_circles:
            _, radii = self.circles(window)
            r, k = np.unique(radii, return_counts=True)
            count += sum(chord_count(float(v)) * int(m) for v, m in zip(r, k, strict=True))
        return count

    # -- motifs ---------------------------------------------------------------
    def _reach(self, radii) -> np.ndarray:
        """Per unit-cell entry: how far its segments reach from its centre, mm (its circle's radius,
        a Hankin polygon's farthest ray end: rays merged across an edge reach into the neighbour)."""
        if self.method != "hankin":
            return radii
        units = self._unit_motifs()
        return np.array(
            [
                max(r, float(np.hypot(*u.reshape(-1, 2).T).max()) if len(u) else 0.0)
                for r, u in zip(radii, units, strict=True)
            ]
        )

    def _hankin_units(self) -> list:
        """Per polygon of the unit cell: its Hankin rays (None for a kind that keeps a motif), centred at 0.

        Without a gap, a ray and the neighbour's ray continuing it across a shared edge are one
        segment, kept by the polygon the edge's outward normal points right (or up) from, so
        each is listed once in the tiling."""
        cell, a = self._cell, self.edge
        angle, gap = self.contact_angle, self.contact_gap
        stars = dict(self._motifs)
        centres = cell.centres * a
        hankin = [int(p) not in stars for p in cell.sides]
        rays: list[Any] = [
            polygon_rays(int(p), a, angle, gap, t) if h else None
            for p, t, h in zip(cell.sides, cell.angles, hankin, strict=True)
        ]
        # the snub hexagonal cell's polygons lie up to 2.5 lattice steps from its origin
        shifts = np.array([(i, j) for i in range(-4, 5) for j in range(-4, 5)], dtype=float) @ self.lattice
        near = (centres[None] + shifts[:, None]).reshape(-1, 2)  # every polygon near the cell
        entry = np.tile(np.arange(len(centres)), len(shifts))
        radii = cell.radii()[entry] * a
        out: list[np.ndarray | None] = []
        for e, p in enumerate(cell.sides.tolist()):
            if not hankin[e]:
                out.append(None)
                continue
            segs = []
            for k in range(p):
                phi = cell.angles[e] + 2 * math.pi * k / p
                o = np.array([math.cos(phi), math.sin(phi)])
                # a gap under 1e-9 of the edge puts both starts on one point to float precision:
                # the rays continue each other across the edge as with none
                if gap <= 1e-9 * a:
                    segs += self._joined_rays(e, k, o, rays, hankin, (near, entry, radii))
                else:
                    segs += [rays[e][k, 0], rays[e][k, 1]]
            out.append(np.array(segs, dtype=float).reshape(-1, 2, 2))
        return out

    def _joined_rays(self, e: int, k: int, o, rays: list, hankin: list, around) -> list:
        """The segments of polygon e's rays on its edge k (outward normal ``o``) when they meet the
        neighbour's there: each ray and the neighbour's one continuing it is one segment, listed by
        the polygon the normal points right (or up) from; a neighbour keeping a motif: the rays.

        ``around``: ``(near, entry, radii)``, the centres of the polygons near the cell, their
        numbers in the cell and their circumradii.
        """
        cell, a = self._cell, self.edge
        near, entry, radii = around
        p = int(cell.sides[e])
        centre = cell.centres[e] * a
        mid = centre + inradius(p, a) * o
        miss = np.hypot(*(near - mid - radii[:, None] * o).T)
        j = int(np.argmin(miss))
        assert miss[j] < 1e-6 * a, "every edge has a neighbour"
        if not hankin[entry[j]]:
            return [rays[e][k, 0], rays[e][k, 1]]
        if not (o[0] > 1e-9 or (abs(o[0]) <= 1e-9 and o[1] > 0)):
            return []  # the neighbour lists the edge's two segments
        q = int(cell.sides[entry[j]])
        turn = math.atan2(*(mid - near[j])[::-1]) - cell.angles[entry[j]]
        kb = round(turn / (2 * math.pi / q)) % q
        other = rays[entry[j]][kb, :, 1] + near[j] - centre
        return [[other[r], rays[e][k, r, 1]] for r in (0, 1)]

    def _unit_motifs(self) -> list:
        """Per unit-cell circle: its motif's segments scaled to the circle, turned, centred at 0
        (``method="hankin"``: a polygon's rays, or its motif); read-only arrays, made once per packing."""
        return _unit_motifs(self)

    def _make_unit_motifs(self) -> list:
        if self.method == "hankin":
            cell = self._cell
            stars = dict(self._motifs)
            radii = cell.radii() * self.edge
            out = self._hankin_units()
            for e, (p, angle, r) in enumerate(zip(cell.sides.tolist(), cell.angles, radii, strict=True)):
                if out[e] is None:
                    star = stars[p]
                    seg = star.segments() * (r * self.fill / star.extent)
                    out[e] = _rotated(seg, angle - _turn(star), 2 * math.pi / star.n)
                out[e].setflags(write=False)
            return out
        else:
            cell = self._cell
            _, radii, _ = self._entries()
            stars = dict(self._motifs)
            turns = [(stars[int(p)], a) for p, a in zip(cell.sides, cell.angles, strict=True)]
            gap_motif = cast(Star, self.gap_motif)  # __post_init__ made it a Star
            turns += [(gap_motif, a) for a in cell.gap_angles]
            cache, out = {}, []
            for (star, angle), r in zip(turns, radii, strict=True):
                key = (star, round(angle - _turn(star), 12), r)
                if key not in cache:
                    seg = star.segments() * (r * self.fill / star.extent)
                    cache[key] = _rotated(seg, angle - _turn(star), 2 * math.pi / star.n)
                    cache[key].setflags(write=False)  # shared by every circle of the kind
                out.append(cache[key])
            return out

    def motif_segments(self, window) -> np.ndarray:
        """The motifs' centre-lines alone (without outline circles), ``(k, 2, 2)`` mm."""
        pts, idx = self._placed(window)
        units = self._unit_motifs()
        parts = [np.empty((0, 2, 2))]
        if self.contact_angle_to is not None:
            rays, motifs = self._parquet_entries()
            pts, idx = pts[motifs[idx]], idx[motifs[idx]]
            parts.append(self._parquet_rays(window, rays))
        for e in np.unique(idx):
            unit = units[e]
            parts.append((unit[None] + pts[idx == e][:, None, None, :]).reshape(-1, 2, 2))
        return np.concatenate(parts)

    def _parquet_entries(self) -> tuple[np.ndarray, np.ndarray]:
        """Per unit-cell polygon: whether it takes Hankin's rays, whether it keeps a motif."""
        stars = dict(self._motifs)
        motifs = np.array([int(p) in stars for p in self._cell.sides])
        return ~motifs, motifs

    def _parquet_rays(self, window, rays: np.ndarray) -> np.ndarray:
        """A parquet deformation's rays, ``(k, 2, 2)`` mm: each polygon meeting ``window`` that takes
        rays (``rays`` per unit-cell entry), at the angle of its centre's place across the window.

        Each polygon's rays are their own segments (the neighbour's continuation bends by the
        difference in angle, so the two are never one straight segment)."""
        cell, a = self._cell, self.edge
        centres, idx = self._frames(window)
        parts = [np.empty((0, 2, 2))]
        for e in np.unique(idx[rays[idx]]).tolist():
            at = centres[idx == e]
            angles = parquet_angles(
                at,
                window,
                self.contact_angle,
                cast(float, self.contact_angle_to),
                self.parquet_direction,
                self.parquet_curve,
            )
            r = polygons_rays(int(cell.sides[e]), a, angles, self.contact_gap, np.full(len(at), cell.angles[e]))
            parts.append((r + at[:, None, None, None, :]).reshape(-1, 2, 2))
        return np.concatenate(parts)

    def segments(self, window) -> np.ndarray:
        """Centre-lines of every motif whose circle meets ``window``; with ``outline_circles``
        the circles follow as chords (:func:`~fabtiles.pattern.packing.circle_segments`).

        Parameters
        ----------
        window : (float, float, float, float)
            ``(xmin, ymin, xmax, ymax)`` in the packing's frame, mm (as :meth:`circles`).

        Returns
        -------
        ndarray, shape (k, 2, 2)
            Each segment's two end points, mm.

        Examples
        --------
        >>> TilingPacking("4.4.4.4", edge=10).segments((0, 0, 6, 6)).shape
        (76, 2, 2)
        """
        parts = [self.motif_segments(window)]
        if self.outline_circles:
            parts.append(circle_segments(*self.circles(window)))
        return np.concatenate(parts)


def rectangular_period(tiling) -> tuple[float, float]:
    """The smallest axis-aligned rectangle ``(px, py)`` that is a period of the tiling, edge 1.

    ``(px, 0)`` and ``(0, py)`` are the shortest lattice vectors along the axes: the first
    lattice vector is along x for every tiling, and the vertical one is found as the
    smallest whole combination with zero x.

    >>> [round(v, 4) for v in rectangular_period("6.6.6")]
    [1.7321, 3.0]
    """
    lat = unit_cell(tiling).lattice
    px = float(lat[0, 0])
    # j * v2 + i * v1 vertical: i = -j * v2x / px must be whole.
    for j in range(1, 13):
        i = -j * lat[1, 0] / px
        if abs(i - round(i)) < 1e-9:
            return px, float(abs(j * lat[1, 1]))
    raise AssertionError(f"no rectangular period for {tiling}")  # pragma: no cover - every tiling has one


def _given_motifs(motifs, kinds: tuple, tiling: str) -> dict:
    """The motifs given, ``{sides: Star}``, each key a kind of polygon of the tiling; a non-mapping refused."""
    if motifs is None:
        return {}
    if not hasattr(motifs, "items"):
        raise ParameterError(
            f"motifs must be a mapping from polygon sides to a Star or preset "
            f"name, like {{8: 'table3-3'}}, got {motifs!r}",
            param="motifs",
        )
    given = {}
    for key, star in motifs.items():
        given[_kind(key, kinds, tiling)] = _motif(f"motifs[{key!r}]", star)
    return given


def _rebuild(params: dict) -> TilingPacking:
    return TilingPacking(**params)


ArchimedeanPacking = TilingPacking
"""The name :class:`TilingPacking` had when it drew the 11 Archimedean tilings only."""


@functools.lru_cache(maxsize=64)
def _unit_motifs(packing: TilingPacking) -> list:
    """A packing's placed motifs, once per distinct packing (packings are values: equal ones share them)."""
    return packing._make_unit_motifs()


def _kind(key, kinds, tiling) -> int:
    text = ", ".join(map(str, kinds))
    if isinstance(key, str) and key.strip().isdigit():
        key = int(key)
    if isinstance(key, bool) or not isinstance(key, numbers.Integral) or int(key) not in kinds:
        entry = f"motifs.{key}" if isinstance(key, numbers.Integral) and not isinstance(key, bool) else "motifs"
        raise ParameterError(
            f"motifs key {key!r} is not a polygon of the tiling {tiling}, must be one of: {text}",
            param="motifs",
            key=entry,
        )
    return int(key)


def _motif(name, star) -> Star:
    if isinstance(star, str):
        try:
            return Star.preset(star)
        except ParameterError as exc:
            raise ParameterError(str(exc), param=name.split("[")[0]) from None
    if not isinstance(star, Star):
        raise ParameterError(f"{name} must be a Star or a preset name, got {star!r}", param=name.split("[")[0])
    return star


# The schema names no module above it: the values and checks of its keys are registered from here.
register_check(TilingPacking, "packing.edge")
