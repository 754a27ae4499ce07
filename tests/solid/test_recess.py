"""A recess sunk into a print's bottom face (a printed piece's number): watertight, its volume gone, in STEP too."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
import trimesh
from mesh_helpers import B, D, T

from fabtiles import FabricationError
from fabtiles.export.step import check_step_file, step_bytes
from fabtiles.geometry.stack import Recess
from fabtiles.solid.print_model import print_model

PLATE = shapely.box(0, 0, 40, 40).difference(shapely.box(10, 10, 30, 30))
OUTLINE = shapely.box(0, 0, 40, 40)
# a ring (an island inside, as a digit's loop) and a bar, under the plate's solid corners
RECESS = Recess(shapely.box(2, 2, 8, 8).difference(shapely.box(4, 4, 6, 6)).union(shapely.box(32, 32, 38, 36)), 0.4)
FLAT = {
    "relief": OUTLINE.area * B + PLATE.area * 1.2,
    "deboss": OUTLINE.area * B - PLATE.area * D,
    "mosaic": OUTLINE.area * (B + 1.2),
    "pierced": PLATE.area * T,
}


def recess_for(style):
    # a pierced print's bottom is its bands: the recess under the band's corner
    return RECESS if style != "pierced" else Recess(shapely.box(2, 2, 8, 8), 0.4)


@pytest.fixture(scope="module", params=sorted(FLAT))
def recessed(request):
    style = request.param
    return style, print_model(PLATE, OUTLINE, profile="fdm-0.4mm", style=style, recess=recess_for(style))


def test_the_recess_leaves_a_watertight_body_less_its_volume(recessed):
    style, model = recessed
    mesh = trimesh.Trimesh(model.fused.vertices, model.fused.faces)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.body_count == 1
    assert mesh.volume == pytest.approx(FLAT[style] - recess_for(style).volume, rel=1e-6)
    # the recess's roof: flat at its depth, facing down, as large as the recess
    flat = np.all(np.isclose(mesh.vertices[mesh.faces][:, :, 2], 0.4), axis=1)
    assert (mesh.face_normals[flat][:, 2] < 0).all()
    assert mesh.area_faces[flat].sum() == pytest.approx(recess_for(style).region.area)


def test_a_relief_parts_keep_the_recess_in_the_base(recessed):
    style, model = recessed
    total = sum(p.mesh.mesh_volume_mm3 for p in model.parts.values())
    assert total == pytest.approx(FLAT[style] - recess_for(style).volume, rel=1e-6)


def test_step_holds_the_recess_and_occt_reads_it_back(recessed, tmp_path):
    style, model = recessed
    path = tmp_path / f"{style}.step"
    path.write_bytes(step_bytes(model))
    assert check_step_file(path, volume=model.brep[1], parts=1) == pytest.approx(
        FLAT[style] - recess_for(style).volume, rel=1e-6
    )


def test_a_recess_reaching_the_edge_is_refused():
    with pytest.raises(FabricationError, match=r"reaches within 0\.5 mm of the edge of its solid bottom"):
        print_model(PLATE, OUTLINE, profile="fdm-0.4mm", recess=Recess(shapely.box(0.2, 2, 5, 5), 0.4))


@pytest.mark.parametrize("depth", [0.0, 2.0])
def test_a_recess_deeper_than_the_plate_is_refused(depth):
    with pytest.raises(FabricationError, match=rf"shallower than the 2 mm of material over it, got {depth:g} mm"):
        print_model(PLATE, OUTLINE, profile="fdm-0.4mm", recess=Recess(shapely.box(2, 2, 5, 5), depth))


def test_a_bottom_that_does_not_tile_with_its_recess_is_an_error_not_a_file(monkeypatch):
    from fabtiles.solid import _mesh_build

    monkeypatch.setattr(_mesh_build, "recessed_bottom", lambda *args: None)
    model = print_model(PLATE, OUTLINE, profile="fdm-0.4mm", style="pierced", recess=recess_for("pierced"))
    with pytest.raises(FabricationError, match=r"the bottom with its recess \(the piece's number\) could not be"):
        model.fused  # noqa: B018 - the mesh is made on first use
