"""Write the laser test card (:mod:`fabtiles.geometry.calibration`) as DXF or SVG.

The card goes through the tile writers' own pieces: kerf-compensated closed
contours in cut order (inner first, see :func:`~fabtiles.geometry.contours.laser_contours`)
on the profile's cut layers, the size labels as open polylines on its score layer,
and the DXF and SVG text of :mod:`fabtiles.export.dxf` and :mod:`fabtiles.export.laser_svg`.
The card is not checked like a tile: its part inside the window is loose and its
smallest features are under the limits on purpose.

>>> import tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "card.svg"
>>> report = write_card(out, "laser-3mm-plywood")
>>> report.stats["features"], report.stats["inner_contours"]
(24, 31)
"""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from ..core.files import atomic_write
from ..core.report import Report
from ..geometry.calibration import calibration_card
from ..geometry.contours import laser_contours
from ..geometry.cut_plan import make_plan
from ..machines.profiles import load_profile


def card_job(profile):
    """The card of ``profile`` as a :class:`~fabtiles.geometry.cut_plan.CutPlan`, and the card."""
    profile = load_profile(profile, kind="laser")
    profile.cutter.check_card(profile)  # its rows measure a kerf, bridges and holes as a laser burns them
    card = calibration_card(profile)
    kx, ky = profile.kerf_xy_mm
    inner, outer = laser_contours(
        card.region, card.outline, kerf_mm=kx, kerf_y_mm=ky, tolerance_mm=profile.tolerance_mm
    )
    score = [np.asarray(p, dtype=float) for p in card.labels]
    return make_plan(profile, "pierced", kx, {"inner": inner, "outer": outer, "score": score}), card


def write_card(path, profile, *, dxf_version=None) -> Report:
    """Write the test card of a laser profile to ``path`` (``.dxf`` or ``.svg``), atomically.

    ``dxf_version``: a DXF card's version (default: the profile's). Returns a
    :class:`~fabtiles.core.report.Report` whose stats give the card's size,
    its features and contour counts.
    """
    from pathlib import Path

    from .formats import FORMATS, FileOptions, names_where

    rows = [FORMATS[n] for n in names_where(card=True)]  # the format table's formats of the card
    suffix = Path(path).suffix.lower()
    fmt = next((f for f in rows if f.suffix == suffix), None)
    if fmt is None:
        raise ParameterError(f"the card must be a {' or '.join(f.suffix for f in rows)} file, got {str(path)!r}")
    job, card = card_job(profile)  # a profile that cannot cut the card is named before the version
    options = FileOptions(dxf_version=dxf_version)
    atomic_write(path, fmt.bytes_of(job, options))
    report = Report(path=str(path), format=fmt.name)
    report.stats.update(
        profile=job.profile.name,
        kerf_mm=job.kerf_mm,
        size_mm=[card.width_mm, card.height_mm],
        features=len(card.features),
        inner_contours=len(job.paths("inner")),
        outer_contours=len(job.paths("outer")),
        score_paths=len(job.paths("score")),
    )
    return report
