"""A plot's pens and hatch fills: the layers vpype reads, the ink inside the faces, the spacing,
the pen-up travel against vpype's ``linesort --two-opt``, bad input."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from test_plot import vpype_linesort_travels

from fabtiles import ParameterError
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import load_design
from fabtiles.making.models import BuildOptions, Models
from fabtiles.making.pipeline import prepare_tile
from fabtiles.making.plot import ANGLES_DEG, plot_drawing

ROOT = Path(__file__).resolve().parents[2]
MOSAIC = ROOT / "samples" / "mosaic-iznik.toml"
SMALL = ["tile.size=40"]
PEN = 0.4


@pytest.fixture(scope="module")
def small():
    """The mosaic sample at 40 mm: its design, its drawing filled and cross-hatched, its tile's classes."""
    design = load_design(MOSAIC, overrides=SMALL)
    drawing = plot_drawing(design, fill=True, pen_mm=PEN, cross=True)
    models = Models(prepare_tile(design), BuildOptions.of_design(design))
    return design, drawing, models


def letters_of(name: str) -> list:
    """The class letters a layer's name lists: ``"cobalt (A, C)"`` -> ``["A", "C"]``."""
    inside = re.search(r"\((.*)\)$", name).group(1)
    return [w for w in inside.split(", ") if re.fullmatch(r"[A-Z]{1,2}", w)]


def test_a_layer_per_pen_named_and_coloured_as_vpype_reads_them(tmp_path):
    vp = pytest.importorskip("vpype")
    out = tmp_path / "filled.svg"
    res = CliRunner().invoke(cli, ["plot", str(MOSAIC), "-o", str(out), "--fill", "--pen", str(PEN), "--set", SMALL[0]])
    assert res.exit_code == 0, res.output
    assert "not hatched (no line fits in the faces, narrower than the 0.4 mm pen or the spacing): class" in res.output
    doc = vp.read_multilayer_svg(str(out), quantization=0.01)
    design = load_design(MOSAIC, overrides=SMALL)
    models = Models(prepare_tile(design), BuildOptions.of_design(design))
    colouring = models.colouring
    layers = {lay.property(vp.METADATA_FIELD_NAME): lay for lay in doc.layers.values()}
    band = colouring.band
    assert f"{band.name} (strands, outline)" in layers
    assert layers[f"{band.name} (strands, outline)"].property(vp.METADATA_FIELD_COLOR) == vp.Color(band.hex)
    hatched = [name for name in layers if letters_of(name)]
    assert hatched  # the classes wide enough for the pen
    colours = [layer.property(vp.METADATA_FIELD_COLOR) for layer in layers.values()]
    assert len(set(map(str, colours))) == len(colours)  # one layer per pen
    for name in hatched:
        colour = colouring.face(letters_of(name)[0])
        assert name.startswith(colour.name + " (")
        assert layers[name].property(vp.METADATA_FIELD_COLOR) == vp.Color(colour.hex)
        assert layers[name].property(vp.METADATA_FIELD_PEN_WIDTH) == pytest.approx(PEN * 96 / 25.4, rel=1e-6)


def test_ink_stays_inside_its_class_faces_and_off_the_bands(small):
    """Each hatch stroke's ink (the stroke swept by the pen's disc) lies in its class's faces, which
    are the outline minus the bands, and crosses no band (GEOS, 1 micron of tolerance)."""
    _, drawing, models = small
    classes = models.face_classes
    bands = shapely.buffer(models.tile.region(), -1e-3)
    for layer in drawing.layers:
        letters = letters_of(layer.name)
        if not letters:
            continue
        faces = shapely.union_all([classes.of(letter) for letter in letters]).buffer(1e-3)
        ink = shapely.buffer(shapely.linestrings(np.array(layer.paths)), PEN / 2, quad_segs=4)
        assert shapely.covers(faces, ink).all(), layer.name
        assert not shapely.intersects(bands, shapely.linestrings(np.array(layer.paths))).any()


def test_the_spacing_is_the_one_asked_for():
    """The strokes of a class lie on lines ``hatch_mm`` apart at the class's angle: neighbouring
    lines through one face differ by the spacing exactly."""
    design = load_design(MOSAIC, overrides=SMALL)
    for hatch_mm in (0.35, 0.8):
        drawing = plot_drawing(design, fill=True, pen_mm=0.3, hatch_mm=hatch_mm, angles_deg={"B": 20.0})
        layer = next(layer for layer in drawing.layers if letters_of(layer.name) == ["B"])
        seg = np.array(layer.paths)
        t = math.radians(20.0)
        d = seg[:, 1] - seg[:, 0]
        assert np.allclose(d[:, 0] * math.sin(t) - d[:, 1] * math.cos(t), 0, atol=1e-9)  # along 20 degrees
        v = np.unique(np.round(seg[:, 0] @ np.array([-math.sin(t), math.cos(t)]), 6))
        steps = np.diff(v)
        assert steps.min() == pytest.approx(hatch_mm, abs=1e-6)
        assert np.allclose(steps / hatch_mm, np.round(steps / hatch_mm), atol=1e-5)


def test_default_spacing_is_the_pen_and_angles_differ_by_class(small):
    _, drawing, models = small
    fill = drawing.stats["fill"]
    assert fill["hatch_mm"] == PEN and fill["cross"] is True
    letters = [c.letter for c in models.face_classes.classes]
    assert list(fill["angles_deg"].values()) == list(ANGLES_DEG[: len(letters)])
    hatched = {x for layer in drawing.layers for x in letters_of(layer.name)}
    assert set(fill["not_hatched"]) == set(letters) - hatched and fill["not_hatched"]  # the kites, under the pen


def test_angles_override_by_class_and_for_all():
    design = load_design(MOSAIC, overrides=SMALL)
    every = plot_drawing(design, fill=True, angles_deg=30).stats["fill"]["angles_deg"]
    assert set(every.values()) == {30.0}
    one = plot_drawing(design, fill=True, angles_deg={"": 10, "B": 60}).stats["fill"]["angles_deg"]
    assert one["B"] == 60.0 and one["A"] == 10.0


@pytest.mark.parametrize("size, cross", [(40, False), (40, True), (100, False)])
def test_pen_up_travel_at_most_vpypes_linesort_two_opt(size, cross):
    """Each layer's pen-up travel from the origin, against vpype's ``linesort --two-opt`` on the same
    lines, given in our order (as ``vpype read`` of our SVG has them) and in the reverse order. The
    100 mm tile's cobalt layer (2,746 strokes) is past the polish, in the full 2-opt's range."""
    from fabtiles.geometry.cut_order import POLISH_MAX, travel

    design = load_design(MOSAIC, overrides=[f"tile.size={size}"])
    drawing = plot_drawing(design, fill=True, pen_mm=PEN if size == 40 else 0.3, cross=cross)
    if size == 100:
        assert max(len(layer.paths) for layer in drawing.layers) > POLISH_MAX
    for layer in drawing.layers:
        ours = travel(layer.paths, closed=False)
        for theirs in vpype_linesort_travels(layer.paths):
            assert ours <= theirs + 1e-6, (layer.name, ours, theirs)


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"hatch_mm": 0.02}, r"hatch_mm must be from 0.03 \(a tenth of the 0.3 mm pen\) to .* got 0.02"),
        ({"hatch_mm": 500}, r"hatch_mm must be from .* mm \(the largest face's size\), got 500"),
        ({"hatch_mm": "wide"}, "hatch_mm must be a finite number, got 'wide'"),
        ({"angles_deg": "steep"}, "angle of class A must be a finite number, got 'steep'"),
        ({"angles_deg": {"Q": 30}}, r"angle's class 'Q' is not one of this design's face classes \(A, B"),
        ({"what": "cut"}, "fill hatches the faces of a pen's drawing: what must be centrelines, got 'cut'"),
    ],
)
def test_bad_fill_options(kw, match):
    with pytest.raises(ParameterError, match=match):
        plot_drawing(load_design(MOSAIC, overrides=SMALL), fill=True, **kw)


def test_fill_without_colours_says_how_to_give_them():
    with pytest.raises(ParameterError, match=r"fill needs the design's colours: add a \[colour\] section"):
        plot_drawing(load_design(ROOT / "samples" / "rosette.toml"), fill=True)
    drawing = plot_drawing(
        load_design(ROOT / "samples" / "rosette.toml", overrides=["colour.by=shape", *SMALL]), fill=True
    )
    assert len(drawing.layers) > 1


@pytest.mark.parametrize(
    "args, message",
    [
        (["--hatch-mm", "0.01"], "--hatch-mm must be from 0.03"),
        (["--hatch-mm", "900"], "(the largest face's size), got 900"),
        (["--angle", "steep"], "angle must be degrees (30) or a class and degrees (B=60), got 'steep'"),
        (["--angle", "Q=30"], "angle's class 'Q' is not one of"),
    ],
)
def test_cli_bad_fill_is_one_line_exit_2_no_file(tmp_path, args, message):
    out = tmp_path / "f.svg"
    res = CliRunner().invoke(cli, ["plot", str(MOSAIC), "-o", str(out), "--fill", "--set", SMALL[0], *args])
    assert res.exit_code == 2 and res.output.count("\n") == 1 and message in res.output, res.output
    assert not out.exists()


def test_cli_fill_without_colours_exit_2_no_file(tmp_path):
    out = tmp_path / "f.svg"
    res = CliRunner().invoke(cli, ["plot", str(ROOT / "samples" / "rosette.toml"), "-o", str(out), "--fill"])
    assert res.exit_code == 2 and "fill needs the design's colours" in res.output and not out.exists()


def test_the_filled_plot_picture_is_up_to_date(tmp_path):
    import importlib.util

    spec = importlib.util.spec_from_file_location("render_plot", ROOT / "samples" / "render_plot.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    out = module.render(MOSAIC, tmp_path / "plot.svg")
    assert out.read_bytes() == (ROOT / "samples" / "renders" / "plot-mosaic-iznik.svg").read_bytes(), (
        "run python samples/render_plot.py"
    )
    assert "](../samples/renders/plot-mosaic-iznik.svg)" in (ROOT / "docs" / "plotters-and-inkscape.md").read_text()


def test_hpgl_selects_a_pen_per_layer(tmp_path):
    pytest.importorskip("vpype")
    out = tmp_path / "filled.hpgl"
    res = CliRunner().invoke(cli, ["plot", str(MOSAIC), "-o", str(out), "--fill", "--set", SMALL[0]])
    assert res.exit_code == 0, res.output
    n = len(plot_drawing(load_design(MOSAIC, overrides=SMALL), fill=True).layers)
    assert re.findall(r"SP(\d+)", out.read_text()) == [str(k) for k in range(1, n + 1)] + ["0"]
