"""A laser test card: measure a profile's ``min_feature_mm``, ``min_hole_mm``, ``kerf_mm`` and inlay fit.

Four rows on a card of at most 120 x 120 mm, each feature labelled with its
nominal size in single-stroke text (:mod:`fabtiles.geometry.stroke_font`, for the
score layer):

``B`` bridges
    Slots side by side; the material between two slots is a bridge, its width
    stepping around ``min_feature_mm`` (x 0.5 ... 2). The narrowest bridge that
    comes out whole and stiff is the material's ``min_feature_mm``.
``H`` holes
    Round holes, their diameters stepping around ``min_hole_mm``. The smallest
    hole that comes out open and clean is ``min_hole_mm``.
``K`` kerf
    A 20 mm square part (cut free inside a window) and a 20 mm square hole, both
    kerf-compensated with the profile's ``kerf_mm`` (printed on the right; with
    ``kerf_x_mm`` and ``kerf_y_mm`` that differ, the X kerf above the Y kerf). With the
    right kerf both measure 20.00 mm and the part fits the hole without play. Measured
    along X, a part ``P_x`` and a hole ``H_x`` (calipers) give the real kerf along X,
    ``kerf_x_mm + (H_x - P_x) / 2``; along Y likewise ``kerf_y_mm + (H_y - P_y) / 2``.

``I`` inlay fit
    The same 6 mm square hole in every column and, under it, a piece cut free in a
    window: the square grown by the fit written below it, stepping around the
    profile's ``inlay_fit_mm`` (-0.1 to +0.1 mm). The piece that presses into a hole
    snugly, without dishing the surface, is the material's ``inlay_fit_mm``.

The card is geometry like a tile's: the material region (the part is a second
piece inside the window), the outline, and the labels as open polylines.

>>> card = calibration_card("laser-3mm-plywood")
>>> [f.label for f in card.features if f.kind == "bridge"]
['0.5', '0.75', '1', '1.25', '1.5', '2']
>>> card.width_mm <= 120 and card.height_mm <= 120
True
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import shapely
from shapely.geometry import Point, box

from ..core.errors import ParameterError
from ..core.schema import key
from ..machines.profiles import load_profile
from .inlay import piece_of_hole
from .stroke_font import text_paths, text_width

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry

STEPS = (0.5, 0.75, 1.0, 1.25, 1.5, 2.0)
"""Feature sizes as multiples of the profile's limit."""
KERF_SQUARE_MM = 20.0
"""Side of the kerf gauge's square part and square hole."""
MAX_CARD_MM = 120.0
LABEL_MM = 2.0
"""Height of the size labels."""
LETTER_MM = 3.0
"""Height of the row letters B, H, K."""
MARGIN_MM = 5.0
SLOT_MM = (8.0, 12.0)
"""Width and height of the slots either side of a bridge."""
CLEARANCE_MM = 3.0
"""Space around the kerf gauge's part inside its window."""
INLAY_MM = 6.0
"""Side of the inlay gauge's square hole; its pieces are that square grown by each fit."""
INLAY_STEPS_MM = (-0.1, -0.05, 0.0, 0.05, 0.1)
"""The inlay gauge's fits, added to the profile's ``inlay_fit_mm`` (and kept within its range, -0.5 to 0.5 mm)."""
FIT = key("output.inlay_fit_mm")


def inlay_fits(profile) -> tuple[float, ...]:
    """The fits the card's inlay gauge steps through, around the profile's ``inlay_fit_mm``.

    >>> inlay_fits(load_profile("laser-3mm-plywood"))
    (0.05, 0.1, 0.15, 0.2, 0.25)
    """
    fits = (
        round(
            FIT.bounds.clamp(profile.inlay_fit_mm + d),
            3,
        )
        for d in INLAY_STEPS_MM
    )
    return tuple(dict.fromkeys(fits))


@dataclass(frozen=True)
class Feature:
    """One measured feature of the card: its kind, nominal size (mm), label and centre."""

    kind: str  # "bridge", "hole", "kerf_part", "kerf_hole", "inlay_piece", "inlay_hole"
    size_mm: float
    label: str
    at: tuple[float, float]


@dataclass(frozen=True)
class Card:
    """The test card: material region, outline, score labels (open polylines), features."""

    region: BaseGeometry
    outline: BaseGeometry
    labels: tuple
    features: tuple[Feature, ...]
    kerf_mm: float

    @property
    def width_mm(self) -> float:
        return float(self.outline.bounds[2] - self.outline.bounds[0])

    @property
    def height_mm(self) -> float:
        return float(self.outline.bounds[3] - self.outline.bounds[1])


def step_sizes(limit_mm: float, *, smallest_mm: float = 0.1) -> tuple[float, ...]:
    """Sizes stepping around ``limit_mm`` (x :data:`STEPS`), rounded to 0.05 mm, at least ``smallest_mm``.

    >>> step_sizes(1.2)
    (0.6, 0.9, 1.2, 1.5, 1.8, 2.4)
    """
    sizes = (max(smallest_mm, round(limit_mm * f / 0.05) * 0.05) for f in STEPS)
    return tuple(sorted({round(s, 2) for s in sizes}))


def _label(value: float) -> str:
    return f"{value:g}"


def calibration_card(profile) -> Card:
    """The test card of a laser profile (see the module text).

    Raises :class:`~fabtiles.ParameterError` when the profile's limits are so large
    that the card would exceed :data:`MAX_CARD_MM`.
    """
    profile = load_profile(profile, kind="laser")
    kerf = profile.kerf_mm
    bridges = step_sizes(profile.min_feature_mm)
    # a hole's contour is kerf_mm narrower than the hole: keep it a real ring
    holes = step_sizes(profile.min_hole_mm, smallest_mm=kerf + 0.1)
    x0 = MARGIN_MM + LETTER_MM + 4.0  # after the row letters
    cut, parts, labels, features = [], [], [], []

    def letter(ch, y_mid):
        labels.extend(text_paths(ch, height_mm=LETTER_MM, x=MARGIN_MM, y=y_mid - LETTER_MM / 2))

    # K: kerf gauge (bottom row)
    y = MARGIN_MM + LABEL_MM + 1.0
    s, c = KERF_SQUARE_MM, CLEARANCE_MM
    cut.append(box(x0, y, x0 + s + 2 * c, y + s + 2 * c))
    part = box(x0 + c, y + c, x0 + c + s, y + c + s)
    parts.append(part)
    hole_x = x0 + s + 2 * c + 10.0
    cut.append(box(hole_x, y + c, hole_x + s, y + c + s))
    mid = y + c + s / 2
    labels.extend(text_paths(_label(s), height_mm=LETTER_MM, x=x0 + c + s / 2, y=mid - LETTER_MM / 2, centre=True))
    labels.extend(text_paths(_label(s), height_mm=LABEL_MM, x=hole_x + s / 2, y=y + c - LABEL_MM - 1.0, centre=True))
    kx, ky = profile.kerf_xy_mm
    if kx == ky:
        labels.extend(text_paths(_label(kerf), height_mm=LABEL_MM, x=hole_x + s + 4.0, y=mid - LABEL_MM / 2))
    else:  # the kerf along X above the one along Y
        labels.extend(text_paths(_label(kx), height_mm=LABEL_MM, x=hole_x + s + 4.0, y=mid + 1.0))
        labels.extend(text_paths(_label(ky), height_mm=LABEL_MM, x=hole_x + s + 4.0, y=mid - LABEL_MM - 1.0))
    features += [
        Feature("kerf_part", s, _label(s), (x0 + c + s / 2, mid)),
        Feature("kerf_hole", s, _label(s), (hole_x + s / 2, mid)),
    ]
    letter("K", mid)
    right = hole_x + s + 4.0 + max(text_width(_label(k), height_mm=LABEL_MM) for k in (kerf, kx, ky))
    y += s + 2 * c + 3.0

    # H: holes stepping around min_hole_mm
    biggest = max(holes)
    pitch = max(10.0, biggest + 4.0, text_width("0.00", height_mm=LABEL_MM) + 3.0)
    cy = y + LABEL_MM + 1.5 + biggest / 2
    for k, d in enumerate(holes):
        cx = x0 + pitch / 2 + k * pitch
        cut.append(Point(cx, cy).buffer(d / 2, quad_segs=32))
        labels.extend(text_paths(_label(d), height_mm=LABEL_MM, x=cx, y=y, centre=True))
        features.append(Feature("hole", d, _label(d), (cx, cy)))
    letter("H", cy)
    right = max(right, x0 + len(holes) * pitch)
    y = cy + biggest / 2 + 3.0

    # B: bridges stepping around min_feature_mm, between slots
    sw, sh = SLOT_MM
    sy = y + LABEL_MM + 1.5
    x = x0
    for k, w in enumerate((0.0,) + bridges):
        x += w
        cut.append(box(x, sy, x + sw, sy + sh))
        if k:
            bx = x - w / 2
            labels.extend(text_paths(_label(w), height_mm=LABEL_MM, x=bx, y=y, centre=True))
            features.append(Feature("bridge", w, _label(w), (bx, sy + sh / 2)))
        x += sw
    letter("B", sy + sh / 2)
    right = max(right, x)
    top = sy + sh

    # I: inlay fits around inlay_fit_mm: the same square hole in every column, under it its piece
    # (the square grown by the fit written below) cut free in a window
    c2 = 2.0
    window = INLAY_MM + 2 * c2
    pitch = max(window + 3.0, text_width("-0.05", height_mm=LABEL_MM) + 3.0)
    y = top + 3.0
    wy = y + LABEL_MM + 1.5
    hy = wy + window + 2.5
    for k, fit in enumerate(inlay_fits(profile)):
        cx = x0 + pitch / 2 + k * pitch
        cut.append(box(cx - window / 2, wy, cx + window / 2, wy + window))
        piece = box(cx - INLAY_MM / 2, wy + c2, cx + INLAY_MM / 2, wy + c2 + INLAY_MM)
        parts.append(piece_of_hole(piece, fit_mm=fit, kerf_mm=max(profile.kerf_xy_mm)))  # as a kit's pieces
        cut.append(box(cx - INLAY_MM / 2, hy, cx + INLAY_MM / 2, hy + INLAY_MM))
        labels.extend(text_paths(_label(fit), height_mm=LABEL_MM, x=cx, y=y, centre=True))
        features += [
            Feature("inlay_piece", fit, _label(fit), (cx, wy + window / 2)),
            Feature("inlay_hole", INLAY_MM, "", (cx, hy + INLAY_MM / 2)),
        ]  # not labelled
    letter("I", (wy + hy + INLAY_MM) / 2)
    right = max(right, x0 + len(inlay_fits(profile)) * pitch)
    top = hy + INLAY_MM

    width, height = right + MARGIN_MM, top + MARGIN_MM
    if width > MAX_CARD_MM or height > MAX_CARD_MM:
        raise ParameterError(
            f"the test card of laser profile {profile.name!r} would be {width:.0f} x {height:.0f} mm, larger "
            f"than {MAX_CARD_MM:g} x {MAX_CARD_MM:g} mm: its min_feature_mm ({profile.min_feature_mm:g}) or "
            f"min_hole_mm ({profile.min_hole_mm:g}) is too large for a test card; measure with a larger part"
        )
    outline = box(0, 0, width, height)
    region = shapely.union_all([outline.difference(shapely.union_all(cut)), *parts])
    return Card(region, outline, tuple(labels), tuple(features), kerf)
