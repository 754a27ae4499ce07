"""A planar B-rep written as a STEP file (ISO 10303-21, AP214, millimetres).

The entities are written as text, as the DXF writer writes its polylines. OCCT's
STEP writer costs the square of a face's edges, and a 200 x 200 mm relief tile's top
face alone has more than a thousand holes: through OCCT such a face took most of a
minute (``docs/speed.md``), where this writer takes well under a second for the whole
file. The B-rep is checked before it is written (:func:`fabtiles.solid.brep.check_brep`),
and ``fabtiles check --deep`` reads the file back with OCCT (:mod:`fabtiles.export.step`).

Each solid is a ``MANIFOLD_SOLID_BREP`` of one ``CLOSED_SHELL`` of
``ADVANCED_FACE``s on ``PLANE``s and ``CYLINDRICAL_SURFACE``s, bounded by
``EDGE_LOOP``s of ``EDGE_CURVE``s on ``LINE``s and ``CIRCLE``s: the entities every
STEP reader supports. An edge of a cylinder carries its curve in the cylinder's
parameters too (``SURFACE_CURVE`` with a ``PCURVE`` for each cylinder it bounds), as
OCCT's own writer does: its reader makes those curves for planes, not for cylinders. The output is byte-identical
for the same input: entities numbered in the order they are written, the header's
time stamp fixed (:data:`TIME_STAMP`).

>>> import shapely
>>> from fabtiles.solid._mesh_build import coverage
>>> from fabtiles.solid.brep import planar_brep
>>> text = step_text([planar_brep(coverage([(shapely.box(0, 0, 10, 10), 2.0)], bottom=0.0))], name="plate")
>>> text.count("ADVANCED_FACE("), text.count("MANIFOLD_SOLID_BREP(")
(6, 1)
"""

from __future__ import annotations

import re

import numpy as np

from ..solid.brep import Brep, seam_direction

TIME_STAMP = "2000-01-01T00:00:00"
"""The ``FILE_NAME`` time stamp of every STEP file (ISO 8601, as the standard asks): the same bytes every run."""


LENGTH_DECIMALS = 9
"""Decimals of every length and coordinate written (mm): a nanometre, a thousandth of the file's
``distance_accuracy_value`` (1e-6 mm), so rounding moves no vertex off its curve or surface as
OCCT measures them; shortest-repr doubles need up to 17 digits each, a larger file
(``docs/speed.md``)."""

DIRECTION_DECIMALS = 12
"""Decimals of the components of a direction: a unit vector's error of 1e-12 moves a point 2.4 m
away (the 2440 mm panel's side) by 2.4e-9 mm, still far inside the accuracy value."""


def _real(x: float, decimals: int = LENGTH_DECIMALS) -> str:
    """A STEP REAL rounded to ``decimals``: always with a decimal point, exponent as ``E``.

    >>> _real(84.41797125771316), _real(3.0), _real(-1e-12), _real(2.5e-10, 12)
    ('84.417971258', '3.', '0.', '2.5E-10')
    """
    # numpy's rounding, as _rows rounds a whole array (Python's round differs in the last digit at times)
    return _text(float(np.round(float(x), decimals)) + 0.0)  # + 0.0: no negative zero


def _text(x: float) -> str:
    """A STEP REAL of a Python float already rounded (:func:`_real`)."""
    s = repr(x)
    if "e" in s:
        mant, exp = s.split("e")
        if "." not in mant:
            mant += "."
        return f"{mant}E{exp}"
    return s[:-1] if s.endswith(".0") else s  # "3." is a STEP REAL, a byte shorter


def _triple(v, decimals: int = LENGTH_DECIMALS) -> str:
    return f"({_real(v[0], decimals)},{_real(v[1], decimals)},{_real(v[2], decimals)})"


_EXPONENT = re.compile(r"(\d+(?:\.\d+)?)e([-+]\d+)")


def _exponent(m) -> str:
    mant = m.group(1)
    return f"{mant if '.' in mant else mant + '.'}E{m.group(2)}"


def _rows(a, decimals: int, unit: bool = False) -> list:
    """Each row of ``a`` as a STEP list of REALs, ``(x,y,z)``, as :func:`_real` writes each number;
    ``unit``: the rows made unit vectors first.

    Rounded in one numpy pass and written by one ``repr`` of all the rows, the shortest text of
    each double as :func:`_real` has it: a sheet's tens of thousands of edges number by number
    cost more than the file's other entities.

    >>> _rows([[3.0, 4.0, 0.0]], 12, unit=True), _rows([[0.1 + 0.2, -0.0, 2e-5], [10.0, 1.0, 0.5]], 9)
    (['(0.6,0.8,0.)'], ['(0.3,0.,2.E-05)', '(10.,1.,0.5)'])
    """
    a = np.asarray(a, dtype=float).reshape(len(a), -1)
    if not len(a):
        return []
    if unit:
        a = a / np.sqrt(np.einsum("ij,ij->i", a, a))[:, None]
    r = np.ascontiguousarray(np.round(a, decimals) + 0.0)  # + 0.0: no negative zero
    if len(r) > 64:  # each row once: a wall's top and bottom edges have one direction (the sheet's half)
        keys = r.view(np.dtype((np.void, r.dtype.itemsize * r.shape[1]))).ravel()
        _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
        texts = _format_rows(r[first])
        return [texts[i] for i in inverse.ravel().tolist()]
    return _format_rows(r)


def _format_rows(r: np.ndarray) -> list:
    text = repr(r.tolist())[1:-1]
    text = text.replace(", ", ",").replace(".0,", ".,").replace(".0]", ".]")
    if "e" in text:
        text = _EXPONENT.sub(_exponent, text)
    return ["(" + row + ")" for row in text[1:-1].split("],[")]


def _name(text: str) -> str:
    """A STEP string: printable ASCII, quotes doubled."""
    clean = "".join(c if 32 <= ord(c) < 127 else "_" for c in text)
    return "'" + clean.replace("\\", "\\\\").replace("'", "''") + "'"


class _Writer:
    def __init__(self):
        self.lines = []
        self.directions = {}
        self.points = {}
        self.placements = {}
        self.vectors = {}
        self.context_2d = None

    def add(self, entity: str) -> int:
        self.lines.append(entity)
        return len(self.lines)

    def extend(self, entities: list) -> range:
        """Add many entities at once; their numbers."""
        first = len(self.lines) + 1
        self.lines.extend(entities)
        return range(first, len(self.lines) + 1)

    def direction(self, v) -> int:
        """A ``DIRECTION``: the unit vector along ``v``, one entity for each written (a wall's plane
        takes its bottom edge's direction, every vertical edge the one up). ``v`` may be its
        text already (:func:`_rows`, ``unit=True``)."""
        text = v if isinstance(v, str) else _rows([v], DIRECTION_DECIMALS, unit=True)[0]
        ref = self.directions.get(text)
        if ref is None:
            ref = self.directions[text] = self.add(f"DIRECTION('',{text})")
        return ref

    def vector(self, v, length: str) -> int:
        """A ``VECTOR`` along ``v`` (as :meth:`direction` takes it) of ``length`` (a STEP REAL): the
        vertical edges of one height share one."""
        text = v if isinstance(v, str) else _rows([v], DIRECTION_DECIMALS, unit=True)[0]
        ref = self.vectors.get((text, length))
        if ref is None:
            ref = self.vectors[(text, length)] = self.add(f"VECTOR('',#{self.direction(text)},{length})")
        return ref

    def point(self, p) -> int:
        """A 3D ``CARTESIAN_POINT``, one entity per point written: a vertex's point is also a wall
        plane's origin and a line's start, a circle's centre also its cylinder's (the entities
        a file holds are a third of its size). ``p`` may be its text already (:func:`_rows`)."""
        text = p if isinstance(p, str) else _triple(p)
        ref = self.points.get(text)
        if ref is None:
            ref = self.points[text] = self.add(f"CARTESIAN_POINT('',{text})")
        return ref

    def placement(self, origin, axis, ref_direction) -> int:
        """An ``AXIS2_PLACEMENT_3D``, shared by the entities that stand on the same one (a cylinder
        and the circle at its foot). Each part as :meth:`point` and :meth:`direction` take it."""
        key = (self.point(origin), self.direction(axis), self.direction(ref_direction))
        ref = self.placements.get(key)
        if ref is None:
            ref = self.placements[key] = self.add("AXIS2_PLACEMENT_3D('',#{},#{},#{})".format(*key))
        return ref


def _pcurve(w: _Writer, surface: int, face, start, arc) -> int:
    """The ``PCURVE`` of an edge of a cylinder face: a line in the cylinder's (angle, height).

    An edge's curve on each curved face it bounds is part of the B-rep: OCCT's STEP
    reader makes it for planes, not for cylinders (measured: without it every
    cylinder face read back without shape healing is invalid). A circle's angle
    starts where its cylinder's does (:func:`~fabtiles.solid.brep.seam_direction`), so its
    curve is ``(t, height)``; a vertical line's is ``(angle, height + t)``, both
    parametrised as their edge.
    """
    if w.context_2d is None:
        w.context_2d = w.add(
            "( GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() "
            "REPRESENTATION_CONTEXT('2D SPACE','') )"
        )
    ref = np.asarray(face.ref[:2], float)
    height = float(start[2] - face.origin[2])
    if arc[2] > 0:
        point, along = (0.0, height), (1.0, 0.0)
    else:
        d = np.asarray(start[:2], float) - face.origin[:2]
        angle = float(np.arctan2(ref[0] * d[1] - ref[1] * d[0], ref @ d)) % (2 * np.pi)
        point, along = (angle, height), (0.0, 1.0)
    p = w.point(f"({_real(point[0], DIRECTION_DECIMALS)},{_real(point[1])})")  # (angle, height): shared too
    vec = w.vector(along, "1.")
    line = w.add(f"LINE('',#{p},#{vec})")
    rep = w.add(f"DEFINITIONAL_REPRESENTATION('',(#{line}),#{w.context_2d})")
    return w.add(f"PCURVE('',#{surface},#{rep})")


def _brep_entities(w: _Writer, brep: Brep, name: str):
    """Write one B-rep's entities; return the entity numbers of its solids.

    In the order points, vertices, cylinders, edges, faces, solids: each entity
    refers only to entities before it.
    """
    cart = [w.point(t) for t in _rows(brep.points, LENGTH_DECIMALS)]
    vert = w.extend([f"VERTEX_POINT('',#{c})" for c in cart])
    # the cylinders first: their edges carry curves in their parameters (see _pcurves)
    surfaces, on_cylinders = _cylinder_surfaces(w, brep)
    edges = _edge_curves(w, brep, cart, vert, surfaces, on_cylinders)
    placed = _plane_placements(brep)
    faces = []
    for f, face in enumerate(brep.faces):
        surface = surfaces[f] if face.radius > 0 else w.add(f"PLANE('',#{w.placement(*placed[f])})")
        faces.append(_face_entity(w, face, surface, edges))
    solids = []
    for i, shell_faces in enumerate(brep.solids):
        shell = w.add("CLOSED_SHELL('',(" + ",".join(f"#{faces[f]}" for f in shell_faces) + "))")
        label = name if len(brep.solids) == 1 else f"{name}-{i + 1}"
        solids.append(w.add(f"MANIFOLD_SOLID_BREP({_name(label)},#{shell})"))
    return solids


def _cylinder_surfaces(w: _Writer, brep: Brep) -> tuple[dict, dict]:
    """Write the ``CYLINDRICAL_SURFACE`` of each cylinder face: ``(face -> entity, edge -> its cylinder faces)``."""
    surfaces: dict = {}
    on_cylinders: dict = {}
    for f, face in enumerate(brep.faces):
        if face.radius > 0:
            place = w.placement(face.origin, face.normal, face.ref)
            surfaces[f] = w.add(f"CYLINDRICAL_SURFACE('',#{place},{_real(face.radius)})")
            for e in face.loops[0]:
                on_cylinders.setdefault(e if e >= 0 else ~e, []).append(f)
    return surfaces, on_cylinders


def _edge_curves(w: _Writer, brep: Brep, cart, vert, surfaces: dict, on_cylinders: dict) -> list:
    """Write each edge's curve (a line or an arc of a circle) and its ``EDGE_CURVE``; return the latter.

    An edge of a cylinder face is a ``SURFACE_CURVE`` with its curve on each such
    face (:func:`_pcurve`).
    """
    pts = brep.points
    edges = []
    d = pts[brep.edges[:, 1]] - pts[brep.edges[:, 0]]
    units = _rows(d, DIRECTION_DECIMALS, unit=True)
    lengths = [t[1:-1] for t in _rows(np.sqrt(np.einsum("ij,ij->i", d, d))[:, None], LENGTH_DECIMALS)]
    arcs = brep.arc_rows()
    for i, ((a, b), unit, ln, arc) in enumerate(zip(brep.edges.tolist(), units, lengths, arcs, strict=True)):
        if arc[2] > 0:  # a counter-clockwise arc of a horizontal circle, its angle starting opposite its middle
            cx, cy, r = (float(v) for v in arc[:3])
            ref = (*seam_direction(pts[a, :2] - (cx, cy), float(arc[3])).tolist(), 0.0)
            place = w.placement((cx, cy, pts[a, 2]), (0.0, 0.0, 1.0), ref)
            curve = w.add(f"CIRCLE('',#{place},{_real(r)})")
        else:
            vec = w.vector(unit, ln)
            curve = w.add(f"LINE('',#{cart[a]},#{vec})")
        if i in on_cylinders:
            pcurves = [_pcurve(w, surfaces[f], brep.faces[f], pts[a], arc) for f in on_cylinders[i]]
            curve = w.add(f"SURFACE_CURVE('',#{curve},(" + ",".join(f"#{p}" for p in pcurves) + "),.CURVE_3D.)")
        edges.append(w.add(f"EDGE_CURVE('',#{vert[a]},#{vert[b]},#{curve},.T.)"))
    return edges


def _plane_placements(brep: Brep) -> dict:
    """Each plane face's placement as text, ``face -> (origin, normal, ref)``, the numbers of all in one pass each."""
    planes = [f for f, face in enumerate(brep.faces) if face.radius <= 0]
    if not planes:
        return {}
    origins = _rows([brep.faces[f].origin for f in planes], LENGTH_DECIMALS)
    normals = _rows([brep.faces[f].normal for f in planes], DIRECTION_DECIMALS, unit=True)
    refs = _rows([brep.faces[f].ref for f in planes], DIRECTION_DECIMALS, unit=True)
    return dict(zip(planes, zip(origins, normals, refs, strict=True), strict=True))


def _face_entity(w: _Writer, face, surface: int, edges: list) -> int:
    """Write a face's loops and its ``ADVANCED_FACE`` on ``surface``; return the face's entity."""
    bounds = []
    for i, loop in enumerate(face.loops):
        oes = w.extend(
            [
                f"ORIENTED_EDGE('',*,*,#{edges[e]},.T.)" if e >= 0 else f"ORIENTED_EDGE('',*,*,#{edges[~e]},.F.)"
                for e in loop
            ]
        )
        el = w.add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oes) + "))")
        kind = "FACE_OUTER_BOUND" if i == 0 else "FACE_BOUND"
        bounds.append(w.add(f"{kind}('',#{el},.T.)"))
    sense = ".F." if face.inward else ".T."  # a hole's wall faces its axis
    return w.add("ADVANCED_FACE('',(" + ",".join(f"#{b}" for b in bounds) + f"),#{surface},{sense})")


def _product(w: _Writer, name: str, pctx: int, dctx: int) -> tuple[int, int]:
    """Write a part's ``PRODUCT`` and its definition; return its ``PRODUCT_DEFINITION`` and its shape."""
    prod = w.add(f"PRODUCT({_name(name)},{_name(name)},'',(#{pctx}))")
    w.add(f"PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{prod}))")
    form = w.add(f"PRODUCT_DEFINITION_FORMATION('','',#{prod})")
    pdef = w.add(f"PRODUCT_DEFINITION('design','',#{form},#{dctx})")
    return pdef, w.add(f"PRODUCT_DEFINITION_SHAPE('','',#{pdef})")


def _brep_representation(name: str, axis: int, solids: list, ctx: int) -> str:
    """The ``ADVANCED_BREP_SHAPE_REPRESENTATION`` of ``solids``, placed by ``axis``."""
    return (
        f"ADVANCED_BREP_SHAPE_REPRESENTATION({_name(name)},(#{axis}," + ",".join(f"#{s}" for s in solids) + f"),#{ctx})"
    )


def _component(w: _Writer, k: int, label: str, solids: list, parent: tuple) -> None:
    """Write product ``label`` holding ``solids`` as the ``k``-th component of the assembly ``parent``
    (its definition, shape representation, placement and contexts), placed where it is modelled."""
    pdef, top, axis, pctx, dctx, ctx = parent
    part_def, part_shape = _product(w, label, pctx, dctx)
    rep = w.add(_brep_representation(label, axis, solids, ctx))
    w.add(f"SHAPE_DEFINITION_REPRESENTATION(#{part_shape},#{rep})")
    use = w.add(f"NEXT_ASSEMBLY_USAGE_OCCURRENCE('{k}',{_name(label)},'',#{pdef},#{part_def},$)")
    placed = w.add(f"PRODUCT_DEFINITION_SHAPE('Placement','Placement of an item',#{use})")
    moved = w.add(f"ITEM_DEFINED_TRANSFORMATION('','',#{axis},#{axis})")  # where it is: no move
    link = w.add(
        f"( REPRESENTATION_RELATIONSHIP('','',#{rep},#{top}) REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#{moved}) "
        "SHAPE_REPRESENTATION_RELATIONSHIP() )"
    )
    w.add(f"CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#{link},#{placed})")


def step_text(breps, *, name: str = "tile", labels=None) -> str:
    """The STEP file (AP214, mm) of one product holding the solids of ``breps``.

    With ``labels`` (one per B-rep), an assembly: the product ``name`` made of one
    product per B-rep, named by its label and holding its solids (a mosaic's parts,
    one per colour: OCCT-based CAD shows each by its name). Each solid is named by its
    B-rep's label (default ``name``), ``<label>-<k>`` when its B-rep has several.
    """
    w = _Writer()
    app = w.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')")
    w.add(f"APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})")
    pctx = w.add(f"PRODUCT_CONTEXT('',#{app},'mechanical')")
    dctx = w.add(f"PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')")
    pdef, pshape = _product(w, name, pctx, dctx)
    mm = w.add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )")
    rad = w.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )")
    sr = w.add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )")
    unc = w.add(
        f"UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-06),#{mm},'distance_accuracy_value','confusion accuracy')"
    )
    ctx = w.add(
        f"( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc})) "
        f"GLOBAL_UNIT_ASSIGNED_CONTEXT((#{mm},#{rad},#{sr})) REPRESENTATION_CONTEXT('','3D') )"
    )
    axis = w.placement((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    if labels is None:
        solids = []
        for brep in breps:
            solids.extend(_brep_entities(w, brep, name))
        rep = w.add(_brep_representation(name, axis, solids, ctx))
        w.add(f"SHAPE_DEFINITION_REPRESENTATION(#{pshape},#{rep})")
    else:
        top = w.add(f"SHAPE_REPRESENTATION({_name(name)},(#{axis}),#{ctx})")
        w.add(f"SHAPE_DEFINITION_REPRESENTATION(#{pshape},#{top})")
        for k, (brep, label) in enumerate(zip(breps, labels, strict=True), 1):
            _component(w, k, label, _brep_entities(w, brep, label), (pdef, top, axis, pctx, dctx, ctx))
    head = (
        "ISO-10303-21;\nHEADER;\n"
        f"FILE_DESCRIPTION(({_name('fabtiles tile')}),'2;1');\n"
        f"FILE_NAME({_name(name + '.step')},{_name(TIME_STAMP)},(''),(''),'fabtiles','fabtiles','');\n"
        "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
    )
    body = "\n".join([f"#{i}={line};" for i, line in enumerate(w.lines, 1)])
    return head + body + "\nENDSEC;\nEND-ISO-10303-21;\n"
