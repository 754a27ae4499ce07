"""Colours of a pattern: a colour's value and name, the palettes, and the materials a design needs.

A design's ``[colour]`` section (``docs/colours.md``) gives the band's colour, the
base's and one per face class (by letter), over a named palette's defaults.
Colours are compared by value: classes given the same colour share one material
(one filament, one wood), so the number of materials is the number of distinct
colours. A colour is ``#rrggbb``, a palette's colour name (``"cobalt"``, read in the
design's palette first) or a CSS colour name (``"navy"``, parsed with ``webcolors``);
it is named in file names and parts by its palette name, its CSS name, or its hex
digits.

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
        r, g, b = (int(self.hex[i : i + 2], 16) / 255 for i in (1, 3, 5))
        return r, g, b

    @property
    def linear(self) -> tuple[float, float, float]:
        """Linear RGB (the 3D view's and glTF's colour space), from sRGB by the sRGB transfer curve.

        >>> [round(c, 4) for c in parse_colour("#808080").linear]
        [0.2159, 0.2159, 0.2159]
        """
        r, g, b = (c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in self.srgb)
        return r, g, b


PART_COLOURS = ("band", "base")
"""The values a face class may take to join the bands' part or the base's: ``B = "band"``."""


def parse_colour(value, *, param: str = "colour", palette=None) -> Colour:
    """``value`` as a :class:`Colour`; a :class:`ParameterError` otherwise.

    ``value`` is ``#rrggbb``, a colour name of the design's ``palette`` (a
    :class:`Palette` or its name: in ``iznik``, ``"cobalt"`` is ``#1e4fa0``), a CSS
    colour name, or a name of one other palette (``"lapis"``) or of a palette
    named first (``"iznik.cobalt"``). A name the design's palette has means the
    palette's colour, so a name the summary prints can be typed back. A hex value
    takes the palette's name of it, else the CSS name, else its hex digits. Without
    a palette, a name any palette has is accepted (its value is settled by the
    design's palette, :func:`colouring`).

    >>> parse_colour("white", palette="iznik"), parse_colour("#1e4fa0", palette="iznik").name
    (Colour(hex='#f5f1e8', name='white'), 'cobalt')
    >>> parse_colour("mamluk.lapis"), parse_colour("bole", palette="zellige").hex
    (Colour(hex='#26428b', name='lapis'), '#b8322a')
    """
    if isinstance(value, Colour):
        return value
    pal = palette if isinstance(palette, Palette) or palette is None else PALETTES.get(palette)
    if isinstance(value, str) and _HEX.fullmatch(value):
        return _hex_colour(value.lower(), pal)
    if isinstance(value, str) and value.strip() and not value.startswith("#"):
        return _named_colour(value, pal, param)
    raise ParameterError(f'{param} must be #rrggbb or a CSS colour name (like "navy"), got {value!r}', param=param)


def _hex_colour(hex_: str, pal) -> Colour:
    """A ``#rrggbb`` colour named by the palette, else by CSS, else by its hex digits."""
    import webcolors

    own = {c.hex: c.name for c in _colours_of(pal)} if pal is not None else {}
    if hex_ in own:
        return Colour(hex_, own[hex_])
    try:
        name = webcolors.hex_to_name(hex_)
    except ValueError:
        name = hex_[1:]
    return Colour(hex_, name)


def _named_colour(value: str, pal, param: str) -> Colour:
    """The colour a name means: a qualified palette name, the design's palette's, CSS's, or one other palette's."""
    import webcolors

    name = value.strip().lower()
    if name in PART_COLOURS:
        raise ParameterError(
            f"{param} {value!r} names a part's colour, which only a face class takes "
            f'([colour.faces] C = "band"); give #rrggbb or a colour name',
            param=param,
        )
    if "." in name:  # a colour of a palette named first: "iznik.cobalt"
        found = _qualified(value, name, param)
        if found is not None:
            return found
    if pal is not None and _named(pal, name) is not None:
        return _named(pal, name)
    try:
        return Colour(webcolors.name_to_hex(name), name)
    except ValueError:
        pass
    return _other_palettes(value, name, pal, param)


def _qualified(value: str, name: str, param: str) -> Colour | None:
    """The colour ``"palette.colour"`` names, None when the part before the dot is no palette."""
    pname, _, cname = name.partition(".")
    if pname not in PALETTES:
        return None
    found = _named(PALETTES[pname], cname)
    if found is not None:
        return found
    hint = did_you_mean(cname, [c.name for c in _colours_of(PALETTES[pname])])
    raise ParameterError(
        f"{param} {value!r}: palette {pname!r} has no colour {cname!r}"
        f"{f' ({hint})' if hint else ''}; its colours: "
        f"{', '.join(_names_of(PALETTES[pname]))}",
        param=param,
    )


def _other_palettes(value: str, name: str, pal, param: str) -> Colour:
    """The colour of that name in the other palettes: one value, or any without a design's palette."""
    others = {p.name: _named(p, name) for p in PALETTES.values() if _named(p, name) is not None}
    values = {c.hex for c in others.values()}
    if len(values) == 1 or (others and pal is None):
        return next(iter(others.values()))
    if others:
        where = ", ".join(f"{p}.{name}" for p in others)
        raise ParameterError(
            f"{param} {value!r} is a colour of several palettes, not of this design's "
            f"({pal.name if pal else None}); name one: {where} (or give #rrggbb)",
            param=param,
        )
    raise _unknown(value, name, param)


def _unknown(value: str, name: str, param: str) -> ParameterError:
    """The error for a name no CSS colour or palette has, with the nearest one."""
    import webcolors

    known = list(webcolors.names("css3")) + sorted({c.name for p in PALETTES.values() for c in _colours_of(p)})
    hint = did_you_mean(name, known)
    return ParameterError(
        f"{param} {value!r} is not a CSS or palette colour name{f' ({hint})' if hint else ''}; "
        f'give #rrggbb, a CSS name like "navy" or a palette\'s like "cobalt"',
        param=param,
    )


def palette_names(palette_name: str) -> dict:
    """``{name: "#rrggbb"}`` of every palette colour name a design of ``palette_name`` reads (its own
    names, another palette's, ``"iznik.cobalt"``), as :func:`parse_colour` reads them: what a page
    resolves a typed name by (a CSS name it knows itself).

    >>> names = palette_names("iznik")
    >>> names["white"], names["lapis"], names["zellige.cobalt"], "turquoise" in palette_names("mamluk")
    ('#f5f1e8', '#26428b', '#1d4e89', False)
    """
    import webcolors

    pal = palette(palette_name)
    out = {}
    for p in PALETTES.values():
        for c in _colours_of(p):
            for name in (c.name, f"{p.name}.{c.name}"):
                try:
                    found = parse_colour(name, palette=pal)
                except ParameterError:
                    continue  # a name of several palettes, not this one's: only its qualified form reads
                if name not in webcolors.names("css3") or _named(pal, name) is not None:
                    out[name] = found.hex
    return out


def _colours_of(pal) -> tuple:
    """A palette's colours: band, base, then the faces'."""
    return (pal.band, pal.base, *pal.faces)


def _names_of(pal) -> list:
    """A palette's colour names, each once, in order."""
    return list(dict.fromkeys(c.name for c in _colours_of(pal)))


def _named(pal, name: str):
    """The colour of ``pal`` called ``name``, or None."""
    return next((c for c in _colours_of(pal) if c.name == name), None)


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


PALETTES = {
    p.name: p
    for p in (
        Palette(
            "zellige",
            "Moroccan zellige (Fez and Meknes, Marinid period to today): hand-cut glazed terracotta "
            "in white, cobalt, green, honey, black and turquoise, the strapwork often white",
            band=_c("#f2ede1", "white"),
            base=_c("#2b2b2b", "black"),
            faces=(
                _c("#1d4e89", "cobalt"),
                _c("#2e6f40", "green"),
                _c("#c98f2b", "honey"),
                _c("#2b2b2b", "black"),
                _c("#2d8c9e", "turquoise"),
                _c("#9c3d26", "terracotta"),
            ),
        ),
        Palette(
            "iznik",
            "Ottoman Iznik ceramics (16th century): a white ground painted in cobalt blue, turquoise, "
            "raised bole red and green, outlined in black",
            band=_c("#f5f1e8", "white"),
            base=_c("#1e2a5a", "navy"),
            faces=(
                _c("#1e4fa0", "cobalt"),
                _c("#23a0a5", "turquoise"),
                _c("#b8322a", "bole"),
                _c("#3a7d4a", "green"),
                _c("#1b1b1b", "black"),
                _c("#7fb3d5", "sky"),
            ),
        ),
        Palette(
            "mamluk",
            "Mamluk Cairo (13th to 16th century) Qur'an illumination and inlaid metalwork: gold "
            "strapwork on lapis blue, black, red and white",
            band=_c("#c9a227", "gold"),
            base=_c("#1a1a1a", "black"),
            faces=(
                _c("#26428b", "lapis"),
                _c("#9e2b25", "red"),
                _c("#1a1a1a", "black"),
                _c("#efe6d2", "ivory"),
                _c("#2f6b4f", "green"),
                _c("#6b8fb8", "pale-blue"),
            ),
        ),
        Palette(
            "alhambra",
            "Nasrid alicatado of the Alhambra (14th century): glazed tile mosaic in black, green, "
            "ochre, blue, white and manganese purple",
            band=_c("#efe9dc", "white"),
            base=_c("#1b1b1b", "black"),
            faces=(
                _c("#2c6e49", "green"),
                _c("#c8932f", "ochre"),
                _c("#27408b", "blue"),
                _c("#1b1b1b", "black"),
                _c("#5b3a4a", "manganese"),
                _c("#8a9a5b", "olive"),
            ),
        ),
        Palette(
            "haft-rangi",
            'Safavid haft-rangi, the "seven colours" tiles of 17th-century Isfahan: cobalt, '
            "turquoise, yellow, green, white, black and a red-brown",
            band=_c("#f2ede2", "white"),
            base=_c("#1f3f95", "cobalt"),
            faces=(
                _c("#2aa1b3", "turquoise"),
                _c("#e0b43a", "yellow"),
                _c("#1f3f95", "cobalt"),
                _c("#3a7d44", "green"),
                _c("#9b4a2c", "red-brown"),
                _c("#1a1a1a", "black"),
            ),
        ),
    )
}
"""The named palettes, ``[colour] palette``; the first is the default."""

PALETTE_NAMES = tuple(PALETTES)


def palette(name: str) -> Palette:
    """The palette called ``name``; an unknown name is a :class:`ParameterError` listing the palettes."""
    try:
        return PALETTES[name]
    except (KeyError, TypeError):
        hint = did_you_mean(name, PALETTE_NAMES) if isinstance(name, str) else ""
        raise ParameterError(
            f"palette {name!r} is not known{f' ({hint})' if hint else ''}, must be one of: {', '.join(PALETTE_NAMES)}",
            param="palette",
        ) from None


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
        seen: dict = {}
        for c in ([self.base] if base else []) + ([self.band] if band else []) + [c for _, c in self.faces]:
            seen.setdefault(c.hex, c)
        return tuple(seen.values())


def colouring(*, palette_name: str = PALETTE_NAMES[0], band=None, base=None, faces=None, classes=("A",)) -> Colouring:
    """The colours of a design whose face classes are ``classes`` (letters).

    ``band``, ``base`` and ``faces`` (``{letter: colour}``) override the palette's; a
    class the palette has no colour for takes the palette's colours again from the
    first (A's), so its material is shared. A class given ``"band"`` or ``"base"``
    takes the bands' or the base's colour, so it joins that part. Names are read in
    the palette first (:func:`parse_colour`), and one value has one name: the first
    it was given (base, bands, A, B, ...), so the class lines and the parts agree.
    A letter in ``faces`` that is not a class is a :class:`ParameterError` naming
    the classes.

    >>> c = colouring(palette_name="iznik", faces={"B": "navy", "C": "band", "D": "#000080"},
    ...               classes=("A", "B", "C", "D"))
    >>> [(k, v.name) for k, v in c.faces], c.band.name  # navy is Iznik's (the base's); #000080 CSS navy
    ([('A', 'cobalt'), ('B', 'navy'), ('C', 'white'), ('D', 'navy-000080')], 'white')
    """
    pal = palette(palette_name)
    faces = dict(faces or {})
    unknown = [k for k in faces if k not in classes]
    if unknown:
        hint = did_you_mean(unknown[0], classes)
        raise ParameterError(
            f"face class {unknown[0]!r} is not one of this design's{f' ({hint})' if hint else ''}: "
            f"{', '.join(classes)}",
            param=f"faces.{unknown[0]}",
        )
    base = pal.base if base is None else parse_colour(base, param="base", palette=pal)
    band = pal.band if band is None else parse_colour(band, param="band", palette=pal)
    parts = {"band": band, "base": base}

    def face(k, i):
        if k not in faces:
            return pal.faces[i % len(pal.faces)]
        value = faces[k]
        if isinstance(value, str) and value.strip().lower() in parts:
            return parts[value.strip().lower()]
        return parse_colour(value, param=f"faces.{k}", palette=pal)

    chosen = tuple((k, face(k, i)) for i, k in enumerate(classes))
    # one name per colour (it names a part and an STL file): a value keeps the first name it was given, and a
    # second value of a name takes its hex digits
    names: dict = {}
    owner: dict = {}

    def named(c):
        if c.hex in names:
            return Colour(c.hex, names[c.hex])
        first = owner.setdefault(c.name, c.hex)
        names[c.hex] = c.name if first == c.hex else f"{c.name}-{c.hex[1:]}"
        return Colour(c.hex, names[c.hex])

    base, band = named(base), named(band)
    return Colouring(band=band, base=base, faces=tuple((k, named(c)) for k, c in chosen))


def check_materials(colours, *, what: str = "print") -> None:
    """Refuse more than :data:`MAX_MATERIALS` distinct colours, saying how to share materials."""
    colours = tuple(colours)
    if len(colours) > MAX_MATERIALS:
        raise ParameterError(
            f"the {what} has {len(colours)} distinct colours, more than the {MAX_MATERIALS} "
            f"filaments a slicer takes; give some face classes the same colour in [colour.faces] "
            f"(classes of one colour share a filament)",
            param="faces",
        )


@dataclass(frozen=True, kw_only=True)
class Colours:
    """How a tile is coloured: a design's ``[colour]`` section, and the export API's ``colours=`` option.

    ``by`` (``"none"`` or ``"shape"``) groups the faces into classes; ``palette`` names
    the palette; ``band_colour`` and ``base_colour`` (``#rrggbb``, a palette's or a CSS
    name) override the palette's; ``faces`` maps class letters to colours (a dict or
    pairs), or to ``"band"`` or ``"base"`` (the class joins that part).
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
    faces: tuple | dict = field(default=())
    shaded: str = ""
    shades: tuple | dict = field(default=())
    given: bool = True

    def __post_init__(self):
        for k in section_keys("colour"):
            if k.type not in ("colours", "shades"):  # tables, checked below
                k.check(getattr(self, k.name))
        _engraved_letters(self.shaded, ())  # its spelling; its letters against the design's classes later
        shades = self.shades.items() if isinstance(self.shades, dict) else self.shades
        for letter, _ in shades:
            _check_letter(letter, "shades")
        object.__setattr__(self, "shades", tuple(sorted((k, _frozen(v)) for k, v in shades)))
        faces = self.faces.items() if isinstance(self.faces, dict) else self.faces
        pairs = []
        for letter, value in faces:
            _check_letter(letter, "faces")
            if not (isinstance(value, str) and value.strip().lower() in PART_COLOURS):
                parse_colour(value, param=letter)
            pairs.append((letter, value))
        object.__setattr__(self, "faces", tuple(sorted(pairs)))

    def engraved(self, classes) -> tuple:
        """The letters of ``shaded`` among the design's ``classes`` (all of them for ``"all"``); an unknown
        letter is a :class:`ParameterError` naming it and the classes."""
        return _engraved_letters(self.shaded, tuple(classes))

    def shade_overrides(self) -> dict:
        """``[colour.shades]`` as letter -> table (plain dicts)."""
        return {letter: dict(table) if isinstance(table, tuple) else table for letter, table in self.shades}

    def colouring(self, classes=("A",)) -> Colouring:
        """The colours of a tile whose face classes are ``classes`` (:func:`colouring`)."""
        return colouring(
            palette_name=self.palette,
            band=self.band_colour,
            base=self.base_colour,
            faces=dict(self.faces),
            classes=classes,
        )


def _check_letter(letter, param: str) -> None:
    """A ``[colour.faces]`` or ``[colour.shades]`` key: a class letter."""
    if not (isinstance(letter, str) and re.fullmatch(r"[A-Z]{1,2}", letter)):
        raise ParameterError(
            f"key {letter!r} must be a class letter (A, B, ... as fabtiles check lists them)", param=param
        )


def _frozen(table):
    """A ``[colour.shades]`` entry as sorted pairs when it is a table (hashable, like the rest of a design)."""
    return tuple(sorted(table.items())) if isinstance(table, dict) else table


def _engraved_letters(text, classes: tuple) -> tuple:
    """The class letters of ``[colour] shaded`` (``"A C"``, ``"A,C"`` or ``"all"``), checked against
    ``classes`` when they are given.

    >>> _engraved_letters("A, c", ("A", "B", "C")), _engraved_letters("all", ("A", "B"))
    (('A', 'C'), ('A', 'B'))
    >>> _engraved_letters("D", ("A", "B"))
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: [colour] shaded names face class 'D', which this design has not (its classes: A, B)
    """  # noqa: E501 - a doctest's lines are as Python prints them
    words = [w.upper() for w in re.split(r"[\s,]+", text.strip()) if w] if isinstance(text, str) else None
    if words is None or any(not re.fullmatch(r"[A-Z]{1,2}|ALL", w) for w in words):
        raise ParameterError(
            f'[colour] shaded must be class letters ("A C") or "all", got {text!r}', param="colour.shaded"
        )
    if not classes:
        return tuple(dict.fromkeys(words))
    if "ALL" in words:
        return tuple(classes)
    unknown = [w for w in words if w not in classes]
    if unknown:
        raise ParameterError(
            f"[colour] shaded names face class {unknown[0]!r}, which this design has not "
            f"(its classes: {', '.join(classes)})",
            param="colour.shaded",
        )
    return tuple(dict.fromkeys(words))


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(PALETTE_NAMES, "colour.palette")
register_type("colour", parse_colour)
