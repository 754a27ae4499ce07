"""Binary STL (mm): one watertight body, written as the mesh check merged it.

The body is built and checked by :mod:`fabtiles.solid.parts` (a relief's plate and
pattern fused into one); this module writes its float32 triangles and reads them
back as a slicer does.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import FabricationError
from ..geometry.material import filament
from ..solid.mesh_check import cross_rows


def model_stl_bytes(model) -> bytes:
    """The binary STL of a :class:`~fabtiles.solid.print_model.PrintModel`: its fused, checked body."""
    fused = model.fused
    return stl_bytes(fused.vertices, fused.faces)


def figures(model) -> dict:
    """What an STL adds to its model's report: its body, triangles, volume, filament and bounds.

    A mosaic of several colours is one STL per colour: its figures are every part's.
    """
    split = model.bodies()
    if len(split) > 1:
        parts = {m.fused_name: m.fused for _, m in split}
        allv = np.concatenate([p.vertices for p in parts.values()])
        return dict(
            model.stats(),
            bodies=list(parts),
            triangles=int(sum(len(p.faces) for p in parts.values())),
            volume_mm3=float(sum(p.mesh_volume_mm3 for p in parts.values())),
            material=filament({n: p.mesh_volume_mm3 for n, p in parts.items()}, model.profile).as_stats(),
            bounds_mm=[allv.min(axis=0).tolist(), allv.max(axis=0).tolist()],
        )
    fused, name = model.fused, model.fused_name
    volume = fused.mesh_volume_mm3
    return dict(
        model.stats(),
        bodies=[name],
        triangles=len(fused.faces),
        volume_mm3=volume,
        material=filament({name: volume}, model.profile).as_stats(),
        bounds_mm=[fused.vertices.min(axis=0).tolist(), fused.vertices.max(axis=0).tolist()],
    )


def stl_bytes(vertices, faces) -> bytes:
    """Binary STL (float32, normals computed in float64 from the float32 corners) of a mesh.

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> len(stl_bytes(v, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    284
    """
    tris = np.asarray(vertices).astype(np.float32)[np.asarray(faces)]  # = vertices[faces] in float32
    # the float32 corners' normal in float64, as admesh and the slicers compute it: a needle of a curved
    # surface (a wrapped print's) has a float32 cross product that is mostly rounding
    t64 = tris.astype(np.float64)
    normals = cross_rows(t64[:, 1] - t64[:, 0], t64[:, 2] - t64[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = (normals / np.where(lengths > 0, lengths, 1)).astype(np.float32)
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"] = normals
    rec["v"] = tris
    header = b"fabtiles binary STL, units mm".ljust(80, b" ")
    return header + np.uint32(len(tris)).tobytes() + rec.tobytes()


def read_stl_triangles(data: bytes) -> np.ndarray:
    """The float32 triangles (m, 3, 3) of binary STL bytes, as a slicer reads them."""
    if len(data) < 84:
        raise FabricationError("not a binary STL: shorter than its header")
    n = int(np.frombuffer(data, "<u4", 1, 80)[0])
    if len(data) != 84 + 50 * n:
        raise FabricationError(f"not a binary STL: {len(data)} bytes for {n} triangles")
    rec = np.frombuffer(data, dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")], count=n, offset=84)
    return rec["v"].copy()
