"""An inlay kit's pieces nested: packed tight on their sheet, each with its letter scored.

A kit's pieces sit in registration by default (``inlay_pieces = "registration"``): the
pieces' sheet is as big as the whole tile although they cover a fraction of it.
``inlay_pieces = "nested"`` packs them with :func:`fabtiles.geometry.nest.nest` onto a
sheet of the tile's size (the bed's, if they do not fit one), half turns allowed so the
wood's grain keeps its direction, 1 mm between cut paths. The assembler then needs to
know which piece goes where: each piece gets its face class's letter scored on it (its
shape's class: congruent pieces are interchangeable) and each lattice hole the same
letter, scored inside the hole before it is cut, so the slugs still in the lattice show
where each letter goes. A coloured kit nests each colour's pieces on that colour's sheet.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import shapely

from ..core.errors import FabricationError
from .contours import laser_contours
from .cut_plan import CutPlan, KitPlans, make_plan
from .nest import nest
from .stroke_font import text_paths

GAP_MM = 0.5
"""Between two nested pieces' cut paths (the kerf included in the paths): what registration leaves between
them on the sample (a 1 mm stroke less twice the 0.15 mm fit and the 0.15 mm kerf: 0.55 mm)."""

TIME_S = 2.0
"""The nesting's time budget per sheet: a kit's pieces are small and alike."""

LETTER_MM = (1.5, 4.0)
"""The letters' smallest and largest height; a piece or hole too small for the smallest gets none."""

ROTATIONS = "180"
"""Half turns only: a piece keeps its wood's grain direction."""


def _label_points(polys):
    """Each polygon's pole of inaccessibility and the diameter of the circle there (``polylabel``)."""
    from shapely.ops import polylabel

    points, sizes = [], []
    for p in polys:
        q = polylabel(p, tolerance=0.05)
        points.append((q.x, q.y))
        sizes.append(2 * float(shapely.distance(q, p.exterior)))
    return np.array(points).reshape(-1, 2), np.array(sizes)


def _letter_paths(letters, polys) -> tuple[list, int]:
    """Score paths of ``letters`` centred in ``polys`` (one each); how many were too small for one."""
    out: list = []
    skipped = 0
    if not len(polys):
        return out, skipped
    points, sizes = _label_points(polys)
    for letter, (x, y), size in zip(letters, points, sizes, strict=True):
        height = min(LETTER_MM[1], 0.6 * size)
        if not letter or height < LETTER_MM[0]:
            skipped += 1
            continue
        out.extend(text_paths(letter, height_mm=height, x=x, y=y - height / 2, centre=True))
    return out, skipped


def class_letters(holes, faces, labels, letters) -> list[str]:
    """The face class letter of each hole: the class of the face holding the hole's inner point."""
    if not len(holes) or not len(faces):
        return [""] * len(holes)
    probe = shapely.point_on_surface(np.asarray(holes, dtype=object))
    near = shapely.STRtree(np.asarray(faces, dtype=object)).query_nearest(probe, return_distance=False)
    out = [""] * len(holes)
    for i, j in zip(*near, strict=True):
        out[int(i)] = letters[int(labels[int(j)])]
    return out


def nest_kit(plans: KitPlans, *, letters_of_holes, time_s: float = TIME_S, tabs=(None, None)) -> KitPlans:
    """``plans`` with the pieces nested and the letters scored (see the module text).

    ``letters_of_holes`` gives each of the kit's holes (``plans.kit.holes``, the order
    of its pieces) its class letter; ``tabs`` is ``(tab_mm, tabs_per_part)`` as the kit
    was planned with (the nested pieces keep their holding tabs). Returns new
    :class:`KitPlans`; the report says how the pieces were packed.
    """
    from .tabs import check_tabs

    kit, lattice = plans.kit, plans.lattice
    profile = lattice.profile
    kx, ky = profile.kerf_xy_mm
    if lattice.kerf_mm != kx:  # the call's own kerf, the same both ways
        kx = ky = lattice.kerf_mm
    tabs = check_tabs(*tabs, kerf_mm=max(kx, ky))
    pieces = np.asarray(kit.pieces, dtype=object)
    letters = list(letters_of_holes)
    groups = plans.by_colour or (("", plans.pieces),)
    nested, notes, stats = [], [], dict(lattice.report.stats.get("nested_pieces", {}))
    for name, plan in groups:
        mine = _pieces_of(plan, pieces)
        if not len(mine):
            continue
        new, note, entry = _nested_plan(name, mine, pieces, letters, lattice, (kx, ky), tabs, time_s)
        nested.append((name, new))
        notes.append(note)
        stats[name or "pieces"] = entry
    report = lattice.report
    if nested:  # the notes first, then the figures: the order the summary has always had
        report = report.extended(notes=notes).extended(nested_pieces=stats)
    new_lattice = _lettered_lattice(lattice, letters, kit, report)
    if plans.by_colour:
        return replace(plans, lattice=new_lattice, by_colour=tuple(nested))
    return replace(plans, lattice=new_lattice, pieces=nested[0][1] if nested else plans.pieces)


def _nested_plan(
    name: str, mine, pieces, letters: list, lattice, kerf_xy: tuple, tabs: tuple[float, int], time_s
) -> tuple[CutPlan, str, dict]:
    """The cut plan of one colour's pieces (``mine``, indices into ``pieces``) nested on a strip of the
    tile's height, each scored with its hole's letter; with the note and figures the lattice's report
    tells of it."""
    from .cut_plan import split_at_tabs

    profile = lattice.profile
    kx, ky = kerf_xy
    d = max(kx, ky) / 2
    x0, y0, x1, y1 = lattice.bounds
    tile = (x1 - x0, y1 - y0)
    parts = [(int(i), shapely.buffer(pieces[i], d)) for i in mine]  # the cut paths' outlines
    # a strip of the tile's height, as long as it must be (the packer makes it as short as it can):
    # one sheet whose used width is what the pieces take
    sheet = (max(float(profile.bed_mm[0]), 4 * tile[0]), tile[1])
    result = nest(parts, sheet_mm=sheet, gap_mm=GAP_MM, rotations=ROTATIONS, time_s=time_s)
    if result.sheets > 1:
        raise FabricationError(
            f"the kit's {len(mine):,} pieces{f' in {name}' if name else ''} do not fit on "
            f"one {sheet[0]:g} x {sheet[1]:g} mm bed when nested {GAP_MM:g} mm apart; "
            f'set inlay_pieces = "registration"',
            param="inlay_pieces",
        )
    placed = np.array([p.place(pieces[p.id]) for p in sorted(result.placements, key=lambda p: p.id)], dtype=object)
    ids = sorted(p.id for p in result.placements)
    paths = {}
    paths["inner"], paths["outer"] = laser_contours(
        shapely.multipolygons(list(shapely.get_parts(placed))),
        kerf_mm=kx,
        kerf_y_mm=ky,
        tolerance_mm=profile.tolerance_mm,
    )
    score, small = _letter_paths([letters[i] for i in ids], placed)
    if score:
        paths["score"] = score
    closed = split_at_tabs(paths, *tabs, None)
    box = shapely.union_all(placed).bounds
    sheet = (box[2] + d, sheet[1])  # the sheet the pieces take: up to the last one's cut
    new = make_plan(
        profile,
        "pierced",
        kx,
        paths,
        bounds=(0.0, 0.0, *sheet),
        part=shapely.union_all(placed),
        outer_closed=closed,
    )
    return (new, *_note_nested(name, ids, small, box, sheet, tile, d))


def _note_nested(name: str, ids: list, small: int, box: tuple, sheet: tuple, tile: tuple, d: float) -> tuple[str, dict]:
    """What the report tells of one colour's nested pieces: how many, their sheet, the room they take,
    the letters (a note), and the figures."""
    width, height = box[2] - box[0] + 2 * d, box[3] - box[1] + 2 * d
    note = (
        f"pieces{f' in {name}' if name else ''} nested: {len(ids):,} on a {sheet[0]:.0f} x "
        f"{sheet[1]:.0f} mm sheet, within {width:.1f} x {height:.1f} mm "
        f"({width * height / (tile[0] * tile[1]):.0%} of the tile's area), {GAP_MM:g} mm apart, "
        f"half turns only (the grain); "
        + (f"{len(ids) - small:,} letters scored" + (f", {small:,} pieces too small for one" if small else ""))
    )
    return note, {
        "pieces": len(ids),
        "sheet_mm": [round(sheet[0], 3), round(sheet[1], 3)],
        "bbox_mm": [round(width, 3), round(height, 3)],
        "bbox_of_tile": round(width * height / (tile[0] * tile[1]), 4),
    }


def _lettered_lattice(lattice, letters: list, kit, report) -> CutPlan:
    """The lattice's plan again with each hole's letter scored inside it, laid as before, with ``report``."""
    # the lattice: each hole's letter scored inside it (on the slug, cut after the scoring)
    hole_score, _ = _letter_paths(letters, np.asarray(kit.holes, dtype=object))
    # the lattice's paths back in the tile's coordinates (the holes' letters are), then moved as before
    back = np.asarray(lattice.offset, dtype=float)
    lattice_paths = {layer.role: [p - back for p in layer.paths] for layer in lattice.layers}
    lattice_paths["score"] = lattice_paths.get("score", []) + hole_score
    groups_of = next((layer.groups for layer in lattice.layers if layer.fill), ())
    outer_closed = next((layer.closed for layer in lattice.layers if layer.role == "outer"), True)
    return make_plan(
        lattice.profile,
        lattice.mode,
        lattice.kerf_mm,
        lattice_paths,
        report=report,
        part=lattice.part,
        groups=groups_of,
        engrave_area_mm2=lattice.engrave_area_mm2,
        like=lattice,
        outer_closed=outer_closed,
    )


def _pieces_of(plan, pieces) -> np.ndarray:
    """The indices of the kit's ``pieces`` that ``plan`` cuts (its part holds their inner points)."""
    part = plan.part
    if isinstance(part, np.ndarray):  # the whole kit's pieces plan holds the pieces themselves
        part = shapely.union_all(part) if len(part) else None
    if part is None or part.is_empty or not len(pieces):
        return np.empty(0, int)
    inside = shapely.contains(part, shapely.point_on_surface(pieces))
    return np.flatnonzero(inside)
