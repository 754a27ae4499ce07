"""The text formats' one spelling of a number and their XML escaping (fabtiles/export/_text.py)."""

from __future__ import annotations

import math
from xml.etree import ElementTree

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles.export._text import attribute, escape, number
from fabtiles.export.plot_svg import svg_text
from fabtiles.geometry.pen import PenDrawing, PenLayer

FINITE = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e12, max_value=1e12)


@settings(max_examples=examples(300))
@given(FINITE, st.integers(1, 9))
def test_a_number_reads_back_within_its_rounding(x, decimals):
    text = number(x, decimals)
    assert "e" not in text.lower() and text != "-0"
    assert not (("." in text) and text.endswith(("0", ".")))  # no trailing zeros, no bare point
    assert math.isclose(float(text), x, abs_tol=0.5 * 10.0**-decimals + abs(x) * 1e-15)


@settings(max_examples=examples(300))
@given(FINITE, st.integers(1, 9))
def test_a_number_is_the_rounded_fixed_point_text_without_its_zeros(x, decimals):
    # what each writer wrote before there was one helper: the same bytes
    s = f"{x:.{decimals}f}".rstrip("0").rstrip(".")
    assert number(x, decimals) == ("0" if s in ("-0", "", "-") else s)


def test_no_decimals_keeps_the_integer_whole():
    assert [number(v, 0) for v in (120.0, -0.4, 0.0, 7.6)] == ["120", "0", "0", "8"]


# XML's characters, without the whitespace controls an attribute value normalises to spaces
XML_TEXT = st.text(st.characters(blacklist_categories=("Cs", "Cc")), max_size=40)


@settings(max_examples=examples(300))
@given(XML_TEXT)
def test_escaped_text_and_attributes_read_back_as_given(text):
    root = ElementTree.fromstring(f'<a name="{attribute(text)}">{escape(text)}</a>')
    assert root.get("name") == text and (root.text or "") == text
    assert ">" not in escape(text).replace("&gt;", "") and '"' not in attribute(text)


def test_a_pen_layers_name_is_escaped_whole():
    # '>' in a label was written as it was before the writers shared one escape
    layer = PenLayer('a<b>&"c"', "#000000", (np.array([[0, 0], [10, 5.0]]),))
    svg = svg_text(PenDrawing((layer,), (0, 0, 10, 5), 0.3))
    assert 'inkscape:label="a&lt;b&gt;&amp;&quot;c&quot;"' in svg
    ink = "{http://www.inkscape.org/namespaces/inkscape}"
    group = ElementTree.fromstring(svg.split("\n", 1)[1]).find("{http://www.w3.org/2000/svg}g")
    assert group is not None and group.get(ink + "label") == 'a<b>&"c"'
