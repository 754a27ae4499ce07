"""The vpype plugin (issue 37): ``vpype fabtiles ...`` found through the entry point, in real vpype.

vpype finds plugins in the ``vpype.plugins`` entry-point group of the installed
distributions. The tests give it one as an installed fabtiles does (a dist-info with
the entry point that pyproject.toml declares) and run the ``vpype`` program itself.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import tomllib
from lxml import etree

from fabtiles.designs.design_file import load_design
from fabtiles.export.plot_svg import PX_PER_MM
from fabtiles.making.plot import plot_drawing

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "table3-3.toml"
VPYPE = Path(sys.executable).with_name("vpype")


@pytest.fixture(scope="module")
def vpype(tmp_path_factory):
    """Run ``vpype ARGS`` with the plugin registered as pyproject.toml registers it: (exit code, stdout, stderr)."""
    entry = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["entry-points"]["vpype.plugins"]
    site = tmp_path_factory.mktemp("site")
    info = site / "fabtiles_plugin_probe-0.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: fabtiles-plugin-probe\nVersion: 0.0\n")
    (info / "entry_points.txt").write_text("[vpype.plugins]\n" + "".join(f"{k} = {v}\n" for k, v in entry.items()))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(site)]))

    def run(*args):
        res = subprocess.run([str(VPYPE), *map(str, args)], capture_output=True, text=True, env=env, cwd=site)
        return res.returncode, res.stdout, res.stderr

    return run


def stat_layers(text: str) -> dict:
    """``vpype stat``'s layers: id -> (length, pen-up length, properties text)."""
    out = {}
    for block in re.split(r"\nLayer ", text)[1:]:
        lid = int(block.split()[0])
        length = float(re.search(r"^\s+Length: ([\d.e+]+)", block, re.M)[1])
        up = float(re.search(r"Pen-up length: ([\d.e+]+)", block)[1])
        out[lid] = (length, up, block)
    return out


@pytest.fixture(scope="module")
def sample_run(vpype, tmp_path_factory):
    """One vpype run of the sample for the stat and the pipeline tests: stat, then sort and write:
    (exit code, stdout, stderr, the SVG written)."""
    svg = tmp_path_factory.mktemp("pipeline") / "out.svg"
    return (*vpype("fabtiles", SAMPLE, "stat", "linesort", "write", svg), svg)


def test_stat_reports_the_layers_and_the_centrelines_length(sample_run):
    code, out, err, _ = sample_run
    assert code == 0, err
    layers = stat_layers(out)
    drawing = plot_drawing(load_design(SAMPLE))
    assert len(layers) == len(drawing.layers)
    for (length, _up, block), layer in zip(layers.values(), drawing.layers, strict=True):
        assert f"vp_name: '{layer.name}'" in block
        assert length / PX_PER_MM == pytest.approx(layer.length_mm, rel=1e-3)
    # the pen-down length is the centre-lines' total (the strands layer), within 0.1 %
    assert layers[1][0] / PX_PER_MM == pytest.approx(drawing.layers[0].length_mm, rel=1e-3)


def test_pipeline_writes_true_size(sample_run):
    # (the --pen option is read in test_fill_gives_the_layers_of_fabtiles_plot_fill and refused in
    # test_errors_are_one_line)
    code, _, err, out = sample_run
    assert code == 0, err
    root = etree.parse(str(out)).getroot()
    assert root.get("width") == "15.0cm" and root.get("height") == "15.0cm"  # the 150 mm tile


def test_options_set_and_cut(vpype):
    code, out, err = vpype("fabtiles", "--what", "cut", "--set", "tile.size=100", SAMPLE, "stat")
    assert code == 0, err
    assert "vp_name: 'INNER'" in out and "vp_name: 'OUTER'" in out


def test_fill_gives_the_layers_of_fabtiles_plot_fill(vpype):
    """``vpype fabtiles --fill ...`` adds the layers ``fabtiles plot --fill`` draws: one per pen, with
    its name, colour, pen-down length and pen-up travel (the same strokes in the same order)."""
    mosaic = ROOT / "samples" / "mosaic-iznik.toml"
    args = ("--fill", "--cross", "--pen", "0.5", "--angle", "B=10", "--set", "tile.size=40")
    code, out, err = vpype("fabtiles", *args, mosaic, "stat")
    assert code == 0, err
    layers = stat_layers(out)
    design = load_design(mosaic, overrides=["tile.size=40"])
    drawing = plot_drawing(design, fill=True, cross=True, pen_mm=0.5, angles_deg={"B": 10.0})
    assert len(layers) == len(drawing.layers) > 2
    from fabtiles.geometry.cut_order import travel

    for (length, up, block), layer in zip(layers.values(), drawing.layers, strict=True):
        assert f"vp_name: '{layer.name}'" in block
        r, g, b = (int(layer.colour[i : i + 2], 16) for i in (1, 3, 5))
        assert f"vp_color: Color(red={r}, green={g}, blue={b}" in block
        assert length / PX_PER_MM == pytest.approx(layer.length_mm, rel=1e-6)
        # vpype's pen-up length leaves out the way to the first stroke
        assert up / PX_PER_MM == pytest.approx(
            travel(layer.paths, closed=False) - float(np.hypot(*layer.paths[0][0])), rel=1e-6
        )


@pytest.mark.parametrize(
    "args, message",
    [
        (["nothere.toml"], "fabtiles: cannot read design file 'nothere.toml'"),
        (["--fill", SAMPLE], "fill needs the design's colours"),
        (["--fill", "--angle", "x", ROOT / "samples" / "mosaic-iznik.toml"], "angle must be degrees"),
        (["--set", "tile.size=-3", SAMPLE], "[tile] size must be"),
        (["--pen", "0", SAMPLE], "--pen must be a finite number > 0"),
    ],
)
def test_errors_are_one_line(vpype, args, message):
    code, _out, err = vpype("fabtiles", *args, "stat")
    assert code != 0
    assert "Traceback" not in err
    lines = [x for x in err.splitlines() if x.strip()]
    assert len(lines) == 1 and lines[0].startswith("Error: fabtiles: ") and message in lines[0], err
