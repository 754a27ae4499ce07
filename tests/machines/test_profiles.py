import pytest

import fabtiles as ft
from fabtiles.machines.profiles import CutterProfile, PrinterProfile, bundled_profiles, load_profile

GOOD_LASER = """
kind = "laser"
[laser]
kerf_mm = 0.1
bed_mm = [300, 200]
[layers]
score = { name = "ENGRAVE", color = 2 }
"""


def write(tmp_path, text, name="p.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_bundled_profiles_load_and_have_the_issue_beds():
    assert set(bundled_profiles()) == {
        "laser-3mm-plywood",
        "laser-3mm-acrylic",
        "fdm-0.4mm",
        "fdm-0.6mm",
        "router-6mm-mdf",
        "router-3.175mm-plywood",
        "waterjet-1mm-aluminium",
    }
    for name in ("laser-3mm-plywood", "laser-3mm-acrylic"):
        p = load_profile(name, kind="laser")
        assert isinstance(p, CutterProfile) and p.bed_mm[0] >= 600 and p.bed_mm[1] >= 400
    for name in ("fdm-0.4mm", "fdm-0.6mm"):
        p = load_profile(name, kind="printer")
        assert isinstance(p, PrinterProfile)
        assert p.min_wall_mm == pytest.approx(2 * p.nozzle_mm)


def test_profile_from_path_with_defaults(tmp_path):
    p = load_profile(write(tmp_path, GOOD_LASER))
    assert p.name == "p" and p.kerf_mm == 0.1 and p.bed_mm == (300.0, 200.0)
    assert p.layers.score.name == "ENGRAVE" and p.layers.score.color == 2
    assert p.layers.outer_cut.name == "OUTER"  # default kept
    assert load_profile(p) is p


def test_profiles_are_frozen():
    p = load_profile("fdm-0.4mm")
    with pytest.raises(AttributeError):
        p.base_mm = 5


@pytest.mark.parametrize(
    "text, match",
    [
        (
            'kind = "laser"\n[laser]\nkerf = 0.1\n',
            r"p.toml: unknown key laser.'kerf' \(did you mean 'kerf_mm'\?\); valid keys: kerf_mm",
        ),
        ('kind = "laser"\ncolour = 1\n', r"p.toml: unknown key 'colour'; valid keys: kind"),
        ('kind = "plasma"\n', r"p.toml: kind must be one of: laser, router, waterjet, printer, got 'plasma'"),
        ('kind = "laser"\n[laser]\nkerf_mm = -0.1\n', r"p.toml: laser.kerf_mm must be >= 0, got -0.1"),
        ('kind = "laser"\n[laser]\nmin_hole_mm = 0\n', r"p.toml: laser.min_hole_mm must be > 0, got 0"),
        (
            'kind = "laser"\n[laser]\ntolerance_mm = "fine"\n',
            r"p.toml: laser.tolerance_mm must be a finite number, got 'fine'",
        ),
        (
            'kind = "laser"\n[laser]\ntolerance_mm = nan\n',
            r"p.toml: laser.tolerance_mm must be a finite number, got nan",
        ),
        ('kind = "laser"\n[laser]\nbed_mm = [600]\n', r"p.toml: laser.bed_mm must be \[width, height\] in mm"),
        ('kind = "laser"\n[laser]\nstrict = "yes"\n', r"p.toml: laser.strict must be true or false"),
        (
            'kind = "router"\n[router]\ntool_diameter_mm = 3\njoint = "finger"\n',
            r"p.toml: router.joint = 'finger' is not valid, must be one of: dovetail, jigsaw",
        ),
        (
            'kind = "laser"\n[laser]\njoint_fit_mm = 0.7\n',
            r"p.toml: laser.joint_fit_mm must be a number of mm from -0.5 to 0.5, got 0.7",
        ),
        ('kind = "laser"\n[laser]\nbed_margin_mm = -1\n', r"p.toml: laser.bed_margin_mm must be >= 0, got -1"),
        ('kind = "laser"\n[laser]\nthickness_mm = 0\n', r"p.toml: laser.thickness_mm must be > 0, got 0"),
        (
            'kind = "laser"\n[laser]\nmode = "etch"\n',
            r"p.toml: laser.mode = 'etch' is not valid, must be one of: pierced, score, engrave",
        ),
        (
            'kind = "laser"\n[laser]\ndxf_version = "R14"\n',
            r"laser.dxf_version = 'R14' is not valid \(did you mean 'R12'\?\), must be one of: R12, R2000",
        ),
        (
            'kind = "printer"\n[printer]\nprint_style = "emboss"\n',
            r"printer.print_style = 'emboss' is not valid "
            r"\(did you mean 'deboss'\?\), must be one of: relief, pierced, deboss",
        ),
        ('kind = "printer"\n[printer]\nbase_mm = -2\n', r"printer.base_mm must be > 0, got -2"),
        (
            'kind = "printer"\n[printer]\nmax_overhang_deg = 90\n',
            r"p.toml: printer.max_overhang_deg must be > 0 and < 90 \(degrees from vertical\), got 90",
        ),
        ('kind = "printer"\n[printer]\nmax_overhang_deg = 0\n', r"p.toml: printer.max_overhang_deg must be > 0, got 0"),
        ('kind = "printer"\n[printer]\nmax_bridge_mm = -1\n', r"p.toml: printer.max_bridge_mm must be >= 0, got -1"),
        (
            'kind = "laser"\n[layers]\nscore = { name = "S", color = 300 }\n',
            r"layers.score.color must be an AutoCAD Color Index 1..255, got 300",
        ),
        (
            'kind = "laser"\n[layers]\nscore = { name = "S", colour = 3 }\n',
            r"unknown key layers.score.'colour' \(did you mean 'color'\?\)",
        ),
        (
            'kind = "laser"\n[layers]\nscore = { name = "A/B" }\n',
            r"layers.score.name must be a non-empty DXF layer name",
        ),
        ('kind = "laser"\n[layers]\nscore = "S"\n', r"layers.score must be a table"),
        ('kind = "laser"\n[layers]\nstencil = { name = "S" }\n', r"unknown key layers.'stencil'"),
        ('kind = "laser"\n[layers]\nscore = { name = "OUTER" }\n', r"layers need three different names"),
        ('kind = "laser"\nlayers = 3\n', r"\[layers\] must be a table"),
        ('kind = "laser"\nlaser = 3\n', r"\[laser\] must be a table"),
        ('kind = "printer"\n[laser]\nkerf_mm = 1\n', r"a printer profile cannot have a \[laser\] section"),
        ('kind = "laser"\ndescription = 3\n', r"description must be text, got 3"),
        ('kind = "laser"\n[laser\n', r"p.toml: not valid TOML"),
    ],
)
def test_bad_profiles_name_file_and_key(tmp_path, text, match):
    with pytest.raises(ft.ProfileError, match=match):
        load_profile(write(tmp_path, text))


def test_unknown_bundled_profile_suggests_and_lists():
    with pytest.raises(
        ft.ProfileError,
        match=r"profile 'laser-3mm-plywod' does not exist "
        r"\(did you mean 'laser-3mm-plywood'\?\); bundled profiles: fdm-0.4mm, "
        r"fdm-0.6mm \(printer\), laser-3mm-acrylic",
    ):
        load_profile("laser-3mm-plywod")


def test_an_unknown_profile_is_matched_among_the_slots_kind():
    # meant as a laser's: a laser profile is suggested, the router's near name said apart with its kind
    with pytest.raises(
        ft.ProfileError,
        match=r"profile 'laser-5mm-mdf' does not exist \(did you mean "
        r"'laser-3mm-plywood'\?; a router profile is near: 'router-6mm-mdf'\); "
        r"bundled profiles for this slot: laser-3mm-acrylic, laser-3mm-plywood "
        r"\(laser\), router-3.175mm-plywood, router-6mm-mdf \(router\)",
    ):
        load_profile("laser-5mm-mdf", kind="laser")
    # a printer slot names no cutter, however near
    with pytest.raises(
        ft.ProfileError,
        match=r"profile 'laser-3mm-plywod' does not exist; bundled printer "
        r"profiles: fdm-0.4mm, fdm-0.6mm; or give the path",
    ):
        load_profile("laser-3mm-plywod", kind="printer")


def test_unreadable_file(tmp_path):
    with pytest.raises(ft.ProfileError, match=r"cannot read profile file '.*missing.toml'"):
        load_profile(tmp_path / "missing.toml")


def test_wrong_kind_is_named():
    with pytest.raises(
        ft.ProfileError,
        match=r"'fdm-0.4mm' is a printer profile, but a laser profile is needed here "
        r"\(or a router or waterjet one\); bundled laser profiles: laser-3mm-acrylic, "
        r"laser-3mm-plywood, router-3.175mm-plywood, router-6mm-mdf, waterjet-1mm-aluminium",
    ):
        load_profile("fdm-0.4mm", kind="laser")


def test_bad_profile_argument_type():
    with pytest.raises(ft.ProfileError, match=r"profile must be a profile name or a path to a .toml file, got 3"):
        load_profile(3)


@pytest.mark.parametrize(
    "line,match",
    [
        ("min_hole_mm = -0.2", r"p.toml: printer.min_hole_mm must be >= 0, got -0.2"),
        ("min_hole_mm = nan", r"p.toml: printer.min_hole_mm must be a finite number, got nan"),
        ("min_hole_mm = inf", r"p.toml: printer.min_hole_mm must be a finite number, got inf"),
        ("min_hole_mm = true", r"p.toml: printer.min_hole_mm must be a finite number, got True"),
    ],
)
def test_bad_printer_min_hole(tmp_path, line, match):
    with pytest.raises(ft.ProfileError, match=match):
        load_profile(write(tmp_path, f'kind = "printer"\n[printer]\n{line}\n'))


def test_printer_min_hole_given_default_and_off(tmp_path):
    assert load_profile(write(tmp_path, 'kind = "printer"\n[printer]\nnozzle_mm = 0.25\n')).min_hole_mm == 0.5
    given = load_profile(write(tmp_path, 'kind = "printer"\n[printer]\nnozzle_mm = 0.4\nmin_hole_mm = 0.6\n'))
    assert given.min_hole_mm == 0.6
    assert load_profile(write(tmp_path, 'kind = "printer"\n[printer]\nmin_hole_mm = 0\n')).min_hole_mm == 0.0


def test_printer_overhang_limit_and_bridge_default_given_and_off(tmp_path):
    bundled = load_profile("fdm-0.4mm")
    assert (bundled.max_overhang_deg, bundled.max_bridge_mm) == (45.0, 5.0)
    given = load_profile(write(tmp_path, 'kind = "printer"\n[printer]\nmax_overhang_deg = 55\nmax_bridge_mm = 0\n'))
    assert (given.max_overhang_deg, given.max_bridge_mm) == (55.0, 0.0)


def test_a_printers_old_style_key_loads_with_a_note_naming_print_style(tmp_path):
    from fabtiles.core.errors import FabtilesDeprecationWarning

    path = write(tmp_path, 'kind = "printer"\n[printer]\nstyle = "deboss"\n')
    with pytest.warns(FabtilesDeprecationWarning, match=r"p.toml: printer.style is now printer.print_style"):
        assert load_profile(path).print_style == "deboss"
    both = write(tmp_path, 'kind = "printer"\n[printer]\nstyle = "deboss"\nprint_style = "relief"\n')
    with pytest.raises(
        ft.ProfileError,
        match=r"printer.style and printer.print_style are one setting; keep "
        r"print_style",
    ):
        load_profile(both)


def test_the_cli_prints_the_renamed_key_as_one_note(tmp_path):
    from click.testing import CliRunner

    from fabtiles.cli.main import cli

    path = tmp_path / "old.toml"
    path.write_text('kind = "printer"\n[printer]\nstyle = "pierced"\n')
    result = CliRunner().invoke(cli, ["profile", "show", str(path)])
    assert result.exit_code == 0, result.output
    assert result.stderr == (
        f"fabtiles: note: {path}: printer.style is now printer.print_style (the design "
        f"key's name); rename it, the old name will stop loading\n"
    )


def test_the_pieces_keys_defaults_by_kind(tmp_path):
    # a laser's pieces keep 5 mm from the bed's edges, a router's and a waterjet's 10 mm (the clamps)
    laser = load_profile(write(tmp_path, 'kind = "laser"\n'))
    assert (laser.margin_mm, laser.joint, laser.joint_fit_mm, laser.thickness_or_default_mm) == (
        5.0,
        "dovetail",
        0.1,
        3.0,
    )
    assert load_profile("router-6mm-mdf").margin_mm == 10.0
    assert load_profile("waterjet-1mm-aluminium").margin_mm == 10.0
    mine = load_profile(
        write(tmp_path, 'kind = "laser"\n[laser]\nbed_margin_mm = 0\njoint = "jigsaw"\nthickness_mm = 4\n')
    )
    assert (mine.margin_mm, mine.joint, mine.thickness_or_default_mm) == (0.0, "jigsaw", 4.0)
