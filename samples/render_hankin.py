"""Draw the pictures of docs/hankin.md into samples/pictures/hankin/.

    python samples/render_hankin.py

``construction.svg``: one octagon's rays, the contact angle and the corners' bisectors,
without and with a contact gap; ``<tiling>-<angle>.svg``: the table of the 11 tilings at
four contact angles, the tiling's edges faint under the centre-lines; ``parquet.svg``: a
parquet deformation, the angle going from 20 to 80 degrees left to right. The files are
reproducible byte for byte; tests/test_doc_pictures.py checks the committed ones are current.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fabtiles import ArchimedeanPacking
from fabtiles.core.files import atomic_write
from fabtiles.pattern.hankin import polygon_rays
from fabtiles.pattern.tilings import TILINGS, circumradius, unit_cell

HERE = Path(__file__).resolve().parent
OUT = HERE / "pictures" / "hankin"
ANGLES = (30, 45, 60, 75)
"""The table's contact angles, degrees (no gap)."""
EDGE = 10.0
HALF = 22.0  # each table picture shows the square (-HALF, HALF)^2 of the pattern, mm
SIZE = 160  # px


def _f(v: float) -> str:
    return f"{v:.3f}".rstrip("0").rstrip(".").replace("-0", "0") if abs(v) >= 5e-4 else "0"


def _lines(segments, **attrs) -> str:
    a = " ".join(f'{k.replace("_", "-")}="{v}"' for k, v in attrs.items())
    d = " ".join(f"M{_f(p[0])} {_f(-p[1])}L{_f(q[0])} {_f(-q[1])}" for p, q in segments)
    return f'<path d="{d}" {a}/>'


def _tiling_edges(tiling: str, half: float) -> np.ndarray:
    """The tiling's polygon edges near the square of half side ``half`` (edge ``EDGE``), each once."""
    cell = unit_cell(tiling)
    lat = cell.lattice * EDGE
    n = int(2 * half / min(np.hypot(*lat.T))) + 4
    edges = {}
    for i in range(-n, n + 1):
        for j in range(-n, n + 1):
            for c, p, a in zip(cell.centres * EDGE, cell.sides.tolist(), cell.angles, strict=True):
                c = c + i * lat[0] + j * lat[1]
                if np.abs(c).max() > half + EDGE * 2:
                    continue
                t = a + math.pi / p + 2 * math.pi * np.arange(p + 1) / p
                v = c + circumradius(p, EDGE) * np.stack([np.cos(t), np.sin(t)], axis=1)
                for k in range(p):
                    key = tuple(sorted((tuple(np.round(v[k], 6)), tuple(np.round(v[k + 1], 6)))))
                    edges[key] = (v[k], v[k + 1])
    return np.array([edges[k] for k in sorted(edges)])


def table_picture(tiling: str, angle: float) -> str:
    """One cell of the table: the tiling ``tiling`` by Hankin's rays at ``angle``, as SVG text."""
    pack = ArchimedeanPacking(tiling, EDGE, method="hankin", contact_angle=angle)
    rays = pack.segments((-HALF, -HALF, HALF, HALF))
    box = f"{_f(-HALF)} {_f(-HALF)} {_f(2 * HALF)} {_f(2 * HALF)}"
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{SIZE}" height="{SIZE}" viewBox="{box}">\n'
        f"<title>{tiling}, contact angle {angle:g} degrees</title>\n"
        f'<defs><clipPath id="c"><rect x="{_f(-HALF)}" y="{_f(-HALF)}" width="{_f(2 * HALF)}" '
        f'height="{_f(2 * HALF)}"/></clipPath></defs>\n'
        f'<rect x="{_f(-HALF)}" y="{_f(-HALF)}" width="{_f(2 * HALF)}" height="{_f(2 * HALF)}" fill="#fff"/>\n'
        f'<g clip-path="url(#c)" fill="none" stroke-linecap="round">\n'
        f"{_lines(_tiling_edges(tiling, HALF), stroke='#b8c4d6', stroke_width='0.25')}\n"
        f"{_lines(rays, stroke='#1d3b6e', stroke_width='0.6')}\n</g>\n</svg>\n"
    )


def parquet_picture(tiling: str = "4.8.8", angles=(20.0, 80.0), half=(66.0, 16.5)) -> str:
    """A strip of ``tiling`` whose contact angle goes from ``angles[0]`` at its left to ``angles[1]`` at its right."""
    w, h = half
    pack = ArchimedeanPacking(
        tiling, EDGE, method="hankin", contact_angle=angles[0], contact_angle_to=angles[1], parquet_direction="x"
    )
    rays = pack.segments((-w, -h, w, h))
    box = f"{_f(-w)} {_f(-h)} {_f(2 * w)} {_f(2 * h)}"
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{4 * SIZE}" height="{round(4 * SIZE * h / w)}" '
        f'viewBox="{box}">\n'
        f"<title>{tiling}, contact angle {angles[0]:g} to {angles[1]:g} degrees left to right</title>\n"
        f'<defs><clipPath id="c"><rect x="{_f(-w)}" y="{_f(-h)}" width="{_f(2 * w)}" '
        f'height="{_f(2 * h)}"/></clipPath></defs>\n'
        f'<rect x="{_f(-w)}" y="{_f(-h)}" width="{_f(2 * w)}" height="{_f(2 * h)}" fill="#fff"/>\n'
        f'<g clip-path="url(#c)" fill="none" stroke-linecap="round">\n'
        f"{_lines(_tiling_edges(tiling, w), stroke='#b8c4d6', stroke_width='0.25')}\n"
        f"{_lines(rays, stroke='#1d3b6e', stroke_width='0.6')}\n</g>\n</svg>\n"
    )


def construction_picture() -> str:
    """An octagon's rays at 60 degrees without a gap (left) and with a gap of a third of the edge (right)."""
    p, a, angle = 8, 40.0, 60.0
    r_in, r_out = a / (2 * math.tan(math.pi / p)), circumradius(p, a)
    parts = []
    for shift, gap, title in ((-55.0, 0.0, "no gap"), (55.0, a / 3, "gap g = a / 3")):
        o = np.array([shift, 0.0])
        t = math.pi / p + 2 * math.pi * np.arange(p + 1) / p
        corners = o + r_out * np.stack([np.cos(t), np.sin(t)], axis=1)
        outline = np.stack([corners[:-1], corners[1:]], axis=1)
        bisectors = np.stack([corners[:-1], np.repeat(o[None], p, axis=0)], axis=1)
        rays = polygon_rays(p, a, angle, gap).reshape(-1, 2, 2) + o
        parts.append(_lines(outline, stroke="#8a99b3", stroke_width="0.6", fill="none"))
        parts.append(_lines(bisectors, stroke="#c9a227", stroke_width="0.4", stroke_dasharray="2 1.5"))
        parts.append(_lines(rays, stroke="#1d3b6e", stroke_width="1.1"))
        # the right-hand edge (k = 0): its midpoint, the ray starts and the angle between a ray and the edge
        mid = o + np.array([r_in, 0.0])
        starts = polygon_rays(p, a, angle, gap)[0, :, 0] + o
        for s in starts:
            parts.append(f'<circle cx="{_f(s[0])}" cy="{_f(-s[1])}" r="1" fill="#c0392b"/>')
        s = starts[0]  # ray 0 starts below the midpoint (gap / 2) and leans up, towards the upper corner
        arc = 9.0
        end = s + arc * np.array([-math.sin(math.radians(angle)), math.cos(math.radians(angle))])
        parts.append(
            f'<path d="M{_f(s[0])} {_f(-(s[1] + arc))}A{_f(arc)} {_f(arc)} 0 0 0 {_f(end[0])} '
            f'{_f(-end[1])}" fill="none" stroke="#c0392b" stroke-width="0.5"/>'
        )
        parts.append(
            f'<text x="{_f(s[0] - 9)}" y="{_f(-(s[1] + 10))}" font-size="4.5" fill="#c0392b">{angle:g}°</text>'
        )
        # the midpoint M, or the gap g between the two starts, beside the edge
        parts.append(
            f'<text x="{_f(mid[0] + 2)}" y="{_f(-mid[1] + 1.5)}" font-size="4" '
            f'fill="{"#c0392b" if gap else "#333"}">{"g" if gap else "M"}</text>'
        )
        parts.append(
            f'<text x="{_f(shift)}" y="{_f(r_out + 8)}" font-size="5" text-anchor="middle" fill="#333">{title}</text>'
        )
    body = "\n".join(parts)
    return (
        '<svg xmlns="http://www.w3.org/2000/svg" width="672" height="372" viewBox="-112 -58 224 124" '
        'font-family="sans-serif">\n<title>Hankin\'s construction on an octagon</title>\n'
        f'<rect x="-112" y="-58" width="224" height="124" fill="#fff"/>\n{body}\n</svg>\n'
    )


def render(out: Path = OUT) -> list[Path]:
    """Write every picture into ``out``; return their paths."""
    out.mkdir(parents=True, exist_ok=True)
    written = [out / "construction.svg"]
    atomic_write(written[0], construction_picture().encode())
    written.append(out / "parquet.svg")
    atomic_write(written[-1], parquet_picture().encode())
    for tiling in TILINGS:
        for angle in ANGLES:
            path = out / f"{tiling}-{angle}.svg"
            atomic_write(path, table_picture(tiling, angle).encode())
            written.append(path)
    return written


def table_markdown() -> str:
    """The docs' table of the pictures: a row per tiling, a column per angle."""
    rows = ["| tiling | " + " | ".join(f"{a}°" for a in ANGLES) + " |", "|---|" + "---|" * len(ANGLES)]
    for tiling in TILINGS:
        cells = " | ".join(f"![{tiling} at {a} degrees](../samples/pictures/hankin/{tiling}-{a}.svg)" for a in ANGLES)
        rows.append(f"| {tiling} | {cells} |")
    return "\n".join(rows)


if __name__ == "__main__":
    for path in render():
        print(f"wrote {path.relative_to(HERE.parent)}")
