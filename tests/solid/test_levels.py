"""The levels of a printed body (solid/levels.py): the layer list and the fast coverage agree."""

import pytest
import shapely
from shapely.geometry import Polygon, box

import fabtiles as ft
from fabtiles.geometry.interlace import tile_dips
from fabtiles.solid import mesh_check as sc
from fabtiles.solid import parts
from fabtiles.solid._mesh_build import QUANTUM, Stack, coverage, mesh_coverage
from fabtiles.solid.brep import build_brep
from fabtiles.solid.levels import (
    APART_MM,
    body_coverage,
    body_layers,
    dip_level,
    dip_z,
    dips_volume,
    split_region,
)

STACK = Stack("relief", base=2.0, relief=1.2, pierced=3.0, deboss=0.8)


def woven():
    tile = ft.Tile(
        "square", 40, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-3")), frame=2, stroke=1.0, interlace=True
    )
    r, o = parts._snapped(tile.region(), tile.outline_shape())
    return r, o, tile_dips(tile)


def areas_by_level(pieces):
    out = {}
    for geom, z in pieces:
        out[round(float(z), 6)] = out.get(round(float(z), 6), 0.0) + geom.area
    return out


@pytest.mark.parametrize("kind", ["relief", "pattern"])
def test_fast_coverage_has_the_layers_of_body_layers(kind):
    r, o, d = woven()
    layers, bottom = body_layers(kind, r, o, STACK, d)
    cov = body_coverage(kind, r, o, STACK, d)
    slow = areas_by_level(layers)
    fast = areas_by_level([(p, cov.levels[lvl]) for p, lvl in cov.pieces])
    assert fast.keys() == slow.keys() and dip_z(STACK) in fast
    for z in slow:
        assert fast[z] == pytest.approx(slow[z], rel=1e-9, abs=1e-6)
    # both mesh into the same watertight body
    for c in (cov, coverage(layers, bottom=bottom)):
        v, f = mesh_coverage(c)
        sc.check_mesh(v, f, bodies=1 if kind == "relief" else None)


@pytest.mark.parametrize("kind", ["relief", "pattern"])
def test_dips_crossed_by_cell_lines_are_cut_with_the_region(kind, monkeypatch):
    """Small cells, so that cell lines cross many dips: those are holes of the region before it is
    cut, their pieces at the dip level (the relief's from the rest of the cell, the pattern's
    noded alike); the levels and the watertight mesh are those of the plain layer list."""
    from fabtiles.solid import _mesh_build as mb

    monkeypatch.setattr(mb, "CELL_VERTICES", 60)
    r, o, d = woven()
    xs, ys, _ = mb.cells_for([r, o], 60)
    parts = shapely.get_parts(d)
    crossed = [
        p
        for p in parts
        if any(p.bounds[0] <= x <= p.bounds[2] for x in xs) or any(p.bounds[1] <= y <= p.bounds[3] for y in ys)
    ]
    assert len(crossed) > 10 and len(crossed) < len(parts)
    cov = body_coverage(kind, r, o, STACK, d)
    # the same cells (kept off the dips' vertices too), no dips
    cells_for = mb.cells_for
    monkeypatch.setattr(
        mb, "cells_for", lambda geoms, *args, avoid=(), **kwargs: cells_for(geoms, *args, avoid=[d], **kwargs)
    )
    plain = body_coverage(kind, r, o, STACK, shapely.Polygon())
    fast = areas_by_level([(p, cov.levels[lvl]) for p, lvl in cov.pieces])
    without = areas_by_level([(p, plain.levels[lvl]) for p, lvl in plain.pieces])
    top, low = STACK.base + STACK.relief, dip_z(STACK)
    # the dips come out of the full level, all of them; their points noded at the cell lines
    # are rounded to the grid (a little area each, far less than one dip's 0.28 mm^2)
    assert fast[top] + fast[low] == pytest.approx(without[top], abs=1e-6)
    assert fast[low] == pytest.approx(d.area, abs=1e-4 * len(crossed))
    assert {z: a for z, a in fast.items() if z not in (top, low)} == pytest.approx(
        {z: a for z, a in without.items() if z != top}, abs=1e-6
    )
    v, f = mesh_coverage(cov)
    sc.check_mesh(v, f, bodies=1 if kind == "relief" else None)


def test_dips_are_holes_of_the_full_level():
    r, _o, d = woven()
    full, dip = split_region(r, d)
    assert full.is_valid and full.area + dip.area == pytest.approx(r.area)
    assert (
        shapely.get_num_interior_rings(shapely.get_parts(full)).sum()
        > shapely.get_num_interior_rings(shapely.get_parts(r)).sum()
    )


def test_no_dips_is_the_plain_body():
    r, o = box(1, 1, 3, 3), box(0, 0, 4, 4)
    assert split_region(r, None)[0] is r
    layers, bottom = body_layers("relief", r, o, STACK, None)
    assert [z for _, z in layers] == [STACK.base + STACK.relief, STACK.base] and bottom == 0.0
    assert [z for _, z in body_layers("pierced", r, o, STACK)[0]] == [STACK.pierced]
    assert [z for _, z in body_layers("base", r, o, STACK)[0]] == [STACK.base]
    assert [z for _, z in body_layers("plate", r, o, STACK)[0]] == [STACK.base - STACK.deboss, STACK.base]


def test_unknown_kinds_are_refused():
    r, o = box(1, 1, 3, 3), box(0, 0, 4, 4)
    with pytest.raises(ValueError, match=r"'lid' is not a valid body kind, must be one of: relief, base"):
        body_layers("lid", r, o, STACK)
    with pytest.raises(ValueError, match=r"'pierced' has no dips, must be one of: relief, pattern"):
        body_coverage("pierced", r, o, STACK, box(1.5, 1.5, 2, 2))


def test_leveled_dips_give_the_same_coverage():
    """The writers level the dips once (dip_level) and pass them on as such."""
    from fabtiles.solid.levels import THIN_MM, dip_level, dips_volume

    r, o, d = woven()
    x, y = r.representative_point().coords[0]
    thin = shapely.box(x, y, x + 0.5, y + THIN_MM / 2)
    assert thin.distance(d) > 0.01
    plain = dip_level(d)
    d = shapely.union(d, thin)  # a dip too thin to print stays at full height
    leveled = dip_level(d)
    assert leveled.area == pytest.approx(plain.area, abs=1e-9) and len(shapely.get_parts(leveled)) > 100
    for kind in ("relief", "pattern"):
        a = body_coverage(kind, r, o, STACK, d)
        b = body_coverage(kind, r, o, STACK, leveled, leveled=True)
        assert [(p.wkb, lvl) for p, lvl in a.pieces] == [(p.wkb, lvl) for p, lvl in b.pieces]
    assert dips_volume(r, leveled, STACK, leveled=True) == pytest.approx(dips_volume(r, d, STACK))


def test_an_island_ringed_by_dips_dips_too():
    """Slivers overlapping all round a point leave a hole in the merged dip: too small to print
    standing, it is filled, in every writer's layers alike."""
    from fabtiles.solid.levels import dip_level

    ring = box(1.25, 1.25, 2.75, 2.75).difference(box(1.75, 1.75, 2.25, 2.25))
    leveled = dip_level(ring)
    assert (
        leveled.area == pytest.approx(1.5**2) and shapely.get_num_interior_rings(shapely.get_parts(leveled)).sum() == 0
    )
    r, o = box(1, 1, 3, 3), box(0, 0, 4, 4)
    for kind in ("relief", "pattern"):
        cov = body_coverage(kind, r, o, STACK, ring)
        by_level = areas_by_level([(p, cov.levels[lvl]) for p, lvl in cov.pieces])
        assert by_level[dip_z(STACK)] == pytest.approx(1.5**2)
        v, f = mesh_coverage(cov)
        sc.check_mesh(v, f, bodies=1 if kind == "relief" else None)


def test_a_dip_ringing_an_opening_of_the_region_stays_at_full_height():
    """A dip around an opening of the region (an outline circle inside a crossing) is not filled over
    the opening: it stays at full height, and the mesh holds the region's volume exactly."""
    outline = box(0, 0, 20, 20)
    region = box(2, 2, 18, 18).difference(box(9, 9, 11, 11))
    dips = box(6, 6, 14, 14).difference(box(8.5, 8.5, 11.5, 11.5))
    (part,) = parts.checked_parts(region, outline, STACK, single=True, dips=dips).values()
    assert part.mesh_volume_mm3 == pytest.approx(outline.area * STACK.base + region.area * STACK.relief)
    # a dip ringing an island of the region still dips, its island with it
    island = box(6, 6, 14, 14).difference(box(9, 9, 11, 11))
    full, dip = split_region(box(2, 2, 18, 18), island)
    assert dip.area == pytest.approx(64.0) and full.area == pytest.approx(256.0 - 64.0)


@pytest.mark.parametrize("kind", ["relief", "pattern"])
def test_a_dip_ringing_a_face_stays_at_full_height(kind):
    """Strands dipping all round a small face: the dip is a ring, and filled it would cover the face."""
    o = box(0, 0, 20, 20)
    r = box(2, 2, 18, 18).difference(box(9, 9, 11, 11))  # a band round a 2 x 2 mm face
    ring = box(8, 8, 12, 12).difference(box(9, 9, 11, 11))  # the dips all round the face
    other = box(4, 4, 5, 6)
    dips = shapely.union_all([ring, other])
    full, dip = split_region(r, dips)
    assert full.is_valid and dip.equals(other)
    assert full.area == pytest.approx(r.area - other.area)
    cov = body_coverage(kind, r, o, STACK, dips)
    v, f = mesh_coverage(cov)
    full_volume = {"relief": o.area * STACK.base + r.area * STACK.relief, "pattern": r.area * STACK.relief}[kind]
    sc.check_mesh(v, f, volume=full_volume - other.area * (STACK.base + STACK.relief - dip_z(STACK)))


@pytest.mark.parametrize("kind", ["relief", "pattern"])
def test_dips_touching_at_a_point_mesh_watertight(kind):
    """Two dips meeting at a corner would put four walls on one vertical edge: they are cut back there."""
    o = box(0, 0, 20, 20)
    r = box(2, 2, 18, 18)
    dips = shapely.MultiPolygon([box(6, 6, 10, 10), box(10, 10, 14, 14)])
    cov = body_coverage(kind, r, o, STACK, dips)
    v, f = mesh_coverage(cov)
    depth = STACK.base + STACK.relief - dip_z(STACK)
    cut = APART_MM**2  # a quarter of the diamond off each of the two dips
    full = {"relief": o.area * STACK.base + r.area * STACK.relief, "pattern": r.area * STACK.relief}[kind]
    sc.check_mesh(v, f, volume=full - (32 - cut) * depth, bodies=1)


@pytest.mark.parametrize("kind", ["relief", "pattern"])
def test_dips_leaving_a_point_at_a_small_angle_mesh_watertight(kind):
    """Two dips leaving their point at 0.064 rad to each other: cut back once, they still touch
    on the grid where the cut ends; they are cut again until apart."""
    o = box(0, 0, 20, 20)
    r = box(2, 2, 18, 18)
    low = Polygon([(10, 10), (4, 10.5), (4, 7), (10, 7)])
    high = Polygon([(10, 10), (10, 13), (4, 13), (4, 10.875)])
    dips = shapely.MultiPolygon([low, high])
    a, b = shapely.get_parts(dip_level(dips, r))
    assert shapely.distance(a, b) > QUANTUM
    v, f = mesh_coverage(body_coverage(kind, r, o, STACK, dips))
    full = {"relief": o.area * STACK.base + r.area * STACK.relief, "pattern": r.area * STACK.relief}[kind]
    sc.check_mesh(v, f, volume=full - dips_volume(r, dips, STACK), bodies=1)


def test_dips_a_fraction_of_a_grid_step_apart_are_cut_back():
    """A dip's corner a third of a grid step from another dip's side: the STEP writer's noding on
    the grid joins them (four walls on one edge of the B-rep) unless they are cut back there."""
    o = box(0, 0, 20, 20)
    r = box(2, 2, 18, 18)
    side = Polygon([(6, 6), (6 + 1000 * QUANTUM, 6 + 1001 * QUANTUM), (6, 8)])
    corner = Polygon([(6 + 500 * QUANTUM, 6 + 500 * QUANTUM), (9, 6), (9, 6.3)])
    assert 0 < shapely.distance(side, corner) < QUANTUM / 2
    dips = shapely.MultiPolygon([side, corner])
    a, b = shapely.get_parts(dip_level(dips, r))
    assert shapely.distance(a, b) > QUANTUM
    _, volume, solids = build_brep(region=r, outline=o, stack=STACK, dips=dips)
    full = o.area * STACK.base + r.area * STACK.relief
    assert solids == 1 and volume == pytest.approx(full - dips_volume(r, dips, STACK), rel=1e-6)
