"""Shaded engraving: each face class on a layer of its own power, read back by GEOS, MeerK40t, lbrnts and Inkscape."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from hypothesis import given
from hypothesis import strategies as st
from PIL import Image
from real_programs import program, run
from test_laser_programs import burns, meerk40t
from test_lbrn2 import lbrnts

from fabtiles import Colours, HexPacking, ParameterError, ProfileError, Star, Tile
from fabtiles.cli.main import cli
from fabtiles.geometry.faces import face_classes
from fabtiles.geometry.shades import MAX_SHADES, darkness, shade_layers, shade_power
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")
FILL = PLY.layers.engrave
SVG = "{http://www.w3.org/2000/svg}"
COLOURS = dict(by="shape", palette="zellige", shaded="all", shades={"B": {"power_pct": 40}})


def tile():
    return Tile("square", 40, HexPacking(10, Star.preset("table3-3")), frame=2, stroke=1.0)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    out = tmp_path_factory.mktemp("shades")
    t, paths, reports = tile(), {}, {}
    for mode, shaded in (("engrave", "all"), ("pierced", "B D")):
        colours = Colours(**{**COLOURS, "shaded": shaded})
        for fmt in ("dxf", "svg", "lbrn2"):
            paths[mode, fmt] = out / f"{mode}.{fmt}"
            reports[mode, fmt] = t.export(paths[mode, fmt], mode=mode, colours=colours)
    return t, paths, reports


def classes_of(t):
    return face_classes(t, by="shape")


def dxf_regions(path, offset) -> dict:
    """Layer -> the area its closed polylines fill, even-odd (GEOS), moved back into the tile's coordinates."""
    rings: dict = {}
    for e in ezdxf.readfile(path).modelspace():
        pts = np.array([p[:2] for p in e.get_points("xy")]) - offset
        rings.setdefault(e.dxf.layer, []).append(shapely.LinearRing(pts))
    return {k: shapely.build_area(shapely.GeometryCollection(v)) for k, v in rings.items()}


def svg_regions(path) -> dict:
    """Group id -> the area its filled paths cover (straight-edged paths, y flipped back)."""
    root = ET.parse(path).getroot()
    out = {}
    for g in root.iter("{http://www.w3.org/2000/svg}g"):
        if g.get("fill") in (None, "none"):
            continue
        polys = []
        for p in g.iter("{http://www.w3.org/2000/svg}path"):
            d = p.get("d")
            assert "A" not in d  # the faces of straight bands: no arcs
            rings = [
                shapely.LinearRing(np.array(re.findall(r"(-?[\d.]+) (-?[\d.]+)", sub), float))
                for sub in re.findall(r"M[^M]*", d)
            ]
            polys.append(shapely.build_area(shapely.GeometryCollection(rings)))
        area = shapely.union_all(polys)
        out[g.get("id")] = area
    return out


def test_each_engraved_class_is_its_faces_in_the_dxf_and_svg(files):
    import shapely.affinity

    t, paths, reports = files
    classes = classes_of(t)
    for mode, letters in (("engrave", [c.letter for c in classes.classes]), ("pierced", ["B", "D"])):
        offset = np.array(reports[mode, "dxf"].stats["file_offset_mm"])
        dxf = dxf_regions(paths[mode, "dxf"], offset)
        svg = {
            k: shapely.affinity.translate(shapely.affinity.scale(v, 1, -1, origin=(0, 0)), -offset[0], -offset[1])
            for k, v in svg_regions(paths[mode, "svg"]).items()
        }
        for letter in letters:
            faces = classes.of(letter)
            for got in (dxf[f"SHADE_{letter}"], svg[f"SHADE_{letter}"]):
                assert got.symmetric_difference(faces).area < 1e-4 * faces.area + 1e-3
        shaded = [k for k in dxf if k.startswith("SHADE_")]
        assert sorted(shaded) == [f"SHADE_{x}" for x in letters]


def test_the_pierced_cut_keeps_the_engraved_classes_and_cuts_the_others(files):
    t, paths, reports = files
    classes = classes_of(t)
    offset = np.array(reports["pierced", "dxf"].stats["file_offset_mm"])
    inner = [
        shapely.Polygon(np.array([p[:2] for p in e.get_points("xy")]) - offset)
        for e in ezdxf.readfile(paths["pierced", "dxf"]).modelspace()
        if e.dxf.layer == PLY.layers.inner_cut.name
    ]
    probes = shapely.point_on_surface(np.asarray(inner, dtype=object))
    for letter in ("B", "D"):  # no hole cut inside an engraved face
        assert not shapely.intersects(classes.of(letter).buffer(-0.2), probes).any()
    assert shapely.intersects(classes.of("A"), probes).any()  # a class not engraved is cut out


def test_the_job_time_counts_each_layer(files, tmp_path):
    _, _, reports = files
    stats = reports["engrave", "dxf"].stats
    fills = sum(s["area_mm2"] / s["line_interval_mm"] / s["speed_mm_s"] * s["passes"] for s in stats["shades"].values())
    plain = tile().export(tmp_path / "plain.dxf", mode="engrave").stats["job"]
    # the shaded job is the plain one (the bands' fill, the outline) and each class's fill at its own
    # speed and interval, and the head's travel between the faces
    assert stats["job"]["seconds"] - plain["seconds"] == pytest.approx(fills, rel=0.5)
    assert stats["job"]["seconds"] - plain["seconds"] > fills
    assert stats["job"]["engrave_area_mm2"] == pytest.approx(40 * 40, rel=1e-3)  # bands and every face


def test_darker_classes_burn_harder_and_overrides_win(files):
    t, _, reports = files
    shades = reports["engrave", "lbrn2"].stats["shades"]
    assert shades["SHADE_B"]["power_pct"] == 40.0
    colours = Colours(**COLOURS).colouring([c.letter for c in classes_of(t).classes])
    derived = [(darkness(colours.face(k).srgb), shades[f"SHADE_{k}"]["power_pct"]) for k in ("A", "C", "D")]
    derived.sort()
    assert [p for _, p in derived] == sorted(p for _, p in derived)
    low, high = FILL.shade_range_pct
    assert all(low <= p <= high for _, p in derived)


# --------------------------------------------------------------------------- the programs


def test_meerk40t_loads_the_project_with_an_engraving_per_class_at_its_power(files, tmp_path):
    _, paths, reports = files
    job = meerk40t(paths["engrave", "lbrn2"], tmp_path, listing="operations")
    ops = re.findall(r"\d+: Raster=\w+ ([0-9.]+)mm/s @([0-9.]+)", job["listing"])
    shades = reports["engrave", "lbrn2"].stats["shades"]
    want = [(FILL.speed_mm_s, FILL.power_pct * 10)] + [(s["speed_mm_s"], s["power_pct"] * 10) for s in shades.values()]
    assert [(float(s), float(p)) for s, p in ops] == want


def test_meerk40t_gives_each_class_of_the_dxf_its_own_engrave_operation(files, tmp_path):
    _, paths, _ = files
    job = meerk40t(paths["engrave", "dxf"], tmp_path)
    layers: dict = {}
    for e in ezdxf.readfile(paths["engrave", "dxf"]).modelspace():
        layers[e.dxf.layer] = layers.get(e.dxf.layer, 0) + 1
    want = [("engrave", n) for k, n in layers.items() if k != PLY.layers.outer_cut.name] + [("cut", 1)]
    assert job["ops"] == want


def svg_layers(path) -> dict:
    """Group id -> the ids of its paths, in the file's order."""
    root = ET.parse(path).getroot()
    return {g.get("id"): [p.get("id") for p in g.iter(f"{SVG}path")] for g in root.iter(f"{SVG}g")}


@pytest.mark.parametrize("mode", ["engrave", "pierced"])
def test_meerk40t_loads_the_svg_with_an_engraving_per_class_at_its_power(files, tmp_path, mode):
    _, paths, reports = files
    job = meerk40t(paths[mode, "svg"], tmp_path, listing="operations")
    layers = svg_layers(paths[mode, "svg"])
    assert job["added"] == sum(len(v) for v in layers.values())
    # MeerK40t makes the file's operations, in its order: each class's raster at its power (per mille)
    # and speed, the cuts after; each operation holds its layer's shapes, every shape in one
    listed = re.findall(r"\d+: (Raster|Cut)=?\w* ([0-9.]+)mm/s @([0-9.]+)", job["listing"])
    shades = reports[mode, "svg"].stats["shades"]
    want = [("Raster", s["speed_mm_s"], s["power_pct"] * 10) for s in shades.values()]
    if mode == "engrave":
        want = [("Raster", FILL.speed_mm_s, FILL.power_pct * 10), *want]
    cuts = [PLY.layers.outer_cut] if mode == "engrave" else [PLY.layers.inner_cut, PLY.layers.outer_cut]
    want += [("Cut", c.speed_mm_s, c.power_pct * 10) for c in cuts]
    assert [(k, float(s), float(p)) for k, s, p in listed] == want
    assert job["ops"] == [
        ("cut" if k == "Cut" else "raster", len(v)) for (k, *_), v in zip(want, layers.values(), strict=True)
    ]
    assert re.findall(r"\s0\.\d+\s+: op \w+ - (\S+)", job["listing"]) == list(layers)  # named by their layers
    # the G-code (headless MeerK40t has no renderer to raster with): every contour cut once at the cut
    # layers' power, the outline last, after the holes (its own operation, after the inner cuts')
    cut = burns(job["gcode"])
    assert len(cut) == sum(len(layers[c.name]) for c in cuts)
    assert set(re.findall(r"S([0-9.]+)", job["gcode"])) == {"0", f"{PLY.layers.outer_cut.power_pct * 10:g}"}
    extents = [np.ptp(b, axis=0).prod() for b in cut]
    assert extents[-1] == max(extents)


def test_meerk40t_runs_a_class_of_the_svg_as_many_passes_as_set(tmp_path):
    path = tmp_path / "passes.svg"
    colours = Colours(**{**COLOURS, "shaded": "B", "shades": {"B": {"power_pct": 40, "passes": 2}}})
    tile().export(path, mode="engrave", colours=colours)
    listing = meerk40t(path, tmp_path, listing="operations")["listing"]
    assert re.findall(r"\d+: (\dX )?Raster", listing) == ["", "2X "]


def test_inkscape_draws_the_svg_as_without_meerk40ts_operations(files, tmp_path):
    # the operations are elements of MeerK40t's namespace: a plain SVG reader draws nothing of them
    inkscape = program("inkscape", "apt-get install inkscape")
    _, paths, _ = files
    text = paths["engrave", "svg"].read_text()
    assert text.count("<meerk40t:operation ") == len(svg_layers(paths["engrave", "svg"]))
    bare = tmp_path / "bare.svg"
    bare.write_text(re.sub(r'<meerk40t:operation [^>]*/>\n| xmlns:meerk40t="[^"]*"', "", text))
    pixels = []
    for svg in (paths["engrave", "svg"], bare):
        png = tmp_path / f"{svg.stem}.png"
        run([inkscape, svg, "--export-type=png", f"--export-filename={png}", "--export-dpi=150"])
        pixels.append(np.asarray(Image.open(png).convert("RGBA")))
    assert pixels[0].shape == pixels[1].shape and (pixels[0] == pixels[1]).all()
    queried = {row.split(",")[0] for row in run([inkscape, "--query-all", paths["engrave", "svg"]]).stdout.splitlines()}
    assert {k for k in svg_layers(paths["engrave", "svg"]) if k.startswith("SHADE_")} <= queried


def test_lbrnts_reads_a_layer_per_class_with_its_settings(files):
    _, paths, reports = files
    (got,) = lbrnts(paths["engrave", "lbrn2"])
    shades = reports["engrave", "lbrn2"].stats["shades"]
    scans = [
        (c["name"], c["type"], c["maxPower"], c["speed"], c["interval"]) for c in got["cuts"] if c["type"] == "Scan"
    ]
    assert scans == [("FILL", "Scan", FILL.power_pct, FILL.speed_mm_s, FILL.line_interval_mm)] + [
        (k, "Scan", s["power_pct"], s["speed_mm_s"], s["line_interval_mm"]) for k, s in shades.items()
    ]
    index = {c["name"]: c["index"] for c in got["cuts"]}
    counts = {k: sum(1 for s in got["shapes"] if s["cutIndex"] == index[k]) for k in shades}
    svg = paths["engrave", "svg"].read_text()
    for k, n in counts.items():  # each class's shapes on its layer: its rings, as many as the DXF's
        assert n == sum(1 for e in ezdxf.readfile(paths["engrave", "dxf"]).modelspace() if e.dxf.layer == k)
        assert f'id="{k}"' in svg


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "colours,msg",
    [
        (
            dict(shades={"B": {"power_pct": 120}}),
            r"colour.shades.B.power_pct must be a percentage > 0 and <= 100, got 120",
        ),
        (dict(shades={"B": {"power_pct": 0}}), r"colour.shades.B.power_pct must be a percentage > 0 and <= 100, got 0"),
        (dict(shades={"B": {"speed_mm_s": -1}}), r"colour.shades.B.speed_mm_s must be a number > 0, got -1"),
        (dict(shades={"B": {"passes": 0}}), r"colour.shades.B.passes must be a whole number >= 1, got 0"),
        (dict(shades={"B": {"power": 10}}), r"\[colour.shades.B\] has an unknown key 'power'"),
        (dict(shades={"B": 10}), r"\[colour.shades.B\] must be a table"),
        (
            dict(shaded="A", shades={"C": {"power_pct": 10}}),
            r"\[colour.shades\] C is not an engraved face class \(engraved: A\)",
        ),
        (dict(shaded="Z"), r"\[colour\] shaded names face class 'Z', which this design has not"),
    ],
)
def test_bad_shades_are_refused_naming_the_value(colours, msg, tmp_path):
    with pytest.raises(ParameterError, match=msg):
        tile().export(tmp_path / "t.dxf", mode="engrave", colours=Colours(**{**COLOURS, **colours}))
    assert not (tmp_path / "t.dxf").exists()


def test_a_design_with_no_faces_has_no_class_to_shade(tmp_path):
    # bands wider than the packing's gaps cover the whole tile: no face, so no class A or B to engrave
    import fabtiles as ft

    covered = ft.Tile("circle", 60, ft.SquarePacking(radius=9, motif=ft.Star.preset("table1-part1")), stroke=6.5)
    with pytest.raises(ParameterError, match=r"shaded = 'B' names face classes, and this design has no faces"):
        covered.export(tmp_path / "t.dxf", mode="engrave", colours=Colours(**{**COLOURS, "shaded": "B"}))
    assert not (tmp_path / "t.dxf").exists()


def test_a_bad_spelling_or_letter_key_is_refused_at_once():
    with pytest.raises(
        ParameterError, match=r'\[colour\] shaded must be class letters \("A C"\) or "all", got \'A-B\''
    ):
        Colours(shaded="A-B")
    with pytest.raises(ParameterError, match=r"key 'b' must be a class letter"):
        Colours(shades={"b": {"power_pct": 10}})


def test_more_classes_than_layers_are_refused():
    with pytest.raises(ParameterError, match=rf"names {MAX_SHADES + 1} face classes, more than the {MAX_SHADES}"):
        shade_layers(PLY, [(f"A{k}", (0.5, 0.5, 0.5)) for k in range(MAX_SHADES + 1)])


def test_a_kit_or_a_sheet_is_not_shaded(tmp_path):
    with pytest.raises(ParameterError, match=r"shades one tile's faces, not an inlay kit"):
        tile().export(tmp_path / "t.dxf", mode="inlay", colours=Colours(**COLOURS))


def test_a_profile_without_an_engrave_layer_cannot_shade():
    bare = load_profile("laser-3mm-plywood").__class__(name="bare")
    with pytest.raises(ProfileError, match="has no engrave layer"):
        shade_layers(bare, [("A", (0.0, 0.0, 0.0))])


@pytest.mark.parametrize("span", ["[30, 10]", "[0, 10]", "[10]", "[10, 101]"])
def test_a_bad_power_range_is_refused(tmp_path, span):
    path = tmp_path / "p.toml"
    path.write_text(
        f'kind = "laser"\n[layers]\nengrave = {{ name = "FILL", color = 6, power_pct = 20, '
        f"line_interval_mm = 0.1, power_range_pct = {span} }}\n"
    )
    with pytest.raises(ProfileError, match=r"layers.engrave.power_range_pct must be \[lightest, darkest\]"):
        load_profile(path)


def test_the_power_range_of_the_profile_spreads_the_classes(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text(
        'kind = "laser"\n[layers]\nengrave = { name = "FILL", color = 6, power_pct = 20, '
        "line_interval_mm = 0.1, power_range_pct = [10, 60] }\n"
    )
    layers = shade_layers(load_profile(path), [("A", (0.0, 0.0, 0.0)), ("B", (1.0, 1.0, 1.0))])
    assert [layer.power_pct for _, layer in layers] == [60.0, 10.0]


DESIGN = """[motif]
preset = "table3-3"
[packing]
kind = "hex"
radius = 10
[tile]
outline = "square"
size = 40
frame = 2
stroke = 1.0
[output]
laser_mode = "engrave"
formats = ["dxf"]
[colour]
by = "shape"
shaded = "all"
[colour.shades]
{shades}
"""


def test_cli_a_power_out_of_range_exits_2_and_writes_nothing(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.format(shades="B = { power_pct = 150 }"))
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert (
        result.exit_code == 2
        and "colour.shades.B.power_pct must be a percentage > 0 and <= 100, got 150" in result.output
    )
    assert result.output.count("\n") == 1 and not (tmp_path / "out").exists()


def test_cli_shades_not_a_table_exits_2(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.format(shades="").replace("[colour.shades]\n", 'shades = "dark"\n'))
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 2 and "[colour.shades] must be a table of class letters" in result.output
    assert not (tmp_path / "out").exists()


def test_cli_a_bad_shades_letter_exits_2(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.format(shades="b = { power_pct = 10 }"))
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 2 and "key 'b' must be a class letter" in result.output


def test_the_score_mode_scores_the_lines_and_shades_the_classes(tmp_path):
    report = tile().export(
        tmp_path / "s.dxf", mode="score", colours=Colours(**{**COLOURS, "shaded": "A", "shades": {}})
    )
    layers = {e.dxf.layer for e in ezdxf.readfile(tmp_path / "s.dxf").modelspace()}
    assert layers == {PLY.layers.score.name, "SHADE_A", PLY.layers.outer_cut.name}
    assert list(report.stats["shades"]) == ["SHADE_A"]


def test_cli_a_sheet_is_not_shaded(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(DESIGN.format(shades=""))
    result = CliRunner().invoke(
        cli, ["build", str(design), "-o", str(tmp_path / "out"), "--copies", "2"], catch_exceptions=False
    )
    assert result.exit_code == 2 and "shades one tile's faces, not a sheet of tiles" in result.output
    assert not (tmp_path / "out").exists()


def test_classes_of_one_colour_engrave_alike_and_the_summary_says_so(tmp_path):
    colours = Colours(by="shape", shaded="A B", faces={"A": "navy", "B": "navy"})
    report = tile().export(tmp_path / "t.lbrn2", mode="engrave", colours=colours)
    shades = report.stats["shades"]
    assert shades["SHADE_A"]["power_pct"] == shades["SHADE_B"]["power_pct"]
    assert any(n.startswith("classes A, B engrave alike") for n in report.stats["notes"])


@given(st.floats(0, 1), st.floats(0, 1), st.floats(1, 100), st.floats(1, 100))
def test_a_darker_colour_never_gets_less_power_and_stays_in_the_range(d1, d2, a, b):
    span = (min(a, b), max(a, b))
    p1, p2 = shade_power(min(d1, d2), span), shade_power(max(d1, d2), span)
    assert p1 <= p2
    assert round(span[0]) - 0.5 <= p1 and p2 <= round(span[1]) + 0.5


@given(st.tuples(st.floats(0, 1), st.floats(0, 1), st.floats(0, 1)), st.floats(0, 1))
def test_darkness_falls_as_any_channel_brightens(rgb, more):
    brighter = tuple(min(1.0, c + more) if k == 1 else c for k, c in enumerate(rgb))
    assert 0.0 <= darkness(brighter) <= darkness(rgb) + 1e-12 <= 1.0 + 1e-12
