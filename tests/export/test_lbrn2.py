"""LightBurn projects (issue 23): the DXF's contours with the profile's settings on every layer.

No LightBurn runs here. The ``.lbrn2`` is read by two independent readers: MeerK40t
(its LightBurn loader, headless) and lbrnts (npm, run by Node), and by our own
reader below, contour for contour against the DXF. What only LightBurn could show
(its own layer list, its preview) is said in ``docs/laser-programs.md``.
"""

from __future__ import annotations

import json
import os
import re
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from model_files import write_cut
from real_programs import program, require, run
from shapely.geometry import box
from test_laser_programs import burns, meerk40t, meerk40t_jobs

from fabtiles import ArchimedeanPacking, HexPacking, ProfileError, Star, Tile
from fabtiles.export import lbrn2
from fabtiles.geometry.job_time import path_lengths
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")
HERE = Path(__file__).parent


def tile(size=60):
    return Tile("square", size, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0)


def hankin_tile(size=60):
    """Issue 36: Hankin's polygons in contact, through LightBurn's project as the paper's motifs."""
    return Tile(
        "square", size, ArchimedeanPacking("4.8.8", 8, method="hankin", contact_angle=67.5), frame=3, stroke=1.0
    )


@pytest.fixture(scope="module", params=["hex", "hankin"])
def files(tmp_path_factory, request):
    out = tmp_path_factory.mktemp(f"lbrn2-{request.param}")
    t, paths, reports = (tile() if request.param == "hex" else hankin_tile()), {}, {}
    for mode in ("pierced", "score"):
        for fmt in ("dxf", "lbrn2"):
            paths[mode, fmt] = out / f"{mode}.{fmt}"
            reports[mode, fmt] = t.export(paths[mode, fmt], mode=mode, fill_small_holes=True)
    return paths, reports


def read_lbrn2(path) -> dict:
    """Our own reader: the CutSettings by index, and each Path's layer, vertices and closure."""
    root = ET.parse(path).getroot()
    assert root.tag == "LightBurnProject" and root.get("FormatVersion") == "1"
    cuts = {}
    for c in root.findall("CutSetting"):
        values = {child.tag: child.get("Value") for child in c}
        cuts[int(values["index"])] = dict(type=c.get("type"), **values)
    shapes = []
    for s in root.findall("Shape"):
        assert s.get("Type") == "Path" and s.find("XForm").text == "1 0 0 1 0 0"
        verts = np.array(
            [[float(x), float(y)] for x, y in re.findall(r"V(-?[0-9.]+) (-?[0-9.]+)c0x1c1x1", s.find("VertList").text)]
        )
        prims = [tuple(map(int, p)) for p in re.findall(r"L(\d+) (\d+)", s.find("PrimList").text)]
        n = len(verts)
        closed = prims == [(i, (i + 1) % n) for i in range(n)]
        assert closed or prims == [(i, i + 1) for i in range(n - 1)], "straight lines, each vertex once, in order"
        shapes.append(dict(index=int(s.get("CutIndex")), vertices=verts, closed=closed))
    return dict(cuts=cuts, shapes=shapes)


def dxf_paths(path) -> list:
    """``(layer, closed, vertices)`` of every DXF polyline, in file order."""
    return [
        (e.dxf.layer, bool(e.closed), np.array([p[:2] for p in e.get_points("xy")]))
        for e in ezdxf.readfile(path).modelspace()
    ]


# --------------------------------------------------------------------------- our own reader


@pytest.mark.parametrize("mode", ["pierced", "score"])
def test_the_project_is_the_dxf_contour_for_contour(files, mode):
    paths, _ = files
    got, want = read_lbrn2(paths[mode, "lbrn2"]), dxf_paths(paths[mode, "dxf"])
    names = {int(i): c["name"] for i, c in got["cuts"].items()}
    assert len(got["shapes"]) == len(want)
    for shape, (layer, closed, verts) in zip(got["shapes"], want, strict=True):
        assert names[shape["index"]] == layer and shape["closed"] == closed
        assert shape["vertices"] == pytest.approx(verts, abs=1e-4)  # 4 decimals
        if closed:  # the first vertex not doubled (a score path may run round a loop back to its start)
            assert not np.allclose(shape["vertices"][0], shape["vertices"][-1])


def test_every_layer_carries_the_profiles_settings_and_runs_inner_before_outer(files):
    paths, _ = files
    for mode, keys in (("pierced", ["inner_cut", "outer_cut"]), ("score", ["score", "outer_cut"])):
        cuts = read_lbrn2(paths[mode, "lbrn2"])["cuts"]
        by_priority = sorted(cuts.values(), key=lambda c: int(c["priority"]))
        for c, key in zip(by_priority, keys, strict=True):
            layer = getattr(PLY.layers, key)
            assert (c["type"], c["name"], float(c["speed"]), float(c["maxPower"]), int(c["numPasses"])) == (
                "Cut",
                layer.name,
                layer.speed_mm_s,
                layer.power_pct,
                layer.passes,
            )
        assert [c["name"] for c in by_priority] == [getattr(PLY.layers, k).name for k in keys]
        assert len({int(i) for i in cuts}) == len(cuts)  # one LightBurn layer each


def test_the_same_bytes_every_run(tmp_path):
    for name in ("a", "b"):
        tile().export(tmp_path / f"{name}.lbrn2")
    assert (tmp_path / "a.lbrn2").read_bytes() == (tmp_path / "b.lbrn2").read_bytes()


def test_cut_length_is_the_dxf_paths_read_back(files):
    paths, reports = files
    for mode in ("pierced", "score"):
        want = sum(float(path_lengths([v], closed).sum()) for _, closed, v in dxf_paths(paths[mode, "dxf"]))
        for fmt in ("dxf", "lbrn2"):
            assert reports[mode, fmt].stats["job"]["cut_total_mm"] == pytest.approx(want, rel=1e-3)


# --------------------------------------------------------------------------- MeerK40t


@pytest.fixture(scope="module")
def jobs(files, tmp_path_factory):
    """MeerK40t's jobs of the pattern's projects and DXFs, in one run, its operations listed: (mode, format) -> job."""
    paths, _ = files
    keys = [(mode, fmt) for mode in ("pierced", "score") for fmt in ("lbrn2", "dxf")]
    done = meerk40t_jobs([paths[k] for k in keys], tmp_path_factory.mktemp("meerk40t"), listing="operations")
    return dict(zip(keys, done, strict=True))


@pytest.mark.parametrize("mode", ["pierced", "score"])
def test_meerk40t_loads_the_project_with_its_speeds_and_powers(files, jobs, mode):
    paths, _ = files
    project = jobs[mode, "lbrn2"]
    want = dxf_paths(paths[mode, "dxf"])
    assert project["added"] == len(want)  # one element per contour and score path
    keys = ["inner_cut", "outer_cut"] if mode == "pierced" else ["score", "outer_cut"]
    ops = re.findall(r"\d+: Cut ([0-9.]+)mm/s @([0-9.]+)", project["listing"])
    assert [(float(s), float(p)) for s, p in ops] == [
        (getattr(PLY.layers, k).speed_mm_s, getattr(PLY.layers, k).power_pct * 10) for k in keys
    ]
    # the G-code burns what the DXF's G-code burns, to the same extent
    dxf_job = jobs[mode, "dxf"]

    def extent(gcode):
        pts = np.concatenate(burns(gcode))
        return pts.max(axis=0) - pts.min(axis=0)

    assert extent(project["gcode"]) == pytest.approx(extent(dxf_job["gcode"]), abs=0.03)


def test_the_time_estimate_against_a_simulation_of_the_same_job(tmp_path):
    """Our estimate against gcode-simulator (GRBL's planner, acceleration included) on MeerK40t's G-code.

    MeerK40t's G-code has no pierce dwell and moves between paths at its own rate, so
    the comparison uses a profile without pierce time and the simulator's rapid rate.
    """
    import importlib.util

    require(
        importlib.util.find_spec("gcode_simulator"), "gcode-simulator", 'pip install gcode-simulator (the "test" extra)'
    )
    import gcode_simulator as sim

    rapid = 200.0
    profile = replace(PLY, pierce_s=0.0, travel_mm_s=rapid)
    path = tmp_path / "t.lbrn2"
    report = tile().export(path, profile=profile, fill_small_holes=True)
    gcode = meerk40t(path, tmp_path)["gcode"].replace("\r", "\n")
    settings = sim.GrblSettings(max_rate_x=rapid * 60, max_rate_y=rapid * 60, max_accel_x=1500, max_accel_y=1500)
    seconds, _ = sim.GCodeSimulator(settings).estimate_time(gcode)
    print(f"estimate {report.stats['job']['seconds']} s, simulated {seconds:.1f} s")
    # Measured: estimate 114.4 s, simulated 124.3 s (0.92). The estimate leaves out acceleration and
    # corner slow-downs, so it is never above the simulation; it stays within 10 % of it (2 points
    # of margin over what is measured).
    assert 0.90 * seconds <= report.stats["job"]["seconds"] <= seconds


# --------------------------------------------------------------------------- lbrnts


def lbrnts(*paths) -> list[dict]:
    """What lbrnts reads in each project, all in one run of Node."""
    folder = os.environ.get("FABTILES_LBRNTS_DIR", "")
    node = program("node", "apt-get install nodejs")
    found = folder and (Path(folder) / "node_modules" / "lbrnts").exists()
    require(
        found,
        "lbrnts",
        "npm install lbrnts svgson transformation-matrix in a folder, then FABTILES_LBRNTS_DIR=that folder",
    )
    out = run([node, HERE / "lbrnts_read.mjs", *paths], cwd=folder).stdout
    return [json.loads(line) for line in out.splitlines()]


def test_lbrnts_reads_every_cut_setting_and_shape(files):
    paths, _ = files
    modes = ("pierced", "score")
    for mode, got in zip(modes, lbrnts(*[paths[m, "lbrn2"] for m in modes]), strict=True):
        ours = read_lbrn2(paths[mode, "lbrn2"])
        assert got["formatVersion"] == "1"
        assert [(c["index"], c["name"], c["type"], c["speed"], c["maxPower"], c["numPasses"]) for c in got["cuts"]] == [
            (i, c["name"], c["type"], float(c["speed"]), float(c["maxPower"]), int(c["numPasses"]))
            for i, c in ours["cuts"].items()
        ]
        assert [(s["cutIndex"], s["vertices"]) for s in got["shapes"]] == [
            (s["index"], len(s["vertices"])) for s in ours["shapes"]
        ]
        # lbrnts 0.0.17 calls a path open only when its primitives are LightBurn's shorthand
        # "LineOpen" (MeerK40t then burns nothing of it): the closed contours it reads right
        assert all(s["closed"] for s, o in zip(got["shapes"], ours["shapes"], strict=True) if o["closed"])


# --------------------------------------------------------------------------- settings


@pytest.mark.parametrize(
    "entry,msg",
    [
        ("speed_mm_s = 0", r"layers.inner_cut.speed_mm_s must be > 0, got 0"),
        ("power_pct = 0", r"layers.inner_cut.power_pct must be a percentage > 0 and <= 100, got 0"),
        ("power_pct = 120", r"layers.inner_cut.power_pct must be a percentage > 0 and <= 100, got 120"),
        ("passes = 0", r"layers.inner_cut.passes must be a whole number >= 1, got 0"),
        ("passes = 1.5", r"layers.inner_cut.passes must be a whole number >= 1, got 1.5"),
    ],
)
def test_bad_layer_settings_name_the_profile_key_and_value(tmp_path, entry, msg):
    p = tmp_path / "bad.toml"
    p.write_text(f'kind = "laser"\n[layers]\ninner_cut = {{ name = "IN", color = 1, {entry} }}\n')
    with pytest.raises(ProfileError, match=rf"{re.escape(str(p))}: {msg}"):
        load_profile(p)


@pytest.mark.parametrize(
    "text,msg",
    [
        (
            '[layers]\nengrave = { name = "F", color = 6, line_interval_mm = 0 }',
            r"layers.engrave.line_interval_mm must be > 0",
        ),
        ("[laser]\nkerf_x_mm = -0.1", r"laser.kerf_x_mm must be >= 0, got -0.1"),
        ("[laser]\npierce_s = -1", r"laser.pierce_s must be >= 0, got -1"),
        ("[laser]\ntravel_mm_s = 0", r"laser.travel_mm_s must be > 0, got 0"),
    ],
)
def test_bad_machine_settings(tmp_path, text, msg):
    p = tmp_path / "bad.toml"
    p.write_text(f'kind = "laser"\n{text}\n')
    with pytest.raises(ProfileError, match=msg):
        load_profile(p)


def test_the_palette_index_of_each_layer():
    assert lbrn2.palette_index("FF0000", set()) == 2 and lbrn2.palette_index("0000FF", set()) == 1
    assert lbrn2.palette_index("FF00FF", set()) == 7
    assert lbrn2.palette_index("FF0000", {2}) != 2


# --------------------------------------------------------------------------- arcs (issue 35)


@pytest.fixture(scope="module")
def arc_files(tmp_path_factory):
    from test_laser_programs import CIRCLES

    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making import build_design

    out = tmp_path_factory.mktemp("lbrn2-arcs")
    build_design(design_from_text(CIRCLES + '[output]\nformats = ["dxf", "lbrn2"]\n', name="circles"), out)
    return {fmt: next(out.glob(f"*.{fmt}")) for fmt in ("dxf", "lbrn2")}


def _drawn(verts, prims, closed) -> np.ndarray:
    """Points along a LightBurn path as a reader draws it: lines, and Beziers from vertex i's c0 to j's c1."""
    t = np.linspace(0, 1, 33)[1:, None]
    out = [np.array(verts[0][:2])[None]]
    n = len(verts)
    for i, kind in enumerate(prims):
        a, z = verts[i], verts[(i + 1) % n]
        p0, p3 = np.array(a[:2]), np.array(z[:2])
        if kind == 1:
            p1, p2 = np.array(a[2:4]), np.array(z[4:6])
            out.append((1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t**2 * p2 + t**3 * p3)
        else:
            out.append(p0 + (p3 - p0) * t)
    return np.vstack(out)


def test_lbrnts_reads_the_arcs_as_beziers_on_the_dxfs_curves(arc_files):
    import shapely
    from dxf_helpers import hausdorff_distance, vertices

    (got,) = lbrnts(arc_files["lbrn2"])
    doc = ezdxf.readfile(arc_files["dxf"])
    want = [vertices(e) for e in doc.modelspace()]
    assert len(got["shapes"]) == len(want)
    beziers = sum(sum(s["prims"]) for s in got["shapes"])
    assert beziers >= sum(int((np.array([p[2] for p in e.get_points("xyb")]) != 0).sum()) for e in doc.modelspace())
    tol = PLY.tolerance_mm
    for shape, ring in zip(got["shapes"], want, strict=True):
        assert shape["closed"]
        drawn = _drawn(shape["verts"], shape["prims"], True)
        # the Beziers as lbrnts reads them lie on the DXF's arcs (ezdxf's drawing of its bulges)
        # within a tenth of the tolerance and the 4 decimals
        d = hausdorff_distance(shapely.LinearRing(drawn), shapely.LinearRing(ring), densify=0.05)
        assert d <= 0.1 * tol + 2e-4


def test_meerk40t_burns_the_projects_beziers_as_the_dxfs_arcs(arc_files, tmp_path):
    lb, dx = (burns(job["gcode"]) for job in meerk40t_jobs([arc_files["lbrn2"], arc_files["dxf"]], tmp_path))
    a, b = np.concatenate(lb), np.concatenate(dx)
    assert len(lb) == len(dx)
    assert a.max(axis=0) - a.min(axis=0) == pytest.approx(b.max(axis=0) - b.min(axis=0), abs=0.05)


def read_beziers(path) -> list:
    """Every Path of a project as points along it: each straight line's end, and each Bezier (``B i j``:
    vertex i's ``c0`` handle, vertex j's ``c1``) at 256 points, as a reader of the format draws it."""
    number = r"(-?[0-9.]+)"
    vertex = re.compile(rf"V{number} {number}(?:c0x{number}c0y{number}|c0x1)(?:c1x{number}c1y{number}|c1x1)")
    t = np.linspace(0, 1, 257)[1:, None]
    out = []
    for s in ET.parse(path).getroot().findall("Shape"):
        v = np.array(
            [[np.nan if x is None else float(x) for x in m.groups()] for m in vertex.finditer(s.find("VertList").text)]
        )
        pts = [v[:1, :2]]
        for kind, i, j in re.findall(r"([LB])(\d+) (\d+)", s.find("PrimList").text):
            a, z = v[int(i)], v[int(j)]
            if kind == "B":
                assert not np.isnan(a[2:4]).any() and not np.isnan(z[4:6]).any()
                pts.append(
                    (1 - t) ** 3 * a[:2] + 3 * (1 - t) ** 2 * t * a[2:4] + 3 * (1 - t) * t**2 * z[4:6] + t**3 * z[:2]
                )
            else:
                pts.append(z[None, :2])
        out.append(np.vstack(pts))
    return out


def dxf_exact_paths(path, sagitta_mm: float = 1e-5) -> list:
    """Every DXF polyline's points, its arcs (bulges) at points on their circles close enough that the
    chords between stand within ``sagitta_mm`` of them."""
    from ezdxf.math import bulge_to_arc

    out = []
    for e in ezdxf.readfile(path).modelspace():
        pts = list(e.get_points("xyb"))
        ring = []
        for i, (x, y, b) in enumerate(pts):
            ring.append((x, y))
            if b == 0 or (i == len(pts) - 1 and not e.closed):
                continue
            x2, y2, _ = pts[(i + 1) % len(pts)]
            c, _, _, r = bulge_to_arc((x, y), (x2, y2), b)
            sweep, start = 4 * np.arctan(b), np.arctan2(y - c[1], x - c[0])
            k = max(8, int(np.ceil(abs(sweep) * r / np.sqrt(8 * sagitta_mm * r))))
            a = start + sweep * np.arange(1, k) / k
            ring += list(zip(c[0] + r * np.cos(a), c[1] + r * np.sin(a), strict=True))
        if e.closed:
            ring.append(ring[0])
        out.append(np.array(ring))
    return out


def _farthest(points, path) -> float:
    """The largest distance from any of ``points`` to the polyline ``path`` (a tree of its segments)."""
    import shapely

    segments = shapely.linestrings(np.stack([path[:-1], path[1:]], axis=1))
    _, d = shapely.STRtree(segments).query_nearest(shapely.points(points), return_distance=True, all_matches=False)
    return float(d.max())


def test_a_large_circles_beziers_lie_on_the_dxfs_arcs_within_the_tolerance(tmp_path):
    """A 140 mm circle tile: every Bezier, drawn, stands within a tenth of the profile's tolerance of the
    DXF's exact arcs (a quarter turn as one cubic would stand 0.019 mm off on this radius), and every
    point of the DXF's arcs within as much of the project's curves."""
    from fabtiles.designs.design_file import load_design
    from fabtiles.making import build_design

    sample = HERE.parents[1] / "samples" / "table3-3.toml"
    design = load_design(
        sample, overrides=('tile.outline="circle"', "tile.size=140", 'output.formats=["dxf", "lbrn2"]')
    )
    build_design(design, tmp_path)
    drawn = read_beziers(tmp_path / "table3-3.lbrn2")
    exact = dxf_exact_paths(tmp_path / "table3-3.dxf")
    assert len(drawn) == len(exact)
    assert max(np.ptp(p[:, 0]) for p in exact) == pytest.approx(140.15, abs=1e-3)  # the outline, kerf outside
    worst = max(
        max(_farthest(ours, theirs), _farthest(theirs, ours)) for ours, theirs in zip(drawn, exact, strict=True)
    )
    assert worst <= 0.1 * PLY.tolerance_mm + 2e-4  # a tenth of the tolerance, and the file's 4 decimals


def test_a_plate_with_one_hole_is_two_path_shapes(tmp_path):
    plate = box(0, 0, 40, 40).difference(box(10, 10, 30, 30))
    out = tmp_path / "plate.lbrn2"
    r = write_cut(out, region=plate, outline=box(0, 0, 40, 40), profile="laser-3mm-plywood")
    shapes = out.read_text().count('<Shape Type="Path"')
    assert (shapes, r.stats["inner_contours"], r.stats["outer_contours"]) == (2, 1, 1)
