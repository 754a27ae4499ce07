"""Parquet deformations of Hankin's rays: the contact angle changing across the tile.

Checked from the segments and the tiling's polygons alone: the strands stay continuous
(both polygons of an edge start their rays at the same points on it), each polygon's rays
make the angle of its centre's place with their edge, the angle changes monotonically, a
constant angle draws today's pattern, and a deformed design weaves and builds into a clean
DXF and a watertight STL; the bad values are refused naming the key, the value and the range.
"""

from __future__ import annotations

import pickle

import ezdxf
import numpy as np
import pytest
import shapely
from designs import assert_cli_refused
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from mesh_helpers import assert_relief_stl

import fabtiles
from fabtiles import DesignError, ParameterError
from fabtiles.designs.design_file import design_from_text
from fabtiles.pattern.archimedean import TilingPacking
from fabtiles.pattern.hankin import max_contact_angle, parquet_angles, polygon_rays, polygons_rays
from fabtiles.pattern.tilings import ALL_TILINGS, unit_cell

WINDOW = (-35.0, -30.0, 35.0, 30.0)
TILINGS = ["4.8.8", "3.12.12", "4.6.12", "3.3.4.3.4", "[3^6; 3^4.6]#1"]


def deformed(tiling, angle=30.0, angle_to=75.0, gap=0.0, **kw):
    return TilingPacking(
        tiling, edge=8, method="hankin", contact_angle=angle, contact_angle_to=angle_to, contact_gap=gap, **kw
    )


def inner(packing, margin):
    """The polygons of ``packing`` lying at least ``margin`` inside WINDOW (all their neighbours are drawn)."""
    x0, y0, x1, y1 = WINDOW
    return [
        p
        for p in packing.polygons(WINDOW)
        if p[:, 0].min() > x0 + margin and p[:, 0].max() < x1 - margin and p[:, 1].min() > y0 + margin
        if p[:, 1].max() < y1 - margin
    ]


def count_at(points, among, tol=1e-7):
    """How many of ``among`` lie within ``tol`` of each of ``points``."""
    d = np.linalg.norm(points[:, None] - among[None], axis=2)
    return (d < tol).sum(axis=1)


def expected_angle(centre, angle=30.0, angle_to=75.0, axis=0, smooth=False):
    """The angle at ``centre``: across x (axis 0) or y (1), or radially from WINDOW's centre (2)."""
    if axis == 2:
        t = min(np.hypot(*centre) / 30.0, 1.0)  # WINDOW is centred on 0, 60 mm high
    else:
        t = min(max((centre[axis] - WINDOW[axis]) / (WINDOW[axis + 2] - WINDOW[axis]), 0.0), 1.0)
    if smooth:
        t = t * t * (3 - 2 * t)
    return angle + (angle_to - angle) * t


def measured(packing):
    """``(centre, angle)`` of each ray of a gapless deformation, centre its polygon's: the angle
    between the ray and its edge, read from the segment and the polygon it runs into."""
    seg = packing.segments(WINDOW)
    polys = packing.polygons(WINDOW)
    shapes = np.array([shapely.Polygon(p) for p in polys])
    out = []
    for s in seg:
        probe = shapely.points((s[0] + s[1]) / 2)
        k = int(np.flatnonzero(shapely.contains(shapes, probe))[0])
        centre = polys[k].mean(axis=0)
        normal = s[0] - centre  # the ray starts at its edge's midpoint
        normal /= np.linalg.norm(normal)
        d = (s[1] - s[0]) / np.linalg.norm(s[1] - s[0])
        out.append((centre, np.degrees(np.arcsin(np.clip(-d @ normal, -1, 1)))))
    return out


@pytest.mark.parametrize("tiling", TILINGS)
@pytest.mark.parametrize("gap", [0.0, 1.0])
def test_strands_stay_continuous_across_every_edge(tiling, gap):
    """Each ray starts where the neighbour's ray across the edge starts (the strand goes through
    there), and ends where its partner in the polygon ends (the strand closes)."""
    packing = deformed(tiling, gap=gap)
    seg = packing.segments(WINDOW)
    starts, ends = seg[:, 0], seg[:, 1]
    for poly in inner(packing, 12):
        for a, b in zip(poly, np.roll(poly, -1, axis=0), strict=True):
            u = (b - a) / np.linalg.norm(b - a)
            mid = (a + b) / 2
            points = np.array([mid]) if gap == 0 else np.array([mid - gap / 2 * u, mid + gap / 2 * u])
            # gapless: both rays of each polygon start at the midpoint; with a gap one of each at each point
            assert (count_at(points, starts) == (4 if gap == 0 else 2)).all(), (tiling, mid)
        centre = poly.mean(axis=0)
        mine = ends[np.linalg.norm(ends - centre, axis=1) < np.linalg.norm(poly[0] - centre) - 1e-9]
        assert (count_at(mine, ends) == 2).all()


@settings(max_examples=examples(20), deadline=None)
@given(
    tiling=st.sampled_from(ALL_TILINGS),
    angles=st.tuples(st.floats(1, 89), st.floats(1, 89)),
    gap_fraction=st.one_of(st.just(0.0), st.floats(0.01, 0.9)),
    direction=st.sampled_from(["x", "y", "radial"]),
    curve=st.sampled_from(["linear", "smooth"]),
)
def test_any_valid_deformation_keeps_every_strand_whole(tiling, angles, gap_fraction, direction, curve):
    """Property: for any two valid angles, each ray's start is shared with the neighbour's rays
    (4 starts at a gapless midpoint, 2 at each gap point) and its end with its partner's; no
    segment twice."""
    edge = 8.0
    gap = gap_fraction * edge
    if any(max(angles) > max_contact_angle(p, edge, gap) for p in set(unit_cell(tiling).sides.tolist())):
        return  # no pattern at one side: refused as contact_angle is (test_hankin)
    packing = deformed(tiling, *angles, gap=gap, parquet_direction=direction, parquet_curve=curve)
    seg = packing.segments(WINDOW)
    middle = (np.abs(seg) < np.array([20.0, 15.0])).all(axis=2)  # both ends well inside the window
    starts, ends = seg[:, 0], seg[:, 1]
    assert (count_at(starts[middle[:, 0]], starts) == (4 if gap == 0 else 2)).all()
    assert (count_at(ends[middle[:, 1]], ends) == 2).all()
    flat = seg.reshape(len(seg), -1)
    assert (count_at(flat, flat) == 1).all()


@pytest.mark.parametrize("tiling", ["4.8.8", "3.4.6.4"])
@pytest.mark.parametrize("direction, curve", [("x", "linear"), ("y", "smooth"), ("radial", "linear")])
def test_each_polygons_rays_make_its_centres_angle_with_their_edge(tiling, direction, curve):
    packing = deformed(tiling, parquet_direction=direction, parquet_curve=curve)
    rays = measured(packing)
    assert len(rays) > 100
    axis = ["x", "y", "radial"].index(direction)
    for centre, angle in rays:
        assert angle == pytest.approx(expected_angle(centre, axis=axis, smooth=curve == "smooth"), abs=1e-7)


@pytest.mark.parametrize("direction", ["x", "y"])
def test_the_angle_changes_monotonically_across_and_not_along(direction):
    axis = "xy".index(direction)
    rays = measured(deformed("4.8.8", angle=70.0, angle_to=20.0, parquet_direction=direction, parquet_curve="smooth"))
    across = np.array([c[axis] for c, _ in rays])
    angle = np.array([a for _, a in rays])
    order = np.argsort(across, kind="stable")
    assert np.all(np.diff(angle[order]) <= 1e-9) and angle.max() > angle.min() + 40
    along = np.array([c[1 - axis] for c, _ in rays])
    same = np.abs(across - across[0]) < 1e-6  # one column (row): one angle whatever the other coordinate
    assert np.ptp(along[same]) > 10 and np.ptp(angle[same]) < 1e-9


def lines(segments):
    return shapely.union_all(shapely.linestrings(segments)).intersection(shapely.box(*WINDOW))


@pytest.mark.parametrize("tiling", TILINGS)
@pytest.mark.parametrize("gap", [0.0, 1.5])
def test_a_constant_angle_draws_todays_pattern(tiling, gap):
    """The deformation's own path (each polygon's rays, never joined across an edge) with
    contact_angle_to = contact_angle covers exactly the lines of the translated unit cell."""
    today = TilingPacking(tiling, edge=8, method="hankin", contact_angle=55, contact_gap=gap)
    same = today.replace(contact_angle_to=55)
    a, b = lines(today.segments(WINDOW)), lines(same.segments(WINDOW))
    # the same lines: as long, and every point of each (densified) on the other
    assert a.length > 500 and b.length == pytest.approx(a.length, abs=1e-9)
    assert shapely.hausdorff_distance(a, b, densify=0.25) < 1e-9
    assert same.segment_count(WINDOW) == len(same.segments(WINDOW))


def test_the_vectorised_rays_are_polygon_rays():
    many = polygons_rays(6, 10.0, [20.0, 50.0, 80.0], 1.0, [0.0, 0.3, 1.0])
    for k, (angle, turn) in enumerate([(20, 0.0), (50, 0.3), (80, 1.0)]):
        assert np.allclose(many[k], polygon_rays(6, 10.0, angle, 1.0, turn), atol=1e-12)


def test_parquet_angles_clamp_outside_the_window():
    assert parquet_angles([[-99, 0], [99, 0]], (-10, -10, 10, 10), 20, 60).tolist() == [20.0, 60.0]
    assert parquet_angles([[0, 0]], (5, 5, 5, 5), 20, 60).tolist() == [20.0]  # an empty window: the near side's


def test_the_parameters_round_trip_and_print():
    p = deformed("4.8.8", parquet_direction="y", parquet_curve="smooth")
    assert p.replace() == p and p != p.replace(contact_angle_to=70)
    assert pickle.loads(pickle.dumps(p)) == p and hash(pickle.loads(pickle.dumps(p))) == hash(p)
    assert "contact_angle_to=75, parquet_direction='y', parquet_curve='smooth'" in repr(p)


# -- a deformed design, built -----------------------------------------------------------------
DESIGN = """
[packing]
kind = "archimedean"
tiling = "4.8.8"
edge = 10
method = "hankin"
contact_angle = 30
contact_angle_to = 75
[tile]
outline = "square"
size = 70
frame = 3
stroke = 1
[output]
formats = ["svg"]
"""


def tile_of(text=DESIGN):
    return design_from_text(text).build_tile(tile_cls=fabtiles.Tile)


def test_a_deformed_design_weaves_through_its_bent_crossings():
    """At each edge midpoint four ray ends meet as two strands bent by the neighbours' difference
    in angle: interlace reads it as a crossing (never a knot) and the weave alternates."""
    tile = tile_of(DESIGN.replace("stroke = 1", "stroke = 1\ninterlace = true"))
    weave = tile.weave()
    assert weave.conflicts == 0 and len(weave.knots) == 0 and len(weave) > 50
    mids = np.concatenate([(p + np.roll(p, -1, axis=0)) / 2 for p in tile.pattern.polygons((-30, -30, 30, 30))])
    mids = mids[np.abs(mids).max(axis=1) < 30] + np.array(tile.centre)
    assert (count_at(mids, weave.points, 1e-6) == 1).all()


def test_a_steep_deformation_knots_the_sharpest_bends_and_still_weaves():
    """Bends of 30 degrees or more (BEND_DEG) at a midpoint are knots, never a crossing bent double."""
    steep = DESIGN.replace("size = 70", "size = 40").replace("contact_angle = 30", "contact_angle = 5")
    weave = tile_of(
        steep.replace("contact_angle_to = 75", "contact_angle_to = 88").replace(
            "stroke = 1", "stroke = 1\ninterlace = true"
        )
    ).weave()
    assert len(weave.knots) > 0 and weave.conflicts == 0 and len(weave) > 10


def test_a_deformed_design_builds_a_clean_dxf_and_a_watertight_stl(tmp_path):
    tile = tile_of()
    tile.export(tmp_path / "t.dxf", profile="laser-3mm-plywood", fill_small_holes=True)
    doc = ezdxf.readfile(tmp_path / "t.dxf")
    assert not doc.audit().has_errors and len(doc.modelspace()) > 30
    assert_relief_stl(tile, tmp_path / "t.stl")


def test_the_colour_classes_of_a_deformed_design(tmp_path):
    from fabtiles.making import build_design

    design = design_from_text(DESIGN + 'print_style = "mosaic"\n[colour]\nby = "shape"\n')
    result = build_design(design, tmp_path / "out", ("3mf",))
    assert len(result.paths) == 1 and (tmp_path / "out").exists()


# -- bad input ----------------------------------------------------------------------------------
def test_bad_parquet_values_are_refused_by_the_packing():
    with pytest.raises(ParameterError, match=r"contact_angle_to must be a finite number > 0 and < 90, got 95"):
        deformed("4.8.8", angle_to=95)
    with pytest.raises(ParameterError, match=r"contact_angle_to 80 has no pattern .* must be > 0 and <= 63\.43"):
        deformed("4.8.8", angle=40, angle_to=80, gap=4)
    with pytest.raises(ParameterError, match=r"parquet_direction = 'z' is not valid, must be one of: x, y, radial"):
        deformed("4.8.8", parquet_direction="z")
    with pytest.raises(ParameterError, match=r"parquet_curve = 'cubic' is not valid, must be one of: linear, smooth"):
        deformed("4.8.8", parquet_curve="cubic")
    with pytest.raises(ParameterError, match=r"contact_angle_to = 70 is a parquet deformation of Hankin's rays"):
        TilingPacking("4.8.8", edge=8, contact_angle_to=70)
    # the motifs have no parquet deformation: its direction and curve are refused there too (their defaults pass)
    for key, value in (("parquet_direction", "y"), ("parquet_curve", "smooth")):
        with pytest.raises(ParameterError, match=rf"{key} = '{value}' shapes a parquet deformation of Hankin's rays, "):
            TilingPacking("4.8.8", edge=8, **{key: value})
    assert TilingPacking("4.8.8", edge=8, parquet_direction="x", parquet_curve="linear").method == "motifs"


def test_contact_angle_to_without_hankins_method_is_refused_in_a_design():
    text = DESIGN.replace('method = "hankin"\ncontact_angle = 30\n', "")
    with pytest.raises(DesignError, match=r'contact_angle_to is a key of method = "hankin"') as err:
        design_from_text(text)
    assert err.value.param == "packing.contact_angle_to"


@pytest.mark.parametrize(
    "setting, match",
    [
        ("packing.contact_angle_to=95", r"contact_angle_to must be a finite number > 0 and < 90, got 95"),
        ("packing.contact_gap=4", r"contact_angle_to 75 has no pattern .* must be > 0 and <= 68\.1986"),
        ('packing.parquet_direction="z"', r"parquet_direction = 'z' is not valid, must be one of: x, y, radial"),
        ('packing.parquet_curve="cubic"', r"parquet_curve = 'cubic' is not valid, must be one of: linear, smooth"),
        ('packing.method="motifs"', r'contact_angle is a key of method = "hankin"'),
    ],
)
def test_cli_exits_2_and_writes_nothing(tmp_path, setting, match):
    path = tmp_path / "p.toml"
    path.write_text(DESIGN, encoding="utf-8")
    assert_cli_refused(["build", path, "-o", tmp_path / "out", "--set", setting], tmp_path / "out", match)


@pytest.mark.parametrize(
    "text,where",
    [
        (DESIGN.replace("[packing]\n", "[packing]\nseamless = true\n"), "seamless = true"),
        (
            DESIGN.replace('["svg"]', '["stl"]').replace('outline = "square"\nsize = 70\nframe = 3\n', "")
            + '[surface]\nshape = "cylinder"\ndiameter = 60\nlength = 40\n',
            "a cylinder's strip",
        ),
    ],
)
def test_a_deformation_cannot_repeat_without_a_seam(text, where):
    with pytest.raises(DesignError, match=rf"contact_angle_to = 75 changes the pattern .*\({where}\)"):
        design_from_text(text)
