"""A mesh file read back by an independent reader (trimesh): the deep check's reader of STL and 3MF.

A 3MF is split into its parts as PrusaSlicer splits it (its volumes' triangle ranges) and each
part checked by trimesh: trimesh's own loader joins the parts into one mesh, where a relief's
plate and pattern meet along the outline in edges of four faces (the file is right, the check
not). Every body must be watertight and wound outwards, the volumes summing to the report's.
"""

from __future__ import annotations

from ..core.errors import FabricationError

MESH_VOLUME_REL = 1e-5
"""The read-back mesh's volume against the report's: both are sums over the same float32
triangles (measured differences below 1e-7), so this only catches a lost or doubled body."""


def read_back_meshes(path, fmt: str, report) -> tuple[str, int, float]:
    """``("trimesh", bodies, volume mm^3)`` of the mesh file ``path`` of format ``fmt``, read back and checked.

    Raises :class:`~fabtiles.FabricationError` for a body that is not watertight or turned
    inside out, or a volume other than ``report.stats["volume_mm3"]``.
    """
    import numpy as np
    import trimesh

    if fmt == "3mf":
        from .threemf import read_3mf

        meshes: list[trimesh.Trimesh] = [
            trimesh.Trimesh(p.vertices.astype(np.float64), p.faces, process=False) for p in read_3mf(str(path)).values()
        ]
    else:
        scene = trimesh.load_scene(str(path), file_type=fmt, process=False)
        meshes = [g for g in scene.dump() if isinstance(g, trimesh.Trimesh)]
    volume = 0.0
    for mesh in meshes:
        mesh.merge_vertices()
        if not mesh.is_watertight or not mesh.is_winding_consistent:
            raise FabricationError(f"the {fmt.upper()} file read back by trimesh has a body that is not watertight")
        if mesh.volume <= 0:
            raise FabricationError(f"the {fmt.upper()} file read back by trimesh has a body turned inside out")
        volume += float(mesh.volume)
    expected = float(report.stats["volume_mm3"])
    if not np.isclose(volume, expected, rtol=MESH_VOLUME_REL):
        raise FabricationError(
            f"the {fmt.upper()} file read back by trimesh holds {volume:.6g} mm^3, not the "
            f"{expected:.6g} mm^3 it was written with"
        )
    return "trimesh", len(meshes), volume
