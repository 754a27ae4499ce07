"""Render docs/surfaces.md's pictures: the texture roller, its imprint in clay, the lampshade lit from inside.

    python samples/render_surfaces.py [--out DIR] [--only roller imprint lampshade]

Needs Pillow. Writes into ``samples/renders/``:

- ``roller-60x80.png``: ``samples/roller-60x80.toml`` as ``fabtiles build`` makes it (the
  design's print, wrapped), standing on its end and seen from a little above: the body
  (plate, bore, rims' inner part) in birch, the raised pattern and rims in teal, as the
  3MF's two parts.
- ``roller-60x80-imprint.png``: what rolling that roller once round over clay leaves. It is
  built with the flat pipeline from the roller's own unrolled strip: the strip's region as
  the roller prints it (mirrored, the rims added, its small openings filled) is mirrored
  back (the clay meets the roller face to face) and sunk into a slab as a deboss as deep
  as the roller's relief (``print_model(..., style="deboss")``), then lit from a low
  light so that the grooves read. The rims' two tracks run along its long edges.
- ``lampshade-120x150.png``: ``samples/lampshade-120x150.toml`` as built, on a dark
  ground, lit from inside by a bulb on its axis: the outside is dim (a faint room
  light), every face turned to the bulb is lit as a diffuse surface, by the cosine of
  its angle to the bulb over the square of its distance, in a warm colour; the bulb is
  drawn as a glowing ball. No shadows inside the shade, no light through the material,
  no light cast out of it: a picture of where the openings are and what they show, not a
  photograph.

The renderer is :mod:`render_3d`'s (imported: perspective, flat-shaded triangles in a
z-buffer at 3x the output size, box-filtered down). Each picture takes a few seconds
and is the same PNG byte for byte on every run with the same numpy, Pillow and fabtiles;
the suite checks that the pictures exist and that the docs show them
(``tests/test_surface_pictures.py``), not their bytes: run this script again when the
cylinders change.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
OUT = HERE / "renders"
ROLLER = HERE / "roller-60x80.toml"
LAMPSHADE = HERE / "lampshade-120x150.toml"

BIRCH = (0.86, 0.80, 0.70)
TEAL = (0.13, 0.42, 0.55)
CLAY = (0.74, 0.45, 0.33)
"""Terracotta."""
SHADE_RGB = (0.93, 0.89, 0.80)
"""The shade's material: a warm white filament."""
BULB_RGB = np.array([1.0, 0.74, 0.42])
"""The bulb's light: warm white, about 2,700 K."""
LIGHT_BACKGROUND = ((0.97, 0.97, 0.96), (0.84, 0.86, 0.88))
DARK_BACKGROUND = ((0.075, 0.07, 0.08), (0.03, 0.028, 0.03))
SUPERSAMPLE = 3

PICTURES = {
    "roller": "roller-60x80.png",
    "imprint": "roller-60x80-imprint.png",
    "lampshade": "lampshade-120x150.png",
}
"""What each picture is written as, in ``--out``."""


def _r3d():
    sys.path.insert(0, str(HERE))
    import render_3d

    return render_3d


def built(design_path):
    """The design's models as ``fabtiles build`` makes them (:class:`~fabtiles.making.models.Models`)."""
    from fabtiles.designs.design_file import load_design
    from fabtiles.making.models import BuildOptions, Models

    design = load_design(design_path)
    return Models(design.build_tile(), BuildOptions.of_design(design))


def _triangles(part) -> np.ndarray:
    return np.asarray(part.vertices, np.float64)[np.asarray(part.faces)]


def _normals(tris):
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    length = np.linalg.norm(n, axis=1)
    ok = length > 0
    n[ok] /= length[ok, None]
    return n, ok


def _frame(tris, eye, right, up, forward, width, height, margin, shift=(0.0, 0.0)):
    """Pixel corners (m, 3, 2) and depths (m, 3) of triangles, the whole fitted in the frame with ``margin``;
    ``shift`` moves the picture by a fraction of the frame (x right, y down)."""
    rel = tris - eye
    cam_z = rel @ forward
    u, v = (rel @ right) / cam_z, (rel @ up) / cam_z
    span = max((u.max() - u.min()) / (width * (1 - 2 * margin)), (v.max() - v.min()) / (height * (1 - 2 * margin)))
    cu, cv = (u.max() + u.min()) / 2, (v.max() + v.min()) / 2

    def to_screen(points):
        r = points - eye
        z = r @ forward
        return np.stack(
            [
                ((r @ right) / z - cu) / span + width * (0.5 + shift[0]),
                height * (0.5 + shift[1]) - ((r @ up) / z - cv) / span,
            ],
            axis=-1,
        )

    return to_screen(tris), cam_z, to_screen


def _background(colours, height, width):
    g = np.linspace(0, 1, height)[:, None, None]
    return (1 - g) * np.asarray(colours[0]) + g * np.asarray(colours[1]) + np.zeros((1, width, 3))


def _floor_shadow(to_screen, centre, radius, width, height, blur):
    """0..1 darkness of a soft contact shadow: a disc of ``radius`` round ``centre`` on the floor ``z = 0``."""
    from PIL import Image, ImageDraw, ImageFilter

    t = np.linspace(0, 2 * np.pi, 180, endpoint=False)
    ring = np.stack([centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t), np.zeros_like(t)], axis=-1)
    pts = to_screen(ring)
    mask = Image.new("L", (width, height), 0)
    ImageDraw.Draw(mask).polygon([tuple(p) for p in pts.round(2)], fill=255)
    return np.asarray(mask.filter(ImageFilter.GaussianBlur(blur)), np.float64) / 255


def _finish(image, width, height):
    image = image.reshape(height, SUPERSAMPLE, width, SUPERSAMPLE, 3).mean(axis=(1, 3))
    return np.round(np.clip(image, 0, 1) * 255).astype(np.uint8)


# --------------------------------------------------------------------------- (a) the roller


def roller_picture(models, width=800, height=700):
    """The roller standing on its end, seen from the front left and a little above: an RGB array."""
    r3d = _r3d()
    cp = models.print
    radius = cp.outer_radius_mm
    length = models.cylinder.length_mm
    centre = np.array([radius, radius, length * 0.5])
    eye, right, up, forward = r3d.camera(
        centre, max(2 * radius, length), azimuth_deg=-30, elevation_deg=24, distance=2.6
    )
    tris, colours = [], []
    for name, part in cp.parts.items():
        t = _triangles(part.mesh)
        col, front = r3d.shade(t, TEAL if name == "pattern" else BIRCH, eye)
        tris.append(t[front])
        colours.append(col[front])
    tris, colours = np.concatenate(tris), np.concatenate(colours)
    w, h = width * SUPERSAMPLE, height * SUPERSAMPLE
    screen, depth, to_screen = _frame(tris, eye, right, up, forward, w, h, margin=0.1, shift=(0.0, -0.02))
    image, covered, zbuf = r3d.rasterize(screen, depth, colours, w, h)
    image *= 1 - r3d.EDGE_DARKEN * r3d._depth_edges(zbuf, covered)[:, :, None]
    bg = _background(LIGHT_BACKGROUND, h, w)
    shadow = _floor_shadow(to_screen, (radius + 2, radius - 3), radius * 1.2, w, h, 8 * SUPERSAMPLE)
    bg *= 1 - 0.5 * shadow[:, :, None]
    return _finish(np.where(covered[:, :, None], image, bg), width, height)


# --------------------------------------------------------------------------- (b) the imprint


def imprint_model(models):
    """The clay the roller leaves, a flat print: the roller's printed strip mirrored back, sunk as a deboss
    ``relief_mm`` deep into a slab (see the module text)."""
    from shapely import affinity

    from fabtiles.solid.print_model import print_model

    cylinder = models.cylinder
    strip = models.print.model  # the flat strip the roller is wrapped from, as printed
    region = strip.region
    if cylinder.mirror:
        region = affinity.scale(region, xfact=-1, yfact=1, origin=(cylinder.circumference_mm / 2, 0))
    return print_model(
        region,
        strip.outline,
        profile=models.options.printer,
        style="deboss",
        deboss_mm=cylinder.heights["relief_mm"],
        base_mm=6.0,
    )


CLAY_KEY = (-0.55, 0.35, 0.45)
"""Towards the imprint's key light: low, from the back left, so that each groove's far wall is lit and its near
wall falls in shade."""


def imprint_picture(models, width=900, height=520):
    """The imprint slab lying flat, seen from the front and above: an RGB array."""
    r3d = _r3d()
    model = imprint_model(models)
    tris = np.concatenate([_triangles(p.mesh) for p in model.parts.values()])
    lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
    centre = np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2]])
    eye, right, up, forward = r3d.camera(centre, hi[0] - lo[0], azimuth_deg=-8, elevation_deg=52, distance=1.5)
    n, ok = _normals(tris)
    front = ok & (np.einsum("ij,ij->i", n, r3d._normalize(eye - tris.mean(axis=1))) > 0)
    key = np.clip(n @ r3d._normalize(CLAY_KEY), 0, None)
    fill = np.clip(n @ r3d._normalize((0.3, -0.5, 0.8)), 0, None)
    light = 0.28 + 0.55 * key + 0.30 * fill
    colours = np.clip(np.asarray(CLAY)[None, :] * light[:, None], 0, 1)
    tris, colours = tris[front], colours[front]
    w, h = width * SUPERSAMPLE, height * SUPERSAMPLE
    screen, depth, _ = _frame(tris, eye, right, up, forward, w, h, margin=0.05)
    image, covered, zbuf = r3d.rasterize(screen, depth, colours, w, h)
    image *= 1 - 0.35 * r3d._depth_edges(zbuf, covered)[:, :, None]
    bg = _background(LIGHT_BACKGROUND, h, w) * (1 - 0.3 * r3d._soft_shadow(covered, SUPERSAMPLE)[:, :, None])
    return _finish(np.where(covered[:, :, None], image, bg), width, height)


# --------------------------------------------------------------------------- (c) the lampshade lit from inside


BULB_HEIGHT = 0.42
"""The bulb's centre on the axis, as a fraction of the shade's length (above the holder at its foot)."""
BULB_RADIUS_MM = 28.0
"""An A60 bulb's glass ball, about 60 mm across."""
ROOM_LIGHT = (-0.5, -0.8, 0.45)
"""Towards the faint room light that shows the outside."""


def _sphere(centre, radius, rings=24, segments=48):
    """Triangles (m, 3, 3) of a UV sphere, wound outwards."""
    theta = np.linspace(0, np.pi, rings + 1)
    phi = np.linspace(0, 2 * np.pi, segments + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    pts = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1) * radius + centre
    a, b = pts[:-1, :-1], pts[:-1, 1:]
    c, d = pts[1:, :-1], pts[1:, 1:]
    return np.concatenate([np.stack([a, c, d], -2).reshape(-1, 3, 3), np.stack([a, d, b], -2).reshape(-1, 3, 3)])


def lampshade_picture(models, width=760, height=700):
    """The shade lit by a bulb on its axis, on a dark ground: an RGB array (see the module text)."""
    r3d = _r3d()
    cp = models.print
    radius = cp.outer_radius_mm
    length = models.cylinder.length_mm
    axis = np.array([radius, radius])
    bulb = np.array([axis[0], axis[1], BULB_HEIGHT * length])
    centre = np.array([radius, radius, length * 0.5])
    eye, right, up, forward = r3d.camera(
        centre, max(2 * radius, length), azimuth_deg=-20, elevation_deg=16, distance=2.4
    )
    tris = np.concatenate([_triangles(p.mesh) for p in cp.parts.values()])
    n, ok = _normals(tris)
    mid = tris.mean(axis=1)
    front = ok & (np.einsum("ij,ij->i", n, r3d._normalize(eye - mid)) > 0)
    to_bulb = bulb - mid
    dist = np.linalg.norm(to_bulb, axis=1)
    facing = np.clip(np.einsum("ij,ij->i", n, to_bulb) / dist, 0, None)
    # the irradiance of a point light, 1 on a wall facing it at the shade's inner radius
    glow = facing * (cp.inner_radius_mm / dist) ** 2
    lit = np.asarray(SHADE_RGB) * BULB_RGB * (1 - np.exp(-2.2 * glow))[:, None] * 1.25
    room = np.clip(n @ r3d._normalize(ROOM_LIGHT), 0, None)
    dim = np.asarray(SHADE_RGB)[None, :] * (0.045 + 0.14 * room)[:, None]
    colours = np.clip(np.where((facing > 0)[:, None], lit + dim, dim), 0, 1)
    ball = _sphere(bulb, BULB_RADIUS_MM)
    bn, _ = _normals(ball)
    ball_front = np.einsum("ij,ij->i", bn, r3d._normalize(eye - ball.mean(axis=1))) > 0
    rim = np.einsum("ij,ij->i", bn, r3d._normalize(eye - ball.mean(axis=1)))
    ball_colours = np.clip(np.array([1.0, 0.93, 0.78])[None, :] * (0.8 + 0.2 * rim)[:, None], 0, 1)
    all_tris = np.concatenate([tris[front], ball[ball_front]])
    all_colours = np.concatenate([colours[front], ball_colours[ball_front]])
    w, h = width * SUPERSAMPLE, height * SUPERSAMPLE
    # framed by the shade alone (the bulb is inside it)
    _, _, to_screen = _frame(tris[front], eye, right, up, forward, w, h, margin=0.08)
    screen = to_screen(all_tris)
    depth = (all_tris - eye) @ forward
    image, covered, zbuf = r3d.rasterize(screen, depth, all_colours, w, h)
    edges = r3d._depth_edges(zbuf, covered)[:, :, None]
    image *= 1 - 0.3 * edges
    bg = _background(DARK_BACKGROUND, h, w)
    # a warm pool on the floor round the foot, where the light through the openings falls
    pool = _floor_shadow(to_screen, axis, radius * 1.9, w, h, 40 * SUPERSAMPLE)
    bg = bg + 0.16 * pool[:, :, None] * BULB_RGB
    return _finish(np.where(covered[:, :, None], image, bg), width, height)


def render(out: Path, only=None) -> list[Path]:
    """Write the pictures (all, or those named in ``only``) into ``out``; returns their paths."""
    from PIL import Image

    out.mkdir(parents=True, exist_ok=True)
    wanted = list(PICTURES) if not only else [k for k in PICTURES if k in only]
    written = []
    roller = built(ROLLER) if {"roller", "imprint"} & set(wanted) else None
    for key in wanted:
        if key == "roller":
            pixels = roller_picture(roller)
        elif key == "imprint":
            pixels = imprint_picture(roller)
        else:
            pixels = lampshade_picture(built(LAMPSHADE))
        path = out / PICTURES[key]
        Image.fromarray(pixels, "RGB").save(path, format="PNG", optimize=True)
        written.append(path)
    return written


def main(argv=None) -> list[Path]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--only", nargs="*", choices=list(PICTURES), help="draw only these pictures")
    args = ap.parse_args(argv)
    written = render(args.out, args.only)
    for p in written:
        print(f"wrote {p}")
    return written


if __name__ == "__main__":
    main()
