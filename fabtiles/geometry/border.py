"""A border: a band just inside a tile's frame, filled with a frieze (``docs/borders.md``).

The band, ``band_mm`` wide, runs along the outline inside the frame; the field (the
packing) fills what it leaves. The band is cut across into cells, each holding one
repeat of the frieze's motif (:mod:`fabtiles.pattern.frieze`, drawn in the square
``[-1, 1]^2`` and mapped onto the cell), a whole number of them on each side:

- square and rectangle: a ``band x band`` square cell at each corner, and each side's
  length between them cut into ``n`` cells as near square as a whole number allows;
- hexagon: each side's band, between its two corners' bisectors, cut into ``n`` cells
  of equal length along the band's centre-line (the two end cells meet the next side's
  on the bisector);
- circle: ``n`` annular sectors of equal length along the band's centre-line.

A cell's map sends each edge of the unit square linearly onto the cell's edge, so
cells sharing an edge meet at the same points and the strands run on across it; where
the map bends lines (a trapezoid's, a sector's) each segment is cut into pieces
within the tiles' chord tolerance.

>>> fit = border_fit("rectangle", (100.0, 80.0), 12.0, frame=3.0)
>>> fit.repeats, [round(c, 3) for c in fit.cell_mm]
((6, 4), [11.667, 12.5])
>>> print(fit.line("stars"))
tile.border_mm: 6 x 4 repeats of 11.67 x 12.5 mm, a 12 mm square cell at each corner (band 12 mm, stars)
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.ops import polylabel

from ..core.errors import ParameterError
from ..core.graph import components
from ..pattern.frieze import frieze_cell
from .stroke import segment_graph

_SQRT3 = math.sqrt(3.0)


@dataclass(frozen=True)
class BorderFit:
    """How a band is cut into cells: ``repeats`` per side (a rectangle's along its width, then its
    height; one number for the others) and each one's cell length ``cell_mm`` (on the band's
    centre-line for a hexagon and a circle), the band's width ``band_mm`` and each side's length
    ``side_mm`` (inside the frame; a hexagon's and a circle's on the band's centre-line)."""

    outline: str
    band_mm: float
    repeats: tuple[int, ...]
    cell_mm: tuple[float, ...]
    side_mm: tuple[float, ...]

    def line(self, motif: str, angle: float | None = None) -> str:
        """The fit in a sentence, as the build reports it."""
        what = f"band {self.band_mm:g} mm, {motif}" + (f" at {angle:g} degrees" if angle is not None else "")
        n, c = self.repeats, self.cell_mm
        if self.outline in ("square", "rectangle"):
            return (
                f"tile.border_mm: {n[0]} x {n[1]} repeats of {c[0]:.4g} x {c[1]:.4g} mm, "
                f"a {self.band_mm:g} mm square cell at each corner ({what})"
            )
        if self.outline == "hexagon":
            return f"tile.border_mm: 6 sides x {n[0]} repeats of {c[0]:.4g} mm on the band's centre-line ({what})"
        return f"tile.border_mm: {n[0]} repeats of {c[0]:.4g} mm round the band's centre-line ({what})"


def _whole(length: float, band: float) -> int:
    """The whole number of cells in ``length`` whose length is nearest ``band`` (at least one)."""
    low = max(1, math.floor(length / band))
    return min((low, low + 1), key=lambda n: (abs(length / n - band), -n))


def border_fit(outline: str, size: tuple[float, float], band_mm: float, *, frame: float = 0.0) -> BorderFit:
    """The cells of a ``band_mm`` band inside the frame of an ``outline`` of ``size`` (see the module)."""
    w, h = size[0] - 2 * frame, size[1] - 2 * frame
    if outline in ("square", "rectangle"):
        sides = (w - 2 * band_mm, h - 2 * band_mm)
    elif outline == "hexagon":
        sides = ((w - band_mm) / _SQRT3,)  # the side of the centre-line's hexagon, across flats w - band
    else:
        sides = (math.pi * (w - band_mm),)
    repeats = tuple(_whole(s, band_mm) for s in sides)
    return BorderFit(outline, band_mm, repeats, tuple(s / n for s, n in zip(sides, repeats, strict=True)), sides)


# -- the cells ------------------------------------------------------------------------------------
def _rectangle_cells(x0: float, y0: float, x1: float, y1: float, fit: BorderFit) -> np.ndarray:
    """The cells ``(k, 4, 2)`` of a rectangle's band, each ``[(-1,-1), (1,-1), (1,1), (-1,1)]``'s image."""
    b = fit.band_mm
    boxes = [(x0, y0, x0 + b, y0 + b), (x1 - b, y0, x1, y0 + b), (x1 - b, y1 - b, x1, y1), (x0, y1 - b, x0 + b, y1)]
    for j in range(fit.repeats[0]):
        xa = x0 + b + j * fit.cell_mm[0]
        boxes += [(xa, y0, xa + fit.cell_mm[0], y0 + b), (xa, y1 - b, xa + fit.cell_mm[0], y1)]
    for j in range(fit.repeats[1]):
        ya = y0 + b + j * fit.cell_mm[1]
        boxes += [(x0, ya, x0 + b, ya + fit.cell_mm[1]), (x1 - b, ya, x1, ya + fit.cell_mm[1])]
    a = np.array(boxes)
    return np.stack([a[:, [0, 1]], a[:, [2, 1]], a[:, [2, 3]], a[:, [0, 3]]], axis=1)


def _polygon_cells(outer: np.ndarray, inner: np.ndarray, band: float, n: int) -> np.ndarray:
    """The cells ``(k, 4, 2)`` of the ``band`` wide band between a convex polygon ``outer`` and ``inner``
    (its corners moved in along their bisectors, in the same order): ``n`` to a side, cut across
    square to the side at equal steps of the centre-line, the end cells on the bisectors."""
    cells = []
    for i in range(len(outer)):
        o0, o1, i0, i1 = outer[i], outer[(i + 1) % len(outer)], inner[i], inner[(i + 1) % len(inner)]
        m0, m1 = (o0 + i0) / 2, (o1 + i1) / 2
        d = (m1 - m0) / np.linalg.norm(m1 - m0)
        normal = np.array([d[1], -d[0]])
        if np.dot(normal, o0 - i0) < 0:  # the normal points out, from the field to the frame
            normal = -normal
        mids = m0 + np.linspace(0.0, 1.0, n + 1)[:, None] * (m1 - m0)
        ins, outs = mids - normal * band / 2, mids + normal * band / 2
        ins[0], outs[0], ins[-1], outs[-1] = i0, o0, i1, o1
        cells += [np.stack([ins[j], ins[j + 1], outs[j + 1], outs[j]]) for j in range(n)]
    return np.array(cells)


def _map_quads(seg: np.ndarray, quads: np.ndarray, pieces: np.ndarray) -> np.ndarray:
    """The unit cell's segments mapped bilinearly onto each quad, each cut into its quad's ``pieces``."""
    out = []
    for quad, k in zip(quads, pieces, strict=True):
        pts = _split(seg, int(k))
        s, t = (pts[..., 0] + 1) / 2, (pts[..., 1] + 1) / 2
        p = (
            ((1 - s) * (1 - t))[..., None] * quad[0]
            + (s * (1 - t))[..., None] * quad[1]
            + (s * t)[..., None] * quad[2]
            + ((1 - s) * t)[..., None] * quad[3]
        )
        out.append(p)
    return np.concatenate(out) if out else np.empty((0, 2, 2))


def _split(seg: np.ndarray, k: int) -> np.ndarray:
    """Each segment cut into ``k`` equal pieces, ``(len * k, 2, 2)``."""
    if k <= 1:
        return seg
    f = np.linspace(0.0, 1.0, k + 1)
    pts = seg[:, None, 0] + f[None, :, None] * (seg[:, None, 1] - seg[:, None, 0])
    return np.stack([pts[:, :-1], pts[:, 1:]], axis=2).reshape(-1, 2, 2)


def _quad_pieces(seg: np.ndarray, quads: np.ndarray, tolerance: float) -> np.ndarray:
    """How many pieces each quad's segments need: the bilinear map bends a segment spanning ``ds`` and
    ``dt`` of the unit cell (each 0 to 1) by ``|twist| ds dt / 4`` at its middle, a quarter of that for
    each halving."""
    twist = quads[:, 0] - quads[:, 1] + quads[:, 2] - quads[:, 3]
    span = float(np.max(np.abs(np.prod(seg[:, 1] - seg[:, 0], axis=1)))) / 4 if len(seg) else 0.0
    bend = np.linalg.norm(twist, axis=1) * span / 4
    return np.maximum(1, np.ceil(np.sqrt(bend / tolerance))).astype(int)


def _sectors(seg: np.ndarray, centre, r_in: float, band: float, n: int, tolerance: float) -> np.ndarray:
    """The unit cell's segments on ``n`` annular sectors from ``r_in`` to ``r_in + band`` (cell 0 centred
    on the +x axis), each cut into pieces that follow the arcs within ``tolerance``."""
    step = 2 * math.pi / n
    k = max(1, math.ceil(step * math.sqrt((r_in + band) / (8 * tolerance))))
    pts = _split(seg, k)
    s, t = (pts[..., 0] + 1) / 2, (pts[..., 1] + 1) / 2
    angle = (np.arange(n)[:, None, None] - 0.5 + s[None]) * step
    radius = r_in + t[None] * band
    xy = np.stack([centre[0] + radius * np.cos(angle), centre[1] + radius * np.sin(angle)], axis=-1)
    return xy.reshape(-1, 2, 2)


def _sector_quads(centre, r_in: float, band: float, n: int) -> np.ndarray:
    """The corners ``(n, 4, 2)`` of the sectors (their edges' chords), for measuring them."""
    step = 2 * math.pi / n
    a = (np.arange(n) - 0.5) * step
    corners = []
    for r, da in ((r_in, 0.0), (r_in, step), (r_in + band, step), (r_in + band, 0.0)):
        corners.append(np.stack([centre[0] + r * np.cos(a + da), centre[1] + r * np.sin(a + da)], axis=1))
    return np.stack(corners, axis=1)


@dataclass(frozen=True)
class Border:
    """A tile's border: the band inside ``outer`` (the outline inside the frame, file coordinates),
    its frieze and the line between band and field.

    ``outline`` and ``size`` are the tile's, ``frame`` its frame; ``motif`` and ``angle`` the frieze's.
    """

    outline: str
    size: tuple[float, float]
    frame: float
    band_mm: float
    motif: str
    angle: float
    centre: tuple[float, float]

    @functools.cached_property
    def fit(self) -> BorderFit:
        """How the band is cut into cells."""
        return border_fit(self.outline, self.size, self.band_mm, frame=self.frame)

    def _outer(self) -> np.ndarray:
        """A hexagon's corners inside the frame, counter-clockwise from the lower right."""
        cx, cy = self.centre
        hw = (self.size[0] - 2 * self.frame) / 2
        hh = hw * 2 / _SQRT3
        return np.array(
            [(cx + hw, cy - hh / 2), (cx + hw, cy + hh / 2), (cx, cy + hh), (cx - hw, cy + hh / 2)]
            + [(cx - hw, cy - hh / 2), (cx, cy - hh)]
        )

    def cells(self) -> np.ndarray:
        """The cells' corners ``(k, 4, 2)``: inner-start, inner-end, outer-end, outer-start (a rectangle's
        cells as boxes); a circle's sectors by their edges' chords."""
        cx, cy = self.centre
        b, f = self.band_mm, self.fit
        if self.outline in ("square", "rectangle"):
            w, h = self.size[0] / 2 - self.frame, self.size[1] / 2 - self.frame
            return _rectangle_cells(cx - w, cy - h, cx + w, cy + h, f)
        if self.outline == "hexagon":
            outer = self._outer()
            scale = 1 - 2 * b / (self.size[0] - 2 * self.frame)
            inner = np.array(self.centre) + (outer - np.array(self.centre)) * scale
            return _polygon_cells(outer, inner, b, f.repeats[0])
        r_out = self.size[0] / 2 - self.frame
        return _sector_quads(self.centre, r_out - b, b, f.repeats[0])

    def frieze(self, tolerance: float = 0.005) -> np.ndarray:
        """The frieze's centre-lines ``(k, 2, 2)``, file coordinates."""
        seg = frieze_cell(self.motif, self.angle)
        if self.outline == "circle":
            r_out = self.size[0] / 2 - self.frame
            return _sectors(seg, self.centre, r_out - self.band_mm, self.band_mm, self.fit.repeats[0], tolerance)
        quads = self.cells()
        return _map_quads(seg, quads, _quad_pieces(seg, quads, tolerance))

    def smallest_cell_mm(self) -> float:
        """The shortest edge of any cell, mm."""
        q = self.cells()
        return float(np.linalg.norm(q - np.roll(q, -1, axis=1), axis=2).min())


def stubs(segments: np.ndarray, shortest: float) -> np.ndarray:
    """Which of the field's clipped centre-lines belong to a piece of pattern (lines joined end to end)
    shorter than ``shortest`` in all: the tips of motifs just reaching past the band's line, a mask.

    An interlace leaves them unwoven: crossing a strand, such a stub would be all gap.

    >>> seg = np.array([[[0, 0], [1, 0]], [[1, 0], [1, 1]], [[5, 5], [9, 5]]], float)
    >>> stubs(seg, 3.0).tolist()
    [True, True, False]
    """
    if not len(segments):
        return np.zeros(0, bool)
    _, _, ids = segment_graph(segments, return_ids=True)
    label = components(int(ids.max()) + 1, ids[:, 0], ids[:, 1])[ids[:, 0]]
    length = np.linalg.norm(segments[:, 1] - segments[:, 0], axis=1)
    total = np.bincount(label, weights=length)
    return total[label] < shortest


@functools.lru_cache(maxsize=64)
def opening_ratio(motif: str, angle: float) -> float:
    """The radius of the smallest opening of the motif in a cell of side 1 (the largest circle in its
    narrowest face): a stroke as wide as the cell's side times twice this closes it."""
    seg = frieze_cell(motif, angle)
    square = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)], dtype=float)
    edges = np.stack([square, np.roll(square, -1, axis=0)], axis=1)
    lines = shapely.unary_union(shapely.linestrings(np.concatenate([seg, edges])))
    faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(lines)))
    radii = [f.boundary.distance(polylabel(f, tolerance=1e-4)) for f in faces if f.area > 1e-9]
    return min(radii) / 2  # the unit cell is 2 wide


def check_border(border: Border, stroke: float) -> None:
    """``border.band_mm`` checked against the tile (a third of its width inside the frame at most)
    and the stroke (every cell wide enough to keep its openings). Raises ParameterError."""
    inside = min(border.size) - 2 * border.frame
    limit = inside / 3
    b = border.band_mm
    if b > limit:
        raise ParameterError(
            f"border_mm must be >= 0 and <= {limit:.4g} mm (a third of the {inside:g} mm across the "
            f"{border.outline} inside its frame), got {b:g}",
            param="border_mm",
        )
    ratio = opening_ratio(border.motif, border.angle)
    need = stroke / (2 * ratio)  # the narrowest cell whose openings stay open at this stroke
    if border.smallest_cell_mm() >= need:
        return
    low = next(
        (
            x
            for x in np.arange(math.ceil(need * 100) / 100, limit + 1e-9, 0.01)
            if _replace(border, float(x)).smallest_cell_mm() >= need
        ),
        None,
    )
    thinner = 2 * ratio * border.smallest_cell_mm()
    what = f"the {border.motif} frieze's openings close at stroke {stroke:g} mm in cells under {need:.3g} mm"
    if low is None:
        raise ParameterError(
            f"border_mm = {b:g} mm is too narrow: {what}, and no band up to {limit:.4g} mm (a third of the "
            f"width inside the frame) is wide enough; make the stroke <= {thinner:.3g} mm",
            param="border_mm",
        )
    raise ParameterError(
        f"border_mm must be >= {low:.4g} mm at this stroke ({what}), got {b:g}; or make the stroke <= {thinner:.3g} mm",
        param="border_mm",
    )


def _replace(border: Border, band_mm: float) -> Border:
    from dataclasses import replace

    return replace(border, band_mm=band_mm)
