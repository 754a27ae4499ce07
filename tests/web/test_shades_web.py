"""The web app's shaded engraving: ``shaded`` and ``shade_<letter>`` reach the laser files, a bad one is named."""

import re
import xml.etree.ElementTree as ET

import pytest
from asgi_client import TestClient

from fabtiles.web.app import create_app
from fabtiles.web.params import design_from_query

SMALL = "width=40&radius=10&frame=2&colour_by=shape&laser_mode=engrave"


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_the_query_says_what_the_design_file_says():
    design = design_from_query({"colour_by": "shape", "shaded": "B D", "shade_B": "power_pct:40, passes:2"})
    assert design["colour"] == {"by": "shape", "shaded": "B D", "shades": {"B": {"power_pct": 40.0, "passes": 2}}}
    assert "shades" not in design_from_query({"colour_by": "shape", "shade_B": ""})["colour"]


def test_the_project_download_has_a_layer_per_shaded_class(client):
    r = client.get(f"/api/export/lbrn2?{SMALL}&shaded=all&shade_B=power_pct:40")
    assert r.status_code == 200, r.text
    cuts = {
        c.find("name").get("Value"): float(c.find("maxPower").get("Value"))
        for c in ET.fromstring(r.content).iter("CutSetting")
    }
    assert cuts["SHADE_B"] == 40.0 and {"SHADE_A", "SHADE_C", "SHADE_D"} <= set(cuts)


@pytest.mark.parametrize(
    "query, field, message",
    [
        (
            "shade_B=power_pct:x",
            "shade_B",
            "shade_B must be settings like power_pct:40,speed_mm_s:200, got 'power_pct:x'",
        ),
        ("shaded=all&shade_B=power_pct:140", "shade_B", "power_pct must be a percentage > 0 and <= 100, got 140.0"),
        ("shaded=Q", "shaded", "shaded names face class 'Q'"),
    ],
)
def test_a_bad_shade_names_its_parameter(client, query, field, message):
    r = client.get(f"/api/export/lbrn2?{SMALL}&{query}")
    assert r.status_code == 422, r.text
    assert message in r.json()["error"], r.json()
    assert r.json()["field"] == field, r.json()


def test_the_preview_draws_the_shaded_classes_burnt_on_wood(client):
    from fabtiles.geometry.shades import WOOD, burn_colour
    from fabtiles.machines.profiles import load_profile

    fill = load_profile("laser-3mm-plywood").layers.engrave
    darkest = fill.shade_range_pct[1]
    svg = client.get(
        f"/api/preview.svg?{SMALL.replace('laser_mode=engrave', 'laser_mode=pierced')}&shaded=B&shade_B=power_pct:10"
    ).text
    # the shaded class burnt at its power, the bands bare wood, the classes cut out left open
    assert re.search(rf'class="face-B"[^>]*fill="{burn_colour(10.0, darkest)}"', svg), svg[:2000]
    assert f'fill="{WOOD}"' in svg and 'class="face-A"' not in svg
    engraved = client.get(f"/api/preview.svg?{SMALL}&shaded=all").text
    assert f'fill="{burn_colour(fill.power_pct, darkest)}"' in engraved  # the engrave mode's bands, engraved
    assert all(f'class="face-{k}"' in engraved for k in "ABCD")
