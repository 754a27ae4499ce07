"""Inlay kits as laser files: ``<name>-lattice.<fmt>`` and ``<name>-pieces.<fmt>``, in registration.

The kit's two cut plans (:func:`fabtiles.geometry.cut_plan.plan_kit`) are written in
any laser format (DXF, SVG, LightBurn ``.lbrn2``), each file with the profile's layers:

- the lattice as a pierced tile (holes cut with the kerf into them, the outline last),
  or with ``base="pocket"`` its holes engraved as pockets on the engrave layer (for
  veneer pieces glued into a solid board) and the outline cut;
- the pieces on the outer-cut layer, each grown by half the kerf so it comes out at its
  nominal size, at its hole's place: cut from a sheet laid like the lattice's, they
  drop out where they belong. The pieces sheet has no outline of its own.

A kit is a multi-file output: :data:`KIT_FILES` names its files' suffixes, and the
build pipeline writes them as it writes any file (staged, both or neither: one format).
"""

from __future__ import annotations

from pathlib import Path

from ..core.files import atomic_write
from ..core.report import Report
from ..geometry.cut_plan import INLAY_BASES, KitPlans, plan_kit  # noqa: F401  (INLAY_BASES: public here too)
from .formats import CUT_FORMATS, FORMATS, format_of

KIT_FORMATS = CUT_FORMATS

KIT_FILES = (("-lattice", "lattice"), ("-pieces", "pieces"))
"""A kit's files: the suffix added to the name, and which of :class:`~fabtiles.geometry.cut_plan.KitPlans`' plans
it holds."""


def kit_paths(path) -> tuple[Path, ...]:
    """``<stem>-lattice<suffix>`` and ``<stem>-pieces<suffix>`` beside ``path``.

    >>> [p.name for p in kit_paths("out/tile.dxf")]
    ['tile-lattice.dxf', 'tile-pieces.dxf']
    """
    path = Path(path)
    return tuple(path.with_name(f"{path.stem}{suffix}{path.suffix}") for suffix, _ in KIT_FILES)


def kit_files(plans: KitPlans, path) -> list:
    """``[(path, plan), ...]``: the kit's files beside ``path`` and the plan each is written from (a kit
    with no piece, its lattice alone: see :meth:`~fabtiles.geometry.cut_plan.KitPlans.files`)."""
    kept = {suffix for suffix, _ in plans.files()}
    return [
        (p, getattr(plans, which))
        for p, (suffix, which) in zip(kit_paths(path), KIT_FILES, strict=True)
        if suffix in kept
    ]


def write_kit(
    path,
    *,
    region,
    outline,
    profile,
    inlay_fit_mm=None,
    inlay_base: str = "pierced",
    kerf_mm=None,
    dxf_version=None,
    stroke=None,
    centrelines=None,
    fill_small_holes=None,
    tab_mm=None,
    tabs_per_part=None,
) -> Report:
    """Write the inlay kit of a tile's material ``region``: the lattice and the pieces files.

    A convenience for scripts (:func:`~fabtiles.geometry.cut_plan.plan_kit`, then both
    files made before either is written, each atomically). ``path`` names the kit
    (``tile.dxf`` writes ``tile-lattice.dxf`` and ``tile-pieces.dxf``); its suffix
    picks the format. The report is the lattice's, with the kit's figures and both
    paths in ``files``. ``centrelines`` and ``fill_small_holes`` are accepted for a
    uniform call: holes too small for a piece are always filled. ``tab_mm`` and
    ``tabs_per_part`` leave holding tabs in the lattice's outline and the pieces' cuts,
    as the design keys of the same names do.
    """
    fmt = format_of(path, allowed=KIT_FORMATS)
    plans = plan_kit(
        region,
        outline,
        profile=profile,
        inlay_fit_mm=inlay_fit_mm,
        inlay_base=inlay_base,
        kerf_mm=kerf_mm,
        dxf_version=dxf_version,
        stroke=stroke,
        path=str(kit_paths(path)[0]),
        fmt=fmt.name,
        tab_mm=tab_mm,
        tabs_per_part=tabs_per_part,
    )
    files = [(p, fmt.bytes_of(plan)) for p, plan in kit_files(plans, path)]  # both made before either is written
    for p, data in files:
        atomic_write(p, data)
    report = plans.report
    report.stats.update(FORMATS[fmt.name].figures(plans.lattice, None), files=[str(p) for p, _ in files])
    return report
