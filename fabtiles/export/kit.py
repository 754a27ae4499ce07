"""Inlay kits as laser files: ``<name>-lattice.<fmt>`` and ``<name>-pieces.<fmt>``, in registration.

The kit (:func:`fabtiles.geometry.inlay.inlay_kit`) is written in any laser format
(DXF, SVG, LightBurn ``.lbrn2``), each file with the profile's layers:

- the lattice as a pierced tile (holes cut with the kerf into them, the outline last),
  or with ``base="pocket"`` its holes engraved as pockets on the engrave layer (for
  veneer pieces glued into a solid board) and the outline cut;
- the pieces on the outer-cut layer, each grown by half the kerf so it comes out at its
  nominal size, at its hole's place: cut from a sheet laid like the lattice's, they
  drop out where they belong. The pieces sheet has no outline of its own.

Both texts are made before either file is written, and both files are written
atomically, so a failing kit leaves no file.
"""

from __future__ import annotations

from pathlib import Path

import shapely

from .._errors import ParameterError
from .._io import atomic_write
from .._profiles import load_profile
from .._report import Report
from .._validate import check_choice
from ..geometry.contours import laser_contours
from ..geometry.inlay import check_fit, inlay_kit
from ..geometry.job_time import estimate
from ..geometry.laser_checks import LaserJob, prepare_laser
from .laser_files import LASER_FILE_FORMATS, laser_bytes

INLAY_BASES = ("pierced", "pocket")
"""How the lattice holds its pieces: holes cut through, or pockets engraved into a board."""

KIT_FORMATS = LASER_FILE_FORMATS


def kit_paths(path) -> tuple[Path, Path]:
    """``<stem>-lattice<suffix>`` and ``<stem>-pieces<suffix>`` beside ``path``.

    >>> [p.name for p in kit_paths("out/tile.dxf")]
    ['tile-lattice.dxf', 'tile-pieces.dxf']
    """
    path = Path(path)
    return path.with_name(f"{path.stem}-lattice{path.suffix}"), path.with_name(f"{path.stem}-pieces{path.suffix}")


def write_kit(path, *, region, outline, profile, inlay_fit_mm=None, inlay_base: str = "pierced", kerf_mm=None,
              dxf_version=None, stroke=None, centrelines=None, fill_small_holes=None) -> Report:
    """Write the inlay kit of a tile's material ``region``: the lattice and the pieces files.

    ``path`` names the kit (``tile.dxf`` writes ``tile-lattice.dxf`` and
    ``tile-pieces.dxf``); its suffix picks the format. ``inlay_fit_mm`` (default: the
    profile's) grows each piece from its hole; ``inlay_base`` is ``"pierced"`` or
    ``"pocket"``. The report is the lattice's, with the kit's figures (``pieces``,
    ``filled_holes``, ``piece_kinds``, both areas, the pieces sheet's ``pieces_job``)
    and both paths in ``kit_files``. ``centrelines`` and ``fill_small_holes`` are
    accepted for a uniform call: holes too small for a piece are always filled.
    """
    profile = load_profile(profile, kind="laser")
    profile.cutter.check_mode(profile, "inlay")  # a router or waterjet cuts no kit
    fmt = Path(path).suffix.lower().lstrip(".")
    if fmt not in KIT_FORMATS:
        raise ParameterError(f"an inlay kit is written as {', '.join(KIT_FORMATS)}, not .{fmt}", param="path")
    base = check_choice("inlay_base", inlay_base, INLAY_BASES)
    fit = check_fit(profile.inlay_fit_mm if inlay_fit_mm is None else inlay_fit_mm)
    lattice_path, pieces_path = kit_paths(path)
    kx, ky = profile.kerf_xy_mm if kerf_mm is None else (kerf_mm, kerf_mm)
    kit = inlay_kit(region, outline, fit_mm=fit, min_piece_mm=profile.min_piece_or_default_mm,
                    kerf_mm=max(kx, ky), tolerance_mm=profile.tolerance_mm)
    if base == "pierced":
        job, report = prepare_laser(lattice_path, fmt, region=kit.lattice, outline=outline, profile=profile,
                                    mode="pierced", dxf_version=dxf_version, kerf_mm=kerf_mm, stroke=stroke)
    else:
        if not len(kit.holes):
            raise ParameterError("the tile has no hole large enough for a piece; nothing to pocket", param="region")
        job, report = prepare_laser(lattice_path, fmt, region=shapely.union_all(kit.holes), outline=outline,
                                    profile=profile, mode="engrave", dxf_version=dxf_version, kerf_mm=kerf_mm)
    pieces_job = _pieces_job(kit, job, profile, kx, ky)
    texts = (laser_bytes(job, fmt), laser_bytes(pieces_job, fmt))  # both made before either is written
    atomic_write(lattice_path, texts[0])
    atomic_write(pieces_path, texts[1])
    report.stats.update(kit.stats(), inlay_fit_mm=fit, inlay_base=base, pieces_job=pieces_job.estimate.as_stats(),
                        kit_files=[str(lattice_path), str(pieces_path)])
    report.stats.setdefault("notes", []).append(
        f"pieces: {pieces_path.name} ({kit.stats()['pieces']:,} pieces of {kit.kinds} shapes, fit {fit:+g} mm, "
        f"{kit.filled_holes:,} holes too small filled); laser job {pieces_job.estimate.line()}")
    return report


def _pieces_job(kit, lattice_job: LaserJob, profile, kx: float, ky: float) -> LaserJob:
    """The pieces sheet: every piece's contours grown by half the kerf.

    It keeps the lattice's bounds, so an SVG (placed by its page) registers with the
    lattice's as a DXF (placed by its coordinates) does.
    """
    job = LaserJob(profile, "pierced", lattice_job.dxf_version, kx)
    if len(kit.pieces):
        job.inner, job.outer = laser_contours(shapely.multipolygons(list(shapely.get_parts(kit.pieces))),
                                              kerf_mm=kx, kerf_y_mm=ky, tolerance_mm=profile.tolerance_mm)
    job.bounds = lattice_job.bounds
    job.estimate = estimate(profile, inner=job.inner, outer=job.outer)
    return job
