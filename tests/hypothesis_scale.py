"""How many hypothesis examples a property test runs.

Tests that set their own ``max_examples`` (the costly pipeline properties use few)
override the loaded profile, so the long run by hand scales them here instead:
``FABTILES_HYPOTHESIS=long`` runs ten times as many examples of every property.
"""

import os

SCALE = 10 if os.environ.get("FABTILES_HYPOTHESIS") == "long" else 1


def examples(n: int) -> int:
    """``n`` examples in CI, ``10 * n`` in the long run."""
    return n * SCALE
