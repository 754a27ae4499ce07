"""3D-printing checks from the printer profile, reported like the laser checks.

:func:`check_print` adds these findings to a :class:`~fabtiles.core.report.Report`:

``small_hole``
    Openings of the print no disc of the profile's ``min_hole_mm`` fits in (default
    two nozzle widths): the lines laid around them squeeze them shut, and the slicer
    still traces each one (3,017 holes, 2,396 of them under 0.4 mm, kept PrusaSlicer
    busy for 12 minutes on one 150 mm tile). What they are depends on the style: holes through a
    pierced tile; gaps in a relief's raised pattern; in a deboss, grooves too narrow
    to stay open and islands of the plate too small to print among the grooves.
    ``fill_small_holes`` (:func:`fill_print_holes`) fills every one of them.
``thin_wall``
    Material narrower than the profile's ``min_wall_mm`` (about two line widths of
    the nozzle): the slicer drops such walls or prints them as a single line. Two
    boundaries of the same piece closer than the minimum are looked for (as the
    laser's thin bridges), whatever the stroke: clipping at the outline and the
    packing's own circles leave slivers narrower than the bands. In a deboss the
    walls are the plate's islands between the grooves.
``thin_layer``
    A height thinner than two layers (``2 * layer_height_mm``): the relief or the
    plate (relief), the tile (pierced), the groove or the floor under it (deboss).
``bed_size``
    The tile does not fit the profile's bed either way round (a finding, not an
    error: the file may be meant for another printer).
``loose_part``
    Pierced style only: pieces of material not joined to the largest one.
``filled_pattern``
    ``fill_small_holes`` filled so many openings that less than
    :data:`~fabtiles.geometry.narrow.PATTERN_KEPT` of the pattern's open area is left
    (a deboss: of its grooves); :func:`check_print_pattern`, run on the region before
    and after the filling.

>>> from shapely.geometry import box
>>> plate = box(0, 0, 300, 20)
>>> r = check_print(plate, plate, "fdm-0.4mm", stroke=0.5, relief_mm=0.3)
>>> [f.code for f in r.findings]
['thin_wall', 'thin_layer', 'bed_size']
>>> holed = box(0, 0, 20, 20).difference(box(5, 5, 5.3, 5.3))
>>> [f.message for f in check_print(holed, box(0, 0, 20, 20), "fdm-0.4mm", style="pierced").findings]
['1 hole through the tile narrower than min_hole_mm = 0.8 mm (narrowest 0.3 mm): the plastic laid around it squeezes it shut while the slicer traces it, slowly; fill_small_holes fills it']
"""  # noqa: E501 - a doctest's lines are as Python prints them

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import shapely

from ..core.errors import FabricationError, ParameterError, ProfileError
from ..core.report import Report, distinct
from ..machines.profiles import PrinterProfile, load_profile
from .contours import polygon_parts
from .interlace import polygonal
from .laser_checks import add_loose_parts, fits_bed
from .narrow import (
    MAX_LOCATIONS,
    add_small_holes,
    check_pattern_kept,
    hole_polygons,
    hole_widths,
    locations,
    narrow_places,
    neck_pieces,
    small_hole_mask,
    without_holes,
)

WALL_TOLERANCE_MM = 0.01
"""A wall this much thinner than the minimum still counts as the minimum (rounding)."""

NECK_MM = 0.098
"""An opening is judged as the pieces either side of a neck narrower than this, as a slicer sees it:
PrusaSlicer closes every crack narrower than twice its ``slice_closing_radius`` (0.049 mm by
default) before it traces a slice, so such a neck splits the opening into loops of their own, and
a side narrower than this goes (the mesh's 2^-10 mm grid can close a neck by itself too)."""

PRINT_TOLERANCE_MM = 0.01
"""Openings of less than this squared in area are slivers of the geometry, not holes: they are
filled with the rest but not counted (the laser profiles' ``tolerance_mm`` does the same)."""

OPENINGS = {
    "pierced": ("hole through the tile", "holes through the tile"),
    "relief": ("gap in the raised pattern", "gaps in the raised pattern"),
    "mosaic": ("face narrower than the nozzle's lines", "faces narrower than the nozzle's lines"),
}
"""What a print's small openings are, by style (a deboss has two kinds, see :func:`small_openings`)."""


class SmallOpenings(NamedTuple):
    """The openings of a print narrower than its printer's ``min_hole_mm`` (shapely polygons)."""

    holes: np.ndarray
    """Holes of the material (pierced, relief); in a deboss, the grooves too narrow to stay open."""
    islands: np.ndarray
    """Deboss: islands of the plate among the grooves, too small to print (empty for the other styles)."""

    @property
    def count(self) -> int:  # type: ignore[override]  # the number of openings; tuple.count is not used
        return len(self.holes) + len(self.islands)


def flatten_holes(region, tolerance_mm: float):
    """``region`` with its holes' rings simplified within ``tolerance_mm`` (Douglas-Peucker, ring by ring).

    The pattern's round joins and circles are flattened for the laser's 0.005 mm; a
    print needs no finer than its ``tolerance_mm``, and a slicer's time grows with the
    points of every slice. Outer rings are kept as they are, so the material still meets
    the outline exactly. Ring by ring, far quicker than GEOS's topology-preserving
    simplification of the whole region (``docs/speed.md``); should simplified rings
    cross, the region is returned unchanged.

    >>> import shapely
    >>> hole = shapely.Point(5, 5).buffer(2, quad_segs=64)
    >>> plate = shapely.box(0, 0, 10, 10).difference(hole)
    >>> flat = flatten_holes(plate, 0.02)
    >>> int(shapely.get_num_coordinates(plate)), int(shapely.get_num_coordinates(flat)), flat.is_valid
    (262, 38, True)
    """
    if tolerance_mm <= 0:
        return region
    parts = shapely.get_parts(region)
    rings, idx = shapely.get_rings(parts, return_index=True)
    if len(rings) == len(parts):
        return region
    outer = np.zeros(len(rings), bool)
    outer[np.concatenate([[0], np.cumsum(shapely.get_num_interior_rings(parts) + 1)[:-1]])] = True
    flat = rings.copy()
    flat[~outer] = _simplify_rings(rings[~outer], tolerance_mm)
    # a ring too small to simplify (collapsed, or no longer a simple ring) stays as it was
    bad = (shapely.get_type_id(flat) != 2) | (shapely.get_num_coordinates(flat) < 4)
    flat[bad] = rings[bad]
    bad = ~shapely.is_valid(shapely.polygons(flat))
    flat[bad] = rings[bad]
    polys = shapely.polygons(flat, indices=idx)
    out = polys[0] if len(polys) == 1 and region.geom_type == "Polygon" else shapely.multipolygons(polys)
    return out if out.is_valid else region


def _simplify_rings(rings, tolerance_mm: float):
    """Closed rings simplified by Douglas-Peucker, each point of a ring within ``tolerance_mm`` of its result.

    GEOS simplifies a ring as a closed loop and may then drop its first point as well; the points
    that point's neighbours had stood for can end up farther than the tolerance (0.026 mm for
    0.02 mm on the inner edge of a 40 mm circle tile's frame). Those rings are simplified again
    as lines from their first point back to it, which keeps every point within the tolerance;
    a ring that collapses so comes back as a line of fewer than four points, which the caller
    keeps as it was.

    >>> import shapely
    >>> arc = shapely.LinearRing([(14.1857, 4.0252), (13.4944, 4.294), (12.8155, 4.5928), (12.1503, 4.9208),
    ...     (11.5, 5.2776), (10.8659, 5.6623), (10.2492, 6.0744), (9.6511, 6.513), (9.0726, 6.9772),
    ...     (8.6858, 7.3164), (10.0, 7.3939), (11.503, 7.3053), (12.7711, 6.4936), (13.935, 5.5384),
    ...     (14.4837, 4.1363), (14.5445, 3.9034)])
    >>> round(float(shapely.hausdorff_distance(arc, shapely.simplify(arc, 0.02, preserve_topology=False))), 4)
    0.0261
    >>> (flat,) = _simplify_rings([arc], 0.02)
    >>> flat.geom_type, float(shapely.hausdorff_distance(arc, flat)) <= 0.02, len(flat.coords) < len(arc.coords)
    ('LinearRing', True, True)
    """
    rings = np.asarray(rings, dtype=object)
    flat = shapely.simplify(rings, tolerance_mm, preserve_topology=False)
    far = np.flatnonzero(shapely.hausdorff_distance(rings, flat) > tolerance_mm)
    if len(far):
        coords, idx = shapely.get_coordinates(rings[far], return_index=True)
        lines = shapely.simplify(shapely.linestrings(coords, indices=idx), tolerance_mm, preserve_topology=False)
        kept = shapely.get_num_coordinates(lines) >= 4
        if kept.any():
            coords, idx = shapely.get_coordinates(lines[kept], return_index=True)
            flat[far[kept]] = shapely.linearrings(coords, indices=idx)
        flat[far[~kept]] = lines[~kept]
    return flat


def print_region(
    region,
    outline,
    profile,
    style: str,
    *,
    fill_small_holes: bool = False,
    flatten: bool = True,
    period_mm: float | None = None,
):
    """The material a print is built from: ``(region, filled)``.

    Its holes thinned within the profile's ``tolerance_mm`` (:func:`flatten_holes`;
    ``flatten=False`` keeps them, for an interlaced relief whose dips lie 0.02 mm inside
    the bands), then, with ``fill_small_holes``, its openings narrower than the profile's
    ``min_hole_mm`` filled (:func:`fill_print_holes`; ``filled`` counts them). The print
    writers, the 3D view and ``fabtiles check`` all build and check this region.

    ``period_mm``: the region repeats along x with this period and its outline is one period
    (a cylinder's unrolled strip): an opening the strip's ends cut is judged whole
    (:func:`fill_periodic_holes`), so both ends are filled alike and still meet.
    """
    profile = load_profile(profile, kind="printer")
    if flatten:
        region = flatten_holes(region, profile.tolerance_mm)
    if not fill_small_holes:
        return region, 0
    check_min_hole(profile, outline)
    if period_mm is not None:
        return fill_periodic_holes(region, outline, profile, style, period_mm=period_mm)
    return fill_print_holes(region, outline, profile, style)


SEAM_GRID_MM = 2.0**-20
"""The grid a periodic region's copies are joined on (:func:`fill_periodic_holes`): far finer than the mesh's
grid, coarse enough that two copies' edges at the seam a rounding apart meet."""


def fill_periodic_holes(region, outline, profile, style: str, *, period_mm: float):
    """:func:`fill_print_holes` of a region that repeats along x every ``period_mm``, its outline one period.

    The openings are judged on the region repeated half a period beyond each end, so one that
    the ends cut is judged whole, once, and filled (or not) at both ends alike; ``count`` is the
    openings changed whose centre lies in the outline's period. ``(region, count)``.

    >>> from shapely.geometry import box
    >>> strip = box(0, 0, 20, 10).difference(box(-0.2, 4, 0.5, 6)).difference(box(19.8, 4, 20.2, 6))
    >>> filled, n = fill_periodic_holes(strip, box(0, 0, 20, 10), "fdm-0.4mm", "pierced", period_mm=20)
    >>> n, round(filled.area, 3)
    (1, 200.0)
    """
    from shapely import affinity

    profile = load_profile(profile, kind="printer")
    x0, y0, x1, y1 = outline.bounds
    if abs((x1 - x0) - period_mm) > 1e-6 * period_mm:
        raise ParameterError(
            f"period_mm = {period_mm:g} is not the outline's width, {x1 - x0:g} mm: a periodic region's outline "
            "is one period"
        )
    wide = shapely.box(x0 - period_mm / 2, y0, x1 + period_mm / 2, y1)
    copies = [affinity.translate(region, xoff=k * period_mm) for k in (-1, 0, 1)]
    # on a fine grid, so that copies whose edges at the seam lie a rounding apart are one (an opening across it
    # split by a gap of nanometres would be judged as two)
    repeated = polygonal(shapely.intersection(shapely.union_all(copies, grid_size=SEAM_GRID_MM), wide))
    filled, _ = fill_print_holes(repeated, wide, profile, style)
    # each change is kept once, where its centre lies in the period, and repeated: an opening at the edge of
    # what a disc fits may be judged apart from its copy one period on, and the strip's ends would then differ
    added, removed = (
        _in_period(polygonal(shapely.difference(a, b, grid_size=SEAM_GRID_MM)), x0, x1)
        for a, b in ((filled, repeated), (repeated, filled))
    )
    count = len(added) + len(removed)
    if not count:
        return polygonal(shapely.intersection(region, outline)), 0
    # made on the period and a hair round it (the repeated region's, on its grid), then cut to the outline
    window = shapely.box(x0 - 1.0, y0 - 1.0, x1 + 1.0, y1 + 1.0)
    base = shapely.intersection(repeated, window, grid_size=SEAM_GRID_MM)
    add, take = (_moved(g, period_mm, window) for g in (added, removed))
    out = shapely.union_all([base, *add], grid_size=SEAM_GRID_MM) if len(add) else base
    if len(take):
        out = shapely.difference(out, shapely.union_all(take, grid_size=SEAM_GRID_MM), grid_size=SEAM_GRID_MM)
    return polygonal(shapely.intersection(out, outline)), count


def _moved(parts: list, period_mm: float, window):
    """``parts`` and their copies a period either way, those that reach into ``window``."""
    from shapely import affinity

    again = np.array([affinity.translate(g, xoff=k * period_mm) for g in parts for k in (-1, 0, 1)], dtype=object)
    return again[shapely.intersects(again, window)] if len(again) else again


def _in_period(geometry, x0: float, x1: float) -> list:
    """The parts of ``geometry`` whose centre lies in ``[x0, x1)``."""
    parts = shapely.get_parts(geometry)
    centres = shapely.get_coordinates(shapely.centroid(parts))[:, 0] if len(parts) else np.empty(0)
    return list(parts[(centres >= x0) & (centres < x1)])


def check_print_pattern(before, after, outline, profile, style: str, *, stroke=None, report: Report) -> float:
    """Report ``filled_pattern`` when ``fill_small_holes`` left too little of the print's pattern.

    ``before`` and ``after`` are the region before and after :func:`fill_print_holes`: the
    pattern's openings (a deboss's islands of plate among its grooves), and a deboss's
    grooves, which are filled with plate when too narrow. Returns the share kept (see
    :func:`~fabtiles.geometry.narrow.check_pattern_kept`).

    >>> from shapely.geometry import box
    >>> plate = box(0, 0, 20, 20).difference(box(4, 4, 4.5, 4.5))
    >>> r = Report(path="", format="")
    >>> check_print_pattern(plate, box(0, 0, 20, 20), box(0, 0, 20, 20), load_profile("fdm-0.4mm"), "relief",
    ...                     stroke=1.0, report=r)
    0.0
    >>> print(r.findings[0].message)  # doctest: +ELLIPSIS
    filling the openings narrower than min_hole_mm = 0.8 mm of printer profile 'fdm-0.4mm' left none of ... or a printer profile with min_hole_mm <= 0.5 mm (a finer nozzle)
    """  # noqa: E501 - a doctest's lines are as Python prints them
    profile = load_profile(profile, kind="printer")
    deboss = style == "deboss"
    return check_pattern_kept(
        report,
        before,
        after,
        outline,
        limit_mm=profile.min_hole_mm,
        limit=f"min_hole_mm = {profile.min_hole_mm:g} mm of printer profile {profile.name!r}",
        openings="islands of the plate" if deboss else "openings",
        stroke=stroke,
        min_stroke_mm=profile.min_wall_mm,
        deboss=deboss,
        tool="a printer profile with min_hole_mm <= {w} mm (a finer nozzle)",
        tolerance_mm=PRINT_TOLERANCE_MM,
    )


def check_min_hole(profile: PrinterProfile, outline) -> None:
    """Refuse a ``min_hole_mm`` larger than the tile (every opening would be filled).

    >>> from dataclasses import replace
    >>> from shapely.geometry import box
    >>> check_min_hole(replace(load_profile("fdm-0.4mm"), min_hole_mm=60.0), box(0, 0, 50, 80))
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ProfileError: printer profile 'fdm-0.4mm': min_hole_mm = 60 mm is larger than the tile (50 x 80 mm); give the narrowest hole the printer makes, about two widths of its 0.4 mm nozzle, or 0 for no limit
    """  # noqa: E501 - a doctest's lines are as Python prints them
    m = profile.min_hole_mm
    if isinstance(m, bool) or not isinstance(m, (int, float)) or not np.isfinite(m) or m < 0:
        raise ProfileError(
            f"printer profile {profile.name!r}: min_hole_mm must be a finite number of mm >= 0, got {m!r}"
        )
    xmin, ymin, xmax, ymax = outline.bounds
    w, h = xmax - xmin, ymax - ymin
    if m > min(w, h):
        raise ProfileError(
            f"printer profile {profile.name!r}: min_hole_mm = {m:g} mm is larger than the tile ({w:g} x {h:g} mm); "
            f"give the narrowest hole the printer makes, about two widths of its {profile.nozzle_mm:g} mm nozzle, "
            "or 0 for no limit"
        )


def _real(polys: np.ndarray) -> np.ndarray:
    return polys[shapely.area(polys) > PRINT_TOLERANCE_MM**2]


def plate_pieces(region, outline) -> np.ndarray:
    """A deboss's plate at the grooves' height, in pieces: ``outline`` less ``region`` (the grooves).

    >>> from shapely.geometry import box
    >>> pieces = plate_pieces(box(0, 4, 10, 5).union(box(4, 0, 5, 10)), box(0, 0, 10, 10))
    >>> sorted(shapely.area(pieces).round(3).tolist())
    [16.0, 20.0, 20.0, 25.0]
    """
    # one GEOS overlay for all the holes
    return _real(shapely.get_parts(shapely.difference(outline, region)))


def material_openings(parts: np.ndarray, outline):
    """The openings of material ``parts`` inside ``outline``: ``(openings, holes)``.

    The openings are the pieces of the outline without material: the holes, and the
    notches where the material does not reach the outline's edge (a tile without a
    frame); ``holes`` counts the first of them, which are the parts' holes in
    :func:`~fabtiles.geometry.narrow.hole_polygons` order (0 when the region is in
    several parts: then every opening comes from one overlay, since a part may lie in
    another's hole).

    >>> from shapely.geometry import box
    >>> plate = box(0, 0, 9, 10).difference(box(2, 2, 4, 4))
    >>> openings, holes = material_openings(shapely.get_parts(plate), box(0, 0, 10, 10))
    >>> shapely.area(openings).tolist(), holes
    ([4.0, 10.0], 1)
    """
    if len(parts) > 1:
        return plate_pieces(shapely.multipolygons(parts), outline), 0
    holes = hole_polygons(parts)[0]
    # only the outer ring against the outline: no overlay of the holes (the sheet's 9,947)
    notches = _real(shapely.get_parts(shapely.difference(outline, shapely.polygons(shapely.get_exterior_ring(parts)))))
    return np.concatenate([holes, notches]), len(holes)


class _Judged(NamedTuple):
    """What of some openings is too small (:func:`_judge`)."""

    whole: np.ndarray
    """Per opening: no piece of it (:data:`NECK_MM`) has room for the disc, or it has no real area."""
    small: np.ndarray
    """What is too small to print, as the slicer traces it: every small piece (an opening split at a
    neck is as many loops), and each opening of real area too thin to leave a piece."""
    partial: np.ndarray
    """For each opening with a roomy and a small side of a neck: the opening less its roomy pieces,
    i.e. the small side, and the tips sharper than the neck's width that the cut took."""


def _judge(openings: np.ndarray, min_hole_mm: float) -> _Judged:
    """Judge each opening by its pieces either side of its necks (:func:`~fabtiles.geometry.narrow.neck_pieces`)."""
    openings = np.asarray(openings, dtype=object)
    pieces, owner = neck_pieces(openings, NECK_MM)
    tiny = shapely.area(pieces) <= PRINT_TOLERANCE_MM**2
    small = (small_hole_mask(pieces, min_hole_mm) & ~tiny) if len(pieces) else tiny
    gone = small | tiny
    n = len(openings)
    whole = np.bincount(owner, weights=~gone, minlength=n) == 0
    real = shapely.area(openings) > PRINT_TOLERANCE_MM**2
    mixed = ~whole & (np.bincount(owner, weights=small, minlength=n) > 0)
    partial = np.empty(0, object)
    if mixed.any():
        roomy = ~gone & mixed[owner]
        # the roomy pieces are the opening by NECK_MM / 2 already; a micron more keeps float hairs
        # along their shared edges with the opening out of the difference
        grown = shapely.intersection(shapely.buffer(pieces[roomy], 1e-3, quad_segs=2), openings[owner[roomy]])
        partial = shapely.difference(openings[mixed], shapely.union_all(grown))
        partial = partial[~shapely.is_empty(partial)]
    # counted as the slicer sees them: each small piece; an opening too thin to leave any piece, once
    bare = whole & real & (np.bincount(owner, weights=small, minlength=n) == 0)
    return _Judged(whole, np.concatenate([pieces[small], openings[bare]]), partial)


def small_openings(region, outline, profile, style: str) -> SmallOpenings:
    """The openings of a print of ``region`` no disc of ``profile.min_hole_mm`` fits in.

    Relief and pierced: the material's holes. Deboss: the grooves (pieces of
    ``region``) and the islands of the plate among them (pieces of
    :func:`plate_pieces`, which include the plate's pieces at the tile's edge). An
    opening that narrows below :data:`NECK_MM` is judged as the pieces either side.

    >>> from shapely.geometry import box
    >>> grooves = box(0, 0, 10, 10).difference(box(1, 1, 1.3, 1.3)).union(box(20, 0, 20.2, 10))
    >>> found = small_openings(grooves, box(-5, -5, 30, 15), load_profile("fdm-0.4mm"), "deboss")
    >>> [shapely.bounds(g).tolist() for g in found.holes], [shapely.bounds(g).tolist() for g in found.islands]
    ([[20.0, 0.0, 20.2, 10.0]], [[1.0, 1.0, 1.3, 1.3]])
    """
    profile = load_profile(profile, kind="printer")
    parts = polygon_parts(region)
    m = profile.min_hole_mm
    if style != "deboss":
        return SmallOpenings(_judge(material_openings(parts, outline)[0], m).small, np.empty(0, object))
    return SmallOpenings(_judge(parts, m).small, _judge(plate_pieces(region, outline), m).small)


def fill_print_holes(region, outline, profile, style: str):
    """``region`` with the openings too small for the printer filled: ``(region, count)``.

    Relief and pierced: the material's small holes become material. Deboss (the
    region is the grooves): an island of the plate too small to print becomes groove,
    and a groove too narrow to stay open becomes plate. An opening with a neck
    narrower than :data:`NECK_MM` is filled on the side of the neck no disc fits in.
    Slivers under :data:`PRINT_TOLERANCE_MM` go too, uncounted.

    >>> from shapely.geometry import box
    >>> plate = box(0, 0, 20, 20).difference(box(5, 5, 5.3, 5.3)).difference(box(8, 8, 12, 12))
    >>> filled, n = fill_print_holes(plate, box(0, 0, 20, 20), "fdm-0.4mm", "pierced")
    >>> n, len(filled.interiors)
    (1, 1)
    """
    profile = load_profile(profile, kind="printer")
    total = 0
    for _ in range(FILL_ROUNDS):  # a partial fill or an overlay can leave a sliver: look again
        region, count, again = _fill_once(region, outline, profile.min_hole_mm, style)
        total += count
        if not again:
            break
    if region.is_empty:
        raise FabricationError(
            f"every groove of this deboss is narrower than min_hole_mm = {profile.min_hole_mm:g} mm of printer "
            f"profile {profile.name!r}, so filling them leaves a blank plate; make the stroke wider, or set "
            "fill_small_holes = false"
        )
    return region, total


FILL_ROUNDS = 3
"""Rounds of :func:`fill_print_holes`: a round that only dropped whole holes (the common case) is the last."""


def _fill_once(region, outline, m: float, style: str):
    """One round of :func:`fill_print_holes`: ``(region, count, look again)``."""
    if style != "deboss":
        parts = polygon_parts(region)
        openings, nholes = material_openings(parts, outline)
        found = _judge(openings, m)
        if not found.whole.any() and not len(found.partial):
            return region, 0, False
        # the small holes' rings are dropped (exact, no overlay); the rest is added to the material
        whole = found.whole.copy()
        out = region
        if nholes:
            holes, owner = hole_polygons(parts)
            out = without_holes(region, parts, holes, owner, whole[:nholes])
            whole[:nholes] = False
        add = np.concatenate([openings[whole], found.partial])
        if len(add):
            out = _polygons(shapely.intersection(shapely.union_all(np.concatenate([[out], add])), outline))
        return out, len(found.small), bool(len(add))
    grooves = shapely.get_parts(region)
    islands = shapely.get_parts(shapely.difference(outline, region))
    g, i = _judge(grooves, m), _judge(islands, m)
    if not (g.whole.any() or i.whole.any() or len(g.partial) or len(i.partial)):
        return region, 0, False
    # the islands too small become groove, then the grooves too narrow plate again
    out = shapely.union_all(np.concatenate([grooves[~g.whole], islands[i.whole], i.partial]))
    if len(g.partial):
        out = shapely.difference(out, shapely.union_all(g.partial))
    return _polygons(shapely.intersection(out, outline)), len(g.small) + len(i.small), True


def _polygons(geometry):
    """The polygons of an overlay's result of real area, as a Polygon or MultiPolygon."""
    parts = shapely.get_parts(geometry)
    parts = parts[(shapely.get_type_id(parts) == 3) & (shapely.area(parts) > PRINT_TOLERANCE_MM**2)]
    if not len(parts):
        return shapely.Polygon()
    return parts[0] if len(parts) == 1 else shapely.multipolygons(parts)


def _report_small_openings(report: Report, found: SmallOpenings, profile: PrinterProfile, style: str) -> None:
    m = profile.min_hole_mm
    assert m is not None  # called for a printer that has a smallest hole
    where = f"narrower than min_hole_mm = {m:g} mm"

    def message(n, narrowest):
        width = f"(narrowest {distinct(narrowest, m)} mm)"
        if style != "deboss":
            one, many = OPENINGS[style]
            it = "it" if n == 1 else "them"
            return (
                f"{n:,} {one if n == 1 else many} {where} {width}: the plastic laid around {it} squeezes {it} "
                f"shut while the slicer traces {it}, slowly; fill_small_holes fills {it}"
            )
        g, i = len(found.holes), len(found.islands)
        kinds = ([f"{g:,} groove{'s' if g != 1 else ''} too narrow to stay open"] if g else []) + (
            [f"{i:,} island{'s' if i != 1 else ''} of the plate too small to print among the grooves"] if i else []
        )
        return (
            f"{' and '.join(kinds)}, {where} {width}: the slicer traces each one, slowly; fill_small_holes fills them"
        )

    add_small_holes(
        report,
        np.concatenate([found.holes, found.islands]),
        tolerance_mm=WALL_TOLERANCE_MM,
        message=message,
        limit_mm=m,
    )


def check_print(
    region,
    outline,
    profile,
    *,
    stroke=None,
    style=None,
    base_mm=None,
    relief_mm=None,
    pierced_mm=None,
    deboss_mm=None,
    mosaic_inset_mm=None,
    report: Report | None = None,
) -> Report:
    """Run the printability checks; findings go into ``report`` (see the module text).

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The material, in file coordinates (mm).
    outline : shapely Polygon or MultiPolygon
        The tile outline.
    profile : str, Path or PrinterProfile
    stroke : float, optional
        Stroke width, named in the message when it is itself thinner than the minimum wall.
    style, base_mm, relief_mm, pierced_mm, deboss_mm : optional
        The part's style and heights; the profile's when not given.
    report : Report, optional
        Added to and returned; a new one (path ``""``) otherwise.
    """
    from .stack import resolve_stack

    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, base_mm, relief_mm, pierced_mm, deboss_mm, mosaic_inset_mm)
    check_min_hole(profile, outline)
    report = report if report is not None else Report(path="", format="print")

    found = small_openings(region, outline, profile, stack.style)
    if found.count:
        _report_small_openings(report, found, profile, stack.style)

    if stack.style == "deboss":  # the walls are the plate's islands among the grooves
        _check_islands(region, outline, profile, report)
    else:
        _check_walls(region, profile, stroke, report)
    _check_layers(stack, profile, report)

    xmin, ymin, xmax, ymax = outline.bounds
    w, h = xmax - xmin, ymax - ymin
    bw, bh = profile.bed_mm
    if not fits_bed(w, h, profile.bed_mm):
        report.add(
            "bed_size",
            f"the tile is {w:g} x {h:g} mm, larger than the {bw:g} x {bh:g} mm bed of printer profile "
            f"{profile.name!r} (either way round)",
        )

    if stack.style == "pierced":
        _check_loose(region, report)
    return report


def _check_islands(region, outline, profile, report: Report) -> None:
    """A debossed plate's walls: its islands among the grooves narrower than ``min_wall_mm``."""
    wall = profile.min_wall_mm
    islands = plate_pieces(region, outline)
    thin = (
        islands[small_hole_mask(islands, wall) & ~small_hole_mask(islands, profile.min_hole_mm)]
        if len(islands)
        else islands
    )
    if len(thin):
        centres, widths = hole_widths(thin, tolerance_mm=WALL_TOLERANCE_MM)
        n = len(thin)
        report.add(
            "thin_wall",
            f"{n:,} island{'s' if n > 1 else ''} of the plate among the grooves narrower than "
            f"min_wall_mm = {wall:g} mm (narrowest {distinct(float(widths.min()), wall)} mm): they "
            "print thin or not at all",
            count=n,
            locations=locations(centres),
            sizes=widths[:MAX_LOCATIONS].round(3),
            worst=round(float(widths.min()), 3),
            limit=wall,
        )


def _check_walls(region, profile, stroke, report: Report) -> None:
    """The walls narrower than ``min_wall_mm``: between two rings, or whole pieces no wall fits in."""
    wall = profile.min_wall_mm
    count, narrowest, mids, widths = narrow_places(region, wall, tolerance=WALL_TOLERANCE_MM)
    # pieces no wall fits in anywhere: one ring each, so no pair of rings finds them
    pieces = _real(polygon_parts(region))
    pieces = pieces[shapely.get_num_interior_rings(pieces) == 0]
    slivers = pieces[small_hole_mask(pieces, wall * (1 - 1e-9) - WALL_TOLERANCE_MM)]
    if len(slivers):
        centres, sizes = hole_widths(slivers, tolerance_mm=WALL_TOLERANCE_MM)
        count += len(slivers)
        narrowest = min(narrowest, float(sizes.min()))
        mids, widths = np.concatenate([mids, centres]), np.concatenate([widths, sizes])
    if stroke is not None and stroke < wall * (1 - 1e-9):
        # the whole pattern is thin; the places come from the geometry, for the overlay
        report.add(
            "thin_wall",
            f"the stroke is {distinct(stroke, wall)} mm, narrower than min_wall_mm = {wall:g} mm "
            f"(about two line widths of the {profile.nozzle_mm:g} mm nozzle): walls print thin or not at all",
            count=max(count, 1),
            locations=locations(mids),
            sizes=widths[:MAX_LOCATIONS].round(3),
            worst=round(min(stroke, narrowest), 3),
            limit=wall,
        )
    elif count:
        extra = (
            f"; the stroke is {stroke:g} mm, so they are slivers the outline or a join cut"
            if stroke is not None
            else ""
        )
        report.add(
            "thin_wall",
            f"{count:,} wall{'s' if count > 1 else ''} narrower than min_wall_mm = {wall:g} mm "
            f"(narrowest {distinct(narrowest, wall)} mm{extra}): they print thin or not at all",
            count=count,
            locations=locations(mids),
            sizes=widths[:MAX_LOCATIONS].round(3),
            worst=round(narrowest, 3),
            limit=wall,
        )


def _check_layers(stack, profile, report: Report) -> None:
    """The style's heights thinner than two layers."""
    layers = 2 * profile.layer_height_mm
    heights = {
        "relief": (("base_mm", stack.base, "the plate"), ("relief_mm", stack.relief, "the relief")),
        "pierced": (("pierced_mm", stack.pierced, "the tile"),),
        "mosaic": (
            ("base_mm", stack.base, "the plate"),
            ("relief_mm - mosaic_inset_mm", stack.relief - stack.inset, "the faces over the plate"),
        ),
        "deboss": (
            ("deboss_mm", stack.deboss, "the groove depth"),
            ("base_mm - deboss_mm", stack.base - stack.deboss, "the floor under the grooves"),
        ),
    }[stack.style]
    for key, value, what in heights:
        if value < layers * (1 - 1e-9):
            report.add(
                "thin_layer",
                f"{what} ({key} = {value:g} mm) is thinner than two layers (2 x layer_height_mm = {layers:g} mm)",
            )


def _check_loose(region, report: Report) -> None:
    """A pierced tile's pieces not joined to the largest (it falls apart)."""
    parts = shapely.get_parts(region)
    parts = parts[shapely.area(parts) > 0]
    if len(parts) > 1:
        area = shapely.area(parts)
        loose = np.ones(len(parts), bool)
        loose[np.argmax(area)] = False
        add_loose_parts(report, parts, area, loose, falls="a pierced tile falls apart")
