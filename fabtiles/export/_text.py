"""Numbers and names as the text formats write them (SVG, LightBurn, 3MF).

One spelling of a number for every hand-written text format, so two writers never disagree on
how ``0.5`` or a negative zero looks, and the standard library's XML escaping
(:func:`xml.sax.saxutils.escape`) for the free text (a design's title, a colour's or a layer's
name) they carry.
"""

from __future__ import annotations

from xml.sax.saxutils import escape

__all__ = ["attribute", "escape", "number"]


def number(x: float, decimals: int = 4) -> str:
    """``x`` in fixed point, rounded to ``decimals``, without trailing zeros.

    Fixed point, not ``repr`` or ``:g``, so a coordinate never takes an exponent (which some
    SVG and LightBurn readers refuse) and the same value gives the same bytes on every run;
    trailing zeros and a bare point are dropped to keep files small, and a value that rounds to
    zero is ``0`` whatever its sign.

    Parameters
    ----------
    x : float
        The number, in the file's unit (mm).
    decimals : int, default 4
        Decimals kept: 4 (0.1 micrometre) in the cutter and plotter files, 3 (a micrometre)
        in the preview pictures.

    Returns
    -------
    str
        The number's text.

    Examples
    --------
    >>> number(12.5), number(3.0), number(-0.00001), number(1e-7), number(2.71828, 3)
    ('12.5', '3', '0', '0', '2.718')
    >>> number(1e21), number(120.0, 0)
    ('1000000000000000000000', '120')
    """
    s = f"{x:.{decimals}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s == "-0" else s


def attribute(text: str) -> str:
    """``text`` escaped for an XML attribute value written between double quotes.

    :func:`xml.sax.saxutils.escape` (``&``, ``<``, ``>``) with ``"`` as ``&quot;``. Unlike
    :func:`xml.sax.saxutils.quoteattr`, the quotes around the value are the caller's and
    always double, so a name holding a quote does not change the quoting of its attribute.

    Parameters
    ----------
    text : str
        Free text: a name, a title, a layer's role.

    Returns
    -------
    str
        The escaped text, without quotes around it.

    Examples
    --------
    >>> attribute('a "b" & <c>')
    'a &quot;b&quot; &amp; &lt;c&gt;'
    """
    return escape(text, _QUOTE)


_QUOTE = {'"': "&quot;"}
