"""Holding tabs in the files (issue 34): open outer-cut pieces in the DXF, the SVG and the LightBurn project,
read back and measured with GEOS against the same tile's file without tabs; MeerK40t plans the job."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely
from shapely.geometry import LinearRing, LineString, Point, Polygon
from test_laser_programs import burns, meerk40t

from fabtiles import HexPacking, ParameterError, Star, Tile
from fabtiles.machines.profiles import load_profile

PLY = load_profile("laser-3mm-plywood")
OUTER, INNER = PLY.layers.outer_cut.name, PLY.layers.inner_cut.name
TAB = 0.5


def tile(frame=3.0):
    return Tile("square", 60, HexPacking(10, Star.preset("table3-3")), frame=frame, stroke=1.0)


def dxf_paths(path) -> list:
    """``(layer, closed, vertices)`` of every polyline (R2000's LWPOLYLINE, R12's POLYLINE), in file order."""
    out = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "LWPOLYLINE":
            out.append((e.dxf.layer, bool(e.closed), np.array([p[:2] for p in e.get_points("xy")])))
        else:
            xy = np.array([(v.dxf.location.x, v.dxf.location.y) for v in e.vertices])
            out.append((e.dxf.layer, bool(e.is_closed), xy))
    return out


def gap_lengths(ring: LinearRing, pieces: list) -> np.ndarray:
    """Each gap's length along ``ring``, from a piece's end to the next piece's start."""
    starts = np.array([ring.project(Point(p[0])) for p in pieces])
    ends = np.array([ring.project(Point(p[-1])) for p in pieces])
    return (np.roll(starts, -1) - ends) % ring.length


@pytest.fixture(scope="module")
def dxfs(tmp_path_factory):
    out = tmp_path_factory.mktemp("tabs")
    paths = {}
    for frame in (3.0, 0.0):
        for version in ("R2000", "R12"):
            for tab in (0.0, TAB):
                paths[frame, version, tab] = out / f"f{frame:g}-{version}-{tab:g}.dxf"
                tile(frame).export(paths[frame, version, tab], tab_mm=tab, tabs_per_part=4, dxf_version=version)
    return paths


@pytest.mark.parametrize("version", ["R2000", "R12"])
def test_the_dxfs_outer_cut_is_four_pieces_around_gaps_of_tab_mm(dxfs, version):
    plain = dxf_paths(dxfs[3.0, version, 0.0])
    tabbed = dxf_paths(dxfs[3.0, version, TAB])
    (ring,) = [LinearRing(v) for layer, closed, v in plain if layer == OUTER]
    pieces = [v for layer, closed, v in tabbed if layer == OUTER]
    assert len(pieces) == 4 and all(not closed for layer, closed, _ in tabbed if layer == OUTER)
    # GEOS: every piece lies on the outline, the gaps are tab_mm long along it (and as the crow flies:
    # they sit on the square's straight sides)
    assert max(ring.distance(LineString(p)) for p in pieces) < 1e-6
    assert gap_lengths(ring, pieces) == pytest.approx([TAB] * 4, abs=0.01)
    chords = [np.hypot(*(b[0] - a[-1])) for a, b in zip(pieces, pieces[1:] + pieces[:1], strict=True)]
    assert chords == pytest.approx([TAB] * 4, abs=0.01)
    # the pieces and the gaps bridged make the closed outline again
    bridges = [LineString([a[-1], b[0]]) for a, b in zip(pieces, pieces[1:] + pieces[:1], strict=True)]
    merged = shapely.line_merge(shapely.union_all([LineString(p) for p in pieces] + bridges))
    assert merged.geom_type == "LineString" and merged.is_closed
    assert Polygon(merged).symmetric_difference(Polygon(ring)).area < 1e-6
    assert sum(LineString(p).length for p in pieces) + 4 * TAB == pytest.approx(ring.length, abs=1e-6)
    # the holes keep their closed contours, every one (the cut order may differ: it heads for the outer cut's start)
    holes = sorted((closed, v.tolist()) for layer, closed, v in plain if layer == INNER)
    assert sorted((closed, v.tolist()) for layer, closed, v in tabbed if layer == INNER) == holes
    assert all(closed for closed, _ in holes)


def test_a_frameless_tiles_jagged_outline_gets_its_tabs_on_its_straight_stretches(dxfs):
    plain = dxf_paths(dxfs[0.0, "R2000", 0.0])
    tabbed = dxf_paths(dxfs[0.0, "R2000", TAB])
    rings = [LinearRing(v) for layer, _, v in plain if layer == OUTER]
    pieces = [v for layer, _, v in tabbed if layer == OUTER]
    assert len(pieces) == 4 * len(rings)
    for k, ring in enumerate(rings):
        mine = pieces[4 * k : 4 * k + 4]
        assert max(ring.distance(LineString(p)) for p in mine) < 1e-6
        assert gap_lengths(ring, mine) == pytest.approx([TAB] * 4, abs=0.01)
        # each gap on one straight edge of the outline: its ends a straight tab_mm apart
        chords = [np.hypot(*(b[0] - a[-1])) for a, b in zip(mine, mine[1:] + mine[:1], strict=True)]
        assert chords == pytest.approx([TAB] * 4, abs=0.01)


def test_the_report_and_the_job_estimate_count_the_pieces(tmp_path):
    t = tile()
    plain = t.export(tmp_path / "plain.dxf")
    report = t.export(tmp_path / "tabbed.dxf", tab_mm=TAB, tabs_per_part=4)
    assert report.stats["job"]["pierces"] == plain.stats["job"]["pierces"] + 3
    assert report.stats["job"]["cut_mm"]["outer_cut"] == pytest.approx(
        plain.stats["job"]["cut_mm"]["outer_cut"] - 4 * TAB, abs=1e-3
    )
    read = [LineString(v).length for layer, _, v in dxf_paths(tmp_path / "tabbed.dxf") if layer == OUTER]
    assert sum(read) == pytest.approx(report.stats["job"]["cut_mm"]["outer_cut"], abs=1e-3)
    note = next(n for n in report.stats["notes"] if n.startswith("holding tabs"))
    assert note.startswith("holding tabs: 4 tabs of 0.5 mm in 1 part (4 per part) at (")
    assert report.stats["tabs"]["midpoints"] and len(report.stats["tabs"]["midpoints"]) == 4


def test_the_svgs_outer_paths_are_open_and_its_holes_closed(tmp_path):
    path = tmp_path / "t.svg"
    tile().export(path, tab_mm=TAB, tabs_per_part=3)
    ns = "{http://www.w3.org/2000/svg}"
    groups = {
        g.get("id"): [p.get("d") for p in g.iter(f"{ns}path")]
        for g in ET.parse(path).getroot().iter(f"{ns}g")
        if g.get("id")
    }
    assert len(groups[OUTER]) == 3 and not any(d.endswith("Z") for d in groups[OUTER])
    assert groups[INNER] and all(d.endswith("Z") for d in groups[INNER])


def test_the_lightburn_projects_outer_shapes_are_open(tmp_path):
    from test_lbrn2 import read_lbrn2

    path = tmp_path / "t.lbrn2"
    tile().export(path, tab_mm=TAB, tabs_per_part=4)
    project = read_lbrn2(path)
    index = {c["name"]: i for i, c in project["cuts"].items()}
    outer = [s for s in project["shapes"] if s["index"] == index[OUTER]]
    inner = [s for s in project["shapes"] if s["index"] == index[INNER]]
    assert len(outer) == 4 and not any(s["closed"] for s in outer)
    assert inner and all(s["closed"] for s in inner)


def test_an_inlay_kits_pieces_file_holds_each_pieces_tabs(tmp_path):
    report = tile().export(tmp_path / "k.dxf", mode="inlay", tab_mm=TAB, tabs_per_part=2)
    pieces = [v for layer, closed, v in dxf_paths(tmp_path / "k-pieces.dxf") if layer == OUTER and not closed]
    assert len(pieces) == report.stats["pieces_tabs"]["outer_pieces"] == 2 * report.stats["pieces"]
    lattice = [v for layer, closed, v in dxf_paths(tmp_path / "k-lattice.dxf") if layer == OUTER]
    assert len(lattice) == 2


def test_a_routers_export_with_tabs_is_refused(tmp_path):
    t = Tile("square", 150, HexPacking(20, Star.preset("table3-3")), frame=5, stroke=5.0)
    with pytest.raises(
        ParameterError,
        match=r"tab_mm must be 0 for router profile 'router-6mm-mdf', got 0\.5: a "
        r"router file holds the part whole and CAM adds the holding tabs",
    ):
        t.export(tmp_path / "r.dxf", profile="router-6mm-mdf", tab_mm=0.5)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("fmt", ["dxf", "svg"])
def test_meerk40t_cuts_the_pieces_and_leaves_the_gaps(tmp_path, fmt):
    path = tmp_path / f"t.{fmt}"
    t = tile()
    t.export(path, tab_mm=TAB, tabs_per_part=4)
    dxf = tmp_path / "t-read.dxf"
    t.export(dxf, tab_mm=TAB, tabs_per_part=4)
    paths = dxf_paths(dxf)
    job = meerk40t(path, tmp_path)
    assert job["added"] == len(paths)
    assert {kind for kind, _ in job["ops"]} == {"cut"}
    assert sum(refs for _, refs in job["ops"]) == len(paths)
    cut = burns(job["gcode"])
    assert len(cut) == len(paths)
    open_burns = [p for p in cut if not np.allclose(p[0], p[-1], atol=0.03)]
    assert len(open_burns) == 4  # the outer cut's pieces, each burned as a path of its own
    # MeerK40t's G-code may be flipped and moved: the gaps between its pieces' ends are still tab_mm
    ends = np.array([[p[0], p[-1]] for p in open_burns]).reshape(-1, 2)
    gap = [min(np.hypot(*(ends[j] - p[-1])) for j in range(0, len(ends), 2)) for p in open_burns]
    assert gap == pytest.approx([TAB] * 4, abs=0.06)  # MeerK40t works in 1/1000 inch steps
