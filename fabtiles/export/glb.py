"""The print as binary glTF (GLB), one mesh per part in its own colour: the web app's 3D view.

The parts are the 3MF's (the same :class:`~fabtiles.solid.print_model.PrintModel`,
after the same printability checks), so what the view turns is what the slicer gets: a
relief's ``base`` and ``pattern``, a pierced ``pattern``, a deboss ``plate`` and
its ``inlay``, an interlaced relief's dips. GLB is indexed float32 vertices and
uint32 triangles, about a third of a binary STL of the same triangles, and three.js
reads it with its own loader. trimesh writes
it (a dependency already); no normals are stored, the view shades the faces flat.
"""

from __future__ import annotations

import numpy as np


def glb_bytes(parts: dict) -> bytes:
    """A GLB of named ``(vertices, faces, colour)`` parts, each a node and mesh of that name in its colour.

    >>> import numpy as np
    >>> tri = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]]), np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> data = glb_bytes({"base": (*tri, (0.9, 0.84, 0.72))})
    >>> data[:4], int.from_bytes(data[8:12], "little") == len(data)
    (b'glTF', True)
    """  # noqa: E501 - a doctest's lines are as Python prints them
    import trimesh

    scene = trimesh.Scene()
    for name, (vertices, faces, colour) in parts.items():
        material = trimesh.visual.material.PBRMaterial(
            name=name, baseColorFactor=[*colour, 1.0], metallicFactor=0.0, roughnessFactor=0.8
        )
        mesh = trimesh.Trimesh(
            np.asarray(vertices, dtype=np.float32),
            faces,
            process=False,
            validate=False,
            visual=trimesh.visual.TextureVisuals(material=material),
        )
        scene.add_geometry(mesh, node_name=name, geom_name=name)
    return scene.export(file_type="glb", include_normals=False)


def model_glb_bytes(model) -> bytes:
    """The GLB of a :class:`~fabtiles.solid.print_model.PrintModel`: each part in its material's colour."""
    return glb_bytes({n: (p.mesh.vertices, p.mesh.faces, p.colour) for n, p in model.parts.items()})


def figures(model, data: bytes | None = None) -> dict:
    """What the 3D view reports: each part's triangles, mesh volume and colour, the totals."""
    parts = model.parts
    out = dict(
        model.stats(),
        parts={
            n: {"triangles": len(p.mesh.faces), "volume_mm3": p.mesh.mesh_volume_mm3, "colour": p.colour}
            for n, p in parts.items()
        },
        triangles=int(sum(len(p.mesh.faces) for p in parts.values())),
        volume_mm3=float(sum(p.mesh.mesh_volume_mm3 for p in parts.values())),
    )
    if data is not None:
        out["bytes"] = len(data)
    return out
