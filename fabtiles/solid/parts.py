"""3D-printable meshes and binary STL, checked as a slicer will read them.

Styles (heights from the printer profile, overridable per call):

``relief``
    A base plate of the outline, ``base_mm`` thick, with the material region raised
    ``relief_mm`` on top. STL: one body. As parts (3MF, see
    :mod:`fabtiles.export.threemf`): ``"base"`` and ``"pattern"``, touching at
    ``z = base_mm`` without overlapping, so a slicer can give each its own filament.
``pierced``
    The material region alone, ``pierced_mm`` thick (body ``"pattern"``).
``deboss``
    A plate ``base_mm`` thick with the region sunk as grooves ``deboss_mm`` deep
    (body ``"plate"``); optionally a second part ``"inlay"`` filling the grooves
    flush with the plate's top, for a two-colour inlay print.

Meshes are built directly as stacked prisms (see :mod:`fabtiles.solid._mesh_build`),
with every x, y on a 2**-10 mm grid that float32 stores exactly. Before anything is
written, each body is checked the way a slicer reads the file
(:mod:`fabtiles.solid.mesh_check`): the float32 triangles merged by position
must be watertight, wound consistently, of positive volume, one body per part and
free of degenerate faces. A mesh failing any of this is a
:class:`~fabtiles.FabricationError`, never a file.
trimesh and manifold3d are imported only inside the functions.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, NamedTuple, Protocol

import numpy as np

from ..core.errors import FabricationError, ParameterError
from ..core.report import Report
from ..machines.profiles import load_profile
from ._mesh_build import (
    QUANTUM,
    Stack,
    check_shapes,
    coverage,
    coverage_pair,
    mesh_coverage,
    polygons_of,
    resolve_stack,
    snap,
)
from .mesh_check import check_indexed

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry


# --------------------------------------------------------------------------- building


def prepare_print(
    region,
    outline,
    profile,
    style,
    heights,
    stroke=None,
    *,
    fill_small_holes: bool = False,
    flatten: bool = True,
    period_mm: float | None = None,
    path="",
    fmt="",
):
    """Validate everything, make the region to print and run the printability checks; nothing is built yet.

    Returns ``(profile, stack, report, region)``: ``region`` is the material to build
    (:func:`~fabtiles.geometry.print_checks.print_region`: its holes thinned within the
    profile's ``tolerance_mm`` unless ``flatten=False``, its openings narrower than the
    profile's ``min_hole_mm`` filled when ``fill_small_holes``; ``report.stats["filled_holes"]``
    counts them; ``period_mm``: the region repeats along x with this period, its outline one
    period, and is filled so: a cylinder's strip). A strict profile with findings raises.
    """
    from ..geometry.print_checks import check_print, check_print_pattern, print_region

    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, **heights)
    if not isinstance(fill_small_holes, (bool, np.bool_)):
        raise ParameterError(
            f"fill_small_holes must be True or False, got {fill_small_holes!r}", param="fill_small_holes"
        )
    region, outline = check_shapes(region, outline)
    report = Report(path=str(path), format=fmt)
    designed, _ = print_region(region, outline, profile, stack.style, flatten=flatten)
    region, filled = print_region(
        designed,
        outline,
        profile,
        stack.style,
        fill_small_holes=bool(fill_small_holes),
        flatten=False,
        period_mm=period_mm,
    )
    if fill_small_holes:
        report.stats["filled_holes"] = filled
        if filled:
            report.note(
                f"filled {filled:,} opening{'s' if filled != 1 else ''} narrower than min_hole_mm = "
                f"{profile.min_hole_mm:g} mm of printer profile {profile.name!r}"
            )
    check_print(
        region,
        outline,
        profile,
        stroke=stroke,
        style=stack.style,
        base_mm=stack.base,
        relief_mm=stack.relief,
        pierced_mm=stack.pierced,
        deboss_mm=stack.deboss,
        mosaic_inset_mm=stack.inset,
        report=report,
    )
    if filled:
        check_print_pattern(designed, region, outline, profile, stack.style, stroke=stroke, report=report)
    report.raise_if_strict(profile.strict)
    return profile, stack, report, region


def _snapped(region, outline):
    import shapely

    o = snap(outline)
    rb, ob = np.array(region.bounds), np.array(outline.bounds)
    if np.any(rb[:2] < ob[:2] - 1e-6) or np.any(rb[2:] > ob[2:] + 1e-6):
        region = shapely.intersection(region, outline)
    r = snap(region)
    if r.is_empty or o.is_empty:
        raise FabricationError("the material region is empty once clipped to the outline and snapped to 1 micron")
    return r, o


def _leveled(dips, r):
    """An interlaced relief's dips in the region ``r`` as meshed (:func:`fabtiles.solid.levels.dip_level`), or None."""
    if dips is None:
        return None
    from .levels import dip_level

    return dip_level(dips, r)


def _body_arrays(kind: str, r, o, stack: Stack, shift: int = 0, dips=None):
    """Vertices, faces and cell lines of one body (``dips``: an interlaced relief's, as
    :func:`_leveled` makes them; see :func:`fabtiles.solid.levels.body_layers`).

    ``kind`` is ``"relief"``, ``"base"``, ``"pattern"``, ``"pierced"``, ``"plate"`` or
    ``"inlay"`` (the plate's grooves filled flush);
    ``shift`` moves the meshing cell lines. Returns ``(vertices, faces, (xs, ys))``.
    """
    b, h, t, d = stack.base, stack.relief, stack.pierced, stack.deboss
    if dips is not None and not dips.is_empty and kind in ("relief", "pattern"):
        from .levels import body_coverage

        cov = body_coverage(kind, r, o, stack, dips, shift=shift, leveled=True)
    elif kind == "relief":
        cov = coverage_pair(r, o, region_z=b + h, rest_z=b, bottom=0.0, shift=shift)
    elif kind == "mosaic":  # the whole mosaic as one body: the faces' tops inset below the bands'
        cov = coverage_pair(r, o, region_z=b + h, rest_z=b + h - stack.inset, bottom=0.0, shift=shift)
    elif kind == "base":
        cov = coverage([(o, b)], bottom=0.0, shift=shift)
    elif kind == "pattern":
        cov = coverage([(r, b + h)], bottom=b, shift=shift)
    elif kind == "pierced":
        cov = coverage([(r, t)], bottom=0.0, shift=shift)
    elif kind == "plate":
        cov = coverage_pair(r, o, region_z=b - d, rest_z=b, bottom=0.0, shift=shift)
    elif kind == "inlay":
        cov = coverage([(r, b)], bottom=b - d, shift=shift)
    else:  # pragma: no cover - internal
        raise ValueError(kind)
    return (*mesh_coverage(cov, _recess(kind, stack)), (cov.xs, cov.ys))


ON_THE_BED = ("relief", "mosaic", "base", "pierced", "plate")
"""The body kinds whose bottom lies on the bed: those a :class:`~fabtiles.geometry.stack.Recess` is sunk into."""


def _recess(kind: str, stack: Stack):
    """The stack's recess if a body of ``kind`` has it (its bottom is the bed's), else None."""
    return stack.recess if kind in ON_THE_BED else None


def _expected(kind, r, o, stack, dips=None):
    """Expected volume and number of bodies of one body kind (``dips`` as :func:`_leveled` makes them)."""
    b, h = stack.base, stack.relief
    nr = len(polygons_of(r))
    no = len(polygons_of(o))
    recess = _recess(kind, stack)
    if recess is not None:
        volume, bodies = _expected(kind, r, o, replace(stack, recess=None), dips)
        return volume - recess.volume, bodies
    if dips is not None and kind in ("relief", "pattern"):
        from .levels import dips_volume

        full = {"relief": o.area * b + r.area * h, "pattern": r.area * h}[kind]
        return full - dips_volume(r, dips, stack, leveled=True), {"relief": no, "pattern": nr}[kind]
    return {
        "relief": (o.area * b + r.area * h, no),
        "mosaic": (o.area * (b + h) - (o.area - r.area) * stack.inset, no),
        "base": (o.area * b, no),
        "pattern": (r.area * h, nr),
        "pierced": (r.area * stack.pierced, nr),
        "plate": (o.area * b - r.area * stack.deboss, no),
        "inlay": (r.area * stack.deboss, nr),
    }[kind]


def part_kinds(style: str, single: bool, inlay: bool = False) -> dict:
    """``{part name: mesh kind}`` of a print style: one body when ``single``, else its parts.

    >>> part_kinds("relief", single=False)
    {'base': 'base', 'pattern': 'pattern'}
    >>> part_kinds("deboss", single=False, inlay=True)
    {'plate': 'plate', 'inlay': 'inlay'}
    """
    if style == "relief":
        return {"body": "relief"} if single else {"base": "base", "pattern": "pattern"}
    if style == "pierced":
        return {"pattern": "pierced"}
    if style == "mosaic":  # its parts, one per colour, are made by :func:`mosaic_parts`
        return {"body": "mosaic"}
    return {"plate": "plate", "inlay": "inlay"} if inlay and not single else {"plate": "plate"}


def _bridge_pinches(r):
    """The region with its pinch points (a vertex shared by two rings) bridged by a tiny square."""
    import shapely

    parts = shapely.get_parts(r)
    rings = np.concatenate(
        [shapely.get_exterior_ring(parts)]
        + [shapely.get_interior_ring(p, np.arange(shapely.get_num_interior_rings(p))) for p in parts]
    )
    coords, ring = shapely.get_coordinates(rings, return_index=True)
    closing = np.r_[ring[1:] != ring[:-1], True]  # each ring's repeated first point
    coords, ring = coords[~closing], ring[~closing]
    key = np.round(coords / QUANTUM).astype(np.int64)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    pinch = coords[cnt[inv.ravel()] > 1]
    if not len(pinch):
        return None
    squares = shapely.buffer(shapely.points(np.unique(pinch, axis=0)), 3 * QUANTUM, quad_segs=1)
    return snap(shapely.union_all(np.concatenate([[r], squares])))


def _close_round(r):
    """The region closed by a few microns with round joins: breaks every point contact."""
    import shapely

    q = 3 * QUANTUM
    return snap(shapely.buffer(shapely.buffer(r, q, quad_segs=2), -q, quad_segs=2))


def _nonmanifold_points(verts, faces):
    """The x, y of every vertex on an edge that does not pair up with exactly one reverse edge.

    ``verts, faces`` is a mesh merged by float32 position (what
    :func:`~fabtiles.solid.mesh_check.check_triangles` attaches to its error as ``mesh``). One sort of the
    undirected edge keys: a good edge's key occurs twice, in opposite directions.

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> _nonmanifold_points(v, np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2]])).tolist()
    [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]
    """
    faces = np.asarray(faces)
    n = len(verts)
    u, v = faces.ravel(), faces[:, [1, 2, 0]].ravel()
    key = np.minimum(u, v) * n + np.maximum(u, v)
    order = np.argsort(key, kind="stable")
    ks = key[order]
    start = np.flatnonzero(np.r_[True, ks[1:] != ks[:-1]])
    count = np.diff(np.r_[start, len(ks)])
    forward = (u < v)[order]
    good = count == 2
    good[good] = forward[start[good]] != forward[start[good] + 1]
    bad = order[np.repeat(~good, count)]
    ends = np.unique(np.concatenate([u[bad], v[bad]]))
    return np.unique(np.asarray(verts)[ends, :2], axis=0)


def _bridge_points(r, o, points):
    """The region with a few microns of material added around ``points`` (the squares clipped to the outline).

    Only the squares are clipped: clipping the whole region again would move its
    other vertices along a slanted outline edge and make new contacts there.
    """
    import shapely

    squares = shapely.buffer(shapely.points(points), 3 * QUANTUM, quad_segs=1)
    return snap(shapely.union(r, shapely.intersection(shapely.union_all(squares), o)))


def _on_cell_lines(points, lines) -> bool:
    """True when any of ``points`` (x, y) lies on one of the cell lines ``(xs, ys)``."""
    xs, ys = lines
    return bool(len(points)) and bool(np.isin(points[:, 0], xs).any() or np.isin(points[:, 1], ys).any())


def _checked_body(kind, name, r, o, stack, dips=None):
    """One body, checked as a slicer reads its STL (float32 corners merged by position).

    Returns ``(vertices, faces, region, volume)``: the merged float32 mesh, which is
    what the writers write (its STL is the same triangles, bit for bit), the region
    actually used and the mesh's volume (mm^3). Two kinds of defect are repaired:

    - a defect on a meshing cell line (a ring noded at the line and snapped onto
      a neighbouring ring's edge), or a piece of the cut that GEOS cannot clip or
      triangulate: the region is fine, the cut was unlucky, so the same region is
      meshed again with the cell lines moved (``GRID_SHIFTS`` tries);
    - two boundaries of the region touching at a single point (a mesh edge would
      join four faces): it retries with those contacts bridged by a few microns of
      material, then closed by a few microns, and last bridges wherever the mesh
      has an unpaired edge, a few rounds (contacts that only appear once the region
      is cut against the outline on the grid: a seamless tile whose strokes cross
      right at its edge).

    A GEOS failure inside a repair counts as a failed attempt; what is raised in
    the end is the first attempt's :class:`~fabtiles.FabricationError`.
    """
    import shapely

    def attempt(g):
        for shift in range(GRID_SHIFTS):
            try:
                extra = {} if dips is None else {"dips": dips}
                verts, faces, lines = _body_arrays(kind, g, o, stack, shift, **extra)
            except (shapely.errors.GEOSException, FabricationError) as exc:
                # a piece the cell lines cut that GEOS cannot clip or triangulate: other lines may do
                if shift + 1 < GRID_SHIFTS:
                    continue
                if isinstance(exc, FabricationError):
                    raise _named(exc, name) from None
                raise FabricationError(
                    f"the {name} mesh could not be cut into cells ({exc}); nothing was written"
                ) from None
            try:
                volume, bodies = _expected(kind, g, o, stack, dips)
                # an STL of these holds verts[faces] in float32: checked merged from the vertices
                mverts, mfaces, vol = check_indexed(
                    verts, faces, name=name, volume=volume, bodies=bodies, with_volume=True
                )
            except FabricationError as exc:
                mesh = getattr(exc, "mesh", None)
                if mesh is not None and shift + 1 < GRID_SHIFTS and _on_cell_lines(_nonmanifold_points(*mesh), lines):
                    continue
                raise
            return mverts, mfaces, g, vol

    error = None
    for repair in (lambda g: g, _bridge_pinches, _close_round):
        g = repair(r) if kind != "base" else r
        if g is None:
            continue
        try:
            return attempt(g)
        except FabricationError as exc:
            error = error or exc
            if kind == "base":
                raise
    assert error is not None  # every repair failed: the loop above returned otherwise
    points, exc = np.empty((0, 2)), error
    for _ in range(BRIDGE_ROUNDS):
        if exc.mesh is None:
            break
        found = _nonmanifold_points(*exc.mesh)
        if not len(found):
            break
        points = np.unique(np.concatenate([points, found]), axis=0)
        g = _bridge_points(r, o, points)
        try:
            return attempt(g)
        except FabricationError as new:
            exc = new
    raise error


def _named(exc: FabricationError, name: str) -> FabricationError:
    """A meshing error naming the part it is about (the check's own errors already do)."""
    if str(exc).startswith(f"the {name} mesh "):
        return exc
    named = FabricationError(f"the {name} mesh could not be made: {exc}; nothing was written")
    named.__dict__.update(exc.__dict__)  # the place (``points``) or the merged mesh it found
    return named


GRID_SHIFTS = 3
"""Meshing tries with moved cell lines when a defect lies on a cell line."""

BRIDGE_ROUNDS = 4
"""Rounds of bridging a region at the unpaired edges of its mesh before giving up."""


class CheckedPart(NamedTuple):
    """One checked part of a print: its merged float32-exact mesh and what it must measure."""

    vertices: np.ndarray
    """(n, 3) float64 holding float32 values, merged by position."""
    faces: np.ndarray
    """(m, 3) int64."""
    volume_mm3: float
    """Area x height of the region actually meshed."""
    bodies: int
    """Connected bodies expected."""
    region: BaseGeometry
    """The region actually meshed: snapped to the grid, point contacts bridged (shapely)."""
    outline: BaseGeometry
    """The outline, snapped to the grid (shapely)."""
    mesh_volume_mm3: float
    """The mesh's own volume, as the check found it."""
    layers: tuple = ()
    """A mosaic part's levels as it was meshed, ``((geometry, top z), ...)`` over :attr:`bottom_mm`, the
    first that holds a point giving its height: what its STEP solid is made of
    (:func:`~fabtiles.solid.brep.brep_of_part`). Empty for every other part, whose B-rep is made from its
    region and outline."""
    bottom_mm: float = 0.0
    """The height of the bottom of :attr:`layers` (a mosaic part standing on the plate: the plate's top)."""


def relief_parts(fused: CheckedPart, stack: Stack) -> dict:
    """A plain relief's ``base`` and ``pattern`` parts, the pattern cut from its checked fused body.

    The pattern is the fused body's triangles at or over the base's top (the
    pattern's top and walls), closed underneath by its top triangulation lowered
    to the base's top and turned over: one meshing of the region serves the STL and
    the 3MF (meshing the pattern again would be an eighth of a sheet's STL build). The
    base is the outline's slab, meshed on its own: its top taken from the fused body
    would hold the pattern's every triangle again (a sheet's 3MF would grow by
    almost half). Each part is checked as a slicer reads it. Only
    for a relief of three heights (0, base, base + relief), which every plain
    relief is.
    """
    b32, t32 = np.float32(stack.base), np.float32(stack.base + stack.relief)
    verts = np.asarray(fused.vertices, np.float64)
    faces = np.asarray(fused.faces, np.int64)
    z = verts[:, 2].astype(np.float32)[faces]
    top = (z == t32).all(axis=1)
    over = (z >= b32).all(axis=1) & ~(z == b32).all(axis=1)
    # the pattern's top, lowered: new vertices after the old ones (merged by the check)
    low_ids = np.unique(faces[top])
    lowered = verts[low_ids].copy()
    lowered[:, 2] = stack.base
    remap = np.zeros(len(verts), np.int64)
    remap[low_ids] = len(verts) + np.arange(len(low_ids))
    tris = np.concatenate([faces[over], remap[faces[top]][:, ::-1]])
    r, o = fused.region, fused.outline
    base_verts, base_faces, used, base_found = _checked_body("base", "base", r, o, stack)
    volume, bodies = _expected("base", used, o, stack)
    out = {"base": CheckedPart(base_verts, base_faces, float(volume), int(bodies), used, o, float(base_found))}
    volume, bodies = _expected("pattern", r, o, stack)
    mverts, mfaces, found = check_indexed(
        np.concatenate([verts, lowered]), tris, name="pattern", volume=volume, bodies=bodies, with_volume=True
    )
    out["pattern"] = CheckedPart(mverts, mfaces, float(volume), int(bodies), r, o, float(found))
    return out


def splits_fused(stack: Stack, single: bool, inlay: bool, dips) -> bool:
    """True when the parts are cut from the fused body (:func:`relief_parts`): a plain relief's parts."""
    return stack.style == "relief" and not single and not inlay and dips is None and stack.base > 0 and stack.relief > 0


def checked_parts(region, outline, stack: Stack, *, single: bool = False, inlay: bool = False, dips=None):
    """The checked parts of a print by name, in print order (see :func:`build_meshes`).

    ``single`` fuses a relief into one body (STL); ``inlay`` adds the deboss
    grooves' filling as a second part; ``dips`` lowers an interlaced relief's under
    strands (see :mod:`fabtiles.solid.levels`). Every part passed :func:`check_indexed`.
    Returns a dict of name to :class:`CheckedPart`.
    """
    r, o = _snapped(region, outline)
    dips = _leveled(dips, r)
    if splits_fused(stack, single, inlay, dips):
        return relief_parts(_fused_part(r, o, stack), stack)
    out = {}
    for name, kind in part_kinds(stack.style, single, inlay).items():
        verts, faces, used, found = _checked_body(kind, name, r, o, stack, dips)
        volume, bodies = _expected(kind, used, o, stack, dips)
        out[name] = CheckedPart(verts, faces, float(volume), int(bodies), used, o, float(found))
    return out


def _fused_part(r, o, stack: Stack) -> CheckedPart:
    """A plain relief's fused body from the snapped region and outline, checked."""
    verts, faces, used, found = _checked_body("relief", "body", r, o, stack)
    volume, bodies = _expected("relief", used, o, stack)
    return CheckedPart(verts, faces, float(volume), int(bodies), used, o, float(found))


def _build(region, outline, stack: Stack, *, single: bool, inlay: bool = False):
    """Checked trimesh bodies by name; ``single`` fuses a relief into one body (STL)."""
    import trimesh

    return {
        name: trimesh.Trimesh(vertices=p.vertices, faces=p.faces, process=False, validate=False)
        for name, p in checked_parts(region, outline, stack, single=single, inlay=inlay).items()
    }


def build_meshes(
    *, region, outline, profile, style=None, base_mm=None, relief_mm=None, pierced_mm=None, deboss_mm=None, inlay=False
):
    """The named, checked bodies of a printed tile, as trimesh meshes (mm).

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon
        The material, in file coordinates (mm, outline's lower-left corner at the origin).
    outline : shapely Polygon
        The tile outline.
    profile : str, Path or PrinterProfile
        Printer profile: default style and heights.
    style : {"relief", "pierced", "deboss"}, optional
    base_mm, relief_mm, pierced_mm, deboss_mm : float, optional
        Heights overriding the profile's.
    inlay : bool, optional
        Deboss only: add the part ``"inlay"`` filling the grooves flush.

    Returns
    -------
    dict of str to trimesh.Trimesh
        relief: ``{"base", "pattern"}``; pierced: ``{"pattern"}``; deboss: ``{"plate"}``
        (and ``"inlay"``). Vertices are float32-exact; every body passed
        :func:`~fabtiles.solid.mesh_check.check_mesh`.
    """
    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, base_mm, relief_mm, pierced_mm, deboss_mm)
    check_inlay(stack, inlay)
    region, outline = check_shapes(region, outline)
    return _build(region, outline, stack, single=False, inlay=inlay)


def check_inlay(stack: Stack, inlay) -> None:
    """Refuse ``inlay`` unless it is a bool, and true only for the deboss style.

    >>> from fabtiles.solid._mesh_build import resolve_stack
    >>> check_inlay(resolve_stack("fdm-0.4mm", "relief"), True)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: inlay=True needs style='deboss' (the inlay fills the deboss grooves), got style='relief'; pass style='deboss' or drop inlay
    """  # noqa: E501 - a doctest's lines are as Python prints them
    if not isinstance(inlay, (bool, np.bool_)):
        raise ParameterError(f"inlay must be True or False, got {inlay!r}")
    if inlay and stack.style != "deboss":
        raise ParameterError(
            f"inlay=True needs style='deboss' (the inlay fills the deboss grooves), "
            f"got style={stack.style!r}; pass style='deboss' or drop inlay"
        )


def fused_body(region, outline, stack: Stack, *, dips=None):
    """The print as one checked body (a relief's plate and pattern fused), for an STL.

    Returns ``(name, vertices, faces, mesh_volume_mm3)``: the mesh merged as a slicer
    merges the float32 corners, which is what is to be written.
    """
    r, o = _snapped(region, outline)
    dips = _leveled(dips, r)
    ((name, kind),) = part_kinds(stack.style, single=True).items()
    mverts, mfaces, _, volume = _checked_body(kind, name, r, o, stack, dips)
    return name, mverts, mfaces, volume


class NamedColour(Protocol):
    """What a part needs of a colour (:class:`~fabtiles.designs.colour.Colour` is one, from the layer above)."""

    hex: str
    name: str


class MosaicPart(NamedTuple):
    """What one part (one colour) of a mosaic print holds: the plate, the bands, some faces."""

    name: str
    """The part's name: its colour and what it holds (``"cobalt (A, C)"``)."""
    base: bool
    """The plate under everything (``0 .. base``)."""
    bands: bool
    """The bands (the region), up to the top."""
    faces: tuple
    """The faces of this colour (shapely polygons, file coordinates), up to the top less the inset."""
    colour: NamedColour | None = None
    """Its :class:`~fabtiles.designs.colour.Colour`: the display colour and the STL file's name."""


def mosaic_parts(region, outline, stack: Stack, specs) -> dict:
    """The checked parts of a mosaic print, one per :class:`MosaicPart` of ``specs``, in that order.

    The faces are the outline less the region, cut on the 2**-10 mm grid so that each
    touches its bands exactly; each takes the part of the spec face holding its
    representative point (a face a spec does not name goes with the part holding the
    bands). A part with the plate is meshed as a relief of its top footprint
    (``coverage_pair``: the footprint up to its top, the rest of the outline to the
    plate's top); one without it stands on the plate (``base`` up). Each part is checked
    as a slicer reads it, alone; the parts touch without overlapping.
    """
    import shapely

    r, o = _snapped(region, outline)
    try:
        faces = np.asarray(polygons_of(shapely.difference(o, r, grid_size=QUANTUM)), dtype=object)
    except shapely.errors.GEOSException as exc:
        raise FabricationError(
            f"the mosaic's faces could not be cut from the outline ({exc}); nothing was written"
        ) from None
    faces = faces[~_slivers(faces)]
    owner = _face_owners(faces, specs)
    out = {}
    for k, spec in enumerate(specs):
        layers = _mosaic_layers(spec, faces[owner == k], r, stack)
        if not layers and not spec.base:
            continue  # a colour no face of this print took (all its faces were filled)
        out[spec.name] = _mosaic_body(spec, layers, o, stack)
    return out


def _face_owners(faces, specs) -> np.ndarray:
    """Per face, the number of the spec whose face holds its representative point (on an edge: the
    nearest); a face no spec names goes with the part holding the bands."""
    import shapely

    owner = np.full(len(faces), -1)
    spec_faces = [(np.asarray(s.faces, dtype=object), k) for k, s in enumerate(specs) if len(s.faces)]
    if len(faces) and spec_faces:
        polys = np.concatenate([f for f, _ in spec_faces])
        which = np.concatenate([np.full(len(f), k) for f, k in spec_faces])
        probe = shapely.point_on_surface(faces)
        a, b = shapely.STRtree(polys).query(probe, predicate="within")
        owner[a] = which[b]
        lost = np.flatnonzero(owner < 0)
        if len(lost):  # snapped faces whose point fell on a spec face's edge: the nearest spec face
            near = shapely.STRtree(polys).query_nearest(probe[lost], return_distance=False)
            owner[lost[near[0]]] = which[near[1]]
    owner[owner < 0] = next((k for k, s in enumerate(specs) if s.bands), 0)
    return owner


def _mosaic_layers(spec: MosaicPart, mine, r, stack: Stack) -> list:
    """A mosaic part's layers ``(geometry, top z)``: the bands ``r`` to the top if it holds them, its
    faces ``mine`` to the top less the inset."""
    import shapely

    b, h, i = stack.base, stack.relief, stack.inset
    # the faces are disjoint parts of one overlay: a MultiPolygon of them is their union (no GEOS
    # union of a sheet's thousands of faces)
    face_geom = shapely.MultiPolygon(list(mine)) if len(mine) else shapely.Polygon()
    layers = []
    if spec.bands:
        layers.append((r, b + h))
    if not face_geom.is_empty:
        layers.append((face_geom, b + h - i))
    return layers


def _slivers(faces) -> np.ndarray:
    """Which of ``faces`` (polygons on the grid) are slivers: nowhere two quanta wide.

    Where the region runs along a slanted edge of the outline, its vertices and the
    outline's round to the grid on either side of the true line: the outline less
    the region leaves chains of slivers a fraction of a micron thin, touching one
    another at their ends. A part holding them would have an edge of four walls
    there (not watertight as a slicer reads it); they are no face of the design.

    >>> import shapely
    >>> _slivers(np.array([shapely.box(0, 0, 1, 1), shapely.box(0, 0, 1, QUANTUM)])).tolist()
    [False, True]
    """
    import shapely

    out = np.zeros(len(faces), bool)
    if not len(faces):
        return out
    # twice the area over the perimeter is about a thin face's width: only those are buffered
    thin = np.flatnonzero(2 * shapely.area(faces) < 4 * QUANTUM * shapely.length(faces))
    out[thin] = shapely.is_empty(shapely.buffer(faces[thin], -QUANTUM, quad_segs=1))
    return out


def _mosaic_body(spec: MosaicPart, layers, o, stack: Stack) -> CheckedPart:
    """One mosaic part meshed and checked (see :func:`mosaic_parts`).

    Two polygons of one part that touch at a single point (two faces of a class on
    either side of a band's tip on a tile's edge) would meet on a vertical edge of
    four walls. So where the mesh's edges do not pair up (off the cell lines, which
    :func:`_mosaic_mesh` moves), a few microns of the part's top layers are cut away
    around each such point (:func:`_apart`), a few rounds. No other part takes that
    speck: the parts still touch without overlapping. The first attempt's error is
    raised when no round helps.
    """
    error, points = None, np.empty((0, 2))
    for _ in range(BRIDGE_ROUNDS + 1):
        try:
            return _mosaic_mesh(spec, _apart(layers, points), o, stack)
        except FabricationError as exc:
            error = error or exc
            mesh = getattr(exc, "mesh", None)
            found = _nonmanifold_points(*mesh) if mesh is not None else np.empty((0, 2))
            if not len(found) or not len(layers):
                break
            points = np.unique(np.concatenate([points, found]), axis=0)
    assert error is not None  # the loop runs at least once and returns or records an error
    raise error


APART_MM = 8 * QUANTUM
"""How far around a point contact :func:`_apart` cuts a part's top layers (a diamond of this radius)."""


def _apart(layers, points):
    """``layers`` (geometry, z) with a diamond of :data:`APART_MM` cut out around each of ``points``.

    >>> import shapely
    >>> (g, z), = _apart([(shapely.box(0, 0, 1, 1), 2.0)], np.array([[1.0, 1.0]]))
    >>> z, round(1 - g.area, 9) == round(APART_MM ** 2 / 2, 9)
    (2.0, True)
    """
    import shapely

    if not len(points):
        return layers
    cut = shapely.union_all(shapely.buffer(shapely.points(points), APART_MM, quad_segs=1))
    out = [(polygons_of(shapely.difference(g, cut, grid_size=QUANTUM)), z) for g, z in layers]
    return [(shapely.MultiPolygon(polys), z) for polys, z in out if polys]


def _mosaic_mesh(spec: MosaicPart, layers, o, stack: Stack) -> CheckedPart:
    """One mosaic part meshed and checked as it is, trying moved cell lines on a defect that lies on them."""
    import shapely

    b = stack.base
    name = f"part {spec.name!r}"
    top = _mosaic_top(layers, name)
    volume, bodies = _mosaic_expected(spec, layers, top, o, b)
    if spec.base and stack.recess is not None:
        volume -= stack.recess.volume
    error = None
    for shift in range(GRID_SHIFTS):
        try:
            cov = _mosaic_coverage(spec, layers, top, o, b, shift)
            verts, faces = mesh_coverage(cov, stack.recess if spec.base else None)
        except shapely.errors.GEOSException as exc:
            error = error or FabricationError(
                f"the {name} mesh could not be cut into cells ({exc}); nothing was written"
            )
            continue
        except FabricationError as exc:  # a piece the lines cut that cannot be triangulated or paired
            error = error or _named(exc, name)
            continue
        try:
            mverts, mfaces, found = check_indexed(
                verts, faces, name=name, volume=volume, bodies=bodies, with_volume=True
            )
        except FabricationError as exc:
            error = error or exc
            if exc.mesh is not None and _on_cell_lines(_nonmanifold_points(*exc.mesh), (cov.xs, cov.ys)):
                continue
            raise error from None
        levels, bottom = _mosaic_levels(spec, layers, o, b)
        return CheckedPart(mverts, mfaces, float(volume), int(bodies), top, o, float(found), levels, bottom)
    assert error is not None  # every attempt failed: the loop above returned otherwise
    raise error


def _mosaic_top(layers, name: str):
    """The footprint of a mosaic part's layers, their union.

    The bands and the faces share their edges exactly (the faces are the outline less
    the bands, on the grid): a coverage union joins them without an overlay.
    """
    import shapely

    geoms = [g for g, _ in layers]
    if not geoms:
        return shapely.Polygon()
    if len(geoms) == 1:
        return geoms[0]
    try:
        return shapely.coverage_union_all(np.concatenate([shapely.get_parts(g) for g in geoms]))
    except shapely.errors.GEOSException as exc:
        raise FabricationError(
            f"the {name} mesh could not be made: its bands and faces do not join ({exc}); nothing was written"
        ) from None


def _mosaic_expected(spec: MosaicPart, layers, top, o, b: float) -> tuple:
    """``(volume, bodies)`` a mosaic part's mesh must have: with the plate, the outline's plate and
    what stands on it, one body per piece of the outline; else its layers above the plate, one body
    per piece of its footprint."""
    if spec.base:
        return o.area * b + sum(g.area * (z - b) for g, z in layers), len(polygons_of(o))
    return sum(g.area * (z - b) for g, z in layers), len(polygons_of(top))


def _mosaic_levels(spec: MosaicPart, layers, o, b: float) -> tuple:
    """``(levels, bottom)``: a mosaic part's layers as :attr:`CheckedPart.layers` keeps them, for its STEP solid.

    A part with the plate stands on the bed, the outline at the plate's top wherever no layer
    of it is (last: a point takes the first level holding it); one without stands on the plate.
    """
    if spec.base:
        return (*layers, (o, b)), 0.0
    return tuple(layers), b


def _mosaic_coverage(spec: MosaicPart, layers, top, o, b: float, shift: int):
    """The coverage a mosaic part is meshed from, its cell lines moved by ``shift``.

    A part with the plate is a relief of its top footprint on the whole outline (the
    rest of the outline to the plate's top ``b``); one without it stands on the plate.
    """
    import shapely

    one_level = len({z for _, z in layers}) <= 1
    if spec.base and not layers:
        return coverage([(o, b)], bottom=0.0, shift=shift)
    if spec.base and one_level:
        return coverage_pair(top, o, region_z=layers[0][1], rest_z=b, bottom=0.0, shift=shift)
    if spec.base:
        rest = shapely.difference(o, top, grid_size=QUANTUM)
        return coverage(layers + ([(rest, b)] if not rest.is_empty else []), bottom=0.0, shift=shift)
    if one_level:
        return coverage([(top, layers[0][1])], bottom=b, shift=shift)
    return coverage(layers, bottom=b, shift=shift)


def stack_stats(stack):
    """The report statistics naming a stack's style and its heights (mm)."""
    if stack.style == "mosaic":
        return dict(style="mosaic", heights_mm={"base": stack.base, "relief": stack.relief, "inset": stack.inset})
    return dict(
        style=stack.style,
        heights_mm={
            "relief": {"base": stack.base, "relief": stack.relief},
            "pierced": {"pierced": stack.pierced},
            "deboss": {"base": stack.base, "deboss": stack.deboss},
        }[stack.style],
    )
