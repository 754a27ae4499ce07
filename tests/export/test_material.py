"""Material and cost of every design (issue 25, its material part): checked against the files read back."""

from __future__ import annotations

import csv
import math
import re
from dataclasses import replace

import pytest
import trimesh
from click.testing import CliRunner

from fabtiles import HexPacking, ProfileError, Star, Tile
from fabtiles.cli.main import cli
from fabtiles.export import threemf
from fabtiles.machines.profiles import load_profile

FDM = load_profile("fdm-0.4mm")
PLY = load_profile("laser-3mm-plywood")
LINE = re.compile(r"print material: ([0-9.]+) g of filament, ([0-9.]+) m")


def tile():
    return Tile("square", 50, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0)


def test_stl_filament_is_the_mesh_read_back_at_the_profiles_density(tmp_path):
    report = tile().export(tmp_path / "t.stl")
    volume = trimesh.load(tmp_path / "t.stl").volume  # mm^3
    m = report.stats["material"]
    assert m["mass_g"] == pytest.approx(volume / 1000 * 1.24, rel=1e-4)
    assert m["length_m"] == pytest.approx(volume / (math.pi * 0.875**2) / 1000, rel=1e-4)
    assert m["cost"] is None  # no price in the profile: no cost


def test_3mf_filament_per_part(tmp_path):
    report = tile().export(tmp_path / "t.3mf", profile=replace(FDM, price_per_kg=25.0))
    parts = threemf.read_3mf(tmp_path / "t.3mf")
    m = report.stats["material"]
    for name, p in parts.items():
        volume = trimesh.Trimesh(p.vertices.astype(float), p.faces).volume
        assert m["parts"][name]["mass_g"] == pytest.approx(volume / 1000 * 1.24, rel=1e-3)
    assert m["cost"] == pytest.approx(m["mass_g"] / 1000 * 25.0, abs=5e-5)  # the cost is given to 4 decimals
    assert re.fullmatch(
        r"[0-9.]+ g of filament, [0-9.]+ m \(base [0-9.]+ g, pattern [0-9.]+ g\), cost [0-9.]+", m["line"]
    )


def test_a_laser_report_gives_its_sheet_and_cost(tmp_path):
    report = tile().export(tmp_path / "t.dxf", profile=replace(PLY, price_per_m2=30.0))
    s = report.stats["sheet"]
    assert s["sheet_m2"] == pytest.approx(50.0 * 50.0 / 1e6)
    assert s["cost"] == pytest.approx(s["sheet_m2"] * 30.0)


def test_build_and_check_print_the_filament(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(
        '[motif]\npreset = "table3-3"\n[packing]\nradius = 10\n[tile]\noutline = "square"\n'
        'size = 50\nframe = 3\n[output]\nformats = ["stl", "dxf"]\n'
    )
    built = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")], catch_exceptions=False)
    checked = CliRunner().invoke(cli, ["check", str(design)], catch_exceptions=False)
    (b,), (c,) = LINE.findall(built.output), LINE.findall(checked.output)
    # check computes it from the areas, without a mesh: within the mesh check's 0.5 %
    assert float(c[0]) == pytest.approx(float(b[0]), rel=0.01) and "print time: ask the slicer" in checked.output
    result = CliRunner().invoke(
        cli,
        ["sweep", str(design), "--vary", "packing.radius=8,12", "-o", str(tmp_path / "sweep"), "--jobs", "1"],
        catch_exceptions=False,
    )
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader((tmp_path / "sweep" / "index.csv").open()))
    assert all(float(r["filament_g"]) > 1 and float(r["filament_m"]) > 0.1 and float(r["sheet_m2"]) > 0 for r in rows)
    assert rows[0]["filament_cost"] == "" and rows[0]["sheet_cost"] == ""  # no prices, no cost


def test_the_web_app_gives_the_material():
    from asgi_client import TestClient

    from fabtiles.web.app import create_app

    data = TestClient(create_app()).get("/api/checks?preset=table3-3&width=50&radius=10&frame=3").json()
    assert data["material"]["mass_g"] > 1 and "g of filament" in data["material"]["line"]


@pytest.mark.parametrize(
    "text,msg",
    [
        ('kind = "printer"\n[printer]\nfilament_density_g_cm3 = 0\n', r"printer.filament_density_g_cm3 must be > 0"),
        ('kind = "printer"\n[printer]\nprice_per_kg = -1\n', r"printer.price_per_kg must be >= 0, got -1"),
        ('kind = "laser"\n[laser]\nprice_per_m2 = -2\n', r"laser.price_per_m2 must be >= 0, got -2"),
    ],
)
def test_bad_prices_and_densities(tmp_path, text, msg):
    p = tmp_path / "p.toml"
    p.write_text(text)
    with pytest.raises(ProfileError, match=msg):
        load_profile(p)
