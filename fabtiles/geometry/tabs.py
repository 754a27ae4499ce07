"""Holding tabs: gaps left in a part's outer cut so the part stays in the sheet.

On a honeycomb bed a part cut free can tip into the cells or shift under the air
assist before the job ends; a few short uncut bridges (tabs) keep it in the sheet,
and a knife frees it after. :func:`tab_paths` takes the outer-cut rings of a plan
(kerf-offset, counter-clockwise, in cut order) and splits each into open pieces,
leaving ``tabs_per_part`` gaps of ``tab_mm`` each, measured along the cut path:

* **Even.** The gaps' midpoints are ``perimeter / n`` apart along the ring, so the
  part is held all round.
* **On straight stretches.** A corner (the path turning by more than
  :data:`CORNER_DEG`) is where a tab is weakest and hardest to clean up, so the whole
  set of midpoints is slid along the ring (one offset for all, the spacing kept) to
  the offset whose tab nearest a corner is farthest from it: a square's tabs land at
  the middle of its sides. A ring without corners (a circle) keeps its tabs where
  they are.
* **Short rings.** A gap must leave a piece between it and the next, so a ring
  shorter than ``3 * tab_mm`` per tab gets fewer tabs (none below one tab's three
  lengths); the report names them.

Holes get no tabs: their slugs should fall. Only a laser's files get them (a router's
and a waterjet's CAM adds its own: :meth:`~fabtiles.machines.cutters.CutterKind.check_tabs`).

>>> sq = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
>>> tabs = tab_paths([sq], tab_mm=1.0, tabs_per_part=4)
>>> len(tabs.pieces), tabs.midpoints.tolist()
(4, [[5.0, 0.0], [10.0, 5.0], [5.0, 10.0], [0.0, 5.0]])
>>> tabs.pieces[0].tolist()
[[5.5, 0.0], [10.0, 0.0], [10.0, 4.5]]
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.errors import ParameterError
from ..core.schema import key
from ..machines.cutters import cutter_kind
from .contours import ROUND_DECIMALS

CORNER_DEG = 20.0
"""A vertex where the path turns by more than this is a corner (a circle's 32-gon turns 11.25 degrees
at each vertex: no corner; a star's points and a square's corners turn 45 to 150)."""

PIECES_PER_TAB = 3.0
"""A ring gets at most ``perimeter / (PIECES_PER_TAB * tab_mm)`` tabs: the gaps then take at most a third
of the ring, and any two gaps are at least two tab lengths apart however they slide."""

PHASES = 64
"""How many evenly spaced offsets of the tabs are tried on each ring, besides one per straight stretch."""

TAB = key("output.tab_mm")
TABS_PER_PART = key("output.tabs_per_part")


@dataclass(frozen=True)
class Tabs:
    """The outer-cut paths with their tabs: open ``pieces`` in cut order, the gaps' ``midpoints``
    ((k, 2), mm, in the same order), how many tabs each ring got (``per_ring``) and the rings too
    short for ``tabs_per_part`` (``short``: their indices)."""

    pieces: list
    midpoints: np.ndarray
    per_ring: np.ndarray
    short: np.ndarray
    tab_mm: float
    tabs_per_part: int

    @property
    def count(self) -> int:
        """How many tabs in all."""
        return int(self.per_ring.sum())

    def note(self) -> str:
        """The report's words: how many tabs, how long, where (the first few midpoints).

        >>> sq = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
        >>> tab_paths([sq], tab_mm=0.5, tabs_per_part=2).note()
        'holding tabs: 2 tabs of 0.5 mm in 1 part (2 per part) at (5, 0), (5, 10); the outer cut is 2 open paths'
        """
        n, parts = self.count, len(self.per_ring)
        shown = ", ".join(f"({x:.4g}, {y:.4g})" for x, y in self.midpoints[:4].tolist())
        more = f" and {n - 4:,} more" if n > 4 else ""
        text = (
            f"holding tabs: {n:,} tab{'s' if n != 1 else ''} of {self.tab_mm:g} mm in {parts:,} "
            f"part{'s' if parts != 1 else ''} ({self.tabs_per_part} per part) at {shown}{more}; the outer cut "
            f"is {len(self.pieces):,} open path{'s' if len(self.pieces) != 1 else ''}"
        )
        if len(self.short):
            k = len(self.short)
            text += (
                f"; {k:,} part{'s' if k != 1 else ''} shorter round than {PIECES_PER_TAB:g} x tab_mm per tab "
                f"got fewer tabs"
            )
        return text

    def as_stats(self) -> dict:
        """The report's ``tabs`` entry."""
        return {
            "length_mm": self.tab_mm,
            "per_part": self.tabs_per_part,
            "tabs": self.count,
            "outer_pieces": len(self.pieces),
            "short_parts": len(self.short),
            "midpoints": np.round(self.midpoints[:20], 3).tolist(),
        }


def check_tabs(tab_mm, tabs_per_part, *, kerf_mm: float = 0.0, profile=None) -> tuple[float, int]:
    """``(tab_mm, tabs_per_part)`` checked: the schema's ranges, a cutter that leaves tabs, a tab wider than the kerf.

    None is the default (no tabs; 4 per part). ``profile``: the cutter's, whose kind
    may leave tabs to CAM (:meth:`~fabtiles.machines.cutters.CutterKind.check_tabs`). The beam
    eats half a kerf at each end of a gap, so the bridge left is ``tab_mm - kerf_mm``
    wide: a tab no wider than the kerf leaves nothing.

    >>> check_tabs(None, None)
    (0.0, 4)
    >>> check_tabs(0.1, 4, kerf_mm=0.15)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: tab_mm must be 0 (no tabs) or more than the kerf (0.15 mm), got 0.1: the beam eats half a kerf at each end of a gap, so the bridge left is tab_mm - kerf_mm wide; make tab_mm larger
    """  # noqa: E501 - a doctest's lines are as Python prints them
    tab = TAB.check(TAB.default if tab_mm is None else tab_mm)
    per = TABS_PER_PART.check(TABS_PER_PART.default if tabs_per_part is None else tabs_per_part)
    if profile is not None:
        cutter_kind(profile).check_tabs(profile, tab)
    if 0 < tab <= kerf_mm:
        raise ParameterError(
            f"tab_mm must be 0 (no tabs) or more than the kerf ({kerf_mm:g} mm), got {tab:g}: "
            "the beam eats half a kerf at each end of a gap, so the bridge left is tab_mm - "
            "kerf_mm wide; make tab_mm larger",
            param="tab_mm",
        )
    return tab, int(per)


def _corner_arcs(ring: np.ndarray, arcs: np.ndarray) -> np.ndarray:
    """The arc positions (mm from the ring's first point) of its corners, sorted."""
    d = np.roll(ring, -1, axis=0) - ring  # edge i: from vertex i to vertex i + 1
    e = np.roll(d, 1, axis=0)  # the edge into vertex i
    turn = np.abs(np.arctan2(e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0], np.einsum("ij,ij->i", e, d)))
    return arcs[:-1][np.degrees(turn) > CORNER_DEG]


def _phase(arcs: np.ndarray, corners: np.ndarray, n: int) -> float:
    """The offset of the first tab's midpoint whose tab nearest a corner is farthest from one."""
    perimeter = arcs[-1]
    step = perimeter / n
    if not len(corners):
        return step / 2
    # the middle of every stretch between corners, brought into the first spacing, and an even grid
    mids = (corners + np.diff(np.append(corners, corners[0] + perimeter)) / 2) % step
    phases = np.concatenate([mids, np.arange(PHASES) * step / PHASES])
    at = (phases[:, None] + np.arange(n) * step) % perimeter  # (P, n) midpoints along the ring
    wrapped = np.concatenate([corners - perimeter, corners, corners + perimeter])
    i = np.searchsorted(wrapped, at)
    dist = np.minimum(at - wrapped[i - 1], wrapped[i] - at)
    worst, total = dist.min(axis=1), dist.sum(axis=1)
    best = np.lexsort((-total, -np.round(worst, 6)))[0]
    return float(phases[best])


def _cut(pts: np.ndarray, s: np.ndarray, a: float, b: float) -> np.ndarray:
    """The stretch from arc position ``a`` to ``b`` of a ring gone round twice (``pts``, their arc positions ``s``)."""
    ab = np.array([a, b])
    out = np.concatenate(
        [
            np.column_stack([np.interp(ab, s, pts[:, 0]), np.interp(ab, s, pts[:, 1])])[:1],
            pts[(s > a) & (s < b)],
            [[np.interp(b, s, pts[:, 0]), np.interp(b, s, pts[:, 1])]],
        ]
    )
    out = np.round(out, ROUND_DECIMALS) + 0.0
    keep = np.ones(len(out), dtype=bool)
    keep[1:] = np.any(out[1:] != out[:-1], axis=1)
    return out[keep]


def tab_paths(rings, *, tab_mm: float, tabs_per_part: int) -> Tabs:
    """The outer-cut ``rings`` split into open pieces around ``tabs_per_part`` gaps of ``tab_mm`` each.

    Parameters
    ----------
    rings : list of ndarray (m, 2)
        Closed rings without the repeated first point (the plan's outer cuts), in cut order.
    tab_mm : float
        Each gap's length along the path (mm), > 0 (check it with :func:`check_tabs`).
    tabs_per_part : int
        Gaps per ring, >= 1; a ring shorter than ``PIECES_PER_TAB * tab_mm`` per gap gets fewer.

    Returns
    -------
    Tabs
        Each ring's pieces in its own direction, one after another, the ring's pieces
        starting after its first gap; a ring too short for one tab stays whole (an open
        path back to its first point).
    """
    pieces, mids, per, short = [], [], [], []
    for index, ring in enumerate(rings):
        ring = np.asarray(ring, dtype=float)
        closed = np.vstack([ring, ring[:1]])
        arcs = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
        perimeter = float(arcs[-1])
        n = min(int(tabs_per_part), int(perimeter // (PIECES_PER_TAB * tab_mm)))
        if n < tabs_per_part:
            short.append(index)
        per.append(n)
        if n == 0:
            pieces.append(closed)
            continue
        step = perimeter / n
        centre = (_phase(arcs, _corner_arcs(ring, arcs), n) + np.arange(n) * step) % perimeter
        centre.sort()
        # the ring twice round, made once for its pieces, so a piece across its first point is one slice
        # (not a new array per piece)
        twice, s = np.concatenate([closed, closed[1:]]), np.concatenate([arcs, arcs[1:] + perimeter])
        for k in range(n):
            a = (centre[k] + tab_mm / 2) % perimeter
            length = (centre[(k + 1) % n] - centre[k]) % perimeter or perimeter
            pieces.append(_cut(twice, s, a, a + length - tab_mm))
        mids.append(np.column_stack([np.interp(centre, arcs, closed[:, 0]), np.interp(centre, arcs, closed[:, 1])]))
    midpoints = np.round(np.concatenate(mids), ROUND_DECIMALS) + 0.0 if mids else np.zeros((0, 2))
    return Tabs(
        pieces, midpoints, np.asarray(per, dtype=int), np.asarray(short, dtype=int), float(tab_mm), int(tabs_per_part)
    )
