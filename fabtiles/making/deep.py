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
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..core.errors import FabricationError
from ..machines import limits as _limits


def _readers() -> dict[str, Callable[[Path, Any], tuple[str, int, float]]]:
    """The format table's deep-check readers, by format."""
    from ..export.formats import FORMATS

    out = {}
    for name, f in FORMATS.items():
        if f.offered and f.read_back is not None:
            out[name] = f.read_back
    return out


def deep_formats() -> tuple[str, ...]:
    """The formats the deep check reads back (the table's rows with a reader), when a design names none of them.

    >>> deep_formats()
    ('stl', '3mf', 'step')
    """
    return tuple(_readers())


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


def read_back(design, *, limits: _limits.Limits = _limits.CLI_LIMITS) -> list[ReadBack]:
    """Write ``design``'s print files (default :func:`deep_formats`) and read each back independently.

    Raises :class:`~fabtiles.FabricationError` when a reader refuses a file or finds
    other solids or another volume than the build reported: the file passed the
    writer's own checks, so that is a bug of fabtiles, and the message says so.
    """
    from .pipeline import build_design, refusal_error

    readers = _readers()
    formats = [f for f in design.output.formats if f in readers] or list(readers)
    out = []
    with tempfile.TemporaryDirectory(prefix="fabtiles-deep-") as tmp:
        result = build_design(design, tmp, formats, limits=limits)
        if result.refused:  # a file the writer refused is not read back: the check fails as its build does
            raise refusal_error(result.refused)
        for report in result.reports:
            path = Path(tmp) / Path(report.path).name
            try:
                reader, bodies, volume = readers[report.format](path, report)
                out.append(ReadBack(report.format, reader, bodies, volume))
            except FabricationError as exc:
                raise FabricationError(
                    f"the deep check found a file the writer's checks passed: {exc} "
                    "(a bug in fabtiles, please report it with the design)"
                ) from None
    return out
