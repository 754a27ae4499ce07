"""`fabtiles batch`: samples plus deliberately broken designs, in parallel processes."""

import subprocess
import sys
from pathlib import Path

SAMPLES = Path(__file__).resolve().parents[2] / "samples"

BROKEN = {
    "bad-n.toml": ('[motif]\nn = 2\nradii = [1, 2]\n[tile]\noutline = "square"\nsize = 50\n',
                   "[motif] n must be an integer >= 3"),
    "typo.toml": ('[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsise = 50\n',
                  "unknown key 'sise' in [tile]"),
    "not-toml.toml": ("[motif\n", "not valid TOML"),
    "frame.toml": ('[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsize = 20\nframe = 15\n',
                   "too small for frame 15 mm"),
}


def run_batch(*args):
    return subprocess.run([sys.executable, "-m", "fabtiles", "batch", *map(str, args)],
                          capture_output=True, text=True, timeout=600)


def test_batch_builds_good_designs_and_reports_broken_ones(tmp_path):
    broken = []
    for name, (text, _) in BROKEN.items():
        (tmp_path / name).write_text(text)
        broken.append(tmp_path / name)
    samples = sorted(SAMPLES.glob("*.toml"))
    out = tmp_path / "out"
    proc = run_batch(*samples, *broken, "-o", out, "--jobs", "2", "--format", "svg", "--format", "dxf")
    assert proc.returncode == 2
    for name, (_, message) in BROKEN.items():
        line = [ln for ln in proc.stderr.splitlines() if ln.startswith(f"FAILED {tmp_path / name}")]
        assert line and message in line[0], proc.stderr
    assert f"{len(samples)} of {len(samples) + len(broken)} designs built, {len(broken)} failed" in proc.stdout
    written = sorted(p.name for p in out.iterdir())
    assert written == sorted(f"{s.stem}.{fmt}" for s in samples for fmt in ("dxf", "svg"))
    assert "building" not in proc.stderr  # no progress bar when piped


def test_batch_all_good_exits_0(tmp_path):
    proc = run_batch(SAMPLES / "rosette.toml", "-o", tmp_path, "--format", "svg")
    assert proc.returncode == 0, proc.stderr
    assert "1 of 1 designs built" in proc.stdout and (tmp_path / "rosette.svg").exists()


def test_batch_refuses_clashing_names(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "rosette.toml").write_text((SAMPLES / "rosette.toml").read_text())
    proc = run_batch(SAMPLES / "rosette.toml", tmp_path / "a" / "rosette.toml", "-o", tmp_path / "out")
    assert proc.returncode == 2 and "two designs would write the same files" in proc.stderr
    assert not (tmp_path / "out").exists()


def test_batch_prints_one_line_per_design_and_the_findings_with_verbose(tmp_path):
    args = (SAMPLES / "table3-3.toml", SAMPLES / "rosette.toml", "-o", tmp_path, "--format", "dxf", "--format", "svg",
            "--format", "stl", "--set", "output.fill_small_holes=false", "--jobs", "1")
    proc = run_batch(*args)
    assert proc.returncode == 0, proc.stderr
    # one line per design: its files and each machine's findings, once whatever the formats
    assert proc.stdout.splitlines() == [
        f"ok     {SAMPLES / 'table3-3.toml'}: 3 files, laser 1 warning, printer 1 warning",
        f"ok     {SAMPLES / 'rosette.toml'}: 3 files, laser 1 warning, printer 0",
        "2 of 2 designs built"]
    proc = run_batch(*args, "-v")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    head = lines.index(f"ok     {SAMPLES / 'table3-3.toml'}: 3 files, laser 1 warning, printer 1 warning")
    assert lines[head + 1].startswith("         - laser laser-3mm-plywood: small_hole: ")
    assert lines[head + 2].startswith("         - printer fdm-0.4mm: small_hole: ")
    assert lines[head + 3].startswith("ok     ")
    assert sum("small_hole" in line for line in lines) == 3  # each finding once, not once per format


def test_batch_bad_set_names_the_option(tmp_path):
    proc = run_batch(SAMPLES / "rosette.toml", "-o", tmp_path, "--set", "tile.stroke=-1")
    assert proc.returncode == 2
    assert f"FAILED {SAMPLES / 'rosette.toml'}: --set tile.stroke=-1: [tile] stroke must be" in proc.stderr
