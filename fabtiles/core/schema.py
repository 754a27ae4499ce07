"""The design keys, each declared once: section, type, range, default, unit, help and web widget.

Every front end reads this table: the design file's validation
(:mod:`fabtiles.designs.design_file`), ``--set`` overrides and the ``star`` command's options
(:mod:`fabtiles.cli`), the web form and its query parser (:mod:`fabtiles.web`),
the build's option lists (:mod:`fabtiles.making`) and the key tables of
``docs/design-files.md`` (``python -m fabtiles.core.schema docs/design-files.md``
rewrites them). ``tests/core/test_schema.py`` fails when a key is declared anywhere else.

The module imports no layer of the package (any layer may read it, the lowest
included): what belongs to a layer above is registered by that layer when it is
imported (the root package imports every such layer): the valid values of a key
(the tilings, the presets, the palettes: :func:`register_choices`), the code that
checks a key's range (:func:`register_check`) and the parser of a value type (a
colour: :func:`register_type`). So every import goes one way, and the import linter
sees it.

>>> fit = key("output.inlay_fit_mm")
>>> fit.range, fit.describe()
(Range(min=-0.5, max=0.5, min_open=False, max_open=False), 'a number of mm from -0.5 to 0.5 (positive: a press fit, negative: play)')
>>> fit.check(0.2)
0.2
>>> key("tile.outline").choice_values()
('square', 'rectangle', 'hexagon', 'circle')
>>> build_options("3mf")[:2], build_options("3mf")[-3:]
(('style', 'base_mm'), ('inlay', 'layout', 'colours'))
"""  # noqa: E501 - a doctest's lines are as Python prints them

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .errors import ParameterError, did_you_mean

SECTIONS = ("motif", "packing", "tile", "output", "colour", "surface")
"""The design's sections, in the order of a design file."""

TYPES = (
    "string",
    "integer",
    "number",
    "numbers",
    "boolean",
    "choice",
    "size",
    "motif",
    "motifs",
    "formats",
    "colour",
    "colours",
    "shades",
)
"""A key's value type. ``numbers`` is a list of numbers, ``size`` a number or a [width, height]
pair, ``motif`` a motif table or a preset name, ``motifs`` a table of motifs keyed by polygon sides,
``formats`` a list of output formats, ``colour`` a ``#rrggbb``, palette or CSS colour name, ``colours`` a table of
face class letters to colours, ``shades`` a table of face class letters to engrave settings."""

WIDGETS = ("slider", "number", "select", "checkbox", "text", "colour")
"""How the web form shows a key."""

FAMILIES = ("cut", "print", "3mf")
"""The build option lists: the 2D cutter's files, the print files, and the 3MF's (the print's and more)."""


@dataclass(frozen=True)
class Range:
    """The values a number may take: ``min``/``max`` (None: unbounded), each end closed unless open.

    >>> Range(0, 1, min_open=True).text(), 0 in Range(0, 1, min_open=True), 1.0 in Range(0, 1, min_open=True)
    ('> 0 and <= 1', False, True)
    >>> Range(-0.5, 0.5).text(), Range(3, 120).text(integer=True)
    ('from -0.5 to 0.5', '>= 3 and <= 120')
    """

    min: float | None = None
    max: float | None = None
    min_open: bool = False
    max_open: bool = False

    def __post_init__(self):
        for end in (self.min, self.max):
            if end is not None and (isinstance(end, bool) or not isinstance(end, numbers.Real) or math.isnan(end)):
                raise ParameterError(f"a Range's ends must be numbers or None, got {end!r}", param="range")
        if self.min is not None and self.max is not None and self.min > self.max:
            raise ParameterError(f"a Range's min must be <= its max, got {self.min!r} > {self.max!r}", param="range")

    def __contains__(self, value) -> bool:
        if isinstance(value, bool) or not isinstance(value, numbers.Real) or math.isnan(value):
            return False
        value = float(value)
        if self.min is not None and (value <= self.min if self.min_open else value < self.min):
            return False
        return not (self.max is not None and (value >= self.max if self.max_open else value > self.max))

    def text(self, *, integer: bool = False) -> str:
        """The range in words: ``"> 0 and <= 1000"``, ``"from -0.5 to 0.5"`` (both ends closed, real)."""
        if self.min is not None and self.max is not None and not (self.min_open or self.max_open or integer):
            return f"from {self.min:g} to {self.max:g}"
        parts = []
        if self.min is not None:
            parts.append(f"{'>' if self.min_open else '>='} {self.min:g}")
        if self.max is not None:
            parts.append(f"{'<' if self.max_open else '<='} {self.max:g}")
        return " and ".join(parts)

    def clamp(self, value: float) -> float:
        """``value`` moved into the range's closed ends (for stepping around a value within it).

        >>> Range(-0.5, 0.5).clamp(0.7)
        0.5
        """
        low = -math.inf if self.min is None else self.min
        high = math.inf if self.max is None else self.max
        return min(high, max(low, value))


@dataclass(frozen=True, kw_only=True)
class Widget:
    """The web form's control of a key.

    ``kind`` is one of :data:`WIDGETS`; a slider's ``min``/``max`` are the slider's
    travel (the number box beside it takes the key's whole range; a list of numbers
    gets a slider per number); ``group`` is the form's box that holds it; ``label`` its
    caption. ``when`` says where the control applies: ``(("outline", ("rectangle",)),)``
    shows it only while the form's ``outline`` is ``rectangle`` (every pair must hold;
    booleans are ``"true"``/``"false"``); empty, always.
    """

    kind: str
    label: str = ""
    min: float | None = None
    max: float | None = None
    step: float | None = None
    group: str = ""
    placeholder: str = ""
    labels: tuple[tuple[str, str], ...] = ()
    """A select's captions of some of its values: ``(("inlay", "inlay kit"),)``."""
    extra: tuple[tuple[str, str], ...] = ()
    """A select's values the web adds to the key's own (``packing=none``), with their captions."""
    when: tuple[tuple[str, tuple[str, ...]], ...] = ()
    """The form's parameters and values under which the control applies (empty: always)."""

    def __post_init__(self):
        if self.kind not in WIDGETS:
            raise ParameterError(
                f"a widget's kind must be one of: {', '.join(WIDGETS)}, got {self.kind!r}", param="kind"
            )
        if self.kind == "slider" and (self.min is None or self.max is None or self.step is None):
            raise ParameterError("a slider needs min, max and step", param="kind")
        for pair in self.when:
            if not _is_condition(pair):
                raise ParameterError(
                    f"a widget's when must hold (parameter, (value, ...)) pairs, got {pair!r}", param="when"
                )


def _is_condition(pair) -> bool:
    """Whether ``pair`` is one of a widget's conditions: ``(parameter, (value, ...))``, all text."""
    return (
        isinstance(pair, tuple)
        and len(pair) == 2
        and isinstance(pair[0], str)
        and isinstance(pair[1], tuple)
        and bool(pair[1])
        and all(isinstance(v, str) for v in pair[1])
    )


@dataclass(frozen=True, kw_only=True)
class BuildOption:
    """A key that is an option of the build: its keyword in the export API and the files it is for."""

    name: str
    families: tuple[str, ...]
    help: str = ""
    """What an option no design key sets means (a key's own help says it otherwise)."""

    def __post_init__(self):
        bad = [f for f in self.families if f not in FAMILIES]
        if bad or not self.families:
            raise ParameterError(
                f"a build option's families must be some of: {', '.join(FAMILIES)}, got {self.families!r}",
                param="families",
            )


@dataclass(frozen=True, kw_only=True)
class Key:
    """One design key.

    ``checked_by`` names the layer whose code checks the value's range where it
    depends on other values (a stroke is at most the packing radius), code that
    layer registers (:func:`register_check`, :attr:`checker`): the schema's
    ``range`` is then the static part of it, for the manual and the web form,
    and only the type is checked here. Without it the schema checks the range.
    ``choices`` are the valid values, or the name of the layer that registers them
    (:func:`register_choices`).
    ``query`` is the web query parameter (None: the key has none). ``requires`` is
    the setting the key belongs to (``'kind = "archimedean"'``), if any.
    """

    section: str
    name: str
    type: str
    help: str
    default: Any = None
    default_text: str = ""
    unit: str = ""
    range: Range | None = None
    note: str = ""
    choices: tuple | str | None = None
    widget: Widget | None = None
    query: str | None = ""
    option: BuildOption | None = None
    checked_by: str | None = None
    requires: str = ""

    def __post_init__(self):
        if self.section not in SECTIONS:
            raise ParameterError(
                f"a key's section must be one of: {', '.join(SECTIONS)}, got {self.section!r}", param="section"
            )
        if self.type not in TYPES:
            raise ParameterError(f"a key's type must be one of: {', '.join(TYPES)}, got {self.type!r}", param="type")
        if self.query == "":
            object.__setattr__(self, "query", self.name)

    @property
    def path(self) -> str:
        """``"section.name"``, as ``--set`` and the errors' ``param`` name it."""
        return f"{self.section}.{self.name}"

    @property
    def bounds(self) -> Range:
        """The key's :class:`Range`, for code that reads the range of a key declared with one.

        >>> key("output.inlay_fit_mm").bounds.max
        0.5
        """
        if self.range is None:
            raise LookupError(f"the key {self.path} is declared without a range")
        return self.range

    @property
    def build(self) -> BuildOption:
        """The key's :class:`BuildOption`, for code that reads the build option of a key declared with one."""
        if self.option is None:
            raise LookupError(f"the key {self.path} is no build option")
        return self.option

    def choice_values(self) -> tuple:
        """The valid values of a ``choice`` (or a ``formats`` list), looked up when named by ``"module:NAME"``."""
        if not isinstance(self.choices, str):
            return tuple(self.choices or ())
        if self.path not in _CHOICES:
            raise LookupError(
                f"the values of {self.path} are registered by the {self.choices} layer, which is not imported"
            )
        return _CHOICES[self.path]

    @property
    def checker(self) -> Callable | None:
        """The code that checks the range (``checked_by``), as its layer registered it; None before."""
        return _CHECKS.get(self.path)

    def describe(self, *, note: bool = True) -> str:
        """What the value must be, as the errors say it: ``"a number of mm > 0"``."""
        if self.type == "boolean":
            return "true or false"
        if self.type in ("integer", "number"):
            words = ["an integer" if self.type == "integer" else "a number"]
            if self.unit == "mm":
                words.append("of mm")
            if self.range is not None:
                words.append(self.range.text(integer=self.type == "integer"))
            if note and self.note:
                words.append(f"({self.note})")
            return " ".join(words)
        if self.type == "choice":
            return f"one of: {', '.join(self.choice_values())}"
        return self.note or f"a {self.type}"

    def check(
        self,
        value,
        *,
        name: str | None = None,
        prefix: str = "",
        error=ParameterError,
        param: str | None = None,
        required: bool = False,
        note: bool = True,
    ):
        """``value`` checked for its type (and its range, unless ``checked_by``), numbers as floats.

        The error (``error``, a :class:`~fabtiles.FabtilesError`) says
        ``"{prefix}{name} must be {describe()}, got {value!r}"`` (a choice not among its
        values: ``"{prefix}{name} = {value!r} is not valid, must be one of: ..."``) and
        carries ``param`` (default: the key's name). ``None`` passes (the key was not given)
        unless ``required``; ``note=False`` leaves the key's note out of the message.

        >>> key("output.inlay_fit_mm").check(0.6, note=False)
        Traceback (most recent call last):
        ...
        fabtiles.core.errors.ParameterError: inlay_fit_mm must be a number of mm from -0.5 to 0.5, got 0.6
        """
        name = name or self.name
        param = param or self.name
        if value is None and not required:
            return None
        if self.type == "colour":
            return self._check_colour(value, name=name, prefix=prefix, error=error, param=param)
        if self.type == "choice":
            ok = self._choice_ok(value, name=name, prefix=prefix, error=error, param=param)
        elif self.type in ("boolean", "integer", "number", "string"):
            ok = self._type_ok(value)
        else:
            raise ParameterError(
                f"{self.path} is a {self.type}: its value is checked where it is read, not by Key.check",
                param=self.path,
            )
        if not ok:
            raise error(f"{prefix}{name} must be {self.describe(note=note)}, got {value!r}", param=param)
        return float(value) if self.type == "number" else value

    def _type_ok(self, value) -> bool:
        """Whether ``value`` is of the key's plain type (boolean, integer, number, string), a number in its range
        (unless ``checked_by``)."""
        if self.type == "boolean":
            return isinstance(value, bool)
        if self.type == "string":
            return isinstance(value, str)
        kinds = numbers.Integral if self.type == "integer" else numbers.Real
        ok = isinstance(value, kinds) and not isinstance(value, bool)
        if ok and self.range is not None and self.checked_by is None:
            ok = value in self.range
        return ok

    def _choice_ok(self, value, *, name: str, prefix: str, error, param: str) -> bool:
        """Whether ``value`` is of a choice's type; a value not among the choices (unless ``checked_by``) raises,
        with the nearest."""
        ok = isinstance(value, str) if self.checked_by else isinstance(value, (str, int, float))
        if ok and self.checked_by is None and value not in self.choice_values():
            hint = did_you_mean(value, self.choice_values())
            raise error(
                f"{prefix}{name} = {value!r} is not valid{f' ({hint})' if hint else ''}, must be one of: "
                f"{', '.join(self.choice_values())}",
                param=param,
            )
        return ok

    def _check_colour(self, value, *, name: str, prefix: str, error, param: str):
        """A colour value checked by the check its layer registered."""
        if self.type not in _TYPE_CHECKS:
            raise LookupError(
                f"the {self.type} values of {self.path} are checked by a layer that "
                f"registers the check, and none is imported"
            )
        try:
            _TYPE_CHECKS[self.type](value, param=name)
        except ParameterError as exc:
            raise error(f"{prefix}{exc}", param=param) from None
        return value


MOTIF_REQUIRED = ("n", "radii")
"""The keys a motif without a preset needs."""

GAP_MOTIF: dict[str, Any] = {"n": 6, "radii": (0.5, 1.0)}
"""The gap circles' motif when a packing names none (a table of motif keys)."""


SURFACE_SHAPES = ("flat", "cylinder", "stamp")
"""``[surface] shape``: a flat tile, the pattern round a cylinder, or a clay stamp (a relief on a block)."""

SURFACE_FITS = ("packing", "diameter")
"""``[surface] fit``: what changes so the circumference holds a whole number of periods."""

ROLLER_BORE_MM = 8.4
"""A roller's axle hole (mm) unless the design gives ``bore_mm``: an 8 mm dowel or rod, with room to turn."""

ROLLER_RIM_MM = 3.0
"""A roller's (relief, deboss) band at each end (mm) unless the design gives ``rim_mm``."""

SHADE_RIM_MM = 5.0
"""A shade's (pierced) closed rim at each end (mm) unless the design gives ``rim_mm``."""

CYLINDER_REQUIRED = ("diameter", "length")
"""The ``[surface]`` keys a cylinder needs."""

STAMP_KEYS = ("mirror", "block_mm", "grip_mm", "groove_mm")
"""The ``[surface]`` keys of a clay stamp (``shape = "stamp"``); the others are a cylinder's."""

STRIP_TILE_KEYS = ("outline", "size", "frame", "corner_radius", "border_mm")
"""The ``[tile]`` keys a cylinder sets itself: its unrolled strip is a rectangle, closed by rims, not a frame."""


PACKED = ("packing", ("hex", "square", "archimedean"))
"""The form's condition of a packing's controls: a packing there is (not ``packing=none``)."""


def _motif_keys(section: str) -> tuple[Key, ...]:
    """The keys of a motif table: ``[motif]``, and the ``gap_motif`` and ``[packing.motifs]`` tables' entries."""
    star = "pattern"
    angle: dict[str, Any] = dict(type="number", unit="degrees", checked_by=star)
    return (
        Key(
            section=section,
            name="preset",
            type="string",
            help="a preset name (`fabtiles presets` lists them; see construction.md)",
            choices="pattern",
            widget=Widget(kind="select", label="Preset"),
        ),
        Key(
            section=section,
            name="n",
            type="integer",
            range=Range(3, 120),
            help="points on each circle",
            checked_by=star,
            widget=Widget(kind="slider", label="n (points)", min=3, max=48, step=1, group="motif-sliders"),
        ),
        Key(
            section=section,
            name="radii",
            type="numbers",
            range=Range(0, None, min_open=True),
            note="2 to 24 numbers > 0",
            help="the circles' radii",
            checked_by=star,
            # only the radii's ratios count (the motif is scaled to its circle): the gallery's tilings give
            # 0.5 and 1, the presets up to 226, so the travel holds both
            widget=Widget(kind="slider", label="r", min=0.05, max=400, step=0.05, group="radii-sliders"),
        ),
        Key(
            section=section,
            name="alpha",
            help="offset of the special points",
            **angle,
            widget=Widget(kind="slider", label="alpha (deg)", min=-90, max=90, step=0.5, group="motif-sliders"),
        ),
        Key(
            section=section,
            name="spr",
            type="number",
            help="the special points lie at `r(special) - spr`",
            checked_by=star,
            widget=Widget(kind="slider", label="spr", min=-300, max=300, step=1, group="motif-sliders"),
        ),
        Key(
            section=section,
            name="special",
            type="integer",
            range=Range(2, None),
            note="2..S",
            default_text="none (a star)",
            help="the special circle, 1-based (omit for a plain star)",
            checked_by=star,
            widget=Widget(kind="select", label="Special circle"),
        ),
        Key(
            section=section,
            name="rotation",
            help="added to every angle",
            default=0.0,
            **angle,
            widget=Widget(kind="slider", label="rotation (deg)", min=-180, max=180, step=0.5, group="motif-sliders"),
        ),
    )


MOTIF = _motif_keys("motif")

_TILE = "geometry"
_ARCH = 'kind = "archimedean"'
_GIRIH = 'kind = "girih"'
_ARCH_OR_GIRIH = 'kind = "archimedean" or "girih"'
_HANKIN = 'method = "hankin"'
_HANKIN_WHEN = (("packing", ("archimedean",)), ("method", ("hankin",)))
_INLAY_WHEN = (("laser_mode", ("inlay",)),)
_INLAY = f'{_INLAY_WHEN[0][0]} = "{_INLAY_WHEN[0][1][0]}"'  # the manual's words for the same
_HEX_SQUARE = (("packing", ("hex", "square")),)
_PACKING = "pattern"
_HEIGHT_RANGE = Range(0, 1000, min_open=True)
_PRINT = ("print",)
FLAT_WHEN = ("shape", ("flat", "stamp"))
"""The web form's condition of the tile's outline, size and frame: a flat tile's or a stamp's (a cylinder's
tile is its unrolled strip, sized by the ``[surface]``)."""
_CYLINDER_WHEN = (("shape", ("cylinder",)),)
_STAMP_WHEN = (("shape", ("stamp",)),)
_ROLLER_WHEN = (*_CYLINDER_WHEN, ("print_style", ("relief", "deboss")))
_SHADE_WHEN = (*_CYLINDER_WHEN, ("print_style", ("pierced",)))
_PARQUET_WHEN = (*_HANKIN_WHEN, FLAT_WHEN, ("seamless", ("false",)), ("parquet", ("true",)))
"""The web form's condition of a parquet deformation's controls: Hankin's rays on a tile that need not repeat
(a seamless tile and a cylinder's strip refuse one), with the page's own box "vary across the tile" ticked."""


def _height(name: str, label: str, what: str, styles: tuple[str, ...]) -> Key:
    """A print height, shown on the form for the print ``styles`` that have it."""
    return Key(
        section="output",
        name=name,
        type="number",
        unit="mm",
        range=_HEIGHT_RANGE,
        default_text="the profile's",
        help=f"print height: {what}, overriding the printer profile's",
        widget=Widget(
            kind="number", label=label, min=0, step=0.1, placeholder="profile", when=(("print_style", styles),)
        ),
        option=BuildOption(name=name, families=_PRINT),
    )


KEYS: tuple[Key, ...] = MOTIF + (
    # [packing]
    Key(
        section="packing",
        name="kind",
        type="choice",
        default="hex",
        query="packing",
        choices=("hex", "square", "archimedean", "girih"),
        help="`hex`, `square`, `archimedean` or `girih` (girih.md)",
        widget=Widget(
            kind="select",
            label="Kind",
            labels=(
                ("hex", "hexagonal (tangent circles)"),
                ("archimedean", "Archimedean tiling (incircles)"),
                ("girih", "girih tiles (strapwork)"),
            ),
            extra=(("none", "none: one motif"),),
        ),
    ),
    Key(
        section="packing",
        name="radius",
        type="number",
        unit="mm",
        range=Range(0, None, min_open=True),
        default=12.5,
        help="radius of the big circles (hex, square)",
        checked_by=_PACKING,
        widget=Widget(
            kind="slider", label="radius R (mm)", min=3, max=100, step=0.5, group="packing-sliders", when=_HEX_SQUARE
        ),
    ),
    Key(
        section="packing",
        name="outline_circles",
        type="boolean",
        default=False,
        help="also stroke the packing circles",
        widget=Widget(kind="checkbox", label="Outline circles", when=(PACKED,)),
    ),
    Key(
        section="packing",
        name="fill",
        type="number",
        range=Range(0, 1, min_open=True),
        default=1.0,
        help="motif extent / circle radius",
        checked_by=_PACKING,
    ),
    Key(
        section="packing",
        name="gap_motif",
        type="motif",
        default=GAP_MOTIF,
        default_text="`{ n = 6, radii = [0.5, 1.0] }`",
        note="a table like [motif] or a preset name",
        query=None,
        help="the gap circles' motif: a table like `[motif]`, or a preset name; its keys are the web's "
        "`gap_` parameters",
    ),
    Key(
        section="packing",
        name="seamless",
        type="boolean",
        default=False,
        help="fit the radius (and a rectangle's height) so the tile repeats seamlessly",
        widget=Widget(kind="checkbox", label="Seamless", when=(("packing", (*PACKED[1], "girih")),)),
    ),
    Key(
        section="packing",
        name="tiling",
        type="choice",
        choices="pattern",
        requires=_ARCH,
        checked_by="pattern",
        help='the vertex configuration, e.g. `"4.8.8"`',
        widget=Widget(kind="select", label="Tiling"),
    ),
    Key(
        section="packing",
        name="edge",
        type="number",
        unit="mm",
        range=Range(0, None, min_open=True),
        default=20.0,
        requires=_ARCH_OR_GIRIH,
        help="the polygons' edge length (instead of `radius`)",
        checked_by="pattern",
        widget=Widget(
            kind="slider",
            label="edge a (mm)",
            min=3,
            max=100,
            step=0.5,
            group="packing-sliders",
            when=(("packing", ("archimedean", "girih")),),
        ),
    ),
    Key(
        section="packing",
        name="girih_pattern",
        type="choice",
        choices="pattern",
        requires=_GIRIH,
        checked_by="pattern",
        help='the girih pattern, e.g. `"decagon-bowtie"` (girih.md)',
        widget=Widget(kind="select", label="Girih pattern", when=(("packing", ("girih",)),)),
    ),
    Key(
        section="packing",
        name="girih_level",
        type="integer",
        range=Range(0, None),
        default=0,
        requires=_GIRIH,
        help="times the pattern is subdivided into girih tiles the golden ratio squared smaller, `edge` "
        "being the smallest tiles' (0: the pattern's own tiles; decagon-bowtie and hexagons; girih.md)",
        widget=Widget(
            kind="number",
            label="Subdivision level",
            min=0,
            max=5,
            step=1,
            placeholder="0",
            when=(("packing", ("girih",)),),
        ),
    ),
    Key(
        section="packing",
        name="motifs",
        type="motifs",
        query=None,
        requires=_ARCH,
        help="`[packing.motifs]`, a motif per polygon kind keyed by its sides "
        '(`8 = "table3-3"`, `4 = { n = 8, radii = [1, 2] }`); `[motif]` fills the kinds not listed '
        '(with `method = "hankin"` the kinds not listed take Hankin\'s rays); on the web, `motif_<sides>`',
    ),
    Key(
        section="packing",
        name="method",
        type="choice",
        default="motifs",
        requires=_ARCH,
        choices="pattern",
        checked_by="pattern",
        help='`"motifs"`: the paper\'s motifs in the incircles and gap circles; `"hankin"`: Hankin\'s '
        "polygons in contact, two rays from each edge at `contact_angle` (see hankin.md)",
        widget=Widget(
            kind="select",
            label="Method",
            labels=(("motifs", "the paper's motifs (incircles)"), ("hankin", "Hankin's polygons in contact")),
            when=(("packing", ("archimedean",)),),
        ),
    ),
    Key(
        section="packing",
        name="contact_angle",
        type="number",
        unit="degrees",
        range=Range(0, 90, min_open=True, max_open=True),
        default=60.0,
        requires=_HANKIN,
        checked_by="pattern",
        help="the rays' angle to their edge; with a gap, at most the tiling's limit (hankin.md)",
        widget=Widget(
            kind="slider",
            label="contact angle (deg)",
            min=1,
            max=89,
            step=0.5,
            group="packing-sliders",
            when=_HANKIN_WHEN,
        ),
    ),
    Key(
        section="packing",
        name="contact_gap",
        type="number",
        unit="mm",
        range=Range(0, None),
        default=0.0,
        requires=_HANKIN,
        checked_by="pattern",
        help="the distance along the edge between the two rays' starts (less than the edge)",
        widget=Widget(
            kind="slider", label="contact gap (mm)", min=0, max=20, step=0.1, group="packing-sliders", when=_HANKIN_WHEN
        ),
    ),
    Key(
        section="packing",
        name="contact_angle_to",
        type="number",
        unit="degrees",
        range=Range(0, 90, min_open=True, max_open=True),
        default=None,
        default_text="none",
        requires=_HANKIN,
        checked_by="pattern",
        help="a parquet deformation: the contact angle at the far side of the tile, `contact_angle` "
        "being the near side's; each polygon takes the angle at its centre (hankin.md)",
        widget=Widget(
            kind="slider",
            label="contact angle to (deg)",
            min=1,
            max=89,
            step=0.5,
            group="parquet-sliders",
            when=_PARQUET_WHEN,
        ),
    ),
    Key(
        section="packing",
        name="parquet_direction",
        type="choice",
        default="x",
        requires=_HANKIN,
        choices="pattern",
        help='across which the angle changes: `"x"` left to right, `"y"` bottom to top, `"radial"` from '
        "the centre out to the inscribed circle",
        widget=Widget(
            kind="select",
            label="Direction",
            labels=(("x", "left to right"), ("y", "bottom to top"), ("radial", "centre out")),
            when=_PARQUET_WHEN,
        ),
    ),
    Key(
        section="packing",
        name="parquet_curve",
        type="choice",
        default="linear",
        requires=_HANKIN,
        choices="pattern",
        help='`"linear"`: the angle in proportion to the distance across; `"smooth"`: smoothstep, '
        "settling into each side's angle",
        widget=Widget(
            kind="select",
            label="Curve",
            labels=(("linear", "linear"), ("smooth", "smooth (settles at each side)")),
            when=_PARQUET_WHEN,
        ),
    ),
    # [tile]
    Key(
        section="tile",
        name="outline",
        type="choice",
        default="square",
        choices=("square", "rectangle", "hexagon", "circle"),
        help="`square`, `rectangle`, `hexagon` (pointy-top) or `circle`",
        widget=Widget(kind="select", label="Outline", when=(FLAT_WHEN,)),
    ),
    Key(
        section="tile",
        name="size",
        type="size",
        unit="mm",
        range=Range(0, None, min_open=True),
        default_text="required",
        note="a number or [width, height] in mm",
        query=None,
        help="a number (side, width across flats, diameter), or `[width, height]` for a rectangle; "
        "on the web, `width` and `height`",
        checked_by="geometry",
    ),
    Key(
        section="tile",
        name="frame",
        type="number",
        unit="mm",
        range=Range(0, None),
        default=0.0,
        help="solid margin inside the outline",
        checked_by=_TILE,
        widget=Widget(
            kind="slider", label="frame (mm)", min=0, max=30, step=0.5, group="tile-sliders", when=(FLAT_WHEN,)
        ),
    ),
    Key(
        section="tile",
        name="stroke",
        type="number",
        unit="mm",
        range=Range(0, None, min_open=True),
        default=1.0,
        help="width of each band; at most the packing radius",
        checked_by=_TILE,
        widget=Widget(kind="slider", label="stroke (mm)", min=0.2, max=6, step=0.1, group="tile-sliders"),
    ),
    Key(
        section="tile",
        name="join",
        type="choice",
        default="miter",
        choices=("miter", "round", "bevel"),
        help="`miter`, `round` or `bevel`",
        widget=Widget(kind="select", label="Join"),
    ),
    Key(
        section="tile",
        name="miter_limit",
        type="number",
        range=Range(1, None),
        default=4.0,
        help="in half stroke widths",
        checked_by=_TILE,
        widget=Widget(
            kind="slider",
            label="miter limit",
            min=1,
            max=20,
            step=0.5,
            group="tile-sliders",
            when=(("join", ("miter",)),),
        ),
    ),
    Key(
        section="tile",
        name="corner_radius",
        type="number",
        unit="mm",
        range=Range(0, None),
        default=0.0,
        help="rounds the outline's corners (not a circle's)",
        checked_by=_TILE,
        widget=Widget(
            kind="slider",
            label="corner r (mm)",
            min=0,
            max=30,
            step=0.5,
            group="tile-sliders",
            when=(FLAT_WHEN, ("outline", ("square", "rectangle", "hexagon"))),
        ),
    ),
    Key(
        section="tile",
        name="interlace",
        type="boolean",
        default=False,
        help="weave the strands over and under at every crossing ([interlace.md](interlace.md))",
        widget=Widget(kind="checkbox", label="Interlace"),
    ),
    Key(
        section="tile",
        name="interlace_gap_mm",
        type="number",
        unit="mm",
        range=Range(0, None),
        default_text="a third of the stroke",
        checked_by=_TILE,
        help="gap on each side of an over strand where the under strand passes",
        widget=Widget(
            kind="number",
            label="Interlace gap (mm)",
            min=0,
            step=0.05,
            placeholder="stroke / 3",
            when=(("interlace", ("true",)),),
        ),
    ),
    Key(
        section="tile",
        name="interlace_cut",
        type="boolean",
        default=False,
        help="laser, pierced: cut the under gaps through, leaving tabs; otherwise they are scored or dipped",
        widget=Widget(
            kind="checkbox", label="Cut the gaps", when=(("interlace", ("true",)), ("laser_mode", ("pierced",)))
        ),
    ),
    Key(
        section="tile",
        name="border_mm",
        type="number",
        unit="mm",
        range=Range(0, None),
        default=0.0,
        checked_by=_TILE,
        help="width of a band inside the frame filled with a frieze, a whole number of repeats on each side "
        "([borders.md](borders.md)); 0: none. At most a third of the tile's width inside the frame",
        widget=Widget(
            kind="slider", label="border (mm)", min=0, max=30, step=0.5, group="tile-sliders", when=(FLAT_WHEN,)
        ),
    ),
    Key(
        section="tile",
        name="border_motif",
        type="choice",
        default="stars",
        choices="pattern",
        checked_by="pattern",
        help='the frieze: `"stars"` (eight-point stars joined at the cells\' edges and corners) or `"hankin"` '
        "(Hankin's rays on square cells: eight-point stars and crosses)",
        widget=Widget(
            kind="select",
            label="Border motif",
            labels=(("stars", "stars"), ("hankin", "Hankin's stars and crosses")),
            when=(FLAT_WHEN,),
        ),
    ),
    Key(
        section="tile",
        name="border_angle",
        type="number",
        unit="degrees",
        range=Range(0, 90, min_open=True, max_open=True),
        default_text='the packing\'s `contact_angle` with `method = "hankin"`, else 67.5',
        requires='border_motif = "hankin"',
        checked_by=_TILE,
        help="the contact angle of the hankin frieze's rays",
        widget=Widget(
            kind="number",
            label="Border angle (deg)",
            min=0,
            max=90,
            step=0.5,
            placeholder="67.5",
            when=(FLAT_WHEN, ("border_motif", ("hankin",))),
        ),
    ),
    # [output]
    Key(
        section="output",
        name="formats",
        type="formats",
        default=("svg",),
        choices="export",
        note="a non-empty list",
        query=None,
        help="any of `dxf`, `svg`, `lbrn2` (LightBurn project), `stl`, `3mf`, `step` (the format table of "
        "[architecture.md](architecture.md#the-format-table)), or a format plugin's; not a web parameter: "
        "each download is one format",
    ),
    Key(
        section="output",
        name="laser_profile",
        type="string",
        note="a profile name or path",
        default_text="`laser-3mm-plywood`",
        help="a bundled profile name or a path to a profile file: a laser, or a CNC router or waterjet "
        "(`router-6mm-mdf`, `router-3.175mm-plywood`, `waterjet-1mm-aluminium`). One key for every 2D "
        "cutter, since the DXF/SVG pipeline is the same: a router's files hold the part as its bit makes it "
        "([cnc-and-waterjet.md](cnc-and-waterjet.md)); on the web, a bundled name only",
        widget=Widget(kind="select", label="Cutter profile"),
    ),
    Key(
        section="output",
        name="printer_profile",
        type="string",
        note="a profile name or path",
        default_text="`fdm-0.4mm`",
        help="likewise, for the print formats",
        widget=Widget(kind="select", label="Printer profile"),
    ),
    Key(
        section="output",
        name="laser_mode",
        type="choice",
        choices="machines",
        default_text="the profile's",
        help="`pierced` (cut every edge of the material), `score` (cut the outline, score the centre-lines), "
        "`engrave` (cut the outline, fill the bands on the profile's engrave layer) or `inlay` (a kit: "
        "`<name>-lattice` and `<name>-pieces` files, see [inlay.md](inlay.md))",
        widget=Widget(kind="select", label="Laser mode", labels=(("inlay", "inlay kit"),)),
        option=BuildOption(name="mode", families=("cut",)),
    ),
    Key(
        section="output",
        name="print_style",
        type="choice",
        choices="machines",
        default_text="the profile's",
        help="`relief`, `pierced`, `deboss` or `mosaic` (a plate with the bands and "
        "every face on it, a part per colour: see [colours.md](colours.md))",
        widget=Widget(kind="select", label="Print style"),
        option=BuildOption(name="style", families=_PRINT),
    ),
    _height("base_mm", "Base (mm)", "the plate under the bands", ("relief", "deboss")),
    _height("relief_mm", "Relief (mm)", "the bands above the plate (relief)", ("relief",)),
    _height("pierced_mm", "Pierced (mm)", "a pierced tile's thickness", ("pierced",)),
    _height("deboss_mm", "Deboss (mm)", "the grooves' depth (deboss)", ("deboss",)),
    Key(
        section="output",
        name="mosaic_inset_mm",
        type="number",
        unit="mm",
        range=Range(0, 1000),
        default_text="0",
        checked_by="geometry",
        note="below relief_mm",
        help="`print_style = \"mosaic\"`: how far the faces' tops sit below the bands' (0: flush; more: the bands "
        "stand proud, cloisonne style); less than the relief height",
        widget=Widget(kind="number", label="Mosaic inset (mm)", min=0, step=0.1, when=(("print_style", ("mosaic",)),)),
        option=BuildOption(name="mosaic_inset_mm", families=_PRINT),
    ),
    Key(
        section="output",
        name="name",
        type="string",
        default_text="the file's stem",
        help="the output files' name (a plain file name: letters, digits, `. _ -` and spaces)",
        widget=Widget(kind="text", label="File name", placeholder="the design's"),
    ),
    Key(
        section="output",
        name="fill_small_holes",
        type="boolean",
        default=True,
        help="fill what each machine cannot make instead of reporting it: in the cutter files the holes narrower "
        "than the cutter profile's `min_hole_mm` (a router's: those its bit cannot enter), in the print files "
        "the openings narrower than the printer profile's `min_hole_mm` (default its nozzle); every summary "
        "says how many it filled for which",
        widget=Widget(kind="checkbox", label="Fill small holes"),
        option=BuildOption(name="fill_small_holes", families=("cut", "print")),
    ),
    Key(
        section="output",
        name="pieces",
        type="boolean",
        default=True,
        help="a tile larger than its machine's bed (either way round) is made as pieces that lock "
        "together, each on the bed with the profile's `bed_margin_mm`: `<name>-piece-01.dxf`, ..., "
        "`<name>-piece-01.stl`, ..., with `<name>-assembly.svg` and `.json` ([pieces.md](pieces.md)); "
        "`false`: such a tile is refused by a cutter, larger than the bed, and a printer warns `bed_size`",
        option=BuildOption(name="pieces", families=("cut", "print")),
    ),
    Key(
        section="output",
        name="pieces_sheets",
        type="boolean",
        default=False,
        help="a panel cut as pieces (`pieces`): its pieces also nested onto sheets of the bed's size, "
        "`<name>-sheet-1.dxf`, ..., as `fabtiles nest` nests tiles; the packer takes a few seconds a sheet",
        option=BuildOption(name="pieces_sheets", families=("cut",)),
    ),
    Key(
        section="output",
        name="inlay",
        type="boolean",
        default=False,
        help="a deboss tile's 3MF gets a second part, `inlay`, filling the grooves flush (two-colour inlay "
        'print); needs `print_style = "deboss"`',
        widget=Widget(kind="checkbox", label="Inlay part (deboss 3MF)", when=(("print_style", ("deboss",)),)),
        option=BuildOption(name="inlay", families=("3mf",)),
    ),
    Key(
        section="output",
        name="threemf_layout",
        type="choice",
        default="volumes",
        choices=("volumes", "components"),
        help='how the 3MF holds its parts: `"volumes"`, one object cut into named parts for PrusaSlicer, '
        'Bambu Studio and OrcaSlicer; `"components"`, one object of components (each part its own mesh '
        "with its Cura extruder) for UltiMaker Cura, which Bambu Studio and OrcaSlicer also read as one "
        "object of parts and PrusaSlicer as separate objects",
        widget=Widget(
            kind="select",
            label="3MF for",
            labels=(("volumes", "PrusaSlicer, Bambu Studio, OrcaSlicer"), ("components", "UltiMaker Cura")),
        ),
        option=BuildOption(name="layout", families=("3mf",)),
    ),
    Key(
        section="output",
        name="inlay_fit_mm",
        type="number",
        unit="mm",
        range=Range(-0.5, 0.5),
        note="positive: a press fit, negative: play",
        default_text="the laser profile's",
        requires=_INLAY,
        help="each piece is grown from its hole by this much; beyond half a "
        "millimetre a piece no longer fits its hole at all (see [inlay.md](inlay.md))",
        widget=Widget(
            kind="number",
            label="Inlay kit: fit (mm)",
            min=-0.5,
            max=0.5,
            step=0.05,
            placeholder="profile",
            when=_INLAY_WHEN,
        ),
        option=BuildOption(name="inlay_fit_mm", families=("cut",)),
    ),
    Key(
        section="output",
        name="inlay_pieces",
        type="choice",
        default="registration",
        choices=("registration", "nested"),
        requires=_INLAY,
        help="`\"registration\"` (each piece at its hole's place: the pieces' sheet as big as the tile) or "
        '`"nested"` (the pieces packed tight, half turns only for the grain, each with its face class\'s '
        "letter scored on it and in its lattice hole; see [inlay.md](inlay.md))",
        widget=Widget(
            kind="select",
            label="Inlay kit: pieces",
            labels=(("registration", "in registration"), ("nested", "nested, lettered")),
            when=_INLAY_WHEN,
        ),
        option=BuildOption(name="inlay_pieces", families=("cut",)),
    ),
    Key(
        section="output",
        name="inlay_base",
        type="choice",
        default="pierced",
        choices=("pierced", "pocket"),
        requires=_INLAY,
        help='`"pierced"` (the lattice\'s holes cut through) or `"pocket"` (engraved as pockets on the engrave layer)',
        widget=Widget(
            kind="select",
            label="Inlay kit: lattice",
            labels=(("pierced", "holes cut through"), ("pocket", "pockets engraved")),
            when=_INLAY_WHEN,
        ),
        option=BuildOption(name="inlay_base", families=("cut",)),
    ),
    Key(
        section="output",
        name="tab_mm",
        type="number",
        unit="mm",
        range=Range(0, 5),
        default=0.0,
        note="0: no tabs; else more than the kerf",
        help="holding tabs (laser only): each part's outer cut leaves `tabs_per_part` uncut gaps this long, "
        "measured along the cut, so the part stays in the sheet on a honeycomb bed; the bridge left is "
        "`tab_mm` less the kerf wide; holes get none; a router's or waterjet's CAM adds its own "
        "([laser-cutting.md](laser-cutting.md#holding-tabs))",
        widget=Widget(kind="number", label="Holding tabs (mm)", min=0, max=5, step=0.1, placeholder="none"),
        option=BuildOption(name="tab_mm", families=("cut",)),
    ),
    Key(
        section="output",
        name="tabs_per_part",
        type="integer",
        range=Range(1, 64),
        default=4,
        help="how many holding tabs each part's outer cut gets when `tab_mm` > 0, spread evenly round it and "
        "slid onto straight stretches away from corners; a part shorter round than three tab lengths per "
        "tab gets fewer",
        widget=Widget(kind="number", label="Tabs per part", min=1, max=64, step=1, placeholder="4"),
        option=BuildOption(name="tabs_per_part", families=("cut",)),
    ),
    # [colour]
    Key(
        section="colour",
        name="by",
        type="choice",
        default="none",
        choices=("none", "shape"),
        query="colour_by",
        help='`"shape"`: the faces of the pattern (the openings between the bands) grouped into classes of '
        'congruent shapes, lettered A, B, ... by total area, each class its own colour; `"none"`: every '
        "face one class, A (the two colours of band and face)",
        widget=Widget(kind="select", label="Colour faces by", labels=(("none", "one colour"), ("shape", "shape"))),
    ),
    Key(
        section="colour",
        name="palette",
        type="choice",
        default="zellige",
        choices="designs",
        help="the named palette giving the band's, the base's and the classes' colours unless set below "
        "([colours.md](colours.md) says where each comes from)",
        widget=Widget(kind="select", label="Palette"),
    ),
    Key(
        section="colour",
        name="band_colour",
        type="colour",
        default_text="the palette's",
        note="#rrggbb, a palette's or a CSS colour name",
        help="the bands' colour (the strapwork): a print's bands, a kit's lattice",
        widget=Widget(kind="colour", label="Band colour"),
    ),
    Key(
        section="colour",
        name="base_colour",
        type="colour",
        default_text="the palette's",
        note="#rrggbb, a palette's or a CSS colour name",
        help="the base plate's colour (relief, mosaic and deboss prints)",
        widget=Widget(kind="colour", label="Base colour"),
    ),
    Key(
        section="colour",
        name="faces",
        type="colours",
        default_text="the palette's, in class order",
        note="a table of class letters to colours",
        query=None,
        help='`[colour.faces]` `A = "navy"`, `B = "#c8553d"`: a colour per face class; classes given one '
        "colour share a material (a filament, a wood), so six classes fit a four-slot AMS as four colours; "
        '`"band"` or `"base"` gives a class the bands\' or the base\'s colour (it joins that part)',
    ),
    Key(
        section="colour",
        name="shaded",
        type="string",
        default="",
        note='class letters ("A C") or "all"',
        widget=Widget(kind="text", label="Shaded on a laser", placeholder="all, or letters: B D"),
        help="the face classes a laser engraves in shades, each on a layer of its own at a power from its "
        "colour's darkness (laser modes pierced, score and engrave; a pierced cut keeps them, engraved, "
        "instead of cutting them out): see [laser-cutting.md](laser-cutting.md#shaded-engraving)",
    ),
    Key(
        section="colour",
        name="shades",
        type="shades",
        default_text="derived from each class's colour",
        note="a table of class letters to engrave settings",
        query=None,
        help="`[colour.shades]` `C = { power_pct = 40 }`: an engraved class's `power_pct`, `speed_mm_s`, "
        "`line_interval_mm` or `passes`, in place of those derived from its colour",
    ),
    # [surface]
    Key(
        section="surface",
        name="shape",
        type="choice",
        default="flat",
        choices=SURFACE_SHAPES,
        widget=Widget(
            kind="select",
            label="Shape",
            labels=(
                ("flat", "a flat tile"),
                ("cylinder", "a cylinder: roller or lampshade"),
                ("stamp", "a clay stamp"),
            ),
        ),
        help='`"flat"`: a tile; `"cylinder"`: the pattern wrapped round a cylinder, seamless: a texture roller '
        '(`relief`, `deboss`) or a lampshade (`pierced`), printed standing on an end; `"stamp"`: a clay stamp, '
        "the relief mirrored on a block with a finger grip, printed pattern up ([surfaces.md](surfaces.md))",
    ),
    Key(
        section="surface",
        name="diameter",
        type="number",
        unit="mm",
        range=Range(0, None, min_open=True),
        default_text="required for a cylinder",
        widget=Widget(
            kind="slider", label="diameter (mm)", min=10, max=250, step=1, group="surface-sliders", when=_CYLINDER_WHEN
        ),
        help="the cylinder's diameter at the pattern's outer surface; its circumference holds a whole number "
        "of the pattern's periods (see `fit`)",
    ),
    Key(
        section="surface",
        name="length",
        type="number",
        unit="mm",
        range=Range(0, None, min_open=True),
        default_text="required for a cylinder",
        widget=Widget(
            kind="slider", label="length (mm)", min=10, max=300, step=1, group="surface-sliders", when=_CYLINDER_WHEN
        ),
        help="the cylinder's length along its axis, the rims included; at most the printer profile's `height_mm`",
    ),
    Key(
        section="surface",
        name="fit",
        type="choice",
        default="packing",
        choices=SURFACE_FITS,
        widget=Widget(
            kind="select",
            label="Fit",
            labels=(("packing", "the packing to the diameter"), ("diameter", "the diameter to the packing")),
            when=_CYLINDER_WHEN,
        ),
        help='how the circumference is made a whole number of periods: `"packing"` changes the packing\'s '
        '`radius` (or `edge`) and keeps the diameter; `"diameter"` keeps the packing and changes the diameter',
    ),
    Key(
        section="surface",
        name="mirror",
        type="boolean",
        default_text="true for a stamp and a roller (relief, deboss), false for a shade (pierced)",
        widget=Widget(
            kind="select",
            label="Mirror",
            extra=(
                ("", "by the style"),
                ("true", "mirrored"),
                ("false", "not mirrored"),
            ),
            when=(("shape", ("cylinder", "stamp")),),
        ),
        help="mirror the pattern (round a cylinder, or a stamp's face), so that what a roller or a stamp leaves "
        "in clay reads as designed (an imprint is the mirror of the surface that made it)",
    ),
    Key(
        section="surface",
        name="bore_mm",
        type="number",
        unit="mm",
        range=Range(0, None, min_open=True),
        default_text=f"{ROLLER_BORE_MM:g}",
        widget=Widget(kind="number", label="Bore (mm)", min=0, step=0.1, placeholder="8.4", when=_ROLLER_WHEN),
        help="a roller's (relief, deboss) axle hole through its length; the default takes an 8 mm dowel or "
        "steel rod with room to turn, printed holes coming out a little small",
    ),
    Key(
        section="surface",
        name="rim_mm",
        type="number",
        unit="mm",
        range=Range(0, None),
        default_text=f"{ROLLER_RIM_MM:g} on a roller, {SHADE_RIM_MM:g} on a shade",
        widget=Widget(kind="number", label="Rims (mm)", min=0, step=0.5, placeholder="3 or 5", when=_CYLINDER_WHEN),
        help="a closed band at each end of the cylinder: a shade's rims (pierced), a roller's bands raised to "
        "the pattern's top that roll on the clay as depth guides (relief) or plain plate (deboss); 0: none",
    ),
    Key(
        section="surface",
        name="lamp_fitting_mm",
        type="number",
        unit="mm",
        range=Range(0, None, min_open=True),
        default_text="none",
        widget=Widget(kind="number", label="Lamp fitting (mm)", min=0, step=1, placeholder="none", when=_SHADE_WHEN),
        help="a pierced shade: a ring inside its lower end holding a lamp fitting of this diameter "
        "(40 for an E27 lampholder, 28 for an E14)",
    ),
    Key(
        section="surface",
        name="pointed_tops",
        type="boolean",
        default=False,
        widget=Widget(kind="checkbox", label="Pointed tops", when=_CYLINDER_WHEN),
        help="a cylinder's openings (a shade's holes, a roller's grooves or gaps) given a pointed top at the printer "
        "profile's `max_overhang_deg`, a teardrop over a round hole, so the wall prints standing without supports; "
        "the print check finds the ceilings that still overhang",
    ),
    Key(
        section="surface",
        name="block_mm",
        type="number",
        unit="mm",
        range=Range(0, 200, min_open=True),
        default=20.0,
        widget=Widget(kind="number", label="Block (mm)", min=1, step=1, placeholder="20", when=_STAMP_WHEN),
        help="a stamp's block: its height from the bed to the relief's plate, the finger groove in its sides",
    ),
    Key(
        section="surface",
        name="grip_mm",
        type="number",
        unit="mm",
        range=Range(0, 20, min_open=True),
        default=3.0,
        widget=Widget(kind="number", label="Finger groove (mm)", min=0.5, step=0.5, placeholder="3", when=_STAMP_WHEN),
        help="how deep a stamp's finger groove goes into the block's sides; its chamfers keep to the printer "
        "profile's overhang limit, so it prints without supports",
    ),
    Key(
        section="surface",
        name="groove_mm",
        type="number",
        unit="mm",
        range=Range(0, 100),
        default=4.0,
        widget=Widget(kind="number", label="Groove middle (mm)", min=0, step=0.5, placeholder="4", when=_STAMP_WHEN),
        help="the height of a stamp's finger groove's straight middle, between its two chamfers (0: a V)",
    ),
)
"""Every design key, section by section in the order of a design file."""

_GAP = (PACKED, ("method", ("motifs",)))  # gap circles: the paper's method only (Hankin's rays leave no gaps)
_ROSETTE = (*_GAP, ("gap_rosette", ("true",)))  # the page's gap rosette box: special circle 2
GAP_WIDGETS = {
    "n": Widget(kind="slider", label="gap n", min=3, max=24, step=1, group="packing-sliders", when=_GAP),
    "rotation": Widget(
        kind="slider", label="gap rotation (deg)", min=-180, max=180, step=0.5, group="packing-sliders", when=_GAP
    ),
    "alpha": Widget(
        kind="slider", label="gap alpha (deg)", min=-90, max=90, step=0.5, group="packing-sliders", when=_ROSETTE
    ),
    "spr": Widget(kind="slider", label="gap spr", min=-2, max=2, step=0.01, group="packing-sliders", when=_ROSETTE),
}
"""The web form's controls of the gap motif's keys (``gap_n``, ...): its circles' radii are about 1, so its
sliders travel less than the motif's."""

SIZE_WIDGETS = {
    "width": Widget(
        kind="slider", label="width (mm)", min=20, max=600, step=1, group="tile-sliders", when=(FLAT_WHEN,)
    ),
    "height": Widget(
        kind="slider",
        label="height (mm)",
        min=20,
        max=400,
        step=1,
        group="tile-sliders",
        when=(FLAT_WHEN, ("outline", ("rectangle",))),
    ),
}
"""The web form's controls of ``[tile] size``: its ``width`` and ``height`` parameters."""

CALL_OPTIONS = (
    BuildOption(
        name="dxf_version",
        families=("cut",),
        help="string, `R12`, `R2000`, `R2004`, `R2007`, `R2010`, `R2013` or `R2018` (default: the cutter "
        "profile's): the DXF version",
    ),
    BuildOption(
        name="kerf_mm",
        families=("cut",),
        help="number >= 0 (mm; default: the cutter profile's): the cut's width, each contour offset by half of it",
    ),
    BuildOption(
        name="colours",
        families=("cut", "print"),
        help="a `fabtiles.Colours` (the `[colour]` section's keys: `by`, `palette`, `band_colour`, "
        '`base_colour`, `faces`, `shaded`, `shades`): the faces classed and coloured, for `style="mosaic"`, the '
        "parts' colours, an inlay kit's pieces by colour and a laser's shaded classes (see docs/colours.md)",
    ),
)
"""Build options of the export API that no design key sets (the cutter profile's, overridden per call)."""

_BY_PATH = {k.path: k for k in KEYS}

_CHOICES: dict[str, tuple] = {}
"""The valid values of the keys whose ``choices`` name a layer, as the layer registered them."""

_CHECKS: dict[str, Callable] = {}
"""The code that checks the range of the keys whose ``checked_by`` names a layer, as it registered it."""

_TYPE_CHECKS: dict[str, Callable] = {}
"""The parser of each value type whose check belongs to a layer above (``colour``)."""


def register_choices(values, *paths: str) -> None:
    """Register ``values`` as the valid values of the keys at ``paths``.

    Called when it is imported by the module that owns the values (the tilings' module its
    tilings), so the schema names no module above it.

    >>> register_choices(("x",), "tile.stroke")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: tile.stroke's choices are not a layer's, it takes no registered values
    """
    for path in paths:
        k = key(path)
        if not isinstance(k.choices, str):
            raise ParameterError(f"{k.path}'s choices are not a layer's, it takes no registered values", param="path")
        _CHOICES[k.path] = tuple(values)


def register_check(check: Callable, *paths: str) -> None:
    """Register ``check`` as the code that checks the range of the keys at ``paths`` (their ``checked_by``).

    >>> register_check(print, "tile.outline")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: tile.outline is checked by the schema, it takes no registered check
    """
    for path in paths:
        k = key(path)
        if k.checked_by is None:
            raise ParameterError(f"{k.path} is checked by the schema, it takes no registered check", param="path")
        _CHECKS[k.path] = check


def register_type(type_: str, parse: Callable) -> None:
    """Register ``parse(value, param=name)`` as the check of the values of type ``type_`` (raises a ParameterError).

    >>> register_type("number", float)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: a value type whose check is registered must be one of: colour, got 'number'
    """
    if type_ not in ("colour",):
        raise ParameterError(
            f"a value type whose check is registered must be one of: colour, got {type_!r}", param="type_"
        )
    _TYPE_CHECKS[type_] = parse


def key(path: str) -> Key:
    """The key at ``"section.name"`` (``"packing.gap_motif.n"``: the motif key ``n``).

    >>> key("tile.stroke").unit
    'mm'
    """
    parts = path.split(".")
    if len(parts) == 3 and parts[0] == "packing" and parts[1] in ("gap_motif", "motifs"):
        path = f"motif.{parts[2]}"
    if path not in _BY_PATH:
        raise ParameterError(f"{path!r} is not a design key, must be one of: {', '.join(_BY_PATH)}", param="key")
    return _BY_PATH[path]


def section_keys(section: str) -> tuple[Key, ...]:
    """The keys of ``section``, in order.

    >>> [k.name for k in section_keys("motif")][:3]
    ['preset', 'n', 'radii']
    """
    if section not in SECTIONS:
        raise ParameterError(f"{section!r} is not a section, must be one of: {', '.join(SECTIONS)}", param="section")
    return tuple(k for k in KEYS if k.section == section)


def names(section: str) -> tuple[str, ...]:
    """The key names of ``section``, in order (what a design file's section may hold)."""
    return tuple(k.name for k in section_keys(section))


def build_options(family: str) -> tuple[str, ...]:
    """The export API's option names of ``family`` (``"cut"``, ``"print"`` or ``"3mf"``).

    The 3MF takes the print's options and its own.

    >>> build_options("cut")
    ('mode', 'dxf_version', 'kerf_mm', 'fill_small_holes', 'pieces', 'pieces_sheets', 'inlay_fit_mm', 'inlay_pieces', 'inlay_base', 'tab_mm', 'tabs_per_part', 'colours')
    """  # noqa: E501 - a doctest's lines are as Python prints them
    wanted = _family(family)
    mine = [k.option.name for k in KEYS if k.option is not None and set(wanted) & set(k.option.families)]
    calls = [o.name for o in CALL_OPTIONS if set(wanted) & set(o.families)]
    last = [c for c in calls if c == "colours"]  # how the tile is coloured: after the machine's options
    calls = [c for c in calls if c != "colours"]
    return tuple(dict.fromkeys(mine[:1] + calls + mine[1:] + last))  # the mode (or style) first, as the API lists them


def option_keys(family: str) -> tuple[Key, ...]:
    """The design keys that are build options of ``family`` (the :class:`~fabtiles.making.BuildOptions` a design gives).

    >>> [k.name for k in option_keys("3mf")][-2:]
    ['inlay', 'threemf_layout']
    """
    wanted = _family(family)
    return tuple(k for k in KEYS if k.option is not None and set(wanted) & set(k.option.families))


def api_options_doc() -> str:
    """The export API's keyword options, each with its files, type, default and meaning (``help(Tile.export)``).

    >>> print(api_options_doc().splitlines()[0])
    Options for cutter files (.dxf, .svg, .lbrn2):
    """

    def plain(text: str) -> str:
        return re.sub(r"\[([^\]]+)\]\([^)]+\)", r"\1", text).replace("`", "")

    out = []
    for family, files in (
        ("cut", "cutter files (.dxf, .svg, .lbrn2)"),
        ("print", "print files (.stl, .3mf, .step)"),
        ("3mf", ".3mf files only"),
    ):
        out.append(f"Options for {files}:")
        calls = {o.name: o for o in CALL_OPTIONS if family in o.families}
        keys = {k.option.name: k for k in KEYS if k.option is not None and family in k.option.families}
        for name in build_options(family):
            if name not in calls and name not in keys:
                continue  # the 3MF's list repeats the print's options
            if name in calls:
                line = f"{name} : {plain(calls[name].help)}"
            else:
                k = keys[name]
                default = plain(_doc_default(k)) or "the profile's"
                line = f"{name} : {plain(_doc_type(k))}; default {default}. {plain(_doc_help(k))}"
            out.append("    " + line)
    return "\n".join(out)


def _family(family: str) -> tuple[str, ...]:
    """The option lists ``family`` takes: the 3MF takes the print's options and its own."""
    if family not in FAMILIES:
        raise ParameterError(
            f"{family!r} is not a family of build options, must be one of: {', '.join(FAMILIES)}", param="family"
        )
    return ("print", "3mf") if family == "3mf" else (family,)


# -- the manual's tables -------------------------------------------------------------------------------------------
_TYPE_WORDS = {
    "string": "string",
    "integer": "integer",
    "number": "number",
    "numbers": "list of numbers",
    "boolean": "true or false",
    "choice": "string",
    "size": "number or [width, height]",
    "motif": "table or preset name",
    "motifs": "table",
    "formats": "list of strings",
    "colour": "string, #rrggbb, a palette's or a CSS colour name",
    "colours": "table of class letters to colours",
    "shades": "table of class letters to tables of engrave settings",
}


def _doc_type(k: Key) -> str:
    words = _TYPE_WORDS[k.type]
    if k.range is not None:
        words += ", " + (k.note if k.type == "numbers" else k.range.text(integer=k.type == "integer"))
        if k.type == "integer" and k.note:
            words = f"{_TYPE_WORDS[k.type]}, {k.note}"
    if k.unit and k.type != "size":
        words += f" ({k.unit})"
    elif k.unit:
        words += f", {k.unit}"
    if k.type == "number" and k.note:
        words += f"; {k.note}"
    return words


def _doc_default(k: Key) -> str:
    if k.default_text:
        return k.default_text
    if k.default is None:
        return ""
    if isinstance(k.default, bool):
        return "true" if k.default else "false"
    if isinstance(k.default, str):
        return f'`"{k.default}"`'
    if isinstance(k.default, tuple):
        return "`[" + ", ".join(f'"{v}"' for v in k.default) + "]`"
    return f"{k.default:g}"


def _doc_help(k: Key) -> str:
    return f"`{k.requires}`: {k.help}" if k.requires else k.help


def markdown_table(section: str) -> str:
    """The manual's table of ``section``'s keys (``docs/design-files.md``).

    >>> markdown_table("motif").splitlines()[2]
    '| `preset` | string |  | a preset name (`fabtiles presets` lists them; see construction.md) |'
    """
    rows = ["| key | type | default | meaning |", "|---|---|---|---|"]
    rows += [f"| `{k.name}` | {_doc_type(k)} | {_doc_default(k)} | {_doc_help(k)} |" for k in section_keys(section)]
    return "\n".join(rows)


_BLOCK = re.compile(r"(<!-- schema:(\w+) -->\n)(.*?)(<!-- /schema:\2 -->)", re.S)


def render_docs(text: str) -> str:
    """``text`` with each ``<!-- schema:SECTION -->`` ... ``<!-- /schema:SECTION -->`` block made from the schema."""

    def table(m):
        return f"{m.group(1)}{markdown_table(m.group(2))}\n{m.group(4)}"

    return _BLOCK.sub(table, text)


def main(argv=None) -> int:
    """``python -m fabtiles.core.schema FILE.md``: rewrite the file's schema blocks.

    ``--check``: exit 1 if they drift.
    """
    import sys
    from pathlib import Path

    args = list(sys.argv[1:] if argv is None else argv)
    check = "--check" in args
    paths = [a for a in args if a != "--check"]
    if len(paths) != 1:
        print("usage: python -m fabtiles.core.schema [--check] docs/design-files.md", file=sys.stderr)
        return 2
    path = Path(paths[0])
    text = path.read_text(encoding="utf-8")
    new = render_docs(text)
    if check:
        return 0 if new == text else 1
    if new != text:
        path.write_text(new, encoding="utf-8")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
