"""The web app's nest (issue 34): POST /api/nest, its zip, and the 422 answers naming the body's field."""

from __future__ import annotations

import io
import re
import zipfile

import ezdxf
import pytest
import shapely
from asgi_client import TestClient

from fabtiles.machines.limits import WEB_LIMITS, Limits
from fabtiles.web.app import create_app
from fabtiles.web.routes.nest import KEPT, NestError, nest_files, read_body

SQUARE = "preset=table3-1&width=40&radius=8&frame=3"
CIRCLE = "preset=table3-3&outline=circle&width=40&radius=8&frame=3"
BODY = {
    "designs": [{"query": SQUARE, "count": 3}, {"query": CIRCLE, "count": 2}],
    "sheet": [120, 80],
    "rotate": "90",
    "time_s": 1,
    "format": "dxf",
}


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


@pytest.fixture(scope="module")
def answer(client):
    res = client.post("/api/nest", json=BODY)
    assert res.status_code == 200, res.text
    return res.json()


def _parts_of(svg: str) -> list[str]:
    return re.findall(r'class="part" data-part="([^"]+)"', svg)


def test_a_nest_of_two_designs_draws_every_part_once(answer):
    drawn = [p for s in answer["sheets"] for p in _parts_of(s["svg"])]
    assert sorted(drawn) == ["table3-1"] * 3 + ["table3-3"] * 2
    assert answer["parts"] == 5 and answer["sheet_mm"] == [120, 80] and answer["rotate"] == "90"
    assert answer["gap_mm"] == pytest.approx(1.15, abs=1e-9)  # the plywood's kerf + 1 mm
    for s in answer["sheets"]:
        assert 0 < s["material_use"] <= 1
        assert sum(s["parts"].values()) == s["count"] == len(_parts_of(s["svg"]))
        assert 'viewBox="0 0 120 80"' in s["svg"]


def test_the_zip_holds_one_dxf_per_sheet_that_ezdxf_reads(client, answer, tmp_path):
    res = client.get(answer["download"])
    assert res.status_code == 200 and res.headers["content-type"] == "application/zip"
    with zipfile.ZipFile(io.BytesIO(res.content)) as zf:
        names = zf.namelist()
        assert names == answer["files"] == [f"nest-sheet-{k + 1}.dxf" for k in range(len(answer["sheets"]))]
        zf.extractall(tmp_path)
    for name in names:
        doc = ezdxf.readfile(tmp_path / name)
        for e in doc.modelspace().query("LWPOLYLINE"):  # every cut path on its sheet (the kerf's 0.075 mm inside)
            xs, ys = zip(*((p[0], p[1]) for p in e.get_points()), strict=True)
            assert min(xs) >= -1e-6 and max(xs) <= 120 + 1e-6 and min(ys) >= -1e-6 and max(ys) <= 80 + 1e-6


def test_the_pictures_parts_are_inside_the_sheet_and_apart(answer):
    for s in answer["sheets"]:
        outlines = []
        for d in re.findall(r'class="part" data-part="[^"]+" d="([^"]+)"', s["svg"]):
            for ring in d.strip("MZ").split("ZM"):
                pts = [tuple(map(float, p.split())) for p in ring.split("L")]
                outlines.append(shapely.Polygon(pts))
        for k, a in enumerate(outlines):
            x0, y0, x1, y1 = a.bounds
            assert x0 >= -1e-3 and y0 >= -1e-3 and x1 <= 120 + 1e-3 and y1 <= 80 + 1e-3
            for b in outlines[k + 1 :]:
                assert a.distance(b) >= 1.15 - 2e-3  # the picture's coordinates are rounded to 1 um


def test_the_zip_of_a_body_at_once_and_in_svg(client):
    res = client.post("/api/nest.zip", json={**BODY, "designs": [{"query": SQUARE, "count": 2}], "format": "svg"})
    assert res.status_code == 200 and res.headers["content-type"] == "application/zip"
    with zipfile.ZipFile(io.BytesIO(res.content)) as zf:
        assert zf.namelist() == ["nest-sheet-1.svg"]
        assert zf.read("nest-sheet-1.svg").startswith(b"<?xml")


def test_a_nest_no_longer_kept_is_404(client):
    res = client.get("/api/nest/0123456789abcdef.zip")
    assert res.status_code == 404 and "press Nest again" in res.json()["error"]
    assert KEPT >= 1


def test_two_edited_designs_of_one_name_stay_apart():
    asked = read_body(
        {
            "designs": [
                {"query": "n=8&radii=1,2&packing=none&width=30"},
                {"query": "n=6&radii=1,2&packing=none&width=30"},
            ]
        },
        limits=WEB_LIMITS,
    )
    assert [d.name for d, _ in asked["designs"]] == ["custom", "custom-2"]
    assert asked["time_s"] == pytest.approx(3.0) and asked["sheet_mm"] is None and asked["rotations"] == "90"


@pytest.mark.parametrize(
    "change, field, match",
    [
        (
            {"designs": [{"query": SQUARE, "count": 0}]},
            "designs[0].count",
            r"designs\[0\]\.count must be a whole number >= 1, got 0",
        ),
        ({"designs": [{"query": SQUARE, "count": 1.5}]}, "designs[0].count", r"got 1\.5"),
        (
            {"designs": [{"query": SQUARE}, {"query": SQUARE + "&stroke=0"}]},
            "designs[1].stroke",
            r"design 2: stroke must be",
        ),
        ({"designs": [{"query": "preset=nope"}]}, "designs[0].preset", r"design 1: .*preset"),
        ({"designs": []}, "designs", r"at least one design"),
        ({"designs": ["preset=table3-1"]}, "designs[0]", r"designs\[0\] must be"),
        ({"designs": [{"query": SQUARE, "count": 61}]}, "designs", r"61 parts, more than the limit of 60"),
        ({"rotate": "45"}, "rotate", r"rotate must be one of: none, 180, 90, free, got '45'"),
        ({"format": "stl"}, "format", r"format must be one of: dxf, svg, lbrn2, got 'stl'"),
        ({"time_s": 0}, "time_s", r"time_s must be > 0 and at most 10 s here, got 0"),
        ({"time_s": 11}, "time_s", r"at most 10 s here, got 11"),
        ({"time_s": "fast"}, "time_s", r"time_s must be a finite number, got 'fast'"),
        ({"sheet": [120]}, "sheet", r"sheet must be \[width, height\]"),
        ({"sheet": [0, 80]}, "sheet", r"each > 0"),
        ({"gap_mm": 0.05}, "gap_mm", r"gap_mm must be >= the cut's width \(0\.15 mm"),
        ({"sheet": [30, 30]}, "sheet", r"does not fit on the 30 x 30 mm sheet"),
        ({"sheet": [5000, 80]}, "sheet", r"larger than the .* bed"),
        ({"speed": 3}, "speed", r"'speed' is not a nest field"),
    ],
)
def test_bad_input_is_422_naming_the_field(client, change, field, match):
    body = {**BODY, **change}
    res = client.post("/api/nest", json=body)
    assert res.status_code == 422
    assert res.json()["field"] == field
    assert re.search(match, res.json()["error"])
    with pytest.raises(NestError, match=match):
        nest_files(body, limits=WEB_LIMITS)


def test_a_body_not_json_or_not_an_object_is_422(client):
    res = client.post("/api/nest", content=b"designs", headers={"Content-Type": "application/json"})
    assert res.status_code == 422 and res.json()["field"] == "designs"
    assert "the body must be JSON" in res.json()["error"]
    res = client.post("/api/nest.zip", json=[1, 2])
    assert res.status_code == 422 and res.json()["field"] == "designs"
    with pytest.raises(NestError, match=r"must be a JSON object .* got list"):
        read_body([1, 2], limits=WEB_LIMITS)


def test_a_design_over_the_segment_limit_names_the_designs():
    small = Limits(max_segments=3_000, max_size_mm=1200, max_nest_parts=60, max_nest_time_s=10)
    with pytest.raises(NestError, match=r"the nest of 40 tiles would hold about") as info:
        nest_files({**BODY, "designs": [{"query": SQUARE, "count": 40}]}, limits=small)
    assert info.value.field == "designs"
