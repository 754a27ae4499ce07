"""The output formats: one table, the only place a format is named.

Each row (a :class:`Format`) says everything fabtiles knows of one format: its name
and suffix, its media type, the model it is written from (its ``family``: ``"cut"``,
a cut plan; ``"print"``, a print model; ``"pen"``, a plotter's drawing), its writer
``write(model, options) -> bytes`` and the figures it adds to its model's report,
the cutter kinds that take it, whether a nest's sheets or the calibration card are
written in it, the build options it takes, the several files it may write of one
model (one STL per colour of a mosaic) and the checks it brings (its own work limit,
the deep check's reader, a library it needs). The schema's choices, ``--format``,
``fabtiles nest``, ``fabtiles plot``, the calibration card, the deep check, the web
app's downloads (through ``/api/schema``) and the manual's table are read from it.

No writer touches the file system: the build pipeline (:mod:`fabtiles.making`)
stages and moves every file. A writer's module is imported when its format is
written, so a DXF never loads manifold3d and only STEP loads build123d/OCP.

Another package adds a format with an entry point in the group ``fabtiles.formats``
whose object is a :class:`Format` (``docs/architecture.md``); the table loads them
on first use, once. A plugin that fails to load, or that takes a built-in name, is
named in a warning and left out.

>>> [f.name for f in FORMATS.values() if f.family == "cut"]
['dxf', 'svg', 'lbrn2']
>>> format_of("tile.DXF").media_type
'image/vnd.dxf'
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterator, Mapping, MutableMapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from ..core.errors import ParameterError
from ..core.schema import FAMILIES, register_choices
from ..core.validate import check_choice
from ..machines.profiles import DXF_VERSIONS

if TYPE_CHECKING:
    from ..core.report import Report

FORMAT_FAMILIES = ("cut", "print", "pen")
"""The models a format is written from: a cut plan, a print model, a pen plotter's drawing."""

ENTRY_POINT_GROUP = "fabtiles.formats"
"""The entry-point group of format plugins: each entry point's object is a :class:`Format`."""


# --------------------------------------------------------------------------- the models' contracts


class CutPlanModel(Protocol):
    """What a cut writer reads of its model (:class:`~fabtiles.geometry.cut_plan.CutPlan`)."""

    profile: Any
    mode: str
    kerf_mm: float
    layers: tuple
    declared: tuple
    bounds: tuple
    report: Report


class CutModel(Protocol):
    """The model of the ``"cut"`` family: a cut plan, an inlay kit's plans
    (:class:`~fabtiles.geometry.cut_plan.KitPlans`) or a nest's sheets, each file's plan by :meth:`files`."""

    @property
    def report(self) -> Report: ...

    def files(self) -> Sequence[tuple[str, CutPlanModel]]:
        """``[(suffix added to the file's stem, the plan the file is written from), ...]``."""
        ...


class PrintBody(Protocol):
    """What a mesh writer reads of a print: its profile, stack, report and one body
    (:class:`~fabtiles.solid.print_model.PrintModel`, or one part of it,
    :class:`~fabtiles.solid.print_model.PartPrint`)."""

    profile: Any
    stack: Any
    report: Report

    @property
    def fused(self) -> Any: ...

    @property
    def fused_name(self) -> str: ...

    def stats(self) -> dict: ...


class PrintModelProtocol(PrintBody, Protocol):
    """The model of the ``"print"`` family (:class:`~fabtiles.solid.print_model.PrintModel`): its body,
    its named parts, and its bodies one by one (:meth:`bodies`: a mosaic's colours)."""

    @property
    def parts(self) -> dict: ...

    def files(self) -> Sequence[tuple[str, PrintBody]]: ...

    def bodies(self) -> Sequence[tuple[str, PrintBody]]: ...


class PenModel(Protocol):
    """The model of the ``"pen"`` family (:class:`~fabtiles.geometry.pen.PenDrawing`)."""

    layers: tuple
    bounds: tuple
    pen_mm: float


# --------------------------------------------------------------------------- the rows


def check_dxf_version(dxf_version: str | None) -> str | None:
    """``dxf_version`` checked against :data:`~fabtiles.machines.profiles.DXF_VERSIONS` (None: the profile's).

    >>> check_dxf_version("R12")
    'R12'
    >>> check_dxf_version("R14")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: 'R14' is not a valid dxf_version, must be one of: R12, R2000, R2004, R2007, R2010, R2013, R2018
    """  # noqa: E501 - a doctest's lines are as Python prints them
    if dxf_version is None:
        return None
    return check_choice("dxf_version", dxf_version, DXF_VERSIONS)


@dataclass(frozen=True)
class FileOptions:
    """What one file needs beyond its model: the name it carries inside, the 3MF's layout, the DXF's version.

    The format's details live here rather than in the model: one cut plan is written as
    any DXF version, an SVG or a LightBurn project alike.
    """

    name: str = "tile"
    """The object's, product's or drawing's name in the file (a file's stem by default)."""
    layout: str = "volumes"
    """The 3MF layout (:data:`fabtiles.export.threemf.LAYOUTS`)."""
    dxf_version: str | None = None
    """The DXF's version (:data:`~fabtiles.machines.profiles.DXF_VERSIONS`); None: the cutter profile's."""

    def __post_init__(self):
        check_dxf_version(self.dxf_version)


def no_figures(model, options) -> dict:
    """The figures of a format that adds none to its model's report."""
    return {}


def _model_files(model) -> Sequence[tuple[str, Any]]:
    return model.files()


@dataclass(frozen=True, slots=True, kw_only=True)
class Format:
    """One output format: one row of the table, everything said of the format.

    Only ``name``, ``family``, ``media_type``, ``description`` and ``write`` are needed; a
    plugin's row is made the same way (``docs/architecture.md``).

    >>> Format(name="txt", family="cut", media_type="text/plain", description="", write=None).suffix
    '.txt'
    >>> Format(name="txt", family="paper", media_type="text/plain", description="", write=None)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: format 'txt': family must be one of: cut, print, pen, got 'paper'
    """

    name: str
    """Its name: ``--format NAME``, ``[output] formats``, ``/api/export/NAME``."""
    family: str
    """The model it is written from (:data:`FORMAT_FAMILIES`): ``"cut"`` a :class:`CutPlanModel`,
    ``"print"`` a :class:`PrintBody`, ``"pen"`` a :class:`PenModel`."""
    media_type: str
    description: str
    write: Callable[[Any, FileOptions], bytes]
    """``write(model, options: FileOptions) -> bytes``: pure, no file written."""
    figures: Callable[[Any, Any], dict] = no_figures
    """``figures(model, options: FileOptions) -> dict``: what the file adds to its model's report."""
    suffix: str = ""
    """Its files' suffix (default ``"." + name``)."""
    label: str = ""
    """Its name for people: a download button's text (default the name in capitals)."""
    title: str = ""
    """Its file as messages name it (``"a LightBurn project"``; default ``"a <label> file"``)."""
    cutters: tuple[str, ...] | None = None
    """The cutter kinds that take it (a cut format); None: every kind."""
    nests: bool = False
    """Whether nested sheets (``fabtiles nest``, the web's nest page) are written in it."""
    card: bool = False
    """Whether the calibration card (``fabtiles calibrate``) is written in it."""
    options: str = ""
    """The schema's family of build options it takes (``"cut"``, ``"print"``, ``"3mf"``;
    default its family's; a pen format takes none)."""
    offered: bool = True
    """Whether a design's ``[output] formats``, ``--format`` and the web app's downloads offer it
    (the GLB is the web's 3D view; a pen format never: it is ``fabtiles plot``'s)."""
    files: Callable[[Any], Sequence[tuple[str, Any]]] = _model_files
    """``files(model) -> [(suffix added to the stem, model of that file), ...]``: the files it writes of
    one model (default the model's own: an inlay kit's lattice and pieces, a nest's sheets)."""
    limit: str | None = None
    """The :class:`~fabtiles.machines.limits.Limits` field of its own, lower segment limit (STEP)."""
    read_back: Callable[[Path, Report], tuple[str, int, float]] | None = None
    """``read_back(path, report) -> (reader, bodies, volume mm^3)``: the deep check's independent reader."""
    requires: Callable[[], object] | None = None
    """Raises when a library it needs is missing, before any geometry (HPGL: vpype)."""

    def __post_init__(self):
        if self.family not in FORMAT_FAMILIES:
            raise ParameterError(
                f"format {self.name!r}: family must be one of: {', '.join(FORMAT_FAMILIES)}, got {self.family!r}",
                param="family",
            )
        # the derived defaults: a frozen row is complete once made
        object.__setattr__(self, "suffix", self.suffix or f".{self.name}")
        object.__setattr__(self, "label", self.label or self.name.upper())
        object.__setattr__(self, "title", self.title or f"a {self.label} file")
        if self.family == "pen":  # a pen's drawing is fabtiles plot's, not a build's
            object.__setattr__(self, "offered", False)
        if not self.options and self.family in FAMILIES:
            object.__setattr__(self, "options", self.family)

    def bytes_of(self, model, options: FileOptions = FileOptions()) -> bytes:
        """The file's bytes."""
        return self.write(model, options)

    def check_cutter(self, profile) -> None:
        """A cutter profile whose kind does not take this format is a ParameterError.

        >>> from fabtiles.machines.profiles import load_profile
        >>> FORMATS["lbrn2"].check_cutter(load_profile("router-6mm-mdf"))
        Traceback (most recent call last):
        ...
        fabtiles.core.errors.ParameterError: a LightBurn project (.lbrn2) is for lasers; router profile 'router-6mm-mdf' writes .dxf or .svg for its CAM
        """  # noqa: E501 - a doctest's lines are as Python prints them
        if self.family != "cut" or self.cutters is None:
            return
        kind = profile.cutter.name
        if kind in self.cutters:
            return
        others = [f.suffix for f in FORMATS.values() if f.family == "cut" and f.offered and f.takes(kind)]
        raise ParameterError(
            f"{self.title} ({self.suffix}) is for {' and '.join(k + 's' for k in self.cutters)}; {kind} profile "
            f"{profile.name!r} writes {' or '.join(others)} for its CAM",
            param="formats",
        )

    def takes(self, kind: str) -> bool:
        """Whether a cutter of ``kind`` takes it."""
        return self.cutters is None or kind in self.cutters

    def row(self) -> dict:
        """What the web app reads of it (``/api/schema``'s ``formats``)."""
        return dict(
            name=self.name,
            family=self.family,
            suffix=self.suffix,
            label=self.label,
            media_type=self.media_type,
            description=self.description,
            cutters=list(self.cutters) if self.cutters is not None else None,
            nests=self.nests,
        )


# --------------------------------------------------------------------------- the built-in writers
# Each writer is imported inside its function: the table itself costs nothing to import.


def _dxf(plan, options):
    from .dxf import dxf_bytes

    return dxf_bytes(plan, dxf_version=options.dxf_version)


def _dxf_figures(plan, options):
    from .dxf import figures

    return figures(plan, dxf_version=options.dxf_version)


def _svg(plan, options):
    from .laser_svg import svg_bytes

    return svg_bytes(plan)


def _lbrn2(plan, options):
    from .lbrn2 import lbrn2_bytes

    return lbrn2_bytes(plan)


def _stl(model, options):
    from .stl import model_stl_bytes

    return model_stl_bytes(model)


def _stl_figures(model, options):
    from .stl import figures

    return figures(model)


def _stl_files(model) -> Sequence[tuple[str, Any]]:
    # an STL holds one body: a mosaic of several colours is one STL per colour
    return model.bodies()


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


def _step_read_back(path, report):
    from .step import check_step_file

    volume = check_step_file(path, volume=report.stats["volume_mm3"], parts=report.stats["solids"])
    return "OCCT", int(report.stats["solids"]), float(volume)


def _mesh_read_back(path, report):
    from .mesh_read import read_back_meshes

    return read_back_meshes(path, report.format, report)


def _glb(model, options):
    from .glb import model_glb_bytes

    return model_glb_bytes(model)


def _glb_figures(model, options):
    from .glb import figures

    return figures(model)


def _plot_svg(drawing, options):
    from .plot_svg import svg_bytes

    return svg_bytes(drawing)


def _hpgl(drawing, options):
    from .plot_svg import hpgl_bytes

    return hpgl_bytes(drawing)


def _need_vpype():
    from .plot_svg import need_vpype

    return need_vpype("HPGL")


BUILT_IN = (
    Format(
        name="dxf",
        family="cut",
        media_type="image/vnd.dxf",
        description="DXF for laser, router and waterjet software",
        write=_dxf,
        figures=_dxf_figures,
        nests=True,
        card=True,
    ),
    Format(
        name="svg",
        family="cut",
        media_type="image/svg+xml",
        description="laser SVG, true millimetres, one group per layer",
        write=_svg,
        nests=True,
        card=True,
    ),
    Format(
        name="lbrn2",
        family="cut",
        media_type="application/xml",
        description="LightBurn project with the profile's cut settings",
        write=_lbrn2,
        label="LightBurn",
        title="a LightBurn project",
        cutters=("laser",),
        nests=True,
    ),
    Format(
        name="stl",
        family="print",
        media_type="model/stl",
        description="binary STL, one watertight body",
        write=_stl,
        figures=_stl_figures,
        files=_stl_files,
        read_back=_mesh_read_back,
    ),
    Format(
        name="3mf",
        family="print",
        media_type="model/3mf",
        description="3MF, one object of named parts, one filament each",
        write=_3mf,
        figures=_3mf_figures,
        options="3mf",
        read_back=_mesh_read_back,
    ),
    Format(
        name="step",
        family="print",
        media_type="model/step",
        description="STEP AP214, planes and cylinders, one solid per piece",
        write=_step,
        figures=_step_figures,
        limit="max_step_segments",
        read_back=_step_read_back,
    ),
    Format(
        name="glb",
        family="print",
        media_type="model/gltf-binary",
        description="binary glTF of the print's parts in colour (the 3D view)",
        write=_glb,
        figures=_glb_figures,
        offered=False,
    ),
    Format(
        name="plot-svg",
        family="pen",
        media_type="image/svg+xml",
        description="a pen plotter's SVG: one layer per pen, merged strokes",
        write=_plot_svg,
        suffix=".svg",
        label="SVG",
    ),
    Format(
        name="hpgl",
        family="pen",
        media_type="application/vnd.hp-hpgl",
        description="HPGL for classic pen plotters, written by vpype",
        write=_hpgl,
        requires=_need_vpype,
    ),
)
"""The formats fabtiles writes itself, in the order the table lists them."""


# --------------------------------------------------------------------------- the table, plugins included


def _plugins(built_in: Mapping[str, Format]) -> dict[str, Format]:
    """The formats installed packages add (entry points of :data:`ENTRY_POINT_GROUP`), each checked.

    An entry point that fails to load, whose object is no :class:`Format`, or that takes a
    built-in or an earlier plugin's name is left out, named in one warning.
    """
    from importlib.metadata import entry_points

    out: dict[str, Format] = {}
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        try:
            row = ep.load()
        except Exception as exc:  # any error of another package's import: the build goes on without it
            warnings.warn(
                f"format plugin {ep.name!r} ({ep.value}) failed to load, left out: {type(exc).__name__}: {exc}",
                stacklevel=3,
            )
            continue
        if not isinstance(row, Format):
            warnings.warn(
                f"format plugin {ep.name!r} ({ep.value}) is not a fabtiles.Format, left out: {row!r}", stacklevel=3
            )
            continue
        if row.name in built_in or row.name in out:
            warnings.warn(
                f"format plugin {ep.name!r} ({ep.value}) names format {row.name!r}, which fabtiles "
                f"{'writes itself' if row.name in built_in else 'has from another plugin'}; left out",
                stacklevel=3,
            )
            continue
        out[row.name] = row
    return out


class FormatTable(MutableMapping[str, Format]):
    """Every output format by name: the built-in rows, then the plugins', loaded on first use, once.

    A row set or deleted changes this process's table only (a test's writer that fails).
    """

    def __init__(self, rows: Sequence[Format]):
        self._built_in = {f.name: f for f in rows}
        self._rows: dict[str, Format] | None = None

    def _all(self) -> dict[str, Format]:
        if self._rows is None:
            self._rows = {**self._built_in, **_plugins(self._built_in)}
            register_choices(design_formats(self._rows), "output.formats")
        return self._rows

    def reload(self) -> None:
        """Look for plugins again (after a package was installed in this process)."""
        self._rows = None
        register_choices(design_formats(self._built_in), "output.formats")

    def __getitem__(self, name: str) -> Format:
        return self._all()[name]

    def __setitem__(self, name: str, row: Format) -> None:
        self._all()[name] = row

    def __delitem__(self, name: str) -> None:
        del self._all()[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._all())

    def __len__(self) -> int:
        return len(self._all())


def design_formats(rows: Mapping[str, Format] | None = None) -> tuple[str, ...]:
    """The formats a design's ``[output] formats``, ``--format`` and the web's downloads offer.

    >>> design_formats()
    ('dxf', 'svg', 'lbrn2', 'stl', '3mf', 'step')
    """
    return tuple(n for n, f in (FORMATS if rows is None else rows).items() if f.offered)


def names_where(**wanted) -> tuple[str, ...]:
    """The offered formats whose fields have the values given.

    >>> names_where(nests=True), names_where(card=True), names_where(family="print")
    (('dxf', 'svg', 'lbrn2'), ('dxf', 'svg'), ('stl', '3mf', 'step'))
    """
    return tuple(n for n, f in FORMATS.items() if f.offered and all(getattr(f, k) == v for k, v in wanted.items()))


FORMATS: FormatTable = FormatTable(BUILT_IN)
"""Every output format by name, the plugins' included (loaded on first use)."""

CUT_FORMATS = tuple(f.name for f in BUILT_IN if f.family == "cut")
"""The built-in formats written from a cut plan (sheets and inlay kits are written in these)."""

FILE_FORMATS = tuple(f.name for f in BUILT_IN if f.offered)
"""The built-in formats a design may name (GLB is the web app's 3D view); with plugins: :func:`design_formats`."""

PEN_FORMATS = tuple(f.suffix for f in BUILT_IN if f.family == "pen")
"""The suffixes ``fabtiles plot`` writes."""

register_choices(FILE_FORMATS, "output.formats")  # the plugins' are added when they are loaded


def format_of(path, *, allowed=None, family: str | None = None) -> Format:
    """The output format named by a path's suffix, among ``allowed`` (default: :func:`design_formats`)
    or, with ``family``, among that family's formats.

    >>> format_of("tile.3mf").family
    'print'
    >>> format_of("drawing.SVG", family="pen").name
    'plot-svg'
    >>> format_of("tile.png")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: 'png' is not a valid output format (from the suffix of 'tile.png'), must be one of: dxf, svg, lbrn2, stl, 3mf, step
    """  # noqa: E501 - a doctest's lines are as Python prints them
    suffix = Path(path).suffix.lower()
    if family is not None:
        rows = [f for f in FORMATS.values() if f.family == family]
    else:
        names = design_formats() if allowed is None else tuple(allowed)
        rows = [FORMATS[n] for n in names]
    for f in rows:
        if f.suffix == suffix:
            return f
    raise ParameterError(
        f"{suffix.lstrip('.')!r} is not a valid output format (from the suffix of {str(path)!r}), "
        f"must be one of: {', '.join(f.name for f in rows)}",
        param="path",
    )


def markdown_table() -> str:
    """The table as ``docs/architecture.md`` shows it (``tests/export/test_formats.py`` compares)."""
    lines = [
        "| format | suffix | written from | media type | cutters | nests | card | what it is |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for f in BUILT_IN:
        cutters = ", ".join(f.cutters) if f.cutters else ("every kind" if f.family == "cut" else "")
        lines.append(
            f"| `{f.name}` | `{f.suffix}` | {f.family} | `{f.media_type}` | {cutters} | "
            f"{'yes' if f.nests else ''} | {'yes' if f.card else ''} | {f.description} |"
        )
    return "\n".join(lines) + "\n"
