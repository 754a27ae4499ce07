"""3MF for slicers: one object whose parts each take their own filament.

A relief is one object of two parts, ``"base"`` and ``"pattern"`` (the pattern
standing on the base at ``z = base_mm``); a deboss tile with ``inlay=True`` is
one object of ``"plate"`` and ``"inlay"`` (the grooves filled flush). Every other
print is one object of one part. Parts touch without overlapping (see
:mod:`fabtiles.export.mesh`).

How the package is laid out, and why (read in PrusaSlicer's
``src/libslic3r/Format/3mf.cpp``, versions 2.5 and 2.9, and Bambu Studio's
``src/libslic3r/Format/bbs_3mf.cpp``, which OrcaSlicer shares; checked with
``prusa-slicer`` 2.5):

- PrusaSlicer makes every mesh object that a build item reaches its own object,
  also through ``<components>``: the core spec's assembly (one object whose
  components are the base and pattern meshes) loads in ``prusa-slicer --info`` as
  two objects (z 0..2 and 2..3.2 mm), and each is dropped to the bed, the pattern
  into the plate. It builds a multi-part object only from ONE mesh object whose
  triangles ``Metadata/Slic3r_PE_model.config`` splits into volumes by
  ``firstid``/``lastid`` (as it saves its own), each volume taking the contiguous
  range of vertices its triangles use. So the model holds one ``<object>`` with one
  ``<mesh>``: the first part's vertices and triangles, then the next part's, each
  part a closed shell of its own (no vertex shared between parts). That is plain
  core 3MF: a mesh of closed shells that touch.
- Bambu Studio and OrcaSlicer read ``Metadata/model_settings.config`` (written
  too, with the same parts) for the object's name and filament, but cut an object
  into parts only along ``<components>``; by their source they load this file as
  one object at full height with one part holding both shells (not run here). No
  one file serves both: they read the same build item, and the layout that makes
  parts for one makes separate objects for the other.

The package is three small XML texts and one mesh, written with the standard
library: trimesh writes neither the slicers' metadata nor several volumes in one
mesh, and lib3mf (a native library) would add a dependency for what one ``%``
over the whole vertex array does in 0.3 to 0.7 s on the 600 x 400 mm sheet
(154,000 vertices, 349,000 triangles, zip included; measured on a shared machine). Coordinates get 9 significant digits,
which read back as exactly the float32 values the mesh was checked with. Before
anything is written, the package is read back the way PrusaSlicer reads it
(volume ranges, float32 vertices) and each part must be the checked mesh, bit for
bit, or pass the checks again (watertight, consistently wound, of the expected
volume and body count).
"""

from __future__ import annotations

import io
import warnings
import zipfile
from typing import NamedTuple
from xml.sax.saxutils import quoteattr

import numpy as np

from .._errors import FabricationError
from .._io import atomic_write
from ._slicer_check import check_triangles
from .mesh import check_inlay, checked_parts, prepare_print, stack_stats

MODEL_PATH = "3D/3dmodel.model"
PRUSA_CONFIG_PATH = "Metadata/Slic3r_PE_model.config"
BAMBU_CONFIG_PATH = "Metadata/model_settings.config"

EXTRUDERS = {"base": 1, "pattern": 2, "plate": 1, "inlay": 2}
"""The filament (1-based extruder) each part is given; the user can change it in the slicer."""

_CORE_NS = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
_CONTENT_TYPES = """<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
 <Default Extension="config" ContentType="application/xml"/>
</Types>
"""
_RELS = """<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"""


class Part(NamedTuple):
    """One part of the object: its name, filament and mesh."""

    name: str
    extruder: int
    vertices: np.ndarray
    faces: np.ndarray


def _numbers(fmt: str, values: np.ndarray) -> str:
    """``fmt`` (one record) applied to every row of ``values`` in one ``%`` call."""
    if not len(values):
        return ""
    return (fmt * len(values)) % tuple(values.ravel().tolist())


def package_3mf(parts, *, name: str, application: str = "fabtiles") -> bytes:
    """The 3MF package (zip bytes) of one object made of ``parts``.

    Parameters
    ----------
    parts : sequence of Part
        Each part's vertices (float32-exact, mm) and faces; written in this order.
    name : str
        The object's name, as the slicer lists it.
    application : str
        The ``Application`` metadata of the model.

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> data = package_3mf([Part("a", 1, v, f), Part("b", 2, v + 1, f)], name="demo")
    >>> {k: (len(p.vertices), len(p.faces)) for k, p in read_3mf(data).items()}
    {'a': (4, 4), 'b': (4, 4)}
    """
    verts, faces, ranges = [], [], []
    nv = nt = 0
    for p in parts:
        verts.append(np.asarray(p.vertices, np.float64))
        faces.append(np.asarray(p.faces, np.int64) + nv)
        ranges.append((nt, nt + len(p.faces) - 1))
        nv += len(p.vertices)
        nt += len(p.faces)
    v = np.concatenate(verts).astype(np.float32).astype(np.float64) + 0.0  # -0.0 -> 0.0
    t = np.concatenate(faces)
    title = quoteattr(name)
    model = "".join([
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="millimeter" xml:lang="en-US" xmlns="{_CORE_NS}">\n',
        f' <metadata name="Application">{_text(application)}</metadata>\n',
        f' <metadata name="Title">{_text(name)}</metadata>\n',
        f' <resources>\n  <object id="1" type="model" name={title}>\n   <mesh>\n    <vertices>\n',
        _numbers('     <vertex x="%.9g" y="%.9g" z="%.9g"/>\n', v),
        '    </vertices>\n    <triangles>\n',
        _numbers('     <triangle v1="%d" v2="%d" v3="%d"/>\n', t),
        '    </triangles>\n   </mesh>\n  </object>\n </resources>\n',
        ' <build>\n  <item objectid="1"/>\n </build>\n</model>\n',
    ])
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        for arcname, text in (("[Content_Types].xml", _CONTENT_TYPES), ("_rels/.rels", _RELS),
                              (MODEL_PATH, model), (PRUSA_CONFIG_PATH, _prusa_config(parts, ranges, name)),
                              (BAMBU_CONFIG_PATH, _bambu_config(parts, ranges, name))):
            info = zipfile.ZipInfo(arcname, date_time=(1980, 1, 1, 0, 0, 0))  # same bytes every run
            info.compress_type = zipfile.ZIP_DEFLATED
            # level 1: the 600 x 400 mm sheet's model packs to 5.7 MB in 0.3 s; the default
            # level 6 gives 4.7 MB in 0.9 s (measured)
            zf.writestr(info, text.encode("utf-8"), compresslevel=1)
    return buf.getvalue()


def _text(s: str) -> str:
    return s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _prusa_config(parts, ranges, name) -> str:
    """PrusaSlicer's per-object config: the volumes as triangle ranges, named, with extruders."""
    out = ['<?xml version="1.0" encoding="UTF-8"?>\n<config>\n <object id="1" instances_count="1">\n',
           f'  <metadata type="object" key="name" value={quoteattr(name)}/>\n',
           '  <metadata type="object" key="extruder" value="1"/>\n']
    for p, (first, last) in zip(parts, ranges):
        out += [f'  <volume firstid="{first}" lastid="{last}">\n',
                f'   <metadata type="volume" key="name" value={quoteattr(p.name)}/>\n',
                '   <metadata type="volume" key="volume_type" value="ModelPart"/>\n',
                f'   <metadata type="volume" key="extruder" value="{p.extruder}"/>\n',
                '   <mesh edges_fixed="0" degenerate_facets="0" facets_removed="0" facets_reversed="0" '
                'backwards_edges="0"/>\n',
                '  </volume>\n']
    out.append(' </object>\n</config>\n')
    return "".join(out)


def _bambu_config(parts, ranges, name) -> str:
    """Bambu Studio / OrcaSlicer's model settings: the object and its parts, names and filaments."""
    out = ['<?xml version="1.0" encoding="UTF-8"?>\n<config>\n <object id="1">\n',
           f'  <metadata key="name" value={quoteattr(name)}/>\n',
           '  <metadata key="extruder" value="1"/>\n']
    for i, (p, (first, last)) in enumerate(zip(parts, ranges), start=1):
        out += [f'  <part id="{i}" subtype="normal_part" firstid="{first}" lastid="{last}">\n',
                f'   <metadata key="name" value={quoteattr(p.name)}/>\n',
                '   <metadata key="matrix" value="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/>\n',
                f'   <metadata key="extruder" value="{p.extruder}"/>\n',
                '   <mesh_stat edges_fixed="0" degenerate_facets="0" facets_removed="0" facets_reversed="0" '
                'backwards_edges="0"/>\n',
                '  </part>\n']
    out.append(' </object>\n</config>\n')
    return "".join(out)


# --------------------------------------------------------------------------- reading back


def _block(model: bytes, block: bytes, tag: bytes, fields: tuple, dtype) -> np.ndarray:
    """The numbers of every ``<tag f1="" f2="" f3=""/>`` in the model's ``<block>``, as an (n, 3) array.

    Our own record format is stripped with ``bytes.replace`` and the numbers parsed
    by numpy in one call: on the 600 x 400 mm sheet 0.3 s where a regular
    expression took 1.4 s (measured).
    """
    start, end = model.find(b"<" + block + b">"), model.find(b"</" + block + b">")
    if start < 0 or end < start:
        raise FabricationError(f"the 3MF model has no <{block.decode()}> block")
    text = model[start + len(block) + 2:end]
    records = text.count(b"<" + tag + b" ")
    text = text.replace(b"<" + tag + b" " + fields[0] + b'="', b" ")
    for f in fields[1:]:
        text = text.replace(b'" ' + f + b'="', b" ")
    text = text.replace(b'"/>', b" ")
    try:
        with warnings.catch_warnings():  # older numpy warns, and stops, where a number does not parse
            warnings.simplefilter("ignore", DeprecationWarning)
            values = np.fromstring(text, dtype=dtype, sep=" ")
    except ValueError:  # numpy 2.4 raises there
        values = np.empty(0)
    if len(values) != 3 * records:
        raise FabricationError(f"the 3MF model's <{tag.decode()}> records do not parse: {len(values)} numbers "
                               f"read for {records} records of 3")
    return values.reshape(-1, 3)


def read_3mf(source) -> dict:
    """The parts of a fabtiles 3MF, split as PrusaSlicer splits them.

    ``source`` is a path or the package bytes. The object's mesh is read with
    float32 coordinates (what slicers read); ``Metadata/Slic3r_PE_model.config``
    cuts its triangles into named volumes, each taking the contiguous range of
    vertices its triangles use. Returns a dict of name to :class:`Part` (faces
    indexing the part's own vertices). Reads the layout :func:`package_3mf`
    writes (attributes in its order), not every 3MF.
    """
    import xml.etree.ElementTree as ET

    data = source if isinstance(source, (bytes, bytearray)) else open(source, "rb").read()
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as zf:
            model = zf.read(MODEL_PATH)
            config = ET.fromstring(zf.read(PRUSA_CONFIG_PATH))
    except (zipfile.BadZipFile, KeyError, ET.ParseError) as exc:
        raise FabricationError(f"not a fabtiles 3MF package ({exc})") from None
    verts = _block(model, b"vertices", b"vertex", (b"x", b"y", b"z"), np.float32)
    tris = _block(model, b"triangles", b"triangle", (b"v1", b"v2", b"v3"), np.int64)
    parts = {}
    for vol in config.iter("volume"):
        first, last = int(vol.get("firstid")), int(vol.get("lastid"))
        meta = {m.get("key"): m.get("value") for m in vol.iter("metadata")}
        f = tris[first:last + 1]
        if not len(f) or last < first or last >= len(tris) or f.min() < 0 or f.max() >= len(verts):
            raise FabricationError(f"the 3MF volume {meta.get('name')!r} has an invalid triangle range "
                                   f"{first}..{last} ({len(tris)} triangles, {len(verts)} vertices)")
        lo, hi = int(f.min()), int(f.max())
        parts[meta.get("name", "")] = Part(meta.get("name", ""), int(meta.get("extruder", 0)),
                                           verts[lo:hi + 1], f - lo)
    return parts


# --------------------------------------------------------------------------- writer


def write_3mf(path, *, region, outline, profile, style=None, stroke=None, base_mm=None, relief_mm=None,
              pierced_mm=None, deboss_mm=None, inlay=False, name=None, dips=None):
    """Write a 3MF (unit millimetre) of the tile: one object of named parts, one filament each.

    Parameters as :func:`~fabtiles.export.mesh.write_stl`, plus:

    inlay : bool, optional
        Deboss only: a second part ``"inlay"`` filling the grooves flush with the
        plate's top (filament 2), for a two-colour inlay print.
    name : str, optional
        The object's name in the slicer (default: the file name without suffix).
    dips : shapely geometry, optional
        An interlaced relief's dipping under strands (see :mod:`fabtiles.export.layers`).

    A relief is parts ``"base"`` (filament 1) and ``"pattern"`` (filament 2);
    pierced is ``"pattern"``, deboss ``"plate"``. The package is read back as
    PrusaSlicer reads it and every part checked again before the file is written
    atomically; a bad mesh is a :class:`~fabtiles.FabricationError` and no file.

    Returns
    -------
    Report
    """
    heights = dict(base_mm=base_mm, relief_mm=relief_mm, pierced_mm=pierced_mm, deboss_mm=deboss_mm)
    profile, stack, report = prepare_print(region, outline, profile, style, heights, stroke, path=path, fmt="3mf")
    check_inlay(stack, inlay)
    checked = checked_parts(region, outline, stack, inlay=bool(inlay), dips=dips)
    parts = [Part(n, EXTRUDERS.get(n, 1) if len(checked) > 1 else 1, p.vertices, p.faces)
             for n, p in checked.items()]
    from .. import __version__

    title = name if name is not None else _stem(path)
    data = package_3mf(parts, name=title, application=f"fabtiles-{__version__}")
    back = read_3mf(data)
    if list(back) != list(checked):
        raise FabricationError(f"the 3MF package lost its part names (read back {list(back)}, wrote "
                               f"{list(checked)}); nothing was written")
    for n, p in back.items():
        c = checked[n]
        if not (np.array_equal(p.faces, c.faces) and np.array_equal(p.vertices, c.vertices.astype(np.float32))):
            # not the mesh that was checked: check what the slicer will read (this raises on a bad mesh)
            check_triangles(p.vertices[p.faces], name=n, volume=c.volume_mm3, bodies=c.bodies)
    atomic_write(path, data)
    allv = np.concatenate([p.vertices for p in checked.values()])
    report.stats.update(
        stack_stats(stack),
        bodies=list(checked),
        parts={n: {"extruder": p.extruder, "triangles": int(len(p.faces))} for n, p in zip(checked, parts)},
        triangles=int(sum(len(p.faces) for p in checked.values())),
        volume_mm3=float(sum(p.mesh_volume_mm3 for p in checked.values())),
        bounds_mm=[allv.min(axis=0).tolist(), allv.max(axis=0).tolist()],
    )
    return report


def _stem(path) -> str:
    from pathlib import Path

    return Path(str(path)).stem or "tile"

