"""The kinds of 2D cutter, each kind's rules in one place: a laser, a CNC router, a waterjet.

A cutter profile (:class:`~fabtiles.machines.profiles.CutterProfile`) names its kind in ``kind``;
the :class:`CutterKind` of that name holds everything that differs between the three:
the keys of its profile section, the modes it cuts, what its kerf means, whether it
opens holes by a tool's radius (the part as a router's bit or a waterjet's jet makes
it), whether it cuts the calibration card and inlay kits,
the comments its files carry, and the checks that raise when asked for more. Nothing
outside this module asks a profile for its kind by name (``tests/machines/test_cutters.py`` reads
the sources); the rest of the package asks the profile's :class:`CutterKind`.

>>> router = KINDS["router"]
>>> router.opens_holes, router.tool, router.modes
(True, 'bit', ('pierced',))
>>> KINDS["laser"].opens_holes, KINDS["laser"].inlay
(False, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.errors import ParameterError, ProfileError
from ..core.schema import register_choices
from ..core.validate import check_choice

LASER_MODES = ("pierced", "score", "engrave", "inlay")
"""Every mode a 2D cutter can be asked for (a laser makes them all)."""

FAMILY = "laser"
"""The family every 2D cutter belongs to: the profile kind the DXF, SVG and LightBurn formats take
(``load_profile(..., kind="laser")``) and the one design key ``[output] laser_profile``."""

JOINTS = ("dovetail", "jigsaw")
"""The joints that lock the pieces of a panel larger than the bed: a dovetail (a trapezoid whose head
is wider than its neck) or a jigsaw knob (a disc on a neck); every kind of cutter makes both."""

PIECE_KEYS = ("thickness_mm", "bed_margin_mm", "joint", "joint_fit_mm")
"""The keys of every cutter's section that say how a panel larger than the bed is cut as pieces."""

KERF_RULES = ("offset", "none", "jet")
"""What a cutter's kerf is: ``"offset"`` (>= 0, the contours offset by half of it), ``"none"``
(must be 0: the file holds the part contour and CAM offsets the tool), ``"jet"`` (> 0, the
jet's diameter: corners round to half of it, then it is offset as a laser's)."""


@dataclass(frozen=True)
class CutterKind:
    """The rules of one kind of 2D cutter (see the module text); :data:`KINDS` holds the three."""

    name: str
    """The profile's ``kind``, and the word messages, reports and titles use ("router profile 'x'", "router job")."""
    keys: tuple[str, ...]
    """The keys of the profile's section (``[laser]``, ``[router]``, ``[waterjet]``), in the order errors list them."""
    modes: tuple[str, ...] = ("pierced",)
    """The modes it cuts (a router and a waterjet only cut through)."""
    kerf: str = "offset"
    """Its kerf rule, one of :data:`KERF_RULES`."""
    zero_keys: tuple[str, ...] = ()
    """Keys of its section that may be 0 (a laser's kerfs); its other lengths must be > 0."""
    fixed: tuple[tuple[str, float], ...] = ()
    """Values set whatever the file says (a router's ``kerf_mm`` and ``min_hole_mm``: the file holds
    the part contour, and the bit decides which holes are cut)."""
    tool: str | None = None
    """The tool that opens its holes, named in messages (``"bit"``, ``"jet"``); None: holes cut as drawn."""
    tool_key: str | None = None
    """The profile key of the tool's diameter, required in its section and named in errors."""
    card: bool = False
    """Whether ``fabtiles calibrate``'s test card is for it (its rows measure a laser's kerf and holes)."""
    named_in_reports: bool = True
    """Whether reports name it (``stats["cutter"]``, "router job: ..."); a laser's reports say "laser" unasked."""
    layers: tuple[str, ...] = ("inner_cut", "outer_cut")
    """The profile layers its DXF declares, in order (an engrave layer only when the job engraves)."""
    dxf_note: str | None = None
    """What its DXF holds, the first 999 comment after ``fabtiles <kind> profile <name>:``; None: no comments.
    Filled with ``{d}`` (the tool's diameter), ``{r}`` (its radius) and ``{kerf}`` (mm)."""
    svg_title: str = ""
    """Its SVG's title, filled with ``{name}``, ``{mode}``, ``{d}``, ``{r}`` and ``{kerf}``."""
    bed_margin_mm: float = 5.0
    """The margin a piece of a panel keeps from the bed's edges unless the profile gives ``bed_margin_mm``."""
    tabs: bool = False
    """Whether fabtiles leaves holding tabs in its outer cut (``tab_mm``); a router's and a waterjet's file
    holds the part whole, and their CAM adds the tabs (with its lead-ins and its own tab heights)."""

    @property
    def opens_holes(self) -> bool:
        """Whether its files hold the part as its tool makes it: every hole opened by the tool's radius."""
        return self.tool is not None

    @property
    def inlay(self) -> bool:
        """Whether it cuts inlay kits."""
        return "inlay" in self.modes

    @property
    def required(self) -> tuple[str, ...]:
        """The keys its profile section must give: the tool's diameter."""
        return (self.tool_key,) if self.tool_key else ()

    def tool_diameter(self, profile):
        """The diameter of ``profile``'s tool as given (a waterjet's: its widest kerf), unchecked; 0 for none."""
        if not self.opens_holes:
            return 0.0
        if self.kerf == "jet":
            return max(profile.kerf_xy_mm)
        return getattr(profile, self.tool_key)  # type: ignore[arg-type]  # a kind that opens holes names its tool

    def tool_radius(self, profile) -> float:
        """The radius ``profile``'s tool rounds a hole's corners to; 0 for a laser.

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("router-6mm-mdf")
        >>> p.cutter.tool_radius(p)
        3.0
        """
        return float(self.tool_diameter(profile) or 0.0) / 2

    def tool_name(self, profile) -> str:
        """How a message names the tool: ``the 6 mm bit (tool_diameter_mm of router profile 'x')``.

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("waterjet-1mm-aluminium")
        >>> p.cutter.tool_name(p)
        "the 1 mm jet (kerf_mm of waterjet profile 'waterjet-1mm-aluminium')"
        """
        return (
            f"the {2 * self.tool_radius(profile):g} mm {self.tool} ({self.tool_key} of {self.name} profile "
            f"{profile.name!r})"
        )

    def check_profile(self, profile) -> None:
        """A router's bit and a waterjet's jet must be wider than 0: a :class:`~fabtiles.ProfileError` otherwise."""
        if not self.opens_holes:
            return
        d = self.tool_diameter(profile)
        if d is None or isinstance(d, bool) or not math.isfinite(d) or d <= 0:
            raise ProfileError(
                f"{self.name} profile {profile.name!r}: {self.tool_key} must be > 0 (the "
                f"{self.tool}'s diameter in mm), got {d!r}",
                param=self.tool_key,
            )

    def check_mode(self, profile, mode) -> None:
        """A ``mode`` it does not cut (None: the profile's own) is a :class:`~fabtiles.ParameterError`.

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("router-6mm-mdf")
        >>> p.cutter.check_mode(p, "engrave")
        Traceback (most recent call last):
        ...
        fabtiles.core.errors.ParameterError: mode must be 'pierced' for router profile 'router-6mm-mdf' (a router cuts through; score, engrave and inlay are laser modes), got 'engrave'
        """  # noqa: E501 - a doctest's lines are as Python prints them
        if mode is None or (isinstance(mode, str) and mode in self.modes):
            return
        if self.modes == LASER_MODES:  # every mode: then it is not a mode at all
            check_choice("mode", mode, self.modes)
        others = [m for m in LASER_MODES if m not in self.modes]
        listed = ", ".join(others[:-1]) + " and " + others[-1] if len(others) > 1 else others[0]
        raise ParameterError(
            f"mode must be {' or '.join(map(repr, self.modes))} for {self.name} profile "
            f"{profile.name!r} (a {self.name} cuts through; {listed} are laser modes), "
            f"got {mode!r}",
            param="mode",
        )

    def check_kerf(self, profile, kerf: float) -> None:
        """A kerf passed to an export, by the kind's kerf rule: a router's must be 0, a waterjet's > 0.

        (Below 0 is every cutter's error, raised where the option is read.)
        """
        if self.kerf == "none" and kerf != 0:
            raise ParameterError(
                f"kerf_mm must be 0 for {self.name} profile {profile.name!r}, got {kerf:g}: a "
                f"{self.name} file holds the part contour and CAM offsets the tool",
                param="kerf_mm",
            )
        if self.kerf == "jet" and kerf <= 0:
            raise ParameterError(
                f"kerf_mm must be > 0 for {self.name} profile {profile.name!r} (the {self.tool}'s "
                f"diameter), got {kerf:g}",
                param="kerf_mm",
            )

    def check_tabs(self, profile, tab_mm: float) -> None:
        """Holding tabs (``tab_mm`` > 0) asked of a cutter whose CAM adds them: a ParameterError.

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("router-6mm-mdf")
        >>> p.cutter.check_tabs(p, 0.0)
        >>> p.cutter.check_tabs(p, 0.5)
        Traceback (most recent call last):
        ...
        fabtiles.core.errors.ParameterError: tab_mm must be 0 for router profile 'router-6mm-mdf', got 0.5: a router file holds the part whole and CAM adds the holding tabs (with its lead-ins); set tab_mm = 0 and add tabs in CAM
        """  # noqa: E501 - a doctest's lines are as Python prints them
        if tab_mm and not self.tabs:
            raise ParameterError(
                f"tab_mm must be 0 for {self.name} profile {profile.name!r}, got {tab_mm:g}: a "
                f"{self.name} file holds the part whole and CAM adds the holding tabs (with its "
                "lead-ins); set tab_mm = 0 and add tabs in CAM",
                param="tab_mm",
            )

    def joint_corner_mm(self, profile) -> float:
        """The radius a joint's corners are rounded to: the tool's (a router's bit cannot cut a socket's
        inner corner sharper than its radius, so the tab is rounded to match); 0 for a laser.

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("router-6mm-mdf")
        >>> p.cutter.joint_corner_mm(p), load_profile("laser-3mm-plywood").cutter.joint_corner_mm(p)
        (3.0, 0.0)
        """
        return self.tool_radius(profile)

    def check_joint(self, profile, neck_mm: float) -> None:
        """A joint whose neck the tool cannot enter (a socket narrower than a router's bit or a waterjet's
        jet, with room for the rounding) is a :class:`~fabtiles.ParameterError`.

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("router-6mm-mdf")
        >>> p.cutter.check_joint(p, 12.0)
        >>> p.cutter.check_joint(p, 5.0)
        Traceback (most recent call last):
        ...
        fabtiles.core.errors.ParameterError: the dovetail joint's neck of 5 mm is narrower than the 6 mm bit (tool_diameter_mm of router profile 'router-6mm-mdf') can cut a socket for; give the profile a thickness_mm of at least 6 mm (the neck is as wide as the material is thick) or use a smaller bit
        """  # noqa: E501 - a doctest's lines are as Python prints them
        d = 2 * self.tool_radius(profile)
        if neck_mm < d - 1e-9:
            raise ParameterError(
                f"the {profile.joint} joint's neck of {neck_mm:g} mm is narrower than {self.tool_name(profile)} "
                f"can cut a socket for; give the profile a thickness_mm of at least {d:g} mm (the neck is as "
                f"wide as the material is thick) or use a smaller {self.tool}",
                param="thickness_mm",
            )

    def check_card(self, profile) -> None:
        """The calibration card of a cutter it is not for is a ParameterError."""
        if not self.card:
            raise ParameterError(
                f"the test card is for lasers; {self.name} profile {profile.name!r} has no kerf "
                "or hole size to measure this way: cut a test piece from the panel's own DXF",
                param="profile",
            )

    def report_stats(self) -> dict:
        """What a report's stats say of the cutter: ``{"cutter": "router"}``, nothing for a laser."""
        return {"cutter": self.name} if self.named_in_reports else {}

    def dxf_comments(self, profile, kerf_mm: float) -> tuple[str, ...]:
        """The comments (DXF group code 999) its DXF starts with: what the file holds, its layers; none for a laser.

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("router-6mm-mdf")
        >>> print("\\n".join(p.cutter.dxf_comments(p, 0.0)))
        fabtiles router profile router-6mm-mdf: the part as the 6 mm bit makes it (hole corners rounded to 3 mm), NO tool compensation: CAM offsets the tool
        layers: INSIDE (inside profiles, cut first), OUTSIDE (outside profile, cut last); millimetres
        """  # noqa: E501 - a doctest's lines are as Python prints them
        if self.dxf_note is None:
            return ()
        what = self.dxf_note.format(**self._values(profile, "", kerf_mm))
        layers = profile.layers
        return (
            f"fabtiles {self.name} profile {profile.name}: {what}",
            f"layers: {layers.inner_cut.name} (inside profiles, cut first), {layers.outer_cut.name} "
            "(outside profile, cut last); millimetres",
        )

    def title(self, profile, mode: str, kerf_mm: float, *, num=None, escape=None) -> str:
        """Its SVG's title: the laser's mode and kerf, or what a router's or waterjet's file holds.

        ``num`` formats the radius and the kerf, ``escape`` the profile's name (default: as given).

        >>> from fabtiles.machines.profiles import load_profile
        >>> p = load_profile("laser-3mm-plywood")
        >>> p.cutter.title(p, "pierced", 0.15)
        'fabtiles laser pierced, profile laser-3mm-plywood, kerf 0.15 mm'
        """
        return self.svg_title.format(**self._values(profile, mode, kerf_mm, num=num, escape=escape))

    def _values(self, profile, mode, kerf_mm, *, num=None, escape=None) -> dict:
        num = num or (lambda x: f"{x:g}")
        r = self.tool_radius(profile)
        return dict(name=(escape or str)(profile.name), mode=mode, d=f"{2 * r:g}", r=num(r), kerf=num(kerf_mm))


LASER = CutterKind(
    "laser",
    keys=(
        "kerf_mm",
        "kerf_x_mm",
        "kerf_y_mm",
        "min_feature_mm",
        "min_hole_mm",
        "tolerance_mm",
        "bed_mm",
        "mode",
        "strict",
        "dxf_version",
        "pierce_s",
        "travel_mm_s",
        "inlay_fit_mm",
        "min_piece_mm",
        "price_per_m2",
        *PIECE_KEYS,
    ),
    modes=LASER_MODES,
    kerf="offset",
    zero_keys=("kerf_mm", "kerf_x_mm", "kerf_y_mm"),
    card=True,
    named_in_reports=False,
    tabs=True,
    layers=("inner_cut", "outer_cut", "score", "engrave"),
    svg_title="fabtiles laser {mode}, profile {name}, kerf {kerf} mm",
)
ROUTER = CutterKind(
    "router",
    keys=(
        "tool_diameter_mm",
        "min_feature_mm",
        "tolerance_mm",
        "bed_mm",
        "mode",
        "strict",
        "dxf_version",
        "pierce_s",
        "travel_mm_s",
        "price_per_m2",
        *PIECE_KEYS,
    ),
    kerf="none",
    bed_margin_mm=10.0,
    fixed=(("kerf_mm", 0.0), ("min_hole_mm", 0.0)),
    tool="bit",
    tool_key="tool_diameter_mm",
    dxf_note="the part as the {d} mm bit makes it (hole corners rounded to {r} mm), NO tool compensation: "
    "CAM offsets the tool",
    svg_title="fabtiles router, profile {name}: the part as the {d} mm bit makes it, no tool compensation "
    "(CAM offsets the tool)",
)
WATERJET = CutterKind(
    "waterjet",
    keys=(
        "kerf_mm",
        "min_feature_mm",
        "min_hole_mm",
        "tolerance_mm",
        "bed_mm",
        "mode",
        "strict",
        "dxf_version",
        "pierce_s",
        "travel_mm_s",
        "price_per_m2",
        *PIECE_KEYS,
    ),
    kerf="jet",
    bed_margin_mm=10.0,
    tool="jet",
    tool_key="kerf_mm",
    dxf_note="the {d} mm jet's centre path (corners rounded to {r} mm, kerf {kerf} mm compensated: contours half "
    "a kerf off the part); no CAM offset",
    svg_title="fabtiles waterjet, profile {name}: corners rounded to {r} mm, kerf {kerf} mm compensated",
)

KINDS = {c.name: c for c in (LASER, ROUTER, WATERJET)}
"""Every kind of 2D cutter by name."""
CUTTER_KINDS = tuple(KINDS)
"""The names of the kinds, as a profile's ``kind`` gives them."""


def cutter_kind(profile) -> CutterKind:
    """The :class:`CutterKind` of a cutter profile; a ProfileError for a kind that is none.

    >>> from fabtiles.machines.profiles import load_profile
    >>> cutter_kind(load_profile("waterjet-1mm-aluminium")).kerf
    'jet'
    """
    try:
        return KINDS[profile.kind]
    except (KeyError, TypeError):
        raise ProfileError(
            f"profile {profile.name!r}: kind must be one of: {', '.join(CUTTER_KINDS)}, got {profile.kind!r}",
            param="kind",
        ) from None


def family(kind: str) -> str:
    """:data:`FAMILY` for every 2D cutter kind (they share one pipeline), else the kind itself.

    >>> family("router"), family("printer")
    ('laser', 'printer')
    """
    return FAMILY if kind in KINDS else kind


def members(fam: str) -> tuple[str, ...]:
    """The profile kinds of a family: ``("laser", "router", "waterjet")`` for the cutters.

    >>> members("laser"), members("printer")
    (('laser', 'router', 'waterjet'), ('printer',))
    """
    return CUTTER_KINDS if fam == FAMILY else (fam,)


# The schema names no module above it: the values and checks of its keys are registered from here.
register_choices(LASER_MODES, "output.laser_mode")
