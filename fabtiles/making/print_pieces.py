"""A print larger than the printer's bed, made as pieces that lock together.

:func:`print_pieces` splits a print's footprint with :func:`~fabtiles.geometry.pieces.split_panel`
and makes each piece a :class:`~fabtiles.solid.print_model.PrintModel` of its own, laid on the
bed (:func:`~fabtiles.geometry.pieces.laid_on_bed`), so every print writer (STL, 3MF, STEP)
writes it as it writes a tile.

- **What is split.** A relief, a deboss or a mosaic stands on a plate of the whole outline,
  solid everywhere: the seams may run anywhere, and they run on the pattern's period when
  the bed allows it (the pieces in the same place of the grid are then congruent). A pierced
  print is its lattice alone: it is split as a cutter's panel is, its joints where the
  bands are wide enough.
- **The joint.** The in-plane dovetail (or jigsaw knob) of the cutters' pieces, cut straight
  down through the whole print, plate and pattern alike. Every wall is vertical, so the
  pieces print flat, on their bottoms, without support in any slicer; they go together from
  above and, laid flat, cannot be pulled apart in the plane. Pins and holes need a hole
  drilled into a 2 mm plate's edge and a pin printed standing (or a support under a
  horizontal hole): the dovetail needs neither. The neck is :data:`NECK_NOZZLES` nozzle widths
  (a few perimeters each side of the infill, not a strand that snaps).
- **The clearance.** The printer profile's ``joint_clearance_mm`` (default half the nozzle:
  0.2 mm on a 0.4 mm nozzle) is the gap between two pieces everywhere they meet, the
  straight seam and round the tab alike: each piece gives half of it. A print's outer walls
  come out a little wide (the squashed first layer most), so parts that slide together
  need room: the slicers' cut tools leave their connectors 0.1 mm (PrusaSlicer's and
  Bambu Studio's default tolerance) for a plug pressed into its hole, and a sliding fit
  takes about twice that.
- **The number.** Each piece's number is sunk :data:`NUMBER_LAYERS` layers into its bottom
  face (:func:`number_recess`), mirrored so that it reads from below, where the plate is
  solid: the layer over it bridges a groove :data:`NUMBER_LINE_NOZZLES` nozzles wide, no
  support needed, and the mesh stays one closed body.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..core.errors import ParameterError
from ..core.report import Report
from ..core.validate import check_float
from .pieces import piece_suffix

if TYPE_CHECKING:
    from ..geometry.pieces import PanelSplit, Piece
    from ..solid.print_model import PrintModel

NECK_NOZZLES = 10
"""A printed joint's neck in nozzle widths (4 mm at 0.4 mm): several perimeters each side."""

MAX_CLEARANCE_MM = 0.5
"""The largest gap between printed pieces: wider, the panel rattles and its seams gape."""

NUMBER_LAYERS = 2
"""How many layers deep a piece's number is sunk into its bottom."""

NUMBER_LINE_NOZZLES = 3
"""A number's strokes, in nozzle widths: wider than the narrowest hole the slicer keeps open."""

NUMBER_HEIGHT_MM = (12.0, 5.0)
"""The height of a piece's number: the first that fits, else smaller down to the second."""

STRAIGHT_OUTLINE_POINTS = 16
"""An outline of at most this many points is straight sides (a rectangle, a hexagon); more: it has curves."""

HAIR_MM = 1e-3
"""Narrower than this on average, a bit :func:`without_slivers` finds is the opening's own hair along a
curved edge, not a sliver the seam cut."""

JOINT_INSET_MM = 0.02
"""How far inside a piece's seams its part of an interlaced relief's dips keeps (they must lie
strictly inside the material)."""


@dataclass(frozen=True)
class PrintedPiece:
    """One printed piece: the piece of the split (number, place in the grid, nominal region in
    panel mm), the 3 x 3 matrix (mm) that carries its file to its place in the panel, its print."""

    piece: Piece
    matrix: np.ndarray
    model: PrintModel

    @property
    def number(self) -> int:
        """The piece's number (1 at the top left, along the rows)."""
        return self.piece.number

    @property
    def cell(self) -> tuple[int, int]:
        """The piece's place in the grid (column, row from the bottom)."""
        return self.piece.cell

    @property
    def region(self):
        """The piece's nominal region in the panel (mm), before the clearance."""
        return self.piece.region

    @property
    def size_mm(self) -> tuple[float, float]:
        """The piece's extents in its file (mm)."""
        x0, y0, x1, y1 = self.model.outline.bounds
        return (x1 - x0, y1 - y0)


@dataclass(frozen=True)
class PrintPieces:
    """A print split into pieces (see the module text): the split, the pieces, the gap between them,
    the panel's outline; the assembly drawing and manifest read it as a cut panel's."""

    split: PanelSplit
    pieces: tuple
    clearance_mm: float
    bed_mm: tuple
    report: Report
    outline: object = None
    """The panel's outline (mm)."""

    def files(self) -> list:
        """``[("-piece-01", print), ...]``: one file of each format per piece."""
        return [(piece_suffix(p.number, len(self.pieces)), p.model) for p in self.pieces]

    @property
    def groups(self) -> tuple[tuple[int, ...], ...]:
        """The pieces' numbers grouped by shape (:func:`~fabtiles.geometry.pieces.congruent_groups`)."""
        from ..geometry.pieces import congruent_groups

        return tuple(tuple(g) for g in congruent_groups(self.split.pieces))

    @property
    def profile(self):
        """The printer profile (every piece's)."""
        return self.pieces[0].model.profile

    def bodies(self) -> list:
        """``[(suffix, print), ...]``: the pieces' bodies (a mosaic piece: one per colour), one STL each."""
        n = len(self.pieces)
        return [(f"{piece_suffix(p.number, n)}{s}", m) for p in self.pieces for s, m in p.model.bodies()]

    def line(self) -> str:
        """What the build says: ``400 x 400 mm panel in 4 pieces for the 256 x 256 mm bed``."""
        x0, y0, x1, y1 = self.split_bounds
        bed = " x ".join(f"{v:g}" for v in self.bed_mm)
        n = len(self.pieces)
        return f"{x1 - x0:g} x {y1 - y0:g} mm panel in {n} piece{'s' if n != 1 else ''} for the {bed} mm bed"

    def material(self) -> dict:
        """The filament of all the pieces (a report's ``material``), by piece, from their meshes (made if not yet)."""
        from ..geometry.material import filament

        volumes = {}
        for p in self.pieces:
            model = p.model
            made = "parts" in vars(model) and "fused" not in vars(model)  # a 3MF's parts, without meshing again
            volume = sum(q.mesh.mesh_volume_mm3 for q in model.parts.values()) if made else model.fused.mesh_volume_mm3
            volumes[f"piece {p.piece.number}"] = volume
        return filament(volumes, self.pieces[0].model.profile).as_stats()

    @property
    def split_bounds(self) -> tuple:
        """The panel's bounds (mm): the pieces' nominal regions together."""
        b = np.array([p.piece.region.bounds for p in self.pieces])
        return (b[:, 0].min(), b[:, 1].min(), b[:, 2].max(), b[:, 3].max())


def print_joint(profile, kind: str = "dovetail"):
    """The joint of printed pieces: its neck :data:`NECK_NOZZLES` nozzle widths (see the module text)."""
    from ..geometry.pieces import joint_for

    return joint_for(kind, thickness_mm=NECK_NOZZLES * profile.nozzle_mm)


def check_clearance(value) -> float:
    """The gap between printed pieces (mm), checked: ``0 <= value <= MAX_CLEARANCE_MM``.

    >>> check_clearance(0.8)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: joint_clearance_mm must be a finite number >= 0 and <= 0.5, got 0.8
    """
    return check_float("joint_clearance_mm", value, low=0.0, high=MAX_CLEARANCE_MM)


def seam_lines(regions) -> list:
    """The lines each of ``regions`` (pieces that tile a panel) shares with the others: its seams."""
    import shapely

    regions = np.asarray(regions, dtype=object)
    tree = shapely.STRtree(regions)
    out = []
    for i, region in enumerate(regions):
        near = [j for j in tree.query(region, predicate="intersects").tolist() if j != i]
        # where the boundaries coincide (split_panel cuts both sides with the same lines), lines only
        touching = shapely.intersection(shapely.boundary(region), shapely.boundary(regions[near]))
        lines = shapely.get_parts(shapely.get_parts(touching))
        lines = lines[shapely.get_type_id(lines) == 1]
        out.append(shapely.line_merge(shapely.union_all(lines)) if len(lines) else shapely.LineString())
    return out


def seam_gaps(regions, seams, clearance_mm: float) -> list:
    """Each region less half of ``clearance_mm`` along its ``seams`` (:func:`seam_lines`).

    Two neighbours then stand ``clearance_mm`` apart wherever they met, on the straight
    seam and round the joints alike; a piece's edges on the panel's outline do not move.
    """
    import shapely

    if clearance_mm <= 0:
        return list(regions)
    # square ends: a seam's end on the panel's edge is cut clean through past the edge
    return [
        region
        if lines.is_empty
        else shapely.difference(region, shapely.buffer(lines, clearance_mm / 2, cap_style="square", join_style="mitre"))
        for region, lines in zip(regions, seams, strict=True)
    ]


def without_slivers(region, seams, width_mm: float):
    """``region`` (a piece's part of the pattern) less the bits narrower than ``width_mm`` that its ``seams``
    cut off: the tip of a band the seam crosses at a slant, a strip of band along it. They would print
    thin or not at all; the plate shows there instead. The pattern's own narrow places, and a band's
    square end at the seam, stay (the print checks report the first).

    The bits are those an opening of ``width_mm`` takes away within ``width_mm`` of the seams,
    larger than twice what it rounds off a square corner (a band's end at the seam keeps its
    corners).
    """
    import shapely

    if seams.is_empty or region.is_empty:
        return region
    zone = shapely.buffer(seams, width_mm)

    def opening(g):  # a corner a segment a quarter: straight edges, no arcs cut into the band
        return shapely.buffer(shapely.buffer(g, -width_mm / 2, quad_segs=1), width_mm / 2, quad_segs=1)

    # only near the seams (the opening of a whole sheet's bands takes seconds), far enough that the window's
    # own edges leave their bits outside the zone
    local = shapely.intersection(region, shapely.buffer(seams, 4 * width_mm, cap_style="flat", join_style="mitre"))
    thin = shapely.get_parts(shapely.difference(local, opening(local)))
    if not len(thin):
        return region
    real = 2 * shapely.area(thin) > HAIR_MM * shapely.length(thin)  # twice the area over the perimeter: its width
    near = shapely.get_parts(shapely.intersection(thin[real], zone))
    square = shapely.box(0, 0, 4 * width_mm, 4 * width_mm)
    corner = (square.area - opening(square).area) / 4  # what the opening takes off a square corner
    cut = near[shapely.area(near) > 2 * corner] if len(near) else near
    if not len(cut):
        return region
    # grown by a hair: no hair of the band is left along the bit's edges, which follow the band's
    return shapely.difference(region, shapely.buffer(shapely.union_all(cut), HAIR_MM / 1000, join_style="mitre"))


def number_recess(number: int, solid, *, profile):
    """A piece's number as a :class:`~fabtiles.geometry.stack.Recess` in its bottom, or None where it fits nowhere.

    The number's strokes (:mod:`fabtiles.geometry.stroke_font`), :data:`NUMBER_LINE_NOZZLES`
    nozzle widths wide, mirrored (it is read from below), at the point of ``solid`` (the
    piece's solid bottom, file mm) farthest from its edges, as high as fits of
    :data:`NUMBER_HEIGHT_MM`; :data:`NUMBER_LAYERS` layers deep.
    """
    import shapely

    from ..geometry.stack import Recess
    from ..geometry.stroke_font import text_paths
    from ..solid.print_model import RECESS_WALL_MM

    width = NUMBER_LINE_NOZZLES * profile.nozzle_mm
    room = shapely.buffer(solid, -(RECESS_WALL_MM + profile.min_wall_mm), quad_segs=2)
    if room.is_empty:
        return None
    centre = shapely.get_coordinates(shapely.maximum_inscribed_circle(room, 0.5))[0]
    for height in np.linspace(*NUMBER_HEIGHT_MM, 5):
        lines = [shapely.LineString(p) for p in text_paths(str(number), height_mm=height, centre=True)]
        text = shapely.buffer(shapely.MultiLineString(lines), width / 2, quad_segs=4)
        # mirrored about its middle, so that it reads from below, and centred on the point found
        cx, cy = shapely.centroid(shapely.envelope(text)).coords[0]
        placed = shapely.transform(
            text, lambda xy, cx=cx, cy=cy: np.c_[centre[0] - (xy[:, 0] - cx), xy[:, 1] - cy + centre[1]]
        )
        if shapely.covers(room, placed):
            return Recess(placed, NUMBER_LAYERS * profile.layer_height_mm)
    return None


def print_split(
    region, outline, *, profile, style=None, heights=None, joint: str = "dovetail", period_mm=None, origin=(0.0, 0.0)
):
    """The :class:`~fabtiles.geometry.pieces.PanelSplit` of a print for the printer profile's bed: on the
    outline (the plate is solid everywhere), or on the lattice itself for a pierced print; the
    arguments as :func:`print_pieces`'s, which raises as it does."""
    from ..geometry.pieces import split_panel
    from ..geometry.stack import resolve_stack
    from ..machines.profiles import load_profile

    profile = load_profile(profile, kind="printer")
    stack = resolve_stack(profile, style, **dict(heights or {}))
    check_clearance(profile.joint_clearance_mm)
    margin = check_float("bed_margin_mm", profile.bed_margin_mm, low=0.0)
    footprint = region if stack.style == "pierced" else outline
    try:
        return split_panel(
            footprint,
            bed_mm=profile.bed_mm,
            margin_mm=margin,
            joint=print_joint(profile, joint),
            min_feature_mm=profile.min_wall_mm,
            period_mm=period_mm,
            origin=origin,
        )
    except ParameterError as exc:  # the bed, named with the tile that does not fit it
        x0, y0, x1, y1 = outline.bounds
        bed = " x ".join(f"{v:g}" for v in profile.bed_mm)
        raise ParameterError(
            f"the {x1 - x0:g} x {y1 - y0:g} mm tile is larger than the {bed} mm bed of printer profile "
            f"{profile.name!r}, and cannot be made as pieces for it: {exc}",
            param=exc.param,
        ) from None


def print_pieces(
    region,
    outline,
    *,
    profile,
    style=None,
    heights=None,
    stroke=None,
    fill_small_holes: bool = False,
    inlay: bool = False,
    dips=None,
    colours=None,
    mosaic=(),
    joint: str = "dovetail",
    period_mm=None,
    origin=(0.0, 0.0),
) -> PrintPieces:
    """A print split for the printer profile's bed into pieces that lock together (see the module text).

    ``region``, ``outline`` and ``dips`` are the print's as :func:`~fabtiles.solid.print_model.print_model`
    takes them (panel mm), and so are the other options (``heights``: its ``base_mm`` and the
    others); ``mosaic``'s faces are in panel mm too. ``period_mm`` and ``origin``: the pattern's
    rectangular period and a point of its lattice (seams there make congruent pieces).
    Raises :class:`~fabtiles.ParameterError` for a clearance out of range or a bed too small
    for a piece with its joint, :class:`~fabtiles.FabricationError` where two pieces can be
    joined nowhere.
    """
    import shapely

    from ..geometry.pieces import laid_on_bed
    from ..geometry.stack import resolve_stack
    from ..machines.profiles import load_profile
    from ..solid._mesh_build import snap
    from ..solid.print_model import print_model

    profile = load_profile(profile, kind="printer")
    heights = dict(heights or {})
    stack = resolve_stack(profile, style, **heights)
    clearance = check_clearance(profile.joint_clearance_mm)
    margin = check_float("bed_margin_mm", profile.bed_margin_mm, low=0.0)
    split = print_split(
        region, outline, profile=profile, style=style, heights=heights, joint=joint, period_mm=period_mm, origin=origin
    )
    # a seam that cuts a curve of the outline ends its arc off the circle: such pieces' STEP walls stay planes
    straight = int(shapely.get_num_coordinates(outline)) <= STRAIGHT_OUTLINE_POINTS
    seams = seam_lines([p.region for p in split.pieces])
    shapes = seam_gaps([p.region for p in split.pieces], seams, clearance)
    made = []
    unnumbered = []
    for piece, shape, lines in zip(split.pieces, shapes, seams, strict=True):
        laid, matrix = laid_on_bed(shape, profile.bed_mm, margin_mm=margin)
        # panel -> file, the inverse of the rigid matrix exactly (a turn's transpose): as laid_on_bed moves it
        turn = matrix[:2, :2].T
        shift = -(turn @ matrix[:2, 2])

        def move(g, turn=turn, shift=shift):
            return shapely.transform(g, lambda xy: xy @ turn.T + shift)

        if stack.style == "pierced":
            kept, mine = shape, laid
        else:
            kept = without_slivers(shapely.intersection(region, shape), lines, profile.min_wall_mm)
            mine = snap(move(kept))  # on the meshes' grid: moved, a hair-thin place stays valid
        piece_dips = None
        if dips is not None:  # strictly inside the piece's material, as the meshes need them
            inside = shapely.get_parts(
                shapely.intersection(dips, shapely.buffer(shape, -JOINT_INSET_MM, join_style="mitre"))
            )
            shapely.prepare(kept)
            inside = inside[shapely.contains_properly(kept, inside)] if len(inside) else inside
            piece_dips = move(shapely.multipolygons(inside)) if len(inside) else None
        recess = number_recess(piece.number, laid, profile=profile)
        if recess is None:
            unnumbered.append(piece.number)
        parts = tuple(s._replace(faces=tuple(move(f) for f in s.faces)) for s in mosaic)
        model = print_model(
            mine,
            laid,
            profile=profile,
            style=stack.style,
            stroke=stroke,
            fill_small_holes=fill_small_holes,
            inlay=inlay,
            dips=piece_dips,
            colours=colours,
            mosaic=parts,
            recess=recess,
            step_arcs=straight,
            **heights,
        )
        made.append(PrintedPiece(piece, matrix, model))
    # the pieces' findings, each once (a finding of the pattern is every piece's)
    findings = list({(f.code, f.message): f for p in made for f in p.model.report.findings}.values())
    report = Report("", "", stats={"pieces": len(made), "joints": len(split.joints)}, findings=findings)
    result = PrintPieces(split, tuple(made), clearance, tuple(profile.bed_mm), report, outline)
    sizes = [(b[2] - b[0], b[3] - b[1]) for b in (p.model.outline.bounds for p in made)]
    w, h = max(sizes, key=lambda s: s[0] * s[1])
    report.stats["largest_piece_mm"] = [round(w, 1), round(h, 1)]
    report.note(
        f"{result.line()} of printer profile {profile.name!r}: {len(split.joints)} {split.joint.kind} "
        f"joint{'s' if len(split.joints) != 1 else ''}, {clearance:g} mm apart, the largest piece {w:.0f} x "
        f"{h:.0f} mm, each piece's number sunk into its bottom"
    )
    if unnumbered:
        report.note(
            f"no room for the number under piece{'s' if len(unnumbered) > 1 else ''} "
            + ", ".join(str(n) for n in unnumbered)
        )
    return result
