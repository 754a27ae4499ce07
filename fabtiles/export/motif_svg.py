"""SVG pictures of one motif (``fabtiles star``); the laser SVG is :mod:`fabtiles.export.laser_svg`.

Written by hand with string formatting: SVG is plain XML and a dependency
would add nothing here; coordinates are printed with fixed precision so files
are reproducible byte for byte.
"""

from __future__ import annotations

import numpy as np

from ..core.files import atomic_write
from ._text import escape as _escape
from ._text import number as _num


def segments_path_data(segments: np.ndarray, *, flip_y: float | None = None) -> str:
    """SVG path data (``M x y L x y`` pairs) for centre-line segments.

    ``flip_y`` mirrors y as ``flip_y - y`` (SVG's y axis points down).

    >>> segments_path_data(np.array([[[0, 0], [1, 2]]]), flip_y=2)
    'M0 2L1 0'
    """
    seg = np.asarray(segments, dtype=float)
    if flip_y is not None:
        seg = seg.copy()
        seg[..., 1] = flip_y - seg[..., 1]
    return "".join(f"M{_num(a[0])} {_num(a[1])}L{_num(b[0])} {_num(b[1])}" for a, b in seg)


def motif_svg(
    segments: np.ndarray,
    *,
    size_mm: float = 100.0,
    stroke: float | None = None,
    color: str = "#1f3b73",
    title: str = "",
) -> str:
    """An SVG picture of a motif's centre-lines, scaled to ``size_mm`` across.

    >>> svg = motif_svg(np.array([[[-1.0, 0.0], [1.0, 0.0]]]), size_mm=10)
    >>> svg.startswith('<?xml') and 'width="10mm"' in svg
    True
    """
    seg = np.asarray(segments, dtype=float)
    extent = float(np.sqrt((seg**2).sum(-1)).max()) if len(seg) else 1.0
    margin = 0.04 * size_mm
    scale = (size_mm / 2 - margin) / extent
    seg = seg * scale + size_mm / 2
    stroke = stroke if stroke is not None else size_mm / 250
    d = segments_path_data(seg, flip_y=size_mm)
    title_el = f"<title>{_escape(title)}</title>" if title else ""
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(size_mm)}mm" height="{_num(size_mm)}mm" '
        f'viewBox="0 0 {_num(size_mm)} {_num(size_mm)}">{title_el}\n'
        f'<rect width="100%" height="100%" fill="#ffffff"/>\n'
        f'<path d="{d}" fill="none" stroke="{color}" stroke-width="{_num(stroke)}" '
        'stroke-linecap="round" stroke-linejoin="round"/>\n</svg>\n'
    )


def write_motif_svg(path, segments: np.ndarray, **options) -> None:
    """Write :func:`motif_svg` to ``path`` atomically."""
    atomic_write(path, motif_svg(segments, **options))
