"""Laser DXF (issue 4): read every file back with ezdxf and check what a laser needs."""

from __future__ import annotations

import io
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest
import shapely
from dxf_helpers import (
    CUT_TYPES,
    assert_golden,
    check_laser_dxf,
    dxf_entities,
    edge_problems,
    is_closed,
    island_region,
    motif_tile,
    read_checked,
    star_plate,
    thin_bridge_region,
    tiny_hole_region,
    vertices,
)
from model_files import write_cut
from shapely.geometry import box

from fabtiles import FabricationError, FabtilesError, ParameterError, ProfileError
from fabtiles.export.dxf import build_document, dxf_text
from fabtiles.geometry.cut_plan import CutOptions, plan_cut
from fabtiles.machines.profiles import LaserLayers, Layer, load_profile

PLY = load_profile("laser-3mm-plywood")
INNER, OUTER, SCORE = PLY.layers.inner_cut, PLY.layers.outer_cut, PLY.layers.score


@pytest.mark.parametrize("version", ["R2000", "R12", "R2018"])
@pytest.mark.parametrize("kerf", [0.0, 0.15, 0.4])
def test_star_plate_round_trip(tmp_path, version, kerf):
    region, outline = star_plate()
    path = tmp_path / "plate.dxf"
    report = write_cut(path, region=region, outline=outline, profile=PLY, kerf_mm=kerf, dxf_version=version)
    doc = check_laser_dxf(path, region, kerf=kerf, version=version)
    assert report.ok, report.summary()
    assert report.stats["inner_contours"] == 9 and report.stats["outer_contours"] == 1
    assert report.stats["dxf_version"] == version
    xmin, ymin, xmax, ymax = (
        np.vstack([vertices(e) for e in doc.modelspace()]).min(0).tolist()
        + np.vstack([vertices(e) for e in doc.modelspace()]).max(0).tolist()
    )
    # the plate grown by half the kerf, moved by half the kerf into the positive quadrant
    assert (xmin, ymin) == (0.0, 0.0) and (xmax, ymax) == pytest.approx((60 + kerf, 60 + kerf))
    assert report.stats["file_offset_mm"] == pytest.approx([kerf / 2, kerf / 2], abs=1e-9)


@pytest.mark.parametrize("kerf", [0.0, 0.2])
def test_motif_tile_round_trip(tmp_path, kerf):
    region, outline, _ = motif_tile()
    path = tmp_path / "motif.dxf"
    report = write_cut(path, region=region, outline=outline, profile=PLY, kerf_mm=kerf, stroke=1.2)
    check_laser_dxf(path, region, kerf=kerf)
    assert report.stats["inner_contours"] > 20
    assert report.stats["cut_length_mm"] > 400
    assert report.stats["area_mm2"] == pytest.approx(region.area, rel=1e-6)


def test_kerf_keeps_star_tips_sharp(tmp_path):
    region, outline = star_plate(grid=1)
    path = tmp_path / "p.dxf"
    write_cut(path, region=region, outline=outline, profile=PLY, kerf_mm=0.3)
    inner = [vertices(e) for e in read_checked(path).modelspace() if e.dxf.layer == INNER.name]
    assert len(inner) == 1 and len(inner[0]) == 16  # 8 tips and 8 notches: no rounding, no bevel


def test_score_mode(tmp_path):
    region, outline, seg = motif_tile()
    path = tmp_path / "score.dxf"
    report = write_cut(path, region=region, outline=outline, centrelines=seg, profile=PLY, mode="score")
    doc = read_checked(path)
    ents = list(doc.modelspace())
    score = [e for e in ents if e.dxf.layer == SCORE.name]
    cut = [e for e in ents if e.dxf.layer != SCORE.name]
    assert len(cut) == 1 and cut[0].dxf.layer == OUTER.name and is_closed(cut[0])
    assert ents[-1] is cut[-1] or ents[-1].dxf.handle == cut[-1].dxf.handle  # scoring before the cut
    assert score and all(e.dxftype() == "LWPOLYLINE" and not is_closed(e) for e in score)
    assert all(e.dxf.color == SCORE.color for e in score)
    assert len(score) < 0.7 * len(seg)  # chains merged, not a LINE soup
    total = sum(float(np.hypot(*np.diff(vertices(e), axis=0).T).sum()) for e in score)
    clipped = shapely.intersection(shapely.multilinestrings(shapely.linestrings(seg)), outline).length
    assert total == pytest.approx(clipped, rel=1e-6)
    assert report.stats["score_paths"] == len(score)
    for e in score:
        assert edge_problems(vertices(e), closed=False)[0] == 0


def test_score_mode_r12(tmp_path):
    region, outline, seg = motif_tile()
    path = tmp_path / "score12.dxf"
    write_cut(path, region=region, outline=outline, centrelines=seg, profile=PLY, mode="score", dxf_version="R12")
    ents = list(read_checked(path).modelspace())
    assert {e.dxftype() for e in ents} == {"POLYLINE"}
    assert [is_closed(e) for e in ents if e.dxf.layer == SCORE.name] == [False] * (len(ents) - 1)


def test_layers_from_profile_file(tmp_path):
    prof = tmp_path / "prof" / "my-laser.toml"
    prof.parent.mkdir()
    prof.write_text(
        'kind = "laser"\n[laser]\nkerf_mm = 0.1\n[layers]\n'
        'inner_cut = { name = "HOLES", color = 6 }\nouter_cut = { name = "OUTLINE", color = 2 }\n'
        'score = { name = "ETCH", color = 4 }\n'
    )
    region, outline = star_plate()
    path = tmp_path / "out" / "p.dxf"
    write_cut(path, region=region, outline=outline, profile=prof)
    check_laser_dxf(path, region, kerf=0.1, profile=load_profile(prof))
    names = {e[0] for e in dxf_entities(path)}
    assert names == {"HOLES", "OUTLINE"}


def test_island_and_loose_parts(tmp_path):
    region, outline = island_region()
    path = tmp_path / "i.dxf"
    report = write_cut(path, region=region, outline=outline, profile=PLY)
    assert [f.code for f in report.findings] == ["loose_part"]
    assert report.findings[0].locations == ((25.0, 25.0),)
    doc = check_laser_dxf(path, region, kerf=PLY.kerf_mm)
    ents = [(e.dxf.layer, vertices(e)) for e in doc.modelspace()]
    # island outline (inside the hole) is cut before the hole around it, the plate's outline last
    assert [layer for layer, _ in ents] == [INNER.name, INNER.name, OUTER.name]
    # the finding is where the tile has it; the file is the tile moved by half the kerf (its outline's
    # kerf reaches -kerf/2), so the island's contour lies at 20 - kerf/2 + kerf/2, the hole's at 10 + kerf
    shift = PLY.kerf_mm / 2
    assert report.stats["file_offset_mm"] == pytest.approx([shift, shift], abs=1e-9)
    assert ents[0][1][:, 0].min() == pytest.approx(20 - PLY.kerf_mm / 2 + shift)
    assert ents[1][1][:, 0].min() == pytest.approx(10 + PLY.kerf_mm / 2 + shift)


def test_fill_small_holes(tmp_path):
    region, outline = tiny_hole_region()
    path = tmp_path / "t.dxf"
    report = write_cut(path, region=region, outline=outline, profile=PLY, kerf_mm=0.1)
    assert [f.code for f in report.findings] == ["small_hole"]
    assert report.stats["inner_contours"] == 2
    report = write_cut(path, region=region, outline=outline, profile=PLY, kerf_mm=0.1, fill_small_holes=True)
    assert report.ok and report.stats["filled_holes"] == 1 and report.stats["inner_contours"] == 1
    assert report.summary().splitlines()[0].endswith("ok")


def test_strict_profile_refuses_and_writes_nothing(tmp_path):
    strict = replace(PLY, strict=True)
    region, outline = thin_bridge_region()
    path = tmp_path / "out.dxf"
    with pytest.raises(FabricationError, match=r"thin_bridge.*strict"):
        write_cut(path, region=region, outline=outline, profile=strict)
    assert list(tmp_path.iterdir()) == []
    region, outline = star_plate()
    assert write_cut(path, region=region, outline=outline, profile=strict).ok


def test_failure_keeps_existing_file(tmp_path):
    region, outline = star_plate()
    path = tmp_path / "keep.dxf"
    write_cut(path, region=region, outline=outline, profile=PLY)
    before = path.read_bytes()
    with pytest.raises(ParameterError):
        write_cut(path, region=region, outline=outline, profile=PLY, kerf_mm=-1)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["keep.dxf"]


BAD = [
    (dict(kerf_mm=-0.1), ParameterError, r"kerf_mm must be a finite number >= 0, got -0.1"),
    (dict(kerf_mm=float("nan")), ParameterError, r"kerf_mm must be a finite number"),
    (dict(kerf_mm=1.5, stroke=1.2), ParameterError, r"kerf_mm must be >= 0 and <= the stroke \(1.2 mm\), got 1.5"),
    (dict(stroke=0.5), ParameterError, r"stroke must be >= min_feature_mm = 1 mm .*, got 0.5"),
    (dict(profile="laser-9mm-unobtainium"), ProfileError, r"profile 'laser-9mm-unobtainium' does not exist"),
    (dict(profile="fdm-0.4mm"), ProfileError, r"printer profile, but a laser profile is needed"),
    (
        dict(profile=replace(PLY, layers=LaserLayers(inner_cut=Layer("INNER", 300)))),
        ProfileError,
        r"layers.inner_cut.color must be an AutoCAD Color Index 1..255, got 300",
    ),
    (dict(mode="etch"), ParameterError, r"'etch' is not a valid mode, must be one of: pierced, score, engrave"),
    (dict(dxf_version="R14"), ParameterError, r"'R14' is not a valid dxf_version"),
    (dict(mode="score"), ParameterError, r"score mode needs centrelines"),
    (dict(region=box(0, 0, 1, 1).boundary), ParameterError, r"region must be a shapely Polygon or MultiPolygon"),
    (dict(region=shapely.Polygon()), ParameterError, r"region is empty"),
    (dict(region=shapely.Polygon([(0, 0), (10, 10), (10, 0), (0, 10)])), ParameterError, r"region is not a valid"),
    (
        dict(outline=box(0, 0, 700, 300)),
        FabricationError,
        r"the tile is 700 x 300 mm, larger than the 600 x 400 mm bed",
    ),
    (dict(fill_small_holes="yes"), ParameterError, r"fill_small_holes must be True or False"),
]


@pytest.mark.parametrize("change, error, message", BAD, ids=[m[:30] for _, _, m in BAD])
def test_bad_input_is_an_error_and_no_file(tmp_path, change, error, message):
    region, outline = star_plate()
    args = dict(region=region, outline=outline, profile=PLY) | change
    with pytest.raises(error, match=message) as info:
        write_cut(tmp_path / "bad.dxf", **args)
    assert isinstance(info.value, FabtilesError)
    assert list(tmp_path.iterdir()) == []


def test_bad_profile_colour_in_file(tmp_path):
    prof = tmp_path / "p.toml"
    prof.write_text('kind = "laser"\n[layers]\nscore = { name = "S", color = 0 }\n')
    region, outline = star_plate()
    with pytest.raises(ProfileError, match=r"layers.score.color must be an AutoCAD Color Index 1..255, got 0"):
        write_cut(tmp_path / "out.dxf", region=region, outline=outline, profile=prof)
    assert [p.name for p in tmp_path.iterdir()] == ["p.toml"]


@pytest.mark.parametrize("version", ["R12", "R2000", "R2004", "R2007", "R2010", "R2013", "R2018"])
@pytest.mark.parametrize("mode", ["pierced", "score"])
def test_fast_writer_matches_ezdxf(version, mode):
    region, outline, seg = motif_tile(size=60, stroke=1.5)
    job = plan_cut(region, outline, CutOptions.of(profile=PLY, mode=mode), centrelines=seg)
    fast, _ = dxf_text(job, dxf_version=version)
    stream = io.StringIO()
    build_document(job, dxf_version=version).write(stream)
    ref = stream.getvalue()

    def body(text):
        start = text.index("ENTITIES")
        return text[start : text.index("ENDSEC", start)]

    def handseed(text):
        at = text.find("$HANDSEED")
        return text[at : at + 30] if at >= 0 else None

    assert body(fast) == body(ref)
    assert handseed(fast) == handseed(ref)


def test_sheet_sized_tile_and_bed_turned(tmp_path):
    region, outline = star_plate(size=400, grid=4)  # 400 x 400: fits the 600 x 400 bed
    assert write_cut(tmp_path / "a.dxf", region=region, outline=outline, profile=PLY).ok
    tall = box(0, 0, 400, 600)  # fits turned by 90 degrees
    assert write_cut(tmp_path / "b.dxf", region=tall, outline=tall, profile=PLY).ok


@pytest.mark.parametrize(
    "name, mode, version",
    [("star_plate", "pierced", "R2000"), ("star_plate_r12", "pierced", "R12"), ("motif_score", "score", "R2000")],
)
def test_golden(tmp_path, name, mode, version):
    if name.startswith("star_plate"):
        region, outline = star_plate(grid=2)
        seg = None
    else:
        region, outline, seg = motif_tile(size=50, stroke=1.2, preset="table2-left")
    path = tmp_path / f"{name}.dxf"
    write_cut(path, region=region, outline=outline, centrelines=seg, profile=PLY, mode=mode, dxf_version=version)
    assert_golden(path, name)


def test_importing_the_writer_does_not_load_ezdxf():
    code = "import sys, fabtiles.export.dxf, fabtiles.export.laser_svg; assert 'ezdxf' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_dispatch_passes_options(tmp_path):
    from fabtiles.making import export_region

    region, outline = star_plate()
    report = export_region(tmp_path / "d.dxf", region=region, outline=outline, stroke=1.0, kerf_mm=0.0)
    assert report.stats["kerf_mm"] == 0.0 and report.format == "dxf"
    assert all(e[1] in CUT_TYPES for e in dxf_entities(tmp_path / "d.dxf"))


def _entity_extents(doc) -> tuple:
    pts = np.vstack([vertices(e) for e in doc.modelspace()])
    return (*pts.min(0).tolist(), *pts.max(0).tolist())


@pytest.mark.parametrize("version", ["R12", "R2000", "R2018"])
@pytest.mark.parametrize("kerf", [0.0, 0.3])
@pytest.mark.parametrize("mode", ["pierced", "score"])
def test_header_extents_are_the_entities_bounding_box(tmp_path, version, kerf, mode):
    """$EXTMIN/$EXTMAX (laser programs zoom to them) bound every entity written, kerf included."""
    import ezdxf

    region, outline, lines = motif_tile()
    path = tmp_path / "motif.dxf"
    write_cut(
        path,
        region=region,
        outline=outline,
        centrelines=lines,
        profile=PLY,
        kerf_mm=kerf,
        dxf_version=version,
        mode=mode,
        stroke=1.2,
    )
    doc = ezdxf.readfile(path)
    xmin, ymin, xmax, ymax = _entity_extents(doc)
    assert tuple(doc.header["$EXTMIN"]) == pytest.approx((xmin, ymin, 0.0), abs=1e-9)
    assert tuple(doc.header["$EXTMAX"]) == pytest.approx((xmax, ymax, 0.0), abs=1e-9)
    # the kerf offset is part of the extents: the outer contour lies kerf/2 outside the outline,
    # and the file is moved into the positive quadrant, its extents from (0, 0)
    x0, y0, x1, y1 = outline.bounds
    assert (xmin, ymin) == (0.0, 0.0)
    assert (xmax, ymax) == pytest.approx((x1 - x0 + kerf, y1 - y0 + kerf), abs=1e-6)


def test_sheet_header_extents(tmp_path):
    """A sheet's extents span all of its tiles."""
    import ezdxf

    from fabtiles.geometry.sheet import layout_sheet

    sheet = layout_sheet([star_plate(size=100)], PLY, copies=5)
    path = tmp_path / "sheet.dxf"
    write_cut(path, region=sheet.region, outline=sheet.outline, profile=PLY)
    doc = ezdxf.readfile(path)
    xmin, ymin, xmax, ymax = _entity_extents(doc)
    kerf = PLY.kerf_mm
    assert (xmin, ymin) == (0.0, 0.0)  # moved by half the kerf: every tile's kerf inside the file
    assert (xmax, ymax) == pytest.approx((sheet.size[0] + kerf, sheet.size[1] + kerf), abs=1e-6)
    assert tuple(doc.header["$EXTMIN"])[:2] == pytest.approx((xmin, ymin), abs=1e-9)
    assert tuple(doc.header["$EXTMAX"])[:2] == pytest.approx((xmax, ymax), abs=1e-9)


# --------------------------------------------------------------------------- reproducible files (issue 31)


def _header_value(text: str, name: str) -> str:
    """The value of the header variable ``name`` in a DXF's text."""
    lines = text.split("\n")
    at = lines.index(name)
    assert lines[at - 1].strip() == "9"
    return lines[at + 2]


def _plate_plan(size=60.0):
    region, outline = star_plate(size=size)
    return plan_cut(region, outline, CutOptions.of(profile=PLY))


@pytest.mark.parametrize("version", ["R12", "R2000", "R2018"])
def test_the_header_holds_fixed_dates_not_todays(version):
    import datetime

    from ezdxf.tools.juliandate import juliandate

    text, _ = dxf_text(_plate_plan(), dxf_version=version)
    fixed = juliandate(datetime.datetime(2000, 1, 1))
    dates = ["$TDCREATE", "$TDUPDATE"] + ([] if version == "R12" else ["$TDUCREATE", "$TDUUPDATE"])
    # read from the text: ezdxf's reader sets $TDCREATE of the document it loads to now
    assert {name: float(_header_value(text, name)) for name in dates} == dict.fromkeys(dates, fixed)
    now = datetime.datetime.now(datetime.timezone.utc)
    for day in (now, now - datetime.timedelta(days=1)):  # a write just after midnight
        assert day.strftime("%Y-%m-%d") not in text and f"{juliandate(day.replace(tzinfo=None)):.0f}" not in text
    assert "CREATED_BY_EZDXF" in text and "WRITTEN_BY_EZDXF" in text  # ezdxf's markers, dated 2000-01-01
    assert text.count("@ 2000-01-01T00:00:00") == 2


def test_the_guids_come_from_the_content():
    def guids(plan):
        text = dxf_text(plan)[0]
        return _header_value(text, "$FINGERPRINTGUID"), _header_value(text, "$VERSIONGUID")

    one = guids(_plate_plan())
    assert one == guids(_plate_plan())
    assert one[0] != one[1] and "{00000000-0000-0000-0000-000000000000}" not in one
    assert all(len(g) == 38 and g[0] + g[-1] == "{}" and g == g.upper() for g in one)
    other = guids(_plate_plan(size=61.0))
    assert not set(one) & set(other)
    assert "$FINGERPRINTGUID" not in dxf_text(_plate_plan(), dxf_version="R12")[0]  # R12 headers have none


def test_a_header_without_ezdxfs_zero_guid_is_an_error():
    from fabtiles.export.dxf import _content_guids

    with pytest.raises(RuntimeError, match=r"unexpected DXF header from ezdxf: \$FINGERPRINTGUID is not the zero GUID"):
        _content_guids("  9\n$FINGERPRINTGUID\n  2\n{C4A1E0F2-0000-4000-8000-000000000000}\n", "R2000")
    assert _content_guids("no header", "R12") == "no header"


@pytest.mark.parametrize("before", [False, True])
def test_ezdxfs_fixed_metadata_option_is_put_back(before):
    import ezdxf

    ezdxf.options.write_fixed_meta_data_for_testing = before
    try:
        dxf_text(_plate_plan())
        assert ezdxf.options.write_fixed_meta_data_for_testing is before
        doc = ezdxf.new("R2000")  # a document of someone else's, after ours: ezdxf's own metadata
        stream = io.StringIO()
        doc.write(stream)
        assert ("{00000000-0000-0000-0000-000000000000}" in stream.getvalue()) is before
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = False


def test_threads_writing_side_by_side_write_the_same_bytes():
    from concurrent.futures import ThreadPoolExecutor

    import ezdxf

    plan = _plate_plan()
    with ThreadPoolExecutor(4) as pool:
        texts = list(pool.map(lambda _: dxf_text(plan, dxf_version="R2018")[0], range(8)))
    assert len(set(texts)) == 1
    assert ezdxf.options.write_fixed_meta_data_for_testing is False


@pytest.mark.parametrize("version", ["R2000", "R2004", "R2018"])
def test_the_classes_do_not_follow_the_order_of_a_set(monkeypatch, version):
    """ezdxf adds a CLASS for each entity type in use, taken from a set (its order: the hash seed's)."""
    from ezdxf.entitydb import EntityDB

    in_use = EntityDB.dxf_types_in_use
    texts = []
    for reverse in (False, True):
        monkeypatch.setattr(
            EntityDB, "dxf_types_in_use", lambda self, r=reverse: dict.fromkeys(sorted(in_use(self), reverse=r)).keys()
        )
        texts.append(dxf_text(_plate_plan(), dxf_version=version)[0])
    assert texts[0] == texts[1]
    at = texts[0].index("\nCLASSES\n")
    classes = texts[0][at : texts[0].index("\nENDSEC\n", at)].split("\n")
    assert "LAYOUT" in classes and "ACDBPLACEHOLDER" in classes


def test_a_plate_with_one_hole_is_one_inner_and_one_outer_contour(tmp_path):
    plate = box(0, 0, 40, 40).difference(box(10, 10, 30, 30))
    r = write_cut(tmp_path / "plate.dxf", region=plate, outline=box(0, 0, 40, 40), profile="laser-3mm-plywood")
    assert (r.stats["inner_contours"], r.stats["outer_contours"], r.ok) == (1, 1, True)
