"""A prepared laser job as the bytes of a file format: one function for the writers that build jobs themselves.

The calibration card and the inlay kit's pieces make their
:class:`~fabtiles.geometry.laser_checks.LaserJob` without the tile pipeline; this turns
one into a DXF (ezdxf's frame, our entities), a laser SVG or a LightBurn project.
"""

from __future__ import annotations

from ..geometry.laser_checks import LaserJob

LASER_FILE_FORMATS = ("dxf", "svg", "lbrn2")


def laser_bytes(job: LaserJob, fmt: str) -> bytes:
    """The file of ``job`` in ``fmt`` (one of :data:`LASER_FILE_FORMATS`), as bytes to write."""
    if fmt == "dxf":
        from .dxf import dxf_text

        text, encoding = dxf_text(job)
        return text.encode(encoding, errors="dxfreplace")
    if fmt == "svg":
        from .laser_svg import svg_text

        return svg_text(job).encode("utf-8")
    if fmt == "lbrn2":
        from .lbrn2 import lbrn2_text

        return lbrn2_text(job).encode("utf-8")
    raise ValueError(f"not a laser file format: {fmt!r}")  # pragma: no cover - callers check the suffix
