"""Interlaced tiles in the files (issue 16): the score DXF read back, the relief STL, the cut, the errors."""

import itertools
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
from dxf_helpers import dxf_entities
from shapely.geometry import Point

import fabtiles as ft
from fabtiles import ParameterError

ROSETTES = ["table1-part2", "table2-left", "table2-right", "table3-1", "table3-2", "table3-3"]
BASE, RELIEF = 2.0, 1.2  # fdm-0.4mm


def small_tile(**kw):
    args = dict(frame=2, stroke=1.0, interlace=True)
    args.update(kw)
    return ft.Tile("square", 50, ft.HexPacking(radius=12, motif=ft.Star.preset("table3-1")), **args)


def brute_crossings(seg):
    """Interior crossings of every pair of segments, O(n^2): (point, i, j, unit dir i, unit dir j)."""
    out = []
    for i, j in itertools.combinations(range(len(seg)), 2):
        p, r = seg[i, 0], seg[i, 1] - seg[i, 0]
        q, s = seg[j, 0], seg[j, 1] - seg[j, 0]
        den = r[0] * s[1] - r[1] * s[0]
        lr, ls = np.linalg.norm(r), np.linalg.norm(s)
        if abs(den) < 1e-9 * lr * ls:
            continue
        t = ((q - p)[0] * s[1] - (q - p)[1] * s[0]) / den
        u = ((q - p)[0] * r[1] - (q - p)[1] * r[0]) / den
        if 1e-6 / lr < t < 1 - 1e-6 / lr and 1e-6 / ls < u < 1 - 1e-6 / ls:
            out.append((p + t * r, i, j, r / lr, s / ls, t, u))
    return out


def score_segments(path):
    import ezdxf

    doc = ezdxf.readfile(path)
    segs = []
    for e in doc.modelspace().query("LWPOLYLINE[layer=='SCORE']"):
        pts = np.array([v[:2] for v in e.get_points("xy")], float)
        segs += [pts[k : k + 2] for k in range(len(pts) - 1)]
    return np.array(segs)


def covered(segs, p, d, half_len):
    """True when the score lines run whole through p along d (from p - half_len d to p + half_len d)."""
    a, b = segs[:, 0], segs[:, 1]
    ab = b - a
    length = np.linalg.norm(ab, axis=1)
    along = np.abs(ab[:, 0] * d[1] - ab[:, 1] * d[0]) < 1e-6 * length
    dist = np.abs((p - a)[:, 0] * ab[:, 1] - (p - a)[:, 1] * ab[:, 0]) / length
    t = np.einsum("ij,ij->i", p - a, ab) / length**2
    return bool(np.any(along & (dist < 1e-4) & (t * length > half_len) & ((1 - t) * length > half_len)))


def test_score_dxf_shows_the_weave(tmp_path):
    tile = small_tile()
    out = tmp_path / "woven.dxf"
    report = tile.export(out, profile="laser-3mm-plywood", mode="score")
    # the file is the tile moved into the positive quadrant (by its outline's half kerf): moved back
    assert report.stats["file_offset_mm"] == pytest.approx([0.075, 0.075], abs=1e-9)
    segs = score_segments(out) - report.stats["file_offset_mm"]
    seg = tile.segments()
    inner = tile.inner_shape()
    # the hidden length is at most (stroke + 2 gap) / sin: stay that far inside
    states = {}
    crossings = brute_crossings(seg)
    points = np.array([c[0] for c in crossings])
    for p, i, j, di, dj, ti, tj in crossings:
        sin = abs(di[0] * dj[1] - di[1] * dj[0])
        reach = (tile.stroke / 2 + tile.interlace_gap_mm) / sin
        if not inner.contains(Point(p).buffer(reach + 0.1)):
            continue
        # crossings closer than two hidden lengths share their gaps: judged apart only
        if np.sort(np.linalg.norm(points - p, axis=1))[1] < 2 * reach + 0.1:
            states.setdefault(i, []).append((ti, None))
            states.setdefault(j, []).append((tj, None))
            continue
        whole_i = covered(segs, p, di, 1e-3)
        whole_j = covered(segs, p, dj, 1e-3)
        assert whole_i != whole_j, f"crossing at {p}: exactly one strand must be whole"
        # the broken strand has no score line within the over band plus the clearance
        under_d = dj if whole_i else di
        assert not covered(segs, p, under_d, 0.0)
        states.setdefault(i, []).append((ti, whole_i))
        states.setdefault(j, []).append((tj, whole_j))
    assert sum(v is not None for visits in states.values() for _, v in visits) >= 40
    checked = 0
    for visits in states.values():
        visits.sort()
        for (_, a), (_, b) in itertools.pairwise(visits):
            if a is not None and b is not None:
                assert a != b, "along a segment the crossings must alternate over, under"
                checked += 1
    assert checked >= 10


def test_pierced_dxf_is_unchanged_without_interlace_cut(tmp_path):
    a, b = tmp_path / "a.dxf", tmp_path / "b.dxf"
    small_tile().export(a)
    small_tile(interlace=False).export(b)
    assert dxf_entities(a) == dxf_entities(b)


def test_interlace_cut_cuts_the_under_gaps_and_keeps_every_piece(tmp_path):
    tile = small_tile(stroke=2.0, interlace_cut=True)
    report = tile.export(tmp_path / "cut.dxf")
    plain = tile.replace(interlace_cut=False).export(tmp_path / "plain.dxf")
    assert report.stats["inner_contours"] > plain.stats["inner_contours"]
    assert "loose_part" not in {f.code for f in report.findings}


def relief_tops(path):
    mesh = trimesh.load(path)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    up = mesh.face_normals[:, 2] > 0.999
    return mesh, {round(float(z), 4) for z in mesh.triangles_center[up, 2]}


def test_relief_stl_dips_under_strands(tmp_path):
    tile = small_tile()
    out = tmp_path / "woven.stl"
    tile.export(out, profile="fdm-0.4mm")
    mesh, tops = relief_tops(out)
    assert tops == {BASE, round(BASE + RELIEF / 2, 4), BASE + RELIEF}
    plain, plain_tops = relief_tops(tile.replace(interlace=False).export(tmp_path / "p.stl") and tmp_path / "p.stl")
    assert plain_tops == {BASE, BASE + RELIEF}
    assert mesh.volume < plain.volume


@pytest.mark.parametrize("preset", ROSETTES + ["plain"])
def test_rosette_presets_and_a_plain_star_weave(tmp_path, preset):
    star = ft.Star(n=8, radii=(51, 70, 172)) if preset == "plain" else ft.Star.preset(preset)
    tile = ft.Tile("circle", 60, star, frame=2, stroke=1.0, interlace=True)
    assert len(tile.weave()) > 0 and tile.weave().conflicts == 0
    woven = tile.export(tmp_path / "t.dxf", mode="score").stats
    plain = tile.replace(interlace=False).export(tmp_path / "u.dxf", mode="score").stats
    assert woven["score_length_mm"] < plain["score_length_mm"]
    _, tops = relief_tops(tile.export(tmp_path / "t.stl") and tmp_path / "t.stl")
    assert round(BASE + RELIEF / 2, 4) in tops and BASE + RELIEF in tops
    assert "<path" in (tile.export(tmp_path / "t.svg") and (tmp_path / "t.svg").read_text())


def test_woven_preview_breaks_the_under_bands():
    from fabtiles.export.preview_svg import tile_svg
    from fabtiles.geometry.interlace import tile_drawing

    tile = small_tile()
    assert tile_drawing(tile).area < tile.region().area
    assert 'stroke="#0b1a3a"' in tile_svg(tile)
    assert 'stroke="none"' in tile_svg(tile.replace(interlace=False))


def test_negative_gap_is_a_parameter_error():
    with pytest.raises(ParameterError, match=r"interlace_gap_mm must be a finite number >= 0, got -0.5"):
        small_tile(interlace_gap_mm=-0.5)


def test_gap_that_swallows_a_strand_is_a_parameter_error(tmp_path):
    tile = small_tile(interlace_gap_mm=40)
    with pytest.raises(ParameterError, match=r"interlace_gap_mm must be >= 0 and <= [0-9.]+ mm .*got 40"):
        tile.export(tmp_path / "t.stl")
    assert not (tmp_path / "t.stl").exists()


@pytest.mark.parametrize("value", ["yes", 1])
def test_interlace_flags_must_be_bools(value):
    with pytest.raises(ParameterError, match=r"interlace must be True or False"):
        small_tile(interlace=value)
    with pytest.raises(ParameterError, match=r"interlace_cut must be True or False"):
        small_tile(interlace_cut=value)


def test_cli_bad_gap_exits_2_and_writes_nothing(tmp_path):
    design = tmp_path / "woven.toml"
    design.write_text(
        '[motif]\npreset = "table3-1"\n[packing]\nradius = 12\n'
        '[tile]\noutline = "square"\nsize = 50\nframe = 2\ninterlace = true\n'
        'interlace_gap_mm = 40\n[output]\nformats = ["stl"]\n'
    )
    out = tmp_path / "out"
    run = subprocess.run(
        [sys.executable, "-m", "fabtiles", "build", str(design), "-o", str(out)], capture_output=True, text=True
    )
    assert run.returncode == 2, run.stderr
    assert "interlace_gap_mm" in run.stderr and "40" in run.stderr
    assert not list(out.glob("*.stl")) if out.exists() else True


def test_design_file_keys(tmp_path):
    from fabtiles.designs.design_file import design_from_text

    d = design_from_text(
        '[motif]\npreset = "table3-1"\n[tile]\nsize = 50\ninterlace = true\n'
        "interlace_gap_mm = 0.2\ninterlace_cut = true\n"
    )
    tile = d.build_tile()
    assert (tile.interlace, tile.interlace_gap_mm, tile.interlace_cut) == (True, 0.2, True)
    with pytest.raises(ft.DesignError, match=r"interlace must be true or false, got 'yes'"):
        design_from_text('[motif]\npreset = "table3-1"\n[tile]\nsize = 50\ninterlace = "yes"\n')
    with pytest.raises(ft.DesignError, match=r"interlace_gap_mm must be a finite number >= 0, got -1"):
        design_from_text('[motif]\npreset = "table3-1"\n[tile]\nsize = 50\ninterlace_gap_mm = -1\n')


def test_default_gap_is_a_third_of_the_stroke():
    assert math.isclose(small_tile(stroke=1.5).interlace_gap_mm, 0.5)


def test_3mf_pattern_part_dips_too(tmp_path):
    out = tmp_path / "woven.3mf"
    small_tile().export(out)
    from fabtiles.export.threemf import read_3mf

    parts = read_3mf(out)
    mesh = trimesh.Trimesh(parts["pattern"].vertices, parts["pattern"].faces, process=False)
    assert mesh.is_watertight
    up = mesh.face_normals[:, 2] > 0.999
    assert {round(float(z), 4) for z in mesh.triangles_center[up, 2]} == {round(BASE + RELIEF / 2, 4), BASE + RELIEF}


def test_step_relief_dips_with_the_mesh_volume(tmp_path):
    tile = ft.Tile("circle", 30, ft.Star.preset("table3-1"), frame=1.5, stroke=1.0, interlace=True)
    stl = tile.export(tmp_path / "t.stl")
    step = tile.export(tmp_path / "t.step")
    assert step.stats["volume_mm3"] == pytest.approx(stl.stats["volume_mm3"], rel=1e-3)
    assert step.stats["volume_mm3"] < tile.replace(interlace=False).export(tmp_path / "p.stl").stats["volume_mm3"]


@pytest.mark.parametrize("tiling", ["4.8.8", "3.12.12"])
def test_archimedean_tilings_weave(tmp_path, tiling):
    tile = ft.Tile("square", 50, ft.ArchimedeanPacking(tiling, 15), frame=2, stroke=1.0, interlace=True)
    w = tile.weave()
    assert len(w) > 0 and w.conflicts == 0
    _, tops = relief_tops(tile.export(tmp_path / "t.stl") and tmp_path / "t.stl")
    assert round(BASE + RELIEF / 2, 4) in tops
    woven = tile.export(tmp_path / "t.dxf", mode="score").stats["score_length_mm"]
    assert woven < tile.replace(interlace=False).export(tmp_path / "u.dxf", mode="score").stats["score_length_mm"]


def test_outline_circles_are_scored_whole_and_not_woven(tmp_path):
    pack = ft.HexPacking(radius=12, motif=ft.Star.preset("table3-1"), outline_circles=True)
    tile = ft.Tile("square", 50, pack, frame=2, stroke=1.0, interlace=True)
    assert len(tile.weave().strand) == len(tile.motif_segments()) < len(tile.segments())
    from fabtiles.geometry.interlace import tile_score_lines

    lines = tile_score_lines(tile)
    # every circle chord inside the outline is still there, whole
    circles = tile.segments()[len(tile.motif_segments()) :]
    mid = circles.mean(axis=1)
    inside = (mid > 0.5).all(axis=1) & (mid < 49.5).all(axis=1)
    lmid = lines.mean(axis=1)
    d = np.linalg.norm(mid[inside][:, None] - lmid[None], axis=2).min(axis=1)
    assert np.all(d < 1e-6)


SAMPLE_FILES = sorted((Path(__file__).resolve().parents[2] / "samples").rglob("*.toml"))


@pytest.mark.parametrize("path", SAMPLE_FILES, ids=[p.stem for p in SAMPLE_FILES])
def test_every_sample_weaves_without_conflicts(path):
    """docs/tile-operation.md says so: every sample alternates at every crossing, tiling samples too."""
    from fabtiles.designs.design_file import load_design

    tile = load_design(path).build_tile(tile_cls=ft.Tile).replace(interlace=True)
    w = tile.weave()
    assert len(w) > 0 and w.conflicts == 0
