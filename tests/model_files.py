"""Files of a bare region, written as the build pipeline writes them: a model, then the format table's writer.

The export tests hold a region and an outline of their own (a plate with a hole, a
strip, a tile's region) and want its file with the model functions' own defaults
(``fill_small_holes=False``, no profile default). Each helper makes the model with
the pipeline's model function (:func:`~fabtiles.geometry.cut_plan.plan_cut`,
:func:`~fabtiles.geometry.cut_plan.plan_kit`,
:func:`~fabtiles.solid.print_model.print_model`), writes
``FORMATS[name].write(model, options)`` to ``path`` and returns the model's report
with what the format adds (``FORMATS[name].figures``), as the pipeline's file report
holds them. Each file is written atomically, as the old file or the new: nothing is written
when the model or the writer raises.
"""

from __future__ import annotations

from pathlib import Path

from fabtiles.core.files import atomic_write
from fabtiles.core.report import Report
from fabtiles.export.formats import CUT_FORMATS, FileOptions, format_of


def write_cut(path, *, region, outline, centrelines=None, dxf_version=None, **options) -> Report:
    """The cutter file (``.dxf``, ``.svg``, ``.lbrn2``) of ``region``: :func:`plan_cut` with ``options``,
    written with ``dxf_version`` (the file's option; default the profile's)."""
    from fabtiles.geometry.cut_plan import CutOptions, plan_cut

    fmt = format_of(path, allowed=CUT_FORMATS)
    checked = CutOptions.of(path=str(path), fmt=fmt.name, **options)
    file_options = FileOptions(name=Path(path).stem, dxf_version=dxf_version)
    fmt.check_cutter(checked.profile)  # the row refuses a cutter its files are not for, as the pipeline asks
    plan = plan_cut(region, outline, checked, centrelines=centrelines)
    atomic_write(path, fmt.write(plan, file_options))
    plan.report.stats.update(fmt.figures(plan, file_options))
    return plan.report


def write_print(path, *, region, outline, name=None, layout="volumes", **options) -> Report:
    """The print file (``.stl``, ``.3mf``, ``.step``) of ``region``: :func:`print_model` with ``options``.

    ``name``: the object's name in the file (default: the file's stem); ``layout``: the 3MF's.
    """
    from fabtiles.export.threemf import check_layout
    from fabtiles.solid.print_model import print_model

    fmt = format_of(path, allowed=("stl", "3mf", "step"))
    check_layout(layout)
    model = print_model(region, outline, path=str(path), fmt=fmt.name, **options)
    file_options = FileOptions(name=name or Path(path).stem or "tile", layout=layout)
    atomic_write(path, fmt.write(model, file_options))
    model.report.stats.update(fmt.figures(model, file_options))
    return model.report


def write_kit(path, *, region, outline, colours=(), dxf_version=None, **options) -> Report:
    """The inlay kit of ``region`` (:func:`plan_kit` with ``options``): ``<stem>-lattice`` and ``<stem>-pieces``
    beside ``path``, in its suffix's format, both made before either is written.

    The report is the kit's, with the lattice file's figures and both paths in ``files``.
    """
    from fabtiles.geometry.cut_plan import KitOptions, plan_kit

    path = Path(path)
    fmt = format_of(path, allowed=CUT_FORMATS)
    lattice = path.with_name(f"{path.stem}-lattice{path.suffix}")
    checked = KitOptions.of(path=str(lattice), fmt=fmt.name, **options)
    file_options = FileOptions(name=path.stem, dxf_version=dxf_version)
    fmt.check_cutter(checked.lattice.profile)
    plans = plan_kit(region, outline, checked, colours=colours)
    files = [
        (path.with_name(f"{path.stem}{suffix}{path.suffix}"), fmt.write(plan, file_options))
        for suffix, plan in plans.files()
    ]
    for p, data in files:
        atomic_write(p, data)
    plans.report.stats.update(fmt.figures(plans.lattice, file_options), files=[str(p) for p, _ in files])
    return plans.report
