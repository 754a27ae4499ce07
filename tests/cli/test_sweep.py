"""``fabtiles sweep``: every variant's files, the contact sheet and the CSV; failures skipped."""

from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest
from test_build import SMALL, run

from fabtiles.designs.design_file import design_from_text


@pytest.fixture
def design(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL, encoding="utf-8")
    return path


def test_sweep_writes_every_variant_the_sheet_and_the_csv(design, tmp_path):
    out = tmp_path / "sweep"
    res = run(
        "sweep",
        design,
        "--vary",
        "packing.radius=6:10:3",
        "--vary",
        "tile.stroke=1.2,20",
        "--format",
        "svg",
        "--format",
        "dxf",
        "-o",
        out,
        "--jobs",
        "1",
    )
    assert res.exit_code == 2, res.output  # the stroke of 20 mm is wider than every radius
    built = [f"small-{k:03d}" for k in (1, 3, 5)]
    failed = [f"small-{k:03d}" for k in (2, 4, 6)]
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted(
        ["index.csv", "index.html"] + [f"{n}{ext}" for n in built for ext in (".svg", ".dxf", ".preview.svg")]
    )
    assert "3 of 6 variants built, 3 failed" in res.output
    assert all(f"FAILED {n} (" in res.output for n in failed)
    assert "ok     small-001 (packing.radius=6, tile.stroke=1.2): wrote 2 files" in res.output
    assert re.search(
        r"FAILED small-002 \(packing\.radius=6, tile\.stroke=20\): .*tile\.stroke=20: \[tile\] "
        r"stroke must be > 0 and <= 6 mm",
        res.output,
    )
    # the variant's files are the variant's design, built as `fabtiles build` would
    want = design_from_text(SMALL, name="small", overrides=["packing.radius=8", "tile.stroke=1.2"])
    assert want.packing.radius == 8
    other = tmp_path / "one"
    assert (
        run(
            "build",
            design,
            "-o",
            other,
            "--format",
            "svg",
            "--set",
            "packing.radius=8",
            "--set",
            "tile.stroke=1.2",
            "--set",
            'output.name="small-003"',
        ).exit_code
        == 0
    )
    assert (out / "small-003.svg").read_bytes() == (other / "small-003.svg").read_bytes()

    rows = list(csv.DictReader((out / "index.csv").open()))
    assert [r["variant"] for r in rows] == [f"small-{k:03d}" for k in range(1, 7)]
    assert [r["status"] for r in rows] == ["ok", "failed"] * 3
    assert [r["packing.radius"] for r in rows] == ["6", "6", "8", "8", "10", "10"]
    assert rows[0]["files"] == "small-001.svg small-001.dxf"
    assert "stroke must be > 0 and <= 6 mm" in rows[1]["details"] and rows[1]["files"] == ""

    page = (out / "index.html").read_text()
    for n in built:
        assert f'<img src="{n}.preview.svg"' in page and f'href="{n}.dxf"' in page
    assert page.count('<figure class="ok"') == 3 and page.count('<figure class="failed"') == 3
    assert "<b>tile.stroke</b> = 20" in page and "3 of 6 variants built, 3 failed" in page
    assert (out / "small-001.preview.svg").read_text().startswith("<?xml")


def test_sweep_lists_findings_in_the_sheet(tmp_path):
    sample = Path(__file__).resolve().parents[2] / "samples" / "table3-3.toml"
    out = tmp_path / "s"
    res = run(
        "sweep", sample, "--vary", "output.fill_small_holes=true,false", "--format", "dxf", "-o", out, "--jobs", "1"
    )
    assert res.exit_code == 0, res.output
    rows = list(csv.DictReader((out / "index.csv").open()))
    assert [r["findings"] for r in rows] == ["0", "1"] and "small_hole" in rows[1]["details"]
    page = (out / "index.html").read_text()
    assert "laser laser-3mm-plywood: small_hole:" in page and "no findings" in page


def test_the_contact_sheet_shows_each_variants_cut_job_and_filament(design, tmp_path):
    out = tmp_path / "s"
    res = run(
        "sweep", design, "--vary", "packing.radius=6,8", "--format", "dxf", "--format", "stl", "-o", out, "--jobs", "1"
    )
    assert res.exit_code == 0, res.output
    rows = {r["variant"]: r for r in csv.DictReader((out / "index.csv").open())}
    page = (out / "index.html").read_text()
    for name, row in rows.items():
        card = page[page.index(f'<figure class="ok" id="{name}">') :]
        card = card[: card.index("</figure>")]
        # under the picture: the laser job (its time) and the filament, as the CSV has them
        job = re.search(r"<div>laser job: ([\d.]+) m of cut, ([\d,]+) pierces?, about (\d+) min</div>", card)
        assert job, card
        assert float(job[1]) == pytest.approx(float(row["cut_length_mm"]) / 1000, abs=0.051)
        assert int(job[2].replace(",", "")) == int(row["pierces"])
        assert int(job[3]) == pytest.approx(float(row["laser_time_s"]) / 60, abs=1)
        filament = re.search(r"<div>print: ([\d.]+) g of filament, ([\d.]+) m</div>", card)
        assert filament, card
        assert float(filament[1]) == pytest.approx(float(row["filament_g"]), rel=0.01)
        assert float(filament[2]) == pytest.approx(float(row["filament_m"]), rel=0.01)
        assert card.index('class="figures"') > card.index("<img")


@pytest.mark.parametrize(
    "args, match",
    [
        (["--vary", "tile.sise=1,2"], r"unknown key 'sise' in \[tile\]; did you mean 'size'\?"),
        (["--vary", "packing.radius=8:1:0"], r"n in a:b:n must be a whole number >= 1, got 0"),
        (["--vary", "packing.radius=x:1:3"], r"a:b:n needs numbers a and b"),
        (
            ["--vary", "packing.radius=1:2:101", "--vary", "tile.stroke=0.1:0.2:100"],
            r"the sweep has 10,100 variants, more than 10,000; pass --yes",
        ),
        ([], r"a sweep needs at least one --vary"),
        (["--vary", "tile.stroke=1", "--set", "tile.frame=99"], r"--set tile\.frame=99: \[tile\] tile size"),
    ],
)
def test_bad_sweeps_exit_2_and_write_nothing(design, tmp_path, args, match):
    out = tmp_path / "out"
    res = run("sweep", design, "-o", out, *args)
    assert res.exit_code == 2
    assert res.output.startswith("fabtiles: error: ") and re.search(match, res.output), res.output
    assert not out.exists()


def test_progress_bar_on_a_terminal(design, tmp_path):
    """On a terminal (stderr a pty) the sweep shows a progress bar; piped, it does not (see above)."""
    import os
    import pty
    import subprocess
    import sys

    master, slave = pty.openpty()
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "fabtiles",
            "sweep",
            str(design),
            "--vary",
            "tile.frame=2,3",
            "--format",
            "svg",
            "-o",
            str(tmp_path / "out"),
            "--jobs",
            "1",
        ],
        stdout=subprocess.PIPE,
        stderr=slave,
        timeout=300,
    )
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # the pty is drained and closed
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    shown = b"".join(chunks).decode(errors="replace")
    assert proc.returncode == 0, shown
    assert "sweeping" in shown and "50%" in shown and "100%" in shown, shown


def test_jobs_and_scheduler_together_is_a_usage_error(design, tmp_path):
    res = run(
        "sweep",
        design,
        "--vary",
        "tile.frame=1,2",
        "-o",
        tmp_path / "o",
        "--jobs",
        "2",
        "--scheduler",
        "tcp://127.0.0.1:1",
    )
    assert res.exit_code == 2 and "--jobs sets local processes" in res.output
    assert not (tmp_path / "o").exists()


def test_a_variant_with_formats_refused_is_built_in_part_exit_3(design, tmp_path, monkeypatch):
    from dataclasses import replace

    from fabtiles import FabricationError
    from fabtiles.export.formats import FORMATS

    def refuse(model, options):
        raise FabricationError("the mesh is bad")

    monkeypatch.setitem(FORMATS, "stl", replace(FORMATS["stl"], write=refuse))  # --jobs 1: built in this process
    out = tmp_path / "sweep"
    res = run(
        "sweep", design, "--vary", "packing.radius=6,8", "--format", "svg", "--format", "stl", "-o", out, "--jobs", "1"
    )
    assert res.exit_code == 3, res.output
    assert (
        "part   small-001 (packing.radius=6): wrote 1 file; laser: 1 finding (filled_pattern 465); "
        "printer: nothing found; refused stl" in res.output
    )
    assert "refused stl: the mesh is bad" in res.output
    assert "0 of 2 variants built, 2 in part (formats refused)" in res.output
    rows = list(csv.DictReader((out / "index.csv").open()))
    assert [r["status"] for r in rows] == ["part", "part"] and rows[0]["details"].startswith("refused stl: the mesh")
    assert "<li>refused stl: the mesh is bad</li>" in (out / "index.html").read_text()
    assert not (out / "small-001.stl").exists() and (out / "small-001.svg").exists()
