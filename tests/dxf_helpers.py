"""Helpers for laser-output tests: read a DXF back and check it, compare with golden files.

``dxf_entities(path)`` turns a DXF into a list of plain tuples (layer, type,
closed, colour, rounded vertices) for entity-by-entity comparison;
``assert_golden(path, golden)`` compares with ``tests/export/golden/<name>.json``
and rewrites the golden file instead when ``FABTILES_UPDATE_GOLDEN=1``
(``assert_golden_summary`` likewise, with counts and a sample of the entities of a
large file). ``check_laser_dxf`` checks a pierced laser DXF as the issue asks.
The region builders make small realistic test parts with shapely.
"""

from __future__ import annotations

import json
import math
import os
import re
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import Polygon, box

GOLDEN = Path(__file__).parent / "export" / "golden"
CUT_TYPES = ("LWPOLYLINE", "POLYLINE")


# --- comparing whole files ------------------------------------------------------------------

VOLATILE_HEADER = frozenset(
    {
        "$TDCREATE",
        "$TDUCREATE",
        "$TDUPDATE",
        "$TDUUPDATE",
        "$TDINDWG",
        "$TDUSRTIMER",
        "$FINGERPRINTGUID",
        "$VERSIONGUID",
    }
)
"""Header variables that hold the time of writing or a fresh GUID: they differ between two runs
unless the writer fixes them, so :func:`dxf_tags` leaves their values out."""

_WRITTEN_AT = re.compile(r"^(.*\S) @ \d{4}-\d\d-\d\dT[0-9:.]+(?:[+-]\d\d:\d\d|Z)?$")
"""ezdxf's ``CREATED_BY_EZDXF`` and ``WRITTEN_BY_EZDXF`` values: ``1.4.5 @ 2026-01-01T10:00:00.123+00:00``."""


def dxf_tags(data: bytes) -> list[tuple[str, str]]:
    """The (group code, value) pairs of an ASCII DXF, with the time and GUID of writing left out.

    The values of :data:`VOLATILE_HEADER` become ``"*"`` and a value ``<version> @ <time>`` keeps
    its version only, so two runs of the same build compare equal whether or not the writer makes
    its headers reproducible; everything else (entities, handles, layers) must match exactly.
    """
    lines = data.decode("utf-8", errors="strict").splitlines()
    assert len(lines) % 2 == 0, f"a DXF is pairs of lines (group code, value); got {len(lines)} lines"
    pairs = [(lines[k].strip(), lines[k + 1]) for k in range(0, len(lines), 2)]
    out, blank_next = [], False
    for code, value in pairs:
        if blank_next and code != "9":
            value, blank_next = "*", False
        elif code == "9":
            blank_next = value in VOLATILE_HEADER
        written = _WRITTEN_AT.match(value)
        out.append((code, written[1] + " @ *" if written else value))
    return out


def assert_same_file(name: str, got: bytes, want: bytes) -> None:
    """Assert that file ``name`` is ``want``: byte for byte, or for a DXF tag for tag up to :func:`dxf_tags`."""
    if str(name).lower().endswith(".dxf"):
        g, w = dxf_tags(got), dxf_tags(want)
        assert len(g) == len(w), f"{name}: {len(g)} tags, expected {len(w)}"
        diff = next((k for k, (a, b) in enumerate(zip(g, w, strict=False)) if a != b), None)  # the first difference
        assert diff is None, f"{name}: tag {diff} is {g[diff]}, expected {w[diff]}"
    else:
        assert got == want, f"{name}: {len(got)} bytes differ from the expected {len(want)}"


# --- reading DXF back ------------------------------------------------------------------------


def read_checked(path, *, allow_fixes: bool = False):
    """``ezdxf.readfile`` + audit; asserts no audit errors (and no fixes unless allowed)."""
    import ezdxf

    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    assert not auditor.errors, [e.message for e in auditor.errors][:5]
    if not allow_fixes:
        assert not auditor.fixes, [f.message for f in auditor.fixes][:5]
    return doc


def raw_vertices(entity) -> np.ndarray:
    """(m, 2) vertices of an LWPOLYLINE or 2D POLYLINE, as written (an arc's ends only)."""
    if entity.dxftype() == "LWPOLYLINE":
        return np.array(entity.get_points("xy"), dtype=float).reshape(-1, 2)
    return np.array([(v.dxf.location.x, v.dxf.location.y) for v in entity.vertices], dtype=float).reshape(-1, 2)


def bulges(entity) -> np.ndarray:
    """(m,) bulge of each vertex of an LWPOLYLINE or 2D POLYLINE (0: a straight edge leaves it)."""
    if entity.dxftype() == "LWPOLYLINE":
        return np.array([p[2] for p in entity.get_points("xyb")], dtype=float)
    return np.array([v.dxf.get("bulge", 0.0) for v in entity.vertices], dtype=float)


FLATTEN_MM = 0.001
"""How finely :func:`vertices` flattens a polyline's arcs (ezdxf's own flattening)."""


def vertices(entity) -> np.ndarray:
    """(m, 2) points of the curve an LWPOLYLINE or 2D POLYLINE draws: its vertices, and its arcs
    (bulges) flattened within :data:`FLATTEN_MM` by ezdxf itself (``ezdxf.path``; 16 Bezier pieces
    a circle at least: ezdxf's default quarter-circle Beziers stand 2.7e-4 of the radius off it).
    A closed polyline's first point is not repeated at its end."""
    raw = raw_vertices(entity)
    if not bulges(entity).any():
        return raw
    from ezdxf import path

    pts = np.array([(v.x, v.y) for v in path.make_path(entity, segments=16).flattening(FLATTEN_MM)], dtype=float)
    if is_closed(entity) and len(pts) > 1 and np.allclose(pts[0], pts[-1], atol=1e-12, rtol=0):
        pts = pts[:-1]
    return pts


def is_closed(entity) -> bool:
    return bool(entity.closed if entity.dxftype() == "LWPOLYLINE" else entity.is_closed)


def dxf_entities(path, decimals: int = 4, doc=None) -> list[tuple]:
    """Every model-space entity as ``(layer, dxftype, closed, color, ((x, y), ...))``, in file order
    (``doc``: the file as ezdxf read it, when the caller has it)."""
    import ezdxf

    doc = doc or ezdxf.readfile(path)
    out = []
    for e in doc.modelspace():
        pts = raw_vertices(e) if e.dxftype() in CUT_TYPES else np.empty((0, 2))
        rounded = tuple(tuple(float(round(c, decimals)) + 0.0 for c in p) for p in pts)
        entity = (
            e.dxf.layer,
            e.dxftype(),
            is_closed(e) if e.dxftype() in CUT_TYPES else False,
            e.dxf.get("color", 256),
            rounded,
        )
        b = bulges(e) if e.dxftype() in CUT_TYPES else np.zeros(0)
        if b.any():  # arcs: the bulges too (a file without arcs compares as before)
            entity += (tuple(float(round(v, decimals)) + 0.0 for v in b),)
        out.append(entity)
    return out


def golden_text(data) -> str:
    """The bytes of a golden file: a list of entities one per line, or a summary dict, as JSON.

    Deterministic (same data, same text), so ``FABTILES_UPDATE_GOLDEN=1`` rewrites
    an unchanged golden byte for byte.
    """
    if isinstance(data, dict):
        return json.dumps(data, indent=1, sort_keys=True) + "\n"
    return "[\n" + ",\n".join(json.dumps(list(e)) for e in data) + "\n]\n"


def _update_golden(golden: Path) -> bool:
    """True when ``golden`` is to be (re)written; an error when it is missing and not asked to."""
    update = os.environ.get("FABTILES_UPDATE_GOLDEN") == "1"
    if not update and not golden.exists():
        raise AssertionError(f"no golden file {golden}; run with FABTILES_UPDATE_GOLDEN=1 to create it")
    return update


def _entity(e) -> tuple:
    """A golden entity read back from JSON, as :func:`dxf_entities` gives it."""
    return (e[0], e[1], e[2], e[3], tuple(tuple(p) for p in e[4])) + ((tuple(e[5]),) if len(e) > 5 else ())


def assert_same_entity(got, want, k, decimals: int = 4) -> None:
    """Entity ``k``: same layer, type, closed flag, colour and vertex count; vertices and bulges within rounding."""
    assert got[:4] == want[:4], f"entity {k}: {got[:4]} != golden {want[:4]}"
    assert len(got[4]) == len(want[4]), f"entity {k}: {len(got[4])} vertices, golden has {len(want[4])}"
    diff = np.abs(np.array(got[4]) - np.array(want[4])).max() if got[4] else 0.0
    assert diff <= 2 * 10.0**-decimals, f"entity {k}: vertices differ by {diff}"
    assert len(got) == len(want), f"entity {k}: {'arcs' if len(got) > 5 else 'no arc'}, golden the other"
    if len(got) > 5:
        bdiff = np.abs(np.array(got[5]) - np.array(want[5])).max()
        assert bdiff <= 2 * 10.0**-decimals, f"entity {k}: bulges differ by {bdiff}"


def assert_golden(path, name: str, decimals: int = 4, doc=None) -> None:
    """Compare the entities of DXF ``path`` (``doc``: as ezdxf read it) with ``golden/<name>.json``, entity
    by entity."""
    got = dxf_entities(path, decimals, doc)
    golden = GOLDEN / f"{name}.json"
    if _update_golden(golden):
        golden.parent.mkdir(parents=True, exist_ok=True)
        golden.write_text(golden_text(got))
        return
    want = [_entity(e) for e in json.loads(golden.read_text())]
    assert len(got) == len(want), f"{len(got)} entities, golden has {len(want)}"
    for k, (g, w) in enumerate(zip(got, want, strict=True)):
        assert_same_entity(g, w, k, decimals)


def entity_summary(entities, samples: int = 40) -> dict:
    """Counts of a (large) DXF's entities and every n-th entity, for :func:`assert_golden_summary`."""
    layers: dict = {}
    for e in entities:
        key = f"{e[0]} {e[1]} {'closed' if e[2] else 'open'} {e[3]}"
        layers[key] = layers.get(key, 0) + 1
    step = max(1, len(entities) // samples)
    return {
        "entities": len(entities),
        "vertices": sum(len(e[4]) for e in entities),
        "by_layer_type_closed_colour": layers,
        "sample_every": step,
        "sample": [list(e) for e in entities[::step]],
    }


def assert_golden_summary(path, name: str, decimals: int = 4, samples: int = 40, doc=None) -> None:
    """Compare a large DXF with ``golden/<name>.json``: exact counts, every n-th entity in full.

    For files whose full golden would be megabytes: entity and vertex counts (in
    total and per layer, type, closed flag and colour) must match exactly, and
    about ``samples`` entities spread over the file are compared entity by entity.
    """
    got = entity_summary(dxf_entities(path, decimals, doc), samples)
    golden = GOLDEN / f"{name}.json"
    if _update_golden(golden):
        golden.parent.mkdir(parents=True, exist_ok=True)
        golden.write_text(golden_text(got))
        return
    want = json.loads(golden.read_text())
    for key in ("entities", "vertices", "by_layer_type_closed_colour", "sample_every"):
        assert got[key] == want[key], f"{key}: {got[key]} != golden {want[key]}"
    for k, (g, w) in enumerate(zip(got["sample"], want["sample"], strict=True)):
        assert_same_entity(_entity(g), _entity(w), k * want["sample_every"], decimals)


def _line_parts(geom) -> list:
    """The lines of ``geom`` GEOS measures Hausdorff distances along: a polygon's rings, a line itself."""
    out = []
    for part in shapely.get_parts(geom):
        if part.geom_type == "Polygon":
            out += [part.exterior, *part.interiors]
        elif part.geom_type in ("LineString", "LinearRing"):
            out.append(part)
        else:
            raise TypeError(f"hausdorff_distance measures lines and polygons, not a {part.geom_type}")
    return out


def hausdorff_distance(a, b, *, densify: float) -> float:
    """GEOS's discrete Hausdorff distance of ``a`` and ``b`` with every segment cut in ``1 / densify``.

    The same points and the same point-to-segment distances as
    ``shapely.hausdorff_distance(a, b, densify=densify)`` (equal to the last bit or two), but each
    point finds its nearest segment through an STRtree: GEOS measures every point against every
    segment, minutes for the tens of thousands of segments of a finely flattened tile. The vertices
    are measured first; a point inside a segment is no farther from the other geometry than from
    the segments nearest to its segment's ends, so only the points where that bound passes the
    largest distance found go through the tree (few: most lie along those segments).
    """
    cuts = round(1 / densify)
    inside = np.arange(1, cuts)[None, :, None] / cuts
    worst = 0.0
    for near, far in ((a, b), (b, a)):
        segments = []
        for line in _line_parts(far):
            c = shapely.get_coordinates(line)
            segments.append(np.stack([c[:-1], c[1:]], axis=1))
        segments = np.concatenate(segments)
        tree = shapely.STRtree(shapely.linestrings(segments))
        lines = [shapely.get_coordinates(line) for line in _line_parts(near)]
        xy = np.concatenate(lines)
        (at, nearest), d = tree.query_nearest(shapely.points(xy), return_distance=True, all_matches=False)
        worst = max(worst, float(d.max()))
        nearest = nearest[np.argsort(at)]
        line = np.repeat(np.arange(len(lines)), [len(c) for c in lines])
        start = np.flatnonzero(line[1:] == line[:-1])  # each segment: a vertex and the next of its line
        p, q = xy[start][:, None], xy[start + 1][:, None]
        points = p + inside * (q - p)
        bound = np.minimum(
            _to_segments(points, segments[nearest[start]]), _to_segments(points, segments[nearest[start + 1]])
        )
        points = points[bound > worst]
        if len(points):
            _, d = tree.query_nearest(shapely.points(points), return_distance=True, all_matches=False)
            worst = max(worst, float(d.max()))
    return worst


def _to_segments(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """The distance of points ``(k, m, 2)`` from segments ``(k, 2, 2)``, each row's points from its segment."""
    s0, v = segments[:, None, 0], (segments[:, 1] - segments[:, 0])[:, None]
    w = points - s0
    t = np.clip((w * v).sum(axis=-1) / np.maximum((v * v).sum(axis=-1), 1e-300), 0.0, 1.0)
    return np.hypot(*np.moveaxis(w - t[..., None] * v, -1, 0))


def ring_polygons(doc, layers) -> list:
    """Closed polylines on ``layers`` as shapely polygons."""
    return [Polygon(vertices(e)) for e in doc.modelspace() if e.dxf.layer in layers and e.dxftype() in CUT_TYPES]


def even_odd_area(polygons) -> float:
    """Area enclosed by an odd number of the rings (the material a laser leaves).

    The symmetric difference of all rings, reduced pairwise (a balanced tree, not
    a running fold): seconds, not minutes, for the thousands of rings of a sheet.
    """
    geoms = np.array(list(polygons), dtype=object)
    if not len(geoms):
        return 0.0
    while len(geoms) > 1:
        pairs = len(geoms) // 2 * 2
        geoms = np.concatenate([shapely.symmetric_difference(geoms[0:pairs:2], geoms[1:pairs:2]), geoms[pairs:]])
    return float(geoms[0].area)


def check_laser_dxf(path, region, *, kerf, version="R2000", profile="laser-3mm-plywood"):
    """Everything the issue asks of a pierced laser DXF; returns the ezdxf document.

    Audit clean, ``$INSUNITS`` = 4 (not in R12), the profile's layers and colours,
    only closed polylines of the version's type on the cut layers, no zero-length or
    repeated edges, inner contours before outer ones, and the even-odd area of the
    contours equal to ``region`` grown by ``kerf / 2`` within 0.5 %.
    """
    import pytest

    from fabtiles.geometry.contours import MITRE_LIMIT
    from fabtiles.machines.profiles import load_profile

    profile = load_profile(profile, kind="laser")
    doc = read_checked(path)
    if version != "R12":
        assert doc.header["$INSUNITS"] == 4
        assert doc.units == 4
    layers = profile.layers
    for layer in (layers.inner_cut, layers.outer_cut, layers.score):
        assert doc.layers.get(layer.name).color == layer.color
    msp = list(doc.modelspace())
    assert msp, "no entities"
    want_type = "POLYLINE" if version == "R12" else "LWPOLYLINE"
    seen_outer = False
    for e in msp:
        assert e.dxftype() == want_type
        assert e.dxf.layer in (layers.inner_cut.name, layers.outer_cut.name)
        assert is_closed(e)
        assert e.dxf.color == (layers.inner_cut if e.dxf.layer == layers.inner_cut.name else layers.outer_cut).color
        pts = vertices(e)
        assert len(pts) >= 3
        assert edge_problems(pts) == (0, 0)
        if e.dxf.layer == layers.outer_cut.name:
            seen_outer = True
        else:
            assert not seen_outer, "an inner contour comes after an outer contour"
    grown = region.buffer(kerf / 2, join_style="mitre", mitre_limit=MITRE_LIMIT) if kerf else region
    area = even_odd_area(ring_polygons(doc, (layers.inner_cut.name, layers.outer_cut.name)))
    assert area == pytest.approx(grown.area, rel=0.005)
    return doc


def edge_problems(pts: np.ndarray, closed: bool = True) -> tuple[int, int]:
    """(zero-length edges, repeated edges) of one polyline."""
    ring = np.vstack([pts, pts[:1]]) if closed else pts
    a, b = ring[:-1], ring[1:]
    zero = int((np.hypot(*(b - a).T) < 1e-9).sum())
    keys = {tuple(sorted((tuple(p), tuple(q)))) for p, q in zip(a.tolist(), b.tolist(), strict=True)}
    return zero, len(a) - len(keys)


# --- test parts ------------------------------------------------------------------------------


def star_polygon(cx, cy, r_out, r_in, n=8, rotation=0.0) -> Polygon:
    t = np.radians(rotation) + np.arange(2 * n) * math.pi / n
    r = np.where(np.arange(2 * n) % 2 == 0, r_out, r_in)
    return Polygon(np.c_[cx + r * np.cos(t), cy + r * np.sin(t)])


def star_plate(size=60.0, grid=3, r_out=7.0, r_in=3.5):
    """A square plate with a ``grid`` x ``grid`` array of 8-pointed star holes: (region, outline)."""
    outline = box(0, 0, size, size)
    step = size / grid
    stars = [
        star_polygon(step * (i + 0.5), step * (j + 0.5), r_out, r_in, rotation=11.25 * (i + j))
        for i in range(grid)
        for j in range(grid)
    ]
    return outline.difference(shapely.union_all(stars)), outline


def motif_tile(size=100.0, frame=5.0, stroke=1.2, preset="table3-3"):
    """One fabtiles motif stroked into a square tile with a frame: (region, outline, centrelines)."""
    import fabtiles as ft

    seg = ft.Star.preset(preset).segments()
    extent = float(np.hypot(seg[..., 0], seg[..., 1]).max())
    seg = seg * ((size / 2 - frame) / extent) + size / 2
    outline = box(0, 0, size, size)
    bands = shapely.buffer(shapely.linestrings(seg), stroke / 2, cap_style="flat", join_style="mitre")
    inner = box(frame, frame, size - frame, size - frame)
    region = shapely.union(shapely.intersection(shapely.union_all(bands), inner), outline.difference(inner))
    return shapely.normalize(region), outline, seg


def island_region():
    """A plate with a square hole holding a loose island: (region, outline)."""
    outline = box(0, 0, 50, 50)
    plate = outline.difference(box(10, 10, 40, 40))
    return plate.union(box(20, 20, 30, 30)), outline


def tiny_hole_region():
    """A plate with one big hole and one 0.5 mm hole: (region, outline)."""
    outline = box(0, 0, 40, 40)
    return outline.difference(box(5, 5, 20, 20)).difference(box(30, 30, 30.5, 30.5)), outline


def thin_bridge_region(width=0.4):
    """Two holes separated by a ``width`` mm bridge: (region, outline)."""
    outline = box(0, 0, 40, 30)
    return outline.difference(box(5, 5, 20, 25)).difference(box(20 + width, 5, 35, 25)), outline


# --- router and waterjet files --------------------------------------------------------------


def opened_reference(region, r: float, quad_segs: int = 64):
    """The part as a tool of radius ``r`` makes it, computed here on its own: every hole
    ``buffer(-r).buffer(r)`` at ``quad_segs`` segments a quarter (GEOS), every outer ring
    closed (``buffer(r).buffer(-r)``) unless it is convex. Returns (part, opened holes)."""
    polys = []
    opened_holes = []
    for part in getattr(region, "geoms", [region]):
        shell = Polygon(part.exterior)
        if shell.convex_hull.area - shell.area > 1e-6:
            shell = shell.union(shell.buffer(r, quad_segs=quad_segs).buffer(-r, quad_segs=quad_segs))
        holes = [Polygon(h).buffer(-r, quad_segs=quad_segs).buffer(r, quad_segs=quad_segs) for h in part.interiors]
        holes = [g for h in holes for g in getattr(h, "geoms", [h]) if not g.is_empty]
        opened_holes += holes
        polys.append(Polygon(shell.exterior, [h.exterior for h in holes]))
    return shapely.union_all(polys), opened_holes


def tightest_arc_radius(ring: np.ndarray, *, interior_left: bool) -> float:
    """The smallest circumradius of three consecutive vertices inside a run of convex turns (an arc).

    On an arc flattened by chords every vertex is on the circle, so the circumradius of three
    consecutive vertices is the arc's radius. Vertices next to a concave turn are left out: where
    two of the tool's arcs meet (a concave junction) the junction is on the chords, not on the
    circles, and a short last chord makes the three-point circle meaningless there.
    """
    p0, p1, p2 = np.roll(ring, 1, axis=0), ring, np.roll(ring, -1, axis=0)
    a, b, c = p1 - p0, p2 - p1, p2 - p0
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    convex = cross > 1e-12 if interior_left else cross < -1e-12
    run = convex & np.roll(convex, 1) & np.roll(convex, -1)
    la, lb, lc = np.hypot(*a.T), np.hypot(*b.T), np.hypot(*c.T)
    radius = la * lb * lc / (2 * np.abs(cross) + 1e-300)
    return float(radius[run].min()) if run.any() else math.inf


def assert_no_corner_sharper_than(hole: Polygon, r: float, tol: float = 0.01) -> None:
    """Every convex corner of ``hole`` has a radius of at least ``r`` (within ``tol``).

    Two ways: the arcs' own radius (:func:`tightest_arc_radius`), and, for any corner at all
    (a star tip left sharp between two long edges has a large three-point circle), that the hole
    is its own opening by ``r - tol``: GEOS at 64 segments a quarter moves it by at most ``tol``.
    """
    ring = np.asarray(shapely.normalize(hole).exterior.coords)[:-1]  # clockwise: the inside on the right
    assert tightest_arc_radius(ring, interior_left=False) >= r - tol
    opened = hole.buffer(-(r - tol), quad_segs=64).buffer(r - tol, quad_segs=64)
    assert hausdorff_distance(hole, opened, densify=0.1) <= tol


def check_router_dxf(path, region, profile, *, rel_area: float = 0.001):
    """A router DXF as the issue asks; returns the ezdxf document.

    Audit clean, mm, the 999 comment saying there is no tool compensation, only the
    profile's two layers (inside profiles first, the outline last), closed LWPOLYLINEs
    without zero-length or repeated edges, and the even-odd area of the contours equal
    to GEOS's own opening of ``region`` by the bit's radius within ``rel_area``.
    """
    import pytest

    doc = read_checked(path)
    assert doc.header["$INSUNITS"] == 4
    head = Path(path).read_text(encoding="cp1252")[:600]
    assert head.startswith("999\n") and "NO tool compensation: CAM offsets the tool" in head
    layers = profile.layers
    assert {layer.dxf.name for layer in doc.layers} - {"0", "Defpoints"} == {
        layers.inner_cut.name,
        layers.outer_cut.name,
    }
    seen_outer = False
    rings = []  # every entity is one of the two layers' rings: flattened once, for both checks
    for e in doc.modelspace():
        assert e.dxftype() == "LWPOLYLINE" and is_closed(e)
        assert e.dxf.layer in (layers.inner_cut.name, layers.outer_cut.name)
        rings.append(vertices(e))
        assert edge_problems(rings[-1]) == (0, 0)
        if e.dxf.layer == layers.outer_cut.name:
            seen_outer = True
        else:
            assert not seen_outer, "an inside profile comes after the outline"
    reference, _ = opened_reference(region, profile.tool_radius_mm)
    area = even_odd_area(Polygon(ring) for ring in rings)
    assert area == pytest.approx(reference.area, rel=rel_area)
    return doc
