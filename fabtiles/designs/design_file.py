"""Design files: a TOML description of one tile, validated into frozen dataclasses
(reference: ``docs/design-files.md``).

A design has up to six sections; every key is checked, and an unknown key is an
error naming the key, its section and the valid keys (with a "did you mean").

``[motif]`` (required)
    ``preset = "table3-3"`` plus optional overrides of its parameters, or the
    parameters ``n``, ``radii``, ``alpha``, ``spr``, ``special``, ``rotation``.
``[packing]`` (optional; without it the tile holds one motif)
    ``kind`` ("hex" | "square" | "archimedean"), ``radius`` (mm), ``outline_circles``, ``fill``,
    ``gap_motif`` (inline table like ``[motif]``, or a preset name), ``seamless``
    (true: fit the radius, and a rectangle's height, with
    :func:`~fabtiles.geometry.seamless.seamless_fit`). ``kind = "archimedean"``
    takes ``tiling`` ("4.8.8", see :class:`~fabtiles.ArchimedeanPacking`) and ``edge``
    (mm) instead of ``radius``, and ``[packing.motifs]``: a motif per polygon kind keyed
    by its sides (``8 = "table3-3"``, ``4 = { n = 8, radii = [1, 2] }``); ``[motif]``
    is then optional and fills the kinds not listed. ``method = "hankin"`` draws Hankin's
    polygons in contact instead (``contact_angle`` degrees, ``contact_gap`` mm): the kinds
    ``[packing.motifs]`` lists keep their motif, ``[motif]`` fills none.
``[tile]`` (required)
    ``outline``, ``size``, ``frame``, ``stroke``, ``join``, ``miter_limit``, ``corner_radius``,
    ``interlace``, ``interlace_gap_mm``, ``interlace_cut`` (woven strands, see
    :mod:`fabtiles.geometry.interlace`), ``border_mm``, ``border_motif``, ``border_angle`` (a frieze
    round the field, see :mod:`fabtiles.geometry.border`).
``[output]`` (optional)
    ``formats`` (subset of dxf svg stl 3mf step; default ["svg"]), ``laser_profile``,
    ``printer_profile``, ``laser_mode``, ``print_style``, ``name`` (default: the
    file's stem), ``fill_small_holes`` (fill what each machine cannot make: the
    cutter's and the print's small holes), ``base_mm``, ``relief_mm``, ``pierced_mm``, ``deboss_mm`` (print heights
    overriding the printer profile's), ``inlay`` (a deboss tile's 3MF gets a second
    part filling the grooves flush, for a two-colour inlay print), ``threemf_layout``
    ("volumes", default, for PrusaSlicer, Bambu Studio and OrcaSlicer; "components"
    for UltiMaker Cura).
``[colour]`` (optional)
    the faces' colours (:class:`~fabtiles.designs.colour.Colours`, ``docs/colours.md``).
``[surface]`` (optional)
    ``shape = "cylinder"`` with ``diameter``, ``length`` (mm), ``fit``, ``mirror``, ``bore_mm``,
    ``rim_mm``, ``lamp_fitting_mm``: the pattern round a cylinder, its tile the unrolled strip
    (:class:`SurfaceSpec`, :mod:`fabtiles.making.cylinder`, ``docs/surfaces.md``).

>>> d = design_from_text('''
... [motif]
... preset = "table3-3"
... [packing]
... radius = 12.5
... [tile]
... outline = "square"
... size = 100
... ''', name="demo")
>>> d.name, d.packing.kind, d.output.formats
('demo', 'hex', ('svg',))
>>> d.tile_spec.size
(100.0, 100.0)
>>> build_tile(d).width_mm
100.0
"""

from __future__ import annotations

import math
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from ..core import schema as _schema
from ..core.errors import DesignError, FabtilesError, LimitError, ParameterError, did_you_mean
from ..export.formats import design_formats
from ..pattern.packing import PACKINGS
from ..pattern.star import Star
from .colour import Colours

FORMATS = _schema.key("output.formats").choice_values()
"""The built-in output formats a design may ask for (the plugins' too:
:func:`~fabtiles.export.formats.design_formats`)."""

THREEMF_LAYOUTS = _schema.key("output.threemf_layout").choice_values()
"""``[output] threemf_layout``: PrusaSlicer's volumes (PrusaSlicer, Bambu Studio, OrcaSlicer) or components (Cura)."""

# The keys of each section, read from the schema (fabtiles/core/schema.py), where each is declared.
SECTIONS = _schema.SECTIONS
MOTIF_KEYS = _schema.names("motif")
PACKING_KEYS = _schema.names("packing")
HANKIN_KEYS = tuple(k.name for k in _schema.section_keys("packing") if k.requires == 'method = "hankin"')
"""The ``[packing]`` keys of ``method = "hankin"`` alone (the contact angle and gap)."""
ARCHIMEDEAN_KEYS = (
    tuple(k.name for k in _schema.section_keys("packing") if k.requires.startswith('kind = "archimedean"'))
    + HANKIN_KEYS
)
"""The ``[packing]`` keys of ``kind = "archimedean"`` (it has no ``radius``)."""
GIRIH_KEYS = tuple(
    k.name for k in _schema.section_keys("packing") if k.requires.startswith("kind = ") and '"girih"' in k.requires
)
"""The ``[packing]`` keys of ``kind = "girih"`` (the pattern and the edge)."""
EDGE_KINDS = ("archimedean", "girih")
"""The packings sized by their polygons' edge (no ``radius``, no ``[motif]`` needed)."""
TILE_KEYS = _schema.names("tile")
HEIGHT_KEYS = tuple(
    k.name
    for k in _schema.section_keys("output")
    if k.option is not None and k.option.families == ("print",) and k.unit == "mm"
)
"""The ``[output]`` keys overriding the printer profile's heights (mm)."""

OUTPUT_KEYS = _schema.names("output")
COLOUR_KEYS = _schema.names("colour")
SURFACE_KEYS = _schema.names("surface")
"""The valid keys of ``[surface]``."""
CYLINDER = "cylinder"
"""``[surface] shape`` of the pattern wrapped round a cylinder."""
STAMP = "stamp"
"""``[surface] shape`` of a clay stamp."""
STAMP_KEYS = _schema.STAMP_KEYS
"""The ``[surface]`` keys of a stamp (the others are a cylinder's)."""
ROLLER_STYLES = ("relief", "deboss")
"""The print styles that make a cylinder a roller (its pattern pressed into clay); ``pierced`` makes a shade."""
STRIP_TILE_KEYS = _schema.STRIP_TILE_KEYS
"""The valid keys of ``[colour]`` (``faces`` is the ``[colour.faces]`` table)."""
"""The valid keys of ``[output]`` (the exporters read the mode/style/profile keys)."""


def _default(path: str):
    return _schema.key(path).default


@dataclass(frozen=True)
class MotifSpec:
    """A motif: a preset name and/or Star parameters (overrides of the preset)."""

    preset: str | None = None
    params: tuple[tuple[str, Any], ...] = ()

    def star(self) -> Star:
        """Build the :class:`~fabtiles.pattern.star.Star`."""
        params = dict(self.params)
        if self.preset is not None:
            return Star.preset(self.preset).replace(**params)
        return Star(**params)


@dataclass(frozen=True)
class PackingSpec:
    """The ``[packing]`` section (the defaults are the schema's, :mod:`fabtiles.core.schema`)."""

    kind: str = _default("packing.kind")
    radius: float = _default("packing.radius")
    outline_circles: bool = _default("packing.outline_circles")
    fill: float = _default("packing.fill")
    gap_motif: MotifSpec | None = None
    seamless: bool = _default("packing.seamless")
    tiling: str | None = _default("packing.tiling")
    edge: float = _default("packing.edge")
    method: str = _default("packing.method")
    contact_angle: float = _default("packing.contact_angle")
    contact_gap: float = _default("packing.contact_gap")
    contact_angle_to: float | None = _default("packing.contact_angle_to")
    parquet_direction: str = _default("packing.parquet_direction")
    parquet_curve: str = _default("packing.parquet_curve")
    motifs: tuple[tuple[int, MotifSpec], ...] = ()
    girih_pattern: str | None = _default("packing.girih_pattern")
    girih_level: int = _default("packing.girih_level")


@dataclass(frozen=True)
class TileSpec:
    """The ``[tile]`` section (``size`` normalised to a float pair)."""

    outline: str = _default("tile.outline")
    size: tuple[float, float] = (150.0, 150.0)
    frame: float = _default("tile.frame")
    stroke: float = _default("tile.stroke")
    join: str = _default("tile.join")
    miter_limit: float = _default("tile.miter_limit")
    corner_radius: float = _default("tile.corner_radius")
    interlace: bool = _default("tile.interlace")
    interlace_gap_mm: float | None = _default("tile.interlace_gap_mm")
    interlace_cut: bool = _default("tile.interlace_cut")
    border_mm: float = _default("tile.border_mm")
    border_motif: str = _default("tile.border_motif")
    border_angle: float | None = _default("tile.border_angle")


@dataclass(frozen=True)
class OutputSpec:
    """The ``[output]`` section."""

    formats: tuple[str, ...] = _default("output.formats")
    laser_profile: str | None = _default("output.laser_profile")
    printer_profile: str | None = _default("output.printer_profile")
    laser_mode: str | None = _default("output.laser_mode")
    print_style: str | None = _default("output.print_style")
    name: str | None = _default("output.name")
    fill_small_holes: bool = _default("output.fill_small_holes")
    pieces: bool = _default("output.pieces")
    pieces_sheets: bool = _default("output.pieces_sheets")
    inlay: bool = _default("output.inlay")
    threemf_layout: str = _default("output.threemf_layout")
    inlay_fit_mm: float | None = _default("output.inlay_fit_mm")
    inlay_pieces: str = _default("output.inlay_pieces")
    inlay_base: str = _default("output.inlay_base")
    tab_mm: float = _default("output.tab_mm")
    tabs_per_part: int = _default("output.tabs_per_part")
    base_mm: float | None = _default("output.base_mm")
    relief_mm: float | None = _default("output.relief_mm")
    pierced_mm: float | None = _default("output.pierced_mm")
    deboss_mm: float | None = _default("output.deboss_mm")
    mosaic_inset_mm: float | None = _default("output.mosaic_inset_mm")

    def heights(self) -> dict:
        """The height overrides given (mm), as keyword arguments of the print exporters."""
        return {k: getattr(self, k) for k in HEIGHT_KEYS if getattr(self, k) is not None}


@dataclass(frozen=True)
class SurfaceSpec:
    """The ``[surface]`` section: a flat tile, or the pattern round a cylinder (``docs/surfaces.md``).

    ``None`` is a value the print style decides (:meth:`mirror_for`, :meth:`bore_for`,
    :meth:`rim_for`): a roller (relief, deboss) is mirrored, bored and banded otherwise than a
    shade (pierced). After the fit, ``diameter`` is the one the cylinder is made at (``fit =
    "diameter"`` moves it), its circumference the unrolled strip's width.
    """

    shape: str = _default("surface.shape")
    diameter: float | None = None
    length: float | None = None
    fit: str = _default("surface.fit")
    mirror: bool | None = None
    bore_mm: float | None = None
    rim_mm: float | None = None
    lamp_fitting_mm: float | None = None
    pointed_tops: bool = _default("surface.pointed_tops")
    block_mm: float = _default("surface.block_mm")
    grip_mm: float = _default("surface.grip_mm")
    groove_mm: float = _default("surface.groove_mm")

    @property
    def cylinder(self) -> bool:
        """Whether the pattern is wrapped round a cylinder."""
        return self.shape == CYLINDER

    @property
    def stamp(self) -> bool:
        """Whether the tile is a clay stamp: its relief mirrored on a block with a finger grip."""
        return self.shape == STAMP

    @staticmethod
    def roller(style: str) -> bool:
        """Whether a cylinder printed in ``style`` is a roller (relief, deboss) rather than a shade (pierced)."""
        return style in ROLLER_STYLES

    def mirror_for(self, style: str) -> bool:
        """Whether the pattern is mirrored: ``mirror``, else a stamp's or a roller's imprint is the mirror of
        its surface."""
        if self.mirror is not None:
            return self.mirror
        return self.stamp or self.roller(style)

    def bore_for(self, style: str) -> float:
        """The axle hole's diameter (mm): a roller's ``bore_mm`` or its default; a shade has none (0)."""
        if not self.roller(style):
            return 0.0
        return _schema.ROLLER_BORE_MM if self.bore_mm is None else self.bore_mm

    def rim_for(self, style: str) -> float:
        """The closed band at each end (mm): ``rim_mm``, else the roller's or the shade's default."""
        if self.rim_mm is not None:
            return self.rim_mm
        return _schema.ROLLER_RIM_MM if self.roller(style) else _schema.SHADE_RIM_MM


@dataclass(frozen=True)
class Design:
    """A validated design. ``name`` is ``[output] name`` or the file's stem."""

    name: str
    motif: MotifSpec | None
    tile_spec: TileSpec
    packing: PackingSpec | None = None
    output: OutputSpec = field(default_factory=OutputSpec)
    source: str = "<design>"
    colour: Colours = field(default_factory=Colours)
    fitted: tuple[str, ...] = ()
    """What ``packing.seamless`` or a cylinder's fit changed (the radius or edge, a rectangle's height, the
    diameter), one line each."""
    surface: SurfaceSpec = field(default_factory=SurfaceSpec)

    def build_tile(self, tile_cls=None):
        """The :class:`~fabtiles.geometry.tile.TileGeometry` of this design (see :func:`build_tile`)."""
        return build_tile(self, tile_cls=tile_cls)


def profile_of(design: Design, which: str):
    """The design's cutter (``which="laser"``) or printer (``"printer"``) profile, loaded.

    An unknown or unreadable profile, or one of the other kind, is a
    :class:`~fabtiles.ProfileError` naming the design and its key, ``[output] laser_profile``.
    """
    from ..core.errors import ProfileError
    from ..machines.profiles import DEFAULT_CUTTER_PROFILE, DEFAULT_PRINTER_PROFILE, load_profile

    key = f"{which}_profile"
    name = getattr(design.output, key)
    try:
        return load_profile(
            name or (DEFAULT_CUTTER_PROFILE if which == "laser" else DEFAULT_PRINTER_PROFILE), kind=which
        )
    except ProfileError as exc:
        raise ProfileError(f"{design.source}: [output] {key}: {exc}", param=f"output.{key}") from None


# -- loading ------------------------------------------------------------------
def load_design(path, overrides=()) -> Design:
    """Read and validate a design file.

    Parameters
    ----------
    path : str or Path
        The TOML file.
    overrides : iterable of str
        ``"section.key=value"`` strings, the value in TOML syntax (``tile.size=[200,200]``,
        ``tile.outline=hexagon`` -- a bare word is taken as a string). Applied
        before validation.

    Returns
    -------
    Design
        The design, frozen: its sections as dataclasses, every key checked against the schema
        (``docs/design-files.md``), the defaults filled in.

    Raises
    ------
    DesignError
        The file cannot be read or parsed, a key is unknown or a value is bad.
        The message names the file and the key.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise DesignError(f"cannot read design file {str(path)!r}: {reason}") from None
    return design_from_text(text, name=path.stem, source=str(path), overrides=overrides)


def design_from_text(text: str, *, name: str = "design", source: str = "<design>", overrides=()) -> Design:
    """Parse and validate a design given as TOML text (see :func:`load_design`)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(f"{source}: not valid TOML: {exc}") from None
    if not overrides:
        return design_from_dict(data, name=name, source=source)
    import copy

    original = copy.deepcopy(data)
    for item in overrides:
        apply_override(data, item, source=source)
    try:
        return design_from_dict(data, name=name, source=source)
    except DesignError as exc:
        raise _blame_overrides(exc, original, tuple(overrides), name=name, source=source) from None


def _blame_overrides(exc: DesignError, original: dict, overrides: tuple, *, name: str, source: str):
    """The error of a design with overrides, naming the --set options when the file alone is valid."""
    try:
        design_from_dict(original, name=name, source=source)
    except DesignError:
        return exc  # the file itself is at fault (too): keep naming it
    message = str(exc).removeprefix(f"{source}: ")
    keys = {item: parse_override(item)[0] for item in overrides}
    param = exc.key or ""
    # The error's key names the override; an error naming no key (or a bare parameter) is matched by its words.
    guilty = [
        item for item, parts in keys.items() if param == ".".join(parts) or param.startswith(".".join(parts) + ".")
    ]
    guilty = (
        guilty
        or [item for item, parts in keys.items() if re.search(rf"(?<![\w]){re.escape(parts[-1])}(?![\w])", message)]
        or list(overrides)
    )
    return DesignError(f"{' '.join(f'--set {item}' for item in guilty)}: {message}", param=exc.param, key=exc.key)


def override_notes(path, overrides) -> list[str]:
    """What each ``--set`` changed in the design file at ``path``: one line per override, for people.

    >>> import tempfile, os
    >>> f = os.path.join(tempfile.mkdtemp(), "d.toml")
    >>> _ = open(f, "w").write('[tile]\\nsize = 150\\nstroke = 1.0\\n')
    >>> for line in override_notes(f, ["tile.size=[200,200]", "tile.stroke=1", "tile.frame=3"]):
    ...     print(line)
    --set tile.size=[200,200] (was 150)
    --set tile.stroke=1 (as the file has it)
    --set tile.frame=3 (not in the file: the default was 0)
    """
    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        data = {}  # the design loaded already; a file that changed since says nothing here
    notes = []
    for item in overrides:
        parts, value = parse_override(item)
        node: Any = data
        for p in parts:
            node = node.get(p, _MISSING) if isinstance(node, dict) else _MISSING
        if node is _MISSING:
            try:
                k = _schema.key(".".join(parts))
                default = k.default_text.strip("`") or (_toml_text(k.default) if k.default is not None else "none")
                was = f"not in the file: the default was {default}"
            except FabtilesError:
                was = "not in the file"
        elif node == value:
            was = "as the file has it"
        else:
            was = f"was {_toml_text(node)}"
        notes.append(f"--set {item} ({was})")
    return notes


_MISSING = object()


def design_notes(design: Design) -> list[str]:
    """What a design file says that the tile will not show, as notes for the build's output: what a
    seamless fit changed, a motif not drawn.

    >>> packing = {"kind": "archimedean", "tiling": "4.8.8", "method": "hankin"}
    >>> print(*design_notes(design_from_dict({"motif": {"preset": "table3-3"}, "packing": packing, "tile": {"size": 60}})))
    [motif] is not drawn: with method = "hankin" the polygons [packing.motifs] leaves out take Hankin's rays (name a motif there for a kind, or remove [motif])
    >>> design_notes(design_from_dict({"packing": packing, "tile": {"size": 60}}))
    []
    """  # noqa: E501 - a doctest's lines are as Python prints them
    p = design.packing
    notes = list(design.fitted)
    if p is not None and p.kind == "archimedean" and p.method == "hankin" and design.motif is not None:
        notes.append(
            '[motif] is not drawn: with method = "hankin" the polygons [packing.motifs] leaves out take '
            "Hankin's rays (name a motif there for a kind, or remove [motif])"
        )
    if p is not None and p.kind == "girih" and design.motif is not None:
        notes.append('[motif] is not drawn: kind = "girih" draws the girih tiles\' strapwork (remove [motif])')
    t = design.tile_spec
    if t.border_mm > 0:
        from ..geometry.border import border_fit

        fit = border_fit(t.outline, t.size, t.border_mm, frame=t.frame)
        notes.append(fit.line(t.border_motif, border_angle(design) if t.border_motif == "hankin" else None))
    return notes


def _toml_text(value) -> str:
    """A value as TOML writes it, short: ``150``, ``[150, 150]``, ``"square"``, ``true``."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_toml_text(v)}" for k, v in value.items()) + " }"
    return str(value)


def parse_override(item: str) -> tuple[list[str], Any]:
    """Split ``"section.key=value"`` into the key path and the TOML value.

    >>> parse_override("tile.size=[200, 200]")
    (['tile', 'size'], [200, 200])
    >>> parse_override("tile.outline=hexagon")
    (['tile', 'outline'], 'hexagon')
    >>> parse_override("packing.tiling=3^4.6")  # a bare tiling name: a string too
    (['packing', 'tiling'], '3^4.6')
    >>> parse_override("output.laser_profile=../my profiles/birch.toml")  # a text key takes any text
    (['output', 'laser_profile'], '../my profiles/birch.toml')
    """
    if not isinstance(item, str) or "=" not in item:
        raise DesignError(f"--set expects section.key=value, got {item!r}")
    key, value = (s.strip() for s in item.split("=", 1))
    parts = key.split(".")
    if len(parts) < 2 or not all(re.fullmatch(r"[A-Za-z0-9_-]+", p) for p in parts):
        raise DesignError(f"--set expects section.key=value (like tile.size=[200,200]), got {item!r}")
    try:
        parsed = tomllib.loads(f"v = {value}")["v"]
    except tomllib.TOMLDecodeError:
        if _text_key(parts):
            parsed = value  # the key takes text (a profile's path, a file name): the value as written
        elif re.fullmatch(r"[A-Za-z_][\w.+-]*|[0-9][0-9^.]*", value):
            parsed = value  # a bare word or tiling (4.8.8, 3^6): a string
        else:
            raise DesignError(f"--set {key}: {value!r} is not a TOML value") from None
    return parts, parsed


def _text_key(parts) -> bool:
    """Whether the schema's key at ``parts`` takes text (a string or a choice)."""
    if list(parts[:2]) == ["colour", "faces"]:  # --set colour.faces.A=navy
        return True
    try:
        return _schema.key(".".join(parts)).type in ("string", "choice", "colour")
    except FabtilesError:
        return False  # not a key: the validation names it


def apply_override(data: dict, item: str, *, source: str = "<design>") -> None:
    """Set one ``section.key=value`` override in the raw design mapping, in place."""
    parts, value = parse_override(item)
    node = data
    for k, p in enumerate(parts[:-1]):
        nxt = node.setdefault(p, {})
        if not isinstance(nxt, dict):
            raise DesignError(f"{source}: --set {'.'.join(parts)}: {'.'.join(parts[: k + 1])} is not a table")
        node = nxt
    node[parts[-1]] = value


def design_from_dict(data: dict, *, name: str = "design", source: str = "<design>") -> Design:
    """Validate a raw design mapping (as parsed from TOML) into a :class:`Design`.

    Every value is checked by building the tile (cheap: no geometry is computed).
    """
    packing, surface = _sections(data, source)
    motif = _motif_spec(data["motif"], source, "[motif]") if "motif" in data else None
    tile_spec = _tile_spec(data.get("tile", {}), source, surface)
    output = _output_spec(data.get("output", {}), source)
    colour = _colour_spec(data["colour"], source) if "colour" in data else Colours(given=False)
    name = output.name or name
    design = Design(
        name=name,
        motif=motif,
        tile_spec=tile_spec,
        packing=packing,
        output=output,
        source=source,
        colour=colour,
        surface=surface,
    )
    return _built(design, source)


def _sections(data: dict, source: str):
    """The design's sections checked (known, tables, motif and tile given): its packing's spec (or None) and
    its surface's."""
    _check_keys(data, SECTIONS, "the design", source, what="section")
    for sec in SECTIONS:
        if sec in data and not isinstance(data[sec], dict):
            raise DesignError(f"{source}: [{sec}] must be a table, got {data[sec]!r}")
    packing = _packing_spec(data["packing"], source) if "packing" in data else None
    surface = _surface_spec(data.get("surface", {}), source)
    for sec in ("motif", "tile"):
        if sec == "tile" and surface.cylinder:
            continue  # a cylinder's strip is its own rectangle; [tile] gives the stroke, if anything
        if sec not in data and not (sec == "motif" and packing is not None and packing.kind in EDGE_KINDS):
            raise DesignError(f"{source}: the design needs a [{sec}] section")
    return packing, surface


def _built(design: Design, source: str) -> Design:
    """The design with its pieces built once, so their values are checked: a ParameterError becomes a
    DesignError naming the key (a seamless tile's fitted size in place)."""
    motif, packing = design.motif, design.packing
    try:
        star = motif.star() if motif is not None else None
    except FabtilesError as exc:
        raise _wrapped(exc, source, "[motif]") from None
    if packing is not None:
        try:
            _build_packing(packing, star)
        except FabtilesError as exc:
            raise _wrapped(exc, source, "[packing]") from None
    if design.surface.cylinder:
        design = _fit_surface(design, star, source)
    try:
        design = _fit_seamless(design)
        build_tile(design)
    except FabtilesError as exc:
        raise _wrapped(exc, source, "[tile]") from None
    return design


def build_tile(design: Design, *, tile_cls=None):
    """Build the tile a design describes.

    ``tile_cls`` is the class to instantiate (default
    :class:`fabtiles.geometry.tile.TileGeometry`; pass a subclass, e.g. one that can export).
    """
    from ..geometry.tile import TileGeometry

    tile_cls = tile_cls or TileGeometry
    star = design.motif.star() if design.motif is not None else None
    pattern = star if design.packing is None else _build_packing(design.packing, star)
    t = design.tile_spec
    return tile_cls(
        t.outline,
        t.size,
        pattern,
        frame=t.frame,
        stroke=t.stroke,
        join=t.join,
        miter_limit=t.miter_limit,
        corner_radius=t.corner_radius,
        interlace=t.interlace,
        interlace_gap_mm=t.interlace_gap_mm,
        interlace_cut=t.interlace_cut,
        border_mm=t.border_mm,
        border_motif=t.border_motif,
        border_angle=border_angle(design),
    )


def border_angle(design: Design) -> float:
    """The hankin frieze's contact angle: ``[tile] border_angle``, else the packing's ``contact_angle``
    with ``method = "hankin"``, else 67.5 degrees."""
    if design.tile_spec.border_angle is not None:
        return design.tile_spec.border_angle
    p = design.packing
    if p is not None and p.kind == "archimedean" and p.method == "hankin":
        return p.contact_angle
    return 67.5


def _fit_seamless(design: Design) -> Design:
    from dataclasses import replace

    from ..geometry.seamless import period_fit, seamless_fit

    p = design.packing
    if p is None:
        return design
    varies = p.kind == "archimedean" and p.contact_angle_to not in (None, p.contact_angle)
    if varies and (p.seamless or design.surface.cylinder):
        where = "a cylinder's strip" if design.surface.cylinder else "seamless = true"
        raise DesignError(
            f"packing.contact_angle_to = {p.contact_angle_to:g} changes the pattern across the tile, so it cannot "
            f"repeat without a seam ({where}): give contact_angle_to = contact_angle, or no seamless fit",
            param="packing.contact_angle_to",
        )
    if not p.seamless or design.surface.cylinder:  # a cylinder's fit is the surface's
        return design
    t = design.tile_spec
    if p.kind == "girih":
        fit = period_fit(
            t.outline, t.size, p.edge, _build_packing(p, None).period, f"the girih pattern {p.girih_pattern}"
        )
        fitted = replace(design, packing=replace(p, edge=fit.edge), tile_spec=replace(t, size=fit.size))
        key, asked = "edge", p.edge
    elif p.kind == "archimedean":
        fit = seamless_fit(t.outline, t.size, p.edge, packing=p.tiling)
        fitted = replace(design, packing=replace(p, edge=fit.edge), tile_spec=replace(t, size=fit.size))
        key, asked = "edge", p.edge
    else:
        fit = seamless_fit(t.outline, t.size, p.radius, packing=p.kind)
        fitted = replace(design, packing=replace(p, radius=fit.radius), tile_spec=replace(t, size=fit.size))
        key, asked = "radius", p.radius
    return replace(fitted, fitted=_fit_lines(key, asked, fit, t))


def _fit_lines(key: str, asked: float, fit, t) -> tuple[str, ...]:
    """What a seamless fit changed, one line each, with how much: the build prints them as notes.

    >>> from fabtiles.geometry.seamless import seamless_fit
    >>> t = TileSpec(outline="rectangle", size=(300.0, 300.0))
    >>> for line in _fit_lines("radius", 14.0, seamless_fit("rectangle", (300, 300), 14), t):
    ...     print(line)
    packing.seamless: radius 14 mm fitted to 13.636 mm (11 periods across the 300 mm width)
    packing.seamless: tile height 300 mm moved to 283.426 mm (-16.574 mm, 6 whole periods up)
    """
    lines = []
    across = "width" if t.outline == "rectangle" else "tile"
    if abs(fit.radius - asked) > 1e-9:
        lines.append(
            f"packing.seamless: {key} {asked:g} mm fitted to {fit.radius:.5g} mm "
            f"({fit.repeats[0]} period{'s' if fit.repeats[0] != 1 else ''} across the "
            f"{fit.size[0]:g} mm {across})"
        )
    h = t.size[1] if isinstance(t.size, (tuple, list)) else t.size
    if abs(fit.size[1] - h) > 1e-9:
        lines.append(
            f"packing.seamless: tile height {h:g} mm moved to {fit.size[1]:.6g} mm "
            f"({fit.size[1] - h:+.5g} mm, {fit.repeats[1]} whole period{'s' if fit.repeats[1] != 1 else ''} up)"
        )
    return tuple(lines)


def _build_packing(p: PackingSpec, star: Star | None):
    gap = p.gap_motif.star() if p.gap_motif is not None else None
    if p.kind == "girih":
        from ..pattern.girih import GirihPacking

        assert p.girih_pattern is not None  # the design's check: a girih packing names its pattern
        return GirihPacking(p.girih_pattern, p.edge, level=p.girih_level)
    if p.kind == "archimedean":
        from ..pattern.archimedean import ArchimedeanPacking
        from ..pattern.tilings import unit_cell

        assert p.tiling is not None  # the design's check: an archimedean packing names its tiling
        motifs = {sides: spec.star() for sides, spec in p.motifs}
        if p.method == "hankin":  # the kinds [packing.motifs] leaves out take Hankin's rays
            return ArchimedeanPacking(
                p.tiling,
                p.edge,
                motifs,
                gap,
                outline_circles=p.outline_circles,
                fill=p.fill,
                method="hankin",
                contact_angle=p.contact_angle,
                contact_gap=p.contact_gap,
                contact_angle_to=p.contact_angle_to,
                parquet_direction=p.parquet_direction,
                parquet_curve=p.parquet_curve,
            )
        if star is not None:  # [motif] fills the kinds [packing.motifs] leaves out
            kinds = set(unit_cell(p.tiling).sides.tolist())
            motifs = {**dict.fromkeys(kinds - set(motifs), star), **motifs}
        return ArchimedeanPacking(p.tiling, p.edge, motifs, gap, outline_circles=p.outline_circles, fill=p.fill)
    return PACKINGS[p.kind](p.radius, star, gap, outline_circles=p.outline_circles, fill=p.fill)  # type: ignore[arg-type]  # a None motif is refused by the packing, by name


# -- sections -------------------------------------------------------------------
def _check_keys(table: dict, valid, where: str, source: str, what: str = "key") -> None:
    for key in table:
        if key not in valid:
            hint = did_you_mean(key, valid)
            hint = f"; {hint}" if hint else ""
            raise DesignError(f"{source}: unknown {what} {key!r} in {where}{hint} (valid {what}s: {', '.join(valid)})")


def _motif_spec(table, source: str, where: str) -> MotifSpec:
    if isinstance(table, str):  # a preset name (gap_motif = "table1-part1")
        table = {"preset": table}
    if not isinstance(table, dict):
        raise DesignError(f"{source}: {where} must be a table or a preset name, got {table!r}")
    _check_keys(table, MOTIF_KEYS, where, source)
    preset = table.get("preset")
    if preset is not None and not isinstance(preset, str):
        raise DesignError(f"{source}: {where} preset must be a string, got {preset!r}")
    params = {k: v for k, v in table.items() if k != "preset"}
    if preset is None:
        _check_required(params, source, where)
    if "radii" in params and isinstance(params["radii"], list):
        params["radii"] = tuple(params["radii"])
    spec = MotifSpec(preset=preset, params=tuple(sorted(params.items())))
    try:
        spec.star()
    except FabtilesError as exc:
        raise _wrapped(exc, source, where) from None
    return spec


def _check_required(params: dict, source: str, where: str) -> None:
    """Refuse a motif with no preset that lacks a parameter the star needs."""
    missing = [k for k in _schema.MOTIF_REQUIRED if k not in params]
    if missing:
        raise DesignError(
            f'{source}: {where} needs preset = "..." or the parameters n and radii (missing: {", ".join(missing)})'
        )


def _wrapped(exc: FabtilesError, source: str, where: str) -> DesignError:
    """A library error raised while reading ``where`` as a :class:`DesignError` naming the file and the key.

    ``param`` is the design key of the library's parameter; ``key`` the most precise key the
    error names (a motif of ``[packing.motifs]``: ``packing.motifs.6``).
    """
    return DesignError(
        f"{source}: {where} {exc}", param=_key(where, exc), key=_key(where, key=getattr(exc, "key", None) or exc.param)
    )


def _key(where: str, exc=None, *, key=None) -> str | None:
    """The design key an error is about, for front ends: ``"packing.gap_motif.n"``.

    >>> _key("[packing] gap_motif", key="n"), _key("[tile]", DesignError("x"))
    ('packing.gap_motif.n', None)
    """
    name = key or getattr(exc, "param", None)
    if name is None or "." in name:  # unknown, or already a design key (a work limit's)
        return name
    return ".".join(where.replace("[", "").replace("]", "").split() + [name])


def _value(table, section: str, name: str, source: str, where: str, default=None):
    """``table[name]`` checked by its key in the schema (type, and range unless the library checks it),
    or ``default``."""
    if name not in table:
        return default
    return _schema.key(f"{section}.{name}").check(
        table[name], prefix=f"{source}: {where} ", error=DesignError, param=_key(where, key=name)
    )


def _section(table, section: str, source: str, where: str, *, skip=()) -> dict:
    """The scalar keys of ``section`` given in ``table``, checked, with the schema's defaults for the rest."""
    scalar = ("string", "integer", "number", "boolean", "choice")
    return {
        k.name: _value(table, section, k.name, source, where, k.default)
        for k in _schema.section_keys(section)
        if k.type in scalar and k.name not in skip
    }


def _packing_spec(table: dict, source: str) -> PackingSpec:
    where = "[packing]"
    _check_keys(table, PACKING_KEYS, where, source)
    gap = table.get("gap_motif")
    kind = _value(table, "packing", "kind", source, where, "hex")
    extra = {"archimedean": _archimedean_spec, "girih": _girih_spec}.get(kind, lambda *_: {})(table, source)
    own = {"archimedean": ARCHIMEDEAN_KEYS, "girih": GIRIH_KEYS}.get(kind, ())
    if kind != "archimedean":
        wrong = [k for k in ARCHIMEDEAN_KEYS if k in table and k not in own]
        if wrong and wrong[0] == "method":
            raise DesignError(
                f"{source}: {where} method = {table['method']!r} is not valid with kind = {kind!r}: "
                f"method (one of: {', '.join(_schema.key('packing.method').choice_values())}) is a key "
                f'of kind = "archimedean", whose polygons may take Hankin\'s rays, while a {kind} '
                f'packing holds motifs in circles; set kind = "archimedean" and a tiling, or remove '
                f"method",
                param=_key(where, key="method"),
            )
        if wrong:
            raise _other_kinds_key(wrong[0], kind, source)
    wrong = [k for k in GIRIH_KEYS if k in table and k not in own]
    if wrong:
        raise _other_kinds_key(wrong[0], kind, source)
    values = _section(table, "packing", source, where, skip=("kind",) + ARCHIMEDEAN_KEYS + GIRIH_KEYS)
    return PackingSpec(
        kind=kind, **extra, **values, gap_motif=None if gap is None else _motif_spec(gap, source, "[packing] gap_motif")
    )


def _other_kinds_key(name: str, kind: str, source: str) -> DesignError:
    """The error of a ``[packing]`` key that belongs to other kinds of packing than ``kind``."""
    kinds = [k for k, keys in (("archimedean", ARCHIMEDEAN_KEYS), ("girih", GIRIH_KEYS)) if name in keys]
    owner = "kind = " + " or ".join(f'"{k}"' for k in kinds)
    return DesignError(
        f"{source}: [packing] {name} is a key of {owner}, not of kind = {kind!r}; "
        f"set {owner.replace(' or ', ' (or ')}{')' if len(kinds) > 1 else ''} or remove it",
        param=_key("[packing]", key=name),
    )


def _edge_kind_keys(table: dict, source: str, kind: str, whose: str, needed: str, choices) -> None:
    """Refuse a packing of ``kind`` (sized by an edge) that gives a radius, or lacks its ``needed`` key."""
    where = "[packing]"
    if "radius" in table:
        raise DesignError(
            f'{source}: {where} kind = "{kind}" has no radius: give {whose} edge (mm) instead, '
            f"like edge = {table['radius']!r}",
            param=_key(where, key="radius"),
        )
    if needed not in table:
        raise DesignError(
            f'{source}: {where} kind = "{kind}" needs {needed} = one of: {", ".join(choices)}',
            param=_key(where, key=needed),
        )


def _archimedean_spec(table: dict, source: str) -> dict:
    from ..pattern.tilings import ALL_TILINGS

    where = "[packing]"
    _edge_kind_keys(table, source, "archimedean", "the tiling's", "tiling", ALL_TILINGS)
    tiling = _value(table, "packing", "tiling", source, where)
    edge = _value(table, "packing", "edge", source, where, _schema.key("packing.edge").default)
    raw = table.get("motifs", {})
    if not isinstance(raw, dict):
        raise DesignError(
            f'{source}: [packing.motifs] must be a table keyed by polygon sides (8 = "table3-3"), got {raw!r}',
            param=_key(where, key="motifs"),
        )
    method, contact = _method(table, source, where)
    motifs = []
    for key, value in raw.items():
        if not str(key).isdigit():
            raise DesignError(
                f'{source}: [packing.motifs] key {key!r} must be a polygon\'s number of sides, like 8 = "table3-3"',
                param=_key(where, key="motifs"),
            )
        motifs.append((int(key), _motif_spec(value, source, f"[packing.motifs] {key}")))
    return dict(tiling=tiling, edge=edge, motifs=tuple(sorted(motifs)), method=method, **contact)


def _girih_spec(table: dict, source: str) -> dict:
    """``kind = "girih"``: its ``girih_pattern`` (required) and edge; no radius."""
    from ..pattern.girih import PATTERNS, check_level

    where = "[packing]"
    _edge_kind_keys(table, source, "girih", "the tiles'", "girih_pattern", PATTERNS)
    pattern = _value(table, "packing", "girih_pattern", source, where)
    check = _schema.key("packing.girih_pattern").checker
    assert check is not None  # registered by fabtiles.pattern.girih, which the package imports
    try:
        check(pattern)
    except FabtilesError as exc:
        raise DesignError(f"{source}: {where} {exc}", param=_key(where, key="girih_pattern")) from None
    edge = _value(table, "packing", "edge", source, where, _schema.key("packing.edge").default)
    level = _value(table, "packing", "girih_level", source, where, _schema.key("packing.girih_level").default)
    try:
        check_level(pattern, level)
    except (ParameterError, LimitError) as exc:  # the library names its argument; the design, its key
        cls = LimitError if isinstance(exc, LimitError) else DesignError  # a work limit stays one
        raise cls(f"{source}: {where} girih_{exc}", param=_key(where, key="girih_level")) from None
    return dict(girih_pattern=pattern, edge=edge, girih_level=level)


def _method(table: dict, source: str, where: str) -> tuple[str, dict]:
    """The packing's construction method and its contact keys (Hankin's method's only)."""
    method = _value(table, "packing", "method", source, where, _schema.key("packing.method").default)
    if method not in _schema.key("packing.method").choice_values():
        valid = _schema.key("packing.method").choice_values()
        hint = did_you_mean(method, valid)
        raise DesignError(
            f"{source}: {where} method = {method!r} is not valid{f' ({hint})' if hint else ''}, "
            f"must be one of: {', '.join(valid)}",
            param=_key(where, key="method"),
        )
    contact = {k: _value(table, "packing", k, source, where, _schema.key(f"packing.{k}").default) for k in HANKIN_KEYS}
    if method != "hankin" and any(k in table for k in HANKIN_KEYS):
        first = next(k for k in HANKIN_KEYS if k in table)
        raise DesignError(
            f'{source}: {where} {first} is a key of method = "hankin", not of method = '
            f'{method!r}; set method = "hankin" or remove it',
            param=_key(where, key=first),
        )
    return method, contact


def _tile_spec(table: dict, source: str, surface: SurfaceSpec | None = None) -> TileSpec:
    from ..geometry.tile import check_tile_size

    where = "[tile]"
    _check_keys(table, TILE_KEYS, where, source)
    if surface is not None and surface.cylinder:
        return _strip_spec(table, source, surface)
    outline = _value(table, "tile", "outline", source, where, "square")
    if "size" not in table:
        raise DesignError(f"{source}: {where} needs size (mm: a number, or [width, height])", param="tile.size")
    try:
        size = check_tile_size(outline, table["size"])
    except FabtilesError as exc:
        raise _wrapped(exc, source, where) from None
    return TileSpec(outline=outline, size=size, **_section(table, "tile", source, where, skip=("outline",)))


def _colour_spec(table: dict, source: str) -> Colours:
    """The ``[colour]`` section: its keys checked (colours parsed); the class letters are checked by the build,
    which knows the design's classes."""
    where = "[colour]"
    _check_keys(table, COLOUR_KEYS, where, source)
    values = _section(table, "colour", source, where)
    values.update(
        {
            k.name: _value(table, "colour", k.name, source, where)
            for k in _schema.section_keys("colour")
            if k.type == "colour"
        }
    )
    faces = table.get("faces", {})
    if not isinstance(faces, dict):
        raise DesignError(
            f'{source}: [colour.faces] must be a table of class letters to colours (A = "navy"), got {faces!r}',
            param="colour.faces",
        )
    shades = table.get("shades", {})
    if not isinstance(shades, dict):
        raise DesignError(
            f"{source}: [colour.shades] must be a table of class letters to engrave settings "
            f"(C = {{ power_pct = 40 }}), got {shades!r}",
            param="colour.shades",
        )
    try:
        return Colours(**values, faces=faces, shades=shades, given=True)
    except FabtilesError as exc:
        if str(exc.param or "").startswith(("colour.", "shades")):
            raise DesignError(f"{source}: {exc}", param=exc.param) from None
        # a bad colour names its class (the web app's face_<letter> parameter): colour.faces.A
        letter = exc.param if re.fullmatch(r"[A-Z]{1,2}", str(getattr(exc, "param", None))) else None
        raise DesignError(
            f"{source}: [colour.faces] {exc}", param=f"colour.faces.{letter}" if letter else "colour.faces"
        ) from None


def _output_spec(table: dict, source: str) -> OutputSpec:
    where = "[output]"
    _check_keys(table, OUTPUT_KEYS, where, source)
    formats = table.get("formats", ["svg"])
    allowed = design_formats()
    if isinstance(formats, str):
        formats = [formats]
    if not isinstance(formats, list) or not formats:
        raise DesignError(
            f"{source}: {where} formats must be a non-empty list of: {', '.join(allowed)}", param="output.formats"
        )
    for f in formats:
        if f not in allowed:
            hint = did_you_mean(f, allowed)
            raise DesignError(
                f"{source}: {where} formats: {f!r} is not a valid format{f' ({hint})' if hint else ''}, "
                f"must be one of: {', '.join(allowed)}",
                param="output.formats",
            )
    name = _value(table, "output", "name", source, where)
    if name is not None and not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._ -]*", name):
        raise DesignError(
            f"{source}: {where} name must be a plain file name (letters, digits, . _ - "
            f"and spaces, no folders), got {name!r}",
            param="output.name",
        )
    return OutputSpec(formats=tuple(dict.fromkeys(formats)), **_section(table, "output", source, where))


# -- the surface ----------------------------------------------------------------------------------------------------
def _surface_spec(table: dict, source: str) -> SurfaceSpec:
    """The ``[surface]`` section: its keys checked; a cylinder's diameter and length required, a flat tile's
    cylinder keys refused."""
    where = "[surface]"
    _check_keys(table, SURFACE_KEYS, where, source)
    values = _section(table, "surface", source, where)
    shape = values["shape"]
    if shape == CYLINDER:
        for name in _schema.CYLINDER_REQUIRED:
            if values[name] is None:
                raise DesignError(
                    f'{source}: {where} shape = "cylinder" needs {name} (mm, > 0)', param=f"surface.{name}"
                )
    own = {CYLINDER: [k for k in SURFACE_KEYS if k not in _schema.STAMP_KEYS or k == "mirror"], STAMP: STAMP_KEYS}
    given = [k for k in SURFACE_KEYS if k != "shape" and k in table and k not in own.get(shape, ())]
    if given:
        whose = "stamp" if given[0] in STAMP_KEYS else "cylinder"
        raise DesignError(
            f'{source}: {where} {given[0]} is a key of shape = "{whose}", not of shape = {shape!r}; '
            f'set shape = "{whose}" or remove it',
            param=f"surface.{given[0]}",
        )
    return SurfaceSpec(**values)


def _strip_spec(table: dict, source: str, surface: SurfaceSpec) -> TileSpec:
    """A cylinder's ``[tile]``: the unrolled strip, a rectangle round the circumference by the length, with no
    frame (its x ends meet at the seam; the rims close its y ends). The keys that would say otherwise are
    refused."""
    given = [k for k in STRIP_TILE_KEYS if k in table]
    if given:
        raise DesignError(
            f'{source}: [tile] {given[0]} is not a key of a cylinder\'s tile: with [surface] shape = "cylinder" '
            "the tile is the unrolled strip, the circumference by the length, framed by rim_mm at its ends; "
            f"remove {given[0]}",
            param=f"tile.{given[0]}",
        )
    assert surface.diameter is not None and surface.length is not None  # required by _surface_spec
    values = _section(table, "tile", source, "[tile]", skip=STRIP_TILE_KEYS)
    size = (math.pi * surface.diameter, surface.length)
    return TileSpec(outline="rectangle", size=size, frame=0.0, corner_radius=0.0, **values)


def _fit_surface(design: Design, star, source: str) -> Design:
    """A cylinder's circumference made a whole number of the pattern's periods along x: the packing's radius
    (or edge) scaled, or the diameter moved (``fit``); the strip's width set to it, and what changed said
    in :attr:`Design.fitted`."""
    from dataclasses import replace

    s, p = design.surface, design.packing
    assert s.diameter is not None and s.length is not None  # required by _surface_spec
    if p is None:
        raise DesignError(
            f'{source}: [surface] shape = "cylinder" needs a [packing]: a lone motif does not repeat round the '
            "cylinder, a packing's pattern does (add [packing] with a radius, or a tiling and edge)",
            param="surface.shape",
        )
    period = float(_build_packing(p, star).period[0])
    key = "edge" if p.kind in EDGE_KINDS else "radius"
    size = getattr(p, key)
    around = math.pi * s.diameter
    if around < period - 1e-9:
        raise DesignError(
            f"{source}: [surface] diameter = {s.diameter:g} mm is too small for one period of the pattern: its "
            f"circumference, {around:.2f} mm, is less than the pattern's period along x, {period:.2f} mm "
            f"(packing {key} {size:g} mm); the diameter must be at least {period / math.pi:.2f} mm, or make the "
            f"packing's {key} smaller",
            param="surface.diameter",
        )
    n = max(1, round(around / period))
    length = s.length
    if s.fit == "packing":
        scale = around / (n * period)
        p = replace(p, **{key: size * scale})
        line = (
            f"surface: cylinder D {s.diameter:g} mm x {s.length:g} mm, {n} period{'s' if n != 1 else ''} around "
            f"(packing {key} {size:.2f} -> {size * scale:.2f} mm, {100 * (scale - 1):+.1f} %)"
        )
    else:
        diameter = n * period / math.pi
        line = (
            f"surface: cylinder D {s.diameter:g} -> {diameter:.2f} mm ({100 * (diameter / s.diameter - 1):+.1f} %) "
            f"x {s.length:g} mm, {n} period{'s' if n != 1 else ''} around (packing {key} {size:g} mm kept)"
        )
        s = replace(s, diameter=diameter)
    width = around if s.fit == "packing" else n * period  # the circumference at the fitted diameter
    tile_spec = replace(design.tile_spec, size=(width, length))
    return replace(design, packing=p, surface=s, tile_spec=tile_spec, fitted=(*design.fitted, line))
