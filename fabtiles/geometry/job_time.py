"""Laser job length and time, from the contours in cut order and the profile's settings.

The estimate (``docs/laser-cutting.md`` gives the formula):

- each layer's paths at its ``speed_mm_s``, ``passes`` times:
  ``length / speed * passes``;
- a pierce at the start of every path of every pass: ``pierces * passes * pierce_s``,
  where the pierces are the closed contours plus the open score paths;
- the head's moves between paths, from the machine's origin (0, 0) through the cut
  order, at ``travel_mm_s``, once per pass;
- an engrave layer's area swept in lines ``line_interval_mm`` apart:
  ``area / interval / speed * passes`` (the length of those lines, at that speed).

Acceleration, overscan and the controller's corner slow-downs are not modelled, so a
real job on many short paths takes longer: the tests hold the estimate against a
simulation of GRBL's motion planner (acceleration included) on the G-code MeerK40t
writes from the same file.

>>> import numpy as np
>>> from fabtiles.machines.profiles import load_profile
>>> square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
>>> job = estimate(load_profile("laser-3mm-plywood"), inner=[square + 20], outer=[square * 5])
>>> job.cut_mm["inner_cut"], job.cut_mm["outer_cut"], job.pierces
(40.0, 200.0, 2)
>>> job.line()
'0.24 m of cut, 2 pierces, about 1 min'
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class JobEstimate:
    """What a laser job costs: lengths per layer (mm), pierces, engraved area, travel, time."""

    cut_mm: dict = field(default_factory=dict)
    """Length of each layer's paths (mm), by profile key (``inner_cut``, ``outer_cut``, ``score``)."""
    pierces: int = 0
    engrave_area_mm2: float = 0.0
    travel_mm: float = 0.0
    seconds: float = 0.0
    travel_before_mm: float | None = None
    """The travel in the order the contours were made in, before :mod:`.cut_order` (None: not reordered)."""

    @property
    def cut_total_mm(self) -> float:
        return float(sum(self.cut_mm.values()))

    def line(self) -> str:
        """The job in one line, for people and scripts: ``12.4 m of cut, 318 pierces, about 17 min``.

        >>> JobEstimate({"inner_cut": 12_400.0}, 318, seconds=1000).line()
        '12.4 m of cut, 318 pierces, about 17 min'
        >>> JobEstimate({"outer_cut": 500.0}, 1, 1250.0, seconds=30).line()
        '0.5 m of cut, 1 pierce, 12.5 cm^2 engraved, about 1 min'
        """
        m = self.cut_total_mm / 1000
        length = f"{m:.3g}" if m < 1 else f"{m:.1f}"
        parts = [f"{length} m of cut", f"{self.pierces:,} pierce{'' if self.pierces == 1 else 's'}"]
        if self.engrave_area_mm2:
            parts.append(f"{self.engrave_area_mm2 / 100:.3g} cm^2 engraved")
        minutes = max(1, round(self.seconds / 60))
        return ", ".join(parts) + f", about {minutes:,} min"

    def as_stats(self) -> dict:
        """The report's ``job`` entry (plain numbers, rounded)."""
        return {
            "cut_mm": {k: round(v, 3) for k, v in self.cut_mm.items()},
            "cut_total_mm": round(self.cut_total_mm, 3),
            "pierces": self.pierces,
            "engrave_area_mm2": round(self.engrave_area_mm2, 3),
            "travel_mm": round(self.travel_mm, 3),
            "seconds": round(self.seconds, 1),
            "line": self.line(),
        } | ({} if self.travel_before_mm is None else {"travel_before_mm": round(self.travel_before_mm, 3)})

    def travel_line(self) -> str:
        """The head's travel between cuts, and what the cut order saved, in words a newcomer reads.

        >>> JobEstimate(travel_mm=20_300.0, travel_before_mm=26_285.0).travel_line()
        'head travel between cuts: 20.3 m, 23 % less than the 26.3 m in the order the contours were drawn'
        """
        line = f"head travel between cuts: {self.travel_mm / 1000:.3g} m"
        if self.travel_before_mm:
            saved = 100 * (1 - self.travel_mm / self.travel_before_mm)
            more_or_less = "less" if saved >= 0 else "more"
            line += (
                f", {abs(saved):.0f} % {more_or_less} than the {self.travel_before_mm / 1000:.3g} m in the order "
                "the contours were drawn"
            )
        return line


def _flat(rings):
    """All points of ``rings`` in one array, and the index of each ring's first and last point."""
    sizes = np.fromiter(map(len, rings), dtype=np.int64, count=len(rings))
    flat = np.concatenate(rings).astype(float, copy=False).reshape(-1, 2)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    return flat, starts, starts + sizes - 1


def path_lengths(rings, closed: bool, flat=None) -> np.ndarray:
    """The length of each path (mm); ``closed`` adds the edge from the last point back to the first.

    In one pass over all points, not a loop over a sheet's thousands of rings.

    >>> path_lengths([np.array([[0, 0], [3, 0], [3, 4]])], closed=True).tolist()
    [12.0]
    """
    if not len(rings):
        return np.zeros(0)
    flat, starts, ends = flat if flat is not None else _flat(rings)
    steps = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(flat, axis=0).T))])
    lengths = steps[ends] - steps[starts]
    if closed:
        lengths = lengths + np.hypot(*(flat[starts] - flat[ends]).T)
    return lengths


def _travel(groups) -> float:
    """Length of the moves between paths in cut order, from (0, 0), each group ``passes`` times."""
    total, here = 0.0, np.zeros(2)
    for (flat, starts, ends), closed, passes in groups:
        first, last = flat[starts], flat[starts] if closed else flat[ends]
        for _ in range(passes):
            before = np.vstack([here[None], last[:-1]])
            total += float(np.hypot(*(first - before).T).sum())
            here = last[-1]
    return total


def _layer_groups(profile, inner, outer, score, engrave, outer_closed: bool) -> list:
    """``(key, layer, rings, closed, role)`` of each layer in cut order: engrave, score, inner, outer."""
    layers = profile.layers
    return [
        ("engrave", layers.engrave, engrave, True, "engrave"),
        ("score", layers.score, score, False, "score"),
        ("inner_cut", layers.inner_cut, inner, True, "inner"),
        ("outer_cut", layers.outer_cut, outer, outer_closed, "outer"),
    ]


def travel_mm(profile, *, inner=(), outer=(), score=(), engrave=(), outer_closed: bool = True) -> float:
    """The head's travel of :func:`estimate` alone, without the cut lengths and times.

    >>> from fabtiles.machines.profiles import load_profile
    >>> square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    >>> round(travel_mm(load_profile("laser-3mm-plywood"), inner=[square + 5], outer=[square * 3]), 6)  # 2 x 5 sqrt 2
    14.142136
    """
    return _travel(
        [
            (_flat(rings), closed, layer.passes)
            for _, layer, rings, closed, _ in _layer_groups(profile, inner, outer, score, engrave, outer_closed)
            if len(rings) and layer is not None
        ]
    )


def estimate(
    profile,
    *,
    inner=(),
    outer=(),
    score=(),
    engrave=(),
    engrave_area_mm2: float = 0.0,
    outer_closed: bool = True,
    curves: dict | None = None,
) -> JobEstimate:
    """The :class:`JobEstimate` of a laser job: its paths by layer, in cut order.

    ``inner``, ``outer`` and ``engrave`` are closed rings, ``score`` open paths
    ((n, 2) arrays, mm); ``engrave_area_mm2`` is the area the engrave layer fills.
    ``outer_closed=False``: the outer cuts are open pieces between holding tabs
    (:mod:`.tabs`), each a pierce of its own. The order is the files' cut order:
    engrave, score, inner cuts, outer cuts. ``curves`` (role -> the paths as
    :class:`~fabtiles.geometry.arcs.Curve` s, whose vertices are the paths given) measures
    the arcs as arcs: a chord of sagitta ``s`` on radius ``r`` is short of its arc by about
    ``(8 * s / r) / 24`` of itself (0.6 % for a 0.575 mm round join at 0.01 mm; the 100 mm
    circle tile's cut: 1,937.8 mm in chords, 1,939.0 mm in arcs).

    >>> from fabtiles.machines.profiles import load_profile
    >>> piece = np.array([[0, 0], [10, 0], [10, 9]], float)
    >>> job = estimate(load_profile("laser-3mm-plywood"), outer=[piece, piece + 20], outer_closed=False)
    >>> job.cut_mm["outer_cut"], job.pierces
    (38.0, 2)
    """
    cut, seconds, pierces, travel_groups = {}, 0.0, 0, []
    for key, layer, rings, closed, role in _layer_groups(profile, inner, outer, score, engrave, outer_closed):
        if not len(rings) or layer is None:
            continue
        flat = _flat(rings)
        travel_groups.append((flat, closed, layer.passes))
        if key == "engrave":  # its outlines are the fill's edges; the fill lines are the time
            sweep = engrave_area_mm2 / layer.line_interval_mm
            seconds += sweep / layer.speed_mm_s * layer.passes
            continue
        if curves is not None and len(curves.get(role, ())) == len(rings):
            from .arcs import curve_lengths

            length = float(curve_lengths(curves[role], closed=closed).sum())
        else:
            length = float(path_lengths(rings, closed, flat).sum())
        cut[key] = length
        seconds += length / layer.speed_mm_s * layer.passes + len(rings) * layer.passes * profile.pierce_s
        pierces += len(rings)
    travel = _travel(travel_groups)
    seconds += travel / profile.travel_mm_s
    return JobEstimate(cut, pierces, float(engrave_area_mm2) if len(engrave) else 0.0, travel, seconds)


def total(estimates) -> JobEstimate:
    """The sum of several jobs (a sheet's tiles, a batch).

    >>> total([JobEstimate({"inner_cut": 1.0}, 2, seconds=3), JobEstimate({"inner_cut": 2.0}, 1, seconds=4)])
    JobEstimate(cut_mm={'inner_cut': 3.0}, pierces=3, engrave_area_mm2=0.0, travel_mm=0.0, seconds=7.0, travel_before_mm=None)
    """  # noqa: E501 - a doctest's lines are as Python prints them
    cut: dict = {}
    estimates = list(estimates)
    for e in estimates:
        for k, v in e.cut_mm.items():
            cut[k] = cut.get(k, 0.0) + v
    before = [e.travel_before_mm for e in estimates]
    return JobEstimate(
        cut,
        sum(e.pierces for e in estimates),
        float(sum(e.engrave_area_mm2 for e in estimates)),
        float(sum(e.travel_mm for e in estimates)),
        float(sum(e.seconds for e in estimates)),
        None if None in before else float(sum(before)),
    )
