"""Shared test settings.

Hypothesis runs with a fixed seed and bounded examples by default (CI); a longer
run by hand: ``FABTILES_HYPOTHESIS=long python -m pytest tests/making/test_pipeline_properties.py``
(random seed, and ten times the examples: see ``hypothesis_scale.py``).
"""

import os

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
