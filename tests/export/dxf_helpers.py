"""Helpers for laser-output tests: read a DXF back and check it, compare with golden files.

``dxf_entities(path)`` turns a DXF into a list of plain tuples (layer, type,
closed, colour, rounded vertices) for entity-by-entity comparison;
``assert_golden(path, golden)`` compares with ``tests/export/golden/<name>.json``
and rewrites the golden file instead when ``FABTILES_UPDATE_GOLDEN=1``.
The region builders make small realistic test parts with shapely.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import Polygon, box

GOLDEN = Path(__file__).parent / "golden"
CUT_TYPES = ("LWPOLYLINE", "POLYLINE")


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


def vertices(entity) -> np.ndarray:
    """(m, 2) vertices of an LWPOLYLINE or 2D POLYLINE."""
    if entity.dxftype() == "LWPOLYLINE":
        return np.array(entity.get_points("xy"), dtype=float).reshape(-1, 2)
    return np.array([(v.dxf.location.x, v.dxf.location.y) for v in entity.vertices], dtype=float).reshape(-1, 2)


def is_closed(entity) -> bool:
    return bool(entity.closed if entity.dxftype() == "LWPOLYLINE" else entity.is_closed)


def dxf_entities(path, decimals: int = 4) -> list[tuple]:
    """Every model-space entity as ``(layer, dxftype, closed, color, ((x, y), ...))``, in file order."""
    import ezdxf

    doc = ezdxf.readfile(path)
    out = []
    for e in doc.modelspace():
        pts = vertices(e) if e.dxftype() in CUT_TYPES else np.empty((0, 2))
        rounded = tuple(tuple(float(round(c, decimals)) + 0.0 for c in p) for p in pts)
        out.append((e.dxf.layer, e.dxftype(), is_closed(e) if e.dxftype() in CUT_TYPES else False,
                    e.dxf.get("color", 256), rounded))
    return out


def assert_golden(path, name: str, decimals: int = 4) -> None:
    """Compare the entities of DXF ``path`` with ``golden/<name>.json``, entity by entity."""
    got = dxf_entities(path, decimals)
    golden = GOLDEN / f"{name}.json"
    if os.environ.get("FABTILES_UPDATE_GOLDEN") == "1" or not golden.exists():
        if not golden.exists() and os.environ.get("FABTILES_UPDATE_GOLDEN") != "1":
            raise AssertionError(f"no golden file {golden}; run with FABTILES_UPDATE_GOLDEN=1 to create it")
        golden.parent.mkdir(parents=True, exist_ok=True)
        golden.write_text("[\n" + ",\n".join(json.dumps(list(e)) for e in got) + "\n]\n")
        return
    want = [(e[0], e[1], e[2], e[3], tuple(tuple(p) for p in e[4])) for e in json.loads(golden.read_text())]
    assert len(got) == len(want), f"{len(got)} entities, golden has {len(want)}"
    for k, (g, w) in enumerate(zip(got, want)):
        assert g[:4] == w[:4], f"entity {k}: {g[:4]} != golden {w[:4]}"
        assert len(g[4]) == len(w[4]), f"entity {k}: {len(g[4])} vertices, golden has {len(w[4])}"
        diff = np.abs(np.array(g[4]) - np.array(w[4])).max() if g[4] else 0.0
        assert diff <= 2 * 10.0 ** -decimals, f"entity {k}: vertices differ by {diff}"


def ring_polygons(doc, layers) -> list:
    """Closed polylines on ``layers`` as shapely polygons."""
    return [Polygon(vertices(e)) for e in doc.modelspace() if e.dxf.layer in layers and e.dxftype() in CUT_TYPES]


def even_odd_area(polygons) -> float:
    """Area enclosed by an odd number of the rings (the material a laser leaves)."""
    result = shapely.Polygon()
    for p in polygons:
        result = result.symmetric_difference(p)
    return float(result.area)


def edge_problems(pts: np.ndarray, closed: bool = True) -> tuple[int, int]:
    """(zero-length edges, repeated edges) of one polyline."""
    ring = np.vstack([pts, pts[:1]]) if closed else pts
    a, b = ring[:-1], ring[1:]
    zero = int((np.hypot(*(b - a).T) < 1e-9).sum())
    keys = {tuple(sorted((tuple(p), tuple(q)))) for p, q in zip(a.tolist(), b.tolist())}
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
    stars = [star_polygon(step * (i + 0.5), step * (j + 0.5), r_out, r_in, rotation=11.25 * (i + j))
             for i in range(grid) for j in range(grid)]
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
