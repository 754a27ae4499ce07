"""The STL sliced by CuraEngine, UltiMaker Cura's slicer (Debian's ``cura-engine``), issue 21.

CuraEngine takes Cura's machine definitions; `.ci/run` unpacks Debian's ``cura``
package for ``fdmprinter.def.json`` (and ``fdmextruder.def.json`` beside it, which
the engine loads itself) without installing Cura. A 50 mm tile at 0.3 mm layers
slices in well under a second (the 150 mm tile at Cura's default 0.1 mm took 96 s).

The summary asserted on is what ``-v`` prints on stderr after slicing; the header
inside the G-code file keeps placeholders (``;TIME:6666``).
"""

from __future__ import annotations

import re

import pytest
from mesh_helpers import B, H, T
from real_programs import cura_definitions, program, run

from fabtiles import HexPacking, Star, Tile

LAYER_MM = 0.3


def slice_stl(tmp_path, stl, **settings):
    engine = program("CuraEngine", "apt-get install cura-engine")
    definitions = cura_definitions()
    cmd = [
        engine,
        "slice",
        "-v",
        "-j",
        definitions / "fdmprinter.def.json",
        "-s",
        f"layer_height={LAYER_MM}",
        "-s",
        f"layer_height_0={LAYER_MM}",
        "-s",
        "adhesion_type=none",
    ]
    for key, value in settings.items():
        cmd += ["-s", f"{key}={value}"]
    done = run([*cmd, "-l", stl, "-o", tmp_path / "out.gcode"], timeout=120)
    err = done.stderr
    summary = err[err.index("Gcode header after slicing:") :]
    return dict(
        layers=int(re.search(r"^Layer count: (\d+)$", err, re.M).group(1)),
        max_z=float(re.search(r"^;MAXZ:([0-9.]+)$", summary, re.M).group(1)),
        filament_mm3=float(re.search(r"^Filament \(mm\^3\): ([0-9.]+)$", err, re.M).group(1)),
    )


@pytest.mark.parametrize("style,height", [("relief", B + H), ("pierced", T), ("deboss", B)])
def test_curaengine_slices_each_print_style_to_its_height(tmp_path, style, height):
    tile = Tile("square", 50, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0)
    stl = tmp_path / f"{style}.stl"
    report = tile.export(stl, style=style)
    got = slice_stl(tmp_path, stl, infill_sparse_density=100)
    # CuraEngine slices each 0.3 mm layer at its middle: as many layers as the height holds, rounded
    assert got["layers"] == round(height / LAYER_MM)
    assert got["max_z"] == pytest.approx(got["layers"] * LAYER_MM, abs=1e-6)
    # solid infill: the filament is the body's volume, to what layer rounding and extrusion overlap leave
    assert got["filament_mm3"] == pytest.approx(report.stats["volume_mm3"] * got["max_z"] / height, rel=0.05)
