"""The cut plan: a 2D cutter's job as ordered layers of paths, made once and read by every writer.

A :class:`CutPlan` is what the DXF, the laser SVG and the LightBurn project of a
tile (or a sheet, or one file of an inlay kit) are made from: the layers in cut
order, each with its role, the profile's layer settings (name, colour, speed,
power, passes) and its paths (closed contours or open score lines), the plan's
bounds, its fabrication findings, its job estimate and the part as the tool makes
it. The writers (:mod:`fabtiles.export.formats`) are pure functions of a plan: a
build makes the plan once, whatever formats it writes.

:class:`CutOptions` holds the options, checked once (:meth:`CutOptions.of`); :func:`plan_cut`
runs the checks (:mod:`.laser_checks`, :mod:`.tool_opening`) and builds the contours
(:mod:`.contours`); :func:`plan_kit` makes an inlay kit's two plans, the lattice and the pieces.

>>> from shapely.geometry import box
>>> plate = box(0, 0, 40, 40).difference(box(10, 10, 30, 30))
>>> plan = plan_cut(plate, box(0, 0, 40, 40), CutOptions.of(profile="laser-3mm-plywood"))
>>> [(layer.role, layer.layer.name, len(layer.paths)) for layer in plan.layers]
[('inner', 'INNER', 1), ('outer', 'OUTER', 1)]
>>> plan.report.ok, plan.estimate.pierces
(True, 2)
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
import shapely

from ..core.errors import FabricationError, ParameterError
from ..core.report import Report, distinct
from ..core.validate import check_choice, check_float
from ..machines.cutters import cutter_kind
from ..machines.profiles import LASER_MODES, LaserProfile, Layer, load_profile
from .arcs import Curve, curve_bounds, curves
from .contours import clean_rings, laser_contours, outline_contours, polygon_parts, score_paths
from .cut_order import path_orders
from .job_time import JobEstimate, total, travel_mm
from .job_time import estimate as job_estimate
from .laser_checks import (
    check_cut_pattern,
    check_engrave,
    check_fits_bed,
    check_laser,
    check_layers,
    engrave_layer,
    fits_bed,
)
from .material import sheet
from .narrow import check_pattern_kept
from .narrow import fill_small_holes as _fill_small_holes
from .tabs import check_tabs, tab_paths

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry

    from .inlay import InlayKit

ROLES = ("engrave", "score", "inner", "outer")
"""The roles of a plan's layers, in cut order: engrave fills first, then score lines, inner
contours, and the outer contours last (a part cut free must not move before its holes are cut)."""

PROFILE_KEYS = {"engrave": "engrave", "score": "score", "inner": "inner_cut", "outer": "outer_cut"}
"""The profile's ``[layers]`` key of each role."""


@dataclass(frozen=True)
class CutLayer:
    """One layer of a cut plan: what it does, the profile's settings for it, its paths.

    ``paths`` are (n, 2) arrays in mm, in cut order, flattened within the profile's
    tolerance; ``curves`` the same paths with their arcs as arcs (one
    :class:`~fabtiles.geometry.arcs.Curve` a path: what the files write); ``closed`` says
    whether each path returns to its start (contours) or not (score lines). ``fill`` layers are
    engraved areas: ``groups[i]`` is the polygon path ``i`` bounds (an outline and
    its holes share a group), and the writers fill each group even-odd.
    """

    role: str
    layer: Layer
    paths: tuple
    closed: bool = True
    fill: bool = False
    groups: tuple = ()
    curves: tuple = ()

    def curves_or_paths(self) -> tuple:
        """The paths as the files write them: :class:`~fabtiles.geometry.arcs.Curve` s, arcs as bulges
        (the flattened paths, with no arc, for a layer made without them)."""
        if len(self.curves) == len(self.paths):
            return self.curves
        return tuple(Curve(p, np.zeros(len(p))) for p in self.paths)

    @property
    def key(self) -> str:
        """The profile's ``[layers]`` key of this layer (``inner_cut``, ``outer_cut``, ``score``, ``engrave``)."""
        return PROFILE_KEYS[self.role]


@dataclass(frozen=True)
class CutPlan:
    """A 2D cutter's job: its layers in cut order and what the checks and the estimate found.

    ``layers`` holds only the layers with paths; ``declared`` is every layer the
    files declare (a DXF's layer table lists the profile's cut and score layers even
    when empty, so a user finds them). ``report`` carries the plan's statistics and
    findings (one set per plan, however many files are written from it);
    ``estimate`` is the job's length and time; ``part`` the material as the tool
    makes it (holes opened by a router's bit, small holes filled), in the tile's
    coordinates; ``bounds`` the extents of every path, from (0, 0) (a kit's pieces keep
    the lattice's, so the two files register); ``offset`` the vector the paths were
    moved by from the tile's coordinates to the file's (see :func:`make_plan`).

    The layers, with their names, colours, speeds and powers, are the plan itself for every
    cutter format (a DXF's layer table, an SVG's groups, a LightBurn project's cut settings),
    so the plan holds them. What one format alone asks (a DXF's version) is the file's option,
    :class:`~fabtiles.export.formats.FileOptions`, so one plan is written in any of them.
    """

    profile: LaserProfile
    mode: str
    kerf_mm: float
    layers: tuple = ()
    declared: tuple = ()
    bounds: tuple = (0.0, 0.0, 0.0, 0.0)
    estimate: JobEstimate = field(default_factory=JobEstimate)
    report: Report = field(default_factory=lambda: Report(path="", format=""))
    part: BaseGeometry | None = None
    engrave_area_mm2: float = 0.0
    offset: tuple = (0.0, 0.0)

    def files(self) -> list:
        """``[("", self)]``: a plan is one file of each format (see :class:`KitPlans` for two)."""
        return [("", self)]

    def paths(self, role: str) -> list:
        """The paths of the layer of ``role`` (empty when the plan has none)."""
        return next((list(layer.paths) for layer in self.layers if layer.role == role), [])

    @property
    def kind(self):
        """The cutter's rules (:class:`~fabtiles.machines.cutters.CutterKind`)."""
        return cutter_kind(self.profile)


@dataclass(frozen=True, slots=True, kw_only=True)
class CutOptions:
    """A cut plan's options, checked against each other and the profile: made by :meth:`of`.

    ``kerf_mm`` and ``kerf_y_mm`` are the cut's width along X and along Y (the profile's
    unless one kerf was given); ``stroke_mm`` the pattern's stroke width, checked against the
    kerf and the profile's ``min_feature_mm`` (None: not checked); ``path`` and ``fmt`` what
    the report names (a strict profile's error names the file).
    """

    profile: LaserProfile
    mode: str
    kerf_mm: float
    kerf_y_mm: float
    stroke_mm: float | None = None
    fill_small_holes: bool = False
    tab_mm: float = 0.0
    tabs_per_part: int = 4
    path: str = ""
    fmt: str = ""

    @classmethod
    def of(
        cls,
        *,
        profile,
        mode=None,
        kerf_mm=None,
        fill_small_holes: bool = False,
        stroke=None,
        tab_mm=None,
        tabs_per_part=None,
        path: str = "",
        fmt: str = "",
    ) -> CutOptions:
        """The options checked, the profile's defaults in place of the Nones.

        Parameters
        ----------
        profile : str, Path or CutterProfile
            The cutter profile (kerf, limits, bed, layers, defaults of the options below).
        mode : {"pierced", "score", "engrave"}, optional
            Default: the profile's. The inlay mode is two plans: :func:`plan_kit`.
        kerf_mm : float, optional
            Width of the cut; default: the profile's (along X and along Y).
        fill_small_holes : bool
            Fill the holes narrower than the profile's ``min_hole_mm`` (or that a
            router's bit cannot enter) instead of cutting them.
        stroke : float, optional
            The pattern's stroke width, to check kerf and ``min_feature_mm`` against.
        tab_mm : float, optional
            Holding tabs: each outer cut is left open at ``tabs_per_part`` gaps this long
            (mm along the cut; default 0, none; a laser's only). See :mod:`.tabs`.
        tabs_per_part : int, optional
            Gaps per part when ``tab_mm`` > 0 (default 4).
        path, fmt : str
            What the report names (a strict profile's error names the file).

        Raises :class:`~fabtiles.ParameterError` for a bad option (naming it, its value and
        its range) and :class:`~fabtiles.ProfileError` for a bad profile.
        """
        profile = load_profile(profile, kind="laser")
        kind = cutter_kind(profile)
        kind.check_profile(profile)
        check_layers(profile)
        mode = _checked_mode(profile, mode)
        if kerf_mm is None:  # the profile's kerf, along X and along Y
            kerf, kerf_y = profile.kerf_xy_mm
        else:
            kerf = kerf_y = check_float("kerf_mm", kerf_mm, low=0)
            kind.check_kerf(profile, kerf)
        tab, per = check_tabs(tab_mm, tabs_per_part, kerf_mm=max(kerf, kerf_y), profile=profile)
        if stroke is not None:
            stroke = _checked_stroke(profile, stroke, max(kerf, kerf_y))
        if not isinstance(fill_small_holes, bool):
            raise ParameterError(
                f"fill_small_holes must be True or False, got {fill_small_holes!r}", param="fill_small_holes"
            )
        return cls(
            profile=profile,
            mode=mode,
            kerf_mm=kerf,
            kerf_y_mm=kerf_y,
            stroke_mm=stroke,
            fill_small_holes=fill_small_holes,
            tab_mm=tab,
            tabs_per_part=per,
            path=str(path),
            fmt=fmt,
        )


def _checked_mode(profile: LaserProfile, mode) -> str:
    """The plan's mode (the profile's when None), one the cutter runs; the inlay mode is refused (two plans)."""
    mode = profile.mode if mode is None else mode
    if mode == "inlay":
        raise ParameterError(
            "the inlay mode writes a kit of two files (lattice and pieces): export it with "
            "Tile.export(..., mode='inlay'), fabtiles.making.export_region(..., mode='inlay') or fabtiles build",
            param="mode",
        )
    mode = check_choice("mode", mode, LASER_MODES)
    cutter_kind(profile).check_mode(profile, mode)
    return mode


def _checked_stroke(profile: LaserProfile, stroke, kerf_mm: float) -> float:
    """The stroke width checked: above the profile's smallest feature, and no narrower than the kerf."""
    stroke = check_float("stroke", stroke, low=0, low_open=True)
    if stroke < profile.min_feature_mm:
        raise ParameterError(
            f"stroke must be >= min_feature_mm = {profile.min_feature_mm:g} mm of {profile.kind} "
            f"profile {profile.name!r}, got {distinct(stroke, profile.min_feature_mm)}",
            param="stroke",
        )
    if kerf_mm > stroke:
        raise ParameterError(
            f"kerf_mm must be >= 0 and <= the stroke ({stroke:g} mm), got {distinct(kerf_mm, stroke)}",
            param="kerf_mm",
        )
    return stroke


@dataclass(frozen=True, slots=True, kw_only=True)
class KitOptions:
    """An inlay kit's options, checked: made by :meth:`of`.

    ``lattice`` is the lattice's plan's options (pierced, or engrave for pockets);
    ``inlay_fit_mm`` how much each piece grows from its hole; ``inlay_base`` how the lattice
    holds the pieces (:data:`INLAY_BASES`); ``stroke_mm`` the pattern's stroke width (what
    the kept-pattern check names; a pierced lattice checks it against the kerf once the kit
    is made, so that the kit's own findings come first).
    """

    lattice: CutOptions
    inlay_fit_mm: float
    inlay_base: str = "pierced"
    stroke_mm: float | None = None

    @classmethod
    def of(
        cls,
        *,
        profile,
        inlay_fit_mm=None,
        inlay_base: str = "pierced",
        kerf_mm=None,
        stroke=None,
        tab_mm=None,
        tabs_per_part=None,
        path: str = "",
        fmt: str = "",
    ) -> KitOptions:
        """The options checked, the profile's defaults in place of the Nones (see :meth:`CutOptions.of`;
        ``inlay_fit_mm``: default the profile's)."""
        from .inlay import check_fit

        profile = load_profile(profile, kind="laser")
        cutter_kind(profile).check_mode(profile, "inlay")
        base = check_choice("inlay_base", inlay_base, INLAY_BASES)
        fit = check_fit(profile.inlay_fit_mm if inlay_fit_mm is None else inlay_fit_mm)
        kx, ky = profile.kerf_xy_mm if kerf_mm is None else (kerf_mm, kerf_mm)
        tabs = check_tabs(tab_mm, tabs_per_part, kerf_mm=max(kx, ky))  # only a laser cuts kits, and leaves tabs
        lattice = CutOptions.of(
            profile=profile,
            mode="pierced" if base == "pierced" else "engrave",
            kerf_mm=kerf_mm,
            tab_mm=tabs[0],
            tabs_per_part=tabs[1],
            path=path,
            fmt=fmt,
        )
        return cls(lattice=lattice, inlay_fit_mm=fit, inlay_base=base, stroke_mm=stroke)


def make_plan(
    profile,
    mode: str,
    kerf_mm: float,
    paths: dict,
    *,
    report: Report | None = None,
    part=None,
    groups=(),
    engrave_area_mm2: float = 0.0,
    bounds=None,
    like: CutPlan | None = None,
    outer_closed: bool = True,
    shades=(),
) -> CutPlan:
    """A :class:`CutPlan` of ``paths`` (role -> list of arrays), its layers, bounds and estimate.

    ``shades``: ``((layer, rings, groups, area_mm2), ...)``, more engrave layers of their own settings
    (a shaded engraving's face classes, :mod:`.shades`), engraved after the ``engrave`` role's fill.

    For plans made without the tile pipeline too (the calibration card, a kit's pieces).
    ``outer_closed=False``: the outer paths are open pieces between holding tabs (:func:`split_at_tabs`).

    Every cutter file lies in the positive quadrant: the paths are moved so that the
    lower-left of their bounding box (``bounds``, when given, the frame the file must
    cover, in the paths' coordinates) is at (0, 0); the plan's ``offset`` is that move.
    ``like`` gives the paths another plan's offset and bounds instead (a kit's pieces
    files share the lattice's, so each piece lies in its hole when the sheets are laid
    alike).

    >>> from fabtiles.machines.profiles import load_profile
    >>> ring = np.array([[-0.075, -0.075], [40.075, -0.075], [40.075, 40.075], [-0.075, 40.075]])
    >>> plan = make_plan(load_profile("laser-3mm-plywood"), "pierced", 0.15, {"outer": [ring]})
    >>> plan.offset, np.round(plan.bounds, 9).tolist(), plan.paths("outer")[0].min(axis=0).tolist()
    ((0.075, 0.075), [0.0, 0.0, 40.15, 40.15], [0.0, 0.0])
    """
    layers_of = profile.layers
    kind = cutter_kind(profile)
    moved = {role: [np.asarray(r, dtype=float) for r in paths.get(role, ())] for role in ROLES}
    closed_of = {role: outer_closed if role == "outer" else role != "score" for role in ROLES}
    arcs = _arcs(moved, closed_of, profile.tolerance_mm)
    moved, arcs, offset, bounds = _into_file(moved, arcs, closed_of, bounds, like)
    # the head's travel made short (.cut_order), from the file's origin; the arcs go with their paths
    travel_before = travel_mm(profile, **moved, outer_closed=outer_closed)
    _in_cut_order(moved, arcs, outer_closed)
    layers = _layers(layers_of, moved, arcs, closed_of, groups)
    # a router or waterjet file has its two profiles' layers only; the engrave layer only when it engraves
    declared = [getattr(layers_of, key) for key in kind.layers if key != "engrave" or paths.get("engrave")]
    shaded = [_shade_layer(profile, s, offset) for s in shades]
    at = 1 if layers and layers[0].role == "engrave" else 0  # after the bands' fill, before the rest
    layers[at:at] = [layer for layer, _ in shaded]
    declared[at:at] = [layer.layer for layer, _ in shaded]
    est = job_estimate(
        profile,
        **{role: [c.xy for c in arcs[role]] for role in ROLES},
        engrave_area_mm2=engrave_area_mm2,
        outer_closed=outer_closed,
        curves=arcs,
    )
    est = replace(est, travel_before_mm=travel_before)
    if shaded:  # each shade's fill at its own speed and interval: the job counts every layer
        est = replace(total([est, *(e for _, e in shaded)]), travel_before_mm=travel_before)
        engrave_area_mm2 += sum(s[3] for s in shades)
    return CutPlan(
        profile,
        mode,
        kerf_mm,
        tuple(layers),
        tuple(declared),
        tuple(bounds),
        est,
        report if report is not None else Report(path="", format=""),
        part,
        engrave_area_mm2,
        tuple(float(v) for v in offset),
    )


def _shade_layer(profile, shade, offset) -> tuple:
    """One shaded class's engrave layer, its rings moved into the file like the plan's, and its job."""
    layer, rings, groups, area = shade
    shift = np.asarray(offset, dtype=float)
    moved = {"engrave": [np.asarray(r, dtype=float) + shift for r in rings]}
    arcs = {"engrave": curves(moved["engrave"], tolerance_mm=profile.tolerance_mm, closed=True)}
    _in_cut_order(moved, arcs, True)
    cut = CutLayer(
        "engrave", layer, tuple(moved["engrave"]), fill=True, groups=tuple(groups), curves=tuple(arcs["engrave"])
    )
    own = replace(profile, layers=replace(profile.layers, engrave=layer))
    est = job_estimate(own, engrave=moved["engrave"], engrave_area_mm2=area, curves=arcs)
    return cut, est


def _arcs(moved: dict, closed_of: dict, tolerance_mm: float) -> dict:
    """The arcs in each role's paths, for the writers, the lengths and the bounds.

    Fitted on the flattened paths, whatever made them (see :mod:`.arcs`).
    """
    return {
        role: curves(rings, tolerance_mm=tolerance_mm, closed=closed_of[role]) if rings else []
        for role, rings in moved.items()
    }


def _layers(layers_of, moved: dict, arcs: dict, closed_of: dict, groups) -> list:
    """The plan's layers in cut order, the roles with paths only, each with the profile's settings."""
    return [
        CutLayer(
            role,
            getattr(layers_of, PROFILE_KEYS[role]),
            tuple(moved[role]),
            closed=closed_of[role],
            fill=role == "engrave",
            groups=tuple(groups) if role == "engrave" else (),
            curves=tuple(arcs[role]),
        )
        for role in ROLES
        if moved[role]
    ]


def _into_file(moved: dict, arcs: dict, closed_of: dict, bounds, like: CutPlan | None) -> tuple:
    """The paths and arcs moved into the file's positive quadrant: ``(moved, arcs, offset, bounds)``.

    ``like``: another plan's offset and bounds, else the paths' own (see :func:`make_plan`).
    """
    offset = like.offset if like is not None else _offset(moved, arcs, closed_of, bounds)
    shift = np.asarray(offset, dtype=float)
    if shift.any():
        moved = {role: [r + shift for r in rings] for role, rings in moved.items()}
        arcs = {role: [Curve(c.xy + shift, c.bulge) for c in cs] for role, cs in arcs.items()}
    bounds = like.bounds if like is not None else _file_bounds(moved, arcs, closed_of, bounds, shift)
    return moved, arcs, offset, bounds


def _offset(moved: dict, arcs: dict, closed_of: dict, bounds) -> tuple:
    """The move that puts the paths' lower-left (or ``bounds``', when lower) at (0, 0)."""
    allr = [r for rings in moved.values() for r in rings]
    # The shift is the paths' true lower-left, not a fixed half kerf: a square's kerf
    # reaches exactly -kerf/2, but a circle's flattened offset reaches a little further,
    # a pointy-top hexagon's mitred tip kerf/2 / sin 60 deg and a larger kerf_y_mm further
    # in y: a half-kerf shift would leave those below 0, and MeerK40t moves such a file to
    # the bed's centre.
    box = [_extent(allr, arcs, closed_of)[0]] if allr else []
    box += [np.asarray(bounds[:2], dtype=float)] if bounds is not None else []
    low = np.min(box, axis=0) if box else np.zeros(2)
    return tuple((0.0 - low).tolist())


def _file_bounds(moved: dict, arcs: dict, closed_of: dict, bounds, shift: np.ndarray) -> tuple:
    """The extents of the moved paths and of ``bounds`` (moved too), the lower-left snapped to (0, 0)."""
    allr = [r for rings in moved.values() for r in rings]
    frame = [np.asarray(bounds, dtype=float).reshape(2, 2) + shift] if bounds is not None else []
    frame += [np.array(_extent(allr, arcs, closed_of))] if allr else []
    flat = np.concatenate(frame) if frame else np.zeros((1, 2))
    # an arc's extreme, moved to 0, comes back as -7e-15 or so: the file's corner is (0, 0)
    low = np.where(np.abs(flat.min(axis=0)) < 1e-9, 0.0, flat.min(axis=0))
    return (*low.tolist(), *flat.max(axis=0).tolist())


def _in_cut_order(moved: dict, arcs: dict, outer_closed: bool) -> None:
    """Each role's paths (and their arcs, in place) put in the order and direction that keep the travel short."""
    for role, (order, flipped) in path_orders(moved, outer_closed=outer_closed).items():
        pairs = list(zip(order.tolist(), flipped.tolist(), strict=True))
        moved[role] = [moved[role][i][::-1] if f else moved[role][i] for i, f in pairs]
        arcs[role] = [_reversed(arcs[role][i]) if f else arcs[role][i] for i, f in pairs]


def _reversed(curve: Curve) -> Curve:
    """An open path with arcs run backwards: each piece's bulge goes with it, turned the other way.

    >>> _reversed(Curve(np.array([[0.0, 0.0], [2.0, 0.0], [3.0, 1.0]]), np.array([1.0, 0.0, 0.0]))).bulge.tolist()
    [0.0, -1.0, 0.0]
    """
    bulge = np.zeros_like(curve.bulge)
    bulge[:-1] = 0.0 - curve.bulge[:-1][::-1]  # 0.0 - b, not -b: no -0.0 in the files
    return Curve(curve.xy[::-1], bulge)


def _extent(rings, arcs: dict, closed_of: dict):
    """Lower-left and upper-right of the paths, arcs as arcs.

    An arc may reach past its vertices (by up to its sagitta, the tolerance): where it does
    by more than 1e-9 mm, its extreme counts; else the vertices' (exact: a circle flattened
    by GEOS has its lowest vertex on the circle, and a file moved by the arc's float extreme
    would put it at -2e-15 mm).
    """
    flat = np.concatenate(rings)
    lo, hi = flat.min(axis=0), flat.max(axis=0)
    ext = np.array([curve_bounds(c, closed=closed_of[role]) for role, c in arcs.items() if c]).reshape(-1, 4)
    alo, ahi = ext[:, :2].min(axis=0), ext[:, 2:].max(axis=0)
    return np.where(alo < lo - 1e-9, alo, lo), np.where(ahi > hi + 1e-9, ahi, hi)


def _length(rings, closed: bool) -> float:
    """Total length of polylines (closed: with the closing edge)."""
    if not rings:
        return 0.0
    flat = np.concatenate(rings)
    total = float(np.hypot(*np.diff(flat, axis=0).T).sum())
    starts = np.cumsum([0] + [len(r) for r in rings])
    # remove the jumps between polylines, add the closing edges
    jumps = flat[starts[1:-1]] - flat[starts[1:-1] - 1]
    total -= float(np.hypot(*jumps.T).sum())
    if closed:
        close = flat[starts[:-1]] - flat[starts[1:] - 1]
        total += float(np.hypot(*close.T).sum())
    return total


def _engrave_paths(region, profile, report: Report):
    """Engrave mode: the material's bands as filled rings (exteriors counter-clockwise, holes clockwise)."""
    check_engrave(region, profile, report)
    report.raise_if_strict(profile.strict)
    parts = shapely.get_parts(region)
    rings, part = shapely.get_rings(parts, return_index=True)
    exterior = np.zeros(len(rings), dtype=bool)
    starts = np.concatenate([[0], np.cumsum(shapely.get_num_interior_rings(parts) + 1)[:-1]])
    exterior[starts] = True
    cleaned, kept = clean_rings(rings, min_area=profile.tolerance_mm**2, ccw=exterior)
    area = float(shapely.area(parts).sum())
    report.stats.update(area_mm2=round(area, 3), engrave_rings=len(cleaned))
    return cleaned, part[kept].tolist(), area


def split_at_tabs(paths: dict, tab_mm: float, tabs_per_part: int, report: Report | None) -> bool:
    """``paths["outer"]`` split at holding tabs when ``tab_mm`` > 0 (:func:`.tabs.tab_paths`), the report
    told how many and where; whether the outer paths are still closed."""
    if not tab_mm or not paths.get("outer"):
        return True
    tabs = tab_paths(paths["outer"], tab_mm=tab_mm, tabs_per_part=tabs_per_part)
    paths["outer"] = tabs.pieces
    if report is not None:
        report.stats["tabs"] = tabs.as_stats()
        report.note(tabs.note())
    return False


def plan_cut(region, outline, options: CutOptions, *, centrelines=None, marks=(), shades=()) -> CutPlan:
    """Run the checks and build the contours: the tile's :class:`CutPlan`.

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The material in file coordinates (mm; the outline's lower-left at (0, 0)).
    outline : shapely Polygon or MultiPolygon
        The tile outline (one polygon per tile on a sheet).
    options : CutOptions
        The profile, mode, kerf, tabs and the rest, checked (:meth:`CutOptions.of`).
    centrelines : ndarray (k, 2, 2), optional
        Centre-line segments in file coordinates; needed by the score mode.
    marks : sequence of ndarray (m, 2)
        Open polylines scored on the material besides (a panel's piece number), file coordinates.
    shades : sequence of (Layer, shapely geometry)
        Faces engraved, each group on its own layer (a shaded engraving, :mod:`.shades`), file
        coordinates; a pierced cut keeps them as material (engraved, not cut out).

    Raises before any contour is made: :class:`~fabtiles.ParameterError` for a bad
    region or outline, :class:`~fabtiles.FabricationError` for a tile larger than the
    bed or, with a strict profile, any finding.
    """
    o = options
    profile, kind = o.profile, cutter_kind(o.profile)
    parts = polygon_parts(region)
    outline_parts = polygon_parts(outline, "outline")
    check_fits_bed(outline, profile)

    report = Report(path=o.path, format=o.fmt)
    report.stats.update(profile=profile.name, mode=o.mode, kerf_mm=o.kerf_mm)
    if o.kerf_y_mm != o.kerf_mm:
        report.stats["kerf_y_mm"] = o.kerf_y_mm
    report.stats.update(kind.report_stats())
    groups, engrave_area = (), 0.0
    if shades:
        engrave_layer(profile)  # the shades are the fill's settings, shaded
        if o.mode == "pierced":  # the engraved faces stay: material, not holes
            region = _kept_faces(region, [faces for _, faces in shades], profile.tolerance_mm)
            parts = polygon_parts(region)
    if o.mode == "pierced":
        paths, part = _pierced_paths(region, parts, outline, o, report)
    elif o.mode == "engrave":
        engrave_layer(profile)
        paths = {"outer": _outline_paths(outline, o)}
        paths["engrave"], groups, engrave_area = _engrave_paths(region, profile, report)
        part = region
    else:
        paths = _score_mode_paths(outline, outline_parts, centrelines, o, report)
        part = outline
    if len(marks):
        paths["score"] = [*paths.get("score", ()), *marks]
    outer_rings = len(paths["outer"])
    closed = split_at_tabs(paths, o.tab_mm, o.tabs_per_part, report)
    plan = make_plan(
        profile,
        o.mode,
        o.kerf_mm,
        paths,
        report=report,
        part=part,
        groups=groups,
        engrave_area_mm2=engrave_area,
        outer_closed=closed,
        shades=[_shade_rings(layer, faces, profile, report) for layer, faces in shades],
    )
    _plan_stats(plan, outline, outer_rings, report)
    return plan


def _kept_faces(region, faces, tolerance_mm: float):
    """``region`` with ``faces`` (some of its holes) filled, and no sliver left along their edges."""
    whole = shapely.union_all([region, *faces])
    parts = []
    for poly in shapely.get_parts(whole):
        holes = [h for h in poly.interiors if shapely.Polygon(h).area > tolerance_mm**2]
        parts.append(shapely.Polygon(poly.exterior, holes))
    return shapely.MultiPolygon(parts) if len(parts) > 1 else parts[0]


def _shade_rings(layer, faces, profile, report: Report) -> tuple:
    """A shaded class's faces as filled rings: ``(layer, rings, groups, area_mm2)``; the report told its settings."""
    parts = shapely.get_parts(faces)
    rings, part = shapely.get_rings(parts, return_index=True)
    exterior = np.zeros(len(rings), dtype=bool)
    starts = np.concatenate([[0], np.cumsum(shapely.get_num_interior_rings(parts) + 1)[:-1]])
    exterior[starts[: len(parts)]] = True
    cleaned, kept = clean_rings(rings, min_area=profile.tolerance_mm**2, ccw=exterior)
    area = float(shapely.area(parts).sum())
    report.stats.setdefault("shades", {})[layer.name] = {
        "power_pct": layer.power_pct,
        "speed_mm_s": layer.speed_mm_s,
        "line_interval_mm": layer.line_interval_mm,
        "passes": layer.passes,
        "faces": len(parts),
        "area_mm2": round(area, 3),
    }
    return layer, cleaned, part[kept].tolist(), area


def _outline_paths(outline, o: CutOptions) -> list:
    """The outline's cut paths, outside it by half the kerf."""
    return outline_contours(outline, kerf_mm=o.kerf_mm, kerf_y_mm=o.kerf_y_mm, tolerance_mm=o.profile.tolerance_mm)


def _pierced_paths(region, parts, outline, o: CutOptions, report: Report) -> tuple[dict, BaseGeometry]:
    """The pierced mode: the part as the tool makes it checked, its inner and outer contours.

    Returns the paths (role -> rings) and the part as cut (holes opened by a router's bit,
    small holes filled).
    """
    from .tool_opening import check_tool

    profile, kind = o.profile, cutter_kind(o.profile)
    designed, tool_filled = region, 0
    if kind.opens_holes:  # the part as the bit or the jet makes it: holes opened by its radius
        region, _, tool_filled = check_tool(region, profile, fill_small_holes=o.fill_small_holes, report=report)
        parts = shapely.get_parts(region)
    if o.fill_small_holes:
        region = _filled(region, tool_filled, o, report)
        parts = shapely.get_parts(region)
    check_laser(region, outline, profile, stroke=o.stroke_mm, report=report, validate=False)
    check_cut_pattern(designed, region, outline, profile, stroke=o.stroke_mm, report=report)
    report.raise_if_strict(profile.strict)
    paths: dict = {}
    paths["inner"], paths["outer"] = laser_contours(
        region, outline, kerf_mm=o.kerf_mm, kerf_y_mm=o.kerf_y_mm, tolerance_mm=profile.tolerance_mm, validate=False
    )
    report.stats["area_mm2"] = round(float(shapely.area(parts).sum()), 3)
    return paths, region


def _filled(region, tool_filled: int, o: CutOptions, report: Report):
    """``region`` with its holes narrower than ``min_hole_mm`` filled, the report told how many of each kind."""
    profile = o.profile
    region, filled = _fill_small_holes(region, profile.min_hole_mm, tolerance_mm=profile.tolerance_mm)
    report.stats["filled_holes"] = filled + tool_filled
    if tool_filled:
        report.note(
            f"filled {tool_filled:,} hole{'s' if tool_filled != 1 else ''} that "
            f"{cutter_kind(profile).tool_name(profile)} cannot enter"
        )
    if filled:
        report.note(
            f"filled {filled:,} hole{'s' if filled != 1 else ''} narrower than min_hole_mm = "
            f"{profile.min_hole_mm:g} mm of {profile.kind} profile {profile.name!r}"
        )
    return region


def _score_mode_paths(outline, outline_parts, centrelines, o: CutOptions, report: Report) -> dict:
    """The score mode: the outline cut, the pattern's centre-lines inside it scored."""
    if centrelines is None:
        raise ParameterError(
            "the score mode needs centrelines (an array of shape (k, 2, 2)), got none", param="centrelines"
        )
    if len(np.asarray(centrelines)) == 0:
        # only the strokes' edges reach into the outline: there is no line to score
        raise FabricationError(
            "the score mode has no line to score: every centre-line of the pattern lies outside the outline "
            "(only the edges of strokes reach in); make the tile larger or the packing smaller, or cut it pierced"
        )
    paths = {"outer": _outline_paths(outline, o)}
    paths["score"] = score_paths(centrelines, outline, tolerance_mm=o.profile.tolerance_mm)
    report.stats["area_mm2"] = round(float(shapely.area(outline_parts).sum()), 3)
    report.stats["score_paths"] = len(paths["score"])
    report.stats["score_length_mm"] = round(_length(paths["score"], False), 3)
    return paths


def _plan_stats(plan: CutPlan, outline, outer_rings: int, report: Report) -> None:
    """The report told the plan's figures: contours, vertices, arcs, cut length, job, sheet, file offset."""
    files = [c for layer in plan.layers for c in layer.curves_or_paths()]
    cut = plan.estimate.cut_mm
    report.stats.update(
        inner_contours=len(plan.paths("inner")),
        outer_contours=outer_rings,
        vertices=int(sum(len(c.xy) for c in files)),
        arcs=int(sum(np.count_nonzero(c.bulge) for c in files)),
        cut_length_mm=round(cut.get("inner_cut", 0.0) + cut.get("outer_cut", 0.0), 3),
    )
    report.stats["job"] = plan.estimate.as_stats()
    report.stats["sheet"] = sheet(outline, plan.profile)
    _note_bed_edge(plan, plan.profile, report)
    # the findings' locations are the tile's coordinates; the files' are these plus the offset
    report.stats["file_offset_mm"] = [round(v, 6) + 0.0 for v in plan.offset]


def _note_bed_edge(plan: CutPlan, profile, report: Report) -> None:
    """Say so when the cut paths reach beyond the bed although the tile fits it.

    A tile of exactly the bed's size (the 600 x 400 mm sheet sample) fits
    (:func:`check_fits_bed` measures the tile), but its outline's cut path runs outside the
    tile by half the kerf on every side (a router's by the bit's radius): 600.15 x 400.15 mm.
    Most machines travel a few mm beyond their nominal bed, so this is a note, not a finding.

    >>> from fabtiles.machines.profiles import load_profile
    >>> ring = np.array([[-0.075, -0.075], [600.075, -0.075], [600.075, 400.075], [-0.075, 400.075]])
    >>> r = Report(path="", format="")
    >>> _note_bed_edge(make_plan(load_profile("laser-3mm-plywood"), "pierced", 0.15, {"outer": [ring]}),
    ...                load_profile("laser-3mm-plywood"), r)
    >>> print(r.stats["notes"][0])
    the cut paths span 600.15 x 400.15 mm, beyond the 600 x 400 mm bed by the cut's width outside the tile: the outline is cut at the sheet's edges (most machines travel a little beyond the nominal bed; if yours does not, make the tile smaller)
    """  # noqa: E501 - a doctest's lines are as Python prints them
    x0, y0, x1, y1 = plan.bounds
    w, h = x1 - x0, y1 - y0
    if fits_bed(w, h, profile.bed_mm):
        return
    bw, bh = profile.bed_mm
    report.note(
        f"the cut paths span {w:.2f} x {h:.2f} mm, beyond the {bw:g} x {bh:g} mm bed by the cut's width "
        f"outside the tile: the outline is cut at the sheet's edges (most machines travel a little beyond "
        f"the nominal bed; if yours does not, make the tile smaller)"
    )


INLAY_BASES = ("pierced", "pocket")
"""How a kit's lattice holds its pieces: holes cut through, or pockets engraved into a board."""


@dataclass(frozen=True)
class KitPlans:
    """An inlay kit's two plans, the lattice and the pieces (in registration), and the kit itself."""

    lattice: CutPlan
    pieces: CutPlan
    kit: InlayKit
    """The :class:`~fabtiles.geometry.inlay.InlayKit` (holes, pieces, figures)."""
    by_colour: tuple = ()
    """A coloured kit's pieces, one plan per face colour: ``((colour name, CutPlan), ...)``."""

    def files(self) -> list:
        """``[(suffix, plan), ...]``: ``-lattice``, then ``-pieces``, or with colours (a design's
        ``[colour]``) a ``-pieces-<colour>`` per colour that has pieces. A kit with no piece (every
        hole too small for one, filled) is its lattice alone: no empty pieces file."""
        if self.by_colour:
            return [("-lattice", self.lattice)] + [(f"-pieces-{name}", plan) for name, plan in self.by_colour]
        if not any(layer.paths for layer in self.pieces.layers):
            return [("-lattice", self.lattice)]
        return [("-lattice", self.lattice), ("-pieces", self.pieces)]

    @property
    def report(self) -> Report:
        """The lattice's report, with the kit's figures."""
        return self.lattice.report


def plan_kit(region, outline, options: KitOptions, *, colours=()) -> KitPlans:
    """The inlay kit of a tile's material ``region`` as two cut plans: the lattice and the pieces.

    The lattice is a pierced tile (holes cut with the kerf into them, the outline
    last), or with ``inlay_base="pocket"`` its holes engraved as pockets (for veneer
    pieces glued into a solid board) and the outline cut. The pieces are each grown
    by half the kerf so they come out at their nominal size, at their holes' places,
    on the outer-cut layer, with the lattice's bounds: cut from a sheet laid like the
    lattice's, they drop out where they belong. ``inlay_fit_mm`` grows each piece from
    its hole. The lattice's report carries the kit's figures (``pieces``,
    ``filled_holes``, ``piece_kinds``, both areas, the pieces' ``pieces_job``).
    ``colours``, ``((colour name, faces), ...)``, splits the pieces into a plan per
    colour: each piece goes with the colour of the face holding its hole (a piece no
    face names goes with the first colour), each plan with the lattice's bounds, so
    every wood's sheet is laid like the lattice's. The options' ``tab_mm`` and
    ``tabs_per_part`` leave holding tabs in the lattice's outer cut and in every
    piece's (the pieces' report: the ``pieces_tabs`` entry). ``options``:
    :meth:`KitOptions.of`.
    """
    from .inlay import inlay_kit

    lo = options.lattice
    profile, fit, tabs = lo.profile, options.inlay_fit_mm, (lo.tab_mm, lo.tabs_per_part)
    kit = inlay_kit(
        region,
        outline,
        fit_mm=fit,
        min_piece_mm=profile.min_piece_or_default_mm,
        kerf_mm=max(lo.kerf_mm, lo.kerf_y_mm),
        tolerance_mm=profile.tolerance_mm,
    )
    if options.inlay_base == "pierced":
        stroke = options.stroke_mm
        if stroke is not None:
            lo = replace(lo, stroke_mm=_checked_stroke(profile, stroke, max(lo.kerf_mm, lo.kerf_y_mm)))
        lattice = plan_cut(kit.lattice, outline, lo)
    else:
        if not len(kit.holes):
            raise ParameterError("the tile has no hole large enough for a piece; nothing to pocket", param="region")
        lattice = plan_cut(shapely.union_all(kit.holes), outline, lo)
    paths = {}
    if len(kit.pieces):
        paths["inner"], paths["outer"] = laser_contours(
            shapely.multipolygons(list(shapely.get_parts(kit.pieces))),
            kerf_mm=lo.kerf_mm,
            kerf_y_mm=lo.kerf_y_mm,
            tolerance_mm=profile.tolerance_mm,
        )
    pieces_report = Report(path="", format="")
    closed = split_at_tabs(paths, *tabs, pieces_report)
    pieces = make_plan(
        profile,
        "pierced",
        lo.kerf_mm,
        paths,
        like=lattice,
        part=kit.pieces,
        outer_closed=closed,
        report=pieces_report,
    )
    report = lattice.report
    stats = kit.stats()
    report.stats.update(stats, inlay_fit_mm=fit, inlay_base=options.inlay_base, pieces_job=pieces.estimate.as_stats())
    if "tabs" in pieces_report.stats:
        report.stats["pieces_tabs"] = pieces_report.stats["tabs"]
        report.note("pieces' " + pieces_report.stats["notes"][0])
    _note_kit(kit, stats, fit, pieces, report)
    # a kit fills the holes too small for a piece: say so when that leaves little of the pattern
    check_pattern_kept(
        report,
        region,
        kit.lattice,
        outline,
        limit_mm=profile.min_piece_or_default_mm,
        limit=f"the smallest piece ({profile.min_piece_or_default_mm:g} mm, min_piece_mm of laser "
        f"profile {profile.name!r})",
        stroke=options.stroke_mm,
        min_stroke_mm=profile.min_feature_mm,
        tool="a profile with min_piece_mm <= {w} mm",
        tolerance_mm=profile.tolerance_mm,
    )
    report.raise_if_strict(profile.strict)
    by_colour = _pieces_by_colour(kit, colours, profile, lattice, lo.kerf_mm, lo.kerf_y_mm, tabs) if colours else ()
    if by_colour:
        report.stats["pieces_by_colour"] = {}
        for name, plan in by_colour:
            _note_colour_sheet(name, plan, report)
    return KitPlans(lattice, pieces, kit, by_colour)


def _note_kit(kit: InlayKit, stats: dict, fit: float, pieces: CutPlan, report: Report) -> None:
    """The report told what the kit did to the holes (necks widened, parts beyond slits cut off) and its pieces."""
    if kit.necks:
        widths = [w for _, _, w in kit.necks]
        report.note(
            f"widened {len(kit.necks):,} neck{'s' if len(kit.necks) != 1 else ''} of holes narrower than the "
            f"kerf (narrowest {min(widths):.3g} mm) so each hole is cut as one opening for its piece"
        )
    if kit.split:
        n = len(kit.split)
        where = ", ".join(f"({x:.4g}, {y:.4g})" for x, y in kit.split[:3]) + (f" and {n - 3:,} more" if n > 3 else "")
        report.add(
            "uncut_slit",
            f"{n:,} part{'s' if n != 1 else ''} of holes beyond a slit narrower than the kerf "
            f"(no straight cut inside the hole reaches {'them' if n != 1 else 'it'}) left as lattice and "
            f"cut off {'their pieces' if n != 1 else 'its piece'} (at {where}); make the stroke narrower "
            f"or the kerf smaller to keep {'them' if n != 1 else 'it'}",
            count=n,
            locations=kit.split,
        )
    if len(kit.pieces):
        report.note(
            f"pieces: {stats['pieces']:,} pieces of {kit.kinds} shapes, fit {fit:+g} mm, "
            f"{kit.filled_holes:,} holes too small filled; laser job {pieces.estimate.line()}"
        )
    else:
        report.note(
            f"pieces: none, every one of the {kit.filled_holes:,} holes is too small for a piece (filled): "
            "the kit is its lattice alone, and no pieces file is written"
        )


def _note_colour_sheet(name: str, plan: CutPlan, report: Report) -> None:
    """The report told one colour's pieces: how many, their area and the sheet they need."""
    part = plan.part if plan.part is not None else shapely.Polygon()
    n = 0 if part.is_empty else len(shapely.get_parts(part))
    area = float(part.area) if n else 0.0
    x0, y0, x1, y1 = part.bounds if n else (0.0, 0.0, 0.0, 0.0)
    report.stats["pieces_by_colour"][name] = {
        "pieces": n,
        "area_mm2": round(area, 3),
        "sheet_mm": [round(x1 - x0, 3), round(y1 - y0, 3)],
    }
    report.note(
        f"pieces in {name}: {n:,} piece{'s' if n != 1 else ''}, {area:,.1f} mm^2, on a sheet of at least "
        f"{x1 - x0:.1f} x {y1 - y0:.1f} mm (laid like the lattice); laser job {plan.estimate.line()}"
    )


def _pieces_by_colour(kit, colours, profile, lattice: CutPlan, kx: float, ky: float, tabs=(0.0, 1)) -> tuple:
    """The kit's pieces as one plan per colour (see :func:`plan_kit`)."""
    pieces = np.asarray(kit.pieces, dtype=object)
    owner = np.zeros(len(pieces), int)
    faces = [(np.asarray(list(f), dtype=object), k) for k, (_, f) in enumerate(colours) if len(f)]
    if len(pieces) and faces:
        polys = np.concatenate([f for f, _ in faces])
        which = np.concatenate([np.full(len(f), k) for f, k in faces])
        probe = shapely.point_on_surface(np.asarray(kit.holes, dtype=object))
        near = shapely.STRtree(polys).query_nearest(probe, return_distance=False)
        owner[near[0]] = which[near[1]]
    out = []
    for k, (name, _) in enumerate(colours):
        mine = pieces[owner == k]
        if not len(mine):
            continue  # a colour whose faces were all too small for a piece (filled): no sheet, no file
        paths = {}
        if len(mine):
            paths["inner"], paths["outer"] = laser_contours(
                shapely.multipolygons(list(shapely.get_parts(mine))),
                kerf_mm=kx,
                kerf_y_mm=ky,
                tolerance_mm=profile.tolerance_mm,
            )
        part = shapely.union_all(mine) if len(mine) else shapely.Polygon()
        closed = split_at_tabs(paths, tabs[0], tabs[1], None)
        out.append(
            (
                name,
                make_plan(profile, "pierced", kx, paths, like=lattice, part=part, outer_closed=closed),
            )
        )
    return tuple(out)


def with_report(plan: CutPlan, report: Report) -> CutPlan:
    """``plan`` with another report (a file's own copy)."""
    return replace(plan, report=report)
