"""Work limits, checked before work starts so no request or design can hang.

The numbers are estimates from the pattern's parameters alone (no geometry is
built): the count of centre-line segments a tile will hold, and its size.

>>> lim = Limits(max_segments=100, max_size_mm=500)
>>> check_size(600, 400, lim)
Traceback (most recent call last):
...
fabtiles.core.errors.LimitError: the tile is 600 x 400 mm, larger than the limit of 500 mm on a side; make it smaller
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.errors import LimitError
from ..core.report import distinct


@dataclass(frozen=True)
class Limits:
    """Largest job accepted: segments before clipping, tile side in mm, the same for STEP, and a nest's
    parts and packing time (seconds)."""

    max_segments: int = 400_000
    max_size_mm: float = 3000.0
    max_step_segments: int = 60_000
    max_nest_parts: int = 5_000
    max_nest_time_s: float = 3600.0


CLI_LIMITS = Limits()
"""Limits of ``fabtiles build``: a 1,200 x 600 mm sheet fits with room to spare."""

WEB_LIMITS = Limits(max_segments=200_000, max_step_segments=30_000, max_nest_parts=60, max_nest_time_s=10.0)
"""Limits of the web app: every request answers in seconds. The work is bounded by the segments; the
size limit is the command line's (:data:`CLI_LIMITS`), so a design the CLI builds is never refused
here for its size alone."""


def check_size(width_mm: float, height_mm: float, limits: Limits) -> None:
    """Refuse a tile larger than ``limits.max_size_mm`` on either side."""
    if max(width_mm, height_mm) > limits.max_size_mm:
        raise LimitError(
            f"the tile is {distinct(width_mm, limits.max_size_mm)} x {distinct(height_mm, limits.max_size_mm)} mm, "
            "larger than the limit of "
            f"{limits.max_size_mm:g} mm on a side; make it smaller",
            param="tile.size",
        )


def estimate_segments(pattern, width_mm: float, height_mm: float) -> int:
    """Centre-line segments a pattern will put on a ``width x height`` tile (an upper estimate).

    >>> from fabtiles.pattern.star import Star
    >>> estimate_segments(Star(n=8, radii=(1, 2)), 100, 100)
    16
    """
    if hasattr(pattern, "segment_count"):  # counts its own motifs per polygon kind
        return pattern.segment_count((-width_mm / 2, -height_mm / 2, width_mm / 2, height_mm / 2))
    motif = getattr(pattern, "motif", None)
    if motif is None:  # a single Star
        return len(pattern.segments())
    # Counting the circles is cheap (numpy on the lattice, no motif is placed).
    _, radii = pattern.circles((-width_mm / 2, -height_mm / 2, width_mm / 2, height_mm / 2))
    big = int(np.count_nonzero(radii >= pattern.radius * (1 - 1e-9)))
    gap = len(radii) - big
    per_big = len(motif.segments())
    gap_motif = getattr(pattern, "gap_motif", None)
    per_gap = len(gap_motif.segments()) if gap_motif is not None else 0
    if getattr(pattern, "outline_circles", False):
        per_big, per_gap = per_big + 256, per_gap + 64  # flattened circles: generous upper bound
    return big * per_big + gap * per_gap


def check_segments(count: int, limits: Limits, *, what: str = "the tile", knob: str = "radius") -> None:
    """Refuse more than ``limits.max_segments`` segments; ``knob`` is the packing's scale
    (``radius``, or ``edge`` for an Archimedean tiling)."""
    if count > limits.max_segments:
        raise LimitError(
            f"{what} would hold about {count:,} segments, more than the limit of "
            f"{limits.max_segments:,}; make the tile smaller, the packing {knob} larger, or n smaller",
            param=f"packing.{knob}",  # the usual knob
        )


def check_tile(pattern, width_mm: float, height_mm: float, limits: Limits) -> int:
    """Check size and segment count before any geometry is built; return the estimate."""
    check_size(width_mm, height_mm, limits)
    count = estimate_segments(pattern, width_mm, height_mm)
    check_segments(count, limits, knob="edge" if hasattr(pattern, "edge") else "radius")
    return count


def check_export(tile, what: str, limit: str, limits: Limits) -> None:
    """A format's own, lower segment limit: ``limits``' field ``limit`` (STEP is slow on huge solids).

    ``what`` names the format in the message (``"STEP"``).
    """
    count = estimate_segments(tile.pattern, tile.width_mm, tile.height_mm)
    most = getattr(limits, limit)
    if count > most:
        raise LimitError(
            f"{what} export of about {count:,} segments is over the limit of {most:,}; "
            "export STL or 3MF, or a smaller tile"
        )


def check_nest(parts: int, time_s: float, limits: Limits) -> None:
    """Refuse a nest of more than ``limits.max_nest_parts`` parts or a packing time over ``limits.max_nest_time_s``.

    >>> check_nest(61, 5, WEB_LIMITS)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.LimitError: the nest has 61 parts, more than the limit of 60; nest fewer copies
    """
    if parts > limits.max_nest_parts:
        raise LimitError(
            f"the nest has {parts:,} parts, more than the limit of {limits.max_nest_parts:,}; nest fewer copies",
            param="count",
        )
    if time_s > limits.max_nest_time_s:
        raise LimitError(
            f"time_s must be at most {limits.max_nest_time_s:g} s here, got {time_s:g}; "
            f"give a time of at most {limits.max_nest_time_s:g}",
            param="time_s",
        )
