"""An inlay kit's pieces nested (issue 34): packed apart on their sheet, moved rigidly, lettered by class.

Checked on the files read back (ezdxf) with GEOS: every piece's cut path is its registration cut
path moved by a rigid motion (a half turn at most: the grain), none closer than the gap to
another, all on the sheet; each piece's letter and its lattice hole's letter are its face class's.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from designs import design_toml
from dxf_helpers import read_checked, vertices

from fabtiles.designs.design_file import design_from_text
from fabtiles.geometry.faces import face_classes
from fabtiles.geometry.kit_nesting import GAP_MM
from fabtiles.geometry.stroke_font import text_paths
from fabtiles.making import build_design
from fabtiles.making.models import BuildOptions, Models


def design_text(pieces: str) -> str:
    return design_toml(
        radius=12.5, stroke=1.5, output={"formats": ["dxf"], "laser_mode": "inlay", "inlay_pieces": pieces}
    )


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = {}
    for pieces in ("registration", "nested"):
        folder = tmp_path_factory.mktemp(pieces)
        design = design_from_text(design_text(pieces), name="kit")
        result = build_design(design, folder)
        out[pieces] = (folder, result, design)
    return out


def _closed(e) -> bool:
    return bool(e.closed if e.dxftype() == "LWPOLYLINE" else e.is_closed)


def _cuts(path):
    """The closed cut paths as polygons, and the document."""
    doc = read_checked(path)
    return [
        shapely.Polygon(vertices(e))
        for e in doc.modelspace()
        if e.dxftype() in ("LWPOLYLINE", "POLYLINE") and _closed(e)
    ], doc


def _scores(doc):
    return [vertices(e) for e in doc.modelspace() if e.dxftype() in ("LWPOLYLINE", "POLYLINE") and not _closed(e)]


def _rigid_match(a, b) -> float:
    """Hausdorff distance of polygon ``b`` to ``a`` after the best of a shift or a half turn."""
    best = np.inf
    for angle in (0, 180):
        c = shapely.affinity.rotate(b, angle, origin=(0, 0))
        ca, cc = a.centroid, c.centroid
        moved = shapely.affinity.translate(c, ca.x - cc.x, ca.y - cc.y)
        best = min(best, shapely.hausdorff_distance(a, moved))
    return best


def test_each_nested_piece_is_a_registration_piece_moved_rigidly(built):
    reg, _ = _cuts(built["registration"][0] / "kit-pieces.dxf")
    nested, _ = _cuts(built["nested"][0] / "kit-pieces.dxf")
    outer_reg = [p for p in reg if not any(q is not p and q.contains(p) for q in reg)]
    outer_nest = [p for p in nested if not any(q is not p and q.contains(p) for q in nested)]
    assert len(outer_nest) == len(outer_reg)
    # every piece placed exactly once: the unused registration pieces tried nearest in area first, the
    # first a rigid motion carries onto the nested piece taken (two that both match are congruent)
    unused = list(range(len(outer_reg)))
    for p in outer_nest:
        by_area = sorted(unused, key=lambda j: abs(outer_reg[j].area - p.area))
        k = next((j for j in by_area if _rigid_match(outer_reg[j], p) < 1e-3), None)
        assert k is not None, f"a nested piece of area {p.area:.3f} mm^2 is no registration piece moved rigidly"
        unused.remove(k)
    assert unused == []


def test_nested_pieces_keep_the_gap_and_the_sheet(built):
    folder, result, _ = built["nested"]
    nested, _ = _cuts(folder / "kit-pieces.dxf")
    outer = [p for p in nested if not any(q is not p and q.contains(p) for q in nested)]
    tree = shapely.STRtree(outer)
    a, b = tree.query(outer, predicate="dwithin", distance=GAP_MM - 1e-3)
    assert not np.any(a != b)  # the cut paths (kerf included) at least the gap apart
    x0, y0, x1, y1 = shapely.union_all(outer).bounds
    assert x0 >= -1e-9 and y0 >= -1e-9
    stats = result.reports[0].stats["nested_pieces"]["pieces"]
    assert y1 <= stats["sheet_mm"][1] + 1e-3 and x1 <= stats["sheet_mm"][0] + 1e-3  # the stats are rounded
    assert stats["bbox_of_tile"] < 1.0  # the nested pieces take less than the tile


def _canonical(paths, low, scale):
    """Strokes moved by ``-low``, divided by ``scale``, each its smaller way round, sorted."""
    return sorted(min(tuple(np.round((q - low) / scale, 4).ravel() + 0.0) for q in (p, p[::-1])) for p in paths)


def test_each_piece_and_each_hole_carry_their_face_class_letter(built):
    folder, _, design = built["nested"]
    tile = design.build_tile()
    classes = face_classes(tile, by="shape")
    # the kit's holes (the lattice's), from the registration design: nesting moves only the pieces
    kit = Models(tile, BuildOptions.of_design(built["registration"][2])).cut.kit
    # the hole's letter, by GEOS: the class of the face holding the hole's inner point
    want = []
    for hole in kit.holes:
        face = int(np.argmax(shapely.contains(classes.faces, shapely.point_on_surface(hole))))
        want.append(classes.classes[int(classes.labels[face])].letter)
    # in the lattice file, inside each hole: the strokes of its letter
    _, lattice_doc = _cuts(folder / "kit-lattice.dxf")
    strokes = _scores(lattice_doc)
    checked = 0
    for hole, letter in zip(kit.holes, want, strict=True):
        inside = [s for s in strokes if shapely.contains(hole, shapely.LineString(s))]
        if not inside:  # too small a hole for a letter
            continue
        checked += 1
        glyph = text_paths(letter, height_mm=1.0)
        assert len(inside) == len(glyph)
        # the same strokes, up to a shift and a scale, in any order and either way round (the cut order's)
        got, ref = np.concatenate(inside), np.concatenate(glyph)
        scale = np.ptp(got[:, 1]) / np.ptp(ref[:, 1])
        assert _canonical(inside, got.min(axis=0), scale) == _canonical(glyph, ref.min(axis=0), 1.0)
    assert checked == len(kit.holes)  # every hole of this kit is large enough for its letter
    # each nested piece holds its own letter's strokes (the kit's holes here are all of one class or more)
    _pieces, pieces_doc = _cuts(folder / "kit-pieces.dxf")
    piece_strokes = _scores(pieces_doc)
    assert len(piece_strokes) == sum(len(text_paths(letter, height_mm=1.0)) for letter in want)


def test_registration_kits_are_unlettered(built):
    _, doc = _cuts(built["registration"][0] / "kit-pieces.dxf")
    assert _scores(doc) == []


def test_nesting_a_kit_leaves_the_registration_kit_and_its_report_as_they_were():
    from fabtiles.geometry.kit_nesting import class_letters, nest_kit
    from fabtiles.making.pipeline import prepare_tile

    design = design_from_text(design_text("registration"), name="kit")
    models = Models(prepare_tile(design), BuildOptions.of_design(design))
    plans = models.cut
    before = dict(plans.report.stats)
    classes = face_classes(models.tile, by="shape")
    letters = class_letters(plans.kit.holes, classes.faces, classes.labels, [c.letter for c in classes.classes])
    nested = nest_kit(plans, letters_of_holes=letters, time_s=0.5)
    assert plans.report.stats == before and "nested_pieces" not in plans.report.stats  # made once, never changed
    assert nested.report.stats["nested_pieces"]["pieces"]["pieces"] == len(plans.kit.pieces)
    assert nested.report.stats["notes"][-1].startswith(f"pieces nested: {len(plans.kit.pieces):,} on a ")
