"""``fabtiles check --deep``: the print files written, then read back by independent readers.

An export checks its models in memory (the STEP writer its B-rep,
:func:`~fabtiles.solid.brep.check_brep`; the mesh writers their checked meshes) and
does not read its own file back, which was most of an export's time. The deep check
does it on request: the design's print files are
written into a temporary folder through the same pipeline, then

- a STEP file is read back by OCCT (the kernel of FreeCAD and build123d), without
  healing, and its solids checked: valid, closed, as many as the report says, of the
  report's volume (:func:`fabtiles.export.step.check_step_file`);
- an STL is read back by trimesh, a 3MF split into its parts as PrusaSlicer splits it and
  each part checked by trimesh: every body watertight and wound outwards, the volumes
  summing to the report's.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..core.errors import FabricationError
from ..machines import limits as _limits

DEEP_FORMATS = ("stl", "3mf", "step")
"""The formats the deep check reads back, when a design names none of them."""

MESH_VOLUME_REL = 1e-5
"""The read-back mesh's volume against the report's: both are sums over the same float32
triangles (measured differences below 1e-7), so this only catches a lost or doubled body."""


@dataclass(frozen=True)
class ReadBack:
    """One file read back: its format, the reader, and what the reader found."""

    fmt: str
    reader: str
    bodies: int
    volume_mm3: float

    def line(self) -> str:
        """One line for people.

        >>> ReadBack("step", "OCCT", 1, 12345.678).line()
        'step read back by OCCT: 1 solid, 12,345.7 mm^3, as written'
        """
        one, many = ("solid", "solids") if self.fmt == "step" else ("mesh", "meshes")
        return (
            f"{self.fmt} read back by {self.reader}: {self.bodies} {one if self.bodies == 1 else many}, "
            f"{self.volume_mm3:,.1f} mm^3, as written"
        )


def _mesh_read_back(path, fmt: str, report) -> ReadBack:
    import numpy as np
    import trimesh

    if fmt == "3mf":
        # one object of parts: split it as PrusaSlicer does (its volumes' triangle ranges), then check each
        # part with trimesh; trimesh's own loader joins the parts into one mesh, where a relief's plate
        # and pattern meet along the outline in edges of four faces (the file is right, the check not)
        from ..export.threemf import read_3mf

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
    return ReadBack(fmt, "trimesh", len(meshes), volume)


def read_back(design, *, limits: _limits.Limits = _limits.CLI_LIMITS) -> list[ReadBack]:
    """Write ``design``'s print files (default :data:`DEEP_FORMATS`) and read each back independently.

    Raises :class:`~fabtiles.FabricationError` when a reader refuses a file or finds
    other solids or another volume than the build reported: the file passed the
    writer's own checks, so that is a bug of fabtiles, and the message says so.
    """
    from ..export.formats import FORMATS
    from ..export.step import check_step_file
    from .pipeline import build_design, refusal_error

    formats = [f for f in design.output.formats if FORMATS[f].family == "print"] or list(DEEP_FORMATS)
    out = []
    with tempfile.TemporaryDirectory(prefix="fabtiles-deep-") as tmp:
        result = build_design(design, tmp, formats, limits=limits)
        if result.refused:  # a file the writer refused is not read back: the check fails as its build does
            raise refusal_error(result.refused)
        for report in result.reports:
            path = Path(tmp) / Path(report.path).name
            try:
                if report.format == "step":
                    volume = check_step_file(path, volume=report.stats["volume_mm3"], parts=report.stats["solids"])
                    out.append(ReadBack("step", "OCCT", int(report.stats["solids"]), float(volume)))
                else:
                    out.append(_mesh_read_back(path, report.format, report))
            except FabricationError as exc:
                raise FabricationError(
                    f"the deep check found a file the writer's checks passed: {exc} "
                    "(a bug in fabtiles, please report it with the design)"
                ) from None
    return out
