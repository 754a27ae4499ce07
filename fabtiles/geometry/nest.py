"""Nesting: parts packed onto as few sheets as they fit, each moved rigidly, a gap apart.

:func:`nest` places parts (shapely polygons, each with an id) on sheets of a given
size: each part is rotated about the origin by one of the allowed angles, then
translated, so that every placed outline lies inside ``[0, w] x [0, h]`` and no two
come closer than ``gap_mm``. A part is its **outer boundary**: its holes are not
used (nothing is nested inside a hole), so a part with holes takes the area its
outer ring encloses.

The packer is Sparrow (arXiv 2509.13329) through ``spyrrow``, a strip packer: a
strip of fixed height and minimal width. Sheets are filled one after another: the
remaining parts are packed in a strip of the sheet's height, the parts that fall
within the sheet's width make the sheet, the rest are packed again.

Why Sparrow and not a bounding-box packing: on tiles of mixed outlines (squares, hexagons,
circles) Sparrow takes the fewest sheets their area allows, where a max-rects packing of their
bounding boxes (``rectpack``) or ``--sheet``'s grid takes one more (``benchmarks/bench_nest.py``;
the figures in ``docs/speed.md``). Sparrow fits the circles and hexagons into each other's
corners, which no packing of boxes can; on rectangles alone the two would tie, so a shelf packer
of our own would add code and save no sheet.

>>> from shapely.geometry import box
>>> n = nest([("a", box(0, 0, 50, 30)), ("b", box(0, 0, 50, 30))], sheet_mm=(60, 70), gap_mm=2, time_s=1,
...          rotations="none")
>>> n.sheets, [p.sheet for p in n.placements]
(1, [0, 0])
>>> all(0 <= v <= 70 for o in n.outlines for v in o.bounds)
True
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Hashable
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Polygon

from ..core.errors import FabricationError, ParameterError
from ..core.validate import check_float

ROTATIONS = {"none": (0.0,), "180": (0.0, 180.0), "90": (0.0, 90.0, 180.0, 270.0), "free": None}
"""The rotation modes and their angles in degrees (``free``: any angle)."""

DEFAULT_TIME_S = 5.0
"""The most time :func:`nest` takes unless given its budget, seconds (see :func:`default_time_s`)."""

SECONDS_PER_PART = 0.2
"""The default budget's share of each part: a few tiles nest as well in a second as in five."""


def default_time_s(parts: int) -> float:
    """The packer's time budget unless one is given: :data:`SECONDS_PER_PART` a part, from one
    second to :data:`DEFAULT_TIME_S`.

    >>> default_time_s(6), default_time_s(40)
    (1.2, 5.0)
    """
    return min(DEFAULT_TIME_S, max(1.0, round(parts * SECONDS_PER_PART, 3)))


MARGIN_MM = 0.01
"""Slack added to the gap and kept from the sheet's edges: spyrrow computes in 32-bit floats
(about 3e-5 mm at 600 mm), so its placements, redone here in 64 bits, may miss by that much."""

_DENSITY_GUESS = 0.75
"""Sheets a strip will need, estimated from the parts' area at this density, to share the time budget."""


@dataclass(frozen=True)
class Placement:
    """Where one part goes: sheet ``sheet`` (0-based), rotated by ``rotation`` degrees
    (counter-clockwise about the origin of the part's coordinates), then moved by ``translation``."""

    id: Hashable
    sheet: int
    rotation: float
    translation: tuple[float, float]

    def move(self, xy) -> np.ndarray:
        """Points ``(n, 2)`` of the part, placed on its sheet.

        >>> Placement("a", 0, 90.0, (10.0, 0.0)).move([[1.0, 0.0]]).round(9).tolist()
        [[10.0, 1.0]]
        """
        a = math.radians(self.rotation)
        c, s = math.cos(a), math.sin(a)
        xy = np.asarray(xy, dtype=float)
        return xy @ np.array([[c, s], [-s, c]]) + self.translation

    def place(self, geometry):
        """A shapely geometry of the part, placed on its sheet."""
        return shapely.transform(geometry, self.move)


@dataclass(frozen=True)
class NestProgress:
    """What :func:`nest` reports while it packs: seconds spent of the budget, parts placed, sheets filled."""

    elapsed_s: float
    budget_s: float
    placed: int
    parts: int
    sheets: int


@dataclass(frozen=True)
class Nesting:
    """The result of :func:`nest`: one placement and one placed outline per part, in input order."""

    placements: tuple
    outlines: tuple
    sheet_mm: tuple[float, float]
    gap_mm: float
    rotations: str

    @property
    def sheets(self) -> int:
        """How many sheets the parts take."""
        return 1 + max(p.sheet for p in self.placements)

    def on_sheet(self, k: int) -> list[int]:
        """The indices (into :attr:`placements`) of the parts on sheet ``k``."""
        return [i for i, p in enumerate(self.placements) if p.sheet == k]

    def material_use(self) -> tuple[float, ...]:
        """Per sheet, the area its parts' outer boundaries enclose over the sheet's area."""
        w, h = self.sheet_mm
        return tuple(
            round(sum(self.outlines[i].area for i in self.on_sheet(k)) / (w * h), 4) for k in range(self.sheets)
        )


def _check_parts(parts) -> tuple[list, list]:
    """``(ids, polygons)``: the outer boundaries of ``parts``, a non-empty sequence of (id, Polygon)."""
    if isinstance(parts, dict):
        parts = list(parts.items())
    if not isinstance(parts, (list, tuple)) or not parts:
        raise ParameterError(
            f"parts must be a non-empty list of (id, shapely Polygon) pairs, got {parts!r:.60}", param="parts"
        )
    ids, shapes = [], []
    for k, pair in enumerate(parts):
        if (
            not isinstance(pair, (list, tuple))
            or len(pair) != 2
            or not isinstance(pair[1], Polygon)
            or pair[1].is_empty
            or pair[1].area <= 0
        ):
            raise ParameterError(
                f"parts[{k}] must be an (id, shapely Polygon of area > 0) pair, got {pair!r:.80}", param="parts"
            )
        ids.append(pair[0])
        shapes.append(shapely.geometry.polygon.orient(Polygon(pair[1].exterior), 1.0))  # holes not used
    seen = set()
    for i in ids:
        if i in seen:
            raise ParameterError(f"parts' ids must be distinct, got {i!r} twice", param="parts")
        seen.add(i)
    return ids, shapes


def _fits(shape, w: float, h: float, angles) -> bool:
    """Whether ``shape`` fits a ``w`` x ``h`` sheet at one of ``angles`` (``None``: free, tried at the quarter
    turns)."""
    for a in (0.0, 90.0) if angles is None else angles:
        x0, y0, x1, y1 = Placement(None, 0, a, (0.0, 0.0)).place(shape).bounds
        if x1 - x0 <= w - 2 * MARGIN_MM and y1 - y0 <= h - 2 * MARGIN_MM:
            return True
    return False


def _fallback(shape, w: float, h: float, angles) -> tuple[float, tuple[float, float]]:
    """A part alone at the sheet's lower-left corner, at the first angle it fits."""
    for a in (0.0, 90.0) if angles is None else angles:
        x0, y0, x1, y1 = Placement(None, 0, a, (0.0, 0.0)).place(shape).bounds
        if x1 - x0 <= w - 2 * MARGIN_MM and y1 - y0 <= h - 2 * MARGIN_MM:
            return a, (MARGIN_MM - x0, MARGIN_MM - y0)
    raise AssertionError("checked by _fits")  # pragma: no cover


SIMPLIFY_MM = 0.02
"""How far the outlines the packer sees may stray outside the parts (they are never inside them)."""


def _packing_shapes(shapes) -> list:
    """The outlines handed to the packer: each part simplified within :data:`SIMPLIFY_MM` and grown by it
    (mitred), so it holds the part and the part keeps the gap; the placements move the parts themselves.

    spyrrow's time grows with the vertices, and round-grown pieces have many: simplified, they keep
    about a fifth, and the packer its time budget (``docs/speed.md``).
    """
    simple = shapely.buffer(
        shapely.simplify(np.asarray(shapes, dtype=object), SIMPLIFY_MM), SIMPLIFY_MM, join_style="mitre"
    )
    out = []
    for original, s in zip(shapes, simple, strict=True):
        s = shapely.geometry.polygon.orient(Polygon(s.exterior), 1.0) if s.geom_type == "Polygon" else original
        out.append(s if s.covers(original) else original)  # never smaller than the part
    return out


def _solve(shapes, idx, height, gap, angles, seconds, on_tick):
    """spyrrow's strip packing of ``shapes[idx]``: ``[(index, rotation, (dx, dy)), ...]``.

    Identical shapes (same outline) are one spyrrow item with a demand, which it packs faster.
    The solver runs in a thread (it releases the GIL) so ``on_tick`` can report while it works.
    """
    import spyrrow

    # copies of one shape anywhere (a kit's pieces are translates of a few: 247 pieces of the sample's kit,
    # 4 shapes) are one item: each shape moved to its lower-left corner and its coordinates rounded to 1 nm
    groups: dict = {}
    corner = {}
    for i in idx:
        ring = np.asarray(shapes[i].exterior.coords)[:-1]
        corner[i] = ring.min(axis=0)
        key = np.round(ring - corner[i], 6).tobytes()
        groups.setdefault(key, []).append(i)
    items = [
        spyrrow.Item(
            str(g),
            [
                (float(p[0]), float(p[1]))
                for p in np.asarray(shapes[members[0]].exterior.coords)[:-1] - corner[members[0]]
            ],
            demand=len(members),
            allowed_orientations=None if angles is None else list(angles),
        )
        for g, members in enumerate(groups.values())
    ]
    instance = spyrrow.StripPackingInstance("fabtiles", float(height), items)
    config = spyrrow.StripPackingConfig(
        early_termination=True, total_computation_time=int(seconds), min_items_separation=gap, num_workers=2, seed=0
    )
    out: dict = {}

    def run():
        try:
            out["solution"] = instance.solve(config)
        except BaseException as exc:
            out["error"] = exc

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    while worker.is_alive():
        worker.join(0.2)
        on_tick()
    if "error" in out:
        raise out["error"]
    members = [list(m) for m in groups.values()]
    placed = []
    for item in out["solution"].placed_items:
        i, rot = members[int(item.id)].pop(0), float(item.rotation)
        # the item is the shape less its corner c: the shape itself goes to R(shape) + t - R(c)
        a = math.radians(rot)
        cx, cy = corner[i]
        tx, ty = map(float, item.translation)
        placed.append(
            (i, rot, (tx - (math.cos(a) * cx - math.sin(a) * cy), ty - (math.sin(a) * cx + math.cos(a) * cy)))
        )
    return placed


_START_SEPARATIONS = 4.0
"""How many separations wide the packer's first strip is kept (it panicked at under one: :func:`_solve_lower`)."""


def _solve_lower(shapes, idx, height, sep, angles, seconds, on_tick):
    """:func:`_solve`, on a lower strip where the packer fails on the sheet's height.

    The packer starts from a strip as wide as the parts' area over its height: parts far smaller
    than the sheet make that narrower than the separation allows, and it panics ("Offset resulted
    in an empty polygon"). A lower strip holds them as well (the sheet's parts are slid to its
    corner afterwards), so the strip is kept low enough for a start of a few separations wide, and
    halved on a panic; at the height of the widest part a lone part is left to the caller (placed
    at the corner) and several are a fabrication error, not a crash.
    """
    lowest = max(float(np.hypot(*np.subtract(*np.reshape(shapes[i].bounds, (2, 2))))) for i in idx) + 2 * sep
    area = sum(shapes[i].area for i in idx)
    height = min(height, max(lowest, area / (_START_SEPARATIONS * max(sep, 1e-9))))
    while True:
        try:
            return _solve(shapes, idx, height, sep, angles, seconds, on_tick)
        except BaseException as exc:
            if type(exc).__name__ != "PanicException":  # pyo3's panic, a BaseException of its own
                raise
            if height <= lowest and len(idx) == 1:
                return []  # the caller places a lone part at the sheet's corner itself
            if height <= lowest:
                raise FabricationError(
                    f"the nesting packer cannot place {len(idx)} parts of at most {lowest - 2 * sep:.3g} mm across "
                    f"{sep:.3g} mm apart (it fails on parts this small for the gap): make gap_mm smaller or the "
                    "parts larger"
                ) from None
            height = max(lowest, height / 2)


def nest(
    parts, *, sheet_mm, gap_mm: float, rotations: str = "90", time_s: float | None = None, progress=None
) -> Nesting:
    """Place ``parts`` on as few ``sheet_mm`` sheets as the packer finds, ``gap_mm`` apart.

    Parameters
    ----------
    parts : sequence of (id, shapely Polygon), or dict id -> Polygon
        The parts; only each polygon's outer boundary is packed (holes are not used).
        Ids are distinct; identical outlines are packed faster.
    sheet_mm : (float, float)
        The sheet's width and height, mm.
    gap_mm : float
        Least distance between two placed outlines, mm (>= 0). Parts may touch the sheet's edges.
    rotations : {"90", "180", "free", "none"}
        Allowed turns: quarter turns, half turns (wood grain), any angle, or none.
    time_s : float, optional
        The time budget, seconds (> 0); the packer counts whole seconds and takes at least
        one per sheet, so a job of several sheets may take a little longer. By default
        :func:`default_time_s` of the parts.
    progress : callable, optional
        Called with a :class:`NestProgress` about five times a second while packing.

    Returns
    -------
    Nesting
        One :class:`Placement` and placed outline per part, in input order.

    Raises
    ------
    ParameterError
        For a bad sheet, gap, rotation mode or time budget, or bad parts.
    FabricationError
        For a part larger than the sheet either way round (in the allowed rotations).
    """
    w, h, gap, budget = _checked(sheet_mm, gap_mm, rotations, DEFAULT_TIME_S if time_s is None else time_s)
    ids, shapes = _check_parts(parts)
    if time_s is None:
        budget = default_time_s(len(shapes))
    angles = ROTATIONS[rotations]
    _check_fit(ids, shapes, (w, h), angles, rotations)

    start = time.monotonic()
    placements: dict = {}
    remaining = list(range(len(shapes)))
    sheet = 0
    sheet_area = w * h

    def tick():
        if progress is not None:
            progress(NestProgress(time.monotonic() - start, budget, len(placements), len(shapes), sheet))

    packed = _packing_shapes(shapes)
    while remaining:
        left = max(0.0, budget - (time.monotonic() - start))
        need = max(1, math.ceil(sum(shapes[i].area for i in remaining) / (sheet_area * _DENSITY_GUESS)))
        seconds = max(1, int(left / need))  # whole seconds, rounded down: spyrrow overruns a solve a little
        # spyrrow keeps the separation from the strip's edges too: the strip is taller by it on both
        # sides, and the placements move back by it, so parts may reach the sheet's edges
        sep = gap + MARGIN_MM
        placed = _solve_lower(packed, remaining, h - 2 * MARGIN_MM + 2 * sep, sep, angles, seconds, tick)
        candidates = _on_sheet(placed, ids, shapes, sheet, sep, (w, h))
        kept = _apart(candidates, gap)
        if not kept:  # nothing within the sheet (a free turn made the first part too wide): one part alone
            i = remaining[0]
            rot, shift = _fallback(shapes[i], w, h, angles)
            kept = [(i, Placement(ids[i], sheet, rot, shift))]
        # the strip packer leaves the parts anywhere up the sheet's height: slid as one block to the sheet's
        # corner (a lone tile at the origin, not half-way up the edge), their gaps unchanged
        placements.update(_to_corner(kept, shapes))
        done = {i for i, _ in kept}
        remaining = [i for i in remaining if i not in done]
        sheet += 1
        tick()
    ordered = tuple(placements[i] for i in range(len(shapes)))
    return Nesting(ordered, tuple(p.place(s) for p, s in zip(ordered, shapes, strict=True)), (w, h), gap, rotations)


def _checked(sheet_mm, gap_mm, rotations, time_s) -> tuple[float, float, float, float]:
    """The sheet's width and height, the gap and the time budget, checked (and the rotation mode)."""
    if not isinstance(sheet_mm, (list, tuple)) or len(sheet_mm) != 2:
        raise ParameterError(f"sheet_mm must be (width, height) in mm, got {sheet_mm!r}", param="sheet_mm")
    w = check_float("sheet_mm[0]", sheet_mm[0], low=0, low_open=True)
    h = check_float("sheet_mm[1]", sheet_mm[1], low=0, low_open=True)
    gap = check_float("gap_mm", gap_mm, low=0)
    if not isinstance(rotations, str) or rotations not in ROTATIONS:
        raise ParameterError(f"rotations must be one of: {', '.join(ROTATIONS)}, got {rotations!r}", param="rotations")
    budget = check_float("time_s", time_s, low=0, low_open=True)
    return w, h, gap, budget


def _check_fit(ids, shapes, sheet_mm: tuple[float, float], angles, rotations: str) -> None:
    """Refuse a part larger than the sheet in every allowed turn."""
    w, h = sheet_mm
    for i, shape in zip(ids, shapes, strict=True):
        if not _fits(shape, w, h, angles):
            x0, y0, x1, y1 = shape.bounds
            turn = "either way round" if angles is None or 90.0 in angles else f"unturned (rotations {rotations!r})"
            raise FabricationError(
                f"part {i!r} ({x1 - x0:.4g} x {y1 - y0:.4g} mm) does not fit on the {w:g} x {h:g} mm sheet "
                f"{turn}; use a larger sheet, a smaller part"
                f"{'' if angles is None or 90.0 in angles else ' or --rotate 90'}",
                param="sheet_mm",
            )


def _on_sheet(placed, ids, shapes, sheet: int, sep: float, sheet_mm: tuple[float, float]) -> list:
    """The packer's placements moved back by the separation, ``[(index, Placement, outline), ...]`` left to
    right, those within the sheet only (the rest are packed again for the next)."""
    w, h = sheet_mm
    candidates = []
    for i, rot, (dx, dy) in sorted(placed, key=lambda p: p[2][0]):
        p = Placement(ids[i], sheet, rot, (dx - sep + MARGIN_MM, dy - sep + MARGIN_MM))
        outline = p.place(shapes[i])
        x0, y0, x1, y1 = outline.bounds
        if x0 < 0 or y0 < 0 or x1 > w or y1 > h:
            continue
        candidates.append((i, p, outline))
    return candidates


def _apart(candidates: list, gap: float) -> list:
    """The candidates kept in turn unless closer than ``gap`` to one kept before: ``[(index, Placement), ...]``.

    spyrrow's separation, checked in 64 bits (a part too close waits for the next sheet); the
    pairs closer than the gap come from one tree query.
    """
    outlines = np.array([c[2] for c in candidates], dtype=object)
    close: dict = {}
    if len(outlines) > 1:
        a, b = shapely.STRtree(outlines).query(outlines, predicate="dwithin", distance=gap * (1 - 1e-12))
        for x, y in zip(a.tolist(), b.tolist(), strict=True):
            if x != y:
                close.setdefault(x, set()).add(y)
    kept: list = []
    taken: set = set()
    for k, (i, p, _) in enumerate(candidates):
        if close.get(k, set()) & taken:
            continue
        kept.append((i, p))
        taken.add(k)
    return kept


def _to_corner(kept: list, shapes) -> dict:
    """The sheet's placements slid as one block to the sheet's corner, their gaps unchanged: ``{index: Placement}``.

    The strip packer leaves the parts anywhere up the sheet's height; a lone tile goes to the
    origin, not half-way up the edge.
    """
    x0, y0 = np.min([p.place(shapes[i]).bounds[:2] for i, p in kept], axis=0)
    out = {}
    for i, p in kept:
        tx, ty = p.translation
        out[i] = Placement(p.id, p.sheet, p.rotation, (tx - x0, ty - y0))
    return out
