"""The format table: its rows, what is read from them, and format plugins (entry points in ``fabtiles.formats``)."""

from __future__ import annotations

import dataclasses
import sys
import textwrap
import warnings
from pathlib import Path

import pytest
from asgi_client import TestClient
from click.testing import CliRunner

import fabtiles as ft
from fabtiles.cli.main import cli
from fabtiles.export.formats import BUILT_IN, FORMATS, design_formats, format_of, markdown_table, names_where

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "table3-3.toml"
SMALL = ["--set", "tile.size=40"]

# A format plugin as another package ships it: a module with a fabtiles.Format, and its entry point.
PLUGIN = '''
import fabtiles


def _write(plan, options):
    """Each path of the plan as G-code moves, layer by layer."""
    out = [f"; {options.name}: {plan.mode}, kerf {plan.kerf_mm} mm"]
    for layer in plan.layers:
        out.append(f"; layer {layer.layer.name}")
        for path in layer.paths:
            (x, y), rest = path[0], path[1:]
            out.append(f"G0 X{x:.3f} Y{y:.3f}")
            out += [f"G1 X{px:.3f} Y{py:.3f}" for px, py in rest]
    return ("\\n".join(out) + "\\n").encode()


GCODE = fabtiles.Format(
    name="gcode",
    family="cut",
    media_type="text/x-gcode",
    description="G-code moves of the cut plan",
    write=_write,
)
DXF_AGAIN = fabtiles.Format(
    name="dxf", family="cut", media_type="text/plain", description="a second DXF", write=_write
)
NOT_A_FORMAT = "gcode"
'''


def install(tmp_path, monkeypatch, entry_points: str, module: str = PLUGIN) -> None:
    """Install a plugin package into ``tmp_path`` (its module and dist-info) and put it on ``sys.path``."""
    site = tmp_path / "site"
    (site / "fabtiles_demo_plugin-0.1.dist-info").mkdir(parents=True)
    (site / "fabtiles_demo_plugin.py").write_text(module, encoding="utf-8")
    info = site / "fabtiles_demo_plugin-0.1.dist-info"
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: fabtiles-demo-plugin\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text("[fabtiles.formats]\n" + textwrap.dedent(entry_points))
    monkeypatch.syspath_prepend(str(site))
    monkeypatch.delitem(sys.modules, "fabtiles_demo_plugin", raising=False)  # another test's plugin module
    FORMATS.reload()


@pytest.fixture(autouse=True)
def _table_without_plugins():
    """Each test starts and leaves with the table looked up again (no plugin of another test)."""
    FORMATS.reload()
    yield
    FORMATS.reload()


@pytest.fixture
def gcode(tmp_path, monkeypatch):
    install(tmp_path, monkeypatch, "gcode = fabtiles_demo_plugin:GCODE\n")
    yield FORMATS["gcode"]
    monkeypatch.undo()  # off sys.path before the table is looked up again


# -- the rows --------------------------------------------------------------------------------------------------------
def test_a_row_is_a_frozen_keyword_only_dataclass_with_defaults():
    row = ft.Format(name="gcode", family="cut", media_type="text/x-gcode", description="moves", write=bytes)
    assert (row.suffix, row.label, row.title, row.options, row.cutters, row.offered) == (
        ".gcode",
        "GCODE",
        "a GCODE file",
        "cut",
        None,
        True,
    )
    assert row.figures(None, None) == {} and row.files is not None and row.read_back is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        row.name = "nc"  # type: ignore[misc]  # the test: a row cannot change
    with pytest.raises(TypeError):
        ft.Format("gcode", "cut", "text/x-gcode", "moves", bytes)  # type: ignore[misc]  # the test: keywords only
    assert not hasattr(row, "__dict__")  # slotted


def test_a_family_the_table_does_not_know_is_an_error():
    with pytest.raises(ft.ParameterError, match=r"^format 'txt': family must be one of: cut, print, pen, got 'paper'$"):
        ft.Format(name="txt", family="paper", media_type="text/plain", description="", write=bytes)


def test_a_pen_format_is_plots_not_a_builds():
    row = ft.Format(name="gpgl", family="pen", media_type="text/plain", description="", write=bytes, offered=True)
    assert not row.offered and row.options == ""


def test_one_cut_plan_is_written_in_the_dxf_version_of_its_file_options():
    from shapely.geometry import box

    from fabtiles.export.formats import FileOptions
    from fabtiles.geometry.cut_plan import CutOptions, plan_cut

    plate = box(0, 0, 30, 30)
    plan = plan_cut(plate.difference(box(10, 10, 20, 20)), plate, CutOptions.of(profile="laser-3mm-plywood"))
    dxf = FORMATS["dxf"]

    def version(data: bytes) -> str:
        lines = data.decode("ascii").splitlines()
        return lines[lines.index("$ACADVER") + 2]

    default, r12, r2018 = (dxf.write(plan, FileOptions(dxf_version=v)) for v in (None, "R12", "R2018"))
    assert (version(default), version(r12), version(r2018)) == ("AC1015", "AC1009", "AC1032")  # R2000: the profile's
    assert dxf.write(plan, FileOptions(dxf_version="R2000")) == default
    assert [dxf.figures(plan, FileOptions(dxf_version=v)) for v in (None, "R12")] == [
        {"dxf_version": "R2000"},
        {"dxf_version": "R12"},
    ]
    with pytest.raises(ft.ParameterError, match=r"^'R14' is not a valid dxf_version, must be one of: R12, R2000, "):
        FileOptions(dxf_version="R14")


def test_what_is_read_from_the_table():
    assert design_formats() == ("dxf", "svg", "lbrn2", "stl", "3mf", "step")
    assert names_where(nests=True) == ("dxf", "svg", "lbrn2")
    assert names_where(card=True) == ("dxf", "svg")
    assert [f.name for f in BUILT_IN if f.family == "pen"] == ["plot-svg", "hpgl"]
    assert [(f.name, f.cutters) for f in BUILT_IN if f.cutters is not None] == [("lbrn2", ("laser",))]
    assert [(f.name, f.limit) for f in BUILT_IN if f.limit is not None] == [("step", "max_step_segments")]
    assert [f.name for f in BUILT_IN if f.read_back is not None] == ["stl", "3mf", "step"]
    from fabtiles.core.schema import key

    assert key("output.formats").choice_values() == design_formats()


def test_each_kind_of_cutter_takes_the_formats_its_row_says():
    # a LightBurn project is for lasers; every kind writes DXF and SVG
    from fabtiles.machines.profiles import load_profile

    laser, router, waterjet = (
        load_profile(p) for p in ("laser-3mm-plywood", "router-6mm-mdf", "waterjet-1mm-aluminium")
    )
    FORMATS["lbrn2"].check_cutter(laser)
    FORMATS["dxf"].check_cutter(router)
    FORMATS["svg"].check_cutter(waterjet)
    with pytest.raises(
        ft.ParameterError,
        match=r"^a LightBurn project \(\.lbrn2\) is for lasers; waterjet profile "
        r"'waterjet-1mm-aluminium' writes \.dxf or \.svg for its CAM$",
    ):
        FORMATS["lbrn2"].check_cutter(waterjet)
    assert [n for n in design_formats() if FORMATS[n].family == "cut" and FORMATS[n].takes("router")] == ["dxf", "svg"]


def test_the_manuals_table_is_the_tables():
    """docs/architecture.md shows the format table as :func:`markdown_table` makes it."""
    assert markdown_table() in (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")


def test_format_of_a_pen_drawing_and_a_bad_suffix():
    assert format_of("a.hpgl", family="pen").name == "hpgl"
    with pytest.raises(
        ft.ParameterError, match=r"^'dxf' is not a valid output format .* must be one of: plot-svg, hpgl"
    ):
        format_of("a.dxf", family="pen")


# -- plugins ---------------------------------------------------------------------------------------------------------
def test_a_plugin_builds_with_its_format_from_the_command_line(gcode, tmp_path):
    assert gcode.name in design_formats() and gcode.family == "cut"
    result = CliRunner().invoke(
        cli, ["build", str(SAMPLE), *SMALL, "--format", "gcode", "--format", "dxf", "-o", str(tmp_path / "out")]
    )
    assert result.exit_code == 0, result.output
    text = (tmp_path / "out" / "table3-3.gcode").read_text()
    assert text.startswith("; table3-3: pierced, kerf") and "G1 X" in text
    assert (tmp_path / "out" / "table3-3.dxf").is_file()


def test_a_plugin_writes_from_the_api_and_a_design(gcode, tmp_path):
    tile = ft.Tile("square", 30, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-3")), frame=2)
    report = tile.export(tmp_path / "t.gcode", kerf_mm=0.1)
    assert report.format == "gcode" and "G0 X" in (tmp_path / "t.gcode").read_text()
    with pytest.raises(ft.ParameterError, match=r"'style' is not a valid option for .gcode files"):
        tile.export(tmp_path / "u.gcode", style="relief")
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.making import build_design

    design = design_from_text(
        '[motif]\npreset = "table3-1"\n[tile]\nsize = 30\n[output]\nformats = ["gcode"]\n', name="d"
    )
    result = build_design(design, tmp_path / "out")
    assert [Path(p).name for p in result.paths] == ["d.gcode"]


def test_the_web_app_offers_a_plugins_format(gcode):
    from fabtiles.web.app import create_app

    client = TestClient(create_app())
    formats = client.get("/api/schema").json()["formats"]
    assert [f["name"] for f in formats] == [*design_formats()]
    assert formats[-1] == dict(
        name="gcode",
        family="cut",
        suffix=".gcode",
        label="GCODE",
        media_type="text/x-gcode",
        description="G-code moves of the cut plan",
        cutters=None,
        nests=False,
    )
    r = client.get("/api/export/gcode?width=40&radius=10&frame=3")
    assert r.status_code == 200, r.text
    assert r.headers["content-type"].startswith("text/x-gcode") and r.content.startswith(b"; ")


def test_a_plugin_that_fails_to_load_is_one_warning_and_the_build_goes_on(tmp_path, monkeypatch):
    install(
        tmp_path,
        monkeypatch,
        "broken = fabtiles_demo_plugin:GCODE\n",
        module="raise ImportError('the demo plugin needs a library that is not installed')\n",
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("ignore")  # the build's own warnings (numpy's, shapely's) are not this test's
        warnings.filterwarnings("always", message="format plugin")  # every plugin warning, repeats too
        result = CliRunner().invoke(cli, ["build", str(SAMPLE), *SMALL, "--format", "svg", "-o", str(tmp_path / "out")])
        assert design_formats() == ("dxf", "svg", "lbrn2", "stl", "3mf", "step")  # asked again: no second warning
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "table3-3.svg").is_file()
    assert [str(w.message) for w in caught] == [
        "format plugin 'broken' (fabtiles_demo_plugin:GCODE) failed to load, left out: ImportError: "
        "the demo plugin needs a library that is not installed"
    ]


def test_a_plugin_may_not_take_a_built_in_name_or_be_no_format(tmp_path, monkeypatch):
    install(
        tmp_path,
        monkeypatch,
        "gcode = fabtiles_demo_plugin:GCODE\ngcode2 = fabtiles_demo_plugin:GCODE\n"
        "dxf2 = fabtiles_demo_plugin:DXF_AGAIN\nwrong = fabtiles_demo_plugin:NOT_A_FORMAT\n",
    )
    with pytest.warns(UserWarning) as caught:
        assert FORMATS["dxf"] is BUILT_IN[0]
    assert design_formats()[-1] == "gcode"
    assert sorted(str(w.message) for w in caught) == [
        "format plugin 'dxf2' (fabtiles_demo_plugin:DXF_AGAIN) names format 'dxf', which fabtiles writes itself; "
        "left out",
        "format plugin 'gcode2' (fabtiles_demo_plugin:GCODE) names format 'gcode', which fabtiles has from "
        "another plugin; left out",
        "format plugin 'wrong' (fabtiles_demo_plugin:NOT_A_FORMAT) is not a fabtiles.Format, left out: 'gcode'",
    ]
