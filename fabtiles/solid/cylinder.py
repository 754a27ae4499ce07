"""A flat print wrapped onto a cylinder: texture rollers and lampshades.

The flat print is made of the UNROLLED STRIP as every flat tile is
(:func:`~fabtiles.solid.print_model.print_model`): ``x`` in ``[0, C]`` around the
circumference, ``y`` in ``[0, L]`` along the axis, ``z`` the print's heights. The
strip's pattern repeats in ``x`` with a period dividing ``C``, so its edges ``x = 0``
and ``x = C`` match. Each checked part is mapped onto the cylinder standing on its
end (:func:`wrap_part`):

- ``y`` -> ``Z`` (the axis, ``0 .. L``), ``x`` -> the angle ``theta = 2 pi x / C``
  (counter-clockwise seen from above), ``z`` -> the radius
  ``r = outer_radius_mm - (top_mm - z)``, the axis at ``(outer_radius_mm, outer_radius_mm)``
  so that the mesh lies in the positive quadrant as flat prints do. The map keeps
  the faces' winding (``(x, y, z) -> (theta, Z, r)`` is an even permutation of the
  cylinder's right-handed ``(r, theta, Z)``).
  With ``C = 2 pi outer_radius_mm`` the pattern keeps its size on the outer surface
  (any other pair stretches it round by their ratio).
- Before the map, the mesh is cut by planes ``x = const`` a small angle apart
  (:data:`CHORD_MM`, :data:`MAX_STEP_RAD`): every edge then spans less than that angle,
  so every chord lies within :data:`CHORD_MM` of its circle. Only triangles crossing a
  plane are cut; walls along ``y`` are left whole. A cut a hair from a corner is made
  at the corner, and a sliver's cut a hair long collapsed (:func:`slice_x`): no needle
  is left whose float32 normal would be rounding.
- The SEAM: the flat part's walls at ``x = 0`` and ``x = C`` would meet face to face.
  They are removed and the two open boundaries glued vertex to vertex by ``(y, z)``
  (a vertex one side has and the other lacks splits the other side's edge: no
  T-junction), so the body is one closed manifold and ``x = C`` *is* ``x = 0``.

The wrapped mesh is checked as a slicer reads it (:mod:`fabtiles.solid.mesh_check`),
against the exact volume of the curved body of the flat mesh (the map's Jacobian is
``r 2 pi / C``), within the check's 0.5 %: the chords cut off a fraction of about
``angle^2 / 6`` of it, at most about 0.1 %.

:func:`cylinder_print` wraps every part of a flat print model (and its fused body),
with a :class:`LampHolder` fused to the inside of a lampshade if asked:
a :class:`CylinderPrint`, which the STL, 3MF and GLB writers read as they read a
flat :class:`~fabtiles.solid.print_model.PrintModel`. A cylinder has no STEP: its
B-rep would be curved faces of the pattern's every edge, which fabtiles does not make.
manifold3d is imported only inside the functions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, cast

import numpy as np

from ..core.errors import FabricationError, ParameterError
from ..core.native import import_uninterrupted
from ..core.validate import check_float, check_int
from ._mesh_build import QUANTUM
from .mesh_check import check_indexed, cross_rows, merge_indexed32
from .parts import CheckedPart, stack_stats
from .print_model import PartPrint, PrintPart

if TYPE_CHECKING:
    from .print_model import PrintModel

NO_STEP = (
    "a cylinder's STEP is not made: its B-rep would need a curved face for every edge of the "
    "pattern wrapped round it, which fabtiles does not build; write STL or 3MF"
)
"""Why a cylinder has no STEP (its :attr:`CylinderPrint.brep` raises it; the web app shows it by the button)."""

CHORD_MM = 0.01
"""Largest distance between a wrapped edge (a chord) and the circle it stands for, at the outer radius."""

SEAM_SNAP_MM = 2.5 * QUANTUM
"""How far (along the axis) a vertex of the strip's edge ``x = C`` may lie from its twin at ``x = 0``
and still be glued to it: the strip's two edges are cut from one periodic pattern, each crossing
rounded to the grid on its own, so a crossing may land one grid step apart."""


# --------------------------------------------------------------------------- wrapping one part


def wrap_part(
    part: CheckedPart,
    *,
    circumference_mm: float,
    outer_radius_mm: float,
    top_mm: float,
    chord_mm: float = CHORD_MM,
    name: str = "part",
) -> CheckedPart:
    """A checked flat part of the unrolled strip wrapped onto the cylinder (see the module text).

    Parameters
    ----------
    part : CheckedPart
        A flat part of a strip ``C x L`` whose pattern is periodic in ``x`` with a period
        dividing ``C`` (its outline's edges ``x = 0`` and ``x = C`` meet).
    circumference_mm : float
        ``C``: the strip's width, the circumference of the outer surface.
    outer_radius_mm : float
        The radius the flat height ``top_mm`` goes to.
    top_mm : float
        The flat print's highest ``z`` (of all its parts, so that parts stay touching).
    chord_mm : float, optional
        Largest distance of a chord from its circle at the outer radius.
    name : str, optional
        The part's name in error messages.

    Returns
    -------
    CheckedPart
        The wrapped mesh, merged by float32 position and checked as a slicer reads it.
        ``volume_mm3`` is the exact volume of the curved body of the flat mesh,
        ``mesh_volume_mm3`` the wrapped mesh's (its chords), ``bodies`` the flat part's
        bodies once those meeting across the seam are one; ``region`` and ``outline``
        stay the flat part's (the strip's 2D shapes, as unrolled).

    Raises
    ------
    ParameterError
        A circumference other than the strip's width, a top below the part's highest
        point or at or beyond the outer radius (no room for the inside).
    FabricationError
        The strip's edges do not meet (a pattern not periodic in ``C``), or the wrapped
        mesh fails the check.
    """
    c = check_float("circumference_mm", circumference_mm, low=0, low_open=True)
    big_r = check_float("outer_radius_mm", outer_radius_mm, low=0, low_open=True)
    top = check_float("top_mm", top_mm, low=0, low_open=True)
    chord = check_float("chord_mm", chord_mm, low=0, low_open=True, high=big_r)
    x0, _, x1, _ = part.outline.bounds
    width = x1 - x0
    if abs(width - c) > 2 * QUANTUM + 1e-9 * c:
        raise ParameterError(
            f"circumference_mm = {c:g} mm must be the strip's width, {width:g} mm (within {2 * QUANTUM:g} mm)",
            param="circumference_mm",
        )
    if top >= big_r:
        raise ParameterError(
            f"top_mm = {top:g} mm must be less than outer_radius_mm = {big_r:g} mm (the inside's radius is their "
            "difference)",
            param="top_mm",
        )
    verts = np.asarray(part.vertices, np.float64)
    faces = np.asarray(part.faces, np.int64)
    zmax = float(verts[:, 2].max())
    if zmax > top + 1e-6:
        raise ParameterError(f"top_mm = {top:g} mm is below the part's highest point, {zmax:g} mm", param="top_mm")
    volume = _wrapped_volume(verts, faces, width=width, inner=big_r - top)
    planes = cut_planes(x0, width, big_r, chord)
    spacing = width / (len(planes) + 1)
    sv, sf = slice_x(verts, faces, planes, SNAP_FRACTION * spacing, chord)
    gv, gf, twins = glue_seam(sv, sf, x0, x1, name=name)
    bodies = _wrapped_bodies(sf, twins, len(gv), part.bodies, name)
    cyl = to_cylinder(gv, x0=x0, width=width, outer_radius_mm=big_r, top_mm=top)
    # two cut points a fraction of a micron apart (a sliver of the flat triangulation cut by a plane) are
    # one float32 point: merged, the sliver's pieces collapse and go (an edge collapsed)
    cyl, gf = merge_indexed32(cyl, gf)
    gf = gf[(gf[:, 0] != gf[:, 1]) & (gf[:, 1] != gf[:, 2]) & (gf[:, 0] != gf[:, 2])]
    mverts, mfaces, found = check_indexed(
        cyl, gf, name=f"wrapped {name}", volume=volume, bodies=bodies, with_volume=True
    )
    return CheckedPart(mverts, mfaces, float(volume), int(bodies), part.region, part.outline, float(found))


def to_cylinder(verts, *, x0: float, width: float, outer_radius_mm: float, top_mm: float) -> np.ndarray:
    """Strip coordinates ``(x, y, z)`` on the cylinder (see the module text); float64.

    >>> p = to_cylinder(np.array([[0.0, 2, 1], [25, 3, 1]]), x0=0, width=100, outer_radius_mm=10, top_mm=1)
    >>> np.round(p, 9).tolist()
    [[20.0, 10.0, 2.0], [10.0, 20.0, 3.0]]
    """
    verts = np.asarray(verts, np.float64)
    theta = (2 * math.pi / width) * (verts[:, 0] - x0)
    r = outer_radius_mm - top_mm + verts[:, 2]
    out = np.column_stack([outer_radius_mm + r * np.cos(theta), outer_radius_mm + r * np.sin(theta), verts[:, 1]])
    return np.maximum(out, 0.0)  # the outer surface touches x = 0 and y = 0: no -1e-8 from rounding


def _wrapped_volume(verts, faces, *, width: float, inner: float) -> float:
    """The exact volume of the flat closed mesh's body wrapped (``r = inner + z``, ``theta = 2 pi x / width``).

    The map's Jacobian is ``r 2 pi / width``: the wrapped volume is ``2 pi / width`` times the flat
    body's ``inner V + integral of z dV``, both sums over the tetrahedra the faces make with the origin.

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    >>> f = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5],
    ...               [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    >>> round(_wrapped_volume(v, f, width=1, inner=2), 9) == round(math.pi * (3**2 - 2**2), 9)
    True
    """
    p0, p1, p2 = (verts[faces[:, k]] for k in range(3))
    six = np.einsum("ij,ij->i", p0, cross_rows(p1, p2))
    vol = six.sum() / 6
    moment = (six * (p0[:, 2] + p1[:, 2] + p2[:, 2])).sum() / 24
    return float(2 * math.pi / width * (inner * vol + moment))


SNAP_FRACTION = 0.02
"""A cut closer than this fraction of the planes' spacing to an edge's end is made at that end
(:func:`slice_x`): no sliver a fraction of a micron wide, whose float32 normal would be noise."""


MAX_STEP_RAD = 0.075
"""The largest angle between the planes, whatever the radius: the chords of a small cylinder then cut
off at most ``angle^2 / 6``, about 0.1 % of its volume (the check allows 0.5 %)."""


def cut_planes(x0: float, width: float, outer_radius_mm: float, chord_mm: float) -> np.ndarray:
    """The ``x`` of the planes the strip is cut at before it is wrapped: equal steps of at most the angle
    whose chord at ``outer_radius_mm`` lies ``chord_mm`` from its arc, and of at most :data:`MAX_STEP_RAD`
    (less the room a cut moved to an
    edge's end takes, :data:`SNAP_FRACTION` either side), each moved half a grid step off the grid (the
    flat mesh's vertices are on it), so no plane passes through a vertex.

    >>> len(cut_planes(0, 100, 30, 0.01))  # 2 acos(1 - 0.01 / 30) = 0.0516 rad, less 4 %: 127 steps
    126
    >>> len(cut_planes(0, 100, 10, 0.01))  # 0.0894 rad: the 0.075 rad at most, less 4 %: 88 steps
    87
    """
    step = min(2 * math.acos(1 - chord_mm / outer_radius_mm), MAX_STEP_RAD) / (1 + 2 * SNAP_FRACTION)
    n = max(math.ceil(2 * math.pi / step), 1)
    planes = x0 + width * np.arange(1, n) / n
    return (np.floor(planes / QUANTUM) + 0.5) * QUANTUM


def slice_x(verts, faces, planes, snap_mm: float = 0.0, collapse_mm: float = 0.0):
    """The mesh with every triangle cut at the planes ``x = planes`` (sorted) it crosses.

    Each cut triangle becomes strips between its planes (a strip holding its middle
    corner a pentagon), each fanned into triangles of the triangle's winding. A point
    on an edge is made once per edge and plane, so the neighbours across an edge cut it
    at the same vertex: the mesh stays closed. An edge whose end lies within ``snap_mm``
    of the plane is cut at that end (the nearer), no new point; a triangle's cut shorter
    than ``collapse_mm`` (a sliver's) is collapsed to its lower-numbered end (an old vertex
    if one is): a needle of a curved surface has a float32 normal that is mostly rounding.
    No plane may pass through a vertex.
    Returns ``(vertices, faces)``: the old vertices first, the new ones after.

    >>> v = np.array([[0.0, 0, 0], [4, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> sv, sf = slice_x(v, f, np.array([1.5, 2.5]))
    >>> len(sv), len(sf), round(check_indexed(sv, sf, volume=4 / 6, bodies=1, with_volume=True)[2], 9)
    (10, 16, 0.666666667)
    """
    verts = np.asarray(verts, np.float64)
    faces = np.asarray(faces, np.int64)
    planes = np.asarray(planes, np.float64)
    x = verts[:, 0]
    order = np.argsort(x[faces], axis=1, kind="stable")
    srt = np.take_along_axis(faces, order, 1)
    ka = np.searchsorted(planes, x[srt[:, 0]], side="right")
    kc = np.searchsorted(planes, x[srt[:, 2]], side="left")
    cut = kc > ka
    if not cut.any():
        return verts, faces
    a, b, c = srt[cut].T
    o = order[cut]
    flip = (o[:, 1] - o[:, 0]) % 3 == 1  # (a, b, c) wound as the face: the strips, wound (a, c, b), turn over
    ka, k = ka[cut], (kc - ka)[cut]
    xb = x[b]
    ns = k + 1
    tri = np.repeat(np.arange(len(a)), ns)
    s = np.arange(int(ns.sum())) - np.repeat(np.cumsum(ns) - ns, ns)
    has_lo, has_hi = s > 0, s < k[tri]
    jlo = np.where(has_lo, ka[tri] + s - 1, 0)
    jhi = np.where(has_hi, ka[tri] + s, 0)
    at, bt, ct = a[tri], b[tri], c[tri]
    lo = np.where(has_lo, planes[jlo], x[at])
    hi = np.where(has_hi, planes[jhi], x[ct])

    # every point wanted: (lower-x end, upper-x end, plane); the chain runs a -> b -> c
    def chain(j):
        below = planes[j] < xb[tri]
        return np.where(below, at, bt), np.where(below, bt, ct)

    clo_u, clo_v = chain(jlo)
    chi_u, chi_v = chain(jhi)
    wants = [(at, ct, jlo, has_lo), (at, ct, jhi, has_hi), (clo_u, clo_v, jlo, has_lo), (chi_u, chi_v, jhi, has_hi)]
    u = np.concatenate([w[0][w[3]] for w in wants])
    v = np.concatenate([w[1][w[3]] for w in wants])
    j = np.concatenate([w[2][w[3]] for w in wants])
    n = len(verts)
    key = (np.minimum(u, v) * n + np.maximum(u, v)) * len(planes) + j
    _, first, inv = np.unique(key, return_index=True, return_inverse=True)
    pu, pv, pj = u[first], v[first], j[first]
    du, dv = np.abs(x[pu] - planes[pj]), np.abs(x[pv] - planes[pj])
    at_end = np.minimum(du, dv) < snap_mm
    fresh = ~at_end
    pu, pv, pj = pu[fresh], pv[fresh], pj[fresh]
    t = (planes[pj] - x[pu]) / (x[pv] - x[pu])
    new = verts[pu] + t[:, None] * (verts[pv] - verts[pu])
    new[:, 0] = planes[pj]
    point = np.where(du <= dv, u[first], v[first])
    point[fresh] = n + np.arange(len(new))
    ids = point[inv.ravel()]
    got = []
    start = 0
    for w in wants:
        out = w[0].copy()  # no point: the strip's end is the triangle's corner a or c
        m = int(w[3].sum())
        out[w[3]] = ids[start : start + m]
        start += m
        got.append(out)
    llo, lhi, clo, chi = got
    llo = np.where(has_lo, llo, at)
    clo = np.where(has_lo, clo, at)
    lhi = np.where(has_hi, lhi, ct)
    chi = np.where(has_hi, chi, ct)
    b_in = (lo <= xb[tri]) & (xb[tri] <= hi)
    bid = np.where(b_in, bt, chi)
    tris = np.concatenate(
        [
            np.column_stack([llo, lhi, chi]),
            np.column_stack([llo, chi, bt])[b_in],
            np.column_stack([llo, bid, clo]),
        ]
    )
    tflip = np.concatenate([flip[tri], flip[tri][b_in], flip[tri]])
    tris[tflip] = tris[tflip][:, ::-1]
    out = np.concatenate([verts, new])
    if collapse_mm > 0:
        # a sliver's two cut points, a hair apart on one plane, are one point: the cut between them collapsed
        pa, pb = lhi[has_hi], chi[has_hi]
        pair = (pa != pb) & ((pa >= n) | (pb >= n))
        pa, pb = pa[pair], pb[pair]
        near = np.linalg.norm(out[pa] - out[pb], axis=1) < collapse_mm
        if near.any():
            from ..core.graph import components

            pa, pb = pa[near], pb[near]
            # a cut point a hair from two old vertices (each a cut moved to an edge's end) joins neither: two
            # old vertices made one would fold the mesh where they are not an edge's two ends
            comp = components(len(out), pa, pb)
            shared = np.bincount(comp[:n], minlength=len(out))[comp] > 1
            keep = ~(shared[pa] & ((pa < n) | (pb < n)))
            pa, pb = pa[keep], pb[keep]
            # a collapse that would open the mesh (its two points share a neighbour beyond the sliver's two
            # triangles) is not made: the sliver stays, closed
            sliced = np.concatenate([faces[~cut], tris])
            for _ in range(COLLAPSE_ROUNDS):
                comp = components(len(out), pa, pb)
                bad = _unpaired_vertices(_proper(comp[sliced]))
                if not len(bad):
                    break
                off = np.isin(comp[pa], bad)
                if not off.any():
                    break
                pa, pb = pa[~off], pb[~off]
            tris = components(len(out), pa, pb)[tris]  # onto the lowest: an old vertex if one is
    return out, np.concatenate([faces[~cut], _proper(tris)])


COLLAPSE_ROUNDS = 4
"""Rounds of :func:`slice_x` taking back the collapses that open the mesh."""


def _proper(tris):
    """The triangles with three distinct corners."""
    return tris[(tris[:, 0] != tris[:, 1]) & (tris[:, 1] != tris[:, 2]) & (tris[:, 0] != tris[:, 2])]


def _unpaired_vertices(faces) -> np.ndarray:
    """The vertices of the edges that are not used exactly once each way round (a closed mesh has none)."""
    e = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    n = int(faces.max()) + 1 if len(faces) else 1
    keys, counts = np.unique(e[:, 0] * n + e[:, 1], return_counts=True)
    back = (keys % n) * n + keys // n
    at = np.minimum(np.searchsorted(keys, back), len(keys) - 1)
    bad = (counts != 1) | (keys[at] != back) | (counts[at] != 1)
    return np.unique(np.concatenate([keys[bad] // n, keys[bad] % n]))


def glue_seam(verts, faces, x0: float, x1: float, *, name: str = "part"):
    """The strip's walls at ``x = x0`` and ``x = x1`` removed and the two boundaries glued.

    Returns ``(vertices, faces, twins)``: the faces with every vertex at ``x1`` replaced by its
    twin at ``x0`` (same ``y, z``; new vertices split edges where one side lacks a vertex the
    other has), and ``twins`` the ``(x1 vertex, x0 vertex)`` pairs.
    """
    verts = np.asarray(verts, np.float64)
    faces = np.asarray(faces, np.int64)
    on = (verts[:, 0] == x0, verts[:, 0] == x1)
    faces = faces[~(on[0][faces].all(axis=1) | on[1][faces].all(axis=1))]
    yz = verts[:, 1:].copy()
    # a crossing rounded to the grid one step apart on the two edges: glue it to its twin's place
    ends = [np.unique(faces[on[s][faces]]) for s in (0, 1)]
    yz = _snap_to_twins(yz, ends[0], ends[1])
    verts = np.column_stack([verts[:, 0], yz])
    for s in (0, 1):
        new_verts: list = []
        faces = _split_at(verts, faces, verts[:, 0] == (x0, x1)[s], yz[ends[1 - s]], new_verts, (x0, x1)[s])
        if new_verts:
            verts = np.concatenate([verts, np.array(new_verts)])
    on = (verts[:, 0] == x0, verts[:, 0] == x1)
    used = np.zeros(len(verts), bool)
    used[faces.ravel()] = True
    zero = {(float(verts[i, 1]), float(verts[i, 2])): int(i) for i in np.flatnonzero(on[0] & used)}
    ones = np.flatnonzero(on[1] & used)
    remap = np.arange(len(verts))
    pairs = []
    lost = 0
    for i in ones:
        twin = zero.pop((float(verts[i, 1]), float(verts[i, 2])), None)
        if twin is None:
            lost += 1
            continue
        remap[i] = twin
        pairs.append((i, twin))
    if lost or zero:
        raise FabricationError(
            f"the {name} mesh's edges x = {x0:g} and x = {x1:g} of the strip do not meet: {lost + len(zero)} "
            "vertices have no twin on the other edge (the strip's pattern must repeat with a period dividing the "
            "circumference); nothing was written"
        )
    return verts, remap[faces], np.array(pairs, np.int64).reshape(-1, 2)


def _snap_to_twins(yz, ends0, ends1):
    """``yz`` with each vertex of ``ends1`` lacking an exact twin among ``ends0`` moved onto the nearest one of
    the same ``z`` within :data:`SEAM_SNAP_MM` along ``y``, unless a vertex of ``ends1`` is there already: then
    the two are one crossing and a point splitting an edge of the same side, which :func:`_split_at` matches."""
    have = {(float(p[0]), float(p[1])) for p in yz[ends0]}
    taken = {(float(p[0]), float(p[1])) for p in yz[ends1]}
    by_z: dict = {}
    for i in ends0:
        by_z.setdefault(float(yz[i, 1]), []).append(float(yz[i, 0]))
    yz = yz.copy()
    for i in ends1:
        y, z = float(yz[i, 0]), float(yz[i, 1])
        if (y, z) in have or z not in by_z:
            continue
        ys = np.array(by_z[z])
        k = int(np.argmin(np.abs(ys - y)))
        if abs(ys[k] - y) <= SEAM_SNAP_MM and (float(ys[k]), z) not in taken:
            yz[i, 0] = ys[k]
    return yz


def _split_at(verts, faces, side, points, new_verts: list, xs: float):
    """``faces`` with each face's edge lying on ``side`` split at those of ``points`` (y, z) strictly inside it
    (a fan from the face's third corner), new vertices at ``x = xs`` appended to ``new_verts``."""
    if not len(points) or not len(faces):
        return faces
    e = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    on_side = side[e].all(axis=1)
    idx = np.flatnonzero(on_side)
    if not len(idx):
        return faces
    p = verts[e[idx, 0], 1:]
    q = verts[e[idx, 1], 1:]
    d = q - p
    length2 = (d * d).sum(axis=1)
    points = np.unique(points, axis=0)
    rel = points[None, :, :] - p[:, None, :]
    t = (rel * d[:, None, :]).sum(axis=2) / length2[:, None]
    off = rel[:, :, 0] * d[:, None, 1] - rel[:, :, 1] * d[:, None, 0]
    inside = (np.abs(off) <= 1e-9 * np.sqrt(length2)[:, None]) & (t > 1e-12) & (t < 1 - 1e-12)
    hit_edges = np.flatnonzero(inside.any(axis=1))
    if not len(hit_edges):
        return faces
    base = len(verts) + len(new_verts)
    made: dict = {}
    drop = []
    extra = []
    for h in hit_edges:
        face, pos = divmod(int(idx[h]), 3)
        a, b = int(e[idx[h], 0]), int(e[idx[h], 1])
        w = int(faces[face, (pos + 2) % 3])
        hits = np.flatnonzero(inside[h])
        chain = [a]
        for k in hits[np.argsort(t[h, hits])]:
            key = (float(points[k, 0]), float(points[k, 1]))
            if key not in made:
                made[key] = base + len(made)
                new_verts.append((xs, *key))
            chain.append(made[key])
        chain.append(b)
        drop.append(face)
        extra += [(chain[i], chain[i + 1], w) for i in range(len(chain) - 1)]
    keep = np.ones(len(faces), bool)
    keep[drop] = False
    return np.concatenate([faces[keep], np.array(extra, np.int64)])


def _wrapped_bodies(flat_faces, twins, n: int, flat_bodies: int, name: str) -> int:
    """The bodies the wrapped part must have: the flat mesh's (which must be the part's ``flat_bodies``),
    those joined across the seam by a pair of twins counted once."""
    from ..core.graph import components

    e = flat_faces[:, [0, 1, 1, 2]].reshape(-1, 2)
    used = np.zeros(n, bool)
    used[e.ravel()] = True
    flat = components(n, e[:, 0], e[:, 1])
    found = int(np.count_nonzero((flat == np.arange(n)) & used))
    if found != flat_bodies:
        raise FabricationError(
            f"the {name} mesh cut for wrapping has {found} bodies where the flat part has {flat_bodies}; "
            "nothing was written"
        )
    if not len(twins):
        return found
    joined = components(n, np.concatenate([e[:, 0], twins[:, 0]]), np.concatenate([e[:, 1], twins[:, 1]]))
    return int(np.count_nonzero((joined == np.arange(n)) & used))


# --------------------------------------------------------------------------- the lamp holder


@dataclass(frozen=True, slots=True)
class LampHolder:
    """A flat ring inside a lampshade's ``Z = 0`` end that holds a lamp fitting.

    An inner ring around the fitting's hole and ``spokes`` straight spokes, each as wide as the
    ring, out into the shade's wall (they overlap it by half its thickness, so the holder and
    the shade are one body). It lies on the bed with the shade's rim: no support.

    >>> LampHolder(fitting_mm=40)
    LampHolder(fitting_mm=40.0, ring_mm=5.0, spokes=3, thickness_mm=2.0)
    >>> LampHolder(fitting_mm=40, spokes=1)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: spokes must be an integer >= 2 and <= 24, got 1
    """

    fitting_mm: float
    """The hole for the lamp fitting (mm): about 40 for an E27 lampholder's ring, 28 for E14."""
    ring_mm: float = 5.0
    """The width of the ring around the hole and of each spoke (mm)."""
    spokes: int = 3
    """How many spokes join the ring to the shade's wall."""
    thickness_mm: float = 2.0
    """The holder's thickness along the axis (mm)."""

    def __post_init__(self):
        object.__setattr__(self, "fitting_mm", check_float("fitting_mm", self.fitting_mm, low=0, low_open=True))
        object.__setattr__(self, "ring_mm", check_float("ring_mm", self.ring_mm, low=0, low_open=True))
        object.__setattr__(self, "spokes", check_int("spokes", self.spokes, low=2, high=24))
        object.__setattr__(self, "thickness_mm", check_float("thickness_mm", self.thickness_mm, low=0, low_open=True))


def holder_outline(holder: LampHolder, *, inner_radius_mm: float, wall_mm: float, chord_mm: float = CHORD_MM):
    """The holder's 2D shape (a manifold3d ``CrossSection``) around the origin: the ring and its spokes,
    which reach half way into the wall ``wall_mm`` thick outside ``inner_radius_mm``.

    Raises :class:`~fabtiles.ParameterError` when the ring does not fit inside the shade with a
    spoke's length to spare.
    """
    m3 = import_uninterrupted("manifold3d")

    hole = holder.fitting_mm / 2
    ring = hole + holder.ring_mm
    if ring + holder.ring_mm > inner_radius_mm:
        raise ParameterError(
            f"fitting_mm = {holder.fitting_mm:g} mm with ring_mm = {holder.ring_mm:g} mm is too wide for the shade: "
            f"the holder's ring and a spoke (diameter {2 * (ring + holder.ring_mm):g} mm) must fit inside its "
            f"inside diameter, {2 * inner_radius_mm:g} mm",
            param="fitting_mm",
        )
    reach = inner_radius_mm + wall_mm / 2

    def circle(r):
        step = 2 * math.acos(1 - min(chord_mm / r, 1.0))
        return m3.CrossSection.circle(r, max(math.ceil(2 * math.pi / step), 12))

    shape = circle(ring) - circle(hole)
    # a spoke from inside the ring to half way into the wall, its far end trimmed to the wall's middle
    spoke = m3.CrossSection.square((reach - hole / 2, holder.ring_mm)).translate((hole / 2, -holder.ring_mm / 2))
    spoke = (spoke - circle(hole)) ^ circle(reach)
    for k in range(holder.spokes):
        shape = shape + spoke.rotate(360.0 * k / holder.spokes)
    return shape


def with_holder(
    part: CheckedPart,
    holder: LampHolder,
    *,
    outer_radius_mm: float,
    inner_radius_mm: float,
    wall_mm: float | None = None,
    name: str = "part",
) -> CheckedPart:
    """A wrapped part fused with the lamp holder at its ``Z = 0`` end (manifold3d's union), checked again.

    The axis is at ``(outer_radius_mm, outer_radius_mm)``; the spokes reach half way into the part's wall,
    ``wall_mm`` thick outside ``inner_radius_mm`` (default: up to the outer radius). ``volume_mm3`` is the
    part's exact volume plus what the union added as meshed; the bodies stay the part's (the holder joins
    the one it touches).
    """
    m3 = import_uninterrupted("manifold3d")

    length = float(part.vertices[:, 2].max())
    if holder.thickness_mm >= length:
        raise ParameterError(
            f"thickness_mm = {holder.thickness_mm:g} mm of the lamp holder must be less than the shade's length, "
            f"{length:g} mm",
            param="thickness_mm",
        )
    shade = m3.Manifold(
        m3.Mesh(
            vert_properties=np.ascontiguousarray(part.vertices, np.float32),
            tri_verts=np.ascontiguousarray(part.faces, np.uint32),
        )
    )
    if shade.status() != m3.Error.NoError:
        raise FabricationError(
            f"the {name} mesh could not be read by manifold3d ({shade.status()}); nothing was written"
        )
    wall = outer_radius_mm - inner_radius_mm if wall_mm is None else wall_mm
    ring = holder_outline(holder, inner_radius_mm=inner_radius_mm, wall_mm=wall)
    body = m3.Manifold.extrude(ring, holder.thickness_mm).translate((outer_radius_mm, outer_radius_mm, 0.0))
    fused = shade + body
    mesh = fused.to_mesh()
    verts = np.asarray(mesh.vert_properties, np.float64)[:, :3]
    faces = np.asarray(mesh.tri_verts, np.int64)
    volume = part.volume_mm3 + fused.volume() - shade.volume()
    mverts, mfaces, found = check_indexed(
        verts, faces, name=f"{name} with its lamp holder", volume=volume, bodies=part.bodies, with_volume=True
    )
    return CheckedPart(mverts, mfaces, float(volume), part.bodies, part.region, part.outline, float(found))


# --------------------------------------------------------------------------- the print model


def stack_top(stack) -> float:
    """The flat print's highest ``z`` (mm): what goes to the outer radius.

    >>> from fabtiles.solid._mesh_build import resolve_stack
    >>> stack_top(resolve_stack("fdm-0.4mm", "pierced"))
    3.0
    """
    if stack.style in ("relief", "mosaic"):
        return float(stack.base + stack.relief)
    if stack.style == "pierced":
        return float(stack.pierced)
    return float(stack.base)


def inner_wall(stack) -> float:
    """The thickness of the print's solid inside (mm): a relief's or mosaic's plate, a deboss plate under its
    grooves, a pierced wall; the lamp holder's spokes reach half way into it.

    >>> from fabtiles.solid._mesh_build import resolve_stack
    >>> inner_wall(resolve_stack("fdm-0.4mm", "deboss", base_mm=2, deboss_mm=0.8))
    1.2
    """
    if stack.style in ("relief", "mosaic"):
        return float(stack.base)
    if stack.style == "pierced":
        return float(stack.pierced)
    return float(stack.base - stack.deboss)


class CylinderPrint:
    """A flat print model's parts wrapped onto a cylinder, read by the STL, 3MF and GLB writers as a
    :class:`~fabtiles.solid.print_model.PrintModel` is (:class:`~fabtiles.export.formats.PrintModelProtocol`).

    Made by :func:`cylinder_print`; each mesh is made on first use, once. ``region`` and ``outline``
    are the flat strip's (unrolled); ``report`` is the flat model's. A cylinder has no STEP
    (:attr:`brep` raises).
    """

    def __init__(self, model, *, circumference_mm: float, outer_radius_mm: float, holder: LampHolder | None = None):
        self.model = model
        """The flat print of the unrolled strip (:class:`~fabtiles.solid.print_model.PrintModel`)."""
        self.profile = model.profile
        self.stack = model.stack
        self.report = model.report
        self.region = model.region
        self.outline = model.outline
        self.circumference_mm = float(circumference_mm)
        self.outer_radius_mm = float(outer_radius_mm)
        self.holder = holder
        self.top_mm = stack_top(model.stack)
        """The flat print's highest ``z``: it goes to the outer radius."""
        self.inner_radius_mm = self.outer_radius_mm - self.top_mm
        """The inside's radius (a roller's bore, a lampshade's inner wall)."""
        _, y0, _, y1 = model.outline.bounds
        self.length_mm = float(y1 - y0)
        """The length along the axis: the strip's height."""

    def _wrap(self, part: CheckedPart, name: str) -> CheckedPart:
        return wrap_part(
            part,
            circumference_mm=self.circumference_mm,
            outer_radius_mm=self.outer_radius_mm,
            top_mm=self.top_mm,
            chord_mm=min(CHORD_MM, self.profile.tolerance_mm),
            name=name,
        )

    def _held(self, part: CheckedPart, name: str) -> CheckedPart:
        if self.holder is None:
            return part
        return with_holder(
            part,
            self.holder,
            outer_radius_mm=self.outer_radius_mm,
            inner_radius_mm=self.inner_radius_mm,
            wall_mm=inner_wall(self.stack),
            name=name,
        )

    @property
    def single_part(self) -> bool:
        """True when the print is one part: its fused body and its part are the same mesh."""
        return self.model.single_part

    @cached_property
    def parts(self) -> dict:
        """The wrapped parts by name, in print order (:class:`~fabtiles.solid.print_model.PrintPart`); the
        lamp holder is fused to the part that reaches the inside (the plate, a pierced wall)."""
        flat = self.model.parts
        if self.single_part:
            ((name, p),) = flat.items()
            return {name: PrintPart(p.name, p.material, p.colour, self.fused)}
        wrapped = {n: PrintPart(p.name, p.material, p.colour, self._wrap(p.mesh, n)) for n, p in flat.items()}
        if self.holder is not None:
            inner = min(wrapped, key=lambda n: _min_radius(wrapped[n].mesh, self.outer_radius_mm))
            p = wrapped[inner]
            wrapped[inner] = PrintPart(p.name, p.material, p.colour, self._held(p.mesh, inner))
        return wrapped

    @cached_property
    def fused(self) -> CheckedPart:
        """The print as one wrapped, checked body (with the lamp holder): what an STL holds.

        Raises :class:`~fabtiles.FabricationError` when it is more than one body: a cylinder prints standing
        as one piece, and a piece of a pierced wall not joined to the rest falls out of it."""
        part = self._held(self._wrap(self.model.fused, self.fused_name), self.fused_name)
        if part.bodies > 1:
            raise FabricationError(
                f"the wrapped {self.fused_name} falls apart into {part.bodies} bodies: {part.bodies - 1} "
                f"piece{'s' if part.bodies > 2 else ''} of material not joined to the rest (fabtiles check lists "
                "them as loose_part); make the stroke wider so that the pattern's pieces meet; nothing was written"
            )
        return part

    @property
    def fused_name(self) -> str:
        return self.model.fused_name

    def files(self) -> list:
        """``[("", self)]``: one file of each format holds the print's parts."""
        return [("", self)]

    def bodies(self) -> list:
        """``[(suffix, print), ...]``: the print as files of one body each (a mosaic's colours)."""
        if self.stack.style == "mosaic" and len(self.parts) > 1:
            # PartPrint reads only the profile, stack and report, which this print has as a PrintModel has
            model = cast("PrintModel", self)
            return [
                (f"-{name.split(' (')[0].replace(' ', '-')}", PartPrint(model, p)) for name, p in self.parts.items()
            ]
        return [("", self)]

    @property
    def brep(self):
        """A cylinder's STEP is not made: raises :class:`~fabtiles.FabricationError`."""
        raise FabricationError(NO_STEP)

    @property
    def breps(self):
        """A cylinder's STEP is not made (:attr:`brep` raises)."""
        return [(None, self.brep)]

    def stats(self) -> dict:
        """The stack's style and heights and the cylinder's sizes, for a file's report."""
        return dict(
            stack_stats(self.stack),
            surface={
                "shape": "cylinder",
                "diameter_mm": 2 * self.outer_radius_mm,
                "circumference_mm": self.circumference_mm,
                "length_mm": self.length_mm,
                "inner_diameter_mm": 2 * self.inner_radius_mm,
            },
        )


def _min_radius(part: CheckedPart, outer_radius_mm: float) -> float:
    """The least distance of a wrapped part's vertices from the axis."""
    v = part.vertices
    return float(np.hypot(v[:, 0] - outer_radius_mm, v[:, 1] - outer_radius_mm).min())


def cylinder_print(
    model, *, circumference_mm: float, outer_radius_mm: float, holder: LampHolder | None = None
) -> CylinderPrint:
    """A flat print of the unrolled strip wrapped onto a cylinder: a :class:`CylinderPrint`.

    Parameters
    ----------
    model : PrintModel
        The flat print of the strip ``C x L`` (:func:`~fabtiles.solid.print_model.print_model`),
        its pattern periodic in ``x`` with a period dividing ``C``.
    circumference_mm : float
        ``C``, the strip's width: the outer surface's circumference.
    outer_radius_mm : float
        The outer surface's radius (the flat print's top goes there).
    holder : LampHolder, optional
        A lamp holder fused inside the ``Z = 0`` end.

    No mesh is made here; the sizes are checked now (:class:`~fabtiles.ParameterError`):
    a circumference other than the strip's width, an outer radius not beyond the print's
    height, a lamp holder too wide for the inside.
    """
    c = check_float("circumference_mm", circumference_mm, low=0, low_open=True)
    big_r = check_float("outer_radius_mm", outer_radius_mm, low=0, low_open=True)
    x0, _, x1, _ = model.outline.bounds
    if abs((x1 - x0) - c) > 2 * QUANTUM + 1e-9 * c:
        raise ParameterError(
            f"circumference_mm = {c:g} mm must be the strip's width, {x1 - x0:g} mm (within {2 * QUANTUM:g} mm)",
            param="circumference_mm",
        )
    top = stack_top(model.stack)
    if top >= big_r:
        raise ParameterError(
            f"outer_radius_mm = {big_r:g} mm must be more than the print's height, {top:g} mm",
            param="outer_radius_mm",
        )
    if holder is not None and not isinstance(holder, LampHolder):
        raise ParameterError(f"holder must be a LampHolder or None, got {holder!r}", param="holder")
    if holder is not None:
        holder_outline(holder, inner_radius_mm=big_r - top, wall_mm=inner_wall(model.stack))
    return CylinderPrint(model, circumference_mm=c, outer_radius_mm=big_r, holder=holder)
