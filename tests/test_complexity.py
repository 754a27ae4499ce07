"""The package's cyclomatic complexity (radon), held to the anchors' level (docs/architecture.md).

No function or method above :data:`MOST`, and at most :data:`PER_KLOC` of them above
:data:`BRANCHY` per 1,000 lines of the package (radon's LOC: every line). Split a function along the seams
its steps already mark rather than raise these.
"""

from pathlib import Path

import pytest

radon_complexity = pytest.importorskip("radon.complexity")
radon_visitors = pytest.importorskip("radon.visitors")

PACKAGE = Path(__file__).resolve().parents[1] / "fabtiles"
MOST = 30
BRANCHY = 12
PER_KLOC = 1.3


def _measure():
    blocks, loc = [], 0
    for path in sorted(PACKAGE.rglob("*.py")):
        code = path.read_text()
        # radon's LOC is every line of the file (its raw analysis, which tokenizes the file to sort
        # the lines into kinds, adds them back up to that count)
        loc += len(code.splitlines())
        for b in radon_complexity.cc_visit(code):
            if not isinstance(b, radon_visitors.Class):  # a class's methods are listed themselves too
                blocks.append((b.complexity, f"{path.relative_to(PACKAGE.parent)}:{b.lineno} {b.name}"))
    return blocks, loc


@pytest.fixture(scope="module")
def measured():
    return _measure()


def test_no_function_is_above_the_most_complexity(measured):
    blocks, _ = measured
    over = sorted(b for b in blocks if b[0] > MOST)
    assert not over, f"functions above complexity {MOST}: {over}"


def test_few_functions_are_branchy_per_thousand_lines(measured):
    blocks, loc = measured
    branchy = sorted((b for b in blocks if b[0] > BRANCHY), reverse=True)
    assert loc > 10_000 and len(blocks) > 500  # the whole package was measured
    assert len(branchy) / (loc / 1000) <= PER_KLOC, (
        f"{len(branchy)} functions above {BRANCHY} in {loc} lines: {branchy[:10]}"
    )
