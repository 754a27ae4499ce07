"""The public :func:`nest`: tiles of one or more designs nested onto sheets, from a script.

The ``fabtiles nest`` command's work (:func:`fabtiles.making.nesting.nest_designs`) for
designs given as files or as loaded designs; see ``docs/nesting.md``.
"""

from __future__ import annotations

from pathlib import Path


def nest(
    designs,
    outdir,
    *,
    formats=("dxf",),
    count: int | None = None,
    sheet_mm=None,
    gap_mm=None,
    rotations: str = "90",
    time_s: float | None = None,
    name: str | None = None,
):
    """Nest tiles of ``designs`` onto sheets and write ``OUTDIR/<name>-sheet-<k>.<format>``, each format on its own.

    Parameters
    ----------
    designs : design, or list of designs or of (design, copies)
        A design is a design file's path or a loaded design (:func:`fabtiles.load_design`);
        ``copies`` (>= 1) overrides ``count`` for that design.
    outdir : str or Path
    formats, count, sheet_mm, gap_mm, rotations, time_s, name
        As the command's options (``docs/nesting.md``): the cutter formats, copies of each
        design (default 1), the sheet (default the cutter profile's bed), the least
        distance between cut paths (default the kerf + 1 mm), ``"90"``, ``"180"``,
        ``"free"`` or ``"none"``, the time budget (default 5 s), the files' stem.

    Returns
    -------
    NestResult
        The build's reports (sheets used, each sheet's parts and material use) and the placements.
    """
    from .designs.design_file import Design, load_design
    from .making.nesting import nest_designs

    def one(d):
        return d if isinstance(d, Design) else load_design(Path(d))

    if isinstance(designs, (str, Path, Design)):
        designs = [designs]
    pairs = [(one(d[0]), d[1]) if isinstance(d, tuple) else (one(d), None) for d in designs]
    return nest_designs(
        pairs,
        outdir,
        formats,
        count=count,
        sheet_mm=sheet_mm,
        gap_mm=gap_mm,
        rotations=rotations,
        time_s=time_s,
        name=name,
    )
