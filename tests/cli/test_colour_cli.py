"""The colours from the command line (issue 33): classes listed, --set of colours, bad input exit 2."""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner
from designs import design_toml

from fabtiles.cli.main import cli

SAMPLE = Path(__file__).resolve().parents[2] / "samples" / "mosaic-iznik.toml"

SMALL = design_toml(
    radius=12.5,
    stroke=1.2,
    output={"formats": ["3mf", "stl"], "print_style": "mosaic"},
    colour={"by": "shape", "palette": "zellige"},
)


def run(*args):
    return CliRunner().invoke(cli, [*map(str, args)], catch_exceptions=False)


def test_check_lists_the_face_classes_with_their_colours():
    result = run("check", SAMPLE)
    assert result.exit_code == 0, result.output
    lines = [line.strip() for line in result.output.splitlines() if "face class" in line]
    # C and D are narrower than the printer's min_hole_mm: filled with the bands, in no colour of their own
    assert lines == [
        "face class A: 108 x concave octagon, 3,035.9 mm^2, cobalt",
        "face class B: 23 x 24-gon, 1,606.0 mm^2, turquoise",
        "face class C: 28 x 6-point star, 8.4 mm^2, filled with the bands (too small to make)",
        "face class D: 212 x kite, 4.5 mm^2, filled with the bands (too small to make)",
    ]
    assert (
        "  print: 4 parts, one filament each: navy (base), white (bands), cobalt (A), turquoise (B)\n" in result.output
    )


def test_check_without_filling_prints_every_class_in_its_colour():
    result = run("check", SAMPLE, "--set", "output.fill_small_holes=false")
    assert "face class C: 28 x 6-point star, 8.4 mm^2, bole" in result.output
    assert (
        "print: 6 parts, one filament each: navy (base), white (bands), cobalt (A), turquoise (B), bole (C), "
        "green (D)" in result.output
    )


def test_a_filled_class_names_no_part():
    # Mamluk's third colour is its base's black: class C, filled, is not in the base's part
    result = run("check", SAMPLE, "--set", "colour.palette=mamluk")
    assert "print: 4 parts, one filament each: black (base), gold (bands), lapis (A), red (B)" in result.output


def test_a_palette_name_the_summary_prints_is_typed_back(tmp_path):
    # iznik's cobalt and white by name: C joins A's part, B the bands' (no CSS white of its own)
    result = run(
        "build",
        SAMPLE,
        "-o",
        tmp_path / "out",
        "--set",
        "colour.faces.A=turquoise",
        "--set",
        "colour.faces.B=white",
        "--set",
        'output.formats=["3mf"]',
        "--set",
        "output.fill_small_holes=false",
        "--set",
        "colour.faces.C=cobalt",
        "--set",
        'colour.faces.D="#1e4fa0"',
    )
    assert result.exit_code == 0, result.output
    assert "face class C: 28 x 6-point star, 8.4 mm^2, cobalt" in result.output
    assert "face class D: 212 x kite, 4.5 mm^2, cobalt" in result.output  # the hex takes the palette's name
    material = re.search(r"print material: (.*)", result.output).group(1)
    assert re.search(
        r"\(navy \(base\) [0-9.]+ g, white \(bands, B\) [0-9.]+ g, turquoise \(A\) [0-9.]+ g, "
        r"cobalt \(C, D\) [0-9.]+ g\)",
        material,
    ), material


def test_band_and_base_join_a_class_to_their_parts():
    result = run("check", SAMPLE, "--set", "colour.faces.A=band", "--set", "colour.faces.B=base")
    assert result.exit_code == 0, result.output
    assert "print: 2 parts, one filament each: navy (base, B), white (bands, A)" in result.output
    assert "face class A: 108 x concave octagon, 3,035.9 mm^2, white" in result.output


def test_an_unknown_colour_name_suggests_palette_names():
    result = CliRunner().invoke(cli, ["check", str(SAMPLE), "--set", "colour.faces.C=cobalx"])
    assert result.exit_code == 2 and result.output.count("\n") == 1
    assert "C 'cobalx' is not a CSS or palette colour name (did you mean 'cobalt'?)" in result.output


def test_set_gives_a_class_its_colour_and_a_palette():
    result = run("check", SAMPLE, "--set", "colour.faces.B=navy", "--set", "colour.palette=mamluk")
    assert result.exit_code == 0, result.output
    assert "face class A: 108 x concave octagon, 3,035.9 mm^2, lapis" in result.output
    assert "face class B: 23 x 24-gon, 1,606.0 mm^2, navy" in result.output


def test_a_mosaic_build_writes_a_part_per_colour(tmp_path):
    design = tmp_path / "m.toml"
    design.write_text(SMALL + '[colour.faces]\nB = "#1d4e89"\n')  # B in A's cobalt: one filament for both
    result = run("build", design, "-o", tmp_path / "out")
    assert result.exit_code == 0, result.output
    names = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert names == ["m-black.stl", "m-cobalt.stl", "m-white.stl", "m.3mf"]
    material = re.search(r"print material: (.*)", result.output).group(1)
    # zellige's fourth colour is its base's black, but class D is filled with the bands: in no part
    assert re.search(r"\(black \(base\) [0-9.]+ g, white \(bands\) [0-9.]+ g, cobalt \(A, B\) [0-9.]+ g\)", material)
    assert "face class D: 62 x kite, 1.3 mm^2, filled with the bands (too small to make)" in result.output


def test_a_letter_the_design_lacks_is_one_line_exit_2(tmp_path):
    design = tmp_path / "bad.toml"
    design.write_text(SMALL + '[colour.faces]\nZ = "red"\n')
    for command in (("build", design, "-o", tmp_path / "out"), ("check", design)):
        result = CliRunner().invoke(cli, list(map(str, command)))
        assert result.exit_code == 2
        assert result.output.count("\n") == 1
        assert re.search(r"face class 'Z' is not one of this design's: A, B, C, D$", result.output.strip())
    assert not (tmp_path / "out").exists()


def test_more_than_sixteen_colours_is_refused(tmp_path):
    """A design of 17 classes, each its own colour, is more filaments than a slicer takes: exit 2, no file."""
    import numpy as np
    import pytest
    import shapely

    from fabtiles import ParameterError
    from fabtiles.designs.colour import Colours, letters
    from fabtiles.designs.design_file import design_from_text
    from fabtiles.geometry.faces import FaceClass, FaceClasses
    from fabtiles.making.models import BuildOptions, Models

    design = design_from_text(SMALL)
    faces = np.array([shapely.box(3 * k, 0, 3 * k + 2, 2) for k in range(17)], dtype=object)
    classes = FaceClasses(faces, np.arange(17), tuple(FaceClass(c, 1, "square", 4.0) for c in letters(17)))
    colours = Colours(by="shape", faces={c: f"#0000{k:02x}" for k, c in enumerate(letters(17))})
    models = Models(
        design.build_tile(), BuildOptions(**{**BuildOptions.of_design(design).__dict__, "colours": colours})
    )
    models.__dict__["face_classes"] = classes
    with pytest.raises(
        ParameterError,
        match=r"the print has 19 distinct colours, more than the 16 filaments a "
        r"slicer takes; give some face classes the same colour",
    ):
        models.mosaic_specs()


def test_an_inset_not_below_the_relief_is_one_line_exit_2(tmp_path):
    design = tmp_path / "m.toml"
    design.write_text(
        SMALL.replace('print_style = "mosaic"', 'print_style = "mosaic"\nrelief_mm = 1.0\nmosaic_inset_mm = 1.0')
    )
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and result.output.count("\n") == 1
    assert (
        "mosaic_inset_mm must be smaller than relief_mm (the bands stand 1 mm above the plate), got 1" in result.output
    )
    assert not (tmp_path / "out").exists()
    design.write_text(SMALL.replace('print_style = "mosaic"', 'print_style = "mosaic"\nmosaic_inset_mm = -0.5'))
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and "mosaic_inset_mm must be a finite number >= 0" in result.output


def test_a_kits_classes_of_no_piece_are_listed_as_filled(tmp_path):
    result = run("build", SAMPLE, "-o", tmp_path / "kit", "--set", "output.laser_mode=inlay", "--format", "svg")
    assert result.exit_code == 0, result.output
    assert "face class A: 108 x concave octagon, 3,035.9 mm^2, cobalt" in result.output
    assert "face class C: 28 x 6-point star, 8.4 mm^2, filled with the bands (too small to make)" in result.output
    assert sorted(p.name for p in (tmp_path / "kit").iterdir()) == [
        "mosaic-iznik-lattice.svg",
        "mosaic-iznik-pieces-cobalt.svg",
        "mosaic-iznik-pieces-turquoise.svg",
    ]


def test_a_coloured_relief_says_its_parts_in_their_colours():
    result = run("check", SAMPLE, "--set", "output.print_style=relief")
    assert "  print: 2 parts (navy (base), white (pattern)), 2 filaments\n" in result.output
    result = run("check", SAMPLE, "--set", "output.print_style=pierced")
    assert "  print: 1 part (white (pattern)), 1 filament\n" in result.output
