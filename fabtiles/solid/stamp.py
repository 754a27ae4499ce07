"""A clay stamp: a tile's relief on a block with a finger grip, printed pattern up with no supports.

The stamp is a relief print (:class:`~fabtiles.solid.print_model.PrintModel`, style
``relief``) raised on a block of the tile's outline. The caller mirrors the pattern
first (:func:`fabtiles.geometry.mirror.mirrored`): a stamp leaves the mirror image of
its face, so a mirrored face leaves the design.

It prints standing on its back, the pattern up: the relief's plate and strands are
flat tops and vertical walls, and the block's only faces that look down are its back
on the bed and the upper side of the finger groove. The groove runs round the block's
sides (a waist): from the foot the sides step in at a chamfer, run straight up the
groove's middle, and step out again at a chamfer that overhangs no more than the
printer's limit (45 degrees from vertical unless the settings or the printer profile
say otherwise), so no part of it needs support.

Each chamfer is the convex hull of the outline and the outline taken in by the groove's
depth, so the outline must be convex, as every tile outline is (square, rectangle,
hexagon, circle). A slicer judges an overhang layer by layer: how far a layer reaches
beyond the one under it, in any direction. A corner of the outline moves farther than
its sides as the groove takes it in (a square's corner by the depth times the square
root of two), so the chamfer's rise is the farthest any point of the outline moves,
the Hausdorff distance of the two outlines, over the tangent of the limit: no point
of any layer reaches beyond the layer under it by more than the layer's height times
that tangent, and the flat sides stand steeper than the limit.

The block and the relief are fused with manifold3d, and every body is checked as a
slicer reads it (:func:`~fabtiles.solid.mesh_check.check_indexed`) before a writer
takes it: the STL holds the fused stamp; the 3MF and the 3D view hold two parts, the
``block`` (with the relief's plate) and the ``pattern`` on it, each with its material.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..core.errors import FabricationError, ParameterError
from ..core.native import import_uninterrupted
from ..core.validate import check_float
from ..geometry.stack import QUANTUM
from ._mesh_build import snap
from .mesh_check import check_indexed
from .parts import CheckedPart, stack_stats
from .print_model import PrintModel, PrintPart

OVERHANG_DEG = 45.0
"""The flattest overhang (degrees from vertical) a printer is taken to lay without support, unless told
otherwise: the figure slicers and makers use."""

LAND_MM = 2.0
"""The straight sides kept at the block's foot (on the bed) and under its shoulder, either side of the groove."""

NECK_MM = 10.0
"""The narrowest the block may be at the groove's bottom (the width of the largest disc that fits there)."""

OVERHANG_RANGE_DEG = (20.0, 70.0)
"""The overhang limits accepted (degrees from vertical)."""


@dataclass(frozen=True, slots=True, kw_only=True)
class StampSettings:
    """A clay stamp's block and grip (see the module text); lengths in mm.

    >>> StampSettings(grip_mm=0)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: grip_mm must be a finite number > 0 and <= 20, got 0
    """

    block_mm: float = 20.0
    """The block's height, from the bed to the relief's plate."""
    grip_mm: float = 3.0
    """How deep the finger groove goes into the block's sides."""
    groove_mm: float = 4.0
    """The height of the groove's straight middle, between its two chamfers (0: a V)."""
    overhang_deg: float | None = None
    """The flattest overhang the printer lays without support (degrees from vertical), which the
    chamfers keep to; None: the printer profile's ``max_overhang_deg`` when it has one, else
    :data:`OVERHANG_DEG`."""

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "block_mm", check_float("block_mm", self.block_mm, low=0, low_open=True, high=200))
        set_(self, "grip_mm", check_float("grip_mm", self.grip_mm, low=0, low_open=True, high=20))
        set_(self, "groove_mm", check_float("groove_mm", self.groove_mm, low=0, high=100))
        if self.overhang_deg is not None:
            low, high = OVERHANG_RANGE_DEG
            set_(self, "overhang_deg", check_float("overhang_deg", self.overhang_deg, low=low, high=high))
        # the least rise (a circle's, whose every point moves the groove's depth): the outline may need more
        check_block(self, self.grip_mm / math.tan(math.radians(self.overhang_deg or OVERHANG_DEG)))


def check_block(settings: StampSettings, rise_mm: float) -> None:
    """Refuse a block too short for its groove: two chamfers of ``rise_mm``, the middle, and a
    :data:`LAND_MM` land at the foot and under the shoulder."""
    need = 2 * rise_mm + settings.groove_mm + 2 * LAND_MM
    if settings.block_mm < need - 1e-9:
        raise ParameterError(
            f"block_mm must be at least {need:.4g} mm for a groove {settings.grip_mm:g} mm deep "
            f"(two chamfers of {rise_mm:.4g} mm, a middle of groove_mm = {settings.groove_mm:g} mm and "
            f"{LAND_MM:g} mm of straight side above and below), got {settings.block_mm:g}",
            param="block_mm",
        )


class Grip:
    """The block's shape: its outline, the waist (the outline taken in by the groove's depth) and heights.

    ``outline`` is the relief's outline (a convex polygon, on the mesh grid); ``overhang_deg`` the limit
    the upper chamfer keeps to. Raises :class:`~fabtiles.ParameterError` for an outline that is not
    convex, a groove deeper than the outline leaves a :data:`NECK_MM` waist for, or a block too short
    for the groove.
    """

    def __init__(self, outline, settings: StampSettings, overhang_deg: float):
        import shapely

        polys = list(getattr(outline, "geoms", [outline]))
        hull = shapely.convex_hull(outline)
        if len(polys) != 1 or hull.area - outline.area > 1e-6 * hull.area:
            raise ParameterError(
                f"a stamp's outline must be one convex polygon (its grip's chamfers are hulls), got a "
                f"{outline.geom_type} whose convex hull is {hull.area - outline.area:.4g} mm^2 larger",
                param="outline",
            )
        radius = shapely.maximum_inscribed_circle(outline, 0.01).length
        deepest = radius - NECK_MM / 2
        if settings.grip_mm > deepest:
            raise ParameterError(
                f"grip_mm must be at most {max(deepest, 0):.3g} mm for this outline (the waist keeps a "
                f"{NECK_MM:g} mm disc; the outline's largest disc is {2 * radius:.3g} mm across), "
                f"got {settings.grip_mm:g}",
                param="grip_mm",
            )
        (outline,) = polys
        self.outer = _ring(outline)
        self.inner = _ring(shapely.buffer(outline, -settings.grip_mm, join_style="mitre"))
        self.overhang_deg = overhang_deg
        # the farthest a point of the outline moves: at one of its corners (the distance to a convex set
        # is largest at a vertex)
        run = float(shapely.distance(shapely.points(self.outer), shapely.Polygon(self.inner)).max())
        self.run_mm = run
        self.rise_mm = _up(run / math.tan(math.radians(overhang_deg)))
        check_block(settings, self.rise_mm)
        self.settings = settings
        total = 2 * self.rise_mm + settings.groove_mm
        self.z = np.cumsum([_up((settings.block_mm - total) / 2), self.rise_mm, settings.groove_mm, self.rise_mm])
        """Where the groove's lower chamfer starts, its middle starts, ends, and its upper chamfer ends."""

    def manifold(self, height_mm: float):
        """The block up to ``height_mm``, as a manifold3d solid: three convex hulls, the foot with its
        chamfer, the waist and the shoulder with its chamfer, each sharing a face with the next."""
        m3 = import_uninterrupted("manifold3d")
        Manifold, OpType = m3.Manifold, m3.OpType

        z1, za, zb, zc = self.z
        o, i = self.outer, self.inner
        pieces = [
            Manifold.hull_points(np.concatenate([_at(o, 0.0), _at(o, z1), _at(i, za)])),
            Manifold.hull_points(np.concatenate([_at(i, za), _at(i, zb)])),
            Manifold.hull_points(np.concatenate([_at(i, zb), _at(o, zc), _at(o, height_mm)])),
        ]
        if zb == za:  # no straight middle: the two chamfers meet at the waist
            del pieces[1]
        return Manifold.batch_boolean(pieces, OpType.Add)

    def volume(self, height_mm: float) -> float:
        """The block's volume up to ``height_mm`` (mm^3), from the rings' areas and mixed area."""
        z1, za, zb, zc = self.z
        a_o, a_i = _area(self.outer), _area(self.inner)
        # a chamfer is a prismatoid: rise / 3 x (A_o + M + A_i), M the rings' mixed area
        chamfer = self.rise_mm / 3 * (a_o + _mixed_area(self.outer, self.inner) + a_i)
        return a_o * z1 + chamfer + a_i * (zb - za) + chamfer + a_o * (height_mm - zc)


def _ring(poly) -> np.ndarray:
    """A convex polygon's exterior, counter-clockwise, without its closing point, on the grid."""
    import shapely

    ring = shapely.get_coordinates(shapely.orient_polygons(poly).exterior)[:-1]
    return np.round(ring / QUANTUM) * QUANTUM


def _at(ring: np.ndarray, z: float) -> np.ndarray:
    return np.column_stack([ring, np.full(len(ring), z)])


def _up(length_mm: float) -> float:
    """``length_mm`` rounded up to the mesh grid."""
    return math.ceil(length_mm / QUANTUM - 1e-6) * QUANTUM


def _support(ring: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """The convex ring's support function at each of ``normals``."""
    return (normals @ ring.T).max(axis=1)


def _area(ring: np.ndarray) -> float:
    x, y = ring.T
    return float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)) / 2


def _mixed_area(a: np.ndarray, b: np.ndarray) -> float:
    """The mixed area of two convex rings: half the sum over ``b``'s edges of ``a``'s support times the edge's length.

    >>> sq = lambda side: np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float) * side
    >>> _mixed_area(sq(3), sq(2))
    6.0
    """
    d = np.roll(b, -1, axis=0) - b
    length = np.linalg.norm(d, axis=1)
    normals = np.stack([d[:, 1], -d[:, 0]], axis=1) / length[:, None]
    return float(np.dot(_support(a, normals), length)) / 2


def _manifold_of(part: CheckedPart, dz: float):
    """A checked mesh, raised by ``dz``, as a manifold3d solid."""
    m3 = import_uninterrupted("manifold3d")
    Manifold, Mesh64 = m3.Manifold, m3.Mesh64

    verts = np.asarray(part.vertices, np.float64) + (0.0, 0.0, dz)
    return Manifold(Mesh64(vert_properties=verts, tri_verts=np.asarray(part.faces, np.uint64)))


def _checked(solid, *, name: str, volume: float, region, outline) -> CheckedPart:
    """A manifold3d solid checked as a slicer reads its STL: one body of ``volume``."""
    mesh = solid.to_mesh64()
    verts, faces, found = check_indexed(
        np.asarray(mesh.vert_properties, np.float64)[:, :3],
        np.asarray(mesh.tri_verts, np.int64),
        name=name,
        volume=volume,
        bodies=1,
        with_volume=True,
    )
    return CheckedPart(verts, faces, float(volume), 1, region, outline, float(found))


NO_STEP = "a clay stamp has no STEP file (its grip's chamfers are not made as a B-rep); write STL or 3MF"
"""Why a stamp has no STEP file, in one line (the build's refusal and the web page's note)."""


class StampPrint:
    """A clay stamp ready for the print writers (STL, 3MF, GLB): made by :func:`stamp_print`.

    It offers what they read of a :class:`~fabtiles.solid.print_model.PrintModel`: the
    profile, the stack, the report, the fused body, the parts, the files and bodies.
    """

    def __init__(self, model: PrintModel, settings: StampSettings, grip: Grip):
        self.model = model
        self.settings = settings
        self.grip = grip
        self.profile = model.profile
        self.stack = model.stack
        self.region = model.region
        self.outline = model.outline
        self.height_mm = round(self.block_top_mm + model.stack.base + model.stack.relief, 6)
        self.report = model.report.extended(
            notes=[
                f"clay stamp: a block {grip.settings.block_mm:g} mm high with a finger groove "
                f"{grip.settings.grip_mm:g} mm deep round its sides, its chamfers overhanging at most "
                f"{grip.overhang_deg:g} degrees from vertical: print it pattern up, no supports"
            ],
            stamp=self.figures(),
        )

    @property
    def block_top_mm(self) -> float:
        """Where the relief's plate sits on the block (mm above the bed): the block's height on the grid."""
        return round(self.settings.block_mm / QUANTUM) * QUANTUM

    def figures(self) -> dict:
        """The stamp's shape, for the report."""
        z1, zc = self.grip.z[[0, 3]]
        return {
            "block_top_mm": self.block_top_mm,
            "groove_depth_mm": self.settings.grip_mm,
            "groove_from_to_mm": [float(z1), float(zc)],
            "chamfer_rise_mm": self.grip.rise_mm,
            "overhang_deg": self.grip.overhang_deg,
            "height_mm": self.height_mm,
        }

    @cached_property
    def fused(self) -> CheckedPart:
        """The stamp as one checked body: the block and the relief fused."""
        top = self.block_top_mm
        relief = self.model.fused
        solid = self.grip.manifold(top) + _manifold_of(relief, top)
        volume = self.grip.volume(top) + relief.volume_mm3
        return _checked(solid, name="stamp", volume=volume, region=relief.region, outline=relief.outline)

    @property
    def fused_name(self) -> str:
        return "stamp"

    @cached_property
    def parts(self) -> dict:
        """The ``block`` (with the relief's plate) and the ``pattern`` on it, with the relief's materials."""
        top = self.block_top_mm
        (base_name, base), (pattern_name, pattern) = self.model.parts.items()
        plate = float(np.float32(self.stack.base))
        block_solid = self.grip.manifold(top + plate)
        block = _checked(
            block_solid,
            name="block",
            volume=self.grip.volume(top + plate),
            region=base.mesh.outline,
            outline=base.mesh.outline,
        )
        raised = pattern.mesh
        verts, faces, found = check_indexed(
            np.asarray(raised.vertices) + (0.0, 0.0, top),
            raised.faces,
            name="pattern",
            volume=raised.volume_mm3,
            bodies=raised.bodies,
            with_volume=True,
        )
        lifted = CheckedPart(verts, faces, raised.volume_mm3, raised.bodies, raised.region, raised.outline, found)
        block_name = "block" if base_name == "base" else base_name
        return {
            block_name: PrintPart(block_name, base.material, base.colour, block),
            pattern_name: PrintPart(pattern_name, pattern.material, pattern.colour, lifted),
        }

    def stats(self) -> dict:
        """The relief's style and heights, and the stamp's shape."""
        return dict(stack_stats(self.stack), stamp=self.figures())

    def files(self) -> list:
        return [("", self)]

    def bodies(self) -> list:
        return [("", self)]

    @property
    def brep(self):
        """No STEP of a stamp: its chamfers are not the planes of a relief's prisms."""
        raise FabricationError(NO_STEP)

    @property
    def breps(self):
        """No STEP of a stamp (:attr:`brep` raises)."""
        return [(None, self.brep)]


def stamp_print(model: PrintModel, *, settings: StampSettings | None = None) -> StampPrint:
    """A clay stamp of a relief print: its relief on a block with a finger grip (see the module text).

    Parameters
    ----------
    model : PrintModel
        A relief print (style ``relief``) of the pattern as the stamp's face shows it:
        mirrored (:func:`fabtiles.geometry.mirror.mirrored`) so that the imprint reads as
        designed. Its outline must be convex.
    settings : StampSettings, optional
        The block and the grip (default :class:`StampSettings()`).

    Returns
    -------
    StampPrint
        What the STL, 3MF and GLB writers take; no mesh is made until one is read.

    Raises
    ------
    ParameterError
        A print that is not a relief, an outline that is not convex, a groove too deep
        for the outline or too tall for the block.
    """
    if not isinstance(model, PrintModel) or model.stack.style != "relief":
        got = model.stack.style if isinstance(model, PrintModel) else type(model).__name__
        raise ParameterError(f"a clay stamp is made of a relief print (style='relief'), got {got!r}", param="style")
    settings = StampSettings() if settings is None else settings
    if not isinstance(settings, StampSettings):
        raise ParameterError(f"settings must be a StampSettings, got {type(settings).__name__}", param="settings")
    overhang = settings.overhang_deg
    if overhang is None:
        overhang = getattr(model.profile, "max_overhang_deg", None) or OVERHANG_DEG
    grip = Grip(snap(model.outline), settings, float(overhang))
    return StampPrint(model, settings, grip)
