"""Shared test settings.

Hypothesis runs with a fixed seed and bounded examples by default (CI); a longer
run by hand: ``FABTILES_HYPOTHESIS=long python -m pytest tests/making/test_pipeline_properties.py``
(random seed, and ten times the examples: see ``hypothesis_scale.py``).
"""

import os

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    derandomize=True,
    database=None,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
settings.register_profile(
    "long",
    max_examples=500,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
settings.load_profile(os.environ.get("FABTILES_HYPOTHESIS", "ci"))


COLLECTED = pytest.StashKey[set]()


FIRST = (
    "tests/solid/test_brep_designs.py",
    "tests/test_docs.py",
    "tests/export/test_stl.py",
    "tests/making/test_reproducible.py",
    "tests/export/test_mosaic_files.py",
)
"""The files that hold the longest tests, run first: the README's command runs the tests on two
workers (``--dist worksteal``), and a long test started last keeps one waiting for the other."""


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    if config.args_source == pytest.Config.ArgsSource.TESTPATHS and not (
        config.getoption("ignore") or config.getoption("ignore_glob") or config.getoption("deselect")
    ):
        config.stash[COLLECTED] = {item.nodeid.split("::", 1)[0] for item in items}
    # a stable sort: each file's tests stay together and in order (its module fixtures made once)
    rank = {name: k for k, name in enumerate(FIRST)}
    items.sort(key=lambda item: rank.get(item.nodeid.split("::", 1)[0], len(FIRST)))


@pytest.fixture(scope="session")
def collected_files(pytestconfig) -> set | None:
    """The files of which this run collected a test, before ``-k`` or ``-m`` deselect any, when the run
    is the README's command (no paths given); else None. tests/test_collection.py checks them instead
    of collecting the whole suite again in a process of its own."""
    return pytestconfig.stash.get(COLLECTED, None)
