"""Panels split into pieces: checked with GEOS on the pieces as placed in the panel."""

import itertools

import numpy as np
import pytest
import shapely
import shapely.affinity
from hypothesis import example, given, settings
from hypothesis import strategies as st
from shapely.geometry import box

import fabtiles as ft
from fabtiles.core.errors import FabricationError, ParameterError
from fabtiles.geometry.laser_checks import fits_bed
from fabtiles.geometry.pieces import (
    MAX_PIECES,
    TAB_SPACING_MM,
    congruent_groups,
    grid_for,
    joint_for,
    laid_on_bed,
    seam_bar_mm,
    split_panel,
)
from fabtiles.geometry.tile import TileGeometry

MIN_MM = 1.0


@pytest.fixture(scope="module")
def lattice():
    """A 600 x 400 mm screen of table3-3 rosettes with 6 mm bands and a 15 mm frame."""
    tile = TileGeometry(
        "rectangle", (600, 400), ft.HexPacking(radius=30, motif=ft.Star.preset("table3-3")), frame=15, stroke=6
    )
    return tile, tile.region()


@pytest.fixture(scope="module")
def split(lattice):
    tile, material = lattice
    return split_panel(
        material,
        bed_mm=(300, 250),
        margin_mm=5,
        joint=joint_for("dovetail", thickness_mm=3),
        min_feature_mm=MIN_MM,
        period_mm=(60, 60 * 3**0.5),
        origin=tile.centre,
    )


def _grid_regions(s):
    return {p.cell: p.region for p in s.pieces}


def test_the_pieces_assemble_into_exactly_the_panel(lattice, split):
    _, material = lattice
    union = shapely.union_all([p.region for p in split.pieces])
    assert shapely.symmetric_difference(union, material).area < 1e-6
    overlap = sum(p.region.area for p in split.pieces) - union.area
    assert abs(overlap) < 1e-6


def test_each_piece_fits_the_bed_less_its_margin(split):
    assert len(split.pieces) == split.grid[0] * split.grid[1] > 1
    for p in split.pieces:
        x0, y0, x1, y1 = p.region.bounds
        assert fits_bed(x1 - x0, y1 - y0, (290, 240)), p.number


def test_pieces_are_numbered_from_the_top_left_along_the_rows(split):
    nx, ny = split.grid
    numbers = {p.cell: p.number for p in split.pieces}
    assert sorted(numbers.values()) == list(range(1, nx * ny + 1))
    assert numbers[(0, ny - 1)] == 1 and numbers[(nx - 1, 0)] == nx * ny


def test_each_piece_is_one_part_with_nothing_thinner_than_the_minimum(split):
    for p in split.pieces:
        assert p.region.geom_type == "Polygon", p.number  # no island falls out
        assert not p.region.buffer(-MIN_MM / 2 + 1e-6).is_empty


def test_every_pair_of_neighbours_is_joined_and_cannot_be_pulled_apart_in_the_plane(split):
    regions = _grid_regions(split)
    by_number = {p.number: p.region for p in split.pieces}
    pairs = {j.pieces for j in split.joints}
    for i, j in regions:
        for other in ((i + 1, j), (i, j + 1)):
            if other in regions:
                a = next(p.number for p in split.pieces if p.cell == (i, j))
                b = next(p.number for p in split.pieces if p.cell == other)
                assert (a, b) in pairs, (a, b)
    for a, b in pairs:
        for angle in range(0, 360, 45):
            v = shapely.affinity.rotate(shapely.Point(2, 0), angle, origin=(0, 0))
            moved = shapely.affinity.translate(by_number[b], v.x, v.y)
            assert shapely.intersection(by_number[a], moved).area > 0.1, (a, b, angle)


def test_tabs_lie_in_their_neighbour_with_material_round_their_sockets(split):
    by_number = {p.number: p.region for p in split.pieces}
    for joint in split.joints:
        a, b = joint.pieces
        assert shapely.contains(by_number[a].buffer(1e-6), joint.tab)
        ring = joint.tab.buffer(MIN_MM - 1e-3, join_style="mitre").difference(joint.tab)
        assert shapely.contains(by_number[a].union(by_number[b]).buffer(1e-6), ring)


def test_a_press_fit_grows_each_tab_by_the_fit(lattice):
    _, material = lattice
    fit = 0.1
    s = split_panel(material, bed_mm=(400, 450), margin_mm=5, joint=joint_for("jigsaw", thickness_mm=3, fit_mm=fit))
    union = shapely.union_all([p.region for p in s.pieces])
    assert shapely.symmetric_difference(union, material).area < 1e-6  # the fit stays inside the neighbour
    overlap = sum(p.region.area for p in s.pieces) - union.area
    assert s.joints
    grown = 0.0  # each tab's fit band beyond its seam (behind the seam it lies in its own piece)
    for j in s.joints:
        x0, y0, x1, y1 = j.tab.bounds
        beyond = (
            box(j.at[0], y0 - 1, x1 + 1, y1 + 1) if abs(x0 - j.at[0]) < 1e-9 else box(x0 - 1, j.at[1], x1 + 1, y1 + 1)
        )
        grown += j.tab.buffer(fit, join_style="mitre").difference(j.tab).intersection(beyond).area
    assert overlap == pytest.approx(grown, rel=1e-3)


@pytest.fixture(scope="module")
def thin():
    """A 300 x 200 mm lattice of 1 mm bands in a 3 mm frame: no seam crosses material wide enough for a joint."""
    return TileGeometry(
        "rectangle", (300, 200), ft.HexPacking(radius=15, motif=ft.Star.preset("table3-3")), frame=3, stroke=1
    ).region()


def test_a_lattice_too_thin_for_any_joint_is_refused_without_bars(thin):
    with pytest.raises(FabricationError, match=r"pieces \d+ and \d+ meet across the seam at . = [\d.]+ mm only"):
        split_panel(thin, bed_mm=(170, 130), margin_mm=5, joint=joint_for("dovetail", thickness_mm=3), bars=False)


def test_a_lattice_too_thin_for_any_joint_gets_seam_bars_holding_the_joints(thin):
    joint = joint_for("dovetail", thickness_mm=3)
    s = split_panel(thin, bed_mm=(170, 130), margin_mm=5, joint=joint)
    assert s.grid == (2, 2) and len(s.bars) == 4  # each of the four pairs on its own bar
    union = shapely.union_all([p.region for p in s.pieces])
    bars = shapely.union_all(s.bars)
    assert shapely.symmetric_difference(union, shapely.union(thin, bars)).area < 1e-6  # the panel and the bars
    assert abs(sum(b.area for b in s.bars) - bars.area) < 1e-6 and not shapely.intersects(bars, thin.buffer(-1e-6))
    assert abs(sum(p.region.area for p in s.pieces) - union.area) < 1e-6  # no overlap
    outline = shapely.box(*thin.bounds)
    x0, y0, x1, y1 = thin.bounds
    width = seam_bar_mm(joint)
    for seam in s.seams_x:  # the whole seam is a bar: a neck behind it, the tab and a neck beyond
        strip = shapely.box(seam - joint.neck_mm, y0, seam - joint.neck_mm + width, y1)
        assert shapely.difference(strip, union).area < 1e-6
    for seam in s.seams_y:
        strip = shapely.box(x0, seam - joint.neck_mm, x1, seam - joint.neck_mm + width)
        assert shapely.difference(strip, union).area < 1e-6
    assert outline.contains(bars)
    for p in s.pieces:
        assert p.region.geom_type == "Polygon", p.number
        x0, y0, x1, y1 = p.region.bounds
        assert fits_bed(x1 - x0, y1 - y0, (160, 120))
    assert {j.pieces for j in s.joints} == {(1, 2), (3, 4), (3, 1), (4, 2)}
    by_number = {p.number: p.region for p in s.pieces}
    for a, b in {j.pieces for j in s.joints}:  # interlocked: moved 2 mm any way in the plane, they collide
        for angle in range(0, 360, 45):
            dx, dy = 2 * np.cos(np.radians(angle)), 2 * np.sin(np.radians(angle))
            moved = shapely.affinity.translate(by_number[b], dx, dy)
            assert shapely.intersection(by_number[a], moved).area > 0.1, (a, b, angle)


def test_a_long_stretch_gets_a_tab_per_spacing():
    frame = box(0, 0, 400, 700).difference(box(60, 60, 340, 640))  # 60 mm sides: each seam crosses two
    s = split_panel(frame, bed_mm=(500, 400), margin_mm=5, joint=joint_for("dovetail", thickness_mm=3))
    assert s.grid == (1, 2)
    assert len(s.joints) == 2  # a 60 mm stretch is shorter than the spacing: one tab each
    wide = box(0, 0, 400, 700).difference(box(10, 10, 390, 690)).union(box(0, 330, 400, 370))
    s = split_panel(wide, bed_mm=(500, 400), margin_mm=5, joint=joint_for("dovetail", thickness_mm=3))
    assert s.seams_y == pytest.approx((350.0,))  # along the band's middle: one 400 mm stretch
    assert np.allclose([j.at for j in s.joints], [(400 / 6, 350), (200, 350), (400 * 5 / 6, 350)])
    assert round(400 / TAB_SPACING_MM) == 3


def test_the_fewest_pieces_either_way_round():
    assert grid_for(500, 300, (600, 400), margin_mm=5, extent_mm=6) == (1, 1)
    assert grid_for(1200, 800, (600, 400), margin_mm=5, extent_mm=6) == (4, 2)  # 300 x 400 cells, turned
    assert grid_for(400, 400, (256, 256), margin_mm=5, extent_mm=6) == (2, 2)


def test_bad_beds_and_joints_are_errors_naming_the_value():
    with pytest.raises(ParameterError, match="leaves no room for a piece"):
        grid_for(400, 400, (15, 300), margin_mm=5, extent_mm=6)
    with pytest.raises(ParameterError, match=f"needs \\d+ pieces .* more than the {MAX_PIECES} allowed"):
        grid_for(5000, 5000, (100, 100), margin_mm=5, extent_mm=6)
    with pytest.raises(ParameterError, match="not a valid joint, must be one of: dovetail, jigsaw"):
        joint_for("biscuit", thickness_mm=3)
    with pytest.raises(ParameterError, match="fit_mm"):
        joint_for("dovetail", thickness_mm=3, fit_mm=1.0)


@settings(max_examples=10)
@given(
    w=st.floats(150, 420),
    h=st.floats(120, 300),
    bed=st.tuples(st.floats(110, 260), st.floats(110, 260)),
    kind=st.sampled_from(["dovetail", "jigsaw"]),
)
@example(w=150.0, h=291.0, bed=(110.0, 163.0), kind="jigsaw")  # a seam through a row of holes: a seam bar
def test_any_grid_panel_splits_into_joined_pieces_that_fit(w, h, bed, kind):
    """A frame with a grid of square holes (bands 8 mm): any size on any bed that holds a joint."""
    material = box(0, 0, w, h)
    holes = [
        box(x + 4, y + 4, x + 16, y + 16)
        for x, y in itertools.product(range(8, int(w) - 28, 20), range(8, int(h) - 28, 20))
    ]
    material = material.difference(shapely.union_all(holes))
    s = split_panel(material, bed_mm=bed, margin_mm=5, joint=joint_for(kind, thickness_mm=2))
    union = shapely.union_all([p.region for p in s.pieces])
    # the panel, and the seam bars where a seam met only bands too thin for a joint
    assert shapely.symmetric_difference(union, shapely.union_all([material, *s.bars])).area < 1e-6
    for p in s.pieces:
        x0, y0, x1, y1 = p.region.bounds
        assert fits_bed(x1 - x0, y1 - y0, (bed[0] - 10, bed[1] - 10))
        assert p.region.geom_type == "Polygon"
    assert len({j.pieces for j in s.joints}) >= (s.grid[0] - 1) * s.grid[1] + (s.grid[1] - 1) * s.grid[0]


def test_each_piece_laid_on_the_bed_goes_back_to_its_place_by_its_matrix(split):
    for p in split.pieces:
        laid, matrix = laid_on_bed(p.region, (300, 250), margin_mm=5)
        x0, y0, x1, y1 = laid.bounds
        assert x0 == pytest.approx(5) and y0 == pytest.approx(5)
        assert x1 <= 295 + 1e-6 and y1 <= 245 + 1e-6  # inside the bed less its margin
        back = shapely.transform(laid, lambda xy, m=matrix: xy @ m[:2, :2].T + m[:2, 2])
        assert shapely.symmetric_difference(back, p.region).area < 1e-6
        assert abs(np.linalg.det(matrix[:2, :2]) - 1) < 1e-12  # a rigid motion, never a mirror


def test_pieces_on_the_period_in_the_same_place_of_the_grid_are_one_shape():
    holes = [box(x + 4, y + 4, x + 16, y + 16) for x, y in itertools.product(range(0, 600, 20), range(0, 100, 20))]
    material = box(-2, -2, 602, 102).difference(shapely.union_all(holes))  # a 20 mm grid of holes, 8 mm bands
    joint = joint_for("dovetail", thickness_mm=2)
    s = split_panel(material, bed_mm=(160, 160), margin_mm=5, joint=joint, period_mm=(20, 20), origin=(10, 10))
    assert all((x - 10) % 20 == pytest.approx(0) for x in s.seams_x)  # through the holes' middles
    groups = congruent_groups(s.pieces)
    inner = [p.number for p in s.pieces if 0 < p.cell[0] < s.grid[0] - 1]
    assert len(inner) >= 2 and any(set(inner) <= set(g) for g in groups), groups
    assert len(groups) <= 3  # the first, the inner ones, the last


def test_a_rounded_tab_has_its_tools_radius_and_grows_without_spikes():
    joint = joint_for("dovetail", thickness_mm=6, fit_mm=0.1, corner_mm=1.5)
    tab = joint.tab((0, 0), (1, 0))
    # the piece with its tab as the bit cuts it from outside (concave corners closed by its radius) and
    # the socket as the bit cuts it (the tab's convex corners, the socket's inner ones, opened): unchanged
    piece = shapely.union(tab, box(-10, -20, 0, 20))
    near = box(-5, -15, 20, 15)
    for made in (piece.buffer(1.5).buffer(-1.5), piece.buffer(-1.5).buffer(1.5)):
        assert shapely.symmetric_difference(piece, made).intersection(near).area < 0.05
    x0, y0, x1, y1 = tab.bounds
    assert x0 == pytest.approx(0) and x1 == pytest.approx(joint.depth_mm)
    grown = joint.grown(tab, 1.0)  # the fillets' cusps at the seam, grown round: 1 mm out, no further
    gx0, gy0, gx1, gy1 = grown.bounds
    assert (gx0, gy0, gx1, gy1) == pytest.approx((x0 - 1, y0 - 1, x1 + 1, y1 + 1), abs=0.01)
    with pytest.raises(ParameterError, match="corner_mm"):
        joint_for("dovetail", thickness_mm=6, corner_mm=-1)


def test_a_tab_moves_along_its_stretch_to_where_the_material_holds_it():
    from fabtiles.geometry.pieces import _Context, _tabs_on_seam

    # a frame along the bottom and a thin band running up the seam from it: the stretch where the two
    # pieces meet is the frame's 10 mm and the band's 30 mm, its middle in the band, too thin for a tab
    material = shapely.union_all([box(0, 0, 300, 10), box(149, 0, 151, 40)])
    joint = joint_for("dovetail", thickness_mm=3)
    ctx = _Context(material, joint, 1.0)
    regions = {(0, 0): material.intersection(box(0, 0, 150, 50)), (1, 0): material.intersection(box(150, 0, 300, 50))}
    stretches = [shapely.LineString([(150, 0), (150, 40)])]
    ((at, tab),) = _tabs_on_seam(ctx, regions, (0, 0), (1, 0), 0, 150.0, stretches, [])
    assert at[0] == pytest.approx(150) and at[1] < 10  # in the frame
    assert shapely.contains(material.buffer(1e-9), tab)
