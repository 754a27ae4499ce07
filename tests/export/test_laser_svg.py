"""Laser SVG: same contours and layers as the DXF, stroke colours, true mm size, reproducible."""

from __future__ import annotations

import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from dxf_helpers import dxf_entities, motif_tile, star_plate
from model_files import write_cut
from shapely.geometry import box

from fabtiles import FabricationError, ParameterError, ProfileError
from fabtiles.export.laser_svg import aci_to_hex
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")
NS = {"s": "http://www.w3.org/2000/svg"}


def parse_path(d: str) -> np.ndarray:
    nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", d)]
    return np.array(nums).reshape(-1, 2)


def test_same_contours_as_dxf(tmp_path):
    region, outline = star_plate()
    svg, dxf = tmp_path / "p.svg", tmp_path / "p.dxf"
    r1 = write_cut(svg, region=region, outline=outline, profile=PLY)
    r2 = write_cut(dxf, region=region, outline=outline, profile=PLY)
    assert r1.format == "svg" and {k: v for k, v in r1.stats.items() if k != "dxf_version"} == {
        k: v for k, v in r2.stats.items() if k != "dxf_version"
    }
    root = ET.parse(svg).getroot()
    k = PLY.kerf_mm / 2
    assert root.get("width") == f"{60 + 2 * k:g}mm" and root.get("height") == f"{60 + 2 * k:g}mm"
    # the plate grown by half the kerf and moved into the positive quadrant: the view from (0, 0)
    assert [float(v) for v in root.get("viewBox").split()] == pytest.approx([0, -60 - 2 * k, 60 + 2 * k, 60 + 2 * k])
    groups = root.findall("s:g", NS)
    assert [g.get("id") for g in groups] == ["INNER", "OUTER"]
    assert [g.get("stroke") for g in groups] == ["#FF0000", "#FF0000"]  # both cuts red (docs/laser-programs.md)
    assert all(g.get("fill") == "none" for g in groups)
    paths = [(g.get("id"), p.get("d")) for g in groups for p in g.findall("s:path", NS)]
    ents = dxf_entities(dxf)
    assert [layer for layer, _ in paths] == [e[0] for e in ents]
    for (_, d), e in zip(paths, ents, strict=True):
        assert d.startswith("M") and d.endswith("Z")
        pts = parse_path(d)
        pts[:, 1] = -pts[:, 1]  # y flipped back
        assert pts == pytest.approx(np.array(e[4]), abs=1e-3)


def test_score_mode_and_colours(tmp_path):
    region, outline, seg = motif_tile()
    svg = tmp_path / "s.svg"
    write_cut(svg, region=region, outline=outline, centrelines=seg, profile=PLY, mode="score", kerf_mm=0)
    root = ET.parse(svg).getroot()
    groups = {g.get("id"): g for g in root.findall("s:g", NS)}
    assert list(groups) == ["SCORE", "OUTER"]
    assert groups["SCORE"].get("stroke") == "#0000FF"
    assert all(not p.get("d").endswith("Z") for p in groups["SCORE"].findall("s:path", NS))
    assert root.get("width") == "100mm"


def test_reproducible_byte_for_byte(tmp_path):
    region, outline, _ = motif_tile()
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    write_cut(a, region=region, outline=outline, profile=PLY)
    write_cut(b, region=region, outline=outline, profile=PLY)
    assert a.read_bytes() == b.read_bytes()
    text = a.read_text()
    assert not re.search(r"[ ML]-0[ LZ\"]", text) and not re.search(r"\de[-+]?\d", text)


def test_aci_colours_are_ezdxfs_and_the_standard_ones_need_no_ezdxf():
    from ezdxf.colors import aci2rgb

    assert [aci_to_hex(c) for c in range(1, 256)] == ["#{:02X}{:02X}{:02X}".format(*aci2rgb(c)) for c in range(1, 256)]
    code = "import sys; from fabtiles.export.laser_svg import aci_to_hex; aci_to_hex(5); print('ezdxf' in sys.modules)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "False"


@pytest.mark.parametrize(
    "change, error",
    [
        (dict(kerf_mm=-1), ParameterError),
        (dict(profile="nope"), ProfileError),
        (dict(outline=box(0, 0, 601, 401)), FabricationError),
    ],
)
def test_bad_input_no_file(tmp_path, change, error):
    region, outline = star_plate()
    with pytest.raises(error):
        write_cut(tmp_path / "x.svg", **(dict(region=region, outline=outline, profile=PLY) | change))
    assert list(tmp_path.iterdir()) == []


def test_a_plate_with_one_hole_is_drawn_at_its_size(tmp_path):
    plate = box(0, 0, 40, 40).difference(box(10, 10, 30, 30))
    out = tmp_path / "plate.svg"
    r = write_cut(out, region=plate, outline=box(0, 0, 40, 40), profile="laser-3mm-plywood", kerf_mm=0)
    assert ('width="40mm"' in out.read_text(), r.stats["inner_contours"]) == (True, 1)
