"""The laser DXF as LibreCAD (Debian's ``librecad``) reads it: printed to PDF headless.

``librecad dxf2pdf`` runs without a display with ``QT_QPA_PLATFORM=offscreen``. The
PDF's page content is plain drawing operators: per colour, the line segments LibreCAD
drew. They must be the file's polylines, edge for edge, in the layers' colours and
in the file's proportions. `.ci/run` installs librecad and sets
FABTILES_REQUIRE_LIBRECAD=1, so there a missing program fails instead of skipping.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import zlib
from dataclasses import replace

import numpy as np
import pytest
from dxf_helpers import bulges, motif_tile, star_plate, vertices
from model_files import write_cut
from real_programs import program

from fabtiles.machines.profiles import LaserLayers, Layer, load_profile

LIBRECAD = shutil.which("librecad")
DEFAULT = load_profile("laser-3mm-plywood")
# The bundled profiles draw both cuts red (docs/laser-programs.md); these tests tell the layers
# apart by colour, so they give each layer its own: inner red, outer blue, score green.
PLY = replace(
    DEFAULT,
    layers=LaserLayers(
        inner_cut=Layer(DEFAULT.layers.inner_cut.name, 1),
        outer_cut=Layer(DEFAULT.layers.outer_cut.name, 5),
        score=Layer(DEFAULT.layers.score.name, 3),
    ),
)
# ACI colours as LibreCAD prints them (RGB 0..1)
RGB = {1: (1.0, 0.0, 0.0), 3: (0.0, 1.0, 0.0), 5: (0.0, 0.0, 1.0)}


@pytest.fixture(scope="module")
def librecad():
    if LIBRECAD is None:
        if os.environ.get("FABTILES_REQUIRE_LIBRECAD") == "1":
            pytest.fail("LibreCAD test required but `librecad` is not installed (apt-get install librecad)")
        pytest.skip("librecad is not installed")
    return LIBRECAD


def _print_pdf(librecad, dxf, tmp_path):
    # LibreCAD 2.2 ignores -o for one file: it prints <name>.dxf to <name>.pdf beside it
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_RUNTIME_DIR=str(tmp_path))
    subprocess.run(
        [librecad, "dxf2pdf", "-a", str(dxf)], env=env, check=True, capture_output=True, timeout=120, cwd=tmp_path
    )
    return dxf.with_suffix(".pdf").read_bytes()


def _segments_by_colour(pdf: bytes) -> dict:
    """The stroked line segments of the PDF's page, by stroke colour: {rgb: array (k, 2, 2)}."""
    out: dict = {}
    for stream in re.findall(rb"stream\r?\n(.*?)endstream", pdf, re.S):
        try:
            text = zlib.decompress(stream).decode("latin-1")
        except zlib.error:
            text = stream.decode("latin-1")
        colour, start, stack = None, None, []
        for tok in text.split():
            if tok == "SCN" and len(stack) >= 3:
                colour = tuple(float(v) for v in stack[-3:])
            elif tok == "m":
                start = (float(stack[-2]), float(stack[-1]))
            elif tok == "l" and colour is not None and start is not None:
                end = (float(stack[-2]), float(stack[-1]))
                out.setdefault(colour, []).append((start, end))
                start = end
            stack = stack[-8:] + [tok] if tok not in ("m", "l") else []
    return {c: np.array(s) for c, s in out.items()}


def _dxf_edges(path, layer) -> int:
    import ezdxf

    n = 0
    for e in ezdxf.readfile(path).modelspace():
        if e.dxf.layer == layer.name:
            n += len(vertices(e)) - (0 if e.is_closed else 1)
    return n


def drawn_and_cut_edges(dxf, tmp_path, profile_name: str = "laser-3mm-plywood") -> tuple[int, int]:
    """The line segments LibreCAD prints of ``dxf`` and the edges of its inner and outer cuts: equal when
    LibreCAD draws every cut."""
    librecad = program("librecad", "apt-get install librecad")
    profile = load_profile(profile_name)
    drawn = _segments_by_colour(_print_pdf(librecad, dxf, tmp_path))
    edges = _dxf_edges(dxf, profile.layers.inner_cut) + _dxf_edges(dxf, profile.layers.outer_cut)
    return sum(len(s) for s in drawn.values()), edges


def _extent(points) -> np.ndarray:
    pts = np.asarray(points).reshape(-1, 2)
    return pts.max(0) - pts.min(0)


def _arc_middles(dxf, layers, doc=None) -> np.ndarray:
    """The middle point of every arc (bulged edge) of the file's polylines on ``layers``, in mm (``doc``:
    the file as ezdxf read it, when the caller has it)."""
    import ezdxf
    from dxf_helpers import bulges, is_closed, raw_vertices

    out = []
    for e in (doc or ezdxf.readfile(dxf)).modelspace():
        if e.dxf.layer not in layers:
            continue
        xy, b = raw_vertices(e), bulges(e)
        nxt = np.roll(xy, -1, axis=0)
        arc = b != 0 if is_closed(e) else (b != 0) & (np.arange(len(b)) < len(b) - 1)
        for (ax, ay), (zx, zy), bb in zip(xy[arc], nxt[arc], b[arc], strict=True):
            # the arc's middle stands off its chord's middle by the sagitta, c/2 * b, to the right of a/z for b > 0
            dx, dy = zx - ax, zy - ay
            out.append(((ax + zx) / 2 + dy * bb / 2, (ay + zy) / 2 - dx * bb / 2))
    return np.array(out).reshape(-1, 2)


def assert_draws_the_curves(drawn: np.ndarray, dxf, layers, *, tol_mm: float) -> None:
    """LibreCAD drew the file's curves: its drawing, moved and scaled onto the file, lies within
    ``tol_mm`` of the polylines as ezdxf draws them (arcs and all), and every arc's middle point
    (off its chord by the sagitta) is on the drawing: an arc drawn as its chord would not be.

    LibreCAD 2.2 puts the points of the arcs it draws up to 0.13 mm off them on a 150 mm sheet
    (its straight edges within 0.007 mm): ``tol_mm`` allows for it; the 20 mm circles' half-turn
    arcs stand 20 mm off their chords."""
    import ezdxf
    from scipy.spatial import cKDTree

    doc = ezdxf.readfile(dxf)
    ref = np.vstack([vertices(e) for e in doc.modelspace() if e.dxf.layer in layers])
    pts = np.asarray(drawn).reshape(-1, 2)
    scale = _extent(pts)[0] / _extent(ref)[0]
    assert _extent(pts)[1] / scale == pytest.approx(_extent(ref)[1], rel=1e-3)
    # points every tenth of the tolerance (at least 0.01 mm): none of the curves more than a twentieth of it off
    tree_ref = cKDTree(_densify(ref, step=max(0.01, tol_mm / 10)))
    seg = np.asarray(drawn).reshape(-1, 2, 2)
    t = np.linspace(0, 1, 5)[None, :, None]
    dense = (seg[:, :1] + (seg[:, 1:] - seg[:, :1]) * t).reshape(-1, 2)

    def onto_file(p, flip):  # the page's y may run down: whichever lays the drawing on the file
        q = (p - pts.min(0)) / scale
        if flip:
            q[:, 1] = _extent(pts)[1] / scale - q[:, 1]
        return q + ref.min(0)

    flip = min((False, True), key=lambda f: np.median(tree_ref.query(onto_file(pts[::97], f))[0]))
    mm, dense = onto_file(pts, flip), onto_file(dense, flip)
    # the drawing against the curves' points (ezdxf's, 1 micrometre apart at most, densified)
    assert tree_ref.query(mm)[0].max() <= tol_mm
    mids = _arc_middles(dxf, layers, doc)
    if len(mids):
        assert cKDTree(dense).query(mids)[0].max() <= tol_mm


def _densify(points: np.ndarray, step: float = 0.01) -> np.ndarray:
    """``points`` with points every ``step`` mm between neighbours closer than 1 mm (the curves' pieces)."""
    a, b = points[:-1], points[1:]
    d = np.hypot(*(b - a).T)
    near = d < 1.0
    k = np.maximum(1, np.ceil(d[near] / step).astype(int))
    reps = np.repeat(np.arange(near.sum()), k)
    t = (np.arange(k.sum()) - np.repeat(np.cumsum(k) - k, k)) / k[reps]
    return np.vstack([points, a[near][reps] + (b[near] - a[near])[reps] * t[:, None]])


@pytest.mark.parametrize("version", ["R12", "R2000"])
def test_librecad_draws_the_cut_contours(librecad, tmp_path, version):
    region, outline = star_plate()
    dxf = tmp_path / "plate.dxf"
    write_cut(dxf, region=region, outline=outline, profile=PLY, dxf_version=version)
    drawn = _segments_by_colour(_print_pdf(librecad, dxf, tmp_path))
    inner, outer = drawn[RGB[PLY.layers.inner_cut.color]], drawn[RGB[PLY.layers.outer_cut.color]]
    assert len(inner) == _dxf_edges(dxf, PLY.layers.inner_cut)  # 9 stars of 16 edges
    assert len(outer) == _dxf_edges(dxf, PLY.layers.outer_cut) == 4
    # proportions: the stars span 60 - 2 * 2.5 mm of the 60.15 mm outer contour (kerf 0.15 mm)
    scale = _extent(outer)[0] / (60 + PLY.kerf_mm)
    assert _extent(outer)[1] / scale == pytest.approx(60 + PLY.kerf_mm, rel=1e-3)
    import ezdxf

    doc = ezdxf.readfile(dxf)
    stars = np.vstack([vertices(e) for e in doc.modelspace() if e.dxf.layer == PLY.layers.inner_cut.name])
    assert _extent(inner) / scale == pytest.approx(_extent(stars), rel=2e-3)


def test_librecad_draws_the_bundled_profiles_cuts_red_and_score_blue(librecad, tmp_path):
    region, outline, lines = motif_tile()
    for mode in ("pierced", "score"):
        dxf = tmp_path / f"{mode}.dxf"
        write_cut(dxf, region=region, outline=outline, centrelines=lines, profile=DEFAULT, mode=mode, stroke=1.2)
        drawn = {c: len(s) for c, s in _segments_by_colour(_print_pdf(librecad, dxf, tmp_path)).items()}
        cuts = _dxf_edges(dxf, DEFAULT.layers.inner_cut) + _dxf_edges(dxf, DEFAULT.layers.outer_cut)
        want = {RGB[1]: cuts}
        if mode == "score":
            want[RGB[5]] = _dxf_edges(dxf, DEFAULT.layers.score)
        assert drawn == want


def test_librecad_draws_the_score_paths(librecad, tmp_path):
    region, outline, lines = motif_tile()
    dxf = tmp_path / "score.dxf"
    write_cut(dxf, region=region, outline=outline, centrelines=lines, profile=PLY, mode="score", stroke=1.2)
    drawn = _segments_by_colour(_print_pdf(librecad, dxf, tmp_path))
    assert len(drawn[RGB[PLY.layers.score.color]]) == _dxf_edges(dxf, PLY.layers.score)
    assert len(drawn[RGB[PLY.layers.outer_cut.color]]) == 4
    assert RGB[PLY.layers.inner_cut.color] not in drawn


def test_librecad_draws_a_nested_sheet(librecad, tmp_path):
    # issue 34: a sheet of two designs nested, turned copies and all, drawn whole and in proportion
    import ezdxf

    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making.nesting import nest_designs

    designs = [
        (
            design_from_text(
                f'[motif]\npreset = "table3-{k}"\n[packing]\nradius = 8\n[tile]\noutline = '
                f'"{outline}"\nsize = 40\nframe = 3\nstroke = 1.0\n',
                name=outline,
            ),
            3,
        )
        for k, outline in ((1, "hexagon"), (3, "circle"))
    ]
    nest_designs(designs, tmp_path, ("dxf",), sheet_mm=(150, 100), time_s=1)
    dxf = tmp_path / "nest-sheet-1.dxf"  # a sheet of several designs is named after none of them
    drawn = _segments_by_colour(_print_pdf(librecad, dxf, tmp_path))
    red = drawn[RGB[1]]  # the bundled profile cuts both layers red
    # every straight edge a segment, every arc (the circle tiles' outlines) several
    straight = sum(int((bulges(e) == 0).sum()) for e in ezdxf.readfile(dxf).modelspace())
    assert len(red) > straight
    assert_draws_the_curves(red, dxf, {DEFAULT.layers.inner_cut.name, DEFAULT.layers.outer_cut.name}, tol_mm=0.2)
    points = np.vstack([vertices(e) for e in ezdxf.readfile(dxf).modelspace()])
    scale = _extent(red)[0] / _extent(points)[0]
    assert _extent(red)[1] / scale == pytest.approx(_extent(points)[1], rel=1e-3)


@pytest.mark.parametrize("version", ["R12", "R2000"])
def test_librecad_draws_the_arcs(librecad, tmp_path, version):
    # issue 35: a circle tile with round joins and outline circles, its curves as arcs (bulges)
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making.models import BuildOptions, Models

    design = design_from_text(
        '[packing]\nkind = "archimedean"\ntiling = "3.3.3.4.4"\noutline_circles = true\n'
        '[tile]\noutline = "circle"\nsize = 60\njoin = "round"\n',
        name="circles",
    )
    plan = Models(design.build_tile(), BuildOptions.of_design(design)).cut
    assert plan.report.stats["arcs"] > 100
    dxf = tmp_path / "circles.dxf"
    write_cut(
        dxf,
        region=design.build_tile().region(),
        outline=design.build_tile().outline_shape(),
        profile=DEFAULT,
        dxf_version=version,
    )
    drawn = _segments_by_colour(_print_pdf(librecad, dxf, tmp_path))
    assert set(drawn) == {RGB[1]}
    assert_draws_the_curves(
        drawn[RGB[1]], dxf, {DEFAULT.layers.inner_cut.name, DEFAULT.layers.outer_cut.name}, tol_mm=0.2
    )
