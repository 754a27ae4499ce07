"""The package's docstrings and comments say what and why: no measurements and no history.

Timings, sizes of files and the issues that led to the code belong in ``docs/speed.md``, the
benchmarks and the commit messages, where they carry the day they were measured; in the source
they go stale without anyone noticing.
"""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import pytest
from doc_pages import SETTING, TIME

ROOT = Path(__file__).resolve().parents[1]
SOURCES = sorted((ROOT / "fabtiles").rglob("*.py"))

ISSUE = re.compile(r"\bissues? #?\d+", re.IGNORECASE)
"""A reference to an issue of the project's tracker: ``issue 35``, ``issues 31``."""
SIZE = re.compile(r"(?<![\w.])\d[\d,]*(?:\.\d+)?\s?[kKMG]B\b")
"""A measured size: ``2.6 MB``, ``530 KB``."""
FSTRING = re.compile(r"[rRbBuU]*[fF]")
"""An f-string's prefix (before Python 3.12 an f-string is one STRING token)."""


def history_and_measurements(source: str) -> list[str]:
    """The docstrings and comments of ``source`` (Python) that name an issue or give a measured time
    or size (a time as the docs' prose check reads one: a bound such as ``within 10 s`` is a setting).
    f-strings are messages for users, not read here."""
    found = []
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type not in (tokenize.COMMENT, tokenize.STRING) or FSTRING.match(tok.string):
            continue
        flat = " ".join(tok.string.split())
        times = [
            m.group(0)
            for m in TIME.finditer(flat)
            if not SETTING.search(flat[max(0, m.start() - 25) : m.start()])
            and not SETTING.search(flat[m.end() : m.end() + 10])
        ]
        for what in [*ISSUE.findall(flat), *times, *SIZE.findall(flat)]:
            found.append(f"line {tok.start[0]}: {what!r}")
    return found


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_issue_numbers_timings_or_sizes_in_the_source(path):
    assert history_and_measurements(path.read_text(encoding="utf-8")) == []


def test_the_check_finds_an_issue_a_timing_and_a_size_but_not_a_setting():
    source = (
        "def f(timeout_s=10):\n"
        '    """The pieces of issue 35, joined in 0.2 s (2.6 MB).\n\n'
        '    Gives up within 10 s; a budget of 5 s."""\n'
        "    # a loop took 45 ms\n"
        '    return f"waited 1 s for {timeout_s} s"\n'
    )
    assert history_and_measurements(source) == [
        "line 2: 'issue 35'",
        "line 2: '0.2 s'",
        "line 2: '2.6 MB'",
        "line 5: '45 ms'",
    ]
