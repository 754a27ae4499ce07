"""Render the relief STL of samples/table3-3.toml as a shaded picture for the README.

    python samples/render_3d.py [--out PATH] [--size 900x700] [--design TOML]

Needs Pillow (installed with the ``step`` extra; else ``pip install pillow``).

A small software renderer (numpy and Pillow, no GPU): the two bodies of the
relief (``build_meshes``: base plate and raised pattern) are seen in perspective
from above the front-left corner, each triangle flat-shaded (Lambert, a key
light and a fill light), rasterised into a z-buffer at 3x the output size and
box-filtered down for smooth edges. The output is deterministic: the same PNG
byte for byte on every run.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
DESIGN = HERE / "table3-3.toml"
OUT = HERE / "renders" / "table3-3-relief.png"

BASE_RGB = (0.86, 0.80, 0.70)
"""Base plate: light birch."""
PATTERN_RGB = (0.13, 0.42, 0.55)
"""Raised pattern: deep teal."""
BACKGROUND = ((0.97, 0.97, 0.96), (0.84, 0.86, 0.88))
"""Background gradient, top to bottom."""
KEY_LIGHT = (-0.45, -0.65, 0.62)
"""Direction towards the key light (from the front left, fairly low: walls stand out)."""
FILL_LIGHT = (0.7, 0.3, 0.65)
"""Direction towards the weaker fill light."""
SUPERSAMPLE = 3
EDGE_DARKEN = 0.45
"""How much the depth-edge lines darken a pixel."""
EDGE_FROM, EDGE_FULL = 2e-4, 2e-3
"""Relative bend of inverse depth where an edge line starts, and over which it reaches full strength."""
SHADOW = 0.35
"""Darkness of the soft shadow under the tile."""


def relief_bodies(design_path=DESIGN):
    """The ``base`` and ``pattern`` trimesh bodies of a design's relief (its printer profile)."""
    import fabtiles
    from fabtiles.designs.design_file import load_design
    from fabtiles.machines.profiles import DEFAULT_PRINTER_PROFILE
    from fabtiles.solid.parts import build_meshes

    design = load_design(design_path)
    tile = design.build_tile(tile_cls=fabtiles.Tile)
    return build_meshes(
        region=tile.region(),
        outline=tile.outline_shape(),
        profile=design.output.printer_profile or DEFAULT_PRINTER_PROFILE,
        style="relief",
    )


def _normalize(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def camera(center, extent, azimuth_deg=-28.0, elevation_deg=34.0, distance=1.45):
    """Eye position and the right, up and forward unit vectors of a camera aimed at ``center``."""
    az, el = np.radians(azimuth_deg), np.radians(elevation_deg)
    back = np.array([np.sin(az) * np.cos(el), -np.cos(az) * np.cos(el), np.sin(el)])
    eye = np.asarray(center, float) + distance * extent * back
    forward = _normalize(np.asarray(center, float) - eye)
    right = _normalize(np.cross(forward, [0.0, 0.0, 1.0]))
    up = np.cross(right, forward)
    return eye, right, up, forward


def shade(tris, rgb, eye):
    """Flat Lambert shading of triangles (m, 3, 3); returns the colours (m, 3) and a front-facing mask."""
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    length = np.linalg.norm(n, axis=1)
    ok = length > 0
    n[ok] /= length[ok, None]
    view = _normalize(eye - tris.mean(axis=1))
    front = ok & (np.einsum("ij,ij->i", n, view) > 0)
    key = np.clip(n @ _normalize(KEY_LIGHT), 0, None)
    fill = np.clip(n @ _normalize(FILL_LIGHT), 0, None)
    light = 0.30 + 0.62 * key + 0.22 * fill
    return np.clip(np.asarray(rgb)[None, :] * light[:, None], 0, 1), front


def rasterize(screen, depth, colors, width, height, chunk_pixels=4_000_000):
    """Z-buffer triangles given in pixel coordinates; returns the image (h, w, 3) and the coverage mask.

    ``screen`` (m, 3, 2) are the corners in pixels (x right, y down), ``depth``
    (m, 3) their distances along the view axis. Pixel centres inside a triangle
    (edge functions; depth ties resolve by triangle order) take its colour where
    it is nearest. Inverse depth is interpolated linearly in screen space, which
    is exact for flat triangles in perspective. Also returns the depth buffer.
    """
    zbuf = np.full(width * height, np.inf)
    image = np.zeros((width * height, 3))
    x0 = np.clip(np.floor(screen[:, :, 0].min(axis=1) - 0.5).astype(np.int64), 0, width - 1)
    x1 = np.clip(np.ceil(screen[:, :, 0].max(axis=1) - 0.5).astype(np.int64), 0, width - 1)
    y0 = np.clip(np.floor(screen[:, :, 1].min(axis=1) - 0.5).astype(np.int64), 0, height - 1)
    y1 = np.clip(np.ceil(screen[:, :, 1].max(axis=1) - 0.5).astype(np.int64), 0, height - 1)
    bw, bh = x1 - x0 + 1, y1 - y0 + 1
    count = bw * bh
    a, b, c = screen[:, 0], screen[:, 1], screen[:, 2]
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    keep = np.abs(area) > 1e-12
    order = np.flatnonzero(keep)
    starts = np.concatenate([[0], np.cumsum(count[order])])
    i = 0
    while i < len(order):
        j = int(np.searchsorted(starts, starts[i] + chunk_pixels, side="right")) - 1
        j = max(j, i + 1)
        t = order[i:j]
        n = count[t]
        tri = np.repeat(t, n)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        px = x0[tri] + k % bw[tri]
        py = y0[tri] + k // bw[tri]
        cx, cy = px + 0.5, py + 0.5
        ta, tb, tc = a[tri], b[tri], c[tri]
        w0 = (tb[:, 0] - cx) * (tc[:, 1] - cy) - (tb[:, 1] - cy) * (tc[:, 0] - cx)
        w1 = (tc[:, 0] - cx) * (ta[:, 1] - cy) - (tc[:, 1] - cy) * (ta[:, 0] - cx)
        w2 = (ta[:, 0] - cx) * (tb[:, 1] - cy) - (ta[:, 1] - cy) * (tb[:, 0] - cx)
        s = area[tri]
        inside = (w0 * s >= 0) & (w1 * s >= 0) & (w2 * s >= 0)
        tri, px, py = tri[inside], px[inside], py[inside]
        w0, w1, w2, s = w0[inside] / s[inside], w1[inside] / s[inside], w2[inside] / s[inside], s[inside]
        inv = w0 / depth[tri, 0] + w1 / depth[tri, 1] + w2 / depth[tri, 2]  # 1/z is affine on screen
        z = 1 / inv
        pix = py * width + px
        srt = np.lexsort((tri, z, pix))  # nearest first; ties by triangle index (deterministic)
        pix, z, tri = pix[srt], z[srt], tri[srt]
        first = np.ones(len(pix), bool)
        first[1:] = pix[1:] != pix[:-1]
        pix, z, tri = pix[first], z[first], tri[first]
        nearer = z < zbuf[pix]
        zbuf[pix[nearer]] = z[nearer]
        image[pix[nearer]] = colors[tri[nearer]]
        i = j
    covered = np.isfinite(zbuf)
    return image.reshape(height, width, 3), covered.reshape(height, width), zbuf.reshape(height, width)


def _depth_edges(zbuf, covered):
    """0..1 strength of silhouette and crease lines, from the depth buffer.

    Inverse depth is affine in screen space across any plane, so its second
    difference between neighbouring pixels is zero inside a face and large where
    the surface kinks (the foot and top of a wall) or jumps (a silhouette).
    """
    inv = np.where(covered, 1 / np.where(covered, zbuf, 1.0), 0.0)
    ref = inv[covered].mean()
    bend = np.zeros_like(inv)
    for axis in (0, 1):
        d2 = np.abs(np.diff(inv, n=2, axis=axis))
        pad = [(0, 0), (0, 0)]
        pad[axis] = (1, 1)
        bend = np.maximum(bend, np.pad(d2, pad))
    return np.clip((bend / ref - EDGE_FROM) / EDGE_FULL, 0, 1)


def _soft_shadow(covered, supersample):
    """A blurred, slightly offset copy of the tile's silhouette (0..1), for a contact shadow."""
    from PIL import Image, ImageFilter

    _h, _w = covered.shape
    shift = 6 * supersample
    m = np.zeros_like(covered, dtype=np.uint8)
    m[shift:, :] = covered[:-shift, :] * 255
    blurred = Image.fromarray(m, "L").filter(ImageFilter.GaussianBlur(10 * supersample))
    return np.asarray(blurred, dtype=np.float64) / 255


def render(bodies, width=900, height=700, supersample=SUPERSAMPLE):
    """Render the named bodies (``base``, ``pattern``) to an RGB uint8 array (height, width, 3)."""
    tris, colors = [], []
    lo = np.min([m.bounds[0] for m in bodies.values()], axis=0)
    hi = np.max([m.bounds[1] for m in bodies.values()], axis=0)
    center = (lo + hi) / 2
    center[2] = lo[2]
    eye, right, up, forward = camera(center, float(np.max(hi[:2] - lo[:2])))
    for name, mesh in bodies.items():
        t = np.asarray(mesh.vertices, np.float64)[np.asarray(mesh.faces)]
        rgb = PATTERN_RGB if name == "pattern" else BASE_RGB
        col, front = shade(t, rgb, eye)
        tris.append(t[front])
        colors.append(col[front])
    tris = np.concatenate(tris)
    colors = np.concatenate(colors)
    rel = tris - eye
    cam_x, cam_y, cam_z = rel @ right, rel @ up, rel @ forward
    u, v = cam_x / cam_z, cam_y / cam_z
    # fit the projected tile into the frame with a margin
    W, Hh = width * supersample, height * supersample
    margin = 0.06
    span = max((u.max() - u.min()) / (W * (1 - 2 * margin)), (v.max() - v.min()) / (Hh * (1 - 2 * margin)))
    sx = (u - (u.max() + u.min()) / 2) / span + W / 2
    sy = Hh / 2 - (v - (v.max() + v.min()) / 2) / span
    screen = np.stack([sx, sy], axis=-1)
    image, covered, zbuf = rasterize(screen, cam_z, colors, W, Hh)
    image *= 1 - EDGE_DARKEN * _depth_edges(zbuf, covered)[:, :, None]
    # background: a vertical gradient with a soft shadow under the tile
    g = np.linspace(0, 1, Hh)[:, None, None]
    bg = (1 - g) * np.asarray(BACKGROUND[0]) + g * np.asarray(BACKGROUND[1])
    bg = bg * (1 - SHADOW * _soft_shadow(covered, supersample)[:, :, None])
    image = np.where(covered[:, :, None], image, bg)
    # box filter down to the output size (anti-aliasing), then gamma-free 8-bit
    image = image.reshape(height, supersample, width, supersample, 3).mean(axis=(1, 3))
    return np.round(np.clip(image, 0, 1) * 255).astype(np.uint8)


def main(argv=None) -> Path:
    """Write the PNG; returns its path."""
    from PIL import Image

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--design", type=Path, default=DESIGN, help="the design to render (default table3-3)")
    ap.add_argument("--size", default="900x700", help="WIDTHxHEIGHT in pixels")
    args = ap.parse_args(argv)
    width, height = (int(s) for s in args.size.lower().split("x"))
    pixels = render(relief_bodies(args.design), width, height)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(pixels, "RGB").save(args.out, format="PNG", optimize=True)
    print(f"wrote {args.out}")
    return args.out


if __name__ == "__main__":
    main()
