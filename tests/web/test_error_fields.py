"""The web app names the field of a bad input from the error's key, never from its message."""

from __future__ import annotations

import pytest
from asgi_client import TestClient
from test_api import BAD

from fabtiles.web import app as app_mod


@pytest.fixture(scope="module")
def client():
    return TestClient(app_mod.create_app())


def test_no_field_is_read_from_a_message():
    """The app has no code reading error messages: the field comes from the error's ``key``."""
    from fabtiles.web import building

    assert not hasattr(app_mod, "_field_of") and not hasattr(building, "_field_of")


@pytest.mark.parametrize("query, field, message", BAD)
def test_field_comes_from_the_parameter(client, query, field, message):
    """Every bad query names its field."""
    r = client.get(f"/api/checks?{query}")
    assert r.status_code == 422 and message in r.json()["error"], r.text
    assert r.json()["field"] == field, r.json()


def test_segment_limit_names_the_radius():
    from fabtiles.machines.limits import Limits

    client = TestClient(app_mod.create_app(limits=Limits(max_segments=100)))
    r = client.get("/api/checks?width=100&radius=5")
    assert r.status_code == 422 and r.json()["field"] == "radius", r.json()
