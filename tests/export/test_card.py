"""The laser test card (``fabtiles calibrate``): DXF and SVG read back, features measured."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from click.testing import CliRunner

from fabtiles import ParameterError
from fabtiles.cli.main import cli
from fabtiles.export.card import write_card
from fabtiles.geometry.calibration import INLAY_MM, MAX_CARD_MM, calibration_card, inlay_fits
from fabtiles.geometry.stroke_font import text_paths
from fabtiles.machines.profiles import load_profile

PROFILES = ["laser-3mm-plywood", "laser-3mm-acrylic"]


def measure(inner, kerf, card):
    """Check every feature's cut contour against its nominal size (contours are kerf-compensated)."""
    boxes = [(r[:, 0].min(), r[:, 1].min(), r[:, 0].max(), r[:, 1].max()) for r in inner]

    def at(x, y):  # the smallest contour around a point
        hits = [b for b in boxes if b[0] < x < b[2] and b[1] < y < b[3]]
        return min(hits, key=lambda b: (b[2] - b[0]) * (b[3] - b[1]))

    for f in card.features:
        x, y = f.at
        if f.kind == "hole":  # the contour is kerf/2 inside the hole all round
            b = at(x, y)
            assert b[2] - b[0] + kerf == pytest.approx(f.size_mm, abs=0.02), f
            assert b[3] - b[1] + kerf == pytest.approx(f.size_mm, abs=0.02), f
        elif f.kind == "bridge":  # two slot contours either side, kerf/2 away from the bridge each
            left, right = at(x - 2, y), at(x + 2, y)
            assert right[0] - left[2] - kerf == pytest.approx(f.size_mm, abs=1e-6), f
        elif f.kind == "inlay_piece":  # the 6 mm square grown by the fit, its contour kerf/2 outside it
            b = at(x, y)
            assert (b[2] - b[0] - kerf, b[3] - b[1] - kerf) == pytest.approx((INLAY_MM + 2 * f.size_mm,) * 2, abs=1e-6)
        elif f.kind == "kerf_part":  # the part's contour is kerf/2 outside it
            b = min((b for b in boxes if b[0] < x < b[2] and b[1] < y < b[3]), key=lambda b: b[2] - b[0])
            assert b[2] - b[0] - kerf == pytest.approx(f.size_mm, abs=1e-6)
        else:
            b = at(x, y)
            assert b[2] - b[0] + kerf == pytest.approx(f.size_mm, abs=1e-6)


def labels_present(score, card):
    """Each feature's size is written on the score layer in the stroke font, centred on it."""
    # either way round: the cut order may draw a score line backwards (geometry/cut_order.py)
    drawn = {tuple(np.round(q, 3).ravel()) for p in score for q in (p, p[::-1])}
    assert len({min(tuple(np.round(q, 3).ravel()) for q in (p, p[::-1])) for p in score}) == len(card.labels)
    for f in card.features:
        if not f.label:  # the inlay gauge's holes: the fit is written under the piece
            continue
        height = 3.0 if f.kind == "kerf_part" else 2.0
        want = text_paths(f.label, height_mm=height, x=f.at[0], y=0, centre=True)
        # the label's baseline: any drawn path shaped like its first stroke, at the same x
        dys = {
            round(q[0, 1] - want[0][0, 1], 3)
            for p in score
            for q in (p, p[::-1])
            if q.shape == want[0].shape and np.allclose(q[:, 0], want[0][:, 0], atol=1e-3)
        }
        assert any(all(tuple(np.round(w + [0, dy], 3).ravel()) in drawn for w in want) for dy in dys), f


@pytest.mark.parametrize("name", PROFILES)
def test_card_dxf_reads_back_with_measured_features(tmp_path, name):
    import ezdxf

    profile = load_profile(name)
    card = calibration_card(profile)
    path = tmp_path / "card.dxf"
    write_card(path, name)
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4 and not doc.audit().has_errors
    ents = list(doc.modelspace())
    assert {e.dxftype() for e in ents} == {"LWPOLYLINE"}
    layers = [e.dxf.layer for e in ents]
    lay = profile.layers
    # cut order: score, every inner contour, then the outer one; cut contours closed, labels open
    assert layers == sorted(layers, key=[lay.score.name, lay.inner_cut.name, lay.outer_cut.name].index)
    assert layers.count(lay.outer_cut.name) == 1
    assert all(e.closed for e in ents if e.dxf.layer != lay.score.name)
    assert not any(e.closed for e in ents if e.dxf.layer == lay.score.name)
    # the file is the card moved by its outline's half kerf into the positive quadrant: moved back
    shift = np.array(profile.kerf_xy_mm) / 2
    # as drawn: the holes are circles, two arcs each, flattened by ezdxf (within 0.001 mm)
    from dxf_helpers import vertices

    rings = {
        k: [vertices(e) - shift for e in ents if e.dxf.layer == k]
        for k in (lay.inner_cut.name, lay.outer_cut.name, lay.score.name)
    }
    outer = rings[lay.outer_cut.name][0]
    assert (outer + shift).min(axis=0).tolist() == [0.0, 0.0]
    w, h = np.ptp(outer, axis=0)
    assert w == pytest.approx(card.width_mm + profile.kerf_mm) and w <= MAX_CARD_MM + 1 and h <= MAX_CARD_MM + 1
    kinds = [f.kind for f in card.features]
    assert kinds.count("bridge") == 6 and kinds.count("hole") == 6
    fits = [f.size_mm for f in card.features if f.kind == "inlay_piece"]
    assert fits == list(inlay_fits(profile)) and profile.inlay_fit_mm in fits and min(fits) < profile.inlay_fit_mm
    bridges = [f.size_mm for f in card.features if f.kind == "bridge"]
    holes = [f.size_mm for f in card.features if f.kind == "hole"]
    assert min(bridges) < profile.min_feature_mm < max(bridges) and profile.min_feature_mm in bridges
    assert min(holes) < profile.min_hole_mm < max(holes) and profile.min_hole_mm in holes
    measure(rings[lay.inner_cut.name], profile.kerf_mm, card)
    labels_present(rings[lay.score.name], card)


def _svg_points(d: str) -> np.ndarray:
    """The vertices of SVG path data, and its arcs (``A``) drawn by svgelements (MeerK40t's SVG
    library) at 64 points each; a closed path's start not repeated."""
    import svgelements

    pts = []
    for seg in svgelements.Path(d):
        if isinstance(seg, svgelements.Move):
            pts.append((seg.end.x, seg.end.y))
        elif isinstance(seg, svgelements.Arc):
            pts.extend((p.x, p.y) for p in (seg.point(t) for t in np.linspace(0, 1, 65)[1:]))
        elif isinstance(seg, svgelements.Line):
            pts.append((seg.end.x, seg.end.y))
    pts = np.array(pts, dtype=float)
    if d.endswith("Z") and len(pts) > 1 and np.allclose(pts[0], pts[-1]):
        pts = pts[:-1]
    return pts


def test_card_svg_reads_back_with_measured_features(tmp_path):
    profile = load_profile("laser-3mm-plywood")
    card = calibration_card(profile)
    path = tmp_path / "card.svg"
    write_card(path, profile)
    root = ET.parse(path).getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    assert root.get("width").endswith("mm")
    groups = {g.get("id"): g for g in root.findall("s:g", ns)}
    assert list(groups) == ["SCORE", "INNER", "OUTER"]  # cut order

    def rings(gid):
        out = []
        for p in groups[gid].findall("s:path", ns):
            d = p.get("d")
            nums = _svg_points(d)
            nums[:, 1] *= -1  # the SVG's y points down
            out.append((nums, d.endswith("Z")))
        return out

    shift = np.array(profile.kerf_xy_mm) / 2  # the file is the card moved by its outline's half kerf
    assert np.concatenate([r for r, _ in rings("OUTER")]).min(axis=0) == pytest.approx([0, 0], abs=1e-9)
    inner = [(r - shift, closed) for r, closed in rings("INNER")]
    assert all(closed for _, closed in inner) and not any(closed for _, closed in rings("SCORE"))
    measure([r for r, _ in inner], profile.kerf_mm, card)
    labels_present([r - shift for r, _ in rings("SCORE")], card)


def test_calibrate_command(tmp_path):
    out = tmp_path / "card.dxf"
    res = CliRunner().invoke(cli, ["calibrate", "--profile", "laser-3mm-acrylic", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert "test card" in res.output and "laser-3mm-acrylic" in res.output and out.exists()


@pytest.mark.parametrize(
    "args, message",
    [
        (["--profile", "fdm-0.4mm", "-o", "{tmp}/card.dxf"], "is a printer profile"),
        (["--profile", "laser-3mm-plywood", "-o", "{tmp}/card.png"], "the card must be a .dxf or .svg file"),
        (["--profile", "nope", "-o", "{tmp}/card.dxf"], "nope"),
        (["--profile", "laser-3mm-plywood", "--dxf-version", "R9", "-o", "{tmp}/card.dxf"], "'R9' is not a valid"),
    ],
)
def test_calibrate_bad_input_exits_2_and_writes_nothing(tmp_path, args, message):
    args = [a.format(tmp=tmp_path) for a in args]
    res = CliRunner().invoke(cli, ["calibrate", *args])
    assert res.exit_code == 2, res.output
    assert message in res.output
    assert not list(tmp_path.iterdir())


def test_card_too_large_for_the_limits_is_an_error(tmp_path):
    from pathlib import Path

    import fabtiles

    bundled = Path(fabtiles.__file__).resolve().parents[1] / "profiles" / "laser-3mm-plywood.toml"
    big = tmp_path / "big.toml"
    big.write_text(bundled.read_text().replace("min_hole_mm = 1.2", "min_hole_mm = 12"))
    with pytest.raises(ParameterError, match=r"would be \d+ x \d+ mm, larger than 120 x 120 mm"):
        calibration_card(big)
