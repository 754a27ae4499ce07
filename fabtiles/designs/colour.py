"""Colours of a pattern: a colour's value and name, the palettes, and the materials a design needs.

A design's ``[colour]`` section (``docs/colours.md``) gives the band's colour, the
base's and one per face class (by letter), over a named palette's defaults.
Colours are compared by value: classes given the same colour share one material
(one filament, one wood), so the number of materials is the number of distinct
colours. A colour is ``#rrggbb`` or a CSS colour name (``"navy"``), parsed with
``webcolors`` (the CSS3 names); it is named in file names and parts by its
palette name, its CSS name, or its hex digits.

>>> parse_colour("Navy")
Colour(hex='#000080', name='navy')
>>> parse_colour("#1F3B73")
Colour(hex='#1f3b73', name='1f3b73')
>>> palette("zellige").faces[0]
Colour(hex='#1d4e89', name='cobalt')
>>> parse_colour("#12345")
Traceback (most recent call last):
...
fabtiles.core.errors.ParameterError: colour must be #rrggbb or a CSS colour name (like "navy"), got '#12345'
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from ..core.errors import ParameterError, did_you_mean
from ..core.schema import register_choices, register_type, section_keys

_HEX = re.compile(r"#[0-9a-fA-F]{6}")

MAX_MATERIALS = 16
"""Distinct colours a print may have: PrusaSlicer's and Bambu Studio's extruder/filament limit is 16
(two AMS units and more need a second printer profile); a kit of more woods is a kit of more sheets."""


@dataclass(frozen=True)
class Colour:
    """One colour: ``hex`` (``#rrggbb``, lower case) and ``name`` (its palette or CSS name, or its hex digits)."""

    hex: str
    name: str

    @property
    def srgb(self) -> tuple[float, float, float]:
        """Red, green and blue from 0 to 1 (sRGB, as written).

        >>> parse_colour("#ff8000").srgb
        (1.0, 0.5019607843137255, 0.0)
        """
        return tuple(int(self.hex[i:i + 2], 16) / 255 for i in (1, 3, 5))

    @property
    def linear(self) -> tuple[float, float, float]:
        """Linear RGB (the 3D view's and glTF's colour space), from sRGB by the sRGB transfer curve.

        >>> [round(c, 4) for c in parse_colour("#808080").linear]
        [0.2159, 0.2159, 0.2159]
        """
        return tuple(c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in self.srgb)


def parse_colour(value, *, param: str = "colour") -> Colour:
    """``value`` (``#rrggbb`` or a CSS colour name) as a :class:`Colour`; a :class:`ParameterError` otherwise.

    A hex value that is a CSS colour's takes its name (``#000080`` is ``navy``).
    """
    import webcolors

    if isinstance(value, Colour):
        return value
    if isinstance(value, str) and _HEX.fullmatch(value):
        hex_ = value.lower()
        try:
            name = webcolors.hex_to_name(hex_)
        except ValueError:
            name = hex_[1:]
        return Colour(hex_, name)
    if isinstance(value, str) and value.strip() and not value.startswith("#"):
        name = value.strip().lower()
        try:
            return Colour(webcolors.name_to_hex(name), name)
        except ValueError:
            hint = did_you_mean(name, webcolors.names("css3"))
            raise ParameterError(f"{param} {value!r} is not a CSS colour name{f' ({hint})' if hint else ''}; give "
                                 f"#rrggbb or a CSS name like \"navy\"", param=param) from None
    raise ParameterError(f"{param} must be #rrggbb or a CSS colour name (like \"navy\"), got {value!r}",
                         param=param)


@dataclass(frozen=True)
class Palette:
    """A named set of colours: the bands', the base's and the faces' in class order (A, B, ...)."""

    name: str
    source: str
    """Where the colours come from, in a sentence (``docs/colours.md`` shows it)."""
    band: Colour
    base: Colour
    faces: tuple[Colour, ...]


def _c(hex_: str, name: str) -> Colour:
    return Colour(hex_, name)


PALETTES = {p.name: p for p in (
    Palette("zellige", "Moroccan zellige (Fez and Meknes, Marinid period to today): hand-cut glazed terracotta "
            "in white, cobalt, green, honey, black and turquoise, the strapwork often white",
            band=_c("#f2ede1", "white"), base=_c("#2b2b2b", "black"),
            faces=(_c("#1d4e89", "cobalt"), _c("#2e6f40", "green"), _c("#c98f2b", "honey"),
                   _c("#2b2b2b", "black"), _c("#2d8c9e", "turquoise"), _c("#9c3d26", "terracotta"))),
    Palette("iznik", "Ottoman Iznik ceramics (16th century): a white ground painted in cobalt blue, turquoise, "
            "raised bole red and green, outlined in black",
            band=_c("#f5f1e8", "white"), base=_c("#1e2a5a", "navy"),
            faces=(_c("#1e4fa0", "cobalt"), _c("#23a0a5", "turquoise"), _c("#b8322a", "bole"),
                   _c("#3a7d4a", "green"), _c("#1b1b1b", "black"), _c("#7fb3d5", "sky"))),
    Palette("mamluk", "Mamluk Cairo (13th to 16th century) Qur'an illumination and inlaid metalwork: gold "
            "strapwork on lapis blue, black, red and white",
            band=_c("#c9a227", "gold"), base=_c("#1a1a1a", "black"),
            faces=(_c("#26428b", "lapis"), _c("#9e2b25", "red"), _c("#1a1a1a", "black"),
                   _c("#efe6d2", "ivory"), _c("#2f6b4f", "green"), _c("#6b8fb8", "pale-blue"))),
    Palette("alhambra", "Nasrid alicatado of the Alhambra (14th century): glazed tile mosaic in black, green, "
            "ochre, blue, white and manganese purple",
            band=_c("#efe9dc", "white"), base=_c("#1b1b1b", "black"),
            faces=(_c("#2c6e49", "green"), _c("#c8932f", "ochre"), _c("#27408b", "blue"),
                   _c("#1b1b1b", "black"), _c("#5b3a4a", "manganese"), _c("#8a9a5b", "olive"))),
    Palette("haft-rangi", "Safavid haft-rangi, the \"seven colours\" tiles of 17th-century Isfahan: cobalt, "
            "turquoise, yellow, green, white, black and a red-brown",
            band=_c("#f2ede2", "white"), base=_c("#1f3f95", "cobalt"),
            faces=(_c("#2aa1b3", "turquoise"), _c("#e0b43a", "yellow"), _c("#1f3f95", "cobalt"),
                   _c("#3a7d44", "green"), _c("#9b4a2c", "red-brown"), _c("#1a1a1a", "black"))),
)}
"""The named palettes, ``[colour] palette``; the first is the default."""

PALETTE_NAMES = tuple(PALETTES)


def palette(name: str) -> Palette:
    """The palette called ``name``; an unknown name is a :class:`ParameterError` listing the palettes."""
    try:
        return PALETTES[name]
    except (KeyError, TypeError):
        hint = did_you_mean(name, PALETTE_NAMES) if isinstance(name, str) else ""
        raise ParameterError(f"palette {name!r} is not known{f' ({hint})' if hint else ''}, must be one of: "
                             f"{', '.join(PALETTE_NAMES)}", param="palette") from None


def letters(n: int) -> tuple[str, ...]:
    """The first ``n`` class letters: A ... Z, then AA, AB, ...

    >>> letters(3), letters(28)[-2:]
    (('A', 'B', 'C'), ('AA', 'AB'))
    """
    out = []
    for i in range(n):
        s, k = "", i
        while True:
            s = chr(ord("A") + k % 26) + s
            k = k // 26 - 1
            if k < 0:
                break
        out.append(s)
    return tuple(out)


@dataclass(frozen=True)
class Colouring:
    """The colours of one design: the band's, the base's and each face class's (by letter)."""

    band: Colour
    base: Colour
    faces: tuple[tuple[str, Colour], ...]

    def face(self, letter: str) -> Colour:
        """The colour of the face class ``letter``."""
        return dict(self.faces)[letter]

    def materials(self, *, base: bool = True, band: bool = True) -> tuple[Colour, ...]:
        """The distinct colours in order of first use (base, band, A, B, ...): one material each."""
        seen = {}
        for c in ([self.base] if base else []) + ([self.band] if band else []) + [c for _, c in self.faces]:
            seen.setdefault(c.hex, c)
        return tuple(seen.values())


def colouring(*, palette_name: str = PALETTE_NAMES[0], band=None, base=None, faces=None,
              classes=("A",)) -> Colouring:
    """The colours of a design whose face classes are ``classes`` (letters).

    ``band``, ``base`` and ``faces`` (``{letter: colour}``) override the palette's; a
    class the palette has no colour for takes the palette's colours again from the
    first (A's), so its material is shared. A letter in ``faces`` that is not a class
    is a :class:`ParameterError` naming the classes.

    >>> c = colouring(palette_name="iznik", faces={"B": "navy"}, classes=("A", "B"))
    >>> [(k, v.name) for k, v in c.faces], c.band.name  # CSS navy is not Iznik's navy base: a name of its own
    ([('A', 'cobalt'), ('B', 'navy-000080')], 'white')
    """
    pal = palette(palette_name)
    faces = dict(faces or {})
    unknown = [k for k in faces if k not in classes]
    if unknown:
        hint = did_you_mean(unknown[0], classes)
        raise ParameterError(f"face class {unknown[0]!r} is not one of this design's{f' ({hint})' if hint else ''}: "
                             f"{', '.join(classes)}", param=f"faces.{unknown[0]}")
    chosen = tuple((k, parse_colour(faces[k], param=f"faces.{k}") if k in faces
                    else pal.faces[i % len(pal.faces)]) for i, k in enumerate(classes))
    base = pal.base if base is None else parse_colour(base, param="base")
    band = pal.band if band is None else parse_colour(band, param="band")
    # one name per colour (it names a part and an STL file): a second colour of a name takes its hex digits
    owner = {}
    def named(c):
        first = owner.setdefault(c.name, c.hex)
        return c if first == c.hex else Colour(c.hex, f"{c.name}-{c.hex[1:]}")
    base, band = named(base), named(band)
    return Colouring(band=band, base=base, faces=tuple((k, named(c)) for k, c in chosen))


def check_materials(colours, *, what: str = "print") -> None:
    """Refuse more than :data:`MAX_MATERIALS` distinct colours, saying how to share materials."""
    colours = tuple(colours)
    if len(colours) > MAX_MATERIALS:
        raise ParameterError(f"the {what} has {len(colours)} distinct colours, more than the {MAX_MATERIALS} "
                             f"filaments a slicer takes; give some face classes the same colour in [colour.faces] "
                             f"(classes of one colour share a filament)", param="faces")


@dataclass(frozen=True, kw_only=True)
class Colours:
    """How a tile is coloured: a design's ``[colour]`` section, and the export API's ``colours=`` option.

    ``by`` (``"none"`` or ``"shape"``) groups the faces into classes; ``palette`` names
    the palette; ``band_colour`` and ``base_colour`` (``#rrggbb`` or a CSS name)
    override the palette's; ``faces`` maps class letters to colours (a dict or pairs).
    ``given`` says that colours were asked for (a design with a ``[colour]`` section:
    a relief's and a deboss's parts then take the base and band colours). Every value
    is checked here; the letters against the design's classes when the build knows them.

    >>> Colours(by="shape", palette="iznik", faces={"B": "navy"}).faces
    (('B', 'navy'),)
    >>> Colours(by="size")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: by = 'size' is not valid, must be one of: none, shape
    """

    by: str = "none"
    palette: str = PALETTE_NAMES[0]
    band_colour: str | None = None
    base_colour: str | None = None
    faces: tuple = field(default=())
    given: bool = True

    def __post_init__(self):
        for k in section_keys("colour"):
            if k.name != "faces":
                k.check(getattr(self, k.name))
        faces = self.faces.items() if isinstance(self.faces, dict) else self.faces
        pairs = []
        for letter, value in faces:
            if not (isinstance(letter, str) and re.fullmatch(r"[A-Z]{1,2}", letter)):
                raise ParameterError(f"key {letter!r} must be a class letter (A, B, ... as fabtiles check "
                                     f"lists them)", param="faces")
            parse_colour(value, param=letter)
            pairs.append((letter, value))
        object.__setattr__(self, "faces", tuple(sorted(pairs)))

    def colouring(self, classes=("A",)) -> Colouring:
        """The colours of a tile whose face classes are ``classes`` (:func:`colouring`)."""
        return colouring(palette_name=self.palette, band=self.band_colour, base=self.base_colour,
                         faces=dict(self.faces), classes=classes)


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(PALETTE_NAMES, "colour.palette")
register_type("colour", parse_colour)
