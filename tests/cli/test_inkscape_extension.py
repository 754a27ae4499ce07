"""The Inkscape extension (issue 37): installed, run as Inkscape runs it, measured by Inkscape."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from lxml import etree
from real_programs import INKSCAPE_EXTENSIONS, SYSTEM_PYTHON, program, require, run

from fabtiles.cli.inkscape import FILES, default_dest
from fabtiles.cli.main import cli

ROOT = Path(__file__).resolve().parents[2]
INK = "{http://www.inkscape.org/namespaces/inkscape}"
PX_PER_MM = 96 / 25.4
BLANK = '<svg xmlns="http://www.w3.org/2000/svg" width="210mm" height="297mm" viewBox="0 0 210 297"></svg>\n'


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    dest = tmp_path_factory.mktemp("extensions")
    res = CliRunner().invoke(cli, ["install-inkscape-extension", "--dest", str(dest)], catch_exceptions=False)
    assert res.exit_code == 0, res.output
    return dest


def inkscape_python() -> str:
    """Debian's python3, with Inkscape's inkex beside it (/usr/share/inkscape/extensions)."""
    found = os.path.exists(SYSTEM_PYTHON) and (INKSCAPE_EXTENSIONS / "inkex").is_dir()
    return require(SYSTEM_PYTHON if found else None, "Inkscape's inkex", "apt-get install inkscape")


def as_inkscape_runs_it(installed, tmp_path, *args):
    """Inkscape's way: its python3, its inkex, the script beside the .inx, the document's path last."""
    python = inkscape_python()
    blank = tmp_path / "blank.svg"
    blank.write_text(BLANK)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(INKSCAPE_EXTENSIONS), str(ROOT)]))
    return subprocess.run(
        [python, str(installed / "fabtiles_render.py"), *args, str(blank)],
        capture_output=True,
        text=True,
        env=env,
        cwd=installed,
        timeout=300,
    )


def test_install_copies_the_pair_and_records_this_python(installed):
    assert sorted(p.name for p in installed.iterdir()) == sorted(FILES)
    script = (installed / "fabtiles_render.py").read_text()
    assert f"FABTILES_PYTHON = {sys.executable!r}" in script
    inx = etree.parse(str(installed / "fabtiles_render.inx")).getroot()
    ns = "{http://www.inkscape.org/namespace/inkscape/extension}"
    assert inx.find(f"{ns}script/{ns}command").text == "fabtiles_render.py"
    assert inx.find(f"{ns}effect/{ns}effects-menu/{ns}submenu").get("name") == "Render"
    assert {p.get("name") for p in inx.iter(f"{ns}param")} >= {"preset", "packing", "radius", "size", "stroke"}


def test_default_dest_is_the_users_inkscape_folder(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    assert default_dest() == tmp_path / "inkscape" / "extensions"


def test_the_readme_sample_at_true_size_in_named_layers(installed, tmp_path):
    res = as_inkscape_runs_it(installed, tmp_path)
    assert res.returncode == 0, res.stderr
    out = tmp_path / "out.svg"
    out.write_text(res.stdout)
    root = etree.fromstring(res.stdout.encode())
    layers = [g for g in root if g.get(INK + "groupmode") == "layer"]
    assert [g.get(INK + "label") for g in layers] == ["INNER", "OUTER"]  # the laser SVG's layers
    # inkex reads it back
    python = inkscape_python()
    check = (
        "import inkex, sys; svg = inkex.load_svg(sys.argv[1]).getroot(); "
        "print([g.label for g in svg.descendants().filter(inkex.Layer)])"
    )
    env = dict(os.environ, PYTHONPATH=str(INKSCAPE_EXTENSIONS))
    assert run([python, "-c", check, out], env=env).stdout.strip() == "['INNER', 'OUTER']"
    # Inkscape measures it: the outer cut is the 150 mm tile plus the kerf (0.15 mm), its hairline included
    inkscape = program("inkscape", "apt-get install inkscape")
    rows = run([inkscape, "--query-all", out], env=dict(os.environ, HOME=str(tmp_path))).stdout.splitlines()
    ids = {g.get("id"): g.get(INK + "label") for g in layers}
    boxes = {
        ids[r.split(",")[0]]: [float(v) / PX_PER_MM for v in r.split(",")[1:]] for r in rows if r.split(",")[0] in ids
    }
    x, y, w, h = boxes["OUTER"]
    assert (x, y) == pytest.approx((-0.0125, -0.0125), abs=0.01)
    assert (w, h) == pytest.approx((150.15 + 0.025, 150.15 + 0.025), abs=0.01)


def test_the_dialogs_values_and_fabtiles_errors_as_one_line(installed, tmp_path):
    res = as_inkscape_runs_it(installed, tmp_path, "--size=100", "--packing=square", "--radius=10")
    assert res.returncode == 0, res.stderr
    root = etree.fromstring(res.stdout.encode())
    assert len(root.findall(".//{http://www.w3.org/2000/svg}path")) > 10
    res = as_inkscape_runs_it(installed, tmp_path, "--stroke=0.01")
    assert res.returncode != 0 and "Traceback" not in res.stderr
    lines = [x for x in res.stderr.splitlines() if x.strip()]
    assert len(lines) == 1 and re.match(r"fabtiles: error: stroke must be >= min_feature_mm", lines[0]), res.stderr
