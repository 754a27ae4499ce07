"""The kinds of 2D cutter (fabtiles/machines/cutters.py): each kind's rules in one place, asked by no name elsewhere."""

from __future__ import annotations

import ast
import re
from dataclasses import fields, replace
from pathlib import Path

import pytest
import shapely
from shapely.geometry import box

from fabtiles import CutterProfile, LaserProfile, ParameterError, ProfileError, load_profile
from fabtiles.machines.cutters import (
    CUTTER_KINDS,
    KINDS,
    LASER,
    LASER_MODES,
    ROUTER,
    WATERJET,
    cutter_kind,
    family,
    members,
)

ROOT = Path(__file__).resolve().parents[2] / "fabtiles"
PROFILE_KINDS = set(CUTTER_KINDS) | {"printer"}
KIND_WORD = re.compile(r"kinds?")


def _mentions_kind(node) -> bool:
    """``node`` reads a kind: a name ``kind`` or ``kinds``, or an attribute ``.kind`` (not a keyword ``kind=``)."""
    return any(
        (isinstance(s, ast.Name) and KIND_WORD.fullmatch(s.id)) or (isinstance(s, ast.Attribute) and s.attr == "kind")
        for s in ast.walk(node)
    )


def _names_a_kind(node, tables) -> bool:
    """``node`` holds a profile kind's name ("router", ...) or one of ``tables`` (the names of the kinds)."""
    for sub in ast.walk(node):
        if isinstance(sub, ast.Constant) and isinstance(sub.value, str) and sub.value in PROFILE_KINDS:
            return True
        if isinstance(sub, (ast.Name, ast.Attribute)) and getattr(sub, "id", getattr(sub, "attr", None)) in tables:
            return True
    return False


def kind_checks(source: str) -> list[str]:
    """Every place ``source`` asks a profile for its kind by name: ``kind == "router"``, ``profile.kind in (...)``,
    ``kinds[n] != "printer"``, a ``match`` on a kind, a table keyed by "router" or "waterjet"."""
    # the tables of kinds: CUTTER_KINDS, and machines.cutters.KINDS (solid's KINDS are a printed body's)
    tables = {"CUTTER_KINDS"} | (
        {"KINDS"} if re.search(r"\bcutters import (\([^)]*|[^\n]*)\bKINDS\b|\bcutters\.KINDS", source) else set()
    )
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Compare):
            operands = [node.left, *node.comparators]
            if any(map(_mentions_kind, operands)) and any(_names_a_kind(o, tables) for o in operands):
                found.append(f"{node.lineno}: {ast.unparse(node)}")
        elif isinstance(node, ast.Match) and _mentions_kind(node.subject):
            if any(_names_a_kind(case.pattern, tables) for case in node.cases):
                found.append(f"{node.lineno}: match {ast.unparse(node.subject)}")
        elif isinstance(node, ast.Dict):
            if any(isinstance(k, ast.Constant) and k.value in ("router", "waterjet") for k in node.keys):
                found.append(f"{node.lineno}: {ast.unparse(node)[:80]}")
    return found


def test_no_kind_checks_outside_the_cutters_module():
    found = []
    for path in sorted(ROOT.rglob("*.py")):
        if path == ROOT / "machines" / "cutters.py":
            continue
        found += [f"{path.relative_to(ROOT.parent)}:{line}" for line in kind_checks(path.read_text(encoding="utf-8"))]
    assert found == []


@pytest.mark.parametrize(
    "code",
    [
        'if profile.kind == "laser": pass',
        'if p.kind != "router": pass',
        'x = kind in ("router", "waterjet")',
        'x = job.profile.kind == "waterjet"',
        "x = kind in CUTTER_KINDS",
        "from fabtiles.machines.cutters import (\n    KINDS)\nx = profile.kind in KINDS",
        "import fabtiles.machines.cutters\nx = profile.kind not in fabtiles.machines.cutters.KINDS",
        'x = [n for n in names if kinds[n] != "printer"]',
        'x = {"router": 1, "waterjet": 2}.get(kind)',
        'match profile.kind:\n    case "router":\n        pass',
    ],
)
def test_the_scan_finds_the_old_checks(code):
    assert len(kind_checks(code)) == 1


@pytest.mark.parametrize(
    "code",
    [
        'if p.kind == "archimedean": pass',  # a packing's kind
        'if kind in ("relief", "pattern"): pass',  # a printed part's kind
        "if kind not in KINDS: pass",  # solid.levels' KINDS: a printed body's
        'if family == "laser": pass',  # which profile a format takes
        'if profile_kind(fmt) == "laser": pass',
        'x = {"laser": a, "printer": b}',  # the web app's menus
        'x = load_profile(name, kind="laser").mode == "inlay"',  # a keyword, not a kind read
    ],
)
def test_the_scan_leaves_other_kinds_alone(code):
    assert kind_checks(code) == []


def test_the_table_is_the_profiles_kinds():
    assert tuple(KINDS) == CUTTER_KINDS == ("laser", "router", "waterjet")
    assert [
        cutter_kind(load_profile(n)) for n in ("laser-3mm-plywood", "router-6mm-mdf", "waterjet-1mm-aluminium")
    ] == [LASER, ROUTER, WATERJET]
    assert load_profile("router-6mm-mdf").cutter is ROUTER
    assert family("waterjet") == "laser" and family("printer") == "printer"
    assert members("laser") == CUTTER_KINDS and members("printer") == ("printer",)


def test_every_profile_key_belongs_to_a_kind():
    keys = [f.name for f in fields(CutterProfile) if f.name not in ("name", "description", "layers", "kind")]
    assert list(LASER.keys) == [k for k in keys if k != "tool_diameter_mm"]  # the order errors list them in
    assert set(ROUTER.keys) | set(WATERJET.keys) <= set(keys)
    for cutter in KINDS.values():
        assert set(cutter.required) <= set(cutter.keys) and set(cutter.zero_keys) <= set(cutter.keys)
        assert set(cutter.modes) <= set(LASER_MODES)


def test_what_each_kind_allows():
    assert [(c.opens_holes, c.card, c.inlay, c.kerf) for c in (LASER, ROUTER, WATERJET)] == [
        (False, True, True, "offset"),
        (True, False, False, "none"),
        (True, False, False, "jet"),
    ]
    assert [c.report_stats() for c in (LASER, ROUTER, WATERJET)] == [{}, {"cutter": "router"}, {"cutter": "waterjet"}]
    router = load_profile("router-6mm-mdf")
    assert ROUTER.tool_name(router) == "the 6 mm bit (tool_diameter_mm of router profile 'router-6mm-mdf')"
    assert [ROUTER.tool_radius(router), LASER.tool_radius(load_profile("laser-3mm-plywood"))] == [3.0, 0.0]


def test_the_files_comments():
    laser, router, jet = (load_profile(n) for n in ("laser-3mm-plywood", "router-6mm-mdf", "waterjet-1mm-aluminium"))
    assert LASER.dxf_comments(laser, 0.15) == ()
    assert WATERJET.dxf_comments(jet, 1.0) == (
        "fabtiles waterjet profile waterjet-1mm-aluminium: the 1 mm jet's centre path (corners rounded to 0.5 mm, "
        "kerf 1 mm compensated: contours half a kerf off the part); no CAM offset",
        "layers: INSIDE (inside profiles, cut first), OUTSIDE (outside profile, cut last); millimetres",
    )
    assert ROUTER.title(router, "pierced", 0.0) == (
        "fabtiles router, profile router-6mm-mdf: the part as the 6 mm "
        "bit makes it, no tool compensation (CAM offsets the tool)"
    )
    assert WATERJET.title(jet, "pierced", 1.0, num=lambda x: f"{x:.2f}", escape=str.upper) == (
        "fabtiles waterjet, profile WATERJET-1MM-ALUMINIUM: corners rounded to 0.50 mm, kerf 1.00 mm compensated"
    )
    assert (
        LASER.title(replace(laser, name="a<b"), "score", 0.2, escape=lambda s: s.replace("<", "&lt;"))
        == "fabtiles laser score, profile a&lt;b, kerf 0.2 mm"
    )


# every raise of the module, with its message


def test_check_profile():
    router = load_profile("router-6mm-mdf")
    ROUTER.check_profile(router)
    LASER.check_profile(load_profile("laser-3mm-plywood"))
    with pytest.raises(
        ProfileError,
        match=r"^router profile 'router-6mm-mdf': tool_diameter_mm must be > 0 "
        r"\(the bit's diameter in mm\), got -1\.0$",
    ):
        ROUTER.check_profile(replace(router, tool_diameter_mm=-1.0))
    with pytest.raises(
        ProfileError,
        match=r"^waterjet profile 'waterjet-1mm-aluminium': kerf_mm must be > 0 "
        r"\(the jet's diameter in mm\), got nan$",
    ):
        WATERJET.check_profile(replace(load_profile("waterjet-1mm-aluminium"), kerf_mm=float("nan")))


def test_check_mode():
    laser, router, jet = (load_profile(n) for n in ("laser-3mm-plywood", "router-6mm-mdf", "waterjet-1mm-aluminium"))
    for mode in (None, *LASER_MODES):
        LASER.check_mode(laser, mode)
    ROUTER.check_mode(router, "pierced")
    with pytest.raises(
        ParameterError,
        match=r"^'carve' is not a valid mode, must be one of: pierced, score, "
        r"engrave, inlay$",
    ):
        LASER.check_mode(laser, "carve")
    with pytest.raises(
        ParameterError,
        match=r"^mode must be 'pierced' for waterjet profile 'waterjet-1mm-aluminium' "
        r"\(a waterjet cuts through; score, engrave and inlay are laser "
        r"modes\), got 'inlay'$",
    ):
        WATERJET.check_mode(jet, "inlay")


def test_check_kerf():
    LASER.check_kerf(load_profile("laser-3mm-plywood"), 0.0)
    ROUTER.check_kerf(load_profile("router-6mm-mdf"), 0.0)
    with pytest.raises(
        ParameterError,
        match=r"^kerf_mm must be 0 for router profile 'router-6mm-mdf', got 0\.2: a "
        r"router file holds the part contour and CAM offsets the tool$",
    ):
        ROUTER.check_kerf(load_profile("router-6mm-mdf"), 0.2)
    with pytest.raises(
        ParameterError,
        match=r"^kerf_mm must be > 0 for waterjet profile 'waterjet-1mm-aluminium' "
        r"\(the jet's diameter\), got 0$",
    ):
        WATERJET.check_kerf(load_profile("waterjet-1mm-aluminium"), 0.0)


def test_check_card():
    # the formats each kind takes are the format table's (tests/export/test_formats.py)
    laser = load_profile("laser-3mm-plywood")
    LASER.check_card(laser)
    with pytest.raises(
        ParameterError,
        match=r"^the test card is for lasers; waterjet profile "
        r"'waterjet-1mm-aluminium' has no kerf or hole size",
    ):
        WATERJET.check_card(load_profile("waterjet-1mm-aluminium"))


def test_a_kind_that_is_no_cutters_is_a_profile_error():
    with pytest.raises(
        ProfileError,
        match=r"^profile 'x': kind must be one of: laser, router, waterjet, "
        r"got 'plasma'$",
    ):
        CutterProfile("x", kind="plasma")
    with pytest.raises(
        ProfileError,
        match=r"^profile 'fdm-0.4mm': kind must be one of: laser, router, waterjet, "
        r"got 'printer'$",
    ):
        cutter_kind(load_profile("fdm-0.4mm"))
    assert LaserProfile("y").cutter is LASER


# the writers called directly, without the dispatcher's checks

PLATE = box(0, 0, 60, 60).difference(shapely.union_all([box(10, 10, 25, 25), box(35, 35, 50, 50)]))


def test_a_lightburn_project_of_a_router_is_refused(tmp_path):
    from model_files import write_cut

    with pytest.raises(
        ParameterError,
        match=r"^a LightBurn project \(\.lbrn2\) is for lasers; router profile "
        r"'router-6mm-mdf' writes \.dxf or \.svg for its CAM$",
    ):
        write_cut(tmp_path / "t.lbrn2", region=PLATE, outline=box(0, 0, 60, 60), profile="router-6mm-mdf")
    assert list(tmp_path.iterdir()) == []


def test_an_inlay_kit_of_a_router_is_refused(tmp_path):
    from model_files import write_kit

    with pytest.raises(
        ParameterError,
        match=r"^mode must be 'pierced' for router profile 'router-6mm-mdf' \(a "
        r"router cuts through; score, engrave and inlay are laser modes\), "
        r"got 'inlay'$",
    ):
        write_kit(tmp_path / "t.dxf", region=PLATE, outline=box(0, 0, 60, 60), profile="router-6mm-mdf")
    assert list(tmp_path.iterdir()) == []
