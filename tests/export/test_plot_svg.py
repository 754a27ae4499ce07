"""The pen plotter's files (issue 37): SVG at true size read back by vpype, its document, HPGL."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import vpype as vp
from lxml import etree

from fabtiles import ParameterError
from fabtiles.designs.design_file import load_design
from fabtiles.export.plot_svg import PX_PER_MM, hpgl_bytes, need_vpype, svg_bytes, vpype_document
from fabtiles.making.plot import plot_drawing

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def drawing():
    return plot_drawing(load_design(ROOT / "samples" / "mosaic-iznik.toml"), pen_mm=0.4)


def test_svg_is_true_size_one_layer_per_pen(drawing, tmp_path):
    path = tmp_path / "p.svg"
    path.write_bytes(svg_bytes(drawing))
    root = etree.parse(str(path)).getroot()
    x0, y0, x1, y1 = drawing.bounds
    assert root.get("width") == f"{x1 - x0:g}mm" and root.get("height") == f"{y1 - y0:g}mm"
    ink = "{http://www.inkscape.org/namespaces/inkscape}"
    groups = [g for g in root if g.get(ink + "groupmode") == "layer"]
    assert [g.get(ink + "label") for g in groups] == [layer.name for layer in drawing.layers]
    assert {g.get("stroke-width") for g in groups} == {"0.4"}
    # vpype reads it back: the same layers, the same lengths (mm)
    doc = vp.read_multilayer_svg(str(path), quantization=0.01, crop=False)  # the outline lies on the page edge
    assert len(doc.layers) == len(drawing.layers)
    got = sorted(lc.length() / PX_PER_MM for lc in doc.layers.values())
    want = sorted(layer.length_mm for layer in drawing.layers)
    assert got == pytest.approx(want, rel=1e-4)
    assert doc.page_size == pytest.approx(((x1 - x0) * PX_PER_MM, (y1 - y0) * PX_PER_MM), rel=1e-6)


def test_vpype_document_names_colours_and_pen(drawing):
    doc = vpype_document(drawing)
    assert [lc.property("vp_name") for lc in doc.layers.values()] == [layer.name for layer in drawing.layers]
    assert [str(lc.property("vp_color")) for lc in doc.layers.values()] == [layer.colour for layer in drawing.layers]
    assert [lc.property("vp_pen_width") for lc in doc.layers.values()] == pytest.approx(
        [0.4 * PX_PER_MM] * len(drawing.layers)
    )
    assert doc.length() / PX_PER_MM == pytest.approx(drawing.length_mm, rel=1e-9)
    # y down: the drawing's top edge at y = 0
    ys = np.concatenate([np.concatenate([line.imag for line in lc]) for lc in doc.layers.values()])
    assert ys.min() == pytest.approx(0, abs=1e-6)


def test_hpgl(drawing):
    data = hpgl_bytes(drawing)
    assert data.startswith(b"IN;") and b"PD" in data and data.count(b"SP") >= len(drawing.layers)


def test_no_vpype(monkeypatch):
    monkeypatch.setitem(sys.modules, "vpype", None)
    with pytest.raises(ParameterError, match=r"needs vpype, which is not installed: pip install 'fabtiles\[vpype\]'"):
        need_vpype("HPGL")
