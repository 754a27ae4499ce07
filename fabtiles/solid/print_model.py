"""The print model: a tile's print as named parts, checked once, read by every print writer.

A :class:`PrintModel` holds what the STL, 3MF, STEP and GLB writers need: the
printer profile, the stack of heights, the region to print (thinned and filled as
the profile says, :func:`~fabtiles.geometry.print_checks.print_region`), the
findings of the printability checks, and, made on first use and then kept:

- ``parts``: N named parts (a relief's ``base`` and ``pattern``, a deboss plate and
  its ``inlay``, a pierced ``pattern``), each with its material (the slicer's
  extruder, 1-based) and display colour and its checked mesh;
- ``fused``: the print as one checked body (an STL holds one body);
- ``brep``: the B-rep of the fused body (planes and cylinders), only for STEP;
- ``breps``: what the STEP holds: that B-rep, or a mosaic's of several colours one per part.

A pierced or deboss print without inlay is one part: its fused body *is* that
part, meshed once. A build makes one model, whatever print formats it writes.

>>> import shapely
>>> plate = shapely.box(0, 0, 40, 40).difference(shapely.box(10, 10, 30, 30))
>>> model = print_model(plate, shapely.box(0, 0, 40, 40), profile="fdm-0.4mm", style="relief")
>>> [(p.name, p.material) for p in model.parts.values()]
[('base', 1), ('pattern', 2)]
>>> round(model.fused.mesh_volume_mm3)
4640
"""

from __future__ import annotations

from dataclasses import replace
from functools import cached_property
from typing import NamedTuple

from ..core.errors import FabricationError, ParameterError
from ..core.report import Report
from .parts import (
    CheckedPart,
    MosaicPart,
    check_inlay,
    checked_parts,
    mosaic_parts,
    part_kinds,
    prepare_print,
    relief_parts,
    splits_fused,
    stack_stats,
)


class Material(NamedTuple):
    """A part's filament (the slicer's extruder, 1-based) and its colour in the 3D view (linear RGB)."""

    extruder: int
    colour: tuple


PART_MATERIALS = {
    "base": Material(1, (0.90, 0.84, 0.72)),  # a light first filament
    "pattern": Material(2, (0.02, 0.07, 0.30)),  # a dark second filament: the preview's ink #1f3b73, linear
    "plate": Material(1, (0.90, 0.84, 0.72)),
    "inlay": Material(2, (0.85, 0.62, 0.12)),
}
"""Each part's material by name: one table for the 3MF's extruders and the 3D view's colours.
A print of one part takes extruder 1 whatever its name; the user can change any of them in the slicer."""

OTHER = Material(1, (0.6, 0.6, 0.6))

HOLDS = {"base": "base", "pattern": "bands", "plate": "base", "inlay": "bands"}
"""What each part of a relief or deboss holds, in a coloured print's part names (``navy (base)``,
``white (bands)``), the words a mosaic's parts use: the 3MF carries a print's colours by its
parts' names and extruders (no display colours, docs/slicers.md)."""


class PrintPart(NamedTuple):
    """One part of a print: its name, material and checked mesh."""

    name: str
    material: int
    colour: tuple
    mesh: CheckedPart


class PrintModel:
    """A tile's print: profile, stack, the region printed, findings, and its meshes made once.

    Made by :func:`print_model`; see the module text.
    """

    def __init__(
        self,
        *,
        profile,
        stack,
        region,
        outline,
        report: Report,
        dips=None,
        inlay: bool = False,
        colours=None,
        mosaic=(),
        arc_radii_mm=(),
        step_arcs: bool = True,
    ):
        self.profile = profile
        self.stack = stack
        self.region = region
        self.outline = outline
        self.report = report
        self.dips = dips
        self.inlay = bool(inlay)
        self.colours = colours
        """The design's :class:`~fabtiles.designs.colour.Colouring`, or None (the parts' own colours)."""
        self.mosaic = tuple(mosaic)
        """A mosaic's parts, one per colour (:class:`~fabtiles.solid.parts.MosaicPart`)."""
        self.arc_radii_mm = tuple(float(r) for r in arc_radii_mm)
        """Radii the region's curves are known to have (half the stroke: its round joins), for the STEP's arcs."""
        self.step_arcs = bool(step_arcs)
        """Whether the STEP finds the arcs of the walls (cylinders); False: planes only (a piece cut from a round
        outline, whose arcs end off their circles where the seams cut them)."""

    def with_classes(self, mosaic, report: Report) -> PrintModel:
        """This print with a mosaic's parts (``mosaic``; none: its own) and a report that says its face
        classes: a new model, made before any mesh, so a model's report is never changed once made."""
        return PrintModel(
            profile=self.profile,
            stack=self.stack,
            region=self.region,
            outline=self.outline,
            report=report,
            dips=self.dips,
            inlay=self.inlay,
            colours=self.colours,
            mosaic=mosaic or self.mosaic,
            arc_radii_mm=self.arc_radii_mm,
            step_arcs=self.step_arcs,
        )

    @property
    def single_part(self) -> bool:
        """True when the print is one part: its fused body and its part are the same mesh."""
        if self.stack.style == "mosaic":
            return False
        return part_kinds(self.stack.style, True, False) == part_kinds(self.stack.style, False, self.inlay)

    @cached_property
    def parts(self) -> dict:
        """The checked parts by name, in print order (:class:`PrintPart`)."""
        if self.stack.style == "mosaic":
            specs = self.mosaic or (MosaicPart("body", True, True, ()),)
            checked = mosaic_parts(self.region, self.outline, self.stack, specs)
            colour = {s.name: s.colour for s in specs}
            return {
                name: PrintPart(name, k + 1, colour[name].linear if colour[name] is not None else OTHER.colour, mesh)
                for k, (name, mesh) in enumerate(checked.items())
            }
        if splits_fused(self.stack, False, self.inlay, self.dips):
            checked = relief_parts(self.fused, self.stack)  # one meshing for the STL and the 3MF
        else:
            checked = checked_parts(self.region, self.outline, self.stack, inlay=self.inlay, dips=self.dips)
        one = len(checked) == 1
        out = {}
        for name, mesh in checked.items():
            label, colour = self._label_and_colour(name, one)
            out[label] = PrintPart(label, 1 if one else PART_MATERIALS.get(name, OTHER).extruder, colour, mesh)
        return out

    def _label_and_colour(self, name: str, one: bool) -> tuple:
        """A checked part's label and display colour: its material's, or with the design's colours (a
        relief's plate and bands, a deboss and its inlay) theirs, a part among several then named as a
        mosaic's parts are, by colour and what it holds."""
        if self.colours is None:
            return name, PART_MATERIALS.get(name, OTHER).colour
        chosen = self.colours.band if name in ("pattern", "inlay") else self.colours.base
        label = f"{chosen.name} ({HOLDS[name]})" if not one and name in HOLDS else name
        return label, chosen.linear

    @cached_property
    def fused(self) -> CheckedPart:
        """The print as one checked body (a relief's base and pattern fused): what an STL holds."""
        if self.single_part:
            (part,) = self.parts.values()
            return part.mesh
        (mesh,) = checked_parts(self.region, self.outline, self.stack, single=True, dips=self.dips).values()
        return mesh

    @property
    def fused_name(self) -> str:
        """The fused body's name (``"body"`` for a relief, else its one part's)."""
        ((name, _),) = part_kinds(self.stack.style, single=True).items()
        return name

    def files(self) -> list:
        """``[("", self)]``: a print is one file of each format that holds its parts (see :meth:`bodies`)."""
        return [("", self)]

    def bodies(self) -> list:
        """``[(suffix, print), ...]``: the print as files of one body each (an STL holds one body).

        A mosaic of several colours is one body per colour, ``-<colour>`` (all in the same
        frame, for slicers without 3MF), each a :class:`PartPrint` of one part; anything
        else is one body, this model.
        """
        if self.stack.style == "mosaic" and len(self.parts) > 1:
            return [(f"-{_slug(name)}", PartPrint(self, part)) for name, part in self.parts.items()]
        return [("", self)]

    @cached_property
    def brep(self):
        """``(brep, mesh volume, solids)``: the B-rep of the fused body (:mod:`.brep`), for STEP."""
        from .brep import brep_of_part

        tolerance = self.profile.tolerance_mm if self.step_arcs else 0.0
        return brep_of_part(self.fused, self.stack, self.dips, tolerance_mm=tolerance, radii=self.arc_radii_mm)

    @cached_property
    def breps(self) -> list:
        """``[(name, (brep, mesh volume, solids)), ...]``: the B-reps a STEP file holds, for STEP.

        A mosaic of several colours: one per part, in the parts' order and named as they are,
        each made from the levels its checked mesh was made from (so it is the body of its
        STL and its 3MF part); anything else: the fused body's (:attr:`brep`), named None
        (the file's name).
        """
        if self.stack.style == "mosaic" and len(self.parts) > 1:
            from .brep import brep_of_part

            tolerance = self.profile.tolerance_mm if self.step_arcs else 0.0
            return [
                (name, brep_of_part(part.mesh, self.stack, tolerance_mm=tolerance, radii=self.arc_radii_mm))
                for name, part in self.parts.items()
            ]
        return [(None, self.brep)]

    def stats(self) -> dict:
        """The stack's style and heights, for a file's report."""
        return stack_stats(self.stack)


def print_model(
    region,
    outline,
    *,
    profile,
    style=None,
    base_mm=None,
    relief_mm=None,
    pierced_mm=None,
    deboss_mm=None,
    mosaic_inset_mm=None,
    stroke=None,
    fill_small_holes: bool = False,
    inlay: bool = False,
    dips=None,
    colours=None,
    mosaic=(),
    recess=None,
    step_arcs: bool = True,
    period_mm: float | None = None,
    path: str = "",
    fmt: str = "",
) -> PrintModel:
    """Validate, make the region to print and run the printability checks: the tile's :class:`PrintModel`.

    Parameters as :func:`~fabtiles.solid.parts.build_meshes`, plus ``period_mm`` (the region repeats
    along x with this period, its outline one period: a cylinder's strip, filled so that its ends
    meet), ``stroke`` (mm, named
    by the thin-wall check), ``fill_small_holes`` (fill the openings no disc of the
    printer profile's ``min_hole_mm`` fits in, see
    :func:`~fabtiles.geometry.print_checks.fill_print_holes`) and ``path``, ``fmt`` (what
    the report names); ``inlay`` (deboss only) adds the grooves' filling as a second
    part; ``dips`` lowers an interlaced relief's under strands (:mod:`fabtiles.solid.levels`); ``colours`` (a
    :class:`~fabtiles.designs.colour.Colouring`) colours the parts, and a mosaic's ``mosaic``
    (:class:`~fabtiles.solid.parts.MosaicPart`, one per colour) says which part holds
    the plate, the bands and which faces; ``recess`` (a :class:`~fabtiles.geometry.stack.Recess`)
    is sunk into the bottom face (:func:`check_recess`); ``step_arcs=False`` writes the STEP's walls as
    planes only. No mesh is built here: the model
    makes each on first use. A strict profile with findings raises.
    """
    heights = dict(
        base_mm=base_mm,
        relief_mm=relief_mm,
        pierced_mm=pierced_mm,
        deboss_mm=deboss_mm,
        mosaic_inset_mm=mosaic_inset_mm,
    )
    profile, stack, report, region = prepare_print(
        region,
        outline,
        profile,
        style,
        heights,
        stroke,
        fill_small_holes=fill_small_holes,
        flatten=dips is None,
        period_mm=period_mm,
        path=path,
        fmt=fmt,
    )
    check_inlay(stack, inlay)
    if recess is not None:
        stack = replace(stack, recess=check_recess(recess, region, outline, stack))
    if mosaic and stack.style != "mosaic":
        raise ParameterError(f"mosaic parts need style='mosaic', got style={stack.style!r}", param="style")
    # the strokes' round joins have half the stroke's radius (the STEP's cylinders find them by it)
    radii = () if stroke is None else (float(stroke) / 2,)
    return PrintModel(
        profile=profile,
        stack=stack,
        region=region,
        outline=outline,
        report=report,
        dips=dips,
        inlay=inlay,
        colours=colours,
        mosaic=mosaic,
        arc_radii_mm=radii,
        step_arcs=step_arcs,
    )


RECESS_WALL_MM = 0.5
"""The least material kept between a recess in the bottom and the bottom's edge (or an opening)."""


def check_recess(recess, region, outline, stack):
    """``recess`` snapped to the grid, checked to lie in the solid bottom and to leave material over it.

    The solid bottom is the outline (relief, deboss, mosaic) or the region (pierced),
    less :data:`RECESS_WALL_MM` all round; the material over the recess is the plate
    (less a deboss's grooves) or the pierced part's thickness. Raises
    :class:`~fabtiles.FabricationError` otherwise: a recess that reached an edge would
    open the part's side.
    """
    import shapely

    from ..geometry.stack import Recess
    from ._mesh_build import snap

    floor = {"relief": stack.base, "mosaic": stack.base, "deboss": stack.base - stack.deboss}.get(
        stack.style, stack.pierced
    )
    if not 0 < recess.depth < floor:
        raise FabricationError(
            f"the recess under the print must be deeper than 0 and shallower than the {floor:g} mm of material "
            f"over it, got {recess.depth:g} mm"
        )
    solid = region if stack.style == "pierced" else outline
    if not shapely.covers(shapely.buffer(solid, -RECESS_WALL_MM, quad_segs=2), recess.region):
        raise FabricationError(
            f"the recess under the print reaches within {RECESS_WALL_MM:g} mm of the edge of its solid bottom"
        )
    return Recess(snap(recess.region), float(recess.depth))


def _slug(name: str) -> str:
    """A part's name as a file name's tail: its colour (``"cobalt (A, C)"`` -> ``"cobalt"``)."""
    return name.split(" (")[0].replace(" ", "-")


class PartPrint:
    """One part of a print as a print of its own (an STL of one colour of a mosaic): its mesh is the fused body."""

    def __init__(self, model: PrintModel, part: PrintPart):
        self.profile = model.profile
        self.stack = model.stack
        self.report = model.report
        self.part = part

    @property
    def fused(self) -> CheckedPart:
        return self.part.mesh

    @property
    def fused_name(self) -> str:
        return self.part.name

    def stats(self) -> dict:
        return stack_stats(self.stack)

    def files(self) -> list:
        return [("", self)]

    def bodies(self) -> list:
        return [("", self)]
