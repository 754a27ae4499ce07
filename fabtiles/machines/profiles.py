"""Machine and material profiles: validated, frozen fabrication settings.

Profiles are TOML files. The bundled ones live in the repository's ``profiles/``
folder (installed as the package ``fabtiles.profiles``); a user's own profile is
given by path. Every key is checked when the file is loaded: an unknown key or
a bad value is a :class:`~fabtiles.ProfileError` that names the file and the key.

>>> p = load_profile("laser-3mm-plywood")
>>> p.kerf_mm, p.layers.outer_cut.name
(0.15, 'OUTER')
>>> load_profile("fdm-0.4mm").min_wall_mm
0.8
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, fields
from importlib import resources
from pathlib import Path
from typing import Any

from ..core.errors import ProfileError, did_you_mean
from ..core.schema import key as schema_key
from ..core.schema import register_choices
from .cutters import CUTTER_KINDS, JOINTS, KINDS, LASER_MODES, cutter_kind, family, members

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

PRINT_STYLES = ("relief", "pierced", "deboss", "mosaic")
PRINTER = "printer"
"""The kind of a 3D printer's profile (every other kind is a 2D cutter's, :data:`~fabtiles.machines.cutters.KINDS`)."""
DEFAULT_THICKNESS_MM = 3.0
"""A cutter profile's sheet thickness when it gives none (it sizes the joints of a panel's pieces)."""
DXF_VERSIONS = ("R12", "R2000", "R2004", "R2007", "R2010", "R2013", "R2018")


@dataclass(frozen=True)
class Layer:
    """A laser layer: its name, AutoCAD Color Index (1..255), and how the laser runs it.

    ``speed_mm_s`` (> 0), ``power_pct`` (0, 100] and ``passes`` (>= 1) are the
    operation's settings, written into LightBurn projects and used for the job time;
    ``line_interval_mm`` (> 0) is an engrave layer's distance between fill lines.
    """

    name: str
    color: int
    speed_mm_s: float = 10.0
    power_pct: float = 60.0
    passes: int = 1
    line_interval_mm: float | None = None
    power_range_pct: tuple[float, float] | None = None
    """An engrave layer's powers for shaded faces, lightest to darkest (see :func:`shade_power`); None:
    from a quarter of ``power_pct`` to ``power_pct``."""

    @property
    def shade_range_pct(self) -> tuple[float, float]:
        """The powers a shaded engraving spreads its classes over: ``power_range_pct``, else a quarter of
        ``power_pct`` to ``power_pct`` (the profile's fill is tuned for its darkest burn)."""
        if self.power_range_pct is not None:
            return self.power_range_pct
        return (max(1.0, round(self.power_pct / 4)), self.power_pct)


@dataclass(frozen=True)
class LaserLayers:
    """Layer of each laser operation.

    Both cuts are red (ACI 1, #FF0000), the only colour that MeerK40t's colour
    classification sends to a Cut operation (it sent our earlier blue outline to
    Engrave), and LightBurn's palette layer 02 exactly; they stay apart by name.
    The names hold neither ``CUT`` nor ``ENGRAVE``: MeerK40t's DXF loader (0.9.7900
    and later) puts such a layer into an operation by its name and then classifies
    it by colour as well, so every contour was cut twice. The score is blue (ACI 5),
    MeerK40t's first Engrave colour and LightBurn's layer 01. See
    ``docs/laser-programs.md``.
    """

    inner_cut: Layer = Layer("INNER", 1)
    outer_cut: Layer = Layer("OUTER", 1)
    score: Layer = Layer("SCORE", 5, speed_mm_s=100.0, power_pct=15.0)
    engrave: Layer | None = None
    """The fill layer of the engrave mode (and of pocket inlays); a profile without it cannot engrave."""


@dataclass(frozen=True)
class CutterProfile:
    """Settings of one 2D cutter (a laser, a CNC router or a waterjet) and sheet material (lengths in mm).

    ``kind`` is ``"laser"``, ``"router"`` or ``"waterjet"``; each kind's rules are its
    :attr:`cutter` (:mod:`fabtiles.machines.cutters`). A router cuts with a
    bit of ``tool_diameter_mm``: its files hold the part as the bit makes it (every
    hole opened by the bit's radius, see :mod:`fabtiles.geometry.tool_opening`) with
    no kerf compensation (CAM offsets the tool). A waterjet's ``kerf_mm`` is the
    jet's diameter: corners are rounded to the jet's radius, then the kerf is
    compensated as a laser's. :class:`LaserProfile` is the same class under its
    former name, kept so scripts keep working.

    >>> p = load_profile("router-6mm-mdf")
    >>> p.kind, p.tool_diameter_mm, p.tool_radius_mm, p.kerf_mm
    ('router', 6.0, 3.0, 0.0)
    >>> load_profile("waterjet-1mm-aluminium").tool_radius_mm
    0.5
    """

    name: str
    description: str = ""
    kerf_mm: float = 0.15
    kerf_x_mm: float | None = None
    kerf_y_mm: float | None = None
    min_feature_mm: float = 1.0
    min_hole_mm: float = 1.2
    tolerance_mm: float = 0.01
    bed_mm: tuple[float, float] = (600.0, 400.0)
    mode: str = "pierced"
    strict: bool = False
    dxf_version: str = "R2000"
    pierce_s: float = 0.1
    travel_mm_s: float = 200.0
    inlay_fit_mm: float = 0.15
    min_piece_mm: float | None = None
    price_per_m2: float | None = None
    layers: LaserLayers = LaserLayers()
    kind: str = "laser"
    tool_diameter_mm: float | None = None
    """A router's bit diameter (mm); None for a laser or a waterjet."""
    thickness_mm: float | None = None
    """The sheet's thickness (mm), which sizes the joints of a panel's pieces; None: 3 mm."""
    bed_margin_mm: float | None = None
    """How far a piece of a panel keeps from the bed's edges (mm); None: the kind's (a laser's 5 mm,
    a router's or waterjet's 10 mm, room for the clamps that hold the sheet)."""
    joint: str = "dovetail"
    """The joint that locks a panel's pieces (:data:`~fabtiles.machines.cutters.JOINTS`)."""
    joint_fit_mm: float = 0.1
    """How much a joint's tab is grown (mm): positive presses in, negative leaves play."""

    def __post_init__(self):
        cutter_kind(self)  # a kind that is no cutter's is a ProfileError

    @property
    def cutter(self):
        """The rules of the profile's kind of cutter (:class:`~fabtiles.machines.cutters.CutterKind`)."""
        return cutter_kind(self)

    @property
    def tool_radius_mm(self) -> float:
        """The radius the cutter rounds a hole's corners to: a router's bit, a waterjet's jet; 0 for a laser."""
        return self.cutter.tool_radius(self)

    @property
    def min_piece_or_default_mm(self) -> float:
        """The smallest hole an inlay kit makes a piece of: ``min_piece_mm``, else twice ``min_hole_mm``."""
        return 2 * self.min_hole_mm if self.min_piece_mm is None else self.min_piece_mm

    @property
    def thickness_or_default_mm(self) -> float:
        """The sheet's thickness: ``thickness_mm``, else 3 mm (the bundled lasers' sheets)."""
        return DEFAULT_THICKNESS_MM if self.thickness_mm is None else self.thickness_mm

    @property
    def margin_mm(self) -> float:
        """The margin a piece keeps from the bed's edges: ``bed_margin_mm``, else the kind's."""
        return self.cutter.bed_margin_mm if self.bed_margin_mm is None else self.bed_margin_mm

    @property
    def kerf_xy_mm(self) -> tuple[float, float]:
        """The kerf along X and along Y (mm): ``kerf_x_mm`` and ``kerf_y_mm``, each ``kerf_mm`` unless given."""
        return (
            self.kerf_mm if self.kerf_x_mm is None else self.kerf_x_mm,
            self.kerf_mm if self.kerf_y_mm is None else self.kerf_y_mm,
        )


LaserProfile = CutterProfile
"""The former name of :class:`CutterProfile` (it covers routers and waterjets too), kept so scripts keep working."""


@dataclass(frozen=True)
class PrinterProfile:
    """Settings of one 3D printer (all lengths in mm).

    ``min_hole_mm`` is the narrowest hole the printer makes: a hole no disc of it fits
    in is a ``small_hole`` finding, and ``fill_small_holes`` fills it. Without it, two
    nozzle widths, as the minimum wall: the lines the slicer lays either side of a
    narrower hole, squeezed flat, close it or leave a slit, while the slicer still
    traces each one as a loop of its own, so the holes too small to print cost most of
    the slicing time (``docs/speed.md``). ``0`` turns the check off.

    >>> load_profile("fdm-0.4mm").min_hole_mm, PrinterProfile("p", nozzle_mm=0.6).min_hole_mm
    (0.8, 1.2)
    """

    name: str
    description: str = ""
    nozzle_mm: float = 0.4
    min_wall_mm: float = 0.8
    min_hole_mm: float | None = None
    tolerance_mm: float = 0.02
    """How far a print's hole edges may move when their points are thinned (0: not at all); see
    :func:`fabtiles.geometry.print_checks.flatten_holes`."""
    layer_height_mm: float = 0.2
    base_mm: float = 2.0
    relief_mm: float = 1.2
    pierced_mm: float = 3.0
    deboss_mm: float = 0.8
    print_style: str = "relief"
    """The print's style unless a design or call gives one: the design key ``[output] print_style``,
    one name for both (a profile's older ``style`` key still loads, with a note)."""
    bed_mm: tuple[float, float] = (256.0, 256.0)
    height_mm: float = 256.0
    """The tallest print the printer builds (mm): a cylinder, printed standing on an end, is at most this long."""
    bed_margin_mm: float = 5.0
    """The bed's edge a piece of a panel larger than the bed keeps clear of (mm)."""
    joint_clearance_mm: float | None = None
    """The gap between two printed pieces of a panel, everywhere they meet (mm); default half the
    nozzle (see :mod:`fabtiles.making.print_pieces`)."""
    max_overhang_deg: float = 45.0
    """The steepest overhang the printer makes without support, in degrees from vertical (> 0 and
    < 90): an opening's ceiling in a wall printed upright that leans further is an ``overhang``
    finding unless it is bridged (see :mod:`fabtiles.geometry.wall_overhangs`). 45 degrees is the
    rule of thumb FDM design guides give: each layer then rests on at least half of the one below."""
    max_bridge_mm: float = 5.0
    """The widest flat ceiling the printer bridges between its two ends (mm, >= 0; 0: none): 5 mm is
    what desktop FDM printers bridge with no visible sag, the figure design guides give (wider
    bridges print, sagging 0.1 mm and more)."""

    @property
    def margin_mm(self) -> float:
        """The margin a piece keeps from the bed's edges (``bed_margin_mm``), as a cutter profile's."""
        return self.bed_margin_mm

    strict: bool = False
    filament_density_g_cm3: float = 1.24
    filament_diameter_mm: float = 1.75
    price_per_kg: float | None = None
    kind = PRINTER

    def __post_init__(self):
        if self.min_hole_mm is None:  # two nozzle widths (see the class text)
            object.__setattr__(self, "min_hole_mm", 2 * self.nozzle_mm)
        if self.joint_clearance_mm is None:
            object.__setattr__(self, "joint_clearance_mm", self.nozzle_mm / 2)


def bundled_profiles(kind: str | None = None) -> tuple[str, ...]:
    """Names of the profiles shipped with fabtiles; with ``kind``, those of that kind (as :func:`load_profile`'s).

    >>> "fdm-0.4mm" in bundled_profiles(), bundled_profiles("printer")
    (True, ('fdm-0.4mm', 'fdm-0.6mm'))
    """
    root = resources.files("fabtiles.profiles")
    names = tuple(sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".toml")))
    return names if kind is None else tuple(n for n in names if family(kind_of(n)) == kind)


DEFAULT_CUTTER_PROFILE = "laser-3mm-plywood"
"""The cutter profile of a design or call that names none."""
DEFAULT_LASER_PROFILE = DEFAULT_CUTTER_PROFILE
DEFAULT_PRINTER_PROFILE = "fdm-0.4mm"
"""The printer profile of a design or call that names none."""


def load_profile(profile, *, kind: str | None = None):
    """Load a profile by bundled name, or from a ``.toml`` path; pass profiles through.

    Parameters
    ----------
    profile : str, Path, CutterProfile or PrinterProfile
        A bundled name (see :func:`bundled_profiles`), a path to a TOML file, or
        an already loaded profile.
    kind : {"laser", "printer"}, optional
        The kind the caller needs; a profile of the other kind is an error. ``"laser"``
        means a 2D cutter: a laser, router or waterjet profile (all :class:`CutterProfile`).

    Returns
    -------
    CutterProfile or PrinterProfile
        The profile, frozen, every key checked (``profile`` itself when it is loaded already).

    Raises
    ------
    ProfileError
        An unknown name, a file that cannot be read or is not TOML, an unknown key or a bad
        value (the message names the file and the key), or a profile of the other kind.
    """
    if isinstance(profile, (CutterProfile, PrinterProfile)):
        result = profile
    else:
        if not isinstance(profile, (str, Path)):
            raise ProfileError(f"profile must be a profile name or a path to a .toml file, got {profile!r}")
        text, source, name = _read(profile, kind)
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise ProfileError(f"{source}: not valid TOML: {exc}") from None
        result = _parse(data, source, name)
    if kind is not None and family(result.kind) != kind:
        also = [k for k in members(kind) if k != kind]
        wanted = f"a {kind} profile is needed here" + (f" (or a {' or '.join(also)} one)" if also else "")
        raise ProfileError(
            f"profile {result.name!r} is a {result.kind} profile, but {wanted}; "
            f"bundled {kind} profiles: {', '.join(bundled_profiles(kind))}"
        )
    return result


def profile_text(profile) -> tuple[str, CutterProfile | PrinterProfile]:
    """The TOML text of a bundled profile (by name) or a profile file (by path), and the profile it loads as.

    The text is validated first (an unknown name or a bad file is the same
    :class:`~fabtiles.ProfileError` as :func:`load_profile`'s), so a copy made of it loads.

    >>> text, p = profile_text("fdm-0.4mm")
    >>> text.splitlines()[1], p.kind
    ('kind = "printer"', 'printer')
    """
    text, source, name = _read(profile)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ProfileError(f"{source}: not valid TOML: {exc}") from None
    return text, _parse(data, source, name)


def kind_of(name: str) -> str:
    """The ``kind`` of a bundled profile: ``"laser"``, ``"router"``, ``"waterjet"`` or ``"printer"``.

    >>> kind_of("router-6mm-mdf"), kind_of("fdm-0.4mm")
    ('router', 'printer')
    """
    return load_profile(name).kind


def _unknown_profile(name: str, kind: str | None) -> str:
    """The message for a profile ``name`` not bundled, in a slot of ``kind`` (None: any).

    The suggestion is among the slot's profiles, and among those of the kind the name
    starts with (``laser-5mm-mdf`` is meant as a laser's); a profile of another kind
    the slot takes, as near as those, is named apart, with its kind.

    >>> _unknown_profile("laser-5mm-mdf", "laser")  # doctest: +NORMALIZE_WHITESPACE
    "profile 'laser-5mm-mdf' does not exist (did you mean 'laser-3mm-plywood'?; a router profile is near:
    'router-6mm-mdf'); bundled profiles for this slot: laser-3mm-acrylic, laser-3mm-plywood (laser),
    router-3.175mm-plywood, router-6mm-mdf (router), waterjet-1mm-aluminium (waterjet); or give the path of a
    .toml file"
    >>> _unknown_profile("laser-3mm-plywod", "printer")
    "profile 'laser-3mm-plywod' does not exist; bundled printer profiles: fdm-0.4mm, fdm-0.6mm; or give the path of a .toml file"
    """  # noqa: E501 - a doctest's lines are as Python prints them
    slot = bundled_profiles(kind) if kind is not None else bundled_profiles()
    kinds = {n: kind_of(n) for n in slot}
    hint_text = _near_names(name, slot, kinds)
    by_kind: dict[str, list[str]] = {}
    for n in slot:
        by_kind.setdefault(kinds[n], []).append(n)
    if len(by_kind) > 1:
        listed = f"bundled profiles{' for this slot' if kind else ''}: " + ", ".join(
            f"{', '.join(v)} ({k})" for k, v in by_kind.items()
        )
    else:
        listed = f"bundled {kind + ' ' if kind else ''}profiles: {', '.join(slot)}"
    return f"profile {name!r} does not exist{hint_text}; {listed}; or give the path of a .toml file"


def _near_names(name: str, slot, kinds: dict) -> str:
    """The suggestion for a profile name not bundled, in brackets (or nothing): the nearest of the kind the
    name starts with, and a profile of another kind named apart when it is as near."""
    import difflib

    typed = name.split("-", 1)[0]
    meant = [n for n in slot if kinds[n] == typed] if typed in kinds.values() else list(slot)

    def closest(candidates):
        near = difflib.get_close_matches(name, candidates, n=1)
        return (near[0], difflib.SequenceMatcher(None, name, near[0]).ratio()) if near else (None, 0.0)

    mine, mine_score = closest(meant)
    other, other_score = closest([n for n in slot if n not in meant])
    hints = [f"did you mean {mine!r}?" if mine else ""]
    if other and other_score >= mine_score:  # as near as any of the kind meant: said apart, with its kind
        hints.append(f"a {kinds[other]} profile is near: {other!r}")
    return f" ({'; '.join(h for h in hints if h)})" if any(hints) else ""


def _read(profile, kind: str | None = None) -> tuple[str, str, str]:
    text_form = str(profile)
    looks_like_path = isinstance(profile, Path) or text_form.endswith(".toml") or "/" in text_form or "\\" in text_form
    if looks_like_path:
        path = Path(profile)
        try:
            return path.read_text(encoding="utf-8"), str(path), path.stem
        except (OSError, UnicodeDecodeError) as exc:
            raise ProfileError(f"cannot read profile file {str(path)!r}: {exc}") from None
    names = bundled_profiles()
    if text_form not in names:
        raise ProfileError(_unknown_profile(text_form, kind))
    res = resources.files("fabtiles.profiles") / f"{text_form}.toml"
    return res.read_text(encoding="utf-8"), f"profiles/{text_form}.toml", text_form


def _unknown(source, where, keys, allowed):
    for key in keys:
        if key not in allowed:
            hint = did_you_mean(key, allowed)
            hint_text = f" ({hint})" if hint else ""
            raise ProfileError(f"{source}: unknown key {where}{key!r}{hint_text}; valid keys: {', '.join(allowed)}")


def _positive(source, key, value, *, allow_zero=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ProfileError(f"{source}: {key} must be a finite number, got {value!r}")
    if value < 0 or (value == 0 and not allow_zero):
        raise ProfileError(f"{source}: {key} must be {'>= 0' if allow_zero else '> 0'}, got {value!r}")
    return float(value)


PRINTER_ZERO_KEYS = ("min_hole_mm", "tolerance_mm", "bed_margin_mm", "joint_clearance_mm", "max_bridge_mm")
"""A printer's keys that may be 0: no hole limit, no thinning, no margin, pieces that touch, no bridges."""


def _parse(data: dict, source: str, name: str):
    """A profile of the parsed TOML ``data``: its kind's section read and checked, a cutter's layers too."""
    kind, description, cutter = _kind_of(data, source)
    cls = CutterProfile if cutter else PrinterProfile
    section = _section(data, kind, cutter, cls, source)
    values: dict[str, Any] = {key: _value(source, kind, cutter, key, value) for key, value in section.items()}
    if cutter:
        values["layers"] = _parse_layers(data.get("layers", {}), source)
        values["kind"] = kind
        values.update(cutter.fixed)  # a router's file holds the part contour: no kerf; the bit decides the holes
    return cls(name=name, description=description, **values)


def _kind_of(data: dict, source: str) -> tuple:
    """The profile's kind, description and cutter kind (None for a printer), its top-level keys checked."""
    kinds = CUTTER_KINDS + (PRINTER,)
    _unknown(source, "", data, ("kind", "description") + kinds + ("layers",))
    kind = data.get("kind")
    if kind not in kinds:
        raise ProfileError(f"{source}: kind must be one of: {', '.join(kinds)}, got {kind!r}")
    description = data.get("description", "")
    if not isinstance(description, str):
        raise ProfileError(f"{source}: description must be text, got {description!r}")
    cutter = KINDS.get(kind)  # None for a printer
    others = [k for k in kinds if k != kind and k in data] + (["layers"] if cutter is None and "layers" in data else [])
    if others:
        raise ProfileError(f"{source}: a {kind} profile cannot have a [{others[0]}] section")
    return kind, description, cutter


def _section(data: dict, kind: str, cutter, cls, source: str) -> dict:
    """The profile's ``[kind]`` table: a table of known keys, with the keys its kind requires."""
    section = data.get(kind, {})
    if not isinstance(section, dict):
        raise ProfileError(f"{source}: [{kind}] must be a table")
    allowed = list(cutter.keys) if cutter else [f.name for f in fields(cls) if f.name not in ("name", "description")]
    if cutter is None and "style" in section:
        section = _renamed_style(section, source)
    _unknown(source, f"{kind}.", section, allowed)
    for key in cutter.required if cutter else ():
        if key not in section:
            raise ProfileError(
                f"{source}: a {kind} profile needs {kind}.{key} (the {cutter.tool}'s diameter in mm, > 0)"
            )
    return section


def _value(source: str, kind: str, cutter, key: str, value):
    """One key of the profile's section, checked and converted."""
    full = f"{kind}.{key}"
    if key == "bed_mm":
        if not isinstance(value, list) or len(value) != 2:
            raise ProfileError(f"{source}: {full} must be [width, height] in mm, got {value!r}")
        return tuple(_positive(source, full, v) for v in value)
    if key == "strict":
        if not isinstance(value, bool):
            raise ProfileError(f"{source}: {full} must be true or false, got {value!r}")
        return value
    if key == "inlay_fit_mm":
        return schema_key("output.inlay_fit_mm").check(
            value, name=full, prefix=f"{source}: ", error=ProfileError, param=full, note=False
        )
    if key == "joint_fit_mm":
        return schema_key("output.inlay_fit_mm").check(
            value, name=full, prefix=f"{source}: ", error=ProfileError, param=full, note=False
        )
    if key in ("mode", "print_style", "dxf_version", "joint"):
        return _choice(source, cutter, key, full, value)
    if key == "max_overhang_deg":
        angle = _positive(source, full, value)
        if angle >= 90:
            raise ProfileError(f"{source}: {full} must be > 0 and < 90 (degrees from vertical), got {value!r}")
        return angle
    zero_ok = key in (cutter.zero_keys if cutter else PRINTER_ZERO_KEYS) or key == "bed_margin_mm"
    return _positive(source, full, value, allow_zero=zero_ok or key in ("pierce_s", "price_per_kg", "price_per_m2"))


def _choice(source: str, cutter, key: str, full: str, value) -> str:
    """A profile's mode, print style or DXF version, one of its choices."""
    choices = {
        "mode": cutter.modes if cutter else LASER_MODES,
        "print_style": PRINT_STYLES,
        "dxf_version": DXF_VERSIONS,
        "joint": JOINTS,
    }[key]
    if value not in choices:
        hint = did_you_mean(value, choices)
        raise ProfileError(
            f"{source}: {full} = {value!r} is not valid{f' ({hint})' if hint else ''}, "
            f"must be one of: {', '.join(choices)}"
        )
    return value


def _renamed_style(section: dict, source: str) -> dict:
    """A printer section with its older ``style`` key read as ``print_style`` (the design key's name),
    with a :class:`~fabtiles.core.errors.FabtilesDeprecationWarning` saying the new name; both keys is an error."""
    import warnings

    from ..core.errors import FabtilesDeprecationWarning

    if "print_style" in section:
        raise ProfileError(f"{source}: printer.style and printer.print_style are one setting; keep print_style")
    warnings.warn(
        f"{source}: printer.style is now printer.print_style (the design key's name); rename it, "
        f"the old name will stop loading",
        FabtilesDeprecationWarning,
        stacklevel=4,
    )
    return {("print_style" if k == "style" else k): v for k, v in section.items()}


def _parse_layers(section, source) -> LaserLayers:
    if not isinstance(section, dict):
        raise ProfileError(f"{source}: [layers] must be a table")
    allowed = [f.name for f in fields(LaserLayers)]
    _unknown(source, "layers.", section, allowed)
    layers = {key: _layer(source, key, value) for key, value in section.items()}
    result = LaserLayers(**layers)
    names = [result.inner_cut.name, result.outer_cut.name, result.score.name]
    names += [result.engrave.name] if result.engrave is not None else []
    if len(set(names)) != len(names):
        count = {3: "three", 4: "four"}[len(names)]
        raise ProfileError(f"{source}: layers need {count} different names, got {', '.join(names)}")
    return result


def _layer(source: str, key: str, value) -> Layer:
    """One ``[layers]`` entry checked: its DXF name, its colour index and its settings."""
    full = f"layers.{key}"
    if not isinstance(value, dict):
        raise ProfileError(f'{source}: {full} must be a table like {{ name = "CUT", color = 1 }}')
    _unknown(source, f"{full}.", value, LAYER_KEYS)
    default = getattr(LaserLayers(), key) or Layer("FILL", 6, speed_mm_s=200.0, power_pct=20.0, line_interval_mm=0.1)
    lname = value.get("name", default.name)
    color = value.get("color", default.color)
    if not isinstance(lname, str) or not lname or any(c in lname for c in "<>/\\\":;?*|='"):
        raise ProfileError(
            f"{source}: {full}.name must be a non-empty DXF layer name without <>/\\\":;?*|=', got {lname!r}"
        )
    if isinstance(color, bool) or not isinstance(color, int) or not 1 <= color <= 255:
        raise ProfileError(f"{source}: {full}.color must be an AutoCAD Color Index 1..255, got {color!r}")
    return Layer(lname, color, **_layer_settings(value, default, source, full))


LAYER_KEYS = ("name", "color", "speed_mm_s", "power_pct", "passes", "line_interval_mm", "power_range_pct")
"""The keys of a ``[layers]`` entry."""


def _layer_settings(value: dict, default: Layer, source: str, full: str) -> dict:
    """A layer's laser settings, checked: speed > 0, power in (0, 100], passes >= 1, interval > 0."""
    speed = _positive(source, f"{full}.speed_mm_s", value.get("speed_mm_s", default.speed_mm_s))
    power = value.get("power_pct", default.power_pct)
    if isinstance(power, bool) or not isinstance(power, (int, float)) or not 0 < power <= 100:
        raise ProfileError(f"{source}: {full}.power_pct must be a percentage > 0 and <= 100, got {power!r}")
    passes = value.get("passes", default.passes)
    if isinstance(passes, bool) or not isinstance(passes, int) or passes < 1:
        raise ProfileError(f"{source}: {full}.passes must be a whole number >= 1, got {passes!r}")
    interval = value.get("line_interval_mm", default.line_interval_mm)
    if interval is not None:
        interval = _positive(source, f"{full}.line_interval_mm", interval)
    span = value.get("power_range_pct")
    if span is not None:
        span = _power_range(span, source, full)
    return dict(
        speed_mm_s=speed, power_pct=float(power), passes=passes, line_interval_mm=interval, power_range_pct=span
    )


def _power_range(span, source: str, full: str) -> tuple[float, float]:
    """A layer's ``power_range_pct``: two percentages in (0, 100], the first no greater than the second."""
    ok = isinstance(span, list) and len(span) == 2
    ok = ok and all(isinstance(v, (int, float)) and not isinstance(v, bool) and 0 < v <= 100 for v in span)
    if not ok or span[0] > span[1]:
        raise ProfileError(
            f"{source}: {full}.power_range_pct must be [lightest, darkest], two percentages > 0 and <= 100, "
            f"the first no greater, got {span!r}"
        )
    return float(span[0]), float(span[1])


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(PRINT_STYLES, "output.print_style")
