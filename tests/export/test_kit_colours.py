"""A coloured inlay kit (issue 33): the lattice in the band's wood and a pieces file per face colour.

The pieces files are read back with ezdxf and compared with the face classes by GEOS:
each holds exactly the faces of its colour (those large enough for a piece), each
piece its face grown by the fit and half the kerf.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from designs import design_toml
from dxf_helpers import read_checked, ring_polygons

from fabtiles.designs.design_file import design_from_text
from fabtiles.machines.profiles import load_profile
from fabtiles.making import build_design
from fabtiles.making.models import BuildOptions, Models

DESIGN = design_toml(
    radius=12.5,
    size=80,
    stroke=1.5,
    output={"formats": ["dxf"], "laser_mode": "inlay"},
    colour={"by": "shape", "palette": "alhambra"},
)


@pytest.fixture(scope="module")
def kit(tmp_path_factory):
    out = tmp_path_factory.mktemp("kit")
    design = design_from_text(DESIGN, name="kit")
    result = build_design(design, out)
    return out, result, Models(design.build_tile(), BuildOptions.of_design(design))


def test_a_pieces_file_per_face_colour(kit):
    out, result, _models = kit
    names = sorted(p.name for p in out.iterdir())
    # class C (6-point stars) is too small for a piece anywhere: no blue sheet
    assert names == ["kit-lattice.dxf", "kit-pieces-green.dxf", "kit-pieces-ochre.dxf"]
    (report,) = result.reports
    assert report.stats["files"] == [
        str(out / n) for n in ("kit-lattice.dxf", "kit-pieces-green.dxf", "kit-pieces-ochre.dxf")
    ]
    by_colour = report.stats["pieces_by_colour"]
    assert {k: v["pieces"] for k, v in by_colour.items()} == {"green": 68, "ochre": 11}


@pytest.mark.parametrize("colour, letter", [("green", "A"), ("ochre", "B")])
def test_each_pieces_file_holds_exactly_its_colours_faces(kit, colour, letter):
    out, _, models = kit
    profile = load_profile("laser-3mm-plywood")
    kerf, fit = max(profile.kerf_xy_mm), profile.inlay_fit_mm
    doc = read_checked(out / f"kit-pieces-{colour}.dxf")
    # every file of the kit is the tile moved by the lattice outline's half kerf: moved back to the faces
    shift = np.array(profile.kerf_xy_mm) / 2
    layers = {layer.dxf.name for layer in doc.layers}
    cuts = [shapely.transform(p, lambda c: c - shift) for p in ring_polygons(doc, layers) if p.area > 0]
    faces = shapely.get_parts(models.face_classes.of(letter))
    faces = faces[shapely.area(faces) > 1.0]  # the faces large enough for a piece
    assert len(cuts) == len(faces)
    tree = shapely.STRtree(cuts)
    for face in faces:
        (hit,) = tree.query(face.representative_point(), predicate="within")
        cut = cuts[hit]
        # the cut path is the face grown by the fit and half the kerf (its sharp tips rounded as the beam
        # rounds the hole's): it holds the face's inside, and lies within the face grown by that
        assert cut.contains(face.buffer(-kerf / 2))
        assert face.buffer(fit + kerf / 2 + 0.01).contains(cut)
        assert cut.area == pytest.approx(face.buffer(fit + kerf / 2).area, rel=0.03)
    # nothing of another colour on this sheet
    others = shapely.union_all(
        [models.face_classes.of(c.letter) for c in models.face_classes.classes if c.letter != letter]
    )
    assert all(shapely.intersection(c, others).area < 1e-6 for c in cuts)


def test_the_report_names_each_wood(kit):
    _, result, _ = kit
    text = result.reports[0].summary()
    assert "pieces in green: 68 pieces" in text and "lattice in white (the band colour)" in text
    assert "face class A: 68 x" in text


def test_an_uncoloured_kit_keeps_its_two_files(tmp_path):
    design = design_from_text(DESIGN.split("[colour]")[0], name="kit")
    build_design(design, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kit-lattice.dxf", "kit-pieces.dxf"]


@pytest.mark.parametrize(
    "colour, files",
    [
        ('[colour]\nby = "none"\n', ["kit-lattice.dxf", "kit-pieces-cobalt.dxf"]),
        ('[colour]\nby = "none"\n[colour.faces]\nA = "teal"\n', ["kit-lattice.dxf", "kit-pieces-teal.dxf"]),
    ],
)
def test_any_colour_section_names_the_pieces_by_colour(tmp_path, colour, files):
    """One rule: with a [colour] section, every pieces file is -pieces-<colour>, one class or many."""
    design = design_from_text(DESIGN.split("[colour]")[0] + colour, name="kit")
    build_design(design, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == files


# every hole of this tile is narrower than 1.2 mm, so none is large enough for a piece (2.4 mm)
NO_PIECES = design_toml(
    preset="table3-2",
    packing={"kind": "archimedean", "tiling": "3.3.3.3.3.3", "edge": 10.14},
    radius=None,
    size=[89.5, 89.5],
    stroke=2.0,
    output={"formats": ["dxf"], "laser_mode": "inlay"},
)


@pytest.mark.parametrize("colour", ["", '[colour]\nby = "shape"\n', '[colour]\nby = "none"\n'])
def test_a_kit_with_no_piece_writes_no_pieces_file(tmp_path, colour):
    design = design_from_text(NO_PIECES + colour, name="kit")
    build_design(design, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kit-lattice.dxf"]
    report = Models(design.build_tile(), BuildOptions.of_design(design)).cut.report
    assert any("no pieces file is written" in n for n in report.stats["notes"])
    assert [f.code for f in report.findings] == ["filled_pattern"]


def test_the_kit_api_writes_no_empty_pieces_file(tmp_path):
    from model_files import write_kit

    tile = design_from_text(NO_PIECES, name="kit").build_tile()
    report = write_kit(
        tmp_path / "k.dxf", region=tile.region(), outline=tile.outline_shape(), profile="laser-3mm-plywood", stroke=2.0
    )
    assert report.stats["files"] == [str(tmp_path / "k-lattice.dxf")]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["k-lattice.dxf"]
