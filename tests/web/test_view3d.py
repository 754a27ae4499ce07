"""The 3D view's endpoint: the 3MF's parts as GLB, checked like the STL, limited like it."""

import io
import json

import numpy as np
import pytest
import trimesh
from asgi_client import TestClient, asgi_get

from fabtiles.machines.limits import Limits
from fabtiles.web.app import create_app

SMALL = "width=40&frame=3&radius=8"


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def _parts(data: bytes) -> dict:
    scene = trimesh.load(io.BytesIO(data), file_type="glb", process=False)
    return {name: scene.geometry[name] for name in scene.geometry}


def _stl_volume(client, query) -> float:
    r = client.get(f"/api/export/stl?{query}")
    assert r.status_code == 200
    return trimesh.load(io.BytesIO(r.content), file_type="stl").volume


@pytest.mark.parametrize(
    "style, names", [("relief", ["base", "pattern"]), ("pierced", ["pattern"]), ("deboss", ["plate"])]
)
def test_parts_watertight_and_as_the_stl(client, style, names):
    q = f"{SMALL}&print_style={style}"
    r = client.get(f"/api/view.glb?{q}")
    assert r.status_code == 200 and r.headers["content-type"] == "model/gltf-binary"
    assert r.content[:4] == b"glTF"
    parts = _parts(r.content)
    assert sorted(parts) == sorted(names)
    for mesh in parts.values():
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    header = json.loads(r.headers["X-Fabtiles-Parts"])
    assert {n: p["triangles"] for n, p in header.items()} == {n: len(m.faces) for n, m in parts.items()}
    total = sum(m.volume for m in parts.values())
    assert total == pytest.approx(_stl_volume(client, q), rel=1e-3)  # the STL fuses the same parts
    assert r.headers["X-Fabtiles-View"] == "the whole 40 x 40 mm tile"


def test_each_part_has_its_colour(client):
    parts = _parts(client.get(f"/api/view.glb?{SMALL}").content)
    colours = {n: tuple(np.round(m.visual.material.baseColorFactor[:3] / 255, 2)) for n, m in parts.items()}
    from fabtiles.solid.print_model import PART_MATERIALS

    assert colours == {n: tuple(round(c, 2) for c in PART_MATERIALS[n].colour) for n in parts}
    assert colours["base"] != colours["pattern"]


def test_deboss_inlay_and_interlaced_dips(client):
    parts = _parts(client.get(f"/api/view.glb?{SMALL}&print_style=deboss&inlay=true").content)
    assert sorted(parts) == ["inlay", "plate"] and all(m.is_watertight for m in parts.values())
    flat = _parts(client.get(f"/api/view.glb?{SMALL}&stroke=2").content)["pattern"]
    woven = _parts(client.get(f"/api/view.glb?{SMALL}&stroke=2&interlace=true").content)["pattern"]
    assert woven.is_watertight
    # the dips are there: the woven pattern is lower somewhere, so it holds less material
    tops = np.unique(np.round(woven.vertices[:, 2], 4))
    assert len(tops) > len(np.unique(np.round(flat.vertices[:, 2], 4)))
    assert woven.volume < flat.volume


def test_default_tile_is_small_enough(client):
    r = client.get("/api/view.glb")
    assert r.status_code == 200 and len(r.content) < 1_000_000  # 530 KB measured
    assert r.headers["X-Fabtiles-View"] == "the whole 150 x 150 mm tile"


def test_a_big_tile_shows_its_centre(client):
    r = client.get("/api/view.glb?outline=rectangle&width=600&height=400")
    assert r.status_code == 200
    view = r.headers["X-Fabtiles-View"]
    assert view.startswith("the centre ") and "of the 600 x 400 mm tile, a lighter preview" in view
    w, h = (float(v) for v in view.split()[2:5:2])
    parts = _parts(r.content)
    lo = np.min([m.bounds[0] for m in parts.values()], axis=0)
    hi = np.max([m.bounds[1] for m in parts.values()], axis=0)
    assert hi[0] - lo[0] == pytest.approx(w, abs=0.6) and hi[1] - lo[1] == pytest.approx(h, abs=0.6)
    assert w < 600 and h < 400 and w / h == pytest.approx(1.5, rel=0.01)
    assert all(m.is_watertight for m in parts.values())
    assert len(r.content) < 4_000_000


def test_print_view_window_figures():
    from fabtiles.designs.design_file import design_from_dict
    from fabtiles.machines.limits import WEB_LIMITS
    from fabtiles.making import VIEW_SEGMENTS, print_view

    def design(size):
        return design_from_dict(
            {
                "motif": {"preset": "table3-3"},
                "packing": {"radius": 15},
                "tile": {"outline": "square", "size": size, "frame": 5},
            },
            name="t",
        )

    _, whole = print_view(design(150), limits=WEB_LIMITS)  # 4,032 segments
    assert "window_mm" not in whole.stats and whole.stats["view"] == "the whole 150 x 150 mm tile"
    _, big = print_view(design(300), limits=WEB_LIMITS)  # 13,752 segments: its centre
    x0, y0, x1, y1 = big.stats["window_mm"]
    assert x1 - x0 == pytest.approx(y1 - y0) and (x0 + x1) / 2 == pytest.approx(150)
    assert x1 - x0 == pytest.approx(300 * (VIEW_SEGMENTS / 13_752) ** 0.5)
    assert big.stats["view"].startswith("the centre 229 x 229 mm of the 300 x 300 mm tile")
    _, smaller = print_view(design(300), limits=WEB_LIMITS, max_segments=VIEW_SEGMENTS // 4)
    assert smaller.stats["triangles"] < big.stats["triangles"] / 2


def test_bad_parameter_is_422_with_its_field(client):
    r = client.get(f"/api/view.glb?{SMALL}&stroke=0")
    assert r.status_code == 422 and r.json()["field"] == "stroke" and "stroke" in r.json()["error"]
    r = client.get(f"/api/view.glb?{SMALL}&print_style=wavy")
    assert r.status_code == 422 and r.json()["field"] == "print_style"
    assert "relief" in r.json()["error"]  # the valid choices are listed


def test_limits_refuse_before_any_work(monkeypatch):
    from fabtiles.solid import parts

    def never(*a, **k):
        raise AssertionError("a mesh was built for a refused tile")

    monkeypatch.setattr(parts, "checked_parts", never)
    small = TestClient(create_app(limits=Limits(max_segments=1000, max_size_mm=100)))
    r = small.get("/api/view.glb?width=150")
    assert r.status_code == 422 and "larger than the limit of 100 mm" in r.json()["error"]
    assert r.json()["field"] == "width"
    r = small.get("/api/view.glb?width=90&radius=4")
    assert r.status_code == 422 and "more than the limit of 1,000" in r.json()["error"]
    assert r.json()["field"] == "radius"


def _never(what):
    def never(*a, **k):
        raise AssertionError(f"{what} for a client that has gone")

    return never


def test_a_request_whose_client_has_gone_is_not_built(monkeypatch):
    """The browser dropped the view (a newer design came) before the server took it up: no design is read,
    no model built."""
    from fabtiles import making
    from fabtiles.web.routes import tile

    monkeypatch.setattr(tile, "build", _never("the design was read"))
    monkeypatch.setattr(making, "print_view", _never("the view was built"))

    async def gone():
        return {"type": "http.disconnect"}

    sent = asgi_get(create_app(), f"/api/view.glb?{SMALL}", gone)
    assert sent[0]["type"] == "http.response.start" and sent[0]["status"] == tile.CLIENT_GONE == 499


def test_the_build_stops_between_its_stages_when_the_client_goes(monkeypatch):
    """The client goes while the print's region is made: its model and meshes are not."""
    import threading

    import anyio

    from fabtiles.making.models import Models
    from fabtiles.web.routes import tile

    left = threading.Event()
    region = Models.print_region

    def region_then_leave(self):
        out = region.fget(self)
        left.set()  # the browser closes the request while the region is made
        return out

    monkeypatch.setattr(Models, "print_region", property(region_then_leave))
    monkeypatch.setattr(Models, "_make_print", _never("the print model was made"))
    messages = iter([{"type": "http.request", "body": b"", "more_body": False}])

    async def receive():
        message = next(messages, None)
        if message is not None:
            return message
        if left.is_set():
            return {"type": "http.disconnect"}
        await anyio.sleep_forever()  # the client is there: nothing to read (is_disconnected does not wait)

    sent = asgi_get(create_app(), f"/api/view.glb?{SMALL}", receive)
    assert left.is_set() and sent[0]["status"] == tile.CLIENT_GONE


def test_print_view_checks_before_each_stage(monkeypatch):
    """``checkpoint`` is called before the region, the model and the meshes; its exception stops the view."""
    from fabtiles.designs.design_file import design_from_dict
    from fabtiles.export import glb
    from fabtiles.machines.limits import WEB_LIMITS
    from fabtiles.making import print_view

    design = design_from_dict(
        {"motif": {"preset": "table3-3"}, "packing": {"radius": 8}, "tile": {"size": 40, "frame": 3}}, name="t"
    )
    calls = []
    data, _ = print_view(design, limits=WEB_LIMITS, checkpoint=lambda: calls.append(1))
    assert len(calls) == 3 and data[:4] == b"glTF"

    class Stop(Exception):
        pass

    def third():
        calls.append(1)
        if len(calls) == 3:
            raise Stop

    calls.clear()
    monkeypatch.setattr(glb, "model_glb_bytes", _never("the meshes were made"))
    with pytest.raises(Stop):
        print_view(design, limits=WEB_LIMITS, checkpoint=third)


def test_viewer_files_are_served_only_from_the_list(client):
    from fabtiles.web import viewer_files

    info = client.get("/api/viewer").json()
    assert info["three"] == viewer_files.VERSION and info["install"] == "fabtiles install-viewer"
    r = client.get("/static/vendor/three/package.json")
    assert r.status_code == 404 and "fabtiles install-viewer" in r.json()["error"]
    r = client.get("/static/vendor/three/../../app.py")
    assert r.status_code == 404
    if info["installed"]:
        r = client.get("/static/vendor/three/build/three.module.js")
        assert r.status_code == 200 and r.headers["content-type"].startswith("text/javascript")
        assert client.get("/static/vendor/three/LICENSE").text.startswith("The MIT License")


def test_page_loads_the_view_from_the_package(client):
    html = client.get("/").text
    assert '"three": "/static/vendor/three/build/three.module.js"' in html
    assert '<script type="module" src="/static/view3d.js">' in html
    assert 'src="http' not in html and 'href="http' not in html  # nothing from the internet: works offline
    js = client.get("/static/view3d.js").text
    assert "/api/view.glb" in js and "fabtiles install-viewer" in js
