"""LightBurn project (``.lbrn2``): the laser file with the profile's settings on every layer.

The same contours, kerf and cut order as the DXF (:func:`~fabtiles.geometry.laser_checks.prepare_laser`),
in LightBurn's own XML, so a job opens with its speeds, powers and passes set:

- ``<LightBurnProject FormatVersion="1">`` (the ``.lbrn2`` layout), millimetres, y up,
  the file's coordinates as they are (LightBurn places the job where the file says).
- One ``<CutSetting>`` per layer used, in cut order: ``type`` ``"Cut"`` (LightBurn's
  *Line* mode) or ``"Scan"`` (*Fill*, for the engrave layer, with its ``interval``);
  ``index`` (the layer's palette colour), ``name``, ``minPower`` and ``maxPower``
  (percent), ``speed`` (mm/s), ``numPasses`` and ``priority`` (lower runs first:
  engrave, score, inner cuts, then the outline).
- Every contour one ``<Shape Type="Path">``: its vertices once each (the first not
  repeated) and a primitive list of straight lines ``L0 1 ... L(n-1) 0`` that closes it;
  a score line the same with no closing line. Its arcs are cubic Beziers (``B i j``, the
  handles on the vertices as ``c0x``/``c0y``, ``c1x``/``c1y``), at most a quarter turn each. No ``VertID``/``PrimID``
  (shared geometry) and an identity ``XForm``.

What the readers in the open read, and why these choices (``docs/laser-programs.md``):
LightBurn's shorthand ``LineClosed`` is read by MeerK40t as one line too many, so the
first edge would be cut twice; the ``type`` attribute is lowercase (MeerK40t and lbrnts
read no other); every ``CutIndex`` a shape names has its ``CutSetting`` (MeerK40t fails
to load a file without). Numbers are fixed-point with 4 decimals (0.1 um): lbrnts reads
no exponents, and the file is the same bytes on every run (coordinates keep their
trailing zeros; the settings are written short). Written with the standard
library: the project is plain XML.
"""

from __future__ import annotations

import functools

import numpy as np

from ..core.files import atomic_write
from ..core.report import Report
from ..geometry.arcs import Beziers, beziers_many
from ..geometry.cut_plan import CutPlan, plan_cut

APP_VERSION = "1.7.03"
"""The LightBurn version the project says it is for (a recent one: older LightBurn opens newer files too)."""

# LightBurn's palette (its layers 00-29), RGB: 00 black, 01 blue, 02 red, 03 green, ...
PALETTE = (
    "000000 0000FF FF0000 00E000 D0D000 FF8000 00E0E0 FF00FF B4B4B4 0000A0 A00000 00A000 A0A000 "
    "C08000 00A0FF A000A0 808080 7D87B9 BB7784 4A6FE3 D33F6A 8CD78C F0B98D F6C4E1 FA9ED4 500A78 "
    "B45A00 004754 86FA88 FFDB66"
).split()


def write_lbrn2(
    path,
    *,
    region,
    outline,
    centrelines=None,
    profile,
    mode=None,
    kerf_mm=None,
    fill_small_holes: bool = False,
    stroke=None,
    dxf_version=None,
) -> Report:
    """Write the LightBurn project of a tile's material ``region`` to ``path``.

    Parameters as :func:`~fabtiles.export.dxf.write_dxf` (``dxf_version`` is accepted
    and ignored, as by the laser SVG).

    >>> import tempfile, pathlib
    >>> from shapely.geometry import box
    >>> plate = box(0, 0, 40, 40).difference(box(10, 10, 30, 30))
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "plate.lbrn2"
    >>> r = write_lbrn2(out, region=plate, outline=box(0, 0, 40, 40), profile="laser-3mm-plywood")
    >>> out.read_text().count('<Shape Type="Path"'), r.stats["inner_contours"], r.stats["outer_contours"]
    (2, 1, 1)
    """
    from ..machines.profiles import load_profile
    from .formats import FORMATS

    profile = load_profile(profile, kind="laser")
    FORMATS["lbrn2"].check_cutter(profile)  # a LightBurn project is for lasers
    plan = plan_cut(
        region,
        outline,
        centrelines=centrelines,
        profile=profile,
        mode=mode,
        kerf_mm=kerf_mm,
        fill_small_holes=fill_small_holes,
        stroke=stroke,
        path=str(path),
        fmt="lbrn2",
    )
    atomic_write(path, lbrn2_bytes(plan))
    return plan.report


def palette_index(color_rgb: str, taken) -> int:
    """The LightBurn layer for a colour ``RRGGBB``: its nearest palette colour not ``taken``.

    >>> palette_index("FF0000", set()), palette_index("FF0000", {2}), palette_index("0000FF", set())
    (2, 10, 1)
    """
    target = np.array([int(color_rgb[i : i + 2], 16) for i in (0, 2, 4)], float)
    rgb = np.array([[int(c[i : i + 2], 16) for i in (0, 2, 4)] for c in PALETTE], float)
    order = np.argsort(np.linalg.norm(rgb - target, axis=1), kind="stable")
    return int(next(i for i in order if int(i) not in taken))


def _num(x: float) -> str:
    s = f"{x:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


@functools.lru_cache(maxsize=4096)
def _prims(n: int, closed: bool) -> str:
    """``L0 1L1 2...``: straight lines through ``n`` vertices in order, closing back to the first if ``closed``."""
    return "".join(f"L{i} {i + 1}" for i in range(n - 1)) + (f"L{n - 1} 0" if closed else "")


def _paths(rings, index: int, closed: bool) -> list:
    """The ``<Shape Type="Path">`` elements of ``rings`` on layer ``index``.

    ``rings`` are (n, 2) arrays (straight lines) or :class:`~fabtiles.geometry.arcs.Beziers`.
    Every coordinate of every ring formatted by one ``%`` with 4 decimals (trailing
    zeros kept: cutting them by regular expression cost more than the rest of the
    file): the 600 x 400 mm sheet's 67,800 vertices in about 0.06 s, where a number
    at a time took 0.2 s.
    """
    if not len(rings):
        return []
    straight = [r for r in rings if not isinstance(r, Beziers)]
    flat = np.concatenate(straight).ravel().tolist() if straight else []
    text = ("V%.4f %.4fc0x1c1x1" * (len(flat) // 2)) % tuple(flat)
    records = text.split("V")[1:]  # one "x yc0x1c1x1" per vertex
    out, at = [], 0
    for r in rings:
        if isinstance(r, Beziers):
            verts, prims = _bezier_path(r, closed)
        else:
            n = len(r)
            verts, prims = "V".join(records[at : at + n]), _prims(n, closed)
            at += n
        out.append(
            f'    <Shape Type="Path" CutIndex="{index}">\n        <XForm>1 0 0 1 0 0</XForm>\n'
            f"        <VertList>V{verts}</VertList>\n"
            f"        <PrimList>{prims}</PrimList>\n    </Shape>\n"
        )
    return out


def _bezier_path(path: Beziers, closed: bool) -> tuple[str, str]:
    """The vertex list (without its first ``V``) and the primitive list of a path with Beziers.

    A vertex is ``x y``, then its outgoing handle ``c0x X c0y Y`` when a Bezier (``B``)
    leaves it (``c0x1``, LightBurn's "no handle", else), then its incoming handle
    ``c1x X c1y Y`` when a Bezier ends there (``c1x1`` else): LightBurn's own layout, read
    by lbrnts and MeerK40t (a ``B i j`` primitive takes vertex i's ``c0`` and j's ``c1``).
    """
    xy, bez = path.xy, path.bezier
    n = len(xy)
    pieces = n if closed else n - 1
    incoming = np.roll(bez, 1) if closed else np.r_[False, bez[:-1]]
    c1_in = np.roll(path.c1, 1, axis=0)
    verts = []
    for i, (x, y) in enumerate(xy.tolist()):
        v = f"{x:.4f} {y:.4f}"
        v += f"c0x{path.c0[i, 0]:.4f}c0y{path.c0[i, 1]:.4f}" if bez[i] and i < pieces else "c0x1"
        v += f"c1x{c1_in[i, 0]:.4f}c1y{c1_in[i, 1]:.4f}" if incoming[i] else "c1x1"
        verts.append(v)
    prims = "".join(f"{'B' if bez[i] else 'L'}{i} {(i + 1) % n}" for i in range(pieces))
    return "V".join(verts), prims


def _cut_setting(layer, index: int, priority: int, kind: str) -> str:
    from xml.sax.saxutils import quoteattr

    rows = [
        ("index", index),
        ("name", layer.name),
        ("minPower", _num(layer.power_pct)),
        ("maxPower", _num(layer.power_pct)),
        ("speed", _num(layer.speed_mm_s)),
        ("numPasses", layer.passes),
        ("priority", priority),
    ]
    if kind == "Scan":
        rows.append(("interval", _num(layer.line_interval_mm)))
    body = "".join(f"        <{k} Value={quoteattr(str(v))}/>\n" for k, v in rows)
    return f'    <CutSetting type="{kind}">\n{body}    </CutSetting>\n'


def layer_groups(job: CutPlan):
    """``(profile key, layer, paths, closed, CutSetting type)`` of each layer, in cut order.

    A path is its (n, 2) vertices, or :class:`~fabtiles.geometry.arcs.Beziers` where it has
    arcs: LightBurn's curves are cubic Beziers (a ``Path``'s ``B`` primitives), so each arc is
    written as Beziers of at most a quarter turn, within a tenth of the profile's tolerance.
    """
    tol = job.profile.tolerance_mm
    out = []
    for cut in job.layers:
        curves = cut.curves_or_paths()
        bent = [k for k, c in enumerate(curves) if c.bulge.any()]
        paths = [c.xy for c in curves]
        for k, b in zip(
            bent, beziers_many([curves[k] for k in bent], tolerance_mm=tol, closed=cut.closed), strict=True
        ):
            paths[k] = b
        out.append((cut.key, cut.layer, paths, cut.closed, "Scan" if cut.fill else "Cut"))
    return out


def lbrn2_bytes(plan: CutPlan) -> bytes:
    """The LightBurn project of ``plan``, as bytes to write."""
    return lbrn2_text(plan).encode("utf-8")


def lbrn2_text(job: CutPlan) -> str:
    """The ``.lbrn2`` XML of a cut plan."""
    from .laser_svg import aci_to_hex

    head = [
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<LightBurnProject AppVersion="{APP_VERSION}" FormatVersion="1" MaterialHeight="0" '
        'MirrorX="False" MirrorY="False">\n',
    ]
    settings: list = []
    shapes: list = []
    taken: set = set()
    for priority, (_, layer, rings, closed, kind) in enumerate(layer_groups(job)):
        index = palette_index(aci_to_hex(layer.color)[1:], taken)
        taken.add(index)
        settings.append(_cut_setting(layer, index, priority, kind))
        shapes.extend(_paths(rings, index, closed))
    return "".join(head + settings + shapes + ["</LightBurnProject>\n"])
