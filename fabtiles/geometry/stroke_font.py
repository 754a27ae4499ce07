"""A tiny single-stroke font for laser labels: digits, the decimal point and the capitals.

Laser software reads polylines reliably everywhere, while DXF TEXT entities depend
on the program's fonts (many laser programs skip them or fill outline fonts), so
labels are drawn as open polylines for the score layer. Each glyph is a few strokes
on a 4 x 6 grid (the cap height is 6 units). fabtiles' own glyphs: the card needs
fourteen characters and a nested kit the capitals (its pieces' class letters), and the
Hershey fonts on PyPI (``hershey-fonts``, last released 2021) would add an unmaintained
dependency for them. The 5 and the S are told apart by the S's serif at the top right.

>>> paths = text_paths("1.5", height_mm=3.0)
>>> len(paths), round(text_width("1.5", height_mm=3.0), 2)
(4, 6.0)
"""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError

_GLYPHS: dict[str, tuple[tuple[tuple[float, float], ...], ...]] = {
    "0": (((0, 0), (4, 0), (4, 6), (0, 6), (0, 0)), ((0, 0), (4, 6))),
    "1": (((1, 5), (2, 6), (2, 0)), ((1, 0), (3, 0))),
    "2": (((0, 6), (4, 6), (4, 3), (0, 3), (0, 0), (4, 0)),),
    "3": (((0, 6), (4, 6), (4, 0), (0, 0)), ((1, 3), (4, 3))),
    "4": (((0, 6), (0, 3), (4, 3)), ((4, 6), (4, 0))),
    "5": (((4, 6), (0, 6), (0, 3), (4, 3), (4, 0), (0, 0)),),
    "6": (((4, 6), (0, 6), (0, 0), (4, 0), (4, 3), (0, 3)),),
    "7": (((0, 6), (4, 6), (1.5, 0)),),
    "8": (((0, 0), (4, 0), (4, 6), (0, 6), (0, 0)), ((0, 3), (4, 3))),
    "9": (((4, 3), (0, 3), (0, 6), (4, 6), (4, 0), (0, 0)),),
    ".": (((0, 0), (0.8, 0), (0.8, 0.8), (0, 0.8), (0, 0)),),
    "B": (((0, 0), (0, 6), (3, 6), (4, 5), (4, 4), (3, 3), (0, 3)), ((3, 3), (4, 2), (4, 1), (3, 0), (0, 0))),
    "H": (((0, 0), (0, 6)), ((4, 0), (4, 6)), ((0, 3), (4, 3))),
    "K": (((0, 0), (0, 6)), ((4, 6), (0, 2)), ((1.3, 3.3), (4, 0))),
    "I": (((2, 0), (2, 6)), ((1, 0), (3, 0)), ((1, 6), (3, 6))),
    # the other capitals: a nested kit's class letters (A, B, ... AA, AB)
    "A": (((0, 0), (2, 6), (4, 0)), ((0.8, 2.4), (3.2, 2.4))),
    "C": (((4, 6), (0, 6), (0, 0), (4, 0)),),
    "D": (((0, 0), (0, 6), (2.5, 6), (4, 4.5), (4, 1.5), (2.5, 0), (0, 0)),),
    "E": (((4, 6), (0, 6), (0, 0), (4, 0)), ((0, 3), (3, 3))),
    "F": (((4, 6), (0, 6), (0, 0)), ((0, 3), (3, 3))),
    "G": (((4, 6), (0, 6), (0, 0), (4, 0), (4, 3), (2, 3)),),
    "J": (((4, 6), (4, 0), (0, 0), (0, 2)),),
    "L": (((0, 6), (0, 0), (4, 0)),),
    "M": (((0, 0), (0, 6), (2, 3), (4, 6), (4, 0)),),
    "N": (((0, 0), (0, 6), (4, 0), (4, 6)),),
    "O": (((0, 0), (4, 0), (4, 6), (0, 6), (0, 0)),),
    "P": (((0, 0), (0, 6), (4, 6), (4, 3), (0, 3)),),
    "Q": (((0, 0), (4, 0), (4, 6), (0, 6), (0, 0)), ((2.5, 1.5), (4, 0))),
    "R": (((0, 0), (0, 6), (4, 6), (4, 3), (0, 3)), ((1.5, 3), (4, 0))),
    "S": (((4, 6), (0, 6), (0, 3), (4, 3), (4, 0), (0, 0)), ((4, 6), (4, 5))),
    "T": (((0, 6), (4, 6)), ((2, 6), (2, 0))),
    "U": (((0, 6), (0, 0), (4, 0), (4, 6)),),
    "V": (((0, 6), (2, 0), (4, 6)),),
    "W": (((0, 6), (1, 0), (2, 3), (3, 0), (4, 6)),),
    "X": (((0, 0), (4, 6)), ((0, 6), (4, 0))),
    "Y": (((0, 6), (2, 3), (4, 6)), ((2, 3), (2, 0))),
    "Z": (((0, 6), (4, 6), (0, 0), (4, 0)),),
    "-": (((0.5, 3), (3.5, 3)),),
    "+": (((0.5, 3), (3.5, 3)), ((2, 1.5), (2, 4.5))),
}
_ADVANCE = {".": 2.0}  # grid units to the next glyph (default 6: 4 wide + 2 space)
_DEFAULT_ADVANCE = 6.0

CHARACTERS = "".join(_GLYPHS) + " "
"""The characters :func:`text_paths` can draw."""


def _check(text: str) -> None:
    bad = sorted({c for c in text if c not in CHARACTERS})
    if bad:
        raise ParameterError(
            f"label {text!r} has characters the stroke font cannot draw: {''.join(bad)!r}; "
            f"use only: {CHARACTERS.strip()} and spaces"
        )


def text_width(text: str, *, height_mm: float) -> float:
    """Width of ``text`` in mm (from the first glyph's left edge to the last one's right edge)."""
    _check(text)
    if not text:
        return 0.0
    units = sum(_ADVANCE.get(c, _DEFAULT_ADVANCE) for c in text[:-1])
    last = text[-1]
    units += 0.8 if last == "." else (0.0 if last == " " else 4.0)
    return units * height_mm / 6


def text_paths(text: str, *, height_mm: float, x: float = 0.0, y: float = 0.0, centre: bool = False) -> list:
    """Open polylines drawing ``text`` with its baseline at ``y`` (mm), as (m, 2) arrays.

    ``x`` is the left edge, or the middle with ``centre=True``. Unknown characters
    raise :class:`~fabtiles.ParameterError`.
    """
    _check(text)
    scale = height_mm / 6
    if centre:
        x -= text_width(text, height_mm=height_mm) / 2
    out = []
    pen = 0.0
    for c in text:
        for stroke in _GLYPHS.get(c, ()):
            pts = np.asarray(stroke, dtype=float)
            out.append(np.c_[x + (pen + pts[:, 0]) * scale, y + pts[:, 1] * scale])
        pen += _ADVANCE.get(c, _DEFAULT_ADVANCE)
    return out
