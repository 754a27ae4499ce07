"""`fabtiles batch`: samples plus deliberately broken designs, in parallel processes."""

import re
import subprocess
import sys
from pathlib import Path

SAMPLES = Path(__file__).resolve().parents[2] / "samples"

BROKEN = {
    "bad-n.toml": (
        '[motif]\nn = 2\nradii = [1, 2]\n[tile]\noutline = "square"\nsize = 50\n',
        "[motif] n must be an integer >= 3",
    ),
    "typo.toml": (
        '[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsise = 50\n',
        "unknown key 'sise' in [tile]",
    ),
    "not-toml.toml": ("[motif\n", "not valid TOML"),
    "frame.toml": (
        '[motif]\npreset = "table3-3"\n[tile]\noutline = "square"\nsize = 20\nframe = 15\n',
        "too small for frame 15 mm",
    ),
}


def run_batch(*args):
    return subprocess.run(
        [sys.executable, "-m", "fabtiles", "batch", *map(str, args)], capture_output=True, text=True, timeout=600
    )


def test_batch_builds_good_designs_and_reports_broken_ones(tmp_path):
    broken = []
    for name, (text, _) in BROKEN.items():
        (tmp_path / name).write_text(text)
        broken.append(tmp_path / name)
    # three samples of one file a format beside the broken designs (every sample's DXF is built by
    # tests/export/test_sample_goldens.py, and every format of each by tests/making/test_reproducible.py)
    samples = [SAMPLES / f"{name}.toml" for name in ("girih-decagon-bowtie", "rosette", "table3-3")]
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
    args = (
        SAMPLES / "table3-3.toml",
        SAMPLES / "rosette.toml",
        "-o",
        tmp_path,
        "--format",
        "dxf",
        "--format",
        "svg",
        "--format",
        "stl",
        "--set",
        "output.fill_small_holes=false",
        "--jobs",
        "1",
    )
    proc = run_batch(*args)
    assert proc.returncode == 0, proc.stderr
    # one line per design: its files and each machine's findings by code and count, once whatever the formats
    lines = proc.stdout.splitlines()
    assert len(lines) == 3 and lines[2] == "2 of 2 designs built"
    assert re.fullmatch(
        rf"ok     {re.escape(str(SAMPLES / 'table3-3.toml'))}: wrote 3 files; "
        r"laser: 1 finding \(small_hole [\d,]+\); printer: 1 finding \(small_hole [\d,]+\)",
        lines[0],
    )
    assert re.fullmatch(
        rf"ok     {re.escape(str(SAMPLES / 'rosette.toml'))}: wrote 3 files; "
        r"laser: 1 finding \(small_hole [\d,]+\); printer: nothing found",
        lines[1],
    )
    proc = run_batch(*args, "-v")  # the same files again: replaced, as fabtiles build says
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith(f"ok     {SAMPLES / 'table3-3.toml'}: "))
    assert lines[head].split(": ", 1)[1].startswith("replaced 3 files; laser: 1 finding (small_hole ")
    assert lines[head + 1].startswith("         - laser laser-3mm-plywood: small_hole: ")
    assert lines[head + 2].startswith("         - printer fdm-0.4mm: small_hole: ")
    assert lines[head + 3].startswith("ok     ")
    assert sum("small_hole" in line for line in lines if line.startswith("         - ")) == 3  # once, not per format


def test_batch_bad_set_names_the_option(tmp_path):
    proc = run_batch(SAMPLES / "rosette.toml", "-o", tmp_path, "--set", "tile.stroke=-1")
    assert proc.returncode == 2
    assert f"FAILED {SAMPLES / 'rosette.toml'}: --set tile.stroke=-1: [tile] stroke must be" in proc.stderr


def test_a_design_with_formats_refused_is_built_in_part_exit_3(tmp_path):
    """A strict printer whose bed the tile does not fit refuses the print formats; the laser's are
    written, the design is "part", each refused format on a line with its reason, exit status 3."""
    from designs import design_toml

    profile = tmp_path / "strict.toml"
    profile.write_text('kind = "printer"\n[printer]\nstrict = true\nbed_mm = [10, 10]\n')
    tile, good = tmp_path / "tile.toml", tmp_path / "good.toml"
    # not made as pieces: the tile larger than the bed is the strict printer's finding
    tile.write_text(design_toml(preset="table3-1", radius=8, output={"printer_profile": str(profile), "pieces": False}))
    good.write_text(design_toml(preset="table3-1", radius=8))
    proc = run_batch(tile, good, "-o", tmp_path / "out", "--format", "svg", "--format", "stl")
    assert proc.returncode == 3, proc.stderr
    assert f"part   {tile}: wrote 1 file; laser: nothing found; refused stl" in proc.stdout
    assert "refused stl: fabrication checks failed" in proc.stderr and "10 x 10 mm bed" in proc.stderr
    assert "1 of 2 designs built, 1 in part (formats refused)" in proc.stdout
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["good.stl", "good.svg", "tile.svg"]
