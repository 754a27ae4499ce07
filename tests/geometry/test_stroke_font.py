"""The single-stroke label font of the test card."""

import numpy as np
import pytest

from fabtiles import ParameterError
from fabtiles.geometry.stroke_font import CHARACTERS, text_paths, text_width


def test_every_glyph_is_open_strokes_inside_its_cell():
    for c in CHARACTERS.strip():
        paths = text_paths(c, height_mm=6.0)
        assert paths, c
        for p in paths:
            assert p.shape[1] == 2 and len(p) >= 2
            assert (np.hypot(*np.diff(p, axis=0).T) > 0).all(), c  # no zero-length edges
            assert p[:, 0].min() >= 0 and p[:, 0].max() <= 4 and p[:, 1].min() >= 0 and p[:, 1].max() <= 6


def test_centred_text_is_centred_and_scaled():
    paths = text_paths("1.25", height_mm=2.0, x=10.0, y=5.0, centre=True)
    pts = np.concatenate(paths)
    assert pts[:, 1].min() == pytest.approx(5.0) and pts[:, 1].max() == pytest.approx(7.0)
    w = text_width("1.25", height_mm=2.0)
    assert pts[:, 0].max() - pts[:, 0].min() <= w + 1e-9
    assert (pts[:, 0].min() + pts[:, 0].max()) / 2 == pytest.approx(10.0, abs=w / 2)


def test_unknown_characters_are_refused():
    with pytest.raises(ParameterError, match=r"label 'x1' has characters the stroke font cannot draw: 'x'"):
        text_paths("x1", height_mm=2)
