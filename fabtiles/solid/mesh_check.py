"""The check every mesh passes before it is written: the file as a slicer reads it.

A binary STL stores float32 corners; a slicer merges them by position. So a mesh
is rounded to float32, merged (:func:`merge_indexed32` from its vertices,
:func:`check_triangles` from an STL's corners: the same arrays), then it must have
no collapsed or flat face, every edge used once each way (watertight, 2-manifold,
consistently wound), a positive volume (within 0.5 % of the expected one when
given) and the expected number of bodies. numpy throughout: importing trimesh and
running its checks would take longer than building a sheet's mesh (``docs/speed.md``);
the tests check every file with trimesh independently.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import FabricationError
from ._triangulate import edges_pair_up

VOLUME_TOLERANCE = 0.005
"""Largest relative difference allowed between a mesh's volume and area x height."""


def _merge_points32(flat: np.ndarray):
    """Merge float32 points (k, 3) by exact position: ``(unique points (n, 3) float64, inverse (k,))``.

    The unique points come out in one order whatever the input order (by a hash of
    their bits, or by coordinates after a hash collision), so merging a mesh's
    vertices gives the same arrays as merging its triangles' corners.
    """
    flat = np.ascontiguousarray(flat, dtype=np.float32) + np.float32(0)  # -0.0 -> 0.0
    bits = flat.view(np.uint32).astype(np.uint64)
    key = (
        (bits[:, 0] * np.uint64(0x9E3779B97F4A7C15))
        ^ (bits[:, 1] * np.uint64(0xC2B2AE3D27D4EB4F))
        ^ (bits[:, 2] * np.uint64(0x165667B19E3779F9))
        ^ (bits[:, 2] << np.uint64(32))
    )
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
    (:func:`fabtiles.export.stl.stl_bytes`); every corner of one vertex has the same bits, so merging
    the used vertices by float32 position gives exactly what merging the file's
    3m corners gives (:func:`_merge_float32`), array for array, from about a
    sixth of the points, in a fraction of the time. Vertices distinct in float64
    that round to one float32 point merge, as in the file.

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
    """Connected components of a graph that hold at least one edge (:func:`fabtiles.core.graph.components`).

    >>> count_bodies(5, np.array([[0, 1], [1, 2], [3, 4]]))
    2
    """
    from ..core.graph import components

    edges = np.asarray(edges)
    parent = components(n_vertices, edges[:, 0], edges[:, 1])
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
    fabtiles.core.errors.FabricationError: the mesh mesh is not watertight as a slicer reads it (float32): 3 open edges; nothing was written
    """  # noqa: E501 - a doctest's lines are as Python prints them
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
    return _check_merged(*_merge_float32(tris32), name=name, volume=volume, bodies=bodies)[:2]


def check_indexed(vertices, faces, *, name="mesh", volume=None, bodies=None, with_volume=False):
    """Check the mesh that the STL of ``(vertices, faces)`` holds, as a slicer reads it; see :func:`check_mesh`.

    The same check as :func:`check_triangles` on the file's triangles, merged from
    the vertices (:func:`merge_indexed32`). Returns the merged ``(vertices, faces)``,
    and with ``with_volume`` the volume (mm^3) the check found (the writers report
    it, without a second pass over the mesh).
    """
    faces = np.asarray(faces)
    if not len(faces):
        _fail(name, "is empty", None)
    if not np.isfinite(np.asarray(vertices, dtype=np.float64)).all():
        _fail(name, "has non-finite coordinates", None)
    verts, faces, vol = _check_merged(*merge_indexed32(vertices, faces), name=name, volume=volume, bodies=bodies)
    return (verts, faces, vol) if with_volume else (verts, faces)


def _fail(name, why, merged):
    exc = FabricationError(f"the {name} mesh {why}; nothing was written")
    exc.mesh = merged  # (vertices, faces) merged by float32 position, or None
    raise exc


def _edge_problems(u, v, n: int) -> str:
    """What is wrong with the directed edges ``u -> v`` (of ``n`` vertices) that do not pair up: the open
    edges and the edges run twice the same way, as a sentence's end."""
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
    return ", ".join(problems)


def _check_merged(verts, faces, *, name, volume, bodies):
    """The checks of :func:`check_mesh` on a mesh merged by float32 position: ``(vertices, faces, volume)``."""
    merged = (verts, faces)
    collapsed = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])
    if collapsed.any():
        _fail(name, f"has {int(collapsed.sum())} faces that collapse when rounded to float32", merged)
    p0 = verts[faces[:, 0]]
    cross = cross_rows(verts[faces[:, 1]] - p0, verts[faces[:, 2]] - p0)
    zero = ~np.any(cross != 0, axis=1)
    if zero.any():
        _fail(name, f"has {int(zero.sum())} zero-area faces in float32", merged)
    # every directed edge exactly once and its reverse exactly once:
    # watertight, 2-manifold and consistently wound
    n = len(verts)
    u = faces.ravel()
    v = faces[:, [1, 2, 0]].ravel()
    if not edges_pair_up(u, v, n):
        _fail(name, "is not watertight as a slicer reads it (float32): " + _edge_problems(u, v, n), merged)
    vol = float(np.einsum("ij,ij->i", p0, cross).sum() / 6.0)
    if not vol > 0:
        _fail(name, f"has a volume of {vol:g} mm^3 (it must be positive: faces point inward)", merged)
    if volume is not None and abs(vol - volume) > VOLUME_TOLERANCE * abs(volume):
        _fail(
            name, f"has a volume of {vol:.6g} mm^3, not the {volume:.6g} mm^3 of area x height (0.5 % allowed)", merged
        )
    if bodies is not None:
        found = count_bodies(n, faces[:, [0, 1, 1, 2]].reshape(-1, 2))  # two edges join a face's corners
        if found != bodies:
            _fail(
                name, f"has {found} separate bodies where {bodies} {'was' if bodies == 1 else 'were'} expected", merged
            )
    return verts, faces, vol


def cross_rows(a, b):
    """Row-wise cross products of (m, 3) arrays, as ``np.cross`` computes them (a third of its time)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), dtype=np.result_type(a, b))
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out
