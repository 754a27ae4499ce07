"""Small designs the tests build, as design-file text: one function instead of the same lines in every module.

>>> print(design_toml(preset="table3-1", radius=8, output={"formats": ["svg"]}))
<BLANKLINE>
[motif]
preset = "table3-1"
[packing]
radius = 8
[tile]
outline = "square"
size = 60
frame = 3
stroke = 1.0
[output]
formats = ["svg"]
<BLANKLINE>
"""

from __future__ import annotations

import json
import re
from pathlib import Path


def _value(v) -> str:
    """A TOML value: JSON's spelling of strings, numbers, booleans and lists is TOML's too."""
    return repr(v) if isinstance(v, float) else json.dumps(v)


def _table(name: str, keys: dict) -> list[str]:
    return [f"[{name}]"] + [f"{k} = {_value(v)}" for k, v in keys.items() if v is not None]


def design_toml(
    *,
    preset: str = "table3-3",
    radius: float = 10,
    outline: str | None = "square",
    size=60,
    frame: float | None = 3,
    stroke: float | None = 1.0,
    packing: dict | None = None,
    tile: dict | None = None,
    output: dict | None = None,
    colour: dict | None = None,
) -> str:
    """A design file's text: the preset motif in a hex packing of ``radius`` on a tile.

    ``None`` leaves a key out (the design's default); ``packing``, ``tile``, ``output`` and
    ``colour`` add keys to those tables (an empty ``output``/``colour`` writes no table).
    """
    lines = [""] + _table("motif", {"preset": preset})
    lines += _table("packing", {"radius": radius, **(packing or {})})
    lines += _table("tile", {"outline": outline, "size": size, "frame": frame, "stroke": stroke, **(tile or {})})
    if output:
        lines += _table("output", output)
    if colour:
        lines += _table("colour", colour)
    return "\n".join(lines) + "\n"


def printed_only(path) -> bool:
    """Whether the design file at ``path`` is printed only (``[surface] shape = "cylinder"`` or ``"stamp"``): a
    roller, a shade or a clay stamp, made in the print formats and built by their own tests
    (tests/making/test_cylinder_build.py, test_stamp_build.py) rather than by the tests that make every flat
    sample's cutter files."""
    from pathlib import Path

    import tomllib

    shape = tomllib.loads(Path(path).read_text(encoding="utf-8")).get("surface", {}).get("shape", "flat")
    return shape != "flat"


def default_sigint() -> None:
    """A child process's Ctrl+C as in a terminal (``preexec_fn``): a shell's background job, such
    as a CI script started with ``&``, hands its children SIGINT ignored, and Python then never
    raises KeyboardInterrupt."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def assert_cli_refused(args, out, match: str) -> str:
    """``fabtiles ARGS`` run in process is refused as the CLI refuses bad input: exit 2, one line
    ``fabtiles: error: ...`` holding the regular expression ``match``, and nothing at ``out``. Returns
    the line."""
    from click.testing import CliRunner

    from fabtiles.cli.main import cli

    result = CliRunner().invoke(cli, [str(a) for a in args], catch_exceptions=False)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("fabtiles: error: ") and result.output.count("\n") == 1, result.output
    assert re.search(match, result.output), result.output
    assert not Path(out).exists()
    return result.output
