"""3MF for slicers: one object whose parts each take their own filament.

A relief is one object of two parts, ``"base"`` and ``"pattern"`` (the pattern
standing on the base at ``z = base_mm``); a deboss tile with ``inlay=True`` is
one object of ``"plate"`` and ``"inlay"`` (the grooves filled flush). Every other
print is one object of one part. Parts touch without overlapping (see
:mod:`fabtiles.solid.parts`). The package holds any number of parts, 1 to
:data:`MAX_EXTRUDERS`, each on its own extruder (a print of N colours: N parts on
extruders 1..N); names are free text, escaped.

No display colours are written (no ``<basematerials>``, no ``m:colorgroup``): Bambu
Studio's and OrcaSlicer's own importer (``bbs_3mf.cpp``, the components layout's
reader) numbers the distinct colours of ``m:colorgroup`` 1, 2, ... and sets each
object's extruder from its ``pid``, and adds a filament per new colour, so colours
would decide the extruders there instead of the file's; with no command line to
measure that here, the file keeps one source of extruders (docs/slicers.md, "N colours").

How the package is laid out, and why. Two layouts, because the slicers' readers
disagree on what a part is; each is read by the programs named, as their source
states (PrusaSlicer 2.9 at 69c8e569 and Debian's 2.5, run here; Bambu Studio and
OrcaSlicer read only, no command line here; Cura's ``plugins/3MFReader`` 4.13 and
libSavitar, run here through Debian's ``python3-savitar``):

``layout="volumes"`` (default): PrusaSlicer, Bambu Studio, OrcaSlicer.
  One ``<object>`` with one ``<mesh>``: the first part's vertices and triangles,
  then the next part's, each part a closed shell of its own (no vertex shared
  between parts), plain core 3MF.

  - PrusaSlicer (``src/libslic3r/Format/3mf.cpp``, ``_load_model_from_file`` and
    ``_generate_volumes``) builds a multi-part object only from ONE mesh object whose
    triangles ``Metadata/Slic3r_PE_model.config`` splits into volumes by
    ``firstid``/``lastid``, each volume taking the contiguous range of vertices its
    triangles use and its ``name``, ``volume_type`` and ``extruder``. Every mesh
    object a build item reaches through ``<components>`` becomes an object of its
    own instead. Its ``_handle_end_metadata`` parses a version from an
    ``Application`` value that starts with ``PrusaSlicer-`` (its own files); any
    other value is ignored.
  - Bambu Studio and OrcaSlicer: ``Model::read_from_archive``
    (``src/libslic3r/Model.cpp``) sends a ``.3mf`` to their copy of PrusaSlicer's
    importer (``load_3mf``) when ``PrusaFileParser::check_3mf_from_prusa``
    (``src/libslic3r/Format/3mf.cpp``) is true: the package has no
    ``3D/_rels/3dmodel.model.rels`` and the text of a ``metadata`` whose name holds
    ``Application`` contains ``PrusaSlicer`` (case-sensitive substring). Otherwise
    their own importer (``load_bbs_3mf``, ``bbs_3mf.cpp``) reads it, which makes
    parts only of ``<components>``: a file called ``fabtiles-0.1.0`` stayed one
    part. So ``Application`` is ``fabtiles <version> (PrusaSlicer 3MF)``
    (:func:`application_name`, :func:`takes_prusa_path`): honest, and not
    ``PrusaSlicer-...``, from which PrusaSlicer would parse a version. Their copy
    reads ``Slic3r_PE_model.config`` alone (not ``Slic3r_PE.config``), keeps the
    volume keys ``name``, ``volume_type``, ``extruder`` (a whitelist), and adds
    filaments up to the largest ``extruder`` (OrcaSlicer's ``Plater::priv::load_files``,
    which says it loads "geometry data only"). The build item has no transform: with
    no ``slic3rpe:Version3mf`` both importers give a lone instance's transform to
    the first volume only.

``layout="components"``: UltiMaker Cura; Bambu Studio, OrcaSlicer.
  Each part its own mesh object (ids 1..k, ``cura:extruder_nr`` 0, 1, ... in its
  ``<metadatagroup>``), one object k+1 of ``<components>`` (no ``p:path``, no
  transform), one build item; no PrusaSlicer config.

  - Cura's ``ThreeMFReader._read`` hands ``3D/3dmodel.model`` alone to libSavitar,
    whose ``ThreeMFParser`` makes one scene node per build item with one child per
    component, its settings from the object's metadata (the ``cura:`` prefix
    stripped); ``_convertSavitarNodeToUMNode`` makes a mesh-less node with children
    a group and gives each child the extruder of its ``extruder_nr``. One mesh of
    several shells would be one single-extruder object.
  - Bambu Studio and OrcaSlicer's own importer resolves components within the model
    file and makes one object of one part per component; ``Metadata/model_settings.config``
    names them: ``<object id>`` the build item's object, ``<part id>`` the
    component's ``objectid``, with ``name`` and ``extruder`` (a ``<part>`` carrying
    ``lastid`` would no longer match its mesh, so none is written).
  - PrusaSlicer opens it as one object per part (its GUI asks whether to make them
    one multi-part object).

The package is a few small XML texts and the meshes, written with the standard
library: trimesh writes neither the slicers' metadata nor several volumes in one
mesh, and lib3mf (a native library, which the tests use as the strict reader) would add a dependency for what one ``%``
over the whole vertex array does (``docs/speed.md``). Coordinates get 9 significant digits,
which read back as exactly the float32 values the mesh was checked with (9 significant
digits round-trip any float32; ``tests/export/test_3mf.py`` proves it for random values
and reads every part of real packages back bit for bit), so the package holds the checked
meshes and the export does not read its own package back (that read-back was about half
of a sheet's 3MF). ``read_3mf`` reads a package the way the
slicers read it (volume ranges or components, float32 vertices), for the tests.
"""

from __future__ import annotations

import io
import re
import warnings
import zipfile
from typing import NamedTuple
from xml.sax.saxutils import quoteattr

import numpy as np

from ..core.errors import FabricationError, ParameterError
from ..core.files import zip_entry
from ..geometry.material import filament
from ._text import escape

MAX_EXTRUDERS = 16
"""The most extruders a package may name: Bambu Studio and OrcaSlicer add filaments up to a file's
highest extruder but stop at 16 (``Plater::priv::load_files``), so a part on a higher one has none."""

LAYOUTS = ("volumes", "components")
"""The 3MF layouts: PrusaSlicer's volumes (default) or the core spec's components (Cura)."""

MODEL_PATH = "3D/3dmodel.model"
PRUSA_CONFIG_PATH = "Metadata/Slic3r_PE_model.config"
BAMBU_CONFIG_PATH = "Metadata/model_settings.config"

_CORE_NS = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
_CURA_NS = "http://software.ultimaker.com/xml/cura/3mf/2015/10"
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


def application_name(layout: str, version: str) -> str:
    """The model's ``Application`` metadata for ``layout``.

    The volumes layout must contain ``PrusaSlicer`` (so that Bambu Studio and
    OrcaSlicer read it with their PrusaSlicer importer, the only one of theirs that
    reads volumes) and must not start with ``PrusaSlicer-`` (PrusaSlicer would parse
    a version of its own from what follows). The components layout names fabtiles
    alone, so that they read it with their own importer, which reads components.

    >>> application_name("volumes", "0.2.0")
    'fabtiles 0.2.0 (PrusaSlicer 3MF)'
    >>> application_name("components", "0.2.0")
    'fabtiles 0.2.0'
    """
    return f"fabtiles {version} (PrusaSlicer 3MF)" if layout == "volumes" else f"fabtiles {version}"


def takes_prusa_path(files: dict) -> bool:
    """Whether Bambu Studio and OrcaSlicer read a package with their PrusaSlicer importer.

    ``files`` maps the package's names to their bytes. The rule their
    ``PrusaFileParser::check_3mf_from_prusa`` (src/libslic3r/Format/3mf.cpp) applies,
    as that source states it: no ``3D/_rels/3dmodel.model.rels`` in the package, and
    the model's ``Application`` metadata containing ``PrusaSlicer``.

    >>> takes_prusa_path({MODEL_PATH: b'<metadata name="Application">fabtiles 1 (PrusaSlicer 3MF)</metadata>'})
    True
    >>> takes_prusa_path({MODEL_PATH: b'<metadata name="Application">fabtiles 1</metadata>'})
    False
    """
    if "3D/_rels/3dmodel.model.rels" in files:
        return False
    m = re.search(rb'<metadata name="Application">([^<]*)</metadata>', files.get(MODEL_PATH, b""))
    return m is not None and b"PrusaSlicer" in m.group(1)


def _numbers(fmt: str, values: np.ndarray) -> str:
    """``fmt`` (one record) applied to every row of ``values`` in one ``%`` call."""
    if not len(values):
        return ""
    return (fmt * len(values)) % tuple(values.ravel().tolist())


def _mesh_xml(vertices: np.ndarray, faces: np.ndarray, indent: str) -> list:
    """A ``<mesh>`` element's text: float32-exact vertices with 9 significant digits, then triangles."""
    return [
        f"{indent}<mesh>\n{indent} <vertices>\n",
        _numbers(f'{indent}  <vertex x="%.9g" y="%.9g" z="%.9g"/>\n', vertices),
        f"{indent} </vertices>\n{indent} <triangles>\n",
        _numbers(f'{indent}  <triangle v1="%d" v2="%d" v3="%d"/>\n', faces),
        f"{indent} </triangles>\n{indent}</mesh>\n",
    ]


def _exact(vertices) -> np.ndarray:
    """Float32 values as float64, ``-0.0`` made ``0.0`` (what the file's text reads back as)."""
    return np.asarray(vertices, np.float64).astype(np.float32).astype(np.float64) + 0.0


def package_3mf(parts, *, name: str, application: str = "fabtiles", layout: str = "volumes") -> bytes:
    """The 3MF package (zip bytes) of one object made of ``parts``.

    Parameters
    ----------
    parts : sequence of Part
        Each part's vertices (float32-exact, mm) and faces; written in this order.
    name : str
        The object's name, as the slicer lists it.
    application : str
        The ``Application`` metadata of the model (see :func:`application_name`).
    layout : {"volumes", "components"}
        ``"volumes"``: one mesh object, cut into parts by the triangle ranges of
        ``Metadata/Slic3r_PE_model.config`` (PrusaSlicer, and Bambu Studio and
        OrcaSlicer through their PrusaSlicer importer). ``"components"``: each part
        its own mesh object with ``cura:extruder_nr`` metadata, one object of
        ``<components>`` (UltiMaker Cura; Bambu Studio and OrcaSlicer).

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> for layout in LAYOUTS:
    ...     data = package_3mf([Part("a", 1, v, f), Part("b", 2, v + 1, f)], name="demo", layout=layout)
    ...     print(layout, {k: (p.extruder, len(p.vertices), len(p.faces)) for k, p in read_3mf(data).items()})
    volumes {'a': (1, 4, 4), 'b': (2, 4, 4)}
    components {'a': (1, 4, 4), 'b': (2, 4, 4)}
    """
    check_layout(layout)
    _check_parts(parts)
    head = [
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="millimeter" xml:lang="en-US" xmlns="{_CORE_NS}"'
        + (f' xmlns:cura="{_CURA_NS}"' if layout == "components" else "")
        + ">\n",
        f' <metadata name="Application">{escape(application)}</metadata>\n',
        f' <metadata name="Title">{escape(name)}</metadata>\n',
        " <resources>\n",
    ]
    if layout == "volumes":
        body, files = _volumes(parts, name)
    else:
        body, files = _components(parts, name)
    model = "".join(head + body)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        for arcname, text in (
            ("[Content_Types].xml", _CONTENT_TYPES),
            ("_rels/.rels", _RELS),
            (MODEL_PATH, model),
            *files,
        ):
            info = zip_entry(arcname)  # dated 1980-01-01: the same bytes every run
            # level 1: the default level 6 packs a fifth smaller in three times as long
            # (docs/speed.md)
            zf.writestr(info, text.encode("utf-8"), compresslevel=1)
    return buf.getvalue()


def _check_parts(parts) -> None:
    """A :class:`~fabtiles.ParameterError` unless there are parts, each on an extruder 1..MAX_EXTRUDERS."""
    if not len(parts):
        raise ParameterError("a 3MF needs at least one part, got none: give the print model's parts", param="parts")
    for p in parts:
        e = p.extruder
        if isinstance(e, bool) or not isinstance(e, (int, np.integer)) or not 1 <= e <= MAX_EXTRUDERS:
            raise ParameterError(
                f"part {p.name!r} has extruder={e!r}, must be an integer from 1 to "
                f"{MAX_EXTRUDERS} (Bambu Studio and OrcaSlicer add filaments up to 16 only): "
                "merge colours so that "
                f"at most {MAX_EXTRUDERS} remain",
                param="extruder",
            )


def _volumes(parts, name):
    """One mesh object of every part's shells in turn; the two configs' triangle ranges name the parts."""
    verts, faces, ranges = [], [], []
    nv = nt = 0
    for p in parts:
        verts.append(np.asarray(p.vertices, np.float64))
        faces.append(np.asarray(p.faces, np.int64) + nv)
        ranges.append((nt, nt + len(p.faces) - 1))
        nv += len(p.vertices)
        nt += len(p.faces)
    body = [
        f'  <object id="1" type="model" name={quoteattr(name)}>\n',
        *_mesh_xml(_exact(np.concatenate(verts)), np.concatenate(faces), "   "),
        "  </object>\n </resources>\n",
        # no transform: their importers give a lone instance's transform to the first volume only
        ' <build>\n  <item objectid="1"/>\n </build>\n</model>\n',
    ]
    return body, (
        (PRUSA_CONFIG_PATH, _prusa_config(parts, ranges, name)),
        (BAMBU_CONFIG_PATH, _bambu_config(parts, ranges, name)),
    )


def _components(parts, name):
    """Each part its own mesh object (ids 1..k, Cura's extruder on each), then object k+1 of components."""
    body = []
    for i, p in enumerate(parts, start=1):
        body += [
            f'  <object id="{i}" type="model" name={quoteattr(p.name)}>\n',
            "   <metadatagroup>\n",
            # Cura's extruders count from 0, the slicers' filaments from 1
            f'    <metadata name="cura:extruder_nr" preserve="1" type="xs:string">{p.extruder - 1}</metadata>\n',
            "   </metadatagroup>\n",
            *_mesh_xml(_exact(p.vertices), np.asarray(p.faces, np.int64), "   "),
            "  </object>\n",
        ]
    k = len(parts) + 1
    body += [
        f'  <object id="{k}" type="model" name={quoteattr(name)}>\n   <components>\n',
        *(f'    <component objectid="{i}"/>\n' for i in range(1, k)),
        "   </components>\n  </object>\n </resources>\n",
        f' <build>\n  <item objectid="{k}"/>\n </build>\n</model>\n',
    ]
    return body, ((BAMBU_CONFIG_PATH, _bambu_components_config(parts, name)),)


def _prusa_config(parts, ranges, name) -> str:
    """PrusaSlicer's per-object config: the volumes as triangle ranges, named, with extruders."""
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>\n<config>\n <object id="1" instances_count="1">\n',
        f'  <metadata type="object" key="name" value={quoteattr(name)}/>\n',
        '  <metadata type="object" key="extruder" value="1"/>\n',
    ]
    for p, (first, last) in zip(parts, ranges, strict=True):
        out += [
            f'  <volume firstid="{first}" lastid="{last}">\n',
            f'   <metadata type="volume" key="name" value={quoteattr(p.name)}/>\n',
            '   <metadata type="volume" key="volume_type" value="ModelPart"/>\n',
            f'   <metadata type="volume" key="extruder" value="{p.extruder}"/>\n',
            '   <mesh edges_fixed="0" degenerate_facets="0" facets_removed="0" facets_reversed="0" '
            'backwards_edges="0"/>\n',
            "  </volume>\n",
        ]
    out.append(" </object>\n</config>\n")
    return "".join(out)


def _bambu_part(part_id, p, extra: str = "") -> list:
    return [
        f'  <part id="{part_id}" subtype="normal_part"{extra}>\n',
        f'   <metadata key="name" value={quoteattr(p.name)}/>\n',
        '   <metadata key="matrix" value="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/>\n',
        f'   <metadata key="extruder" value="{p.extruder}"/>\n',
        '   <mesh_stat edges_fixed="0" degenerate_facets="0" facets_removed="0" facets_reversed="0" '
        'backwards_edges="0"/>\n',
        "  </part>\n",
    ]


def _bambu_config(parts, ranges, name) -> str:
    """Bambu Studio / OrcaSlicer's model settings: the object and its parts, names and filaments."""
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>\n<config>\n <object id="1">\n',
        f'  <metadata key="name" value={quoteattr(name)}/>\n',
        '  <metadata key="extruder" value="1"/>\n',
    ]
    for i, (p, (first, last)) in enumerate(zip(parts, ranges, strict=True), start=1):
        out += _bambu_part(i, p, f' firstid="{first}" lastid="{last}"')
    out.append(" </object>\n</config>\n")
    return "".join(out)


def _bambu_components_config(parts, name) -> str:
    """The model settings of the components layout: the assembly (id k+1), each part by its object's id."""
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>\n<config>\n',
        f' <object id="{len(parts) + 1}">\n',
        f'  <metadata key="name" value={quoteattr(name)}/>\n',
        '  <metadata key="extruder" value="1"/>\n',
    ]
    for i, p in enumerate(parts, start=1):
        out += _bambu_part(i, p)
    out.append(" </object>\n</config>\n")
    return "".join(out)


# --------------------------------------------------------------------------- reading back


def _block(model: bytes, block: bytes, tag: bytes, fields: tuple, dtype) -> np.ndarray:
    """The numbers of every ``<tag f1="" f2="" f3=""/>`` in the model's ``<block>``, as an (n, 3) array.

    Our own record format is stripped with ``bytes.replace`` and the numbers parsed
    by numpy in one call, several times quicker than a regular expression.
    """
    start, end = model.find(b"<" + block + b">"), model.find(b"</" + block + b">")
    if start < 0 or end < start:
        raise FabricationError(f"the 3MF model has no <{block.decode()}> block")
    text = model[start + len(block) + 2 : end]
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
        raise FabricationError(
            f"the 3MF model's <{tag.decode()}> records do not parse: {len(values)} numbers "
            f"read for {records} records of 3"
        )
    return values.reshape(-1, 3)


def read_3mf(source) -> dict:
    """The parts of a fabtiles 3MF, split as the slicers split them.

    ``source`` is a path or the package bytes. Vertices are read as float32 (what
    slicers read). In the volumes layout ``Metadata/Slic3r_PE_model.config`` cuts
    the one object's triangles into named volumes, each taking the contiguous range
    of vertices its triangles use (as PrusaSlicer does); in the components layout
    each component of the build item's object is a part, its extruder the object's
    ``cura:extruder_nr`` plus one. Returns a dict of name to :class:`Part` (faces
    indexing the part's own vertices). Reads the layouts :func:`package_3mf`
    writes (attributes in its order), not every 3MF.
    """
    model, config = _package_parts(source)
    if config is None:
        return _read_components(model)
    return _read_volumes(model, config)


def _package_parts(source):
    """``(model bytes, PrusaSlicer config element or None)`` of a 3MF package, a path or its bytes."""
    import xml.etree.ElementTree as ET

    data = source if isinstance(source, (bytes, bytearray)) else open(source, "rb").read()
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as zf:
            model = zf.read(MODEL_PATH)
            names = set(zf.namelist())
            config = ET.fromstring(zf.read(PRUSA_CONFIG_PATH)) if PRUSA_CONFIG_PATH in names else None
    except (zipfile.BadZipFile, KeyError, ET.ParseError) as exc:
        raise FabricationError(f"not a fabtiles 3MF package ({exc})") from None
    return model, config


def _read_volumes(model: bytes, config) -> dict:
    """The volumes layout's parts: the one object's triangles cut into the config's named volumes."""
    verts = _block(model, b"vertices", b"vertex", (b"x", b"y", b"z"), np.float32)
    tris = _block(model, b"triangles", b"triangle", (b"v1", b"v2", b"v3"), np.int64)
    parts = {}
    for vol in config.iter("volume"):
        first, last = int(vol.get("firstid", "")), int(vol.get("lastid", ""))
        meta = {m.get("key"): m.get("value") for m in vol.iter("metadata")}
        f = tris[first : last + 1]
        if not len(f) or last < first or last >= len(tris) or f.min() < 0 or f.max() >= len(verts):
            raise FabricationError(
                f"the 3MF volume {meta.get('name')!r} has an invalid triangle range "
                f"{first}..{last} ({len(tris)} triangles, {len(verts)} vertices)"
            )
        lo, hi = int(f.min()), int(f.max())
        parts[meta.get("name") or ""] = Part(
            meta.get("name") or "", int(meta.get("extruder") or 0), verts[lo : hi + 1], f - lo
        )
    return parts


_OBJECT = re.compile(rb'<object id="(\d+)" type="model" name=("[^"]*"|\'[^\']*\')>')
_EXTRUDER = re.compile(rb'<metadata name="cura:extruder_nr"[^>]*>(\d+)</metadata>')


def _object_bodies(model: bytes) -> dict:
    """``{object id: (name, its text)}`` of the model's objects."""
    from xml.sax.saxutils import unescape

    bodies = {}
    for m in _OBJECT.finditer(model):
        end = model.find(b"</object>", m.end())
        bodies[int(m.group(1))] = (unescape(m.group(2)[1:-1].decode("utf-8"), {"&quot;": '"'}), model[m.end() : end])
    return bodies


def _read_components(model: bytes) -> dict:
    """The components layout's parts: the mesh objects that the build item's object is made of."""
    bodies = _object_bodies(model)
    item = re.search(rb'<item objectid="(\d+)"', model)
    if item is None or int(item.group(1)) not in bodies:
        raise FabricationError("the 3MF model has no build item naming one of its objects")
    ids = [int(i) for i in re.findall(rb'<component objectid="(\d+)"', bodies[int(item.group(1))][1])]
    if not ids or any(i not in bodies for i in ids):
        raise FabricationError(
            f"the 3MF build object's components {ids} are not objects of the model (objects {sorted(bodies)})"
        )
    parts = {}
    for i in ids:
        name, text = bodies[i]
        nr = _EXTRUDER.search(text)
        verts = _block(text, b"vertices", b"vertex", (b"x", b"y", b"z"), np.float32)
        faces = _block(text, b"triangles", b"triangle", (b"v1", b"v2", b"v3"), np.int64)
        if len(faces) and (faces.min() < 0 or faces.max() >= len(verts)):
            raise FabricationError(f"the 3MF object {name!r} has triangles indexing past its {len(verts)} vertices")
        parts[name] = Part(name, int(nr.group(1)) + 1 if nr else 0, verts, faces)
    return parts


# --------------------------------------------------------------------------- writer


def check_layout(layout) -> str:
    """``layout`` if it is one of :data:`LAYOUTS`, else a :class:`~fabtiles.ParameterError` listing them."""
    if layout not in LAYOUTS:
        raise ParameterError(
            f"layout={layout!r} is not a valid 3MF layout, must be one of: {', '.join(LAYOUTS)}", param="layout"
        )
    return layout


def model_3mf_bytes(model, *, name: str = "tile", layout: str = "volumes") -> bytes:
    """The 3MF package of a :class:`~fabtiles.solid.print_model.PrintModel`: one object of its parts.

    Each part is its checked mesh (:class:`~fabtiles.solid.parts.CheckedPart`),
    written float32-exact, so the slicer reads the mesh that was checked.
    """
    from .. import __version__

    check_layout(layout)
    parts = [Part(n, p.material, p.mesh.vertices, p.mesh.faces) for n, p in model.parts.items()]
    return package_3mf(parts, name=name, application=application_name(layout, __version__), layout=layout)


def figures(model, *, layout: str = "volumes") -> dict:
    """What a 3MF adds to its model's report: its parts and their filaments, triangles, volume, bounds."""
    checked = model.parts
    allv = np.concatenate([p.mesh.vertices for p in checked.values()])
    return dict(
        model.stats(),
        bodies=list(checked),
        parts={n: {"extruder": p.material, "triangles": len(p.mesh.faces)} for n, p in checked.items()},
        layout=layout,
        triangles=int(sum(len(p.mesh.faces) for p in checked.values())),
        volume_mm3=float(sum(p.mesh.mesh_volume_mm3 for p in checked.values())),
        material=filament({n: p.mesh.mesh_volume_mm3 for n, p in checked.items()}, model.profile).as_stats(),
        bounds_mm=[allv.min(axis=0).tolist(), allv.max(axis=0).tolist()],
    )
