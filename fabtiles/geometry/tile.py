"""A tile: an outline, a size, a frame and a pattern, turned into material (``docs/file-conventions.md``).

Coordinates are millimetres in *file coordinates*: the outline's bounding box has
its lower-left corner at (0, 0). The pattern's own frame (lattice point (0, 0) of a
packing, or the centre of a single motif) sits at the tile's centre.
"""

from __future__ import annotations

import math
import numbers

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from ..core.errors import ParameterError
from ..core.native import import_uninterrupted
from ..core.report import distinct
from ..core.schema import key, register_check
from ..core.validate import check_choice, check_float
from ..pattern.archimedean import ArchimedeanPacking
from ..pattern.frieze import check_frieze_motif
from ..pattern.girih import GirihPacking
from ..pattern.packing import Packing
from ..pattern.star import Star
from .border import Border, check_border, stubs
from .stroke import JOINS, clip_segments, stroke_cross_section, to_cross_section, to_shapely

OUTLINES: tuple[str, ...] = key("tile.outline").choice_values()
"""Valid tile outlines. ``hexagon`` is pointy-top, its size is the width across flats."""

TOLERANCE = 0.005
"""Largest chord error (mm) of flattened arcs: circles, round joins, rounded corners."""


def _segments_for(radius: float, sweep: float = 2 * math.pi, multiple: int = 1) -> int:
    """Chords needed on an arc of ``radius`` and ``sweep`` for sagitta <= TOLERANCE."""
    if radius <= TOLERANCE:
        return multiple
    step = 2.0 * math.acos(1.0 - TOLERANCE / radius)
    k = max(1, math.ceil(sweep / step))
    return multiple * math.ceil(k / multiple)


def outline_polygon(
    outline: str, width: float, height: float, corner_radius: float = 0.0, centre=(0.0, 0.0)
) -> Polygon:
    """The outline as a shapely Polygon centred at ``centre``.

    ``width``/``height`` are the bounding box of the outline (for a pointy-top
    hexagon: across flats and across corners). Rounded corners are the opening
    of the sharp outline by a disc of ``corner_radius``.

    >>> round(outline_polygon("hexagon", 10, 20 / math.sqrt(3)).area, 4)
    86.6025
    """
    cx, cy = centre
    if outline in ("square", "rectangle"):
        poly = shapely.box(cx - width / 2, cy - height / 2, cx + width / 2, cy + height / 2)
    elif outline == "hexagon":
        # Pointy-top: vertical sides at cx +- width/2, points at cy +- height/2 (exact).
        hw, hh = width / 2, height / 2
        poly = Polygon(
            [
                (cx + hw, cy - hh / 2),
                (cx + hw, cy + hh / 2),
                (cx, cy + hh),
                (cx - hw, cy + hh / 2),
                (cx - hw, cy - hh / 2),
                (cx, cy - hh),
            ]
        )
    else:  # circle
        k = _segments_for(width / 2, multiple=24)
        t = np.linspace(0.0, 2 * math.pi, k, endpoint=False)
        return Polygon(np.stack([cx + width / 2 * np.cos(t), cy + width / 2 * np.sin(t)], axis=1))
    if corner_radius > 0:
        quad = max(1, _segments_for(corner_radius, math.pi / 2))
        poly = poly.buffer(-corner_radius, join_style="mitre").buffer(corner_radius, quad_segs=quad, join_style="round")
    return shapely.geometry.polygon.orient(poly, 1.0)


class TileGeometry:
    """A tile of material: pattern centre-lines stroked, framed and clipped to an outline.

    Parameters
    ----------
    outline : {"square", "rectangle", "hexagon", "circle"}
        Shape of the tile. The hexagon is pointy-top.
    size : float or (float, float)
        mm. ``square``, ``hexagon`` (width across flats) and ``circle`` (diameter)
        take one number or an equal pair; ``rectangle`` takes ``(width, height)``.
    pattern : HexPacking, SquarePacking, ArchimedeanPacking, GirihPacking or Star
        A packing (its lattice point (0, 0) at the tile centre), or a single motif
        centred and scaled to the largest circle inside the frame.
    frame : float
        Width of the solid margin along the outline, mm (>= 0; 0 for seamless tiles).
    stroke : float
        Width of the band around each centre-line, mm (> 0, at most the packing
        radius, or the motif circle's radius for a single motif).
    join : {"miter", "round", "bevel"}
        How bands meet at vertices. Miter keeps star tips sharp.
    miter_limit : float
        Largest distance of a miter tip from its vertex, in half stroke widths (>= 1);
        beyond it the miter is cut square at that distance.
    corner_radius : float
        Radius of rounded outline corners, mm (0 for sharp; not for circles).
    interlace : bool
        Weave the strands over and under each other (``docs/tile-operation.md``, see
        :mod:`fabtiles.geometry.interlace`): the drawing, the score lines and
        the relief show it.
    interlace_gap_mm : float, optional
        Clearance each side of an over band, mm (>= 0; default a third of the stroke).
    interlace_cut : bool
        Laser, pierced: cut the under strands' gaps through too (tabs keep every
        piece joined).
    border_mm : float
        Width of a band just inside the frame filled with a frieze, mm (0: none; at
        most a third of the width inside the frame): see :mod:`fabtiles.geometry.border`.
        The field (the pattern) fills the inside of the band, and a line of the stroke
        parts the two.
    border_motif : {"stars", "hankin"}
        The frieze's motif (:mod:`fabtiles.pattern.frieze`).
    border_angle : float
        The hankin frieze's contact angle, degrees (0 to 90, open).

    Examples
    --------
    >>> from fabtiles.pattern.packing import HexPacking
    >>> pack = HexPacking(radius=12.5, motif=Star.preset("table3-3"))
    >>> tile = TileGeometry("square", 60, pack, frame=3, stroke=0.8)
    >>> tile.width_mm, tile.height_mm
    (60.0, 60.0)
    >>> tile.region().is_valid, tile.outline_shape().bounds
    (True, (0.0, 0.0, 60.0, 60.0))
    >>> TileGeometry("square", 60, pack, join="zigzag")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: 'zigzag' is not a valid join, must be one of: miter, round, bevel
    """

    def __init__(
        self,
        outline,
        size,
        pattern,
        *,
        frame=0.0,
        stroke=1.0,
        join="miter",
        miter_limit=4.0,
        corner_radius=0.0,
        interlace=False,
        interlace_gap_mm=None,
        interlace_cut=False,
        border_mm=0.0,
        border_motif="stars",
        border_angle=67.5,
    ):
        self._outline = check_choice("outline", outline, OUTLINES)
        self._size = check_tile_size(self._outline, size)
        if not isinstance(pattern, (Packing, ArchimedeanPacking, GirihPacking, Star)):
            raise ParameterError(
                f"pattern must be a HexPacking, SquarePacking, ArchimedeanPacking, GirihPacking or Star, "
                f"got {type(pattern).__name__}",
                param="pattern",
            )
        self._pattern = pattern
        self._frame = check_float("frame", frame, low=0)
        self._stroke = check_float("stroke", stroke, low=0, low_open=True)
        self._join = check_choice("join", join, JOINS)
        self._miter_limit = check_float("miter_limit", miter_limit, low=1)
        self._corner_radius = check_float("corner_radius", corner_radius, low=0)
        w = self._size[0]
        self._width = w
        self._height = 2 * w / math.sqrt(3) if self._outline == "hexagon" else self._size[1]
        across = min(self._size)  # the narrowest width across the outline
        if across <= 2 * self._frame:
            raise ParameterError(
                f"tile size {_fmt_size(self._size)} mm is too small for frame {self._frame:g} mm: "
                f"the {self._outline} must be wider than twice the frame ({2 * self._frame:g} mm)",
                param="frame",
            )
        if self._corner_radius > 0:
            if self._outline == "circle":
                raise ParameterError(
                    f"corner_radius must be 0 for a circle outline, got {self._corner_radius:g}", param="corner_radius"
                )
            if self._corner_radius > across / 2:
                raise ParameterError(
                    f"corner_radius must be >= 0 and <= {across / 2:g} (half the tile's "
                    f"narrowest width), got {self._corner_radius:g}",
                    param="corner_radius",
                )
        self._border_mm = check_float("border_mm", border_mm, low=0)
        self._border_motif = check_frieze_motif(border_motif)
        self._border_angle = check_float("border_angle", border_angle, low=0, high=90, low_open=True, high_open=True)
        self._border = self._checked_border()
        limit, what = (
            (self.motif_radius, "the motif circle's radius")
            if isinstance(pattern, Star)
            else (pattern.radius, "the packing radius")
        )
        if self._stroke > limit:
            raise ParameterError(
                f"stroke must be > 0 and <= {limit:g} mm ({what}), got {distinct(self._stroke, limit)}", param="stroke"
            )
        self._interlace = _check_bool("interlace", interlace)
        self._interlace_cut = _check_bool("interlace_cut", interlace_cut)
        self._interlace_gap = (
            None if interlace_gap_mm is None else check_float("interlace_gap_mm", interlace_gap_mm, low=0)
        )
        self._segments = None
        self._woven = 0
        self._region = None
        self._centrelines = None
        self._weave = None

    # -- parameters ---------------------------------------------------------
    outline = property(lambda self: self._outline, doc="Outline name.")
    size = property(lambda self: self._size, doc="Size as given, normalised to a float pair.")
    pattern = property(lambda self: self._pattern, doc="The packing or single Star.")
    frame = property(lambda self: self._frame, doc="Frame width, mm.")
    stroke = property(lambda self: self._stroke, doc="Stroke width, mm.")
    join = property(lambda self: self._join, doc="Join style.")
    miter_limit = property(lambda self: self._miter_limit, doc="Miter limit, half stroke widths.")
    corner_radius = property(lambda self: self._corner_radius, doc="Corner radius, mm.")
    width_mm = property(lambda self: self._width, doc="Width of the outline's bounding box, mm.")
    height_mm = property(lambda self: self._height, doc="Height of the outline's bounding box, mm.")

    def params(self) -> dict:
        """The constructor arguments, so ``TileGeometry(**tile.params())`` rebuilds the tile."""
        return dict(
            outline=self._outline,
            size=self._size,
            pattern=self._pattern,
            frame=self._frame,
            stroke=self._stroke,
            join=self._join,
            miter_limit=self._miter_limit,
            corner_radius=self._corner_radius,
            interlace=self._interlace,
            interlace_gap_mm=self._interlace_gap,
            interlace_cut=self._interlace_cut,
            border_mm=self._border_mm,
            border_motif=self._border_motif,
            border_angle=self._border_angle,
        )

    interlace = property(lambda self: self._interlace, doc="Whether the strands are woven.")
    border_mm = property(lambda self: self._border_mm, doc="Width of the border's band, mm (0: none).")
    border_motif = property(lambda self: self._border_motif, doc="The border frieze's motif.")
    border_angle = property(lambda self: self._border_angle, doc="The hankin frieze's contact angle, degrees.")

    def _checked_border(self) -> Border | None:
        """The border, its width checked against the tile and the stroke; None without one."""
        if self._border_mm == 0:
            return None
        if self._corner_radius > self._frame:
            raise ParameterError(
                f"corner_radius must be <= the frame ({self._frame:g} mm) with a border (the band turns square "
                f"corners inside the frame), got {self._corner_radius:g}",
                param="corner_radius",
            )
        border = Border(
            self._outline,
            self._size,
            self._frame,
            self._border_mm,
            self._border_motif,
            self._border_angle,
            self.centre,
        )
        check_border(border, self._stroke)
        return border

    def border(self) -> Border | None:
        """The border (:class:`~fabtiles.geometry.border.Border`: its fit, cells and frieze), or None."""
        return self._border

    def border_segments(self) -> np.ndarray:
        """The border's centre-lines ``(k, 2, 2)``, file coordinates: the frieze and the line between the
        band and the field (empty without a border)."""
        if self._border is None:
            return np.empty((0, 2, 2))
        ring = np.asarray(self.field_shape().exterior.coords)
        return np.concatenate([self._border.frieze(TOLERANCE), np.stack([ring[:-1], ring[1:]], axis=1)])

    interlace_cut = property(lambda self: self._interlace_cut, doc="Cut the under gaps (laser, pierced).")

    @property
    def interlace_gap_mm(self) -> float:
        """Clearance each side of an over band, mm: as given, else a third of the stroke."""
        return self._stroke / 3 if self._interlace_gap is None else self._interlace_gap

    def weave(self):
        """The strands and their over/under (:class:`fabtiles.pattern.interlace.Weave`), cached.

        Woven are the motifs' centre-lines, in file coordinates (outline circles
        kiss each other at every tangency and are not woven). Raises
        :class:`~fabtiles.ParameterError` when ``interlace_gap_mm`` is so large
        that an under strand's gap reaches the next crossing along it.
        """
        if self._weave is None:
            from .interlace import checked_weave

            self._weave = checked_weave(self)
        return self._weave

    def replace(self, **changes) -> TileGeometry:
        """A copy (of the same class) with some parameters changed, validated again.

        >>> t = TileGeometry("circle", 50, Star.preset("table2-left"), frame=2)
        >>> t.replace(size=80).width_mm
        80.0
        """
        return type(self)(**{**self.params(), **changes})

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}({self._outline!r}, {_fmt_size(self._size)}, {self._pattern!r}, "
            f"frame={self._frame:g}, stroke={self._stroke:g}, join={self._join!r})"
        )

    @property
    def centre(self) -> tuple[float, float]:
        """Centre of the tile (the pattern's origin) in file coordinates."""
        return (self._width / 2, self._height / 2)

    @property
    def motif_radius(self) -> float:
        """Radius of the circle a single motif fills: the inscribed circle inside the frame (and the border)."""
        return min(self._size) / 2 - self._frame - self._border_mm

    # -- geometry -------------------------------------------------------------
    def outline_shape(self) -> Polygon:
        """The outline as a shapely Polygon in file coordinates (bbox lower-left at (0, 0))."""
        return outline_polygon(self._outline, self._width, self._height, self._corner_radius, self.centre)

    def inner_shape(self) -> Polygon:
        """The outline inset by the frame (the patterned area), file coordinates."""
        f = self._frame
        if f == 0:
            return self.outline_shape()
        if self._outline == "hexagon":
            w = self._width - 2 * f
            wh = (w, 2 * w / math.sqrt(3))
        else:
            wh = (self._width - 2 * f, self._height - 2 * f)
        return outline_polygon(self._outline, *wh, max(0.0, self._corner_radius - f), self.centre)

    def field_shape(self) -> Polygon:
        """Where the pattern lies: inside the frame, and inside the border's band if there is one."""
        if self._border_mm == 0:
            return self.inner_shape()
        inset = self._frame + self._border_mm
        w = self._width - 2 * inset
        h = 2 * w / math.sqrt(3) if self._outline == "hexagon" else self._height - 2 * inset
        return outline_polygon(self._outline, w, h, 0.0, self.centre)

    def segments(self) -> np.ndarray:
        """Centre-lines ``(k, 2, 2)`` in file coordinates (mm), before clipping.

        For a packing: every motif whose circle reaches the outline's bounding box
        (grown by half the stroke), so the segments cover the whole outline. With a
        border, the field's centre-lines clipped to :meth:`field_shape`, then the
        border's (:meth:`border_segments`), then the field's outline circles, if any.
        """
        if self._segments is None:
            cx, cy = self.centre
            if isinstance(self._pattern, Star):
                star = self._pattern
                seg = star.segments() * (self.motif_radius / star.extent)
            else:
                seg = self._pattern.segments(self._window())
            seg = seg + np.array([cx, cy])
            if self._border is not None:
                motifs = self._field_motifs()
                field = self.field_shape()
                clipped = clip_segments(motifs, field)
                stub = stubs(clipped, 4 * self._stroke)
                frieze = self._border.frieze(TOLERANCE)
                # the woven lines first (the field's and the frieze's), then the stubs, the line and the circles
                self._woven = int(np.count_nonzero(~stub)) + len(frieze)
                seg = np.concatenate(
                    [clipped[~stub], frieze, clipped[stub], self.border_segments()[len(frieze) :]]
                    + [clip_segments(seg[len(motifs) :], field)] * (len(seg) > len(motifs))
                )
            self._segments = seg
        return self._segments.copy()

    def _field_motifs(self) -> np.ndarray:
        """The field's motifs' centre-lines (not its outline circles), unclipped, file coordinates."""
        if isinstance(self._pattern, Star) or not getattr(self._pattern, "outline_circles", False):
            if self._border is None:
                return self.segments()
            star_or_packing = self._pattern
            seg = (
                star_or_packing.segments() * (self.motif_radius / star_or_packing.extent)
                if isinstance(star_or_packing, Star)
                else star_or_packing.segments(self._window())
            )
            return seg + np.array(self.centre)
        return self._pattern.motif_segments(self._window()) + np.array(self.centre)

    def motif_segments(self) -> np.ndarray:
        """The motifs' centre-lines alone (without a packing's outline circles), file coordinates;
        with a border, the field's clipped to :meth:`field_shape` and the frieze's (the line between
        them is, like the outline circles, no strand of an interlace: the lines end on it).

        >>> from fabtiles.pattern.packing import HexPacking
        >>> t = TileGeometry("square", 40, HexPacking(10, Star.preset("table3-3"), outline_circles=True))
        >>> len(t.motif_segments()) < len(t.segments())
        True
        """
        if self._border is None:
            return self._field_motifs()
        return self.segments()[: self._woven]

    def _window(self) -> tuple[float, float, float, float]:
        """The outline's bounding box grown by the farthest a band reaches past its centre-lines
        (half the stroke; a miter tip up to ``miter_limit`` half strokes), pattern coordinates.

        Growing by half the stroke alone missed miter tips of motifs just outside the
        tile poking in: 0.005 mm^2 specks along the edges of a seamless 3.3.4.3.4 tile.
        """
        reach = self._miter_limit if self._join == "miter" else 1.0
        cx, cy, h = *self.centre, self._stroke / 2 * reach
        return (-cx - h, -cy - h, cx + h, cy + h)

    def region(self) -> Polygon | MultiPolygon:
        """The material: union of the stroked bands and the frame, clipped to the outline.

        A valid shapely Polygon or MultiPolygon in file coordinates, computed once
        and cached (see :mod:`fabtiles.geometry.stroke` for how and why).
        """
        if self._region is None:
            m3d = import_uninterrupted("manifold3d")

            if isinstance(self._pattern, Star) or not self._pattern.outline_circles:
                segments, circles = self._field_motifs(), None
            else:  # the circles as exact annuli, the motifs as bands (see stroke_cross_section)
                centre = np.array(self.centre)
                segments = self._pattern.motif_segments(self._window()) + centre
                centres, radii = self._pattern.circles(self._window())
                circles = (centres + centre, radii)
            bands = stroke_cross_section(
                segments,
                self._stroke,
                join=self._join,
                miter_limit=self._miter_limit,
                tolerance=TOLERANCE,
                circles=circles,
            )
            outline = self.outline_shape()
            if self._border is not None:  # the field inside the band, the band's lines stroked on their own
                field = to_cross_section(self.field_shape())
                bands = m3d.CrossSection.batch_boolean([bands, field], m3d.OpType.Intersect)
                border = stroke_cross_section(
                    self.border_segments(),
                    self._stroke,
                    join=self._join,
                    miter_limit=self._miter_limit,
                    tolerance=TOLERANCE,
                )
                bands = m3d.CrossSection.batch_boolean([bands, border], m3d.OpType.Add)
            parts = [bands]
            if self._frame > 0:
                parts.append(to_cross_section(outline.difference(self.inner_shape())))
            material = m3d.CrossSection.batch_boolean(parts, m3d.OpType.Add) if len(parts) > 1 else bands
            clipped = m3d.CrossSection.batch_boolean([material, to_cross_section(outline)], m3d.OpType.Intersect)
            self._region = to_shapely(clipped)
        return self._region

    def centrelines(self) -> np.ndarray:
        """Centre-lines clipped to the outline, ``(k, 2, 2)`` float array in file coordinates.

        For the laser "score" mode. Every outline is convex, so each segment clips
        to at most one segment; pieces of zero length are dropped, endpoints closer
        than 1e-6 mm are merged and duplicate segments (shared by two motifs) kept once.
        """
        if self._centrelines is None:
            self._centrelines = clip_segments(self.segments(), self.outline_shape())
        return self._centrelines.copy()


def _check_bool(name: str, value) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise ParameterError(f"{name} must be True or False, got {value!r}", param=name)
    return bool(value)


def _fmt_size(size) -> str:
    return f"({size[0]:g}, {size[1]:g})"


def check_tile_size(outline: str, size) -> tuple[float, float]:
    if isinstance(size, numbers.Real) and not isinstance(size, bool):
        if outline == "rectangle":
            raise ParameterError(
                f"size of a rectangle must be a pair (width, height) in mm, got {size!r}", param="size"
            )
        s = check_float("size", size, low=0, low_open=True)
        return (s, s)
    try:
        pair = list(size)
    except TypeError:
        raise ParameterError(
            f"size must be a number or a (width, height) pair in mm, got {size!r}", param="size"
        ) from None
    if len(pair) != 2:
        raise ParameterError(f"size must be a number or a (width, height) pair in mm, got {size!r}", param="size")
    w = check_float("size[0]", pair[0], low=0, low_open=True)
    h = check_float("size[1]", pair[1], low=0, low_open=True)
    if outline != "rectangle" and w != h:
        what = {"square": "side", "hexagon": "width across flats", "circle": "diameter"}[outline]
        raise ParameterError(
            f"size of a {outline} is one number (its {what}) or an equal pair, got ({w:g}, {h:g}); "
            f"use outline 'rectangle' for unequal sides"
            if outline == "square"
            else f"size of a {outline} is one number (its {what}) or an equal pair, got ({w:g}, {h:g})",
            param="size",
        )
    return (w, h)


# The schema names no module above it: the values and checks of its keys are registered from here.
register_check(check_tile_size, "tile.size")
register_check(
    TileGeometry,
    "tile.frame",
    "tile.stroke",
    "tile.miter_limit",
    "tile.corner_radius",
    "tile.interlace_gap_mm",
    "tile.border_mm",
    "tile.border_angle",
)
