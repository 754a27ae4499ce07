"""Engrave mode and kerf per axis (issue 23), checked with GEOS and the programs, not our own offsetting."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

import ezdxf
import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import Polygon, box
from test_laser_programs import meerk40t

from fabtiles import HexPacking, ParameterError, ProfileError, Star, Tile
from fabtiles.export.card import write_card
from fabtiles.geometry.contours import laser_contours, outline_contours
from fabtiles.machines.profiles import LaserLayers, load_profile

PLY = load_profile("laser-3mm-plywood")
ANISO = replace(PLY, kerf_x_mm=0.12, kerf_y_mm=0.3)


def tile(size=60):
    return Tile("square", size, HexPacking(10, Star.preset("table3-3")), frame=3, stroke=1.0)


def layer_rings(path) -> dict:
    out: dict = {}
    for e in ezdxf.readfile(path).modelspace():
        out.setdefault(e.dxf.layer, []).append((bool(e.closed), np.array([p[:2] for p in e.get_points("xy")])))
    return out


# --------------------------------------------------------------------------- engrave


def test_engrave_fills_the_bands_and_cuts_the_outline(tmp_path):
    t = tile()
    report = t.export(tmp_path / "e.dxf", mode="engrave")
    layers = layer_rings(tmp_path / "e.dxf")
    fill, outer = PLY.layers.engrave.name, PLY.layers.outer_cut.name
    assert set(layers) == {fill, outer} and len(layers[outer]) == 1
    assert all(closed for closed, _ in layers[fill])
    # the fill's rings, read back, moved back by the file's offset (half the outline's kerf: the file
    # lies in the positive quadrant) and filled even-odd by GEOS, are the tile's material
    assert report.stats["file_offset_mm"] == pytest.approx([PLY.kerf_mm / 2] * 2, abs=1e-9)
    rings = [shapely.LinearRing(v - PLY.kerf_mm / 2) for _, v in layers[fill]]
    filled = shapely.build_area(shapely.GeometryCollection(rings))  # even-odd: a ring in an odd number is a hole
    region = t.region()
    assert filled.symmetric_difference(region).area < 1e-6 * region.area
    assert len(rings) == len(shapely.get_rings(shapely.get_parts(region)))
    assert report.stats["job"]["engrave_area_mm2"] == pytest.approx(region.area, rel=1e-6)
    assert [f.code for f in report.findings] == []  # nothing falls out: no bridges, no loose parts


def test_engrave_svg_is_filled_even_odd_and_the_project_a_fill_layer(tmp_path):
    import re
    import xml.etree.ElementTree as ET

    t = tile()
    t.export(tmp_path / "e.svg", mode="engrave")
    t.export(tmp_path / "e.lbrn2", mode="engrave")
    ns = {"s": "http://www.w3.org/2000/svg"}
    groups = {g.get("id"): g for g in ET.parse(tmp_path / "e.svg").getroot().findall("s:g", ns)}
    fill = groups[PLY.layers.engrave.name]
    assert fill.get("fill") == "#FF00FF" and fill.get("fill-rule") == "evenodd" and fill.get("stroke") == "none"
    subpaths = sum(p.get("d").count("M") for p in fill.findall("s:path", ns))
    assert subpaths == len(shapely.get_rings(shapely.get_parts(t.region())))
    text = (tmp_path / "e.lbrn2").read_text()
    scan = re.search(r'<CutSetting type="Scan">(.*?)</CutSetting>', text, re.S).group(1)
    assert f'<name Value="{PLY.layers.engrave.name}"/>' in scan and '<interval Value="0.1"/>' in scan
    assert '<priority Value="0"/>' in scan  # the fill first, the outline last


def test_a_band_narrower_than_two_fill_lines_is_a_finding(tmp_path):
    plate = box(0, 0, 40, 40).difference(box(5, 5, 20, 35)).difference(box(20.15, 5, 35, 35))
    from model_files import write_cut

    report = write_cut(tmp_path / "t.dxf", region=plate, outline=box(0, 0, 40, 40), profile=PLY, mode="engrave")
    (finding,) = report.findings
    assert finding.code == "thin_fill" and finding.worst == pytest.approx(0.15, abs=0.01)
    assert "narrower than two fill lines (0.2 mm at line_interval_mm = 0.1" in finding.message


def test_engrave_needs_an_engrave_layer(tmp_path):
    bare = replace(
        PLY, layers=LaserLayers(inner_cut=PLY.layers.inner_cut, outer_cut=PLY.layers.outer_cut, score=PLY.layers.score)
    )
    with pytest.raises(
        ProfileError,
        match=r"has no engrave layer, which the engrave mode fills: add engrave = "
        r"\{ name = \"FILL\", color = 6",
    ):
        tile().export(tmp_path / "e.dxf", mode="engrave", profile=bare)
    assert list(tmp_path.iterdir()) == []


def test_cli_engrave_with_a_profile_without_the_layer_exits_2(tmp_path):
    from click.testing import CliRunner

    from fabtiles.cli.main import cli

    profile = tmp_path / "bare.toml"
    profile.write_text('kind = "laser"\n[laser]\nmode = "engrave"\n')
    design = tmp_path / "d.toml"
    design.write_text(
        f'[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsize = 40\n'
        f'[output]\nformats = ["dxf"]\nlaser_profile = "{profile}"\n'
    )
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 2 and "has no engrave layer" in result.output
    assert result.output.count("\n") == 1 and not (tmp_path / "out").exists()


def test_meerk40t_engraves_the_fill_and_cuts_the_outline(tmp_path):
    t = tile()
    t.export(tmp_path / "e.dxf", mode="engrave")
    job = meerk40t(tmp_path / "e.dxf", tmp_path)
    kinds: dict = {}
    for kind, refs in job["ops"]:
        kinds[kind] = kinds.get(kind, 0) + refs
    fills = len(layer_rings(tmp_path / "e.dxf")[PLY.layers.engrave.name])
    assert kinds == {"engrave": fills, "cut": 1}


# --------------------------------------------------------------------------- kerf per axis


def support(points: np.ndarray, normal: np.ndarray) -> float:
    return float((points @ normal).max())


def ellipse_support(normal, kx, ky) -> float:
    """How far the cut edge stands off along ``normal``: the support of the ellipse of half-kerfs."""
    return math.hypot(kx / 2 * normal[0], ky / 2 * normal[1])


@settings(max_examples=40)
@given(st.integers(3, 9), st.floats(0, 360), st.one_of(st.just(0.0), st.floats(0.01, 0.4)), st.floats(0.05, 0.4))
def test_an_edge_moves_by_the_kerf_across_it(n, turn, kx, ky):
    """Every edge of a convex part moves out by the ellipse's support along its normal (corners mitred)."""
    t = np.radians(turn) + 2 * np.pi * np.arange(n) / n
    part = Polygon(np.c_[20 * np.cos(t), 20 * np.sin(t)])
    if kx == 0:
        with pytest.raises(ParameterError, match="kerf_x_mm and kerf_y_mm must both be > 0 or both equal"):
            laser_contours(part, kerf_mm=kx, kerf_y_mm=ky)
        return
    _, (ring,) = laser_contours(part, kerf_mm=kx, kerf_y_mm=ky)
    pts = np.asarray(part.exterior.coords)
    for a, b in itertools.pairwise(pts):
        edge = b - a
        normal = np.array([edge[1], -edge[0]]) / np.hypot(*edge)  # outward: the ring runs counter-clockwise
        assert support(ring, normal) == pytest.approx(support(pts, normal) + ellipse_support(normal, kx, ky), abs=2e-6)


def test_the_gauge_measures_nominal_plus_and_minus_half_the_kerf_on_each_axis(tmp_path):
    report = write_card(tmp_path / "card.dxf", ANISO)
    assert report.stats["kerf_mm"] == ANISO.kerf_x_mm
    layers = layer_rings(tmp_path / "card.dxf")
    squares = []
    for _, v in layers[PLY.layers.inner_cut.name] + layers[PLY.layers.outer_cut.name]:
        w, h = np.ptp(v, axis=0)
        if len(v) == 4 and 19 < w < 21 and 19 < h < 21:
            squares.append((w, h))
    part, hole = max(squares), min(squares)
    kx, ky = ANISO.kerf_x_mm, ANISO.kerf_y_mm
    assert part == pytest.approx((20 + kx, 20 + ky), abs=1e-6)
    assert hole == pytest.approx((20 - kx, 20 - ky), abs=1e-6)


def test_a_tile_and_its_outline_take_the_kerf_of_each_axis(tmp_path):
    t = tile()
    for mode in ("pierced", "score"):
        report = t.export(tmp_path / f"{mode}.dxf", profile=ANISO, mode=mode)
        ((_, outline),) = layer_rings(tmp_path / f"{mode}.dxf")[PLY.layers.outer_cut.name]
        assert np.ptp(outline, axis=0) == pytest.approx([60 + ANISO.kerf_x_mm, 60 + ANISO.kerf_y_mm], abs=1e-6)
        assert (report.stats["kerf_mm"], report.stats["kerf_y_mm"]) == (ANISO.kerf_x_mm, ANISO.kerf_y_mm)
    assert outline_contours(box(0, 0, 1, 1), kerf_mm=0.2, kerf_y_mm=0.4)[0].min(axis=0).tolist() == [-0.1, -0.2]
