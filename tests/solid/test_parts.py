"""A relief's parts: the pattern cut from the fused body, so the STL and the 3MF share one meshing."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples
from shapely.geometry import box

from fabtiles import FabricationError
from fabtiles.solid import parts as solid_parts
from fabtiles.solid._mesh_build import resolve_stack
from fabtiles.solid.parts import checked_parts, relief_parts, splits_fused
from fabtiles.solid.print_model import print_model

STACK = resolve_stack("fdm-0.4mm", "relief")


def _triangles(part, z):
    """The part's triangles lying at height ``z``, as a sorted array of corner coordinates."""
    tris = part.vertices[part.faces]
    flat = tris[(tris[:, :, 2] == z).all(axis=1)]
    return flat[np.lexsort(flat.reshape(len(flat), -1).T)]


def _region(holes):
    outline = box(0, 0, 40, 30)
    cut = shapely.union_all([shapely.Point(x, y).buffer(r, quad_segs=6) for x, y, r in holes])
    return outline.difference(cut), outline


@settings(max_examples=examples(25), deadline=None)
@given(st.lists(st.tuples(st.floats(4, 36), st.floats(4, 26), st.floats(0.8, 3.5)), min_size=1, max_size=6))
def test_the_pattern_is_the_fused_body_over_the_base(holes):
    region, outline = _region(holes)
    parts = checked_parts(region, outline, STACK)
    (fused,) = checked_parts(region, outline, STACK, single=True).values()
    base, pattern = parts["base"], parts["pattern"]
    top = np.float32(STACK.base + STACK.relief)
    # the pattern's top is the fused body's top, triangle for triangle
    np.testing.assert_array_equal(_triangles(pattern, top), _triangles(fused, top))
    # and its bottom the same triangles at the base's top, turned over
    bottom = pattern.vertices[pattern.faces]
    bottom = bottom[(bottom[:, :, 2] == np.float32(STACK.base)).all(axis=1)]
    assert len(bottom) == len(_triangles(fused, top))
    a, c = bottom[:, 1, :2] - bottom[:, 0, :2], bottom[:, 2, :2] - bottom[:, 0, :2]
    area = 0.5 * (a[:, 0] * c[:, 1] - a[:, 1] * c[:, 0]).sum()
    assert area == pytest.approx(-fused.region.area, rel=1e-9)
    # volumes: each part its own area x height (heights in float32), together the fused body's
    assert pattern.mesh_volume_mm3 == pytest.approx(fused.region.area * STACK.relief, rel=1e-6)
    assert base.mesh_volume_mm3 == pytest.approx(outline.area * STACK.base, rel=1e-6)
    assert base.mesh_volume_mm3 + pattern.mesh_volume_mm3 == pytest.approx(fused.mesh_volume_mm3, rel=1e-9)


def test_the_model_and_the_api_make_the_same_parts():
    """A 3MF written alone holds the same parts as one written beside an STL (the model's fused body first)."""
    region, outline = _region([(10, 10, 3), (30, 20, 2.5)])
    api = checked_parts(region, outline, STACK)
    model = print_model(region, outline, profile="fdm-0.4mm", style="relief")
    _ = model.fused  # the STL's body made first, as a build writing STL and 3MF does
    for name, part in model.parts.items():
        np.testing.assert_array_equal(part.mesh.vertices, api[name].vertices)
        np.testing.assert_array_equal(part.mesh.faces, api[name].faces)


@pytest.mark.parametrize(
    "style, inlay, dips, expected",
    [
        ("relief", False, None, True),
        ("relief", False, shapely.box(0, 0, 1, 1), False),  # an interlaced relief has more heights
        ("deboss", True, None, False),
        ("pierced", False, None, False),
    ],
)
def test_only_a_plain_relief_is_cut_from_its_fused_body(style, inlay, dips, expected):
    assert splits_fused(resolve_stack("fdm-0.4mm", style), False, inlay, dips) is expected
    assert splits_fused(resolve_stack("fdm-0.4mm", style), True, inlay, dips) is False


def test_relief_parts_keeps_the_base_a_plain_slab():
    """The base is meshed on its own: it does not carry the pattern's triangles (the 3MF stays small)."""
    region, outline = _region([(20, 15, 6)])
    (fused,) = checked_parts(region, outline, STACK, single=True).values()
    parts = relief_parts(fused, STACK)
    assert len(parts["base"].faces) < len(parts["pattern"].faces) / 2


def test_a_piece_that_cannot_be_triangulated_is_refused_by_name_after_moved_lines(monkeypatch):
    shifts = []

    def broken(kind, r, o, stack, shift=0, **kwargs):
        shifts.append(shift)
        exc = FabricationError("cannot triangulate the region near (1, 2) mm: GEOS stops there")
        exc.points = np.array([[1.0, 2.0]])
        raise exc

    monkeypatch.setattr(solid_parts, "_body_arrays", broken)
    region, outline = _region([(10, 10, 3)])
    with pytest.raises(
        FabricationError,
        match=r"^the body mesh could not be made: cannot triangulate the region "
        r"near \(1, 2\) mm: GEOS stops there; nothing was written$",
    ) as info:
        checked_parts(region, outline, STACK, single=True)
    assert shifts[:3] == [0, 1, 2]  # every cut of lines tried before the refusal
    assert info.value.points.tolist() == [[1.0, 2.0]]
