"""Laser DXF: closed polylines on one layer per operation, millimetres, inner cuts first.

The file imports into LightBurn, RDWorks, LaserGRBL or a CAM package as is:
``$INSUNITS`` = 4 (mm), closed LWPOLYLINEs (DXF R2000 and later) or closed R12
POLYLINEs (``dxf_version="R12"``, for old laser software; the version is the file's
option, :class:`~fabtiles.export.formats.FileOptions`, the cutter profile's by default), no SPLINEs, no loose
LINEs, no repeated points. Curves are arcs: a polyline's arc is a bulge on the vertex
it leaves from (group code 42, ``tan(sweep / 4)``, at most a half turn each), as AutoCAD
writes them; CAM turns each into one G2/G3 move (:mod:`fabtiles.geometry.arcs` finds them). Layers and ACI colours
come from the profile; each
entity also carries its layer's colour explicitly, for programs that ignore layers.
Entity order is cut order: score paths, inner contours, outer contours (see
:mod:`fabtiles.geometry.contours`).

The same plan gives the same bytes, run after run and process after process: the
header's dates are 2000-01-01, its GUIDs are derived from the file's content,
handles are numbered from the same seed and the CLASSES come in a fixed order
(see :func:`_fixed_metadata` and :func:`_register_classes`).

ezdxf is imported when a file is written, not when fabtiles is imported.
"""

from __future__ import annotations

import threading
from contextlib import contextmanager

from ..geometry.cut_plan import CutPlan
from .formats import check_dxf_version


def version_of(plan: CutPlan, dxf_version: str | None = None) -> str:
    """The DXF version a file of ``plan`` is written in: ``dxf_version`` checked, else the cutter profile's."""
    return check_dxf_version(dxf_version) or plan.profile.dxf_version


def figures(plan: CutPlan, *, dxf_version: str | None = None) -> dict:
    """What a DXF adds to its plan's report: its version."""
    return {"dxf_version": version_of(plan, dxf_version)}


def dxf_bytes(plan: CutPlan, *, dxf_version: str | None = None) -> bytes:
    """The DXF file of ``plan`` in ``dxf_version`` (default: the cutter profile's), as bytes to write."""
    text, encoding = dxf_text(plan, dxf_version=dxf_version)
    return text.encode(encoding, errors="dxfreplace")


def build_document(job: CutPlan, *, dxf_version: str | None = None, entities: bool = True):
    """The ezdxf document of a :class:`~fabtiles.geometry.cut_plan.CutPlan` in ``dxf_version``
    (default: the cutter profile's).

    With ``entities=False`` only the header, units, layers and empty model space:
    :func:`dxf_text` writes the (many) polylines itself, see :func:`entities_text`.
    """
    import ezdxf
    from ezdxf import units

    version = version_of(job, dxf_version)
    with _fixed_metadata():  # ezdxf.new stamps its "created by" marker with the time
        if version == "R12":  # R12 has no unit header; its coordinates are mm all the same
            doc = _new_r12()
        else:
            doc = ezdxf.new(version, setup=False, units=units.MM)
    if version != "R12":
        doc.header["$MEASUREMENT"] = 1
    # The drawing's extents (some laser programs zoom to them). ezdxf copies the model
    # space layout's extents over the header's when it writes, unless one of them is the
    # zero vector (a tile at the origin without kerf): so both are set.
    xmin, ymin, xmax, ymax = job.bounds
    msp = doc.modelspace()
    for key, value in (("extmin", (xmin, ymin, 0.0)), ("extmax", (xmax, ymax, 0.0))):
        msp.dxf.set(key, value)
        doc.header[f"${key.upper()}"] = value
    for layer in job.declared:
        doc.layers.add(layer.name, color=layer.color)
    if not entities:
        return doc
    for curves, layer, closed in _groups(job):
        attribs = {"layer": layer.name, "color": layer.color}
        for xy, bulge in curves:
            if version == "R12":
                points = [(x, y, 0.0, 0.0, b) for (x, y), b in zip(xy.tolist(), bulge.tolist(), strict=True)]
                msp.add_polyline2d(points, format="xyseb", close=closed, dxfattribs=attribs)
            else:
                points = [(x, y, b) for (x, y), b in zip(xy.tolist(), bulge.tolist(), strict=True)]
                msp.add_lwpolyline(points, format="xyb", close=closed, dxfattribs=attribs)
    return doc


def _new_r12():
    """A new R12 document, without ezdxf's log warning that R12 has no $INSUNITS (we know)."""
    import logging

    import ezdxf

    log = logging.getLogger("ezdxf")
    quiet = _DropUnitsWarning()
    log.addFilter(quiet)
    try:
        return ezdxf.new("R12", setup=False, units=0)
    finally:
        log.removeFilter(quiet)


class _DropUnitsWarning:
    def filter(self, record) -> bool:
        return "$INSUNITS" not in record.getMessage()


def _groups(job: CutPlan):
    """``(curves, layer, closed)`` of each layer, in cut order: its paths with their arcs as bulges."""
    return [(layer.curves_or_paths(), layer.layer, layer.closed) for layer in job.layers]


def entities_text(job: CutPlan, first_handle: int, owner: str, *, dxf_version: str | None = None) -> tuple[str, int]:
    """The ENTITIES section body of ``job`` as DXF text in ``dxf_version`` (default: the cutter
    profile's), and the next free handle.

    Byte for byte what ezdxf writes for the same polylines (the tests compare the
    two), without ezdxf's per-entity and per-vertex Python objects, which cost most
    of a sheet's DXF. LWPOLYLINE for R2000+, POLYLINE/VERTEX/SEQEND
    for R12.
    """
    out: list[str] = []
    h = first_handle
    polyline = _r12_polyline if version_of(job, dxf_version) == "R12" else _lwpolyline
    for curves, layer, closed in _groups(job):
        flag = 1 if closed else 0
        common = f"  8\n{layer.name}\n 62\n{layer.color}\n"
        for ring, bulge in curves:
            # an arc: the bulge (group code 42, tan(sweep / 4)) of the vertex it leaves from
            bulges = [f" 42\n{b!r}\n" if b else "" for b in bulge.tolist()] if bulge.any() else None
            h = polyline(out, h, layer.name, common, flag, ring, bulges, owner)
    return "".join(out), h


def _r12_polyline(out: list, h: int, name: str, common: str, flag: int, ring, bulges, owner: str) -> int:
    """Append an R12 POLYLINE, its VERTEXes and SEQEND to ``out``; return the next free handle."""
    xy = ring.ravel().tolist()
    n = len(ring)
    out.append(f"  0\nPOLYLINE\n  5\n{h:X}\n{common} 66\n1\n 10\n0.0\n 20\n0.0\n 30\n0.0\n 70\n{flag}\n")
    if bulges is None:
        vtx = "".join(
            f"  0\nVERTEX\n  5\n{h + 2 + k:X}\n  8\n{name}\n 10\n%r\n 20\n%r\n 30\n0.0\n 70\n0\n" for k in range(n)
        )
        out.append(vtx % tuple(xy))
    else:
        out.append(
            "".join(
                f"  0\nVERTEX\n  5\n{h + 2 + k:X}\n  8\n{name}\n 10\n{xy[2 * k]!r}\n"
                f" 20\n{xy[2 * k + 1]!r}\n 30\n0.0\n{bulges[k]} 70\n0\n"
                for k in range(n)
            )
        )
    out.append(f"  0\nSEQEND\n  5\n{h + 1:X}\n  8\n{name}\n")
    return h + n + 2


def _lwpolyline(out: list, h: int, name: str, common: str, flag: int, ring, bulges, owner: str) -> int:
    """Append an LWPOLYLINE (R2000 and later) to ``out``; return the next free handle."""
    xy = ring.ravel().tolist()
    n = len(ring)
    out.append(
        f"  0\nLWPOLYLINE\n  5\n{h:X}\n330\n{owner}\n100\nAcDbEntity\n{common}"
        f"100\nAcDbPolyline\n 90\n{n}\n 70\n{flag}\n"
    )
    if bulges is None:
        out.append((" 10\n%r\n 20\n%r\n" * n) % tuple(xy))
    else:
        out.append("".join(f" 10\n{xy[2 * k]!r}\n 20\n{xy[2 * k + 1]!r}\n{bulges[k]}" for k in range(n)))
    return h + 1


_ENTITIES = "  0\nSECTION\n  2\nENTITIES\n"


def dxf_text(job: CutPlan, *, dxf_version: str | None = None) -> tuple[str, str]:
    """The DXF file of ``job`` in ``dxf_version`` (default: the cutter profile's) as text, and its encoding.

    ezdxf writes the frame (header, tables, blocks, objects), :func:`entities_text` the polylines.
    """
    version = version_of(job, dxf_version)
    doc = build_document(job, dxf_version=version, entities=False)
    owner = doc.modelspace().layout_key
    handles = doc.entitydb.handles
    first = int(handles.next(), 16)
    body, nxt = entities_text(job, first, owner, dxf_version=version)
    handles.reset(f"{nxt:X}")  # $HANDSEED above every handle used
    text = _fixed_frame(doc)
    at = text.index(_ENTITIES) + len(_ENTITIES)
    if not text.startswith("  0\nENDSEC\n", at):  # pragma: no cover - ezdxf layout changed
        raise RuntimeError("unexpected DXF layout from ezdxf: the ENTITIES section is not empty")
    return _content_guids(cutter_comment(job) + text[:at] + body + text[at:], version), doc.output_encoding


_FIXED_META = threading.Lock()
"""Held while ezdxf's process-wide fixed-metadata option is switched on (see :func:`_fixed_metadata`)."""


def _fixed_frame(doc) -> str:
    """``doc`` as ezdxf writes it with fixed metadata and classes in a fixed order: the same text every run."""
    import io

    if doc.dxfversion > "AC1009":  # R12 has no CLASSES section
        _register_classes(doc)
    stream = io.StringIO()
    with _fixed_metadata():
        doc.write(stream)
    return stream.getvalue()


def _register_classes(doc) -> None:
    """Register the CLASSES of ``doc`` in ezdxf's order, then the classes of its entity types sorted by name.

    On write ezdxf adds its required classes, then one for each entity type in use,
    taken from a set: from DXF R2004 on the LAYOUT and ACDBPLACEHOLDER classes came
    in either order, by the process's string hash seed. A class already registered
    is kept where it is, so registering them here first fixes the order.
    """
    from ezdxf.sections.classes import REQ_R2004, REQUIRED_CLASSES

    for name in [*REQUIRED_CLASSES.get(doc.dxfversion, REQ_R2004), *sorted(doc.entitydb.dxf_types_in_use())]:
        doc.classes.add_class(name)


@contextmanager
def _fixed_metadata():
    """ezdxf's fixed metadata switched on, for one new document or one write.

    ezdxf stamps a new document's header with the time ($TDCREATE) and a random
    $FINGERPRINTGUID, and each write with the time ($TDUPDATE), a random
    $VERSIONGUID and its "created by" and "written by" markers with the time.
    Its ``write_fixed_meta_data_for_testing`` option writes 2000-01-01, zero GUIDs
    and a fixed marker instead. The option is global to the process, so it is
    switched on only for the call, under a lock (web requests and Dask threads
    write DXFs side by side), and put back. :func:`_content_guids` then replaces
    the zero GUIDs.
    """
    import ezdxf

    with _FIXED_META:
        before = ezdxf.options.write_fixed_meta_data_for_testing
        ezdxf.options.write_fixed_meta_data_for_testing = True
        try:
            yield
        finally:
            ezdxf.options.write_fixed_meta_data_for_testing = before


_ZERO_GUID = "{00000000-0000-0000-0000-000000000000}"
_GUIDS = ("$FINGERPRINTGUID", "$VERSIONGUID")
"""The header's GUIDs (DXF R2000 and later): each a name-based UUID of the file's content."""


def _content_guids(text: str, dxf_version: str) -> str:
    r"""``text`` with its zero header GUIDs replaced by GUIDs derived from the whole file.

    AutoCAD reads $FINGERPRINTGUID as the drawing's identity and $VERSIONGUID as
    its revision's: different drawings get different GUIDs, the same drawing the
    same ones, run after run (a UUID version 5 of the SHA-256 of the text).

    >>> header = "".join(f"  9\n{name}\n  2\n{_ZERO_GUID}\n" for name in _GUIDS)
    >>> print(_content_guids(header, "R2000"), end="")
      9
    $FINGERPRINTGUID
      2
    {CE072E9B-0A04-518B-BF0B-5DE30DC9B5F6}
      9
    $VERSIONGUID
      2
    {AB4AFD1A-73CE-53DE-A98D-CAAAD3C2D6FC}
    """
    import hashlib
    import uuid

    digest = hashlib.sha256(text.encode("utf-8", errors="surrogatepass")).hexdigest()
    for name in () if dxf_version == "R12" else _GUIDS:  # R12 headers have no GUIDs
        key = f"{name}\n  2\n"
        if key + _ZERO_GUID not in text:  # ezdxf's fixed metadata changed
            raise RuntimeError(f"unexpected DXF header from ezdxf: {name} is not the zero GUID")
        guid = uuid.uuid5(uuid.NAMESPACE_URL, f"urn:fabtiles:dxf:{name}:{digest}")
        text = text.replace(key + _ZERO_GUID, key + "{" + str(guid).upper() + "}", 1)
    return text


def cutter_comment(job: CutPlan) -> str:
    """DXF comments (group code 999) saying what a router's or waterjet's file holds; none for a laser.

    CAM programs skip 999 groups, ezdxf's reader drops them, LibreCAD draws the file as
    before (tests/export/test_router.py). A laser's file stays byte for byte as it was.

    >>> from fabtiles.machines.profiles import load_profile
    >>> from fabtiles.geometry.cut_plan import make_plan
    >>> print(cutter_comment(make_plan(load_profile("router-6mm-mdf"), "pierced", 0.0, {})), end="")
    999
    fabtiles router profile router-6mm-mdf: the part as the 6 mm bit makes it (hole corners rounded to 3 mm), NO tool compensation: CAM offsets the tool
    999
    layers: INSIDE (inside profiles, cut first), OUTSIDE (outside profile, cut last); millimetres
    """  # noqa: E501 - a doctest's lines are as Python prints them
    return "".join(f"999\n{line}\n" for line in job.profile.cutter.dxf_comments(job.profile, job.kerf_mm))
