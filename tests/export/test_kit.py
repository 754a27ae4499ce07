"""Inlay kits (issue 24): checked with GEOS on the files read back, and opened by LibreCAD and MeerK40t."""

from __future__ import annotations

import itertools
import re
from dataclasses import replace

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from real_programs import program, run
from test_laser_programs import burns, meerk40t

from fabtiles import DesignError, FabricationError, HexPacking, ParameterError, ProfileError, Star, Tile
from fabtiles.cli.main import cli
from fabtiles.geometry.inlay import inlay_kit, shape_key
from fabtiles.machines.profiles import LaserLayers, load_profile

PLY = load_profile("laser-3mm-plywood")
KERF, FIT = PLY.kerf_mm, PLY.inlay_fit_mm
OFFSET = KERF / 2
"""Both files of a kit are the tile moved by half the kerf: the lattice outline's kerf, into the positive quadrant."""


def tile(size=60, radius=10, stroke=1.0):
    return Tile("square", size, HexPacking(radius, Star.preset("table3-3")), frame=3, stroke=stroke)


def rings(path, layer):
    """The polylines on ``layer`` as drawn: their arcs (a piece's rounded corners) flattened by ezdxf."""
    from dxf_helpers import vertices

    return [vertices(e) for e in ezdxf.readfile(path).modelspace() if e.dxf.layer == layer]


@pytest.fixture(scope="module")
def kit(tmp_path_factory):
    out = tmp_path_factory.mktemp("kit")
    t = tile()
    report = t.export(out / "t.dxf", mode="inlay")
    expected = inlay_kit(
        t.region(), t.outline_shape(), fit_mm=FIT, min_piece_mm=PLY.min_piece_or_default_mm, kerf_mm=KERF
    )
    return t, report, out / "t-lattice.dxf", out / "t-pieces.dxf", expected


def test_a_kit_is_two_files_in_registration(kit):
    _t, report, lattice, pieces, _ = kit
    assert report.stats["files"] == [str(lattice), str(pieces)]
    assert not (lattice.parent / "t.dxf").exists()
    assert report.stats["file_offset_mm"] == pytest.approx([OFFSET, OFFSET], abs=1e-9)
    outer = rings(lattice, PLY.layers.outer_cut.name)
    assert len(outer) == 1 and np.ptp(outer[0], axis=0) == pytest.approx([60 + KERF] * 2, abs=1e-6)
    cut = [shapely.Polygon(r) for r in rings(pieces, PLY.layers.outer_cut.name)]
    assert len(cut) == report.stats["pieces"] > 10
    # every piece lies over its own hole of the lattice: the same origin
    holes = [shapely.Polygon(r) for r in rings(lattice, PLY.layers.inner_cut.name)]
    tree = shapely.STRtree(holes)
    for piece in cut:
        (k,) = tree.query(shapely.point_on_surface(piece), predicate="within")
        assert holes[k].within(piece)


def test_each_hole_comes_out_at_the_designs_hole(kit):
    """The lattice file's holes, grown back by the half kerf they carry (GEOS), are the design's holes."""
    _, _, lattice, _, expected = kit
    holes = [shapely.Polygon(r - OFFSET) for r in rings(lattice, PLY.layers.inner_cut.name)]  # the tile's place
    assert len(holes) == len(expected.holes)
    tree = shapely.STRtree(expected.holes)
    for h in holes:
        (k,) = tree.query(shapely.point_on_surface(h), predicate="within")
        design = expected.holes[k]
        # every edge of the design's hole stands half a kerf off the file's (1 um)
        pts = shapely.get_coordinates(design.exterior)
        mids = shapely.points((pts[:-1] + pts[1:]) / 2)
        assert shapely.distance(mids, h.exterior) == pytest.approx(KERF / 2, abs=1e-6)


def test_each_piece_is_its_hole_grown_by_the_fit(kit):
    """The pieces file's contours carry half a kerf outward; under it each edge stands the fit off its hole."""
    _, _, _, pieces, expected = kit
    tree = shapely.STRtree(expected.holes)
    for r in rings(pieces, PLY.layers.outer_cut.name):
        cut = shapely.Polygon(r - OFFSET)  # moved back to the tile's place
        (k,) = tree.query(shapely.point_on_surface(cut), predicate="within")
        hole = expected.holes[k]
        pts = shapely.get_coordinates(hole.exterior)
        mids = shapely.points((pts[:-1] + pts[1:]) / 2)
        # edge by edge: the fit plus the half kerf the file carries (1 um)
        assert shapely.distance(mids, cut.exterior) == pytest.approx(FIT + KERF / 2, abs=1e-6)
        assert cut.contains(hole)


def test_no_two_pieces_touch_on_their_sheet(kit):
    _, _, _, pieces, _ = kit
    cut = np.array([shapely.Polygon(r) for r in rings(pieces, PLY.layers.outer_cut.name)])
    a, b = shapely.STRtree(cut).query(cut, predicate="intersects")
    assert (a == b).all()


def test_the_areas_add_up(kit):
    t, report, _, _, expected = kit
    overlap = float(shapely.area(expected.pieces).sum() - shapely.area(expected.holes).sum())
    total = report.stats["lattice_area_mm2"] + report.stats["pieces_area_mm2"]
    assert total == pytest.approx(t.outline_shape().area + overlap, rel=1e-6)
    assert overlap > 0  # a press fit: the pieces are larger than their holes


def _congruent(p, q, tol=1e-3) -> bool:
    """Brute force: some vertex of ``q`` onto vertex 0 of ``p``, turned (and mirrored), matches."""
    if abs(p.area - q.area) > tol or len(p.exterior.coords) != len(q.exterior.coords):
        return False
    a = shapely.get_coordinates(shapely.orient_polygons(p).exterior)[:-1]
    for mirror in (False, True):
        b0 = shapely.get_coordinates(shapely.orient_polygons(q).exterior)[:-1]
        b = b0 * [1, -1] if mirror else b0
        for k in range(len(b)):
            # the rotation taking b's edge at k onto a's first edge
            ea, eb = a[1] - a[0], np.roll(b, -k, axis=0)[1] - np.roll(b, -k, axis=0)[0]
            for bb in (np.roll(b, -k, axis=0), np.roll(b[::-1], -k, axis=0)):
                eb = bb[1] - bb[0]
                t = np.arctan2(ea[1], ea[0]) - np.arctan2(eb[1], eb[0])
                rot = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
                moved = (bb - bb[0]) @ rot.T + a[0]
                if shapely.Polygon(moved).hausdorff_distance(shapely.Polygon(a)) < tol:
                    return True
    return False


def test_distinct_shapes_match_a_brute_force_count():
    t = tile(size=40, radius=8)
    k = inlay_kit(t.region(), t.outline_shape(), fit_mm=0.1, min_piece_mm=1.5, kerf_mm=KERF)
    pieces = list(k.pieces)
    classes: list = []
    for p in pieces:
        for c in classes:
            if _congruent(c[0], p):
                c.append(p)
                break
        else:
            classes.append([p])
    assert k.kinds == len(classes) and 1 < k.kinds < len(pieces)
    # and the key agrees pair by pair on a sample
    for p, q in itertools.combinations(pieces[:12], 2):
        assert (shape_key(p) == shape_key(q)) == _congruent(p, q)


def test_pocket_inlay_engraves_the_holes_and_cuts_the_outline(tmp_path):
    t = tile()
    report = t.export(tmp_path / "p.dxf", mode="inlay", inlay_base="pocket")
    lattice = tmp_path / "p-lattice.dxf"
    layers = {e.dxf.layer for e in ezdxf.readfile(lattice).modelspace()}
    assert layers == {PLY.layers.engrave.name, PLY.layers.outer_cut.name}
    pockets = shapely.union_all([shapely.Polygon(r) for r in rings(lattice, PLY.layers.engrave.name)])
    assert pockets.area == pytest.approx(report.stats["job"]["engrave_area_mm2"], rel=1e-6)
    assert report.stats["inlay_base"] == "pocket"


def test_librecad_and_meerk40t_open_both_files_at_true_size(kit, tmp_path):
    import os

    _, _, lattice, pieces, _ = kit
    librecad = program("librecad", "apt-get install librecad")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_RUNTIME_DIR=str(tmp_path))
    for path in (lattice, pieces):
        copy = tmp_path / path.name
        copy.write_bytes(path.read_bytes())
        run([librecad, "dxf2pdf", "-a", copy], env=env, cwd=tmp_path, timeout=120)
        assert copy.with_suffix(".pdf").stat().st_size > 1000
    jobs = {p.name: meerk40t(p, tmp_path / p.stem) for p in (lattice, pieces)}
    lat, pcs = (np.concatenate(burns(jobs[p.name]["gcode"])) for p in (lattice, pieces))
    # true size: the lattice at the tile plus kerf, the pieces at their own extent in the file
    assert np.ptp(lat, axis=0) == pytest.approx([60 + KERF] * 2, abs=0.05)
    drawn = np.concatenate(rings(pieces, PLY.layers.outer_cut.name))
    assert np.ptp(pcs, axis=0) == pytest.approx(np.ptp(drawn, axis=0), abs=0.05)
    assert jobs[pieces.name]["added"] == len(rings(pieces, PLY.layers.outer_cut.name))
    # MeerK40t moved a file reaching past the bed's origin (the lattice's kerf at -0.075 mm, before
    # every file was moved into the positive quadrant) 87.5 mm to the bed's centre and left the pieces
    # where they lay; now it leaves both where they lie, the lattice's corner at (0, 0): they register
    lattice_drawn = np.concatenate(
        [r for e in (PLY.layers.inner_cut.name, PLY.layers.outer_cut.name) for r in rings(lattice, e)]
    )
    assert lattice_drawn.min(axis=0).tolist() == [0.0, 0.0]
    assert lat.min(axis=0) == pytest.approx(lattice_drawn.min(axis=0), abs=0.05)
    assert pcs.min(axis=0) == pytest.approx(drawn.min(axis=0), abs=0.05)


# --------------------------------------------------------------------------- bad input


def test_a_fit_that_makes_pieces_touch_names_the_narrowest_band(tmp_path):
    t = tile(stroke=0.9)
    with pytest.raises(
        FabricationError,
        match=r"pairs of inlay pieces would touch on the pieces sheet: the narrowest "
        r"gap between two pieces is 0 mm \(at .*, where the band of lattice "
        r"between their holes is 0\.9\d+ mm\), and pieces must stand more than "
        r"the kerf = 0\.15 mm apart, so bands must be wider than "
        r"kerf \+ 2 x fit = 1\.15 mm",
    ):
        t.export(tmp_path / "t.dxf", mode="inlay", inlay_fit_mm=0.5)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "options,error,msg",
    [
        (dict(inlay_fit_mm=0.6), ParameterError, r"inlay_fit_mm must be a number of mm from -0\.5 to 0\.5"),
        (
            dict(inlay_base="glued"),
            ParameterError,
            r"'glued' is not a valid inlay_base, must be one of: pierced, pocket",
        ),
    ],
)
def test_bad_kit_options(tmp_path, options, error, msg):
    with pytest.raises(error, match=msg):
        tile().export(tmp_path / "t.dxf", mode="inlay", **options)
    with pytest.raises(
        ParameterError, match=r"inlay_fit_mm, inlay_pieces and inlay_base are options of the inlay mode"
    ):
        tile().export(tmp_path / "t.dxf", inlay_fit_mm=0.1)
    assert list(tmp_path.iterdir()) == []


def test_pocket_needs_an_engrave_layer(tmp_path):
    bare = replace(
        PLY, layers=LaserLayers(inner_cut=PLY.layers.inner_cut, outer_cut=PLY.layers.outer_cut, score=PLY.layers.score)
    )
    with pytest.raises(ProfileError, match=r"has no engrave layer"):
        tile().export(tmp_path / "t.dxf", mode="inlay", inlay_base="pocket", profile=bare)
    assert list(tmp_path.iterdir()) == []


def test_design_and_cli_errors(tmp_path):
    from fabtiles.designs.design_file import design_from_text

    text = '[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsize = 40\n[output]\nlaser_mode = "inlay"\n'
    with pytest.raises(DesignError, match=r"\[output\] inlay_fit_mm must be a number of mm from -0\.5 to 0\.5"):
        design_from_text(text + "inlay_fit_mm = 0.7\n")
    with pytest.raises(
        DesignError, match=r"\[output\] inlay_base = 'glued' is not valid, must be one of: pierced, pocket"
    ):
        design_from_text(text + 'inlay_base = "glued"\n')
    profile = tmp_path / "p.toml"
    profile.write_text('kind = "laser"\n[laser]\ninlay_fit_mm = 0.8\n')
    with pytest.raises(ProfileError, match=r"laser.inlay_fit_mm must be a number of mm from -0.5 to 0.5, got 0.8"):
        load_profile(profile)
    design = tmp_path / "d.toml"
    design.write_text(text + 'formats = ["dxf"]\ninlay_fit_mm = 0.7\n')
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 2 and result.output.count("\n") == 1 and not (tmp_path / "out").exists()


def test_cli_builds_a_kit_in_every_laser_format(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text(
        '[motif]\npreset = "table3-3"\n[packing]\nradius = 10\n[tile]\noutline = "square"\n'
        'size = 60\nframe = 3\n[output]\nformats = ["dxf", "svg", "lbrn2"]\nlaser_mode = "inlay"\n'
        "inlay_fit_mm = 0.1\n"
    )
    result = CliRunner().invoke(cli, ["build", str(design), "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(
        f"d-{part}.{fmt}" for part in ("lattice", "pieces") for fmt in ("dxf", "svg", "lbrn2")
    )
    assert "laser laser-3mm-plywood (inlay kit): ok\n" in result.output
    assert re.search(r"^  pieces: \d+ pieces of \d+ shapes, fit \+0\.1 mm", result.output, re.M), result.output


def test_the_web_app_downloads_a_kit_as_one_archive():
    import io
    import zipfile

    from asgi_client import TestClient

    from fabtiles.web.app import create_app

    client = TestClient(create_app())
    r = client.get("/api/export/dxf?preset=table3-3&width=60&radius=10&frame=3&laser_mode=inlay&inlay_fit_mm=0.1")
    assert r.status_code == 200 and r.headers["content-type"] == "application/zip"
    names = zipfile.ZipFile(io.BytesIO(r.content)).namelist()
    assert names == ["table3-3-lattice.dxf", "table3-3-pieces.dxf"]
    bad = client.get("/api/export/dxf?preset=table3-3&width=60&radius=10&frame=3&laser_mode=inlay&inlay_fit_mm=0.9")
    assert bad.status_code == 422 and bad.json()["field"] == "inlay_fit_mm"


def test_the_kit_picture_of_the_sample_is_up_to_date(tmp_path):
    import importlib.util
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    spec = importlib.util.spec_from_file_location("render_kit", root / "samples" / "render_kit.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    out = module.render(root / "samples" / "table3-3.toml", tmp_path / "kit.svg")
    assert out.read_bytes() == (root / "samples" / "pictures" / "kit-table3-3.svg").read_bytes(), (
        "run python samples/render_kit.py"
    )
    assert out.read_text().count('class="pieces"') == 3


def test_the_web_app_draws_the_kit():
    from asgi_client import TestClient

    from fabtiles.web.app import create_app

    client = TestClient(create_app())
    r = client.get("/api/kit.svg?preset=table3-3&width=60&radius=10&frame=3&inlay_fit_mm=0.1")
    assert r.status_code == 200 and r.headers["content-type"].startswith("image/svg+xml")
    assert r.text.count('class="lattice"') == 3 and r.text.count('class="pieces"') == 3
    assert client.get("/api/kit.svg?preset=table3-3&width=60&inlay_fit_mm=2").status_code == 422


def test_write_kit_leaves_holding_tabs_as_the_design_keys_do(tmp_path):
    from model_files import write_kit

    t = tile()
    report = write_kit(
        tmp_path / "t.dxf", region=t.region(), outline=t.outline_shape(), profile=PLY, tab_mm=1.0, tabs_per_part=2
    )
    # the lattice's outline: two open pieces around two 1 mm gaps, not one closed ring
    doc = ezdxf.readfile(tmp_path / "t-lattice.dxf")
    outer = [e for e in doc.modelspace() if e.dxf.layer == PLY.layers.outer_cut.name]
    assert len(outer) == 2 and not any(e.closed for e in outer)
    length = sum(shapely.LineString(np.array([p[:2] for p in e.get_points("xy")])).length for e in outer)
    assert length == pytest.approx(4 * (60 + KERF) - 2 * 1.0, abs=0.05)
    assert any(n.startswith("holding tabs") for n in report.stats["notes"])
