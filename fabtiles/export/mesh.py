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

Meshes are built directly as stacked prisms (see :mod:`fabtiles.export._mesh_build`),
with every x, y on a 2**-10 mm grid that float32 stores exactly. Before anything is
written, each body is checked the way a slicer reads the file: the float32
triangles are merged by position, then trimesh must find it watertight, wound
consistently, of positive volume, one body per part and free of degenerate faces.
A mesh failing any of this is a :class:`~fabtiles.FabricationError`, never a file.
trimesh and manifold3d are imported only inside the functions.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._errors import FabricationError, ParameterError
from .._io import atomic_write
from .._profiles import load_profile
from .._report import Report
from ._mesh_build import (
    QUANTUM,
    Stack,
    check_shapes,
    coverage,
    coverage_pair,
    edges_pair_up,
    mesh_coverage,
    polygons_of,
    resolve_stack,
    snap,
)

VOLUME_TOLERANCE = 0.005
"""Largest relative difference allowed between a mesh's volume and area x height."""


# --------------------------------------------------------------------------- building


def prepare_print(region, outline, profile, style, heights, stroke=None, *, path="", fmt=""):
    """Validate everything and run the printability checks; nothing is built yet.

    Returns ``(profile, stack, report)``; a strict profile with findings raises.
    """
    from ..geometry.print_checks import check_print

    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, **heights)
    region, outline = check_shapes(region, outline)
    report = Report(path=str(path), format=fmt)
    check_print(region, outline, profile, stroke=stroke, style=stack.style, base_mm=stack.base,
                relief_mm=stack.relief, pierced_mm=stack.pierced, deboss_mm=stack.deboss, report=report)
    report.raise_if_strict(profile.strict)
    return profile, stack, report


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


def _leveled(dips):
    """An interlaced relief's dips as meshed (:func:`fabtiles.export.layers.dip_level`), or None."""
    if dips is None:
        return None
    from .layers import dip_level

    return dip_level(dips)


def _body_arrays(kind: str, r, o, stack: Stack, shift: int = 0, dips=None):
    """Vertices, faces and cell lines of one body (``dips``: an interlaced relief's, as
    :func:`_leveled` makes them; see :func:`fabtiles.export.layers.body_layers`).

    ``kind`` is ``"relief"``, ``"base"``, ``"pattern"``, ``"pierced"``, ``"plate"`` or
    ``"inlay"`` (the plate's grooves filled flush);
    ``shift`` moves the meshing cell lines. Returns ``(vertices, faces, (xs, ys))``.
    """
    b, h, t, d = stack.base, stack.relief, stack.pierced, stack.deboss
    if dips is not None and not dips.is_empty and kind in ("relief", "pattern"):
        from .layers import body_coverage

        cov = body_coverage(kind, r, o, stack, dips, shift=shift, leveled=True)
    elif kind == "relief":
        cov = coverage_pair(r, o, region_z=b + h, rest_z=b, bottom=0.0, shift=shift)
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
    return (*mesh_coverage(cov), (cov.xs, cov.ys))


def _expected(kind, r, o, stack, dips=None):
    """Expected volume and number of bodies of one body kind (``dips`` as :func:`_leveled` makes them)."""
    b, h = stack.base, stack.relief
    nr = len(polygons_of(r))
    no = len(polygons_of(o))
    if dips is not None and kind in ("relief", "pattern"):
        from .layers import dips_volume

        full = {"relief": o.area * b + r.area * h, "pattern": r.area * h}[kind]
        return full - dips_volume(r, dips, stack, leveled=True), {"relief": no, "pattern": nr}[kind]
    return {
        "relief": (o.area * b + r.area * h, no),
        "base": (o.area * b, no),
        "pattern": (r.area * h, nr),
        "pierced": (r.area * stack.pierced, nr),
        "plate": (o.area * b - r.area * stack.deboss, no),
        "inlay": (r.area * stack.deboss, nr),
    }[kind]


def _kinds(style: str, single: bool, inlay: bool = False):
    if style == "relief":
        return {"body": "relief"} if single else {"base": "base", "pattern": "pattern"}
    if style == "pierced":
        return {"pattern": "pierced"}
    return {"plate": "plate", "inlay": "inlay"} if inlay and not single else {"plate": "plate"}


def _bridge_pinches(r):
    """The region with its pinch points (a vertex shared by two rings) bridged by a tiny square."""
    import shapely

    parts = shapely.get_parts(r)
    rings = np.concatenate([shapely.get_exterior_ring(parts)]
                           + [shapely.get_interior_ring(p, np.arange(shapely.get_num_interior_rings(p)))
                              for p in parts])
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
    :func:`check_triangles` attaches to its error as ``mesh``). One sort of the
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

    Returns ``(vertices, faces, region)``: the merged float32 mesh, which is what
    the writers write (its STL is the same triangles, bit for bit), and the region
    actually used. Two kinds of defect are repaired:

    - a defect on a meshing cell line (a ring noded at the line and snapped onto
      a neighbouring ring's edge): the region is fine, the cut was unlucky, so the
      same region is meshed again with the cell lines moved (``GRID_SHIFTS`` tries);
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
            except shapely.errors.GEOSException as exc:
                raise FabricationError(f"the {name} mesh could not be cut into cells ({exc}); "
                                       "nothing was written") from None
            try:
                volume, bodies = _expected(kind, g, o, stack, dips)
                # an STL of these holds verts[faces] in float32: checked merged from the vertices
                mverts, mfaces = check_indexed(verts, faces, name=name, volume=volume, bodies=bodies)
            except FabricationError as exc:
                mesh = getattr(exc, "mesh", None)
                if mesh is not None and shift + 1 < GRID_SHIFTS and _on_cell_lines(_nonmanifold_points(*mesh), lines):
                    continue
                raise
            return mverts, mfaces, g

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
    points, exc = np.empty((0, 2)), error
    for _ in range(BRIDGE_ROUNDS):
        if getattr(exc, "mesh", None) is None:
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
    region: object
    """The region actually meshed: snapped to the grid, point contacts bridged (shapely)."""
    outline: object
    """The outline, snapped to the grid (shapely)."""


def checked_parts(region, outline, stack: Stack, *, single: bool = False, inlay: bool = False, dips=None):
    """The checked parts of a print by name, in print order (see :func:`build_meshes`).

    ``single`` fuses a relief into one body (STL); ``inlay`` adds the deboss
    grooves' filling as a second part; ``dips`` lowers an interlaced relief's under
    strands (see :mod:`fabtiles.export.layers`). Every part passed :func:`check_indexed`.
    Returns a dict of name to :class:`CheckedPart`.
    """
    r, o = _snapped(region, outline)
    dips = _leveled(dips)
    out = {}
    for name, kind in _kinds(stack.style, single, inlay).items():
        verts, faces, used = _checked_body(kind, name, r, o, stack, dips)
        volume, bodies = _expected(kind, used, o, stack, dips)
        out[name] = CheckedPart(verts, faces, float(volume), int(bodies), used, o)
    return out


def _build(region, outline, stack: Stack, *, single: bool, inlay: bool = False):
    """Checked trimesh bodies by name; ``single`` fuses a relief into one body (STL)."""
    import trimesh

    return {name: trimesh.Trimesh(vertices=p.vertices, faces=p.faces, process=False, validate=False)
            for name, p in checked_parts(region, outline, stack, single=single, inlay=inlay).items()}


def build_meshes(*, region, outline, profile, style=None, base_mm=None, relief_mm=None, pierced_mm=None,
                 deboss_mm=None, inlay=False):
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
        (and ``"inlay"``). Vertices are float32-exact; every body passed :func:`check_mesh`.
    """
    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, base_mm, relief_mm, pierced_mm, deboss_mm)
    check_inlay(stack, inlay)
    region, outline = check_shapes(region, outline)
    return _build(region, outline, stack, single=False, inlay=inlay)


def check_inlay(stack: Stack, inlay) -> None:
    """Refuse ``inlay`` unless it is a bool, and true only for the deboss style.

    >>> from fabtiles.export._mesh_build import resolve_stack
    >>> check_inlay(resolve_stack("fdm-0.4mm", "relief"), True)
    Traceback (most recent call last):
    ...
    fabtiles._errors.ParameterError: inlay=True needs style='deboss' (the inlay fills the deboss grooves), got style='relief'; pass style='deboss' or drop inlay
    """
    if not isinstance(inlay, (bool, np.bool_)):
        raise ParameterError(f"inlay must be True or False, got {inlay!r}")
    if inlay and stack.style != "deboss":
        raise ParameterError(f"inlay=True needs style='deboss' (the inlay fills the deboss grooves), "
                             f"got style={stack.style!r}; pass style='deboss' or drop inlay")


# --------------------------------------------------------------------------- checks


def _merge_points32(flat: np.ndarray):
    """Merge float32 points (k, 3) by exact position: ``(unique points (n, 3) float64, inverse (k,))``.

    The unique points come out in one order whatever the input order (by a hash of
    their bits, or by coordinates after a hash collision), so merging a mesh's
    vertices gives the same arrays as merging its triangles' corners.
    """
    flat = np.ascontiguousarray(flat, dtype=np.float32) + np.float32(0)  # -0.0 -> 0.0
    bits = flat.view(np.uint32).astype(np.uint64)
    key = (bits[:, 0] * np.uint64(0x9E3779B97F4A7C15)) ^ (bits[:, 1] * np.uint64(0xC2B2AE3D27D4EB4F)) \
        ^ (bits[:, 2] * np.uint64(0x165667B19E3779F9)) ^ (bits[:, 2] << np.uint64(32))
    _, first, inv = np.unique(key, return_index=True, return_inverse=True)
    inv = inv.ravel()
    if not np.array_equal(flat[first][inv], flat):  # a hash collision: merge exactly instead
        order = np.lexsort(flat.T[::-1])
        srt = flat[order]
        new = np.ones(len(srt), bool)
        new[1:] = np.any(srt[1:] != srt[:-1], axis=1)
        ids = np.cumsum(new) - 1
        inv = np.empty(len(flat), np.int64)
        inv[order] = ids
        first = order[new]
    return flat[first].astype(np.float64), inv.astype(np.int64)


def _merge_float32(tris32: np.ndarray):
    """Merge float32 triangle corners by exact position, as a slicer does.

    Returns ``(vertices (n, 3) float64, faces (m, 3) int64)``.
    """
    verts, inv = _merge_points32(np.asarray(tris32).reshape(-1, 3))
    return verts, inv.reshape(-1, 3)


def merge_indexed32(vertices, faces):
    """The merged mesh a slicer reads from the STL of ``(vertices, faces)``, from the vertices.

    The STL holds ``vertices`` rounded to float32, gathered by ``faces``
    (:func:`stl_bytes`); every corner of one vertex has the same bits, so merging
    the used vertices by float32 position gives exactly what merging the file's
    3m corners gives (:func:`_merge_float32`), array for array, from about a
    sixth of the points (0.5 s to 0.06 s for the 716,000 triangles of the
    interlaced 600 x 400 mm sheet). Vertices distinct in float64 that round to one
    float32 point merge, as in the file.

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [1 + 1e-9, 0, 0], [0, 1, 0]], float)
    >>> merged, f = merge_indexed32(v, np.array([[0, 1, 3], [0, 2, 3]]))
    >>> len(merged), f[0].tolist() == f[1].tolist()  # (1, 0, 0) and (1 + 1e-9, 0, 0) are one float32 point
    (3, True)
    """
    faces = np.asarray(faces, dtype=np.int64)
    v32 = np.asarray(vertices).astype(np.float32)
    used = np.zeros(len(v32), bool)
    used[faces.ravel()] = True
    idx = np.flatnonzero(used)
    verts, inv = _merge_points32(v32[idx])
    remap = np.zeros(len(v32), np.int64)
    remap[idx] = inv
    return verts, remap[faces]


def count_bodies(n_vertices: int, edges: np.ndarray) -> int:
    """Connected components of a graph that hold at least one edge (union-find in numpy).

    Each round hooks the larger root of every edge onto the smaller one and jumps
    pointers to the roots; edges inside one component drop out. Five or six rounds
    on the sheets' meshes: 0.06 s for the 600 x 400 mm relief, 0.11 s interlaced
    (scipy's ``connected_components`` takes 0.07 s but 0.24 s to import, which
    every command that writes a small tile would pay).

    >>> count_bodies(5, np.array([[0, 1], [1, 2], [3, 4]]))
    2
    """
    edges = np.asarray(edges)
    parent = np.arange(n_vertices)
    u, v = edges[:, 0], edges[:, 1]
    while len(u):
        pu, pv = parent[u], parent[v]
        apart = pu != pv
        u, v, pu, pv = u[apart], v[apart], pu[apart], pv[apart]
        if not len(u):
            break
        np.minimum.at(parent, np.maximum(pu, pv), np.minimum(pu, pv))
        while True:
            nxt = parent[parent]
            if np.array_equal(nxt, parent):
                break
            parent = nxt
    used = np.zeros(n_vertices, bool)
    used[edges.ravel()] = True
    return int(np.count_nonzero((parent == np.arange(n_vertices)) & used))


def check_mesh(vertices, faces, *, name="mesh", volume=None, bodies=None):
    """Check a mesh as a slicer reads it; return it as a trimesh.Trimesh (float32-exact).

    The triangles are rounded to float32 (what STL stores) and merged by position.
    Then there must be no collapsed or zero-area face, every edge must join exactly
    two faces wound in opposite directions (watertight, consistent winding), the
    volume must be positive (and within 0.5 % of ``volume`` if given) and the mesh
    must hold ``bodies`` connected bodies if given.

    Raises
    ------
    FabricationError
        Naming the body and what failed.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> round(float(check_mesh(v, f, volume=1 / 6, bodies=1).volume), 6)
    0.166667
    >>> check_mesh(v, f[:3])
    Traceback (most recent call last):
    ...
    fabtiles._errors.FabricationError: the mesh mesh is not watertight as a slicer reads it (float32): 3 open edges; nothing was written
    """
    import trimesh

    verts, faces = check_indexed(vertices, faces, name=name, volume=volume, bodies=bodies)
    return trimesh.Trimesh(vertices=verts, faces=faces, process=False, validate=False)


def check_triangles(tris32, *, name="mesh", volume=None, bodies=None):
    """Check float32 triangles (m, 3, 3) as a slicer reads them (an STL read back); see :func:`check_mesh`.

    Returns the merged ``(vertices, faces)``.
    """
    tris32 = np.asarray(tris32)
    if not np.isfinite(tris32).all():
        _fail(name, "has non-finite coordinates", None)
    if not len(tris32):
        _fail(name, "is empty", None)
    return _check_merged(*_merge_float32(tris32), name=name, volume=volume, bodies=bodies)


def check_indexed(vertices, faces, *, name="mesh", volume=None, bodies=None):
    """Check the mesh that the STL of ``(vertices, faces)`` holds, as a slicer reads it; see :func:`check_mesh`.

    The same check as :func:`check_triangles` on the file's triangles, merged from
    the vertices (:func:`merge_indexed32`). Returns the merged ``(vertices, faces)``.
    """
    faces = np.asarray(faces)
    if not len(faces):
        _fail(name, "is empty", None)
    if not np.isfinite(np.asarray(vertices, dtype=np.float64)).all():
        _fail(name, "has non-finite coordinates", None)
    return _check_merged(*merge_indexed32(vertices, faces), name=name, volume=volume, bodies=bodies)


def _fail(name, why, merged):
    exc = FabricationError(f"the {name} mesh {why}; nothing was written")
    exc.mesh = merged  # (vertices, faces) merged by float32 position, or None
    raise exc


def _check_merged(verts, faces, *, name, volume, bodies):
    """The checks of :func:`check_mesh` on a mesh merged by float32 position."""
    merged = (verts, faces)
    collapsed = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])
    if collapsed.any():
        _fail(name, f"has {int(collapsed.sum())} faces that collapse when rounded to float32", merged)
    p0 = verts[faces[:, 0]]
    cross = _cross3(verts[faces[:, 1]] - p0, verts[faces[:, 2]] - p0)
    zero = ~np.any(cross != 0, axis=1)
    if zero.any():
        _fail(name, f"has {int(zero.sum())} zero-area faces in float32", merged)
    # every directed edge exactly once and its reverse exactly once:
    # watertight, 2-manifold and consistently wound
    n = len(verts)
    u = faces.ravel()
    v = faces[:, [1, 2, 0]].ravel()
    if not edges_pair_up(u, v, n):
        key = np.sort(u * n + v)
        dup = int(np.count_nonzero(key[1:] == key[:-1]))
        rev = np.sort(v * n + u)
        pos = np.minimum(np.searchsorted(key, rev), len(key) - 1)
        missing = int(np.count_nonzero(key[pos] != rev))
        problems = []
        if missing or not dup:
            problems.append(f"{max(missing, 1)} open edges")
        if dup:
            problems.append(f"{dup} edges wound the same way twice or shared by more than two faces")
        _fail(name, "is not watertight as a slicer reads it (float32): " + ", ".join(problems), merged)
    vol = float(np.einsum("ij,ij->i", p0, cross).sum() / 6.0)
    if not vol > 0:
        _fail(name, f"has a volume of {vol:g} mm^3 (it must be positive: faces point inward)", merged)
    if volume is not None and abs(vol - volume) > VOLUME_TOLERANCE * abs(volume):
        _fail(name, f"has a volume of {vol:.6g} mm^3, not the {volume:.6g} mm^3 of area x height (0.5 % allowed)",
              merged)
    if bodies is not None:
        found = count_bodies(n, faces[:, [0, 1, 1, 2]].reshape(-1, 2))  # two edges join a face's corners
        if found != bodies:
            _fail(name, f"has {found} separate bodies where {bodies} {'was' if bodies == 1 else 'were'} expected",
                  merged)
    return verts, faces


# --------------------------------------------------------------------------- STL


def stl_bytes(vertices, faces) -> bytes:
    """Binary STL (float32, normals from the float32 corners) of a mesh.

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> len(stl_bytes(v, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    284
    """
    tris = np.asarray(vertices).astype(np.float32)[np.asarray(faces)]  # = vertices[faces] in float32
    normals = _cross3(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]).astype(np.float64)
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = (normals / np.where(lengths > 0, lengths, 1)).astype(np.float32)
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"] = normals
    rec["v"] = tris
    header = b"fabtiles binary STL, units mm".ljust(80, b" ")
    return header + np.uint32(len(tris)).tobytes() + rec.tobytes()


def _cross3(a, b):
    """Row-wise cross products of (m, 3) arrays, as ``np.cross`` computes them (a third of its time)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), dtype=np.result_type(a, b))
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out


def mesh_volume(vertices, faces) -> float:
    """Enclosed volume of a closed, outward-wound mesh (mm^3).

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> round(mesh_volume(v, np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])), 6)
    0.166667
    """
    v, f = np.asarray(vertices, dtype=np.float64), np.asarray(faces)
    return float(np.einsum("ij,ij->i", v[f[:, 0]], _cross3(v[f[:, 1]], v[f[:, 2]])).sum() / 6.0)


def read_stl_triangles(data: bytes) -> np.ndarray:
    """The float32 triangles (m, 3, 3) of binary STL bytes, as a slicer reads them."""
    if len(data) < 84:
        raise FabricationError("not a binary STL: shorter than its header")
    n = int(np.frombuffer(data, "<u4", 1, 80)[0])
    if len(data) != 84 + 50 * n:
        raise FabricationError(f"not a binary STL: {len(data)} bytes for {n} triangles")
    rec = np.frombuffer(data, dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")], count=n, offset=84)
    return rec["v"].copy()


def write_stl(path, *, region, outline, profile, style=None, stroke=None, base_mm=None, relief_mm=None,
              pierced_mm=None, deboss_mm=None, dips=None) -> Report:
    """Write a binary STL (mm) of the tile, one watertight body (a relief's plate and pattern fused).

    The mesh is checked as a slicer reads the file (float32 corners merged by
    position) and that merged mesh is what is written, atomically. Parameters as :func:`build_meshes`, plus ``stroke``
    (mm, for the thin-wall check) and ``dips`` (an interlaced relief's, see
    :mod:`fabtiles.export.layers`). Strict profile with findings, or a bad mesh:
    :class:`~fabtiles.FabricationError` and no file.
    """
    heights = dict(base_mm=base_mm, relief_mm=relief_mm, pierced_mm=pierced_mm, deboss_mm=deboss_mm)
    profile, stack, report = prepare_print(region, outline, profile, style, heights, stroke, path=path, fmt="stl")
    r, o = _snapped(region, outline)
    dips = _leveled(dips)
    ((name, kind),) = _kinds(stack.style, single=True).items()
    # checked as a slicer will read it: the merged float32 mesh, written as it is
    mverts, mfaces, _ = _checked_body(kind, name, r, o, stack, dips)
    atomic_write(path, stl_bytes(mverts, mfaces))
    report.stats.update(stack_stats(stack), bodies=[name], triangles=len(mfaces),
                        volume_mm3=mesh_volume(mverts, mfaces),
                        bounds_mm=[mverts.min(axis=0).tolist(), mverts.max(axis=0).tolist()])
    return report


def stack_stats(stack):
    """The report statistics naming a stack's style and its heights (mm)."""
    return dict(style=stack.style,
                heights_mm={"relief": {"base": stack.base, "relief": stack.relief},
                            "pierced": {"pierced": stack.pierced},
                            "deboss": {"base": stack.base, "deboss": stack.deboss}}[stack.style])
