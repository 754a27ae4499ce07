"""3MF export (issue 12): one object of named parts, opened by the slicers' own readers.

The PrusaSlicer tests run Debian's ``prusa-slicer`` (2.5) headless. `.ci/run`
installs it and sets FABTILES_REQUIRE_PRUSA=1, so there (or wherever CI or that
variable is set) a missing slicer fails instead of skipping.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
import shapely
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from mesh_helpers import (
    VOLUME_REL,
    B,
    D,
    H,
    T,
    assert_section,
    assert_solid,
    assert_touch_without_overlap,
    load_3mf_parts,
)
from model_files import write_print

from fabtiles import FabricationError, ParameterError, Star
from fabtiles import Tile as PublicTile
from fabtiles.export import threemf
from fabtiles.geometry.tile import TileGeometry
from fabtiles.pattern.packing import HexPacking
from fabtiles.solid import parts

PRUSA = shutil.which("prusa-slicer") or "/usr/bin/prusa-slicer"
REQUIRED = bool(os.environ.get("CI")) or os.environ.get("FABTILES_REQUIRE_PRUSA") == "1"

TWO_EXTRUDERS = """\
nozzle_diameter = 0.4,0.4
extruder_colour = "";""
extruder_offset = 0x0,0x0
retract_length = 2,2
retract_lift = 0,0
wipe_tower = 0
layer_height = 0.2
first_layer_height = 0.2
"""
"""A two-extruder PrusaSlicer printer (no wipe tower: the tile alone sets the layers)."""


def small_tile(size=40, preset="table3-3"):
    return TileGeometry("square", size, HexPacking(10, Star.preset(preset)), frame=3, stroke=1.0)


@pytest.fixture(scope="module")
def shapes():
    tile = small_tile()
    return tile.region(), tile.outline_shape()


@pytest.fixture(scope="module")
def prusa():
    if not os.path.exists(PRUSA):
        if REQUIRED:
            pytest.fail(
                f"PrusaSlicer is required here (CI or FABTILES_REQUIRE_PRUSA=1) but {PRUSA} is not "
                "installed: apt-get install prusa-slicer"
            )
        pytest.skip(f"{PRUSA} is not installed")
    return PRUSA


def run_prusa(tmp_path, *args) -> str:
    """Run prusa-slicer headless with its settings kept in ``tmp_path``; return its stdout."""
    cmd = [PRUSA, "--loglevel", "1", "--datadir", str(tmp_path / "prusa-data"), *map(str, args)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, f"{cmd} failed:\n{done.stdout}\n{done.stderr}"
    return done.stdout


def prusa_info(tmp_path, path) -> list[dict]:
    """``prusa-slicer --info``: one dict of key -> value per object it loaded."""
    objects = []
    for line in run_prusa(tmp_path, "--info", path).splitlines():
        if re.fullmatch(r"\[.*\]", line.strip()):
            objects.append({})
        elif "=" in line and objects:
            key, value = (s.strip() for s in line.split("=", 1))
            objects[-1][key] = value
    return objects


def prusa_volumes(tmp_path, path) -> list[list[dict]]:
    """The objects and volumes PrusaSlicer made of ``path``, as it saves them again (``--export-3mf``)."""
    out = tmp_path / "prusa-saved.3mf"
    run_prusa(tmp_path, "--export-3mf", "--output", out, path)
    config = ET.fromstring(zipfile.ZipFile(out).read("Metadata/Slic3r_PE_model.config"))
    return [
        [{m.get("key"): m.get("value") for m in vol.iter("metadata")} for vol in obj.iter("volume")]
        for obj in config.iter("object")
    ]


def layers(gcode: str) -> list[float]:
    """The print heights of a PrusaSlicer G-code, one per layer."""
    return [float(z) for z in re.findall(r"^;Z:([0-9.]+)$", gcode, flags=re.M)]


# --------------------------------------------------------------------------- PrusaSlicer


def test_relief_is_one_object_of_two_parts_in_prusaslicer(tmp_path, shapes, prusa):
    region, outline = shapes
    path = tmp_path / "tile.3mf"
    report = write_print(path, region=region, outline=outline, profile="fdm-0.4mm")
    assert {n: p["extruder"] for n, p in report.stats["parts"].items()} == {"base": 1, "pattern": 2}
    (info,) = prusa_info(tmp_path, path)  # one object, not one per part
    # number_of_parts counts the object's shells: the base plate and the pattern (one piece with its frame)
    assert len(shapely.get_parts(region)) == 1
    assert int(info["number_of_parts"]) == 2
    assert info["manifold"] == "yes"
    assert float(info["min_z"]) == pytest.approx(0, abs=1e-5)
    assert float(info["max_z"]) == pytest.approx(B + H, abs=1e-5)
    assert float(info["volume"]) == pytest.approx(outline.area * B + region.area * H, rel=0.005)
    ((base, pattern),) = prusa_volumes(tmp_path, path)
    assert (base["name"], base["extruder"]) == ("base", "1")
    assert (pattern["name"], pattern["extruder"]) == ("pattern", "2")
    assert base["volume_type"] == pattern["volume_type"] == "ModelPart"


def test_relief_slices_like_its_stl_with_the_pattern_on_the_second_filament(tmp_path, shapes, prusa):
    region, outline = shapes
    ini = tmp_path / "two-extruders.ini"
    ini.write_text(TWO_EXTRUDERS)
    write_print(tmp_path / "tile.3mf", region=region, outline=outline, profile="fdm-0.4mm")
    write_print(tmp_path / "tile.stl", region=region, outline=outline, profile="fdm-0.4mm")
    got = {}
    for fmt in ("3mf", "stl"):
        run_prusa(
            tmp_path,
            "--load",
            ini,
            "--export-gcode",
            "--dont-arrange",
            "--center",
            "100,100",
            "--output",
            tmp_path / f"{fmt}.gcode",
            tmp_path / f"tile.{fmt}",
        )
        got[fmt] = (tmp_path / f"{fmt}.gcode").read_text()
    z3, zs = layers(got["3mf"]), layers(got["stl"])
    assert z3 == zs and len(z3) == round((B + H) / 0.2)
    # the base prints with the first filament, the pattern (above z = base) with the second
    lines = got["3mf"].splitlines()
    first_t1 = next(i for i, line in enumerate(lines) if line == "T1")
    last_z = [float(line[3:]) for line in lines[:first_t1] if line.startswith(";Z:")][-1]
    assert last_z > B
    assert not any(line == "T1" for line in got["stl"].splitlines())


def test_deboss_inlay_fills_the_grooves_flush(tmp_path, shapes, prusa):
    region, outline = shapes
    path = tmp_path / "inlay.3mf"
    report = PublicTile("square", 40, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0).export(
        path, style="deboss", inlay=True, fill_small_holes=False
    )
    assert report.stats["bodies"] == ["plate", "inlay"]
    parts = load_3mf_parts(path)
    assert list(parts) == ["plate", "inlay"]
    plate, inlay = parts["plate"], parts["inlay"]
    assert_solid(plate, outline.area * B - region.area * D, outline.bounds, B)
    assert_solid(inlay, region.area * D, outline.bounds, B, zmin=B - D, bodies=len(shapely.get_parts(region)))
    assert_section(plate, (B - D) / 2, outline)
    assert_section(plate, B - D / 2, outline.difference(region))
    assert_section(inlay, B - D / 2, region)
    # flush: the inlay's top is the plate's top; together they are the full plate, without overlap
    assert inlay.bounds[1][2] == plate.bounds[1][2] == np.float32(B)
    assert plate.volume + inlay.volume == pytest.approx(outline.area * B, rel=1e-4)
    assert report.stats["volume_mm3"] == pytest.approx(plate.volume + inlay.volume, rel=1e-9)  # the file's parts
    assert_touch_without_overlap(plate, inlay)
    (info,) = prusa_info(tmp_path, path)
    assert int(info["number_of_parts"]) == 1 + len(shapely.get_parts(region))
    assert float(info["max_z"]) == pytest.approx(B, abs=1e-5)
    assert float(info["volume"]) == pytest.approx(outline.area * B, rel=0.005)
    ((p, i),) = prusa_volumes(tmp_path, path)
    assert (p["name"], p["extruder"], i["name"], i["extruder"]) == ("plate", "1", "inlay", "2")


@pytest.mark.parametrize("style,name,top", [("pierced", "pattern", T), ("deboss", "plate", B)])
def test_single_body_styles_are_one_object_of_one_part(tmp_path, shapes, prusa, style, name, top):
    region, outline = shapes
    path = tmp_path / "t.3mf"
    write_print(path, region=region, outline=outline, profile="fdm-0.4mm", style=style)
    assert list(load_3mf_parts(path)) == [name]
    (info,) = prusa_info(tmp_path, path)
    assert float(info["max_z"]) == pytest.approx(top, abs=1e-5)
    ((volume,),) = prusa_volumes(tmp_path, path)
    assert (volume["name"], volume["extruder"]) == (name, "1")


# --------------------------------------------------------------------------- the package


def test_slicer_metadata_agree_with_the_model(tmp_path, shapes):
    region, outline = shapes
    path = tmp_path / "My tile.3mf"
    write_print(path, region=region, outline=outline, profile="fdm-0.4mm")
    zf = zipfile.ZipFile(path)
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    model = ET.fromstring(zf.read("3D/3dmodel.model"))
    assert model.get("unit") == "millimeter"
    (obj,) = model.findall("m:resources/m:object", ns)
    assert obj.get("name") == "My tile" and obj.get("type") == "model"
    assert [i.get("objectid") for i in model.findall("m:build/m:item", ns)] == [obj.get("id")]
    ntri = len(obj.findall("m:mesh/m:triangles/m:triangle", ns))

    def parts_of(config, tag, key):
        (o,) = config.iter("object")
        assert o.get("id") == obj.get("id")
        meta = {m.get("key"): m.get("value") for m in o.findall("metadata")}
        assert meta["name"] == "My tile"
        return [
            (int(v.get("firstid")), int(v.get("lastid")), {m.get("key"): m.get("value") for m in v.findall("metadata")})
            for v in o.findall(tag)
        ]

    prusa = parts_of(ET.fromstring(zf.read("Metadata/Slic3r_PE_model.config")), "volume", "type")
    bambu = parts_of(ET.fromstring(zf.read("Metadata/model_settings.config")), "part", "key")
    for ranges in (prusa, bambu):
        assert [(r[2]["name"], r[2]["extruder"]) for r in ranges] == [("base", "1"), ("pattern", "2")]
        # the ranges tile the triangles in order
        assert ranges[0][0] == 0 and ranges[0][1] + 1 == ranges[1][0] and ranges[1][1] == ntri - 1
    assert [r[:2] for r in prusa] == [r[:2] for r in bambu]
    assert all(
        p.get("subtype") == "normal_part" for p in ET.fromstring(zf.read("Metadata/model_settings.config")).iter("part")
    )
    # every part closed on its own vertices: no vertex index shared between parts
    parts = threemf.read_3mf(path)
    assert len(parts["base"].vertices) + len(parts["pattern"].vertices) == len(
        obj.findall("m:mesh/m:vertices/m:vertex", ns)
    )


def test_the_same_bytes_every_run(tmp_path, shapes):
    region, outline = shapes
    for name in ("a", "b"):
        write_print(tmp_path / name / "t.3mf", region=region, outline=outline, profile="fdm-0.4mm")
    assert (tmp_path / "a" / "t.3mf").read_bytes() == (tmp_path / "b" / "t.3mf").read_bytes()


def test_trimesh_reads_the_object(tmp_path, shapes):
    region, outline = shapes
    path = tmp_path / "tile.3mf"
    write_print(path, region=region, outline=outline, profile="fdm-0.4mm")
    scene = trimesh.load(path, file_type="3mf")
    assert list(scene.geometry) == ["tile"]
    assert scene.geometry["tile"].volume == pytest.approx(outline.area * B + region.area * H, rel=VOLUME_REL)


def test_vertices_read_back_are_the_checked_float32_values(shapes):
    region, outline = shapes
    stack = parts.resolve_stack("fdm-0.4mm", "relief")
    checked = parts.checked_parts(region, outline, stack)
    data = threemf.package_3mf([threemf.Part(n, 1, p.vertices, p.faces) for n, p in checked.items()], name="t")
    back = threemf.read_3mf(data)
    for n, p in checked.items():
        assert np.array_equal(back[n].vertices, p.vertices.astype(np.float32))
        assert np.array_equal(back[n].faces, p.faces)


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "kwargs,msg",
    [
        (dict(inlay=True), r"inlay=True needs style='deboss' .* got style='relief'"),
        (dict(inlay=True, style="pierced"), r"inlay=True needs style='deboss' .* got style='pierced'"),
        (dict(inlay="yes", style="deboss"), r"inlay must be True or False, got 'yes'"),
    ],
)
def test_bad_inlay_no_file(tmp_path, shapes, kwargs, msg):
    region, outline = shapes
    with pytest.raises(ParameterError, match=msg):
        write_print(tmp_path / "t.3mf", region=region, outline=outline, profile="fdm-0.4mm", **kwargs)
    with pytest.raises(ParameterError, match=msg):
        parts.build_meshes(region=region, outline=outline, profile="fdm-0.4mm", **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_inlay_is_a_3mf_option_only(tmp_path):
    tile = PublicTile("square", 40, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0)
    for fmt in ("stl", "step"):
        with pytest.raises(
            ParameterError,
            match=rf"'inlay' is not a valid option for .{fmt} files, must be one of: "
            r"style, base_mm, relief_mm, pierced_mm, deboss_mm, mosaic_inset_mm, fill_small_holes, pieces, colours$",
        ):
            tile.export(tmp_path / f"t.{fmt}", style="deboss", inlay=True)
    assert list(tmp_path.iterdir()) == []


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.floats(width=32, allow_nan=False, allow_infinity=False, min_value=-1e4, max_value=1e4),
        min_size=9,
        max_size=60,
    ).filter(lambda xs: len(xs) % 3 == 0)
)
def test_nine_digits_read_back_as_the_float32_written(values):
    """Why the export need not read its package back: "%.9g" of any float32 reads back as that float32
    (signed zero made 0, as the writer does), so every vertex the slicer reads is the checked one.
    Not as float64: 1000.640625 is written "1000.64062", which only float32 reads back exactly."""
    v = np.asarray(values, np.float32).reshape(-1, 3).astype(np.float64) + 0.0
    f = np.arange(len(v) // 3 * 3).reshape(-1, 3) if len(v) >= 3 else np.zeros((0, 3), int)
    text = threemf._mesh_xml(v, f, "")
    back = np.array([[float(x) for x in m] for m in re.findall(r'x="([^"]+)" y="([^"]+)" z="([^"]+)"', "".join(text))])
    assert np.array_equal(back.astype(np.float32), v.astype(np.float32))  # as float32, what slicers read


@pytest.mark.parametrize("layout", threemf.LAYOUTS)
@pytest.mark.parametrize("style, inlay", [("relief", False), ("deboss", True), ("pierced", False)])
def test_every_part_of_a_written_package_is_its_checked_mesh_bit_for_bit(tmp_path, shapes, style, inlay, layout):
    from fabtiles.solid.print_model import print_model

    region, outline = shapes
    model = print_model(region, outline, profile="fdm-0.4mm", style=style, inlay=inlay)
    back = threemf.read_3mf(threemf.model_3mf_bytes(model, layout=layout))
    assert list(back) == list(model.parts)
    for name, part in back.items():
        mesh = model.parts[name].mesh
        assert part.extruder == model.parts[name].material
        assert np.array_equal(part.faces, mesh.faces)
        assert np.array_equal(part.vertices, mesh.vertices.astype(np.float32))


def test_read_3mf_refuses_other_files(tmp_path, shapes):
    with pytest.raises(FabricationError, match="not a fabtiles 3MF package"):
        threemf.read_3mf(b"solid not a zip")
    region, outline = shapes
    path = tmp_path / "t.3mf"
    write_print(path, region=region, outline=outline, profile="fdm-0.4mm")
    files = {n: zipfile.ZipFile(path).read(n) for n in zipfile.ZipFile(path).namelist()}
    files["Metadata/Slic3r_PE_model.config"] = re.sub(
        rb'lastid="\d+">\s*<metadata type="volume" key="name" '
        rb'value="pattern"',
        b'lastid="99999999"><metadata type="volume" key="name" value="pattern"',
        files["Metadata/Slic3r_PE_model.config"],
    )
    bad = tmp_path / "bad.3mf"
    with zipfile.ZipFile(bad, "w") as zf:
        for n, data in files.items():
            zf.writestr(n, data)
    with pytest.raises(FabricationError, match=r"the 3MF volume 'pattern' has an invalid triangle range"):
        threemf.read_3mf(bad)


@pytest.mark.parametrize(
    "old,new,msg",
    [
        (b"<vertices>", b"<points>", r"the 3MF model has no <vertices> block"),
        (b'y="', b'y="y', r"the 3MF model's <vertex> records do not parse: \d+ numbers read for \d+ records of 3"),
        (b' v3="', b' v4="', r"the 3MF model's <triangle> records do not parse"),
    ],
)
def test_read_3mf_refuses_a_broken_model(tmp_path, shapes, old, new, msg):
    region, outline = shapes
    path = tmp_path / "t.3mf"
    write_print(path, region=region, outline=outline, profile="fdm-0.4mm")
    files = {n: zipfile.ZipFile(path).read(n) for n in zipfile.ZipFile(path).namelist()}
    files["3D/3dmodel.model"] = files["3D/3dmodel.model"].replace(old, new, 1)
    bad = tmp_path / "bad.3mf"
    with zipfile.ZipFile(bad, "w") as zf:
        for n, data in files.items():
            zf.writestr(n, data)
    with pytest.raises(FabricationError, match=msg):
        threemf.read_3mf(bad)


def test_interlaced_relief_keeps_its_dips(tmp_path):
    tile = PublicTile("square", 60, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.5, interlace=True)
    stl = tile.export(tmp_path / "w.stl")
    report = tile.export(tmp_path / "w.3mf")
    parts = load_3mf_parts(tmp_path / "w.3mf")
    assert list(parts) == ["base", "pattern"]
    # the dips lower the under strands: less than the full relief, as much as the STL's one body
    assert sum(p.volume for p in parts.values()) == pytest.approx(stl.stats["volume_mm3"], rel=1e-6)
    assert report.stats["volume_mm3"] == pytest.approx(stl.stats["volume_mm3"], rel=1e-6)
    region, outline = tile.region(), tile.outline_shape()
    assert stl.stats["volume_mm3"] < 0.999 * (outline.area * B + region.area * H)
