"""Nested sheets: tiles of several designs packed onto the cutter's sheets, one file per sheet and format.

Each design's tile is planned once, as the cutter cuts it (its
:class:`~fabtiles.geometry.cut_plan.CutPlan`: every layer, kerf included); its part
is the outer boundary of its cut paths, and :func:`~fabtiles.geometry.nest.nest`
places the copies. A sheet is a cut plan too: each placed copy's paths, every layer,
moved rigidly (turned and translated), so the writers of the format table write it
unchanged, through the pipeline's staging (all files or none):
``<name>-sheet-1.dxf``, ``<name>-sheet-2.dxf``, ...
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
import shapely

from ..core.errors import ParameterError
from ..core.report import Report
from ..core.validate import check_float, check_int
from ..machines import limits as _limits
from .models import BuildOptions

if TYPE_CHECKING:
    from ..geometry.nest import Nesting
    from .pipeline import BuildResult

NEST_SUFFIX = "-sheet-"
"""Nested sheets are ``<name>-sheet-<k>.<format>``, k from 1."""

GAP_EXTRA_MM = 1.0
"""The default gap between the nested parts' cut paths: the kerf (a router's bit) plus this much."""


@dataclass(frozen=True)
class NestedSheets:
    """The cut model of a nest: one plan per sheet (the format table writes each as a file)."""

    plans: tuple
    nesting: Nesting
    report: Report

    def files(self) -> list:
        """``[(suffix, plan), ...]``: ``-sheet-1``, ``-sheet-2``, ..."""
        return [(f"{NEST_SUFFIX}{k + 1}", plan) for k, plan in enumerate(self.plans)]


class _NestModels:
    """A nest's :class:`~fabtiles.making.models.BuildModels`: its sheets are its one cut model."""

    def __init__(self, options: BuildOptions, sheets: NestedSheets, reports):
        self.options = options
        self.cut = sheets
        self._reports = reports

    def model(self, family: str):
        return self.cut

    def reports(self, files=()):
        return list(self._reports)


@dataclass
class NestResult:
    """What :func:`nest_designs` wrote and found: the build's files and reports, the nesting,
    and per sheet its parts (design names), material use and job."""

    build: BuildResult
    nesting: Nesting
    sheets: list = field(default_factory=list)


def part_outline(plan):
    """The outer boundary a cut plan takes on a sheet: its outer cut paths (kerf included) filled.

    When they are several pieces, or a path of another layer lies outside them, the
    convex hull of every path (so every cut of the part stays inside its outline).

    >>> from shapely.geometry import box
    >>> from fabtiles.geometry.cut_plan import CutOptions, plan_cut
    >>> plan = plan_cut(box(0, 0, 40, 40).difference(box(10, 10, 30, 30)), box(0, 0, 40, 40), CutOptions.of(profile="laser-3mm-plywood"))
    >>> [round(v, 3) for v in part_outline(plan).bounds]
    [0.0, 0.0, 40.15, 40.15]
    """  # noqa: E501 - a doctest's lines are as Python prints them
    outer = [shapely.Polygon(r) for r in plan.paths("outer") if len(r) >= 3]
    every = np.concatenate([r for layer in plan.layers for r in layer.paths])
    part = shapely.union_all([p.buffer(0) for p in outer]) if outer else shapely.Polygon()
    if isinstance(part, shapely.Polygon) and not part.is_empty:
        part = shapely.Polygon(part.exterior)
        if shapely.covers(part.buffer(1e-6), shapely.points(every)).all():
            return part
    return shapely.MultiPoint(every).convex_hull


def parse_counts(designs, count: int | None):
    """``[(design, copies), ...]`` from ``[(design, copies or None), ...]`` and the count for all (default 1)."""
    out = []
    default = 1 if count is None else check_int("count", count, low=1, high=10_000)
    for design, n in designs:
        n = default if n is None else check_int(f"count of {design.name}", n, low=1, high=10_000)
        out.append((design, n))
    return out


def sheet_plan(profile, plans, nesting, k, shapes, mode, kerf):
    """The cut plan of sheet ``k``: each placed copy's paths, every layer, moved rigidly."""
    from ..geometry.cut_plan import ROLES, make_plan

    paths: dict = {r: [] for r in ROLES}
    groups: list = []
    engrave_area = 0.0
    parts: list = []
    for i in nesting.on_sheet(k):
        p = nesting.placements[i]
        plan = plans[shapes[i]]
        for layer in plan.layers:
            if layer.fill:  # an engraved fill's groups number its polygons: shifted past the sheet's
                base = 1 + max(groups, default=-1)
                groups.extend(base + g for g in layer.groups)
            paths[layer.role].extend(p.move(r) for r in layer.paths)
        engrave_area += plan.engrave_area_mm2
        if plan.part is not None:
            parts.append(p.place(plan.part))
    w, h = nesting.sheet_mm
    report = Report(path="", format="")
    used = nesting.material_use()[k]
    report.stats.update(
        profile=profile.name, sheet=k + 1, sheet_mm=[w, h], parts=len(nesting.on_sheet(k)), material_use=used
    )
    sheet = make_plan(
        profile,
        mode,
        kerf,
        paths,
        report=report,
        part=shapely.union_all(parts) if parts else None,
        groups=groups,
        engrave_area_mm2=engrave_area,
        bounds=(0.0, 0.0, w, h),
    )
    report.stats["job"] = sheet.estimate.as_stats()
    return sheet


@dataclass(frozen=True)
class NestJob:
    """A nest planned and checked, nothing written: the sheets' cut plans and what is on each.

    Made by :func:`plan_nest`; :func:`nest_designs` writes it into a folder,
    :func:`nest_bytes` as bytes (the web app's downloads).
    """

    model: NestedSheets
    options: BuildOptions
    labels: list
    """``(label, report)`` of each design's cut plan (its findings)."""
    designs: list
    """``[(design, copies), ...]``."""
    shapes: list
    """Per part (in the nesting's order), the index of its design."""
    formats: tuple
    stem: str

    @property
    def nesting(self):
        return self.model.nesting

    def sheets(self) -> list[dict]:
        """Per sheet: its number, parts, each design's copies, material use, job and files."""
        nesting, out = self.model.nesting, []
        for k, plan in enumerate(self.model.plans):
            names = [self.designs[self.shapes[i]][0].name for i in nesting.on_sheet(k)]
            out.append(
                dict(
                    sheet=k + 1,
                    parts=len(names),
                    designs={n: names.count(n) for n in dict.fromkeys(names)},
                    material_use=nesting.material_use()[k],
                    job=plan.estimate.as_stats(),
                    files=[f"{self.stem}{NEST_SUFFIX}{k + 1}.{fmt}" for fmt in self.formats],
                )
            )
        return out

    def picture(self, k: int) -> str:
        """Sheet ``k`` (0-based) drawn: the sheet, each part's outline named, every cut path."""
        from ..export.preview_svg import nested_sheet_svg

        nesting = self.model.nesting
        on = nesting.on_sheet(k)
        parts = [(self.designs[self.shapes[i]][0].name, nesting.outlines[i]) for i in on]
        return nested_sheet_svg(
            self.model.plans[k],
            parts,
            nesting.sheet_mm,
            title=f"sheet {k + 1}: {len(on)} part{'s' if len(on) != 1 else ''}, "
            f"material use {nesting.material_use()[k]:.0%}",
        )


def plan_nest(
    designs,
    formats=("dxf",),
    *,
    count: int | None = None,
    sheet_mm=None,
    gap_mm: float | None = None,
    rotations: str = "90",
    time_s: float | None = None,
    name: str | None = None,
    progress=None,
    limits: _limits.Limits = _limits.CLI_LIMITS,
) -> NestJob:
    """Nest tiles of ``designs`` onto sheets: each sheet's cut plan, checked, nothing written.

    The parameters and errors are :func:`nest_designs`'s (which writes the job).
    """
    from ..geometry.nest import nest

    designs, time_s = _counted(designs, count, time_s, limits)
    cut = _cut_formats(formats)
    options = _nest_options(designs, cut)
    profile = options[0].cutter
    w, h = _sheet_size(sheet_mm, profile)
    tiles = _tiles(designs, limits)
    from .models import Models

    # each design's tile one part: one larger than the bed is refused as before, not cut as pieces
    plans = [Models(t, replace(o, pieces=False)).cut for t, o in zip(tiles, options, strict=True)]
    kerf = max(p.kerf_mm for p in plans)
    gap = gap_between(gap_mm, kerf, profile)
    _check_rotations(rotations, plans, profile)
    outlines = [part_outline(p) for p in plans]
    parts, shapes = _parts(designs, outlines)
    nesting = nest(parts, sheet_mm=(w, h), gap_mm=gap, rotations=rotations, time_s=time_s, progress=progress)
    mode = plans[0].mode
    sheets = tuple(sheet_plan(profile, plans, nesting, k, shapes, mode, kerf) for k in range(nesting.sheets))
    report = Report(path="", format="")
    report.stats.update(
        profile=profile.name,
        sheets=nesting.sheets,
        sheet_mm=[w, h],
        gap_mm=gap,
        rotations=rotations,
        parts=len(parts),
        material_use=list(nesting.material_use()),
    )
    labels = [(f"{profile.kind} {profile.name}: {d.name}", p.report) for (d, _), p in zip(designs, plans, strict=True)]
    stem = name if name is not None else default_stem([d for d, _ in designs])
    return NestJob(NestedSheets(sheets, nesting, report), options[0], labels, designs, shapes, cut, stem)


def _counted(designs, count, time_s, limits: _limits.Limits) -> tuple[list, float]:
    """The designs with their counts and the nest's time, checked against the limits."""
    from ..geometry.nest import default_time_s

    if not designs:
        raise ParameterError("give at least one design to nest", param="designs")
    designs = parse_counts(designs, count)
    parts = sum(n for _, n in designs)
    time_s = default_time_s(parts) if time_s is None else check_float("time_s", time_s, low=0, low_open=True)
    _limits.check_nest(sum(n for _, n in designs), time_s, limits)
    return designs, time_s


def _cut_formats(formats) -> tuple:
    """The nest's formats: those the table says nest, only."""
    from ..export.formats import names_where

    formats = tuple(dict.fromkeys(formats))
    nests = names_where(nests=True)
    cut = tuple(f for f in formats if f in nests)
    if len(cut) < len(formats) or not cut:
        raise ParameterError(
            f"nested sheets are written in the cutter formats ({', '.join(nests)}) only, got "
            f"{', '.join(formats) or 'none'}; use --format {', '.join(nests[:-1])} or {nests[-1]}",
            param="formats",
        )
    return cut


def _tiles(designs, limits: _limits.Limits) -> list:
    """Each design's tile, the nest's segments checked against the limits."""
    from .pipeline import prepare_tile

    tiles = [prepare_tile(d, limits=limits) for d, _ in designs]
    _limits.check_segments(
        sum(len(t.segments()) * n for t, (_, n) in zip(tiles, designs, strict=True)),
        limits,
        what=f"the nest of {sum(n for _, n in designs)} tiles",
    )
    return tiles


def _nest_options(designs, cut) -> list:
    """Each design's build options, checked for a nest: one cutter profile, no inlay kit, formats it takes."""
    from ..export.formats import FORMATS

    options = [BuildOptions.of_design(d) for d, _ in designs]
    profile = options[0].cutter
    for (d, _), o in zip(designs, options, strict=True):
        if o.cutter.name != profile.name:
            raise ParameterError(
                f"every nested design must use one cutter profile (one material): "
                f"{designs[0][0].name} uses {profile.name!r}, {d.name} uses {o.cutter.name!r}; "
                f"set [output] laser_profile alike",
                param="laser_profile",
            )
        if o.kit:
            raise ParameterError(
                f'{d.name} is an inlay kit (laser_mode = "inlay"), which is not nested; '
                f'choose laser_mode = "pierced", "score" or "engrave"',
                param="laser_mode",
            )
        for fmt in cut:  # the cutter's kind allows the format (a LightBurn project is for lasers)
            FORMATS[fmt].check_cutter(o.cutter)
    return options


def _sheet_size(sheet_mm, profile) -> tuple[float, float]:
    """The sheet's width and height in mm, checked to fit the bed (None: the bed's)."""
    bed_w, bed_h = profile.bed_mm
    if sheet_mm is None:
        sheet_mm = (bed_w, bed_h)
    if not isinstance(sheet_mm, (list, tuple)) or len(sheet_mm) != 2:
        raise ParameterError(f"sheet_mm must be (width, height) in mm, got {sheet_mm!r}", param="sheet_mm")
    w = check_float("sheet width", sheet_mm[0], low=0, low_open=True)
    h = check_float("sheet height", sheet_mm[1], low=0, low_open=True)
    if w > bed_w + 1e-9 or h > bed_h + 1e-9:
        raise ParameterError(
            f"the sheet {w:g} x {h:g} mm is larger than the {bed_w:g} x {bed_h:g} mm bed of "
            f"{profile.kind} profile {profile.name!r}; use a sheet of at most the bed "
            f"(--sheet {bed_w:g}x{bed_h:g})",
            param="sheet_mm",
        )
    return w, h


def gap_between(gap_mm, kerf: float, profile) -> float:
    """The gap between parts in mm, checked to keep two parts' cuts apart (None: the cut's width and a margin)."""
    least = max(kerf, 2 * profile.tool_radius_mm)  # a router's bit must pass between two parts
    gap = least + GAP_EXTRA_MM if gap_mm is None else check_float("gap_mm", gap_mm)
    if gap < least:
        raise ParameterError(
            f"gap_mm must be >= the cut's width ({least:g} mm, the kerf of {profile.kind} "
            f"profile {profile.name!r}) so the cuts of two parts stay apart, got {gap:g}; "
            f"use --gap {least + GAP_EXTRA_MM:g}",
            param="gap_mm",
        )
    return gap


def _check_rotations(rotations: str, plans, profile) -> None:
    """Refuse quarter turns when the cutter's kerf along Y differs from along X (a quarter turn swaps them)."""
    turns = rotations in ("90", "free")
    if turns and any("kerf_y_mm" in p.report.stats for p in plans):
        raise ParameterError(
            f"{profile.kind} profile {profile.name!r} has a kerf along Y unlike along X "
            f"(kerf_x_mm, kerf_y_mm): a part turned by a quarter would be cut to the wrong size; "
            f"use --rotate 180 or --rotate none, got {rotations!r}",
            param="rotations",
        )


def _parts(designs, outlines) -> tuple[list, list]:
    """The nest's parts, ``[(name, outline), ...]``, each design's copies in turn, and each part's design index."""
    parts, shapes = [], []
    for k, ((d, n), outline) in enumerate(zip(designs, outlines, strict=True)):
        for c in range(n):
            parts.append((f"{d.name}#{k}:{c + 1}", outline))
            shapes.append(k)
    return parts, shapes


def default_stem(designs) -> str:
    """The nested files' stem when none is given: the design's name when all parts are of one design,
    else ``nest`` (a sheet holding several designs is named after none of them).

    >>> from types import SimpleNamespace as D
    >>> default_stem([D(name="rosette")]), default_stem([D(name="a"), D(name="b")])
    ('rosette', 'nest')
    """
    names = {d.name for d in designs}
    return names.pop() if len(names) == 1 else "nest"


def nest_designs(
    designs,
    outdir,
    formats=("dxf",),
    *,
    count: int | None = None,
    sheet_mm=None,
    gap_mm: float | None = None,
    rotations: str = "90",
    time_s: float | None = None,
    name: str | None = None,
    progress=None,
    limits: _limits.Limits = _limits.CLI_LIMITS,
) -> NestResult:
    """Nest tiles of ``designs`` onto sheets and write ``OUTDIR/<name>-sheet-<k>.<format>``, each format on its own.

    Parameters
    ----------
    designs : list of (Design, int or None)
        Each design and its copies (``None``: ``count``).
    outdir : str or Path
        Output folder.
    formats : iterable of str
        Cutter formats (``dxf``, ``svg``, ``lbrn2``).
    count : int, optional
        Copies of each design whose own count is ``None`` (>= 1; default 1).
    sheet_mm : (float, float), optional
        The sheet; default the cutter profile's bed; larger than the bed is an error.
    gap_mm : float, optional
        Least distance between two parts' cut paths (>= the kerf, or a router's bit);
        default that + 1 mm.
    rotations, time_s, progress
        As :func:`~fabtiles.geometry.nest.nest` (``time_s`` default 5 s).
    name : str, optional
        The files' stem; default :func:`default_stem`: the design's name, or ``nest`` for several.
    limits : Limits
        The work limits (segments, parts, time).

    Raises
    ------
    FabtilesError
        With nothing written: a count < 1, designs of different cutter profiles, an
        inlay kit, a print format, a gap below the kerf, a sheet larger than the bed,
        a part larger than the sheet, a job over the limits. A format its writer
        refuses is in ``result.build.refused``, the others written (see
        :func:`~fabtiles.making.pipeline.write_files`).
    """
    from .pipeline import write_files

    job = plan_nest(
        designs,
        formats,
        count=count,
        sheet_mm=sheet_mm,
        gap_mm=gap_mm,
        rotations=rotations,
        time_s=time_s,
        name=name,
        progress=progress,
        limits=limits,
    )
    result = write_files(_NestModels(job.options, job.model, job.labels), job.formats, outdir, job.stem)
    return NestResult(result, job.nesting, job.sheets())


@dataclass(frozen=True)
class NestedFiles:
    """A nest's files as bytes (:func:`nest_bytes`): ``files`` is ``[(file name, bytes), ...]``."""

    job: NestJob
    files: list

    def zip_bytes(self) -> bytes:
        """Every file in one zip archive, in sheet order."""
        import io
        import zipfile

        from ..core.files import zip_entry

        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
            for fname, data in self.files:
                zf.writestr(zip_entry(fname), data, compress_type=zipfile.ZIP_DEFLATED)
        return buf.getvalue()


def nest_bytes(designs, formats=("dxf",), **options) -> NestedFiles:
    """Nest tiles of ``designs`` as :func:`nest_designs` does, and make the files as bytes (no folder).

    Takes :func:`nest_designs`'s keyword ``options`` but ``outdir``; the files are
    the same writers' (``<name>-sheet-<k>.<format>``), for the web app's downloads.
    """
    from ..export.formats import FORMATS, FileOptions

    job = plan_nest(designs, formats, **options)
    opts = FileOptions(name=job.stem, layout=job.options.threemf_layout, dxf_version=job.options.dxf_version)
    files = [
        (f"{job.stem}{suffix}.{fmt}", FORMATS[fmt].write(plan, opts))
        for fmt in job.formats
        for suffix, plan in FORMATS[fmt].files(job.model)
    ]
    return NestedFiles(job, files)
