"""Inlay kits on designs whose holes have necks, slits and sharp tips (issue 33), checked with GEOS."""

from __future__ import annotations

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from dxf_helpers import vertices

from fabtiles import FabricationError
from fabtiles.cli.main import cli
from fabtiles.designs.design_file import design_from_text
from fabtiles.geometry.inlay import inlay_kit
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")
KERF, FIT = PLY.kerf_mm, PLY.inlay_fit_mm

NECKS = """
[motif]
preset = "table3-2"
[packing]
kind = "archimedean"
tiling = "4.6.12"
edge = 12.96
[packing.motifs]
4 = "table1-part1"
6 = "table3-2"
12 = "table2-right"
[tile]
outline = "rectangle"
size = [97.7, 77.4]
frame = 5.0
stroke = 2.0
join = "round"
[output]
laser_mode = "inlay"
"""
"""8 holes whose lattice cut (the hole shrunk by half the kerf) fell into 3 holes each (issue 33)."""

SLITS = """
[motif]
preset = "table3-3"
[packing]
kind = "archimedean"
tiling = "4.6.12"
edge = 16.52
[packing.motifs]
4 = "table2-left"
6 = "table3-2"
[tile]
outline = "rectangle"
size = [93, 121]
frame = 8.0
stroke = 2.0
join = "bevel"
interlace = true
[output]
laser_mode = "inlay"
"""
"""Interlaced: 3 pieces over 8 lattice holes, others over uncut 17-degree tips (issue 33)."""

STARS = """
[motif]
n = 5
radii = [55.3, 170.7]
alpha = 25.4
spr = 5.2
special = 2
[packing]
kind = "hex"
radius = 19.19
[tile]
outline = "circle"
size = 102
frame = 3.0
stroke = 1.0
join = "round"
[output]
laser_mode = "inlay"
"""
"""5-point stars whose mitred tips reached 0.55 mm past their holes: refused at fit 0.16 mm (issue 33)."""


def _rings(path, layer):
    return [shapely.Polygon(vertices(e)) for e in ezdxf.readfile(path).modelspace() if e.dxf.layer == layer]


def _build(tmp_path, text, *sets):
    design = tmp_path / "kit.toml"
    design.write_text(text)
    args = ["build", str(design), "-o", str(tmp_path / "out"), "--format", "dxf"]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    return result.output, tmp_path / "out" / "kit-lattice.dxf", tmp_path / "out" / "kit-pieces.dxf"


@pytest.mark.parametrize("text", [NECKS, SLITS, STARS], ids=["necks", "slits", "stars"])
def test_every_piece_drops_into_exactly_one_lattice_opening(tmp_path, text):
    """Read back: the lattice's openings are its cut paths swept by the round beam; a piece is its cut path less half
    the kerf. Each piece lies within one opening grown by the fit (and the arcs' tolerance) and meets no other; one
    piece per opening."""
    _, lattice, pieces = _build(tmp_path, text)
    openings = np.array([h.buffer(KERF / 2, quad_segs=64) for h in _rings(lattice, PLY.layers.inner_cut.name)])
    cut = _rings(pieces, PLY.layers.outer_cut.name)
    parts = np.array([p.buffer(-KERF / 2, join_style="mitre", mitre_limit=5) for p in cut])
    tree = shapely.STRtree(openings)
    held = set()
    for piece in parts:
        # an opening the piece overlaps by more than its fit's press holds it
        near = tree.query(piece, predicate="intersects")
        over = [k for k in near if shapely.intersection(piece, openings[k]).area > 0.01]
        assert len(over) == 1, (piece.representative_point(), len(over))
        (k,) = over
        # the files' arcs stand off their chords by up to the profile's tolerance (a piece's arc where its
        # opening kept chords): within the fit and that
        outside = shapely.difference(piece, openings[k].buffer(FIT + PLY.tolerance_mm + 1e-3, quad_segs=64))
        assert outside.area == pytest.approx(0, abs=1e-6)
        held.add(int(k))
    assert len(held) == len(parts) > 10


def test_necks_narrower_than_the_kerf_are_widened(tmp_path):
    output, lattice, pieces = _build(tmp_path, NECKS)
    assert "widened 8 necks of holes narrower than the kerf (narrowest 0.076" in output
    # the lattice: one opening per piece, and the frame
    assert len(_rings(lattice, PLY.layers.inner_cut.name)) == len(_rings(pieces, PLY.layers.outer_cut.name)) == 35
    # the 12-gons' horns, which no straight cut inside the hole reaches, are a finding with their places
    assert "uncut_slit: 8 parts of holes beyond a slit narrower than the kerf" in output
    assert "(at (6.114, 54.81)" in output or "(6.114, 54.81)" in output


def _kit(text, fit):
    tile = design_from_text(text).build_tile()
    return inlay_kit(
        tile.region(), tile.outline_shape(), fit_mm=fit, min_piece_mm=PLY.min_piece_or_default_mm, kerf_mm=KERF
    )


def test_the_five_point_stars_tips_reach_no_more_than_the_fit_past_their_holes():
    # the mitred tips reached 0.55 mm past their holes at fit 0.15 mm, and at 0.16 mm the pieces' cuts met
    for fit in (0.15, 0.16, 0.3):
        kit = _kit(STARS, fit)
        reach = shapely.hausdorff_distance(kit.pieces, kit.holes)
        # GEOS's round joins (8 chords a quarter circle) stand past their arcs by under 1% of the radius,
        # kerf/2 + fit (measured: 1.4 um at fit 0.15 mm, 2.8 um at 0.3 mm)
        assert len(kit.pieces) == 17 and reach.max() <= fit + 0.01 * (fit + KERF / 2)
        # the pieces stand more than the kerf apart: the bands (0.8 mm) are wider than kerf + 2 x fit
        a, b = shapely.STRtree(kit.pieces).query(kit.pieces, predicate="dwithin", distance=1.0)
        gaps = shapely.distance(kit.pieces[a[a < b]], kit.pieces[b[a < b]])
        bands = shapely.distance(kit.holes[a[a < b]], kit.holes[b[a < b]])
        assert bands.min() == pytest.approx(0.8004, abs=1e-3)
        assert gaps.min() > bands.min() - 2 * fit - 2e-3 > KERF


def test_a_fit_past_the_band_names_the_pieces_gap_and_the_band():
    # bands of 0.8 mm: a fit of 0.42 mm leaves under the 0.15 mm kerf between the pieces
    with pytest.raises(
        FabricationError,
        match=r"the narrowest gap between two pieces is 0\.\d+ mm \(at \(.*\), "
        r"where the band of lattice between their holes is 0\.8 mm\), and "
        r"pieces must stand more than the kerf = 0\.15 mm apart, so bands must "
        r"be wider than kerf \+ 2 x fit = 0\.99 mm",
    ):
        _kit(STARS, 0.42)


def test_the_calibration_cards_pieces_are_grown_as_a_kits():
    """The card's inlay gauge measures the fit the kits get: a kit's piece of a square hole is piece_of_hole's."""
    import shapely as _shapely

    from fabtiles.geometry.inlay import inlay_kit, piece_of_hole

    hole = _shapely.box(10, 10, 16, 16)
    plate = _shapely.box(0, 0, 30, 30).difference(hole)
    kit = inlay_kit(plate, _shapely.box(0, 0, 30, 30), fit_mm=0.1, min_piece_mm=2.4, kerf_mm=0.15)
    (piece,) = kit.pieces
    card = piece_of_hole(hole, fit_mm=0.1, kerf_mm=0.15)
    assert piece.symmetric_difference(card).area < 1e-9
