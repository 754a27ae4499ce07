"""A panel larger than the cutter's bed, cut as pieces that lock together: the pieces model.

When a tile's outline fits its cutter profile's bed neither way round (and the design's
``[output] pieces`` is on, the default), its cut model is a :class:`PanelPieces`: the
material the cutter keeps (:func:`~fabtiles.geometry.machine_geometry.cut_geometry`, nominal,
before the kerf; the whole plate in the score and engrave modes) split by
:func:`~fabtiles.geometry.pieces.split_panel` on the pattern's period, the joints sized from
the profile's ``thickness_mm``, kerf, ``joint_fit_mm`` and its tool's radius. Each piece is
laid on the bed (:func:`~fabtiles.geometry.pieces.laid_on_bed`) and made into its own
:class:`~fabtiles.geometry.cut_plan.CutPlan` by the same :func:`~fabtiles.geometry.cut_plan.plan_cut`
as any tile (kerf, checks, layers, order, job time), its number scored on it where the text
fits inside the material (a laser's score layer). :meth:`PanelPieces.files` gives one plan per
piece, ``-piece-01``, ``-piece-02``, ..., so every cutter format writes them with no change;
the build adds the assembly drawing and manifest (:mod:`fabtiles.export.assembly`).

The model names no machine beyond its profile: a printer's pieces can be the same
``(number, cell, matrix, region)`` records, and the same manifest and drawing describe them.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
import shapely

from ..core.errors import FabricationError, ParameterError
from ..core.report import Report

if TYPE_CHECKING:
    from ..geometry.cut_plan import CutPlan
    from ..geometry.pieces import PanelSplit
    from ..machines.profiles import CutterProfile

PIECE_SUFFIX = "-piece-"
"""A piece's file is ``<name>-piece-01.<format>``, numbered from 1 at the top left along the rows."""

ASSEMBLY_SUFFIX = "-assembly"
"""The assembly drawing and manifest: ``<name>-assembly.svg`` and ``<name>-assembly.json``."""

NEST_TIME_S = 2.0
"""The packer's time budget when a panel's pieces are nested onto sheets, seconds."""

LABEL_HEIGHTS_MM = (12.0, 8.0, 6.0, 4.0, 3.0)
"""The heights a piece's number is tried at, largest first (a laser's score reads from 3 mm up)."""


def piece_suffix(number: int, count: int) -> str:
    """The suffix of piece ``number`` of ``count``: two digits at least, as many as the count needs.

    >>> piece_suffix(3, 8), piece_suffix(7, 100)
    ('-piece-03', '-piece-007')
    """
    return f"{PIECE_SUFFIX}{number:0{max(2, len(str(count)))}d}"


@dataclass(frozen=True)
class CutPiece:
    """One piece of a panel: its number, its cell (column, row from the bottom), its plan, the 3 x 3
    matrix (mm) carrying its file's coordinates to the panel's, its region in the panel, and where
    its number is scored (file coordinates, with the text's height), None where none fits."""

    number: int
    cell: tuple[int, int]
    plan: CutPlan
    matrix: np.ndarray
    region: shapely.Geometry
    label: tuple[float, float, float] | None

    @property
    def size_mm(self) -> tuple[float, float]:
        """The piece's extents in its file (its material, before the kerf)."""
        x0, y0, x1, y1 = shapely.transform(self.region, _apply(np.linalg.inv(self.matrix))).bounds
        return (x1 - x0, y1 - y0)


@dataclass(frozen=True)
class PanelPieces:
    """A panel cut as pieces (see the module text): the split, the pieces in number order, the
    congruent groups, the panel's outline, its profile and one report for them all."""

    split: PanelSplit
    pieces: tuple[CutPiece, ...]
    groups: tuple[tuple[int, ...], ...]
    outline: shapely.Geometry
    profile: CutterProfile
    report: Report
    sheets: tuple = ()
    """The pieces nested onto bed-sized sheets (``[output] pieces_sheets``): a cut plan per sheet."""

    def files(self) -> list:
        """``[(suffix, plan), ...]``: ``-piece-01``, ``-piece-02``, ... (see :func:`piece_suffix`), then the
        nested sheets' ``-sheet-1``, ``-sheet-2``, ... when they were asked for."""
        from .nesting import NEST_SUFFIX

        pieces = [(piece_suffix(p.number, len(self.pieces)), p.plan) for p in self.pieces]
        return pieces + [(f"{NEST_SUFFIX}{k + 1}", plan) for k, plan in enumerate(self.sheets)]

    @property
    def panel_mm(self) -> tuple[float, float]:
        """The panel's width and height (its outline's extents)."""
        x0, y0, x1, y1 = self.outline.bounds
        return (x1 - x0, y1 - y0)

    @property
    def joints(self) -> tuple:
        """The split's joints (:class:`~fabtiles.geometry.pieces.PlacedJoint`)."""
        return self.split.joints


def _apply(m: np.ndarray):
    """A function for :func:`shapely.transform` applying the 3 x 3 matrix ``m`` to points."""
    return lambda xy: xy @ m[:2, :2].T + m[:2, 2]


def too_big(outline, profile) -> bool:
    """Whether ``outline`` fits the bed of ``profile`` neither way round."""
    from ..geometry.laser_checks import fits_bed

    x0, y0, x1, y1 = outline.bounds
    return not fits_bed(x1 - x0, y1 - y0, profile.bed_mm)


def split_for_cutter(tile, region, profile, *, mode: str, kerf_mm: float):
    """The :class:`~fabtiles.geometry.pieces.PanelSplit` of ``tile`` for the bed of the cutter ``profile``:
    its joint from the profile, seams on the pattern's period; ``region`` is the cutter's material
    (a scored or engraved plate, ``mode`` other than pierced, is all material). Raises as
    :func:`pieces_model`."""
    from ..geometry.pieces import joint_for, split_panel

    kind = profile.cutter
    outline = tile.outline_shape()
    material = region if mode == "pierced" else outline
    joint = joint_for(
        profile.joint,
        thickness_mm=profile.thickness_or_default_mm,
        kerf_mm=kerf_mm,
        fit_mm=profile.joint_fit_mm,
        corner_mm=kind.joint_corner_mm(profile),
    )
    kind.check_joint(profile, joint.neck_mm)
    period, origin = pattern_period(tile)
    try:
        return split_panel(
            material,
            bed_mm=profile.bed_mm,
            margin_mm=profile.margin_mm,
            joint=joint,
            min_feature_mm=profile.min_feature_mm,
            period_mm=period,
            origin=origin,
        )
    except ParameterError as exc:  # the bed too small for a piece, or too many pieces: say which tile and bed
        x0, y0, x1, y1 = outline.bounds
        bw, bh = profile.bed_mm
        raise ParameterError(
            f"the tile is {x1 - x0:g} x {y1 - y0:g} mm, larger than the {bw:g} x {bh:g} mm bed of {profile.kind} "
            f"profile {profile.name!r}, and cannot be cut as pieces: {exc}",
            param=exc.param,
        ) from None


def pieces_model(tile, region, centrelines, profile, cut_options) -> PanelPieces:
    """The :class:`PanelPieces` of ``tile`` too big for the bed of the cutter ``profile``.

    ``region`` and ``centrelines`` are the cutter's (:attr:`~fabtiles.making.models.Models.cut_region`),
    ``cut_options`` the checked :class:`~fabtiles.geometry.cut_plan.CutOptions` every piece is planned
    with. Raises :class:`~fabtiles.FabricationError` where two neighbours can be joined nowhere and
    :class:`~fabtiles.ParameterError` for a bed too small for a piece and its joints, or a panel of
    more pieces than :data:`~fabtiles.geometry.pieces.MAX_PIECES`.
    """
    from ..geometry.pieces import congruent_groups, laid_on_bed

    kind = profile.cutter
    outline = tile.outline_shape()
    mode = cut_options.mode
    split = split_for_cutter(tile, region, profile, mode=mode, kerf_mm=max(cut_options.kerf_mm, cut_options.kerf_y_mm))
    marks = "score" in kind.modes  # a laser scores the numbers; a router or waterjet has no score layer
    pieces = []
    for piece in split.pieces:
        laid, to_panel = laid_on_bed(piece.region, profile.bed_mm, margin_mm=profile.margin_mm)
        to_file = np.linalg.inv(to_panel)
        piece_outline = _outline_of(laid)
        piece_region = (
            laid if mode == "pierced" else shapely.intersection(shapely.transform(region, _apply(to_file)), laid)
        )
        lines = None
        if centrelines is not None and len(centrelines):
            lines = (np.asarray(centrelines, float) @ to_file[:2, :2].T) + to_file[:2, 2]
        label = _label_spot(laid, piece.number, profile.min_feature_mm) if marks else None
        text = _label_paths(piece.number, label) if label is not None else []
        plan = _plan(piece_region, piece_outline, cut_options, lines, text, piece.number)
        shift = np.eye(3)
        shift[:2, 2] = -np.asarray(plan.offset)  # the plan moved the paths by its offset into the file
        matrix = to_panel @ shift
        if label is not None:
            label = (label[0] + plan.offset[0], label[1] + plan.offset[1], label[2])
        pieces.append(CutPiece(piece.number, piece.cell, plan, matrix, piece.region, label))
    groups = tuple(tuple(g) for g in congruent_groups(split.pieces))
    report = _report(split, pieces, groups, outline, profile, marks)
    return PanelPieces(split, tuple(pieces), groups, outline, profile, report)


def with_sheets(model: PanelPieces, *, time_s: float = NEST_TIME_S) -> PanelPieces:
    """``model`` with its pieces also nested onto sheets of the bed's size less its margin, as
    ``fabtiles nest`` nests tiles (:mod:`.nesting`): quarter turns, the cut's width and a margin apart,
    within ``time_s`` seconds of packing; the report says how many sheets."""
    from ..geometry.nest import nest
    from .nesting import gap_between, part_outline, sheet_plan

    profile = model.profile
    plans = [p.plan for p in model.pieces]
    kerf = max(p.kerf_mm for p in plans)
    m = profile.margin_mm
    bw, bh = profile.bed_mm
    parts = [(p.number, part_outline(p.plan)) for p in model.pieces]
    nesting = nest(parts, sheet_mm=(bw - 2 * m, bh - 2 * m), gap_mm=gap_between(None, kerf, profile), time_s=time_s)
    mode = plans[0].mode
    shapes = list(range(len(plans)))
    sheets = tuple(sheet_plan(profile, plans, nesting, k, shapes, mode, kerf) for k in range(nesting.sheets))
    use = ", ".join(f"{u:.0%}" for u in nesting.material_use())
    report = model.report.extended(
        notes=[
            f"nested onto {nesting.sheets} sheet{'s' if nesting.sheets != 1 else ''} of the bed (material use {use})"
        ],
        nested_sheets=nesting.sheets,
    )
    return replace(model, sheets=sheets, report=report)


def pattern_period(tile):
    """The pattern's rectangular period and a lattice point of it (panel mm), or ``(None, (0, 0))``."""
    period = getattr(getattr(tile, "pattern", None), "period", None)
    if not isinstance(period, tuple):
        return None, (0.0, 0.0)
    return (float(period[0]), float(period[1])), tuple(float(v) for v in tile.centre)


def _outline_of(region):
    """A piece's outline: each of its parts without its holes."""
    return shapely.union_all([shapely.Polygon(p.exterior) for p in shapely.get_parts(region)])


def _plan(region, outline, cut_options, lines, marks, number: int):
    """One piece's cut plan; a strict profile's findings name the piece."""
    from ..geometry.cut_plan import plan_cut

    try:
        return plan_cut(region, outline, cut_options, centrelines=lines, marks=marks)
    except FabricationError as exc:
        raise FabricationError(f"piece {number}: {exc}") from None


def _label_spot(region, number: int, min_mm: float):
    """Where piece ``number``'s number fits inside ``region`` with ``min_mm`` of material round it:
    ``(x, y, height)``, the text's middle and baseline, or None.

    Tried at each of :data:`LABEL_HEIGHTS_MM`, largest first: the text's box grown by ``min_mm``
    placed on a grid over the piece (a quarter of the text's smaller side apart), the place
    nearest the piece's middle where the box lies in the material. Boxes tested all at once
    against the prepared region: eroding a lattice of thousands of holes took minutes.
    """
    from ..geometry.stroke_font import text_width

    text = str(number)
    shapely.prepare(region)
    x0, y0, x1, y1 = region.bounds
    middle = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    for h in LABEL_HEIGHTS_MM:
        w = text_width(text, height_mm=h)
        hw, hh = w / 2 + min_mm, h / 2 + min_mm
        step = max(0.5, min(w, h) / 4)
        gx, gy = np.meshgrid(np.arange(x0 + hw, x1 - hw + 1e-9, step), np.arange(y0 + hh, y1 - hh + 1e-9, step))
        xy = np.column_stack([gx.ravel(), gy.ravel()])
        xy = xy[shapely.contains_xy(region, xy[:, 0], xy[:, 1])]
        if not len(xy):
            continue
        fits = shapely.contains(region, shapely.box(xy[:, 0] - hw, xy[:, 1] - hh, xy[:, 0] + hw, xy[:, 1] + hh))
        if fits.any():
            best = xy[fits][np.argmin(np.linalg.norm(xy[fits] - middle, axis=1))]
            return (float(best[0]), float(best[1] - h / 2), h)
    return None


def _label_paths(number: int, label) -> list:
    from ..geometry.stroke_font import text_paths

    x, y, h = label
    return text_paths(str(number), height_mm=h, x=x, y=y, centre=True)


def _report(split, pieces, groups, outline, profile, marks: bool) -> Report:
    """The pieces' one report: what the split made, the largest piece against the bed, the jobs and
    material summed, and each piece's findings (named, located in the panel)."""
    report = Report(path="", format="")
    first = pieces[0].plan.report.stats
    report.stats.update({k: first[k] for k in ("profile", "mode", "kerf_mm", "kerf_y_mm", "cutter") if k in first})
    report.stats.update(_figures(split, pieces, groups, outline, profile))
    _notes(report, split, pieces, groups, profile, marks)
    for p in pieces:
        _add_findings(report, p)
    return report


def _summed_job(pieces):
    """The pieces' jobs as one: lengths, pierces, travel and time added."""
    from ..geometry.job_time import JobEstimate

    jobs = [p.plan.estimate for p in pieces]
    cut: dict = {}
    for j in jobs:
        for k, v in j.cut_mm.items():
            cut[k] = cut.get(k, 0.0) + v
    return JobEstimate(
        cut,
        sum(j.pierces for j in jobs),
        sum(j.engrave_area_mm2 for j in jobs),
        sum(j.travel_mm for j in jobs),
        sum(j.seconds for j in jobs),
    )


def _figures(split, pieces, groups, outline, profile) -> dict:
    """The report's figures of the split: the panel, grid, seams, joints, largest piece, material, job."""
    x0, y0, x1, y1 = outline.bounds
    joint = split.joint
    sizes = {p.number: p.size_mm for p in pieces}
    largest = max(pieces, key=lambda p: sizes[p.number][0] * sizes[p.number][1])
    area = sum(float(p.plan.report.stats.get("area_mm2", 0.0)) for p in pieces)
    sheet_m2 = sum(w * h for w, h in sizes.values()) / 1e6
    cost = None if profile.price_per_m2 is None else round(sheet_m2 * profile.price_per_m2, 4)
    figures = dict(
        panel_mm=[round(x1 - x0, 3), round(y1 - y0, 3)],
        pieces=len(pieces),
        grid=list(split.grid),
        seams_x=[round(v, 3) for v in split.seams_x],
        seams_y=[round(v, 3) for v in split.seams_y],
        joints=len(split.joints),
        joint=joint.figures(),
        largest_piece=largest.number,
        largest_piece_mm=[round(v, 3) for v in sizes[largest.number]],
        bed_mm=list(profile.bed_mm),
        bed_margin_mm=profile.margin_mm,
        congruent=[list(g) for g in groups],
        area_mm2=round(area, 3),
        sheet={"sheet_m2": round(sheet_m2, 6), "cost": cost},
        job=_summed_job(pieces).as_stats(),
        unnumbered=[p.number for p in pieces if p.label is None],
        seam_bars=len(split.bars),
        seam_bars_mm2=round(sum(b.area for b in split.bars), 3),
    )
    filled = sum(int(p.plan.report.stats.get("filled_holes", 0)) for p in pieces)
    return figures | ({"filled_holes": filled} if filled else {})


def _notes(report: Report, split, pieces, groups, profile, marks: bool) -> None:
    """The report's lines for people: the panel in pieces, the joints, the largest piece, the material,
    the alike pieces, the numbers not scored, the holes filled."""
    st = report.stats
    (w, h), (bw, bh), (nx, ny) = st["panel_mm"], profile.bed_mm, split.grid
    joint, n_j = split.joint, len(split.joints)
    kinds = {"dovetail": "dovetail", "jigsaw": "jigsaw joint"}
    report.note(
        f"{w:g} x {h:g} mm panel in {len(pieces)} pieces ({nx} x {ny}) for the {bw:g} x {bh:g} mm bed of "
        f"{profile.kind} profile {profile.name!r}"
    )
    report.note(
        f"joints: {n_j} {kinds[joint.kind]}{'s' if n_j != 1 else ''}, neck {joint.neck_mm:g} mm, head "
        f"{joint.head_mm:.3g} mm, {joint.depth_mm:.3g} mm deep, fit {joint.fit_mm:+g} mm"
        + (f", corners rounded to {joint.corner_mm:g} mm for the tool" if joint.corner_mm else "")
    )
    if split.bars:
        from ..geometry.pieces import seam_bar_mm

        report.note(
            f"seam bars: {len(split.bars)} ({seam_bar_mm(joint):g} mm wide) laid along the seams where the bands "
            "are too thin to hold a joint; the panel gains them"
        )
    lw, lh = st["largest_piece_mm"]
    report.note(
        f"largest piece {lw:.1f} x {lh:.1f} mm (piece {st['largest_piece']}) on the {bw:g} x {bh:g} mm bed, "
        f"{profile.margin_mm:g} mm margin"
    )
    cost = st["sheet"]["cost"]
    price = "" if cost is None else f", about {cost:.2f} at price_per_m2 = {profile.price_per_m2:g}"
    report.note(
        f"material: {st['area_mm2'] / 1e6:.3g} m^2 in the pieces, cut from {st['sheet']['sheet_m2']:.3g} m^2 of "
        f"sheet (each piece's extents){price}; job time summed over every piece"
    )
    alike = [g for g in groups if len(g) > 1]
    if alike:
        report.note("alike pieces (one shape, interchangeable): " + "; ".join(", ".join(map(str, g)) for g in alike))
    unmarked = st["unnumbered"]
    if not marks:
        report.note(
            f"a {profile.kind} has no score layer: the pieces' numbers are in the assembly drawing only; "
            "mark each piece as it comes off the machine"
        )
    elif unmarked:
        report.note(
            f"no room to score the number on piece{'s' if len(unmarked) > 1 else ''} "
            f"{', '.join(map(str, unmarked))} (the material is narrower than the smallest text with "
            f"{profile.min_feature_mm:g} mm round it): see the assembly drawing"
        )
    if "filled_holes" in st:
        report.note(f"filled {st['filled_holes']:,} holes too small for the {profile.kind} to cut, over the pieces")


def _add_findings(report: Report, piece: CutPiece) -> None:
    """Piece ``piece``'s findings added to ``report``, each named with its piece and located in the panel."""
    m = piece.matrix
    offset = np.asarray(piece.plan.offset)
    for f in piece.plan.report.findings:
        # a plan's findings are located in the coordinates it was given, the file's less its offset
        where = [tuple((m @ [x + offset[0], y + offset[1], 1.0])[:2]) for x, y in f.locations]
        located = tuple((float(x), float(y)) for x, y in where)
        report.findings.append(replace(f, message=f"piece {piece.number}: {f.message}", locations=located))
