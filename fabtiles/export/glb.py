"""The print as binary glTF (GLB), one mesh per part in its own colour: the web app's 3D view.

The parts are the 3MF's (:func:`~fabtiles.solid.parts.checked_parts`, after the
same printability checks), so what the view turns is what the slicer gets: a
relief's ``base`` and ``pattern``, a pierced ``pattern``, a deboss ``plate`` and
its ``inlay``, an interlaced relief's dips. GLB is indexed float32 vertices and
uint32 triangles: 530 KB for the 150 mm default tile's 30,544 triangles, against
1.5 MB as binary STL, and three.js reads it with its own loader. trimesh writes
it (a dependency already); no normals are stored, the view shades the faces flat.
"""

from __future__ import annotations

import numpy as np

from ..solid.parts import check_inlay, checked_parts, prepare_print, stack_stats

PART_COLOURS = {
    "base": (0.90, 0.84, 0.72),  # a light first filament
    "pattern": (0.02, 0.07, 0.30),  # a dark second filament: the preview's ink #1f3b73, as linear RGB
    "plate": (0.90, 0.84, 0.72),
    "inlay": (0.85, 0.62, 0.12),
}
"""Each part's colour in the view (linear RGB)."""


def glb_bytes(parts: dict) -> bytes:
    """A GLB of named ``(vertices, faces)`` parts, each a node and mesh of that name in its colour.

    >>> import numpy as np
    >>> tri = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]]), np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> data = glb_bytes({"base": tri})
    >>> data[:4], int.from_bytes(data[8:12], "little") == len(data)
    (b'glTF', True)
    """
    import trimesh

    scene = trimesh.Scene()
    for name, (vertices, faces) in parts.items():
        colour = PART_COLOURS.get(name, (0.6, 0.6, 0.6))
        material = trimesh.visual.material.PBRMaterial(
            name=name, baseColorFactor=[*colour, 1.0], metallicFactor=0.0, roughnessFactor=0.8)
        mesh = trimesh.Trimesh(np.asarray(vertices, dtype=np.float32), faces, process=False, validate=False,
                               visual=trimesh.visual.TextureVisuals(material=material))
        scene.add_geometry(mesh, node_name=name, geom_name=name)
    return scene.export(file_type="glb", include_normals=False)


def print_glb(*, region, outline, profile, style=None, stroke=None, base_mm=None, relief_mm=None, pierced_mm=None,
              deboss_mm=None, fill_small_holes=False, inlay=False, dips=None):
    """The print's checked parts as GLB bytes and their report (as :func:`~fabtiles.export.threemf.write_3mf`).

    Returns
    -------
    (bytes, Report)
        The report's ``parts`` give each part's triangles, mesh volume (mm³) and colour.
    """
    heights = dict(base_mm=base_mm, relief_mm=relief_mm, pierced_mm=pierced_mm, deboss_mm=deboss_mm)
    _, stack, report, region = prepare_print(region, outline, profile, style, heights, stroke, fmt="glb",
                                              fill_small_holes=fill_small_holes, flatten=dips is None)
    check_inlay(stack, inlay)
    checked = checked_parts(region, outline, stack, inlay=bool(inlay), dips=dips)
    data = glb_bytes({n: (p.vertices, p.faces) for n, p in checked.items()})
    report.stats.update(
        stack_stats(stack),
        parts={n: {"triangles": len(p.faces), "volume_mm3": p.mesh_volume_mm3,
                   "colour": PART_COLOURS.get(n)} for n, p in checked.items()},
        triangles=int(sum(len(p.faces) for p in checked.values())),
        volume_mm3=float(sum(p.mesh_volume_mm3 for p in checked.values())),
        bytes=len(data),
    )
    return data, report
