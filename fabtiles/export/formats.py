"""The output formats: one table, the only place a format is named.

Each row says which model a format is written from (``"cut"``: a
:class:`~fabtiles.geometry.cut_plan.CutPlan`; ``"print"``: a
:class:`~fabtiles.solid.print_model.PrintModel`), its media type, and two pure
functions of that model: ``write(model, options) -> bytes`` and
``figures(model, options) -> dict`` (what the file adds to its model's report).
No writer touches the file system: the build pipeline (:mod:`fabtiles.making`)
stages and moves every file. A writer's module is imported when its format is
written, so a DXF never loads manifold3d and only STEP loads build123d/OCP.

A new format is one module with its ``*_bytes`` function and one row here
(``docs/architecture.md`` walks through the GLB row).

>>> [f.name for f in FORMATS.values() if f.family == "cut"]
['dxf', 'svg', 'lbrn2']
>>> format_of("tile.DXF").media_type
'image/vnd.dxf'
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ..core.errors import ParameterError


@dataclass(frozen=True)
class FileOptions:
    """What one file needs beyond its model: the name it carries inside, the 3MF's layout."""

    name: str = "tile"
    """The object's, product's or drawing's name in the file (a file's stem by default)."""
    layout: str = "volumes"
    """The 3MF layout (:data:`fabtiles.export.threemf.LAYOUTS`)."""


@dataclass(frozen=True)
class Format:
    """One output format: its suffix, the model it is written from, its media type and writer."""

    name: str
    family: str
    """``"cut"`` (written from a cut plan) or ``"print"`` (from a print model)."""
    media_type: str
    description: str
    write: Callable
    """``write(model, options: FileOptions) -> bytes``."""
    figures: Callable
    """``figures(model, options: FileOptions) -> dict``: statistics the file adds to its report."""

    @property
    def suffix(self) -> str:
        return f".{self.name}"

    def bytes_of(self, model, options: FileOptions = FileOptions()) -> bytes:
        """The file's bytes."""
        return self.write(model, options)


# Each writer is imported inside its function: the table itself costs nothing to import.
def _dxf(plan, options):
    from .dxf import dxf_bytes

    return dxf_bytes(plan)


def _dxf_figures(plan, options):
    from .dxf import figures

    return figures(plan)


def _svg(plan, options):
    from .laser_svg import svg_bytes

    return svg_bytes(plan)


def _lbrn2(plan, options):
    from .lbrn2 import lbrn2_bytes

    return lbrn2_bytes(plan)


def _none(model, options):
    return {}


def _stl(model, options):
    from .stl import model_stl_bytes

    return model_stl_bytes(model)


def _stl_figures(model, options):
    from .stl import figures

    return figures(model)


def _3mf(model, options):
    from .threemf import model_3mf_bytes

    return model_3mf_bytes(model, name=options.name, layout=options.layout)


def _3mf_figures(model, options):
    from .threemf import figures

    return figures(model, layout=options.layout)


def _step(model, options):
    from .step import step_bytes

    return step_bytes(model, name=options.name)


def _step_figures(model, options):
    from .step import figures

    return figures(model)


def _glb(model, options):
    from .glb import model_glb_bytes

    return model_glb_bytes(model)


def _glb_figures(model, options):
    from .glb import figures

    return figures(model)


FORMATS = {
    f.name: f
    for f in (
        Format("dxf", "cut", "image/vnd.dxf", "DXF for laser, router and waterjet software", _dxf, _dxf_figures),
        Format("svg", "cut", "image/svg+xml", "laser SVG, true millimetres, one group per layer", _svg, _none),
        Format("lbrn2", "cut", "application/xml", "LightBurn project with the profile's cut settings", _lbrn2, _none),
        Format("stl", "print", "model/stl", "binary STL, one watertight body", _stl, _stl_figures),
        Format("3mf", "print", "model/3mf", "3MF, one object of named parts, one filament each", _3mf, _3mf_figures),
        Format(
            "step", "print", "model/step", "STEP AP214, planes and cylinders, one solid per piece", _step, _step_figures
        ),
        Format(
            "glb",
            "print",
            "model/gltf-binary",
            "binary glTF of the print's parts in colour (the 3D view)",
            _glb,
            _glb_figures,
        ),
    )
}
"""Every output format by name (= file suffix without the dot)."""

FILE_FORMATS = ("dxf", "svg", "lbrn2", "stl", "3mf", "step")
"""The formats a design's ``[output] formats`` may name (GLB is the web app's 3D view)."""

CUT_FORMATS = tuple(n for n, f in FORMATS.items() if f.family == "cut")
"""The formats written from a cut plan (sheets and inlay kits are written in these)."""


def format_of(path, *, allowed=FILE_FORMATS) -> Format:
    """The output format named by a path's suffix.

    >>> format_of("tile.3mf").family
    'print'
    >>> format_of("tile.png")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: 'png' is not a valid output format (from the suffix of 'tile.png'), must be one of: dxf, svg, lbrn2, stl, 3mf, step
    """  # noqa: E501 - a doctest's lines are as Python prints them
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in allowed:
        raise ParameterError(
            f"{suffix!r} is not a valid output format (from the suffix of {str(path)!r}), "
            f"must be one of: {', '.join(allowed)}",
            param="path",
        )
    return FORMATS[suffix]
