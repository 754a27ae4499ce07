import re
import subprocess
import sys

import pytest
from click.testing import CliRunner

from fabtiles.cli.main import cli


def run(*args):
    return CliRunner().invoke(cli, list(args))


def test_star_from_preset_writes_svg(tmp_path):
    out = tmp_path / "star.svg"
    res = run("star", "--preset", "table1-part1", "-o", str(out))
    assert res.exit_code == 0, res.output
    text = out.read_text()
    assert text.startswith("<?xml") and 'width="100mm"' in text
    d = re.search(r' d="([^"]*)"', text).group(1)
    assert d.count("M") == 32 and d.count("L") == 32  # one move + line per segment
    assert "wrote" in res.output and "32 segments" in res.output


def test_star_from_parameters(tmp_path):
    out = tmp_path / "star.svg"
    res = run("star", "--n", "8", "--radii", "51,70,172", "-o", str(out))
    assert res.exit_code == 0, res.output
    preset = tmp_path / "preset.svg"
    run("star", "--preset", "table1-part1", "-o", str(preset))
    assert out.read_text() == preset.read_text()


def test_preset_with_override(tmp_path):
    out = tmp_path / "s.svg"
    res = run("star", "--preset", "table3-3", "--alpha", "10", "-o", str(out))
    assert res.exit_code == 0, res.output
    assert "alpha=10" in out.read_text()


def test_presets_lists_every_preset():
    res = run("presets")
    assert res.exit_code == 0
    for name in ("table1-part1", "table1-part2", "table2-left", "table2-right", "table3-1", "table3-2", "table3-3"):
        assert name in res.output
    assert "n=9   radii=93,225" in res.output


@pytest.mark.parametrize(
    "args, message",
    [
        (["--n", "2", "--radii", "1,2"], "n must be an integer >= 3 and <= 120, got 2"),
        (["--n", "8", "--radii", "1"], "radii must hold 2 to 24 numbers, got 1"),
        (["--n", "8", "--radii", "1,-2"], "radii[1] must be a finite number > 0, got -2"),
        (["--n", "8", "--radii", "1,nan"], "radii[1] must be a finite number > 0, got nan"),
        (["--n", "8", "--radii", "1,2", "--special", "3"], "special must be an integer >= 2 and <= 2, got 3"),
        (["--preset", "nope"], "preset 'nope' is unknown (presets: table1-part1"),
    ],
)
def test_bad_input_is_one_line_exit_2_no_file(tmp_path, args, message):
    out = tmp_path / "star.svg"
    res = CliRunner().invoke(cli, ["star", *args, "-o", str(out)])
    assert res.exit_code == 2
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], res.output
    assert "Traceback" not in res.output
    assert list(tmp_path.iterdir()) == []


def test_usage_errors_exit_2(tmp_path):
    res = run("star", "-o", str(tmp_path / "s.svg"))
    assert res.exit_code == 2 and "give --preset, or --n and --radii" in res.output
    res = run("star", "--n", "8", "--radii", "1,x", "-o", str(tmp_path / "s.svg"))
    assert res.exit_code == 2 and "comma-separated numbers" in res.output
    res = run("star", "--preset", "table3-3", "-o", str(tmp_path / "s.png"))
    assert res.exit_code == 2 and "must be an .svg file" in res.output
    assert list(tmp_path.iterdir()) == []


def test_real_process_exit_status_and_stderr(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "fabtiles", "star", "--n", "1", "--radii", "1,2", "-o", str(tmp_path / "s.svg")],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert proc.stderr.strip() == "fabtiles: error: n must be an integer >= 3 and <= 120, got 1"
    assert not (tmp_path / "s.svg").exists()


def test_help_does_not_import_heavy_libraries():
    code = (
        "import sys\n"
        "from fabtiles.cli.main import main\n"
        "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('shapely', 'build123d', 'OCP', 'trimesh', 'manifold3d', 'ezdxf', 'fastapi', 'uvicorn')"
        " if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "HEAVY []" in proc.stdout, proc.stdout
