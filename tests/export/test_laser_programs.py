"""The laser files in the programs laser users open them with (issue 21).

- MeerK40t (PyPI, in the "test" extra), a laser control program, run headless: it
  loads the file, classifies the elements into operations by colour, plans the job
  and writes GRBL G-code. Each run gets its own HOME: MeerK40t keeps the operations
  of earlier runs in its settings.
- Inkscape: ``--query-all`` measures the SVG; its DXF import is the Python extension
  ``dxf_input.py``, run with Debian's python3 as Inkscape runs it (Inkscape's own
  command line needs a display to import DXF).

What they do with each of our layers is tabled in ``docs/laser-programs.md``.
"""

from __future__ import annotations

import os
import re
import shutil
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from real_programs import INKSCAPE_EXTENSIONS, SYSTEM_PYTHON, program, require, run

from fabtiles import ArchimedeanPacking, HexPacking, Star, Tile
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")
SIZE = 60.0  # inside MeerK40t's default 235 mm bed, which it would otherwise scale the job to
GRBL_STEP = 0.0254  # MeerK40t works in 1/1000 inch


PATTERNS = {
    "hex": lambda: HexPacking(10, Star.preset("table3-3")),
    # issue 36: Hankin's polygons in contact go through the programs as the paper's motifs do
    "hankin": lambda: ArchimedeanPacking("4.8.8", 8, method="hankin", contact_angle=67.5),
}


@pytest.fixture(scope="module", params=sorted(PATTERNS))
def files(tmp_path_factory, request):
    out = tmp_path_factory.mktemp(f"laser-{request.param}")
    tile = Tile("square", SIZE, PATTERNS[request.param](), frame=3, stroke=1.0)
    paths = {}
    for mode in ("pierced", "score"):
        for fmt in ("dxf", "svg"):
            paths[mode, fmt] = out / f"{mode}.{fmt}"
            tile.export(paths[mode, fmt], mode=mode, fill_small_holes=True)
    return paths


def dxf_layers(path) -> dict:
    """Layer name -> [closed flag of each entity], from the file itself."""
    layers = {}
    for e in ezdxf.readfile(path).modelspace():
        layers.setdefault(e.dxf.layer, []).append(bool(e.closed))
    return layers


# --------------------------------------------------------------------------- MeerK40t


def meerk40t(path, tmp_path, listing: str = "tree list") -> dict:
    """Load ``path`` into MeerK40t (a GRBL diode laser), classify, plan, save the G-code.

    Returns the elements added, the operations of ``tree list`` with their references,
    what the ``listing`` command printed, and the G-code.
    """
    return meerk40t_jobs([path], tmp_path, listing)[0]


def meerk40t_jobs(paths, tmp_path, listing: str = "tree list") -> list[dict]:
    """:func:`meerk40t` of each of ``paths``, in one run of MeerK40t (its start is most of a run's time).

    Between two files the elements and the operations are deleted and the plan cleared, so each file
    is loaded, classified and planned as in a run of its own: its operations and G-code are those of
    a fresh start (a DXF's burns in another order at times, as from one fresh run to the next).
    """
    exe = shutil.which("meerk40t") or str(Path(sys.executable).with_name("meerk40t"))
    require(os.path.exists(exe) and exe, "meerk40t", 'pip install "meerk40t[dxf]" (in the "test" extra)')
    home = tmp_path / "meerk40t-home"
    home.mkdir(parents=True, exist_ok=True)
    gcodes = [tmp_path / f"{k}-{Path(path).stem}.gcode" for k, path in enumerate(paths)]
    env = {**os.environ, "HOME": str(home), "XDG_CONFIG_HOME": str(home / ".config")}
    extra = ["-e", listing] if listing != "tree list" else []
    commands = []
    for k, (path, gcode) in enumerate(zip(paths, gcodes, strict=True)):
        if k:
            commands += ["-e", "element* delete", "-e", "operation* delete", "-e", "plan clear"]
        commands += [
            "-e",
            f"load {path}",
            "-e",
            "tree list",
            *extra,
            "-e",
            "plan copy preprocess validate blob preopt optimize",
            "-e",
            f"plan save_job {gcode}",
        ]
    done = run([exe, "-Z", "-X", "-A", "-e", "device add grbl-diode", *commands, "-e", "quit"], env=env, timeout=180)
    out = re.sub(r"\x1b\[[0-9;]*m", "", done.stdout + done.stderr)
    # each file's part of the console: from the echo of its load command to the next file's
    starts, at = [], 0
    for path in paths:
        at = out.index(f"load {path}", at)
        starts.append(at)
        at += 1
    jobs = []
    for start, stop, gcode in zip(starts, [*starts[1:], len(out)], gcodes, strict=True):
        part = out[start:stop]
        added = int(re.search(r"Elements before: 0, after: \d+, added: (\d+)", part).group(1))
        ops = []  # (kind, references) of each operation, in the tree's order
        for line in part[part.index("Tree:") :].splitlines():
            m = re.search(r"\s(\d+)\.(\d+)(\.\d+)?\s+: (op (\w+)|reference)", line)
            if m and m.group(1) == "0":
                if m.group(5):
                    ops.append([m.group(5), 0])
                elif m.group(3):
                    ops[-1][1] += 1
        jobs.append(dict(added=added, ops=[tuple(op) for op in ops], listing=part, gcode=gcode.read_text()))
    return jobs


def burns(gcode: str) -> list[np.ndarray]:
    """The paths the laser burns: each G0 travel's end, then the G1 moves with power that follow."""
    paths, x, y, power, current = [], None, None, 0.0, None
    for line in gcode.splitlines():
        words = dict(re.findall(r"([GXYSF])(-?[0-9.]+)", line))
        if "S" in words:
            power = float(words["S"])
        start = (x, y)
        x, y = float(words.get("X", x or 0)), float(words.get("Y", y or 0))
        if words.get("G") == "0":
            current = None
        elif words.get("G") == "1" and power > 0:
            if current is None:
                current = [start]
                paths.append(current)
            current.append((x, y))
    return [np.array(p) for p in paths]


@pytest.fixture(scope="module")
def jobs(files, tmp_path_factory):
    """MeerK40t's jobs of the pattern's pierced DXF and SVG and its score DXF, in one run: (mode, format) -> job."""
    keys = [("pierced", "dxf"), ("pierced", "svg"), ("score", "dxf")]
    done = meerk40t_jobs([files[k] for k in keys], tmp_path_factory.mktemp("meerk40t"))
    return dict(zip(keys, done, strict=True))


@pytest.mark.parametrize("fmt", ["dxf", "svg"])
def test_meerk40t_cuts_every_contour_once_at_the_tile_size(files, jobs, fmt):
    job = jobs["pierced", fmt]
    layers = dxf_layers(files["pierced", "dxf"])
    contours = sum(len(v) for v in layers.values())
    assert all(all(closed) for closed in layers.values())
    assert job["added"] == contours
    # both cut layers (red) land in cut operations, each contour in exactly one: nothing engraved,
    # nothing cut twice (a layer named with "CUT" would be put in a second operation by its name)
    assert {kind for kind, _ in job["ops"]} == {"cut"}
    assert sum(refs for _, refs in job["ops"]) == contours
    paths = burns(job["gcode"])
    assert len(paths) == contours
    assert all(np.allclose(p[0], p[-1], atol=GRBL_STEP) for p in paths)  # every burn closes on itself
    allp = np.concatenate(paths)
    extent = allp.max(axis=0) - allp.min(axis=0)
    assert extent == pytest.approx([SIZE + PLY.kerf_mm] * 2, abs=0.05)
    # burnt where the file lies, the outline's kerf included. A DXF from (0, 0): one reaching below 0
    # (the kerf at -0.075 mm, before every file was moved into the positive quadrant) MeerK40t moved
    # to the centre of its bed, burnt from (87.427, 87.427). An SVG is placed by its page, the top-left
    # corner at the bed's (y down): x from 0 as the file's, y up to the 235 mm bed's top
    if fmt == "dxf":
        assert allp.min(axis=0) == pytest.approx([0, 0], abs=GRBL_STEP)
    else:
        assert allp.min(axis=0)[0] == pytest.approx(0, abs=GRBL_STEP)


def test_meerk40t_engraves_the_score_lines_and_cuts_the_outline(files, jobs):
    job = jobs["score", "dxf"]
    layers = dxf_layers(files["score", "dxf"])
    assert layers.keys() == {PLY.layers.score.name, PLY.layers.outer_cut.name}
    assert job["added"] == len(layers[PLY.layers.score.name]) + 1
    kinds = {}
    for kind, refs in job["ops"]:
        kinds[kind] = kinds.get(kind, 0) + refs
    assert kinds == {"engrave": len(layers[PLY.layers.score.name]), "cut": 1}


# --------------------------------------------------------------------------- Inkscape


def test_inkscape_measures_the_svg_in_true_millimetres(files):
    inkscape = program("inkscape", "apt-get install inkscape")
    svg = files["pierced", "svg"]
    rows = [line.split(",") for line in run([inkscape, "--query-all", svg]).stdout.splitlines()]
    boxes = {r[0]: np.array([float(v) for v in r[1:]]) * 25.4 / 96 for r in rows}  # px at 96 per inch -> mm
    root = ET.parse(svg).getroot()
    stroke = float(root.find("{http://www.w3.org/2000/svg}g").get("stroke-width"))
    # the visual box: the kerf-compensated outline plus half the hairline stroke on each side
    (_, _, w, h) = boxes[rows[0][0]]
    assert (w, h) == pytest.approx((SIZE + PLY.kerf_mm + stroke,) * 2, abs=0.005)
    assert {PLY.layers.inner_cut.name, PLY.layers.outer_cut.name} <= boxes.keys()


@pytest.mark.parametrize("mode", ["pierced", "score"])
def test_inkscape_imports_the_dxf_with_every_layer_and_contour(files, tmp_path, mode):
    python = require(os.path.exists(SYSTEM_PYTHON) and SYSTEM_PYTHON, SYSTEM_PYTHON, "apt-get install python3")
    extension = require(
        (INKSCAPE_EXTENSIONS / "dxf_input.py").exists() and INKSCAPE_EXTENSIONS / "dxf_input.py",
        "Inkscape's dxf_input.py",
        "apt-get install inkscape",
    )
    dxf = files[mode, "dxf"]
    svg = run([python, extension, dxf], cwd=INKSCAPE_EXTENSIONS).stdout
    root = ET.fromstring(svg)
    ns = {"s": "http://www.w3.org/2000/svg", "i": "http://www.inkscape.org/namespaces/inkscape"}
    label = "{{{}}}label".format(ns["i"])
    imported = {
        g.get(label): g.findall("s:path", ns)
        for g in root.iter("{{{}}}g".format(ns["s"]))
        if g.get("{{{}}}groupmode".format(ns["i"])) == "layer" and g.findall("s:path", ns)
    }
    layers = dxf_layers(dxf)
    assert {k: len(v) for k, v in imported.items()} == {k: len(v) for k, v in layers.items()}
    colours = {
        PLY.layers.inner_cut.name: "#FF0000",
        PLY.layers.outer_cut.name: "#FF0000",
        PLY.layers.score.name: "#0000FF",
    }
    for name, paths in imported.items():
        for p, closed in zip(paths, layers[name], strict=True):
            assert p.get("d").strip().lower().endswith("z") == closed
            assert f"stroke:{colours[name]}" in p.get("style")
    # millimetres: Inkscape's default import scale reads one DXF unit as 1 mm (96 px per inch)
    xs = np.array(
        [float(v) for p in imported[PLY.layers.outer_cut.name] for v in re.findall(r"-?\d+\.?\d*", p.get("d"))[0::2]]
    )
    assert (xs.max() - xs.min()) * 25.4 / 96 == pytest.approx(SIZE + PLY.kerf_mm, abs=0.002)


# --------------------------------------------------------------------------- arcs (issue 35)

CIRCLES = (
    '[packing]\nkind = "archimedean"\ntiling = "3.3.3.4.4"\noutline_circles = true\n'
    '[tile]\noutline = "circle"\nsize = 60\njoin = "round"\n'
)


@pytest.fixture(scope="module")
def arc_files(tmp_path_factory):
    """The 60 mm circle tile with round joins and outline circles: its DXF and SVG, curves as arcs."""
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making import build_design

    out = tmp_path_factory.mktemp("arcs")
    design = design_from_text(CIRCLES + '[output]\nformats = ["dxf", "svg"]\n', name="circles")
    build_design(design, out)
    return {fmt: next(out.glob(f"*.{fmt}")) for fmt in ("dxf", "svg")}


def _curve_points(dxf) -> np.ndarray:
    from dxf_helpers import vertices

    return np.vstack([vertices(e) for e in ezdxf.readfile(dxf).modelspace()])


@pytest.fixture(scope="module")
def arc_jobs(arc_files, tmp_path_factory):
    """MeerK40t's jobs of the circle tile's DXF and SVG, in one run: format -> job."""
    done = meerk40t_jobs([arc_files["dxf"], arc_files["svg"]], tmp_path_factory.mktemp("meerk40t-arcs"))
    return dict(zip(("dxf", "svg"), done, strict=True))


@pytest.mark.parametrize("fmt", ["dxf", "svg"])
def test_meerk40t_cuts_the_arcs_as_arcs(arc_files, arc_jobs, fmt):
    from scipy.spatial import cKDTree
    from test_dxf_librecad import _arc_middles, _densify

    dxf = arc_files["dxf"]
    job = arc_jobs[fmt]
    paths = burns(job["gcode"])
    layers = dxf_layers(dxf)
    assert len(paths) == sum(len(v) for v in layers.values())
    burnt = np.concatenate(paths)
    curves = _curve_points(dxf)
    # the extents of what it burns are the file's, arcs as arcs (the tile's circle is two half-turn
    # arcs: read as chords, it would burn a line), within 0.05 mm
    assert burnt.max(axis=0) - burnt.min(axis=0) == pytest.approx(curves.max(axis=0) - curves.min(axis=0), abs=0.05)
    if fmt == "svg":
        # MeerK40t 0.9 burns a few of the SVG's paths off the file (the outline's circle up to 1.6 mm,
        # thin slivers between the outline and the pattern's circles up to 0.85 mm), the same whether
        # the SVG's curves are arcs or the flattened polylines it had before: its SVG import's, not ours
        return
    # every burnt point on the file's curves, every arc's middle burnt (a chord would miss it)
    moved = burnt - burnt.min(axis=0) + curves.min(axis=0)
    assert cKDTree(_densify(curves)).query(moved)[0].max() <= 0.05
    mids = _arc_middles(dxf, set(layers))
    assert len(mids) > 100
    assert cKDTree(_densify(moved, step=0.005)).query(mids)[0].max() <= 0.05


def test_inkscape_imports_the_dxf_arcs(arc_files):
    python = require(os.path.exists(SYSTEM_PYTHON) and SYSTEM_PYTHON, SYSTEM_PYTHON, "apt-get install python3")
    extension = require(
        (INKSCAPE_EXTENSIONS / "dxf_input.py").exists() and INKSCAPE_EXTENSIONS / "dxf_input.py",
        "Inkscape's dxf_input.py",
        "apt-get install inkscape",
    )
    dxf = arc_files["dxf"]
    svg = run([python, extension, dxf], cwd=INKSCAPE_EXTENSIONS).stdout
    root = ET.fromstring(svg)
    ns = {"s": "http://www.w3.org/2000/svg", "i": "http://www.inkscape.org/namespaces/inkscape"}
    paths = [
        p.get("d")
        for g in root.iter("{{{}}}g".format(ns["s"]))
        if g.get("{{{}}}groupmode".format(ns["i"])) == "layer"
        for p in g.findall("s:path", ns)
    ]
    assert len(paths) == sum(len(v) for v in dxf_layers(dxf).values())
    bulged = sum(
        int((np.array([p[2] for p in e.get_points("xyb")]) != 0).sum()) for e in ezdxf.readfile(dxf).modelspace()
    )
    # Inkscape draws each bulge as an SVG arc ("A")
    assert sum(d.count("A") for d in paths) == bulged


def test_inkscape_measures_the_svg_arcs(arc_files):
    # the circle tile's outline is two SVG arcs: Inkscape's box of the file is the circle's, kerf and
    # hairline included (as chords, the two arcs would measure a line)
    inkscape = program("inkscape", "apt-get install inkscape")
    svg = arc_files["svg"]
    assert "A" in svg.read_text()
    rows = [line.split(",") for line in run([inkscape, "--query-all", svg]).stdout.splitlines()]
    (_, _, w, h) = np.array([float(v) for v in rows[0][1:]]) * 25.4 / 96
    curves = _curve_points(arc_files["dxf"])
    size = curves.max(axis=0) - curves.min(axis=0)
    stroke = float(ET.parse(svg).getroot().find("{http://www.w3.org/2000/svg}g").get("stroke-width"))
    assert (w, h) == pytest.approx(tuple(size + stroke), abs=0.005)
