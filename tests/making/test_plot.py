"""The plot drawing of a design (issue 37): strands, outline, colours; or the cutter's contours."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from fabtiles import ParameterError
from fabtiles.designs.design_file import load_design
from fabtiles.geometry.interlace import tile_score_lines
from fabtiles.making.pipeline import prepare_tile
from fabtiles.making.plot import plot_drawing

ROOT = Path(__file__).resolve().parents[2]


def test_strands_are_the_centrelines_once():
    design = load_design(ROOT / "samples" / "table3-3.toml")
    d = plot_drawing(design)
    assert [layer.name for layer in d.layers] == ["strands", "outline"]
    seg = tile_score_lines(prepare_tile(design))
    want = float(np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1).sum())
    strands = d.layers[0]
    assert strands.length_mm == pytest.approx(want, rel=1e-6)
    assert len(strands.paths) < len(seg) / 4  # merged into long strokes
    x0, y0, x1, y1 = d.bounds
    assert (x1 - x0, y1 - y0) == pytest.approx((150, 150), abs=1e-6)


def test_interlace_breaks_the_strands():
    plain = plot_drawing(load_design(ROOT / "samples" / "table3-3.toml"))
    woven = plot_drawing(load_design(ROOT / "samples" / "table3-3.toml", overrides=["tile.interlace=true"]))
    assert woven.layers[0].length_mm < plain.layers[0].length_mm
    assert len(woven.layers[0].paths) > len(plain.layers[0].paths)


def test_colours_are_layers_of_their_names():
    d = plot_drawing(load_design(ROOT / "samples" / "mosaic-iznik.toml"))
    names = [layer.name for layer in d.layers]
    assert names[:2] == ["strands", "outline"] and len(names) > 2
    assert all(layer.colour.startswith("#") and len(layer.colour) == 7 for layer in d.layers)


def test_cut_is_the_cut_plan_in_cut_order():
    d = plot_drawing(load_design(ROOT / "samples" / "rosette.toml"), what="cut", pen_mm=0.5)
    assert [layer.name for layer in d.layers] == ["INNER", "OUTER"]
    assert d.pen_mm == 0.5 and all(np.array_equal(p[0], p[-1]) for layer in d.layers for p in layer.paths)


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"what": "engrave"}, "not a valid what, must be one of: centrelines, cut"),
        ({"pen_mm": 0}, "pen_mm must be"),
        ({"pen_mm": 11}, "pen_mm must be"),
    ],
)
def test_bad_options(kw, match):
    with pytest.raises(ParameterError, match=match):
        plot_drawing(load_design(ROOT / "samples" / "rosette.toml"), **kw)


def vpype_linesort_travels(paths) -> list[float]:
    """The pen-up travel from the origin of vpype's ``linesort --two-opt`` of ``paths`` (open strokes,
    ``(m, 2)`` arrays), given in their order (as ``vpype read`` of our SVG has them) and in reverse."""
    vp = pytest.importorskip("vpype")
    vpype_cli = pytest.importorskip("vpype_cli")
    from fabtiles.geometry.cut_order import travel

    out = []
    for given in (list(paths), list(paths)[::-1]):
        doc = vp.Document()
        doc.add(vp.LineCollection([p[:, 0] + 1j * p[:, 1] for p in given]), 1)
        lines = vpype_cli.execute("linesort --two-opt", doc).layers[1]
        out.append(travel([np.column_stack([line.real, line.imag]) for line in lines], closed=False))
    return out


@pytest.mark.parametrize("sample", ["table3-3", "table3-2", "mosaic-iznik"])
def test_strokes_travel_no_further_than_vpypes_linesort_two_opt(sample):
    """Each layer's pen-up travel from the origin, against vpype's ``linesort --two-opt`` on the same
    strokes: given in our order (as ``vpype read`` of our SVG has them) and in the reverse order."""
    from fabtiles.geometry.cut_order import travel

    drawing = plot_drawing(load_design(ROOT / "samples" / f"{sample}.toml"))
    for layer in drawing.layers:
        ours = travel(layer.paths, closed=False)
        for theirs in vpype_linesort_travels(layer.paths):
            assert ours <= 1.005 * theirs, (layer.name, ours, theirs)
    if sample == "table3-3":  # its strands chain end to end: 1,276 mm with 2-opt alone, 1,213 mm by vpype
        assert drawing.layers[0].name == "strands" and travel(drawing.layers[0].paths, closed=False) < 500
