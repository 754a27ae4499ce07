"""Any valid parameters give valid geometry and files that read back valid; any invalid
parameters give a FabtilesError and nothing else (issue 8).

Hard cases are drawn on purpose: radii in any order, alpha beyond half a step, negative
spr, strokes that merge everything, tiles smaller than one motif.
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

import fabtiles as ft

OUTLINES = ("square", "rectangle", "hexagon", "circle")


@st.composite
def motifs(draw, max_n=16):
    n = draw(st.integers(3, max_n))
    radii = draw(st.lists(st.floats(0.1, 10), min_size=2, max_size=4))  # any order
    special = draw(st.none() | st.integers(2, len(radii)))
    return ft.Star(
        n=n,
        radii=radii,
        special=special,
        alpha=draw(st.floats(-2, 2).map(lambda k: k * 180 / n)),  # up to two half-steps either way
        spr=draw(st.floats(-10, 10)),
        rotation=draw(st.floats(-180, 180)),
    )


@st.composite
def tiles(draw):
    outline = draw(st.sampled_from(OUTLINES))
    w = draw(st.floats(6, 60))
    h = draw(st.floats(6, 60)) if outline == "rectangle" else w
    frame = draw(st.sampled_from([0.0, 0.5, 2.0]))
    assume(min(w, h) > 2 * frame + 0.5)
    motif = draw(motifs())
    if draw(st.booleans()):
        radius = draw(st.floats(2, 30))  # up to tiles smaller than one motif
        pattern = ft.HexPacking(
            radius=radius, motif=motif, gap_motif=draw(st.none() | motifs(max_n=8)), outline_circles=draw(st.booleans())
        )
        max_stroke = radius
    else:
        pattern = motif
        max_stroke = min(w, h) / 2 - frame  # the motif's circle inside the frame
    stroke = draw(st.floats(0.2, max(0.2, min(max_stroke, 5.0))))  # up to strokes that merge everything
    join = draw(st.sampled_from(["miter", "round", "bevel"]))
    return ft.Tile(outline, (w, h), pattern, frame=frame, stroke=stroke, join=join)


def _parts(geom):
    return list(getattr(geom, "geoms", [geom]))


@settings(max_examples=examples(40))
@given(tiles())
def test_any_valid_tile_has_a_valid_region_inside_its_outline(tile):
    region = tile.region()
    assert region.is_valid  # may be empty: a tile smaller than one motif can miss every stroke
    outline = tile.outline_shape()
    assert outline.bounds[:2] == pytest.approx((0, 0), abs=1e-9)
    assert region.difference(outline.buffer(1e-6)).area < 1e-9
    for p in _parts(region):  # closed rings
        assert p.exterior.is_closed and all(h.is_closed for h in p.interiors)


def _profile(tmp_path, stroke):
    """A laser profile whose minimum feature admits the drawn stroke."""
    path = tmp_path / "laser.toml"
    path.write_text(
        f'kind = "laser"\n[laser]\nkerf_mm = {min(0.1, stroke / 2):.4f}\n'
        f"min_feature_mm = {stroke * 0.99:.4f}\nbed_mm = [600, 400]\n"
    )
    return path


@settings(max_examples=examples(25), suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(tile=tiles(), r12=st.booleans(), score=st.booleans())
def test_any_valid_tile_writes_a_clean_dxf(tmp_path, tile, r12, score):
    import ezdxf

    path = tmp_path / "t.dxf"
    path.unlink(missing_ok=True)  # tmp_path is shared by the examples of one test
    options = dict(
        profile=_profile(tmp_path, tile.stroke),
        dxf_version="R12" if r12 else None,
        mode="score" if score else "pierced",
    )
    if tile.region().is_empty:
        with pytest.raises(ft.FabricationError, match="the tile holds no material"):
            tile.export(path, **options)
        assert not path.exists()
        return
    if score and not len(tile.centrelines()):
        with pytest.raises(ft.FabricationError, match="the score mode has no line to score"):
            tile.export(path, **options)
        assert not path.exists()
        return
    tile.export(path, **options)
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    for e in doc.modelspace():
        assert e.dxftype() in ("LWPOLYLINE", "POLYLINE")
        if e.dxf.layer.startswith("CUT"):
            assert e.is_closed


@settings(max_examples=examples(12), suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(tile=tiles(), style=st.sampled_from(["relief", "pierced", "deboss"]), fmt=st.sampled_from(["stl", "3mf"]))
def test_any_valid_tile_writes_a_watertight_mesh(tmp_path, tile, style, fmt):
    import trimesh

    path = tmp_path / f"t.{fmt}"
    path.unlink(missing_ok=True)  # tmp_path is shared by the examples of one test
    if tile.region().is_empty:
        with pytest.raises(ft.FabricationError, match="the tile holds no material"):
            tile.export(path, style=style)
        assert not path.exists()
        return
    try:
        tile.export(path, style=style)
    except ft.FabricationError as exc:
        # a deboss whose every groove is too narrow to print (filled by default) would be a blank plate:
        # refused by design, with no file (seen on a 6 mm tile of 0.5 mm strokes)
        assert style == "deboss" and "every groove of this deboss is narrower than min_hole_mm" in str(exc)
        assert not path.exists()
        return
    if fmt == "3mf":  # one object; its parts as a slicer splits them
        from fabtiles.export.threemf import read_3mf

        meshes = [trimesh.Trimesh(p.vertices.astype(float), p.faces) for p in read_3mf(path).values()]
    else:
        meshes = [trimesh.load(path)]
    for mesh in meshes:
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0


@pytest.mark.slow
@settings(max_examples=examples(4), suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(tile=tiles())
def test_any_valid_tile_writes_one_step_solid(tmp_path, tile):
    path = tmp_path / "t.step"
    path.unlink(missing_ok=True)  # tmp_path is shared by the examples of one test
    if tile.region().is_empty:
        with pytest.raises(ft.FabricationError, match="the tile holds no material"):
            tile.export(path)
        assert not path.exists()
        return
    tile.export(path)
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    shape = reader.OneShape()
    explorer, solids = TopExp_Explorer(shape, TopAbs_SOLID), 0
    while explorer.More():
        solids += 1
        explorer.Next()
    assert solids == 1


# -- invalid input: a FabtilesError and nothing else ----------------------------------

anything = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-5, 200),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=5),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=30),
    st.tuples(st.integers(-3, 3), st.integers(-3, 3)),
)


@settings(max_examples=examples(300))
@given(n=anything, radii=anything, alpha=anything, spr=anything, special=anything, rotation=anything)
def test_star_accepts_or_raises_fabtiles_error(n, radii, alpha, spr, special, rotation):
    try:
        star = ft.Star(n=n, radii=radii, alpha=alpha, spr=spr, special=special, rotation=rotation)
    except ft.FabtilesError as exc:
        assert isinstance(exc, ValueError) and str(exc)
        return
    seg = star.segments()
    assert seg.ndim == 3 and np.isfinite(seg).all()


@settings(max_examples=examples(200))
@given(
    outline=st.one_of(st.sampled_from(OUTLINES), anything),
    size=anything,
    frame=anything,
    stroke=anything,
    join=st.one_of(st.sampled_from(["miter", "round", "bevel"]), anything),
    radius=anything,
    corner=anything,
)
def test_tile_accepts_or_raises_fabtiles_error(outline, size, frame, stroke, join, radius, corner):
    motif = ft.Star.preset("table3-3")
    try:
        pattern = ft.HexPacking(radius=radius, motif=motif)
        tile = ft.Tile(outline, size, pattern, frame=frame, stroke=stroke, join=join, corner_radius=corner)
    except ft.FabtilesError as exc:
        assert isinstance(exc, ValueError) and str(exc)
        return
    assume(tile.width_mm * tile.height_mm / max(pattern.radius, 1) ** 2 < 400)  # keep it quick
    assert tile.region().is_valid


@settings(max_examples=examples(60), suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kerf=anything, mode=anything, version=anything, style=anything, base=anything, relief=anything)
def test_export_options_accept_or_raise_fabtiles_error(tmp_path, kerf, mode, version, style, base, relief):
    tile = ft.Tile("square", 30, ft.HexPacking(radius=10, motif=ft.Star.preset("table3-3")), frame=2, stroke=1.2)
    for path, options in (
        (tmp_path / "t.dxf", dict(kerf_mm=kerf, mode=mode, dxf_version=version)),
        (tmp_path / "t.stl", dict(style=style, base_mm=base, relief_mm=relief)),
    ):
        try:
            tile.export(path, **options)
        except ft.FabtilesError as exc:
            assert str(exc)
            assert not path.exists()
        else:
            assert path.stat().st_size > 0
        path.unlink(missing_ok=True)
        assert list(tmp_path.iterdir()) == []


def test_a_deboss_of_only_unprintable_grooves_is_refused_with_no_file(tmp_path):
    """The case the property above found: every groove under the nozzle, filled, would leave a blank plate."""
    tile = ft.Tile("square", (6, 6), ft.Star(n=3, radii=(1, 1)), frame=0, stroke=0.5, join="miter")
    with pytest.raises(ft.FabricationError, match=r"every groove of this deboss is narrower than min_hole_mm = 0.8 mm"):
        tile.export(tmp_path / "t.stl", style="deboss")
    assert not (tmp_path / "t.stl").exists()


def test_a_score_tile_with_no_centre_line_inside_is_refused_saying_so(tmp_path):
    """Only the edges of strokes reach into a tile smaller than its packing's motifs: nothing to score."""
    tile = ft.Tile("square", 6, ft.HexPacking(radius=7, motif=ft.Star(n=3, radii=(2, 3))), frame=0, stroke=1)
    assert not tile.region().is_empty and not len(tile.centrelines())
    with pytest.raises(ft.FabricationError, match="every centre-line of the pattern lies outside the outline"):
        tile.export(tmp_path / "t.dxf", profile=_profile(tmp_path, 1.0), mode="score")
    assert not (tmp_path / "t.dxf").exists()
