"""STEP output: the printed tile as a solid a CAD user would have modelled, checked by OCCT.

The solid (:func:`fabtiles.solid.brep.build_brep`) has planar faces and vertical cylinders:
the bottom is one face, each connected flat region on top is one face with its
holes, each straight side of the outline is one wall face, each round wall (arcs
recovered within the printer profile's ``tolerance_mm``) a cylinder bounded by circle
edges, and vertical edges stand at the outline's corners. So OCCT-based CAD (FreeCAD,
CadQuery, build123d) shows a hole's diameter, fillets its rim and its corners, drills
it and reports its true volume.

It is written as STEP text (:mod:`fabtiles.export.step_file`): OCCT's own writer
costs the square of a face's edges, and the 200 x 200 mm relief tile's top face
has 1,573 holes. Before it is written the B-rep is checked in memory
(:func:`~fabtiles.solid.brep.check_brep`: closed, oriented, valid faces, the
checked mesh's volume); :func:`check_step_file` reads a written file back with OCCT
and checks it solid by solid (:func:`check_solids`), for ``fabtiles check --deep``
and the tests. build123d's OCP is imported only inside these functions.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import FabricationError, ProfileError
from ..geometry.material import filament
from ..geometry.stack import QUANTUM
from ..solid.brep import brep_volume, check_brep
from .step_file import step_text

STEP_VOLUME_TOLERANCE = 0.0005
"""Largest relative difference between OCCT's volume of the solid and the mesh's (0.05 %)."""

BIG_FACE_WIRES = 64
"""Faces with more wires than this are checked wire by wire (see :func:`check_solids`)."""

# --------------------------------------------------------------------------- reading back


def _quiet():
    """Keep OCCT's transfer statistics off stdout."""
    from OCP.Message import Message, Message_Gravity

    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


def read_step(path):
    """Read a STEP file as CAD programs do (OCCT's reader, shape healing on): one shape.

    Healing runs per wire over the whole face, so a top face with a thousand holes
    or more takes OCCT long to read this way (``docs/speed.md``).
    """
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader

    _quiet()
    reader = STEPControl_Reader()
    if reader.ReadFile(str(path)) != IFSelect_RetDone:
        raise FabricationError(f"cannot read back the STEP file {str(path)!r}")
    reader.TransferRoots()
    return reader.OneShape()


def read_step_solids(path):
    """The solids of a STEP file, translated by OCCT as written (no shape healing).

    OCCT parses the file and builds each ``MANIFOLD_SOLID_BREP`` with its STEP
    translator, skipping the healing that :func:`read_step` adds: what is checked
    is the file itself, not a repaired copy, and far quicker.
    """
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.StepShape import StepShape_ManifoldSolidBrep
    from OCP.StepToTopoDS import StepToTopoDS_Builder
    from OCP.Transfer import Transfer_TransientProcess

    _quiet()
    reader = STEPControl_Reader()
    if reader.ReadFile(str(path)) != IFSelect_RetDone:
        raise FabricationError(f"cannot read back the STEP file {str(path)!r}")
    model = reader.StepModel()
    process = Transfer_TransientProcess(model.NbEntities())
    process.SetModel(model)
    solids = []
    for i in range(1, model.NbEntities() + 1):
        entity = model.Value(i)
        if isinstance(entity, StepShape_ManifoldSolidBrep):
            builder = StepToTopoDS_Builder()
            builder.Init(entity, process)
            if not builder.IsDone():
                raise FabricationError(f"OCCT cannot translate solid #{i} of the STEP file {str(path)!r}")
            solids.append(builder.Value())
    return solids


def _wires(face):
    from OCP.TopAbs import TopAbs_WIRE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    out = []
    exp = TopExp_Explorer(face, TopAbs_WIRE)
    while exp.More():
        out.append(TopoDS.Wire(exp.Current()))
        exp.Next()
    return out


def _plane_pcurves(face) -> None:
    """Store the 2D curve of each edge of a planar face on its plane.

    STEP leaves them out for planes, and OCCT then projects an edge onto the plane
    afresh each time a check asks for it; projected once and kept, the same curves
    make ``BRepCheck_Analyzer`` and the volume quicker (``docs/speed.md``).
    """
    from OCP.BRepLib import BRepLib
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    build = BRepLib.BuildPCurveForEdgeOnPlane_s
    edges = TopExp_Explorer(face, TopAbs_EDGE)
    while edges.More():
        build(TopoDS.Edge(edges.Current()), face)
        edges.Next()


def _big_face_valid(face) -> bool:
    """A face with many holes: each wire by OCCT, how the wires lie together by GEOS.

    ``BRepCheck_Analyzer`` checks every vertex of a face against all its edges, which
    takes tens of seconds on a face of a thousand holes (``docs/speed.md``). Checked
    instead: each wire as the boundary of a face of its own on the same plane
    (OCCT: edges, vertices, closure, self-intersection), and the wires' vertices,
    in the plane's coordinates, as one polygon that GEOS must find valid (no
    wire crossing or touching another, every hole inside the outer wire).
    """
    import shapely
    from OCP.BRep import BRep_Tool
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.GeomAdaptor import GeomAdaptor_Surface
    from OCP.TopoDS import TopoDS

    geom = BRep_Tool.Surface_s(face)
    surface = GeomAdaptor_Surface(geom)
    if surface.GetType() != GeomAbs_Plane:
        return False
    _plane_pcurves(face)
    plane = surface.Plane()
    pos = plane.Position()
    o, xd, yd = pos.Location(), pos.XDirection(), pos.YDirection()
    outer = BRepTools.OuterWire_s(face)
    rings, outer_ring = [], None
    for wire in _wires(face):
        is_outer = wire.IsSame(outer)
        single = BRepBuilderAPI_MakeFace(geom, wire if is_outer else TopoDS.Wire(wire.Reversed()), True)
        if not single.IsDone() or not BRepCheck_Analyzer(single.Face()).IsValid():
            return False
        pts = []
        walk = BRepTools_WireExplorer(wire, face)
        while walk.More():
            p = BRep_Tool.Pnt_s(walk.CurrentVertex())
            d = (p.X() - o.X(), p.Y() - o.Y(), p.Z() - o.Z())
            pts.append((d[0] * xd.X() + d[1] * xd.Y() + d[2] * xd.Z(), d[0] * yd.X() + d[1] * yd.Y() + d[2] * yd.Z()))
            walk.Next()
        if len(pts) < 3:
            return False
        if is_outer:
            outer_ring = pts
        else:
            rings.append(pts)
    if outer_ring is None:
        return False
    return bool(shapely.is_valid(shapely.Polygon(outer_ring, rings)))


def _edge_uses(shell):
    """How often OCCT's shell uses each of its edges, and the sum of their senses (+1, -1).

    A shell is closed when every edge bounds exactly two faces, and consistently
    oriented when they run it in opposite senses (the sum is 0). Read from OCCT's
    own topology of the file. ``BRepCheck_Shell.Orientation`` answers the same but
    grows with the square of the faces, minutes on a sheet's tens of thousands where
    this takes seconds (``docs/speed.md``).
    """
    from OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as ShapeMap
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FORWARD, TopAbs_REVERSED
    from OCP.TopExp import TopExp, TopExp_Explorer

    edges = ShapeMap()
    TopExp.MapShapes_s(shell, TopAbs_EDGE, edges)
    index, sense = [], []
    find, sign = edges.FindIndex, {TopAbs_FORWARD: 1, TopAbs_REVERSED: -1}.get
    # one explorer visits each face's edges in turn, their senses composed with the face's
    walk = TopExp_Explorer(shell, TopAbs_EDGE)
    while walk.More():
        edge = walk.Current()
        index.append(find(edge))
        sense.append(sign(edge.Orientation(), 0))
        walk.Next()
    n = edges.Extent() + 1
    count = np.bincount(np.asarray(index, np.int64), minlength=n)[1:]
    turn = np.bincount(np.asarray(index, np.int64), weights=np.asarray(sense, float), minlength=n)[1:]
    return count, turn


def check_solids(solids, *, volume: float, parts: int, name: str = "STEP file read back"):
    """Check solids read back from STEP: valid, closed, as many as expected, the mesh's volume.

    Each face is checked with ``BRepCheck_Analyzer`` (faces with more than
    ``BIG_FACE_WIRES`` wires wire by wire, see :func:`_big_face_valid`), each
    shell must be closed and consistently oriented (:func:`_edge_uses`), and OCCT's
    own volume of all solids (``BRepGProp``, as CAD programs report it) must be
    within ``STEP_VOLUME_TOLERANCE`` of ``volume``.
    Raises :class:`~fabtiles.FabricationError`.
    """
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    def fail(why):
        raise FabricationError(f"the {name} {why}; nothing was written")

    if len(solids) != parts:
        fail(f"holds {len(solids)} solids, not {parts}")
    total = 0.0
    for k, solid in enumerate(solids, 1):
        if solid is None or solid.IsNull():
            fail(f"has an empty solid ({k})")
        why = _shell_fault(solid, k) or _face_fault(solid, k)
        if why:
            fail(why)
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(solid, props)
        if not props.Mass() > 0:
            fail(f"has a solid of volume {props.Mass():.6g} mm^3 (solid {k}): inside out")
        total += props.Mass()
    if abs(total - volume) > STEP_VOLUME_TOLERANCE * abs(volume):
        fail(
            f"has a volume of {total:.6g} mm^3 (OCCT), not the mesh's {volume:.6g} mm^3 "
            f"({STEP_VOLUME_TOLERANCE:.2%} allowed)"
        )
    return total


def _shell_fault(solid, k: int) -> str | None:
    """What is wrong with the shells of solid number k (not one, open, oriented both ways), or None."""
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer

    shells = TopExp_Explorer(solid, TopAbs_SHELL)
    n_shells = 0
    while shells.More():
        n_shells += 1
        count, turn = _edge_uses(shells.Current())
        if np.any(count != 2):
            return f"has an open shell (solid {k})"
        if np.any(turn != 0):
            return f"has a shell with faces oriented both ways (solid {k})"
        shells.Next()
    return None if n_shells == 1 else f"has {n_shells} shells in solid {k}, not 1"


def _face_fault(solid, k: int) -> str | None:
    """Why solid number k has an invalid face by ``BRepCheck_Analyzer`` (see :func:`_big_face_valid`), or None."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    faces = TopExp_Explorer(solid, TopAbs_FACE)
    while faces.More():
        face = TopoDS.Face(faces.Current())
        # a face's children are its wires: only the few with many are counted
        big = face.NbChildren() > BIG_FACE_WIRES and len(_wires(face)) > BIG_FACE_WIRES
        if not big:
            _plane_pcurves(face)
        ok = _big_face_valid(face) if big else BRepCheck_Analyzer(face).IsValid()
        if not ok:
            return f"has an invalid face (solid {k}, BRepCheck_Analyzer)"
        faces.Next()
    return None


def check_step_file(path, *, volume: float, parts: int) -> float:
    """Read a written STEP file back with OCCT and check its solids (:func:`check_solids`); return OCCT's volume.

    The writer checks the B-rep in memory (:func:`~fabtiles.solid.brep.check_brep`);
    this is the independent check, for ``fabtiles check --deep`` and the tests.
    """
    return check_solids(read_step_solids(path), volume=volume, parts=parts, name=f"STEP file {str(path)!r}")


# --------------------------------------------------------------------------- writing


ARC_VOLUME_LIMIT = 0.005
"""Largest relative difference between the STEP's volume, its round walls true arcs, and the flattened
mesh's (0.5 %). Arcs recovered within a fine ``tolerance_mm`` stay far inside it (0.02 mm, the profiles'
default: 0.04 % on a 100 mm pierced circle tile, 0.17 % on the 3.3.3.4.4 sample as a 100 mm
pierced circle with round joins); a coarse one takes polygons for circles."""


def step_bytes(model, *, name: str = "tile") -> bytes:
    """The STEP file (AP214, mm) of a :class:`~fabtiles.solid.print_model.PrintModel`: planes and cylinders,
    one solid per piece, checked in memory (:func:`~fabtiles.solid.brep.check_brep`) before it is returned.

    A mosaic of several colours is an assembly of a product per part, in the 3MF's order
    and named as its parts (:attr:`~fabtiles.solid.print_model.PrintModel.breps`), each
    part's solids checked against its own mesh.

    Raises :class:`~fabtiles.ProfileError` when the printer profile's ``tolerance_mm`` is so coarse that
    the arcs found within it move the print's volume by more than :data:`ARC_VOLUME_LIMIT`.
    """
    breps = model.breps
    exact = volume = 0.0
    for label, (brep, mesh_volume, parts) in breps:
        what = "STEP solid" if label is None else f"STEP solid of part {label!r}"
        exact += check_brep(brep, volume=mesh_volume, parts=parts, what=what)
        volume += mesh_volume
    # the print's volume, not a part's: a small round face of a mosaic alone moves by more than the whole does
    if abs(exact - volume) > ARC_VOLUME_LIMIT * volume:
        tol = model.profile.tolerance_mm
        # the default where it is finer, else a quarter: holes thinned within 0.02 mm for the slicers can
        # differ from their arcs by more than the limit where there are many small ones
        finer = "0.02 (the default)" if tol > 0.02 else f"{tol / 4:g}"
        raise ProfileError(
            f"printer profile {model.profile.name!r}: tolerance_mm = {tol:g} mm is too coarse for the round "
            f"walls of this tile's STEP: the arcs found within it change the solid's volume by "
            f"{abs(exact - volume) / volume:.2%} (at most {ARC_VOLUME_LIMIT:.1%}); set printer.tolerance_mm "
            f"to {finer} or finer",
            param="tolerance_mm",
            key="printer.tolerance_mm",
        )
    # named parts make the file an assembly of them; else one product of the file's name
    labels = [label for label, _ in breps] if any(label is not None for label, _ in breps) else None
    return step_text([brep for _, (brep, _, _) in breps], name=name, labels=labels).encode("ascii")


def figures(model) -> dict:
    """What a STEP file adds to its model's report (a mosaic's parts' B-reps summed)."""
    breps = [b for _, b in model.breps]
    return dict(
        material=filament({"solid": sum(volume for _, volume, _ in breps)}, model.profile).as_stats(),
        style=model.stack.style,
        solids=sum(parts for _, _, parts in breps),
        volume_mm3=sum(brep_volume(brep) for brep, _, _ in breps),
        grid_mm=QUANTUM,
        faces=sum(len(brep.faces) for brep, _, _ in breps),
        cylinders=sum(f.radius > 0 for brep, _, _ in breps for f in brep.faces),
        edges=sum(len(brep.edges) for brep, _, _ in breps),
    )
