"""Every cutter file in the positive quadrant (issue 34), read back from the files the build writes.

For each sample and mode (pierced, score, engrave, an inlay kit's lattice and pieces, a
router, a sheet, a circle and a pointy-top hexagon, whose kerf reaches past -kerf/2): every
coordinate of every DXF, SVG and LightBurn project is >= 0, the drawing starts at (0, 0), and
the DXF's extents are the SVG's and the project's. The SVG and the project write 4 decimals,
so their far corner is the DXF's to half a unit of the 4th decimal (5e-5 mm); the near corner
is (0, 0) in all three exactly.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from fabtiles.designs.design_file import load_design
from fabtiles.making import build_design

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"
PRINTED = 5e-5 + 1e-9
"""How far a coordinate the SVG or the project prints (4 decimals) may lie from the DXF's."""

CASES = {
    "pierced": ("table3-3", [], False),
    "score": ("table3-3", ['output.laser_mode="score"'], False),
    "engrave": ("table3-3", ['output.laser_mode="engrave"'], False),
    "inlay": ("table3-3", ['output.laser_mode="inlay"'], False),
    "inlay-pocket": ("table3-3", ['output.laser_mode="inlay"', 'output.inlay_base="pocket"'], False),
    "circle": ("rosette", [], False),
    "hexagon": ("table3-3", ['tile.outline="hexagon"'], False),
    "seamless": ("seamless-hexagon", [], False),
    "router": (
        "table3-3",
        [
            'output.laser_profile="router-6mm-mdf"',
            "tile.stroke=12",
            "packing.radius=60",
            "tile.frame=20",
            "tile.size=[300,300]",
        ],
        False,
    ),
    "waterjet": ("table3-3", ['output.laser_profile="waterjet-1mm-aluminium"', "tile.stroke=3"], False),
    "sheet": ("table3-3", [], True),
}


def dxf_read(path):
    """(every vertex, the drawing's corners, $EXTMIN, $EXTMAX) of a DXF read back by ezdxf.

    The drawing's corners take its arcs (bulges) as ezdxf's own arcs: ``bulge_to_arc``, and each
    arc's exact bounding box (an arc reaches past its end vertices).
    """
    from dxf_helpers import bulges, is_closed, raw_vertices
    from ezdxf.math import ConstructionArc, bulge_to_arc

    doc = ezdxf.readfile(path)
    pts, corners = [], []
    for e in doc.modelspace():
        xy, b = raw_vertices(e), bulges(e)
        pts.append(xy)
        corners.append(xy)
        for i in np.flatnonzero(b if is_closed(e) else b[:-1]):
            centre, start, end, radius = bulge_to_arc(xy[i], xy[(i + 1) % len(xy)], b[i])
            box = ConstructionArc(centre, radius, np.degrees(start), np.degrees(end)).bounding_box
            corners.append(np.array([[box.extmin.x, box.extmin.y], [box.extmax.x, box.extmax.y]]))
    corners = np.concatenate(corners)
    drawn = np.array([corners.min(axis=0), corners.max(axis=0)])
    return np.concatenate(pts), drawn, np.array(doc.header["$EXTMIN"][:2]), np.array(doc.header["$EXTMAX"][:2])


def svg_read(path):
    """(every vertex with y up, an arc's end too, the viewBox's lower-left, its upper-right, width and height in mm)."""
    root = ET.parse(path).getroot()
    x, y, w, h = map(float, root.get("viewBox").split())
    size = [float(root.get(k).removesuffix("mm")) for k in ("width", "height")]
    pts = np.array(
        [
            (float(a), -float(b))
            for p in root.iter("{http://www.w3.org/2000/svg}path")
            for a, b in re.findall(r"(?:[ML]|A\S+ \S+ 0 [01] [01] )(-?[0-9.]+) (-?[0-9.]+)", p.get("d"))
        ]
    )
    return pts, np.array([x, -(y + h)]), np.array([x + w, -y]), np.array(size)


def lbrn2_shapes(path) -> list:
    """The vertices of each shape of a LightBurn project, as written."""
    root = ET.parse(path).getroot()
    return [
        np.array([(float(a), float(b)) for a, b in re.findall(r"V(-?[0-9.]+) (-?[0-9.]+)c", s.find("VertList").text)])
        for s in root.findall("Shape")
    ]


@pytest.fixture(scope="module")
def builds(tmp_path_factory):
    """The build of a case, once for the module's tests: ``builds(case)`` is (the output folder, the result)."""
    done: dict = {}

    def build(case):
        if case not in done:
            sample, overrides, sheet = CASES[case]
            design = load_design(SAMPLES / f"{sample}.toml", overrides=overrides)
            router = "router" in case or "waterjet" in case  # LightBurn is for lasers
            formats = ["dxf", "svg"] if router else ["dxf", "svg", "lbrn2"]
            out = tmp_path_factory.mktemp(case)
            done[case] = out, build_design(design, out, formats, copies=3 if sheet else None)
        return done[case]

    return build


@pytest.fixture(scope="module", params=list(CASES))
def built(request, builds):
    return (request.param, *builds(request.param))


def test_every_coordinate_is_at_least_0_and_the_extents_agree(built):
    case, out, _ = built
    stems = sorted({p.stem for p in out.glob("*.dxf")})
    assert len(stems) == (2 if case.startswith("inlay") else 1)
    for stem in stems:
        pts, drawn, extmin, extmax = dxf_read(out / f"{stem}.dxf")
        assert pts.min() >= 0.0, f"{stem}.dxf: a coordinate {pts.min()} below 0"
        assert drawn.min() >= -1e-9, f"{stem}.dxf: an arc reaches {drawn.min()}, below 0"
        assert extmin.tolist() == [0.0, 0.0]
        if not stem.endswith("-pieces"):  # a kit's pieces file keeps the lattice's extents
            assert drawn[0] == pytest.approx([0.0, 0.0], abs=1e-9)  # the drawing starts at the origin
            assert extmax == pytest.approx(drawn[1], abs=1e-9)
        svg, low, high, size = svg_read(out / f"{stem}.svg")
        assert svg.min() >= 0.0, f"{stem}.svg: a coordinate {svg.min()} below 0"
        assert low.tolist() == [0.0, 0.0]
        assert high == pytest.approx(extmax, abs=PRINTED) and size == pytest.approx(extmax, abs=PRINTED)
        # its vertices: the DXF's, and points on the DXF's arcs where a half turn is cut in quarters
        assert (svg.max(axis=0) >= pts.max(axis=0) - PRINTED).all()
        assert (svg.max(axis=0) <= drawn[1] + PRINTED).all()
        project = out / f"{stem}.lbrn2"
        if project.exists():
            shapes = np.concatenate(lbrn2_shapes(project))
            assert shapes.min() >= 0.0, f"{stem}.lbrn2: a coordinate {shapes.min()} below 0"
            # its vertices: the DXF's, and points on the DXF's arcs where a Bezier of a long arc ends
            assert (shapes.min(axis=0) <= pts.min(axis=0) + PRINTED).all()
            assert (shapes.min(axis=0) >= drawn[0] - PRINTED).all()
            assert (shapes.max(axis=0) >= pts.max(axis=0) - PRINTED).all()
            assert (shapes.max(axis=0) <= drawn[1] + PRINTED).all()


def test_the_report_gives_the_files_move_from_the_tile(built):
    case, _, result = built
    stats = result.reports[0].stats
    offset = stats["file_offset_mm"]
    if case == "router":  # no kerf: the part as the bit makes it is not moved
        assert offset == [0.0, 0.0]
    elif case == "hexagon":  # the mitred tip of the pointy-top hexagon's kerf: kerf/2 / sin 60 deg below
        assert offset == pytest.approx([0.075, 0.075 / np.sin(np.pi / 3)], abs=1e-6)
    elif case == "circle":  # the flattened circle's kerf reaches a little past -kerf/2
        assert 0.075 < offset[0] < 0.07501 and offset[0] == offset[1]
    elif case == "waterjet":
        assert offset == [0.5, 0.5]
    elif case != "seamless":
        assert offset == pytest.approx([0.075, 0.075], abs=1e-9)


@pytest.mark.parametrize("fmt", ["dxf", "lbrn2"])
def test_a_kits_pieces_lie_in_their_lattice_holes_read_back(builds, fmt):
    """The lattice and the pieces share one origin: each piece's cut, read back, holds a hole of the lattice's."""
    tmp_path, _ = builds("inlay")  # the table3-3 sample as an inlay kit, its DXFs and projects
    if fmt == "dxf":

        def contours(path, layer):
            return [
                np.array([p[:2] for p in e.get_points("xy")])
                for e in ezdxf.readfile(path).modelspace()
                if e.dxf.layer == layer
            ]

        holes = contours(tmp_path / "table3-3-lattice.dxf", "INNER")
        pieces = contours(tmp_path / "table3-3-pieces.dxf", "OUTER")
    else:
        holes = lbrn2_shapes(tmp_path / "table3-3-lattice.lbrn2")[:-1]  # the outline is the last shape
        pieces = lbrn2_shapes(tmp_path / "table3-3-pieces.lbrn2")
    holes, pieces = (np.array([shapely.Polygon(r) for r in rings]) for rings in (holes, pieces))
    assert len(pieces) > 100 and len(holes) >= len(pieces)
    tree, worst = shapely.STRtree(holes), []
    for piece in pieces:
        inside = tree.query(piece, predicate="contains_properly")
        assert len(inside) == 1, "each piece over exactly one hole"
        # in register, not merely overlapping: the centres of the piece's cut (the hole grown by the fit
        # and half the kerf) and of the hole's (shrunk by half the kerf) lie at most 0.016 mm apart
        # (measured: a grown and a shrunk kite do not share a centroid exactly); the pieces moved by
        # half the kerf (0.075 mm) against the lattice put them at least 0.059 mm apart
        centres = shapely.get_coordinates(shapely.centroid([piece, holes[inside[0]]]))
        worst.append(float(np.hypot(*(centres[0] - centres[1]))))
    assert max(worst) < 0.03, max(worst)
