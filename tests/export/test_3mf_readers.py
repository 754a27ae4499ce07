"""The 3MF as the slicers' own readers see it, in both layouts (issue 21).

- PrusaSlicer (``prusa-slicer --info``) and Slic3r (``slic3r --info``) run here;
- lib3mf, the 3MF Consortium's library, reads in strict mode;
- Cura's parser libSavitar (Debian's ``python3-savitar``, for Debian's python3)
  parses the model as Cura's 3MF reader hands it over;
- Bambu Studio and OrcaSlicer have no command line here: the rule by which their
  ``Model::read_from_archive`` sends a file to their PrusaSlicer importer is
  checked on the package as their source states it (see
  :mod:`fabtiles.export.threemf`).
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
import shapely
from mesh_helpers import B, H
from real_programs import program, require, run, system_python_module

from fabtiles import DesignError, FabricationError, ParameterError, Star
from fabtiles import Tile as PublicTile
from fabtiles import __version__ as VERSION
from fabtiles.export import threemf
from fabtiles.pattern.packing import HexPacking

CORE = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"


def small_tile():
    return PublicTile("square", 40, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The relief tile in both layouts, and a deboss tile with its inlay in both."""
    out = tmp_path_factory.mktemp("3mf")
    tile = small_tile()
    paths = {}
    for layout in threemf.LAYOUTS:
        paths["relief", layout] = out / f"relief-{layout}.3mf"
        tile.export(paths["relief", layout], layout=layout)
        paths["inlay", layout] = out / f"inlay-{layout}.3mf"
        tile.export(paths["inlay", layout], style="deboss", inlay=True, layout=layout)
    return tile, paths


def package(path) -> dict:
    with zipfile.ZipFile(path) as zf:
        return {n: zf.read(n) for n in zf.namelist()}


# --------------------------------------------------------------------------- Bambu Studio / OrcaSlicer, by their source


def application(model: bytes) -> str:
    (meta,) = [m for m in ET.fromstring(model).findall(f"{CORE}metadata") if m.get("name") == "Application"]
    return meta.text


@pytest.mark.parametrize("kind", ["relief", "inlay"])
def test_volumes_layout_takes_the_prusaslicer_importer_of_bambu_and_orca(files, kind):
    pkg = package(files[1][kind, "volumes"])
    app = application(pkg["3D/3dmodel.model"])
    # check_3mf_from_prusa: no 3D/_rels/3dmodel.model.rels, and "PrusaSlicer" in the Application metadata
    assert "3D/_rels/3dmodel.model.rels" not in pkg
    assert "PrusaSlicer" in app
    # PrusaSlicer itself parses a version from "PrusaSlicer-..." (its own files): not ours
    assert not app.startswith("PrusaSlicer-")
    assert app == f"fabtiles {VERSION} (PrusaSlicer 3MF)"
    assert threemf.takes_prusa_path(pkg)
    model = ET.fromstring(pkg["3D/3dmodel.model"])
    (item,) = model.iter(f"{CORE}item")
    assert item.get("transform") is None  # identity: a lone instance's transform goes to the first volume only
    # the importer splits the one mesh by the volumes' triangle ranges and gives each its extruder
    config = ET.fromstring(pkg["Metadata/Slic3r_PE_model.config"])
    (obj,) = config.iter("object")
    assert obj.get("id") == item.get("objectid")
    volumes = [{m.get("key"): m.get("value") for m in v.iter("metadata")} for v in obj.iter("volume")]
    names = ["base", "pattern"] if kind == "relief" else ["plate", "inlay"]
    assert [(v["name"], v["extruder"], v["volume_type"]) for v in volumes] == [
        (names[0], "1", "ModelPart"),
        (names[1], "2", "ModelPart"),
    ]


@pytest.mark.parametrize("kind", ["relief", "inlay"])
def test_components_layout_takes_their_own_importer(files, kind):
    pkg = package(files[1][kind, "components"])
    assert application(pkg["3D/3dmodel.model"]) == f"fabtiles {VERSION}"
    assert not threemf.takes_prusa_path(pkg)
    assert "Metadata/Slic3r_PE_model.config" not in pkg
    model = ET.fromstring(pkg["3D/3dmodel.model"])
    objects = {o.get("id"): o for o in model.iter(f"{CORE}object")}
    (item,) = model.iter(f"{CORE}item")
    assembly = objects[item.get("objectid")]
    ids = [c.get("objectid") for c in assembly.iter(f"{CORE}component")]
    assert len(ids) == 2 and assembly.find(f"{CORE}mesh") is None
    assert all(c.get("transform") is None and c.get("path") is None for c in assembly.iter(f"{CORE}component"))
    # model_settings.config: the assembly by its id, each part by its mesh object's id, named, with its filament
    (obj,) = ET.fromstring(pkg["Metadata/model_settings.config"]).iter("object")
    assert obj.get("id") == item.get("objectid")
    parts = {p.get("id"): {m.get("key"): m.get("value") for m in p.iter("metadata")} for p in obj.iter("part")}
    assert list(parts) == ids
    names = ["base", "pattern"] if kind == "relief" else ["plate", "inlay"]
    assert [(parts[i]["name"], parts[i]["extruder"]) for i in ids] == [(names[0], "1"), (names[1], "2")]
    assert [objects[i].get("name") for i in ids] == names


# --------------------------------------------------------------------------- lib3mf, strict


def lib3mf_read(path):
    """What lib3mf's strict reader makes of ``path``: warnings, unit, mesh objects, components, build items."""
    import importlib.util

    require(importlib.util.find_spec("lib3mf"), "lib3mf", 'pip install lib3mf (in the "test" extra)')
    import lib3mf

    wrapper = lib3mf.get_wrapper()
    model = wrapper.CreateModel()
    reader = model.QueryReader("3mf")
    reader.SetStrictModeActive(True)
    reader.ReadFromFile(str(path))
    warnings = [reader.GetWarning(i) for i in range(reader.GetWarningCount())]
    meshes, comps, items = {}, {}, []
    it = model.GetMeshObjects()
    while it.MoveNext():
        o = it.GetCurrentMeshObject()
        group = o.GetMetaDataGroup()
        meta = {
            (group.GetMetaData(i).GetNameSpace(), group.GetMetaData(i).GetName()): group.GetMetaData(i).GetValue()
            for i in range(group.GetMetaDataCount())
        }
        meshes[o.GetResourceID()] = (o.GetName(), o.GetTriangleCount(), o.IsManifoldAndOriented(), meta)
    it = model.GetComponentsObjects()
    while it.MoveNext():
        o = it.GetCurrentComponentsObject()
        comps[o.GetResourceID()] = [o.GetComponent(i).GetObjectResourceID() for i in range(o.GetComponentCount())]
    it = model.GetBuildItems()
    while it.MoveNext():
        items.append(it.GetCurrent().GetObjectResourceID())
    return dict(
        warnings=warnings,
        unit=model.GetUnit(),
        mm=lib3mf.ModelUnit.MilliMeter,
        meshes=meshes,
        components=comps,
        items=items,
    )


@pytest.mark.parametrize("layout", threemf.LAYOUTS)
@pytest.mark.parametrize("kind", ["relief", "inlay"])
def test_lib3mf_strict_reads_both_layouts_without_a_warning(files, layout, kind):
    got = lib3mf_read(files[1][kind, layout])
    assert got["warnings"] == []
    assert got["unit"] == got["mm"]
    assert all(manifold for _, _, manifold, _ in got["meshes"].values())
    written = threemf.read_3mf(files[1][kind, layout])
    if layout == "volumes":
        assert got["components"] == {} and len(got["meshes"]) == 1 and len(got["items"]) == 1
        (tris,) = [t for _, t, _, _ in got["meshes"].values()]
        assert tris == sum(len(p.faces) for p in written.values())
    else:
        ((assembly, ids),) = got["components"].items()
        assert got["items"] == [assembly]
        cura = "http://software.ultimaker.com/xml/cura/3mf/2015/10"
        assert [(got["meshes"][i][0], got["meshes"][i][1], got["meshes"][i][3][cura, "extruder_nr"]) for i in ids] == [
            (n, len(p.faces), str(p.extruder - 1)) for n, p in written.items()
        ]


# --------------------------------------------------------------------------- Cura's parser, libSavitar

SAVITAR = """
import json, sys, zipfile, Savitar
# as Cura's ThreeMFReader: the model file of the package, parsed by libSavitar
scene = Savitar.ThreeMFParser().parse(zipfile.ZipFile(sys.argv[1]).read("3D/3dmodel.model"))
def node(n):
    mesh = n.getMeshData()
    return dict(name=n.getName(), settings={k: v.value for k, v in n.getSettings().items()},
                vertices=len(mesh.getVerticesAsBytes()) // 12, faces=len(mesh.getFacesAsBytes()) // 12,
                children=[node(c) for c in n.getChildren()])
print(json.dumps(dict(unit=scene.getUnit(), nodes=[node(n) for n in scene.getSceneNodes()])))
"""


def savitar(path) -> dict:
    python = system_python_module("Savitar", "apt-get install python3-savitar")
    return json.loads(run([python, "-c", SAVITAR, path]).stdout)


@pytest.mark.parametrize("kind", ["relief", "inlay"])
def test_cura_sees_the_components_layout_as_one_group_of_parts_with_their_extruders(files, kind):
    got = savitar(files[1][kind, "components"])
    assert got["unit"] == "millimeter"
    (group,) = got["nodes"]
    assert group["faces"] == 0  # the group holds no mesh of its own
    written = threemf.read_3mf(files[1][kind, "components"])
    assert [(c["name"], c["settings"], c["faces"], c["children"]) for c in group["children"]] == [
        (n, {"extruder_nr": str(p.extruder - 1)}, len(p.faces), []) for n, p in written.items()
    ]
    assert [c["settings"]["extruder_nr"] for c in group["children"]] == ["0", "1"]


def test_cura_sees_the_volumes_layout_as_one_mesh(files):
    (node,) = savitar(files[1]["relief", "volumes"])["nodes"]
    assert node["children"] == [] and node["settings"] == {}
    assert node["faces"] == sum(len(p.faces) for p in threemf.read_3mf(files[1]["relief", "volumes"]).values())


# --------------------------------------------------------------------------- PrusaSlicer and Slic3r


def info(cmd, path, tmp_path) -> list[dict]:
    """``--info``: one dict per object the program loaded."""
    objects = []
    for line in run([*cmd, "--info", path], cwd=tmp_path).stdout.splitlines():
        if re.fullmatch(r"\[.*\]", line.strip()):
            objects.append({})
        elif "=" in line and objects:
            key, value = (s.strip() for s in line.split("=", 1))
            objects[-1][key] = value
    return objects


def test_prusaslicer_opens_the_components_layout_as_one_object_per_part(files, tmp_path):
    prusa = program("prusa-slicer", "apt-get install prusa-slicer")
    _tile, paths = files
    base, pattern = info(
        [prusa, "--loglevel", "1", "--datadir", tmp_path / "data"], paths["relief", "components"], tmp_path
    )
    assert (float(base["min_z"]), float(base["max_z"])) == pytest.approx((0, B), abs=1e-5)
    assert (float(pattern["min_z"]), float(pattern["max_z"])) == pytest.approx((B, B + H), abs=1e-5)


@pytest.mark.parametrize("layout", threemf.LAYOUTS)
def test_slic3r_reads_one_object_of_two_parts(files, tmp_path, layout):
    slic3r = program("slic3r", "apt-get install slic3r")
    tile, paths = files
    region, outline = tile.region(), tile.outline_shape()
    (obj,) = info([slic3r], paths["relief", layout], tmp_path)
    assert len(shapely.get_parts(region)) == 1
    assert int(obj["number_of_parts"]) == 2  # base and pattern, each closed
    assert obj["manifold"] == "yes"
    assert float(obj["max_z"]) == pytest.approx(B + H, abs=1e-5)
    assert float(obj["volume"]) == pytest.approx(outline.area * B + region.area * H, rel=0.005)
    (inlay,) = info([slic3r], paths["inlay", layout], tmp_path)
    assert float(inlay["max_z"]) == pytest.approx(B, abs=1e-5)
    assert float(inlay["volume"]) == pytest.approx(outline.area * B, rel=0.005)


# --------------------------------------------------------------------------- the layout, from every front end


def test_both_layouts_hold_the_same_parts(files):
    _, paths = files
    for kind in ("relief", "inlay"):
        volumes, components = (threemf.read_3mf(paths[kind, layout]) for layout in threemf.LAYOUTS)
        assert list(volumes) == list(components)
        for n in volumes:
            assert volumes[n].extruder == components[n].extruder
            assert np.array_equal(volumes[n].vertices, components[n].vertices)
            assert np.array_equal(volumes[n].faces, components[n].faces)


def test_the_design_key_picks_the_layout(tmp_path):
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making import build_design

    text = (
        '[motif]\npreset = "table3-3"\n[packing]\nradius = 10\n[tile]\noutline = "square"\nsize = 40\n'
        'frame = 3\n[output]\nformats = ["3mf"]\nthreemf_layout = "components"\n'
    )
    build_design(design_from_text(text, name="t"), tmp_path)
    pkg = package(tmp_path / "t.3mf")
    assert "Metadata/Slic3r_PE_model.config" not in pkg and b"<components>" in pkg["3D/3dmodel.model"]
    build_design(design_from_text(text.replace('"components"', '"volumes"'), name="v"), tmp_path)
    assert "Metadata/Slic3r_PE_model.config" in package(tmp_path / "v.3mf")


def test_a_bad_layout_names_the_valid_ones(tmp_path):
    from fabtiles.designs.design_file import design_from_text

    text = (
        '[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsize = 40\n[output]\nthreemf_layout = "assembly"\n'
    )
    with pytest.raises(
        DesignError,
        match=r"\[output\] threemf_layout = 'assembly' is not valid, must be one of: "
        r"volumes, components",
    ):
        design_from_text(text)
    with pytest.raises(
        ParameterError,
        match=r"layout='assembly' is not a valid 3MF layout, must be one of: "
        r"volumes, components",
    ):
        small_tile().export(tmp_path / "t.3mf", layout="assembly")
    with pytest.raises(ParameterError, match=r"layout='assembly' is not a valid 3MF layout"):
        threemf.package_3mf([], name="t", layout="assembly")
    with pytest.raises(ParameterError, match=r"'layout' is not a valid option for .stl files"):
        small_tile().export(tmp_path / "t.stl", layout="components")
    assert list(tmp_path.iterdir()) == []


def test_cli_refuses_a_bad_layout_with_one_line_and_no_file(tmp_path):
    from click.testing import CliRunner

    from fabtiles.cli.main import cli

    design = tmp_path / "d.toml"
    design.write_text(
        '[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsize = 40\n[output]\nformats = ["3mf"]\n'
    )
    result = CliRunner().invoke(
        cli,
        ["build", str(design), "-o", str(tmp_path / "out"), "--set", "output.threemf_layout=groups"],
        catch_exceptions=False,
    )
    assert result.exit_code == 2
    assert result.output.startswith("fabtiles: error: ") and result.output.count("\n") == 1
    assert "threemf_layout = 'groups' is not valid, must be one of: volumes, components" in result.output
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    "old,new,msg",
    [
        (b'<item objectid="3"', b'<item objectid="9"', r"has no build item naming one of its objects"),
        (b'<component objectid="2"', b'<component objectid="7"', r"components \[1, 7\] are not objects of the model"),
        (
            b'<triangle v1="0"',
            b'<triangle v1="99999"',
            r"the 3MF object 'base' has triangles indexing past its 8 vertices",
        ),
    ],
)
def test_read_3mf_refuses_a_broken_components_model(files, tmp_path, old, new, msg):
    pkg = package(files[1]["relief", "components"])
    assert old in pkg["3D/3dmodel.model"]
    pkg["3D/3dmodel.model"] = pkg["3D/3dmodel.model"].replace(old, new, 1)
    bad = tmp_path / "bad.3mf"
    with zipfile.ZipFile(bad, "w") as zf:
        for n, data in pkg.items():
            zf.writestr(n, data)
    with pytest.raises(FabricationError, match=msg):
        threemf.read_3mf(bad)
