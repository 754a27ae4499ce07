"""One schema of design keys: every key declared once in fabtiles/core/schema.py, every front end reading it."""

from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import pytest

from fabtiles.core import schema as _schema
from fabtiles.core.errors import DesignError, ParameterError, ProfileError
from fabtiles.core.schema import BuildOption, Key, Range, Widget

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "fabtiles"
NAMES = {k.name for k in _schema.KEYS}

# Collections of key names outside the schema that are values, not declarations of keys.
ALLOWED = {
    "fabtiles/web/gallery.py": "the gallery's entries: editor queries (values of keys), not keys",
    "fabtiles/web/params.py": "DEFAULTS, the page's start values; the sections of the query fields",
    "fabtiles/making/sweep.py": "the keys a sweep may not vary (formats come from --format, names are the sweep's)",
}


def key_collections(path: Path):
    """``(line, names)`` of each tuple, list, set or dict literal holding two or more design key names."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            elements = node.elts
        elif isinstance(node, ast.Dict):
            elements = [k for k in node.keys if k is not None]
        else:
            continue
        found = {e.value for e in elements if isinstance(e, ast.Constant) and isinstance(e.value, str)} & NAMES
        if len(found) >= 2:
            yield node.lineno, sorted(found)


def test_no_design_key_is_declared_outside_the_schema():
    """A list of key names anywhere else in the package is a second declaration: read the schema instead."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = str(path.relative_to(ROOT))
        if path == PACKAGE / "core" / "schema.py" or rel in ALLOWED:
            continue
        found += [f"{rel}:{line} {names}" for line, names in key_collections(path)]
    assert found == []


def test_the_scan_finds_a_declaration(tmp_path):
    """The scan is live: a module listing keys is caught."""
    module = tmp_path / "m.py"
    module.write_text('HEIGHTS = ("base_mm", "relief_mm")\nOTHER = ("x", "base_mm")\n')
    assert list(key_collections(module)) == [(1, ["base_mm", "relief_mm"])]


def test_the_javascript_lists_no_key():
    """The web form's sliders, boxes and menus come from /api/schema: app.js lists no keys but the query's own."""
    import re

    text = (PACKAGE / "web" / "static" / "app.js").read_text(encoding="utf-8")
    lists = [
        m.group(0)
        for m in re.finditer(r"\[[^\[\]]*\]", text)
        if len(set(re.findall(r'"(\w+)"', m.group(0))) & NAMES) >= 2
    ]
    # the menus with code of their own; the parameters the page always sends (the others only when set)
    assert lists == [
        '["preset", "special", "tiling"]',
        '["stroke", "join", "laser_profile", "laser_mode",\n'
        '                   "printer_profile", "print_style", "colour_by", "palette"]',
    ]


def test_the_validated_sections_hold_the_schemas_keys():
    from fabtiles.designs.design_file import OutputSpec, PackingSpec, SurfaceSpec, TileSpec
    from fabtiles.making.models import BuildOptions

    sections = ((PackingSpec, "packing"), (TileSpec, "tile"), (OutputSpec, "output"), (SurfaceSpec, "surface"))
    for cls, section in sections:
        assert {f.name for f in dataclasses.fields(cls)} == set(_schema.names(section)), section
        for f in dataclasses.fields(cls):
            k = _schema.key(f"{section}.{f.name}")
            if k.default is not None and not isinstance(k.default, dict):
                assert f.default == k.default, k.path
    options = {f.name for f in dataclasses.fields(BuildOptions)}
    assert {k.name for k in _schema.option_keys("cut") + _schema.option_keys("3mf") if k.unit != "mm"} <= options


def test_the_manual_tables_are_the_schemas():
    """docs/design-files.md's key tables are made from the schema: rerun
    `python -m fabtiles.core.schema docs/design-files.md`."""
    path = ROOT / "docs" / "design-files.md"
    text = path.read_text(encoding="utf-8")
    assert _schema.render_docs(text) == text
    assert _schema.main(["--check", str(path)]) == 0
    for section in _schema.SECTIONS:
        assert f"<!-- schema:{section} -->" in text


def test_the_docs_command_rewrites_a_drifted_table(tmp_path):
    path = tmp_path / "keys.md"
    good = f"# keys\n<!-- schema:tile -->\n{_schema.markdown_table('tile')}\n<!-- /schema:tile -->\nend\n"
    path.write_text(good.replace("`stroke`", "`strokes`"))
    assert _schema.main(["--check", str(path)]) == 1
    assert _schema.main([str(path)]) == 0 and path.read_text() == good
    assert _schema.main([]) == 2


def test_the_inlay_fit_range_is_declared_once():
    from fabtiles.geometry import calibration, inlay

    fit = _schema.key("output.inlay_fit_mm")
    assert inlay.FIT_RANGE_MM == (fit.range.min, fit.range.max) == (-0.5, 0.5)
    with pytest.raises(
        ParameterError,
        match=r"inlay_fit_mm must be a number of mm from -0\.5 to 0\.5 "
        r"\(positive: a press fit, negative: play\), got None",
    ) as info:
        inlay.check_fit(None)
    assert info.value.key == "inlay_fit_mm"
    assert calibration.FIT is fit and fit.range.clamp(-0.7) == -0.5


def test_design_errors_carry_their_key():
    from fabtiles.designs.design_file import design_from_text

    base = '[motif]\npreset = "table3-3"\n[tile]\nsize = 100\n'
    for extra, key in (
        ("[output]\ninlay_fit_mm = 0.8", "output.inlay_fit_mm"),
        ("[output]\nbase_mm = 0", "output.base_mm"),
        ("[output]\nformats = []", "output.formats"),
        ("[output]\nname = '../x'", "output.name"),
    ):
        with pytest.raises(DesignError, match=key.split(".")[1]) as info:
            design_from_text(base + extra)
        assert info.value.key == key


def test_profile_fit_error_names_the_profile_key(tmp_path):
    from fabtiles.machines.profiles import load_profile

    path = tmp_path / "p.toml"
    path.write_text('kind = "laser"\n[laser]\ninlay_fit_mm = true\n')
    with pytest.raises(ProfileError, match=r"laser\.inlay_fit_mm must be a number of mm from -0\.5 to 0\.5, got True"):
        load_profile(path)


def test_build_options_are_the_schemas():
    # the options each format takes: its row's family of options (the format table), the schema's list
    from fabtiles.core.schema import build_options
    from fabtiles.export.formats import FORMATS

    cut, printed, threemf = (build_options(FORMATS[f].options) for f in ("dxf", "stl", "3mf"))
    assert {build_options(FORMATS[f].options) for f in ("dxf", "svg", "lbrn2")} == {cut}
    assert build_options(FORMATS["step"].options) == printed
    assert cut == (
        "mode",
        "dxf_version",
        "kerf_mm",
        "fill_small_holes",
        "pieces",
        "pieces_sheets",
        "inlay_fit_mm",
        "inlay_pieces",
        "inlay_base",
        "tab_mm",
        "tabs_per_part",
        "colours",
    )
    assert threemf == printed[:-1] + ("inlay", "layout", "colours")
    assert "mosaic_inset_mm" in printed


# -- every raise of the module ----------------------------------------------------------------------------------------
def test_range_checks_its_ends():
    with pytest.raises(ParameterError, match=r"a Range's ends must be numbers or None, got 'a'"):
        Range("a", 1)
    with pytest.raises(ParameterError, match=r"a Range's ends must be numbers or None, got nan"):
        Range(0, float("nan"))
    with pytest.raises(ParameterError, match=r"a Range's min must be <= its max, got 2 > 1"):
        Range(2, 1)
    r = Range(0, 10, max_open=True)
    assert 0 in r and 10 not in r and float("nan") not in r and True not in r and "1" not in r
    assert r.text() == ">= 0 and < 10" and Range(None, 5).clamp(9) == 5


def test_widget_checks_its_kind():
    with pytest.raises(
        ParameterError,
        match=r"a widget's kind must be one of: slider, number, select, checkbox, "
        r"text, colour, got 'knob'",
    ):
        Widget(kind="knob")
    with pytest.raises(ParameterError, match=r"a slider needs min, max and step"):
        Widget(kind="slider", min=0, max=1)
    with pytest.raises(
        ParameterError,
        match=r"a widget's when must hold \(parameter, \(value, \.\.\.\)\) pairs, "
        r"got \('outline', 'rectangle'\)",
    ):
        Widget(kind="number", when=(("outline", "rectangle"),))


def test_a_colour_picker_is_a_colour_keys():
    """The page's colour pickers (``<input type="color">``) are the colour keys' and only theirs."""
    pickers = {k.path for k in _schema.KEYS if k.widget is not None and k.widget.kind == "colour"}
    assert pickers == {"colour.band_colour", "colour.base_colour"}
    assert all(_schema.key(p).type == "colour" for p in pickers)


def test_every_condition_of_a_control_names_a_form_parameter_and_its_values():
    """A control shown only where it applies names a parameter of the form, and values that parameter takes."""
    from fabtiles.web.params import FIELDS
    from fabtiles.web.schema_json import schema_json

    fields = schema_json()["fields"]
    conditions = [(q, pair) for q, f in fields.items() if f["widget"] for pair in f["widget"]["when"]]
    assert len(conditions) >= 15
    for query, (param, values) in conditions:
        if param in ("gap_rosette", "parquet"):  # the page's own boxes: the gap rosette, a parquet deformation
            assert list(values) == ["true"]
            continue
        assert param in FIELDS, (query, param)
        f = fields[param]
        valid = [v for v, _ in f["choices"]] if f["choices"] else ["true", "false"]
        assert set(values) <= set(valid), (query, param, values)


def test_build_option_checks_its_families():
    with pytest.raises(
        ParameterError,
        match=r"a build option's families must be some of: cut, print, 3mf, "
        r"got \('plot',\)",
    ):
        BuildOption(name="pen", families=("plot",))
    with pytest.raises(ParameterError, match=r"a build option's families must be some of"):
        BuildOption(name="pen", families=())


def test_key_checks_its_section_and_type():
    with pytest.raises(
        ParameterError,
        match=r"a key's section must be one of: motif, packing, tile, output, "
        r"colour, surface, got 'finish'",
    ):
        Key(section="finish", name="x", type="string", help="")
    with pytest.raises(ParameterError, match=r"a key's type must be one of: string, integer, .*, got 'date'"):
        Key(section="tile", name="x", type="date", help="")


def test_key_check():
    stroke = _schema.key("tile.stroke")
    assert stroke.check(2) == 2.0 and isinstance(stroke.check(2), float) and stroke.check(None) is None
    assert stroke.check(-1) == -1.0  # the tile checks the stroke's range (it depends on the radius)
    with pytest.raises(ParameterError, match=r"stroke must be a number of mm > 0, got True"):
        stroke.check(True)
    with pytest.raises(
        DesignError,
        match=r"^f: \[tile\] join = 'zigzag' is not valid, must be one of: miter, round, "
        r"bevel$",
    ) as info:
        _schema.key("tile.join").check("zigzag", prefix="f: [tile] ", error=DesignError, param="tile.join")
    assert info.value.key == "tile.join"
    with pytest.raises(ParameterError, match=r"tiling must be one of: 3\.3\.3\.3\.3\.3.*, got 488"):
        _schema.key("packing.tiling").check(488)
    assert _schema.key("packing.tiling").check("5.5.5") == "5.5.5"  # the tilings' own check names it
    with pytest.raises(ParameterError, match=r"base_mm must be a number of mm > 0 and <= 1000, got 1001"):
        _schema.key("output.base_mm").check(1001)
    with pytest.raises(ParameterError, match=r"n must be an integer >= 3 and <= 120, got 2\.5"):
        _schema.key("motif.n").check(2.5)
    with pytest.raises(ParameterError, match=r"tile\.size is a size: its value is checked where it is read"):
        _schema.key("tile.size").check(100)
    assert _schema.key("output.name").check("x") == "x"
    with pytest.raises(ParameterError, match=r"name must be a string, got 3"):
        _schema.key("output.name").check(3)
    with pytest.raises(ParameterError, match=r"interlace must be true or false, got 1"):
        _schema.key("tile.interlace").check(1)


def test_key_lookup():
    assert _schema.key("packing.gap_motif.n") is _schema.key("motif.n")
    assert _schema.key("packing.motifs.alpha") is _schema.key("motif.alpha")
    with pytest.raises(ParameterError, match=r"'tile\.colour' is not a design key, must be one of: motif\.preset"):
        _schema.key("tile.colour")
    with pytest.raises(
        ParameterError,
        match=r"'finish' is not a section, must be one of: motif, packing, tile, "
        r"output, colour",
    ):
        _schema.section_keys("finish")
    with pytest.raises(
        ParameterError,
        match=r"'plot' is not a family of build options, must be one of: cut, print, "
        r"3mf",
    ):
        _schema.build_options("plot")
    with pytest.raises(ParameterError, match=r"'plot' is not a family of build options"):
        _schema.option_keys("plot")


def test_every_key_is_documented_and_typed():
    for k in _schema.KEYS:
        assert k.help and k.path.count(".") == 1
        if k.type == "choice":
            assert k.choice_values(), k.path
        if k.widget is not None and k.widget.kind == "slider" and k.range is not None:
            assert k.widget.min in k.range or k.range.min == k.widget.min, k.path


def test_what_belongs_to_a_layer_above_is_registered_by_it():
    """A key's values and range checks that a layer owns are registered by a module of that layer, when imported."""
    import fabtiles.geometry.stack
    import fabtiles.geometry.tile

    layered = [k for k in _schema.KEYS if isinstance(k.choices, str)]
    assert {k.choices for k in layered} == {"pattern", "machines", "export", "designs"}
    for k in layered:
        assert k.choice_values(), k.path
    checked = [k for k in _schema.KEYS if k.checked_by is not None]
    assert {k.checked_by for k in checked} == {"pattern", "geometry"}
    for k in checked:
        assert k.checker is not None and k.checker.__module__.startswith(f"fabtiles.{k.checked_by}."), k.path
    assert _schema.key("tile.outline").checker is None  # the schema checks it: one of its choices
    assert fabtiles.geometry.tile.OUTLINES == _schema.key("tile.outline").choice_values()


def test_a_layers_values_not_registered_are_an_error(monkeypatch):
    """A key whose values no imported layer registered says so (a programming error, not a user's)."""
    unregistered = Key(section="tile", name="finish", type="choice", choices="geometry", help="a finish")
    with pytest.raises(
        LookupError,
        match=r"the values of tile\.finish are registered by the geometry layer, "
        r"which is not imported",
    ):
        unregistered.choice_values()
    monkeypatch.delitem(_schema._TYPE_CHECKS, "colour")
    with pytest.raises(
        LookupError,
        match=r"the colour values of colour\.band_colour are checked by a layer that "
        r"registers the check, and none is imported",
    ):
        _schema.key("colour.band_colour").check("navy")


def test_a_keys_bounds_and_build_option_are_its_declared_ones_and_never_none():
    fit = _schema.key("output.inlay_fit_mm")
    assert fit.bounds is fit.range and fit.build is fit.option
    bare = Key(section="tile", name="x", type="number", help="")
    with pytest.raises(LookupError, match=r"^the key tile\.x is declared without a range$"):
        _ = bare.bounds
    with pytest.raises(LookupError, match=r"^the key tile\.x is no build option$"):
        _ = bare.build
