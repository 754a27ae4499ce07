"""A 3MF of N colours: one object of N parts, each on its own extruder, read by the slicers (issue 33).

The model is synthetic: N boxes side by side on the plate, box k (0-based) at
``x = 10k .. 10k + 8`` mm and ``2 + 0.4k`` mm high, part k on extruder k + 1, so a
tool's extrusions show which part it printed. The readers:

- PrusaSlicer slices it with an N-extruder printer (tool changes T0..T(N-1), each
  tool inside its own box) and with fewer extruders (silently: a part on a missing
  extruder takes the first; one extruder, no tool change at all); ``--info`` and
  ``--export-3mf`` keep N volumes;
- Cura's parser libSavitar sees the components layout as one group of N children
  with ``extruder_nr`` 0..N-1;
- lib3mf reads both layouts strictly, without a warning.

Bambu Studio and OrcaSlicer have no command line here; docs/slicers.md ("N colours")
says what their source does with N extruders. CuraEngine reads no 3MF (Cura's
front end does), so it is not run here.
"""

from __future__ import annotations

import re
import types
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
from real_programs import program, run
from test_3mf_readers import info, lib3mf_read, savitar

from fabtiles import ParameterError
from fabtiles.export import threemf
from fabtiles.solid.parts import CheckedPart
from fabtiles.solid.print_model import PrintPart

CURA = "http://software.ultimaker.com/xml/cura/3mf/2015/10"

COLOURS = [
    "#1f3b73",
    "#e6d6b8",
    "#c0392b",
    "#27ae60",
    "#f1c40f",
    "#8e44ad",
    "#16a085",
    "#d35400",
    "#2c3e50",
    "#7f8c8d",
    "#e84393",
    "#00cec9",
    "#6c5ce7",
    "#fdcb6e",
    "#b33939",
    "#218c74",
]

LAYER = 0.2

# the box's corners and its 12 triangles, wound outward
_CORNERS = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
_FACES = np.array(
    [
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ]
)


def name(k: int) -> str:
    """Part k's name: its class and colour, as a mosaic names them; one of them holds XML's special characters."""
    text = f"{chr(ord('A') + k)} {COLOURS[k]}"
    return text + ' & "quoted" <b>' if k == 2 else text


def height(k: int) -> float:
    return 2 + 0.4 * k


def boxes(n: int) -> list:
    """N closed boxes side by side, box k on extruder k + 1."""
    return [threemf.Part(name(k), k + 1, _CORNERS * [8, 8, height(k)] + [10 * k, 0, 0], _FACES) for k in range(n)]


def write(tmp_path, n: int, layout: str):
    path = tmp_path / f"mosaic-{n}-{layout}.3mf"
    path.write_bytes(
        threemf.package_3mf(
            boxes(n), name="mosaic & co", layout=layout, application=threemf.application_name(layout, "test")
        )
    )
    return path


def entries(path) -> dict:
    with zipfile.ZipFile(path) as zf:
        return {n: zf.read(n) for n in zf.namelist()}


# --------------------------------------------------------------------------- the package


@pytest.mark.parametrize("n", [1, 2, 4, 6, 16])
def test_each_of_n_parts_keeps_its_name_and_extruder_in_both_layouts(tmp_path, n):
    want = [(name(k), k + 1) for k in range(n)]
    for layout in threemf.LAYOUTS:
        parts = threemf.read_3mf(write(tmp_path, n, layout))
        assert [(p.name, p.extruder) for p in parts.values()] == want
        for k, p in enumerate(parts.values()):
            assert len(p.faces) == 12 and len(p.vertices) == 8
            assert p.vertices.min(axis=0) == pytest.approx([10 * k, 0, 0], abs=1e-6)
            assert p.vertices.max(axis=0) == pytest.approx([10 * k + 8, 8, height(k)], abs=1e-6)


@pytest.mark.parametrize("n", [4, 16])
def test_the_volumes_configs_give_every_volume_its_extruder(tmp_path, n):
    pkg = entries(write(tmp_path, n, "volumes"))
    (obj,) = ET.fromstring(pkg[threemf.PRUSA_CONFIG_PATH]).iter("object")
    volumes = [{m.get("key"): m.get("value") for m in v.iter("metadata")} for v in obj.iter("volume")]
    assert [(v["name"], v["extruder"], v["volume_type"]) for v in volumes] == [
        (name(k), str(k + 1), "ModelPart") for k in range(n)
    ]
    ranges = [(int(v.get("firstid")), int(v.get("lastid"))) for v in obj.iter("volume")]
    assert ranges == [(12 * k, 12 * k + 11) for k in range(n)]  # contiguous, in order
    # Bambu Studio / OrcaSlicer's model settings: the same parts, names and filaments
    (obj,) = ET.fromstring(pkg[threemf.BAMBU_CONFIG_PATH]).iter("object")
    parts = [{m.get("key"): m.get("value") for m in p.iter("metadata")} for p in obj.iter("part")]
    assert [(p["name"], p["extruder"]) for p in parts] == [(name(k), str(k + 1)) for k in range(n)]
    assert threemf.takes_prusa_path(pkg)


@pytest.mark.parametrize("n", [4, 16])
def test_the_components_layout_gives_cura_extruders_0_to_n_minus_1(tmp_path, n):
    pkg = entries(write(tmp_path, n, "components"))
    core = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"
    model = ET.fromstring(pkg[threemf.MODEL_PATH])
    objects = {o.get("id"): o for o in model.iter(f"{core}object")}
    (item,) = model.iter(f"{core}item")
    ids = [c.get("objectid") for c in objects[item.get("objectid")].iter(f"{core}component")]
    assert ids == [str(k) for k in range(1, n + 1)] and item.get("objectid") == str(n + 1)
    got = [(objects[i].get("name"), {m.get("name"): m.text for m in objects[i].iter(f"{core}metadata")}) for i in ids]
    assert got == [(name(k), {"cura:extruder_nr": str(k)}) for k in range(n)]
    (obj,) = ET.fromstring(pkg[threemf.BAMBU_CONFIG_PATH]).iter("object")
    assert obj.get("id") == str(n + 1)
    parts = {p.get("id"): {m.get("key"): m.get("value") for m in p.iter("metadata")} for p in obj.iter("part")}
    assert [(i, parts[i]["name"], parts[i]["extruder"]) for i in ids] == [
        (str(k + 1), name(k), str(k + 1)) for k in range(n)
    ]
    assert not threemf.takes_prusa_path(pkg)


def test_names_are_escaped_text_and_write_no_display_colour(tmp_path):
    for layout in threemf.LAYOUTS:
        pkg = entries(write(tmp_path, 4, layout))
        assert b'& "quoted" <b>' not in pkg[threemf.MODEL_PATH]
        assert b"&amp;" in pkg[threemf.MODEL_PATH]  # the object's Title, and in components the part's name
        # one source of extruders: no basematerials or colour groups (see the module text of threemf)
        assert b"basematerials" not in pkg[threemf.MODEL_PATH] and b"colorgroup" not in pkg[threemf.MODEL_PATH]
        assert b"pid=" not in pkg[threemf.MODEL_PATH]


def test_a_print_model_of_n_parts_is_written_in_its_order_and_extruders():
    """model_3mf_bytes writes a print model's N parts (their materials the extruders), not only two."""
    parts = {}
    for k, p in enumerate(boxes(6)):
        mesh = CheckedPart(p.vertices, p.faces, 0.0, 1, None, None, 8 * 8 * height(k))
        parts[p.name] = PrintPart(p.name, 6 - k, (0.1, 0.2, 0.3), mesh)  # extruders in reverse: kept as given
    model = types.SimpleNamespace(parts=parts)
    for layout in threemf.LAYOUTS:
        got = threemf.read_3mf(threemf.model_3mf_bytes(model, name="m", layout=layout))
        assert [(p.name, p.extruder) for p in got.values()] == [(name(k), 6 - k) for k in range(6)]


@pytest.mark.parametrize("extruder", [0, 17, -1, 1.5, "2", True])
def test_a_part_off_the_extruders_is_refused(extruder):
    parts = boxes(2)
    parts[1] = parts[1]._replace(extruder=extruder)
    with pytest.raises(
        ParameterError,
        match=r"part 'B #e6d6b8' has extruder=.*, must be an integer from 1 to 16 "
        r"\(Bambu Studio and OrcaSlicer add filaments up to 16 only\): merge colours so "
        r"that at most 16 remain",
    ):
        threemf.package_3mf(parts, name="t")


def test_sixteen_parts_are_the_most():
    parts = boxes(16)
    parts.append(threemf.Part("Q #000000", 17, parts[0].vertices + [0, 20, 0], parts[0].faces))
    with pytest.raises(ParameterError, match=r"extruder=17, must be an integer from 1 to 16"):
        threemf.package_3mf(parts, name="t", layout="components")


def test_no_parts_is_refused():
    with pytest.raises(ParameterError, match=r"a 3MF needs at least one part, got none"):
        threemf.package_3mf([], name="t")


# --------------------------------------------------------------------------- PrusaSlicer


def printer_ini(tmp_path, n: int):
    """A PrusaSlicer printer of ``n`` extruders (0.4 mm nozzles, no offsets, no wipe tower, no skirt).

    No extra perimeters, the classic perimeter generator and no gap fill: Arachne's variable-width
    perimeters and the gap fill are the slowest passes over a mosaic of many small faces, and which
    tool prints what is the same without them.
    """
    ini = tmp_path / f"printer-{n}.ini"
    each = lambda value, sep=",": sep.join([value] * n)  # noqa: E731 - one value per extruder
    blank = '""'
    ini.write_text(
        f"nozzle_diameter = {each('0.4')}\nextruder_colour = {each(blank, ';')}\n"
        f"extruder_offset = {each('0x0')}\nretract_length = {each('2')}\nretract_lift = {each('0')}\n"
        f"wipe_tower = 0\nskirts = 0\nbrim_width = 0\nuse_relative_e_distances = 1\n"
        f"layer_height = {LAYER}\nfirst_layer_height = {LAYER}\nextra_perimeters = 0\n"
        "perimeter_generator = classic\ngap_fill_enabled = 0\n"
        "bed_shape = 0x0,250x0,250x210,0x210\n"
    )
    return ini


def prusa_cmd(tmp_path) -> list:
    return [
        program("prusa-slicer", "apt-get install prusa-slicer"),
        "--loglevel",
        "1",
        "--datadir",
        tmp_path / "prusa-data",
    ]


CENTRE = (125.0, 100.0)


def slice_gcode(tmp_path, path, extruders: int) -> str:
    out = tmp_path / f"{path.stem}-{extruders}.gcode"
    run(
        [
            *prusa_cmd(tmp_path),
            "--load",
            printer_ini(tmp_path, extruders),
            "--export-gcode",
            "--dont-arrange",
            "--center",
            f"{CENTRE[0]},{CENTRE[1]}",
            "--output",
            out,
            path,
        ],
        cwd=tmp_path,
    )
    return out.read_text()


def extrusions_by_tool(gcode: str) -> dict:
    """The x of every extruding move, by the tool that made it (None before any tool command)."""
    tool, xs = None, {}
    for line in gcode.splitlines():
        if re.fullmatch(r"T\d+", line.strip()):
            tool = int(line.strip()[1:])
            continue
        m = re.match(r"G1 X([-\d.]+) Y[-\d.]+ E([-\d.]+)", line)
        if m and float(m.group(2)) > 0:  # relative E: a positive value is an extrusion
            xs.setdefault(tool, []).append(float(m.group(1)))
    return xs


@pytest.mark.parametrize("n", [4, 6])
def test_prusaslicer_with_n_extruders_prints_each_part_with_its_own_tool(tmp_path, n):
    gcode = slice_gcode(tmp_path, write(tmp_path, n, "volumes"), n)
    tools = sorted({int(t) for t in re.findall(r"^T(\d+)\s*$", gcode, flags=re.M)})
    assert tools == list(range(n))  # T0..T(N-1), each at least once
    xs = extrusions_by_tool(gcode)
    assert sorted(xs) == list(range(n))  # nothing extruded before the first tool command
    shift = CENTRE[0] - (10 * n - 2) / 2  # --center puts the boxes' middle there
    for tool, x in xs.items():
        # every extrusion of tool k lies inside box k (perimeters sit half a line width inside)
        assert 10 * tool - 0.01 <= min(x) - shift and max(x) - shift <= 10 * tool + 8 + 0.01, tool
    layers = [float(z) for z in re.findall(r"^;Z:([0-9.]+)$", gcode, flags=re.M)]
    assert max(layers) == pytest.approx(height(n - 1), abs=1e-6)


@pytest.mark.parametrize("extruders", [1, 2])
def test_prusaslicer_with_fewer_extruders_prints_the_other_parts_with_the_first(tmp_path, extruders):
    """A printer of fewer extruders than parts slices without a word: a part on a missing extruder takes the first.

    One extruder: no tool change at all, the whole print in one filament.
    """
    gcode = slice_gcode(tmp_path, write(tmp_path, 4, "volumes"), extruders)
    shift = CENTRE[0] - (10 * 4 - 2) / 2
    boxes_by_tool = {tool: {int((x - shift) // 10) for x in xs} for tool, xs in extrusions_by_tool(gcode).items()}
    if extruders == 1:
        assert re.findall(r"^T\d+", gcode, flags=re.M) == []
        assert boxes_by_tool == {None: {0, 1, 2, 3}}
    else:
        assert boxes_by_tool == {0: {0, 2, 3}, 1: {1}}  # boxes 3 and 4 (extruders 3, 4) on the first


@pytest.mark.parametrize("n", [4, 6])
def test_prusaslicer_reads_one_object_of_n_volumes_and_saves_them_again(tmp_path, n):
    path = write(tmp_path, n, "volumes")
    (obj,) = info(prusa_cmd(tmp_path), path, tmp_path)
    assert int(obj["number_of_parts"]) == n and obj["manifold"] == "yes"
    assert float(obj["volume"]) == pytest.approx(sum(64 * height(k) for k in range(n)), rel=1e-6)
    saved = tmp_path / "saved.3mf"
    run([*prusa_cmd(tmp_path), "--export-3mf", "--output", saved, path], cwd=tmp_path)
    (saved_obj,) = ET.fromstring(entries(saved)[threemf.PRUSA_CONFIG_PATH]).iter("object")
    volumes = [{m.get("key"): m.get("value") for m in v.iter("metadata")} for v in saved_obj.iter("volume")]
    assert [(v["name"], v["extruder"]) for v in volumes] == [(name(k), str(k + 1)) for k in range(n)]


def test_prusaslicer_opens_the_components_layout_as_one_object_per_part(tmp_path):
    objects = info(prusa_cmd(tmp_path), write(tmp_path, 4, "components"), tmp_path)
    assert [float(o["max_z"]) for o in objects] == pytest.approx([height(k) for k in range(4)], abs=1e-5)


# --------------------------------------------------------------------------- Cura's parser, lib3mf


@pytest.mark.parametrize("n", [4, 6])
def test_cura_sees_n_children_on_extruders_0_to_n_minus_1(tmp_path, n):
    got = savitar(write(tmp_path, n, "components"))
    (group,) = got["nodes"]
    assert group["faces"] == 0
    assert [(c["name"], c["settings"], c["faces"]) for c in group["children"]] == [
        (name(k), {"extruder_nr": str(k)}, 12) for k in range(n)
    ]


@pytest.mark.parametrize("layout", threemf.LAYOUTS)
@pytest.mark.parametrize("n", [4, 6])
def test_lib3mf_strict_reads_n_parts(tmp_path, n, layout):
    got = lib3mf_read(write(tmp_path, n, layout))
    assert got["warnings"] == [] and got["unit"] == got["mm"]
    assert all(manifold for _, _, manifold, _ in got["meshes"].values())
    if layout == "volumes":
        assert got["components"] == {} and len(got["items"]) == 1
        assert [(tris, meta) for _, tris, _, meta in got["meshes"].values()] == [(12 * n, {})]
    else:
        ((assembly, ids),) = got["components"].items()
        assert got["items"] == [assembly] and ids == list(range(1, n + 1))
        assert [(got["meshes"][i][0], got["meshes"][i][1], got["meshes"][i][3]) for i in ids] == [
            (name(k), 12, {(CURA, "extruder_nr"): str(k)}) for k in range(n)
        ]
