"""The build pipeline (fabtiles/making.py): limits for every front end, staging, outcomes."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from designs import design_toml

from fabtiles import DesignError, LimitError, ParameterError
from fabtiles import making as pipeline
from fabtiles.designs.design_file import design_from_text, load_design
from fabtiles.machines.limits import CLI_LIMITS, Limits, estimate_segments

SMALL = design_toml(preset="table3-1", radius=8, outline=None)
ROOT = Path(__file__).resolve().parents[2]


def small(**kw):
    return design_from_text(SMALL, name="small", **kw)


def test_step_limit_applies_to_every_front_end(tmp_path):
    """The STEP limit the web app applies holds for `fabtiles build` too, before any geometry."""
    big = load_design(
        ROOT / "samples" / "table3-3.toml",
        overrides=["tile.size=[400,400]", "packing.radius=6", "tile.stroke=0.5", "tile.frame=3"],
    )
    tile = pipeline.prepare_tile(big)
    count = estimate_segments(tile.pattern, tile.width_mm, tile.height_mm)
    assert CLI_LIMITS.max_step_segments < count < CLI_LIMITS.max_segments
    with pytest.raises(LimitError, match=r"STEP export of about [\d,]+ segments is over the limit of 60,000"):
        pipeline.build_design(big, tmp_path / "out", ["svg", "step"])
    assert not (tmp_path / "out").exists()
    from click.testing import CliRunner

    from fabtiles.cli.main import cli

    res = CliRunner().invoke(
        cli,
        [
            "build",
            str(ROOT / "samples" / "table3-3.toml"),
            "-o",
            str(tmp_path / "c"),
            "--format",
            "step",
            "--set",
            "tile.size=[400,400]",
            "--set",
            "packing.radius=6",
            "--set",
            "tile.stroke=0.5",
            "--set",
            "tile.frame=3",
        ],
    )
    assert res.exit_code == 2 and "STEP export of about" in res.output
    assert not (tmp_path / "c").exists()


def test_limits_are_the_callers(tmp_path):
    with pytest.raises(LimitError, match="larger than the limit of 50 mm on a side"):
        pipeline.build_design(small(), tmp_path, ["svg"], limits=Limits(max_size_mm=50))
    with pytest.raises(LimitError, match="more than the limit of 10"):
        pipeline.build_design(small(), tmp_path, ["svg"], limits=Limits(max_segments=10))
    assert list(tmp_path.iterdir()) == []


def test_build_bytes_is_the_file_build_design_writes(tmp_path):
    download = pipeline.build_bytes(small(), "svg", limits=CLI_LIMITS)
    result = pipeline.build_design(small(), tmp_path, ["svg"])
    assert Path(result.paths[0]).read_bytes() == download.data
    assert download.report.stats == result.reports[0].stats
    assert (download.media_type, download.file_name) == ("image/svg+xml", "small.svg")


def test_file_name_needs_one_format(tmp_path):
    with pytest.raises(ParameterError, match=r"file_name 'x.svg' names one file, but 2 formats are asked for"):
        pipeline.build_design(small(), tmp_path, ["svg", "dxf"], file_name="x.svg")


def test_sheet_skips_print_formats(tmp_path):
    result = pipeline.build_design(small(), tmp_path, ["svg", "stl"], copies=2)
    assert result.skipped == ("stl",) and [Path(p).name for p in result.paths] == ["small-sheet.svg"]


def test_stale_staging_of_dead_processes_is_removed(tmp_path):
    import os
    import socket

    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    host = socket.gethostname()
    dead = tmp_path / f"{pipeline.STAGING_PREFIX}{host}-{proc.pid}-abc123"
    live = tmp_path / f"{pipeline.STAGING_PREFIX}{host}-{os.getpid()}-def456"
    other = tmp_path / f"{pipeline.STAGING_PREFIX}elsewhere-{proc.pid}-ghi789"
    for d in (dead, live, other):
        d.mkdir()
        (d / "half.stl").write_text("partial")
    assert pipeline.remove_stale_staging(tmp_path) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([live.name, other.name])
    assert pipeline.remove_stale_staging(tmp_path / "missing") == 0


def test_run_job_turns_failures_into_outcomes(tmp_path):
    ok = pipeline.run_job("good", small, str(tmp_path), ("svg",))
    assert ok.ok and ok.message.startswith("wrote 1 file") and ok.paths == [str(tmp_path / "small.svg")]

    def bad():
        raise DesignError("broken.toml: [tile] frame too big")

    failed = pipeline.run_job("bad", bad, str(tmp_path), ())
    assert not failed.ok and failed.message == "broken.toml: [tile] frame too big"

    def bug():
        raise KeyError("oops")

    crashed = pipeline.run_job("bug", bug, str(tmp_path), ())
    assert not crashed.ok and crashed.message.startswith("internal error (a bug, please report):")
    assert "KeyError: 'oops'" in crashed.message


def test_outcome_lists_findings(tmp_path):
    design = load_design(ROOT / "samples" / "table3-3.toml", overrides=["output.fill_small_holes=false"])
    out = pipeline.run_job("t", lambda: design, str(tmp_path), ("dxf",))
    assert out.ok and out.counts == [("laser", 1)]
    assert re.fullmatch(r"wrote 1 file; laser: 1 finding \(small_hole [\d,]+\)", out.message), out.message
    assert len(out.findings) == 1 and out.findings[0].startswith("laser laser-3mm-plywood: small_hole: ")


@pytest.mark.parametrize(
    "overrides, match",
    [
        (["tile.stroke=50"], r"^--set tile\.stroke=50: \[tile\] stroke must be > 0 and <= 8 mm"),
        (
            ["tile.frame=1", "tile.size=[80,40]"],
            r"^--set tile\.size=\[80,40\]: \[tile\] size of a square is one number",
        ),
        (["motif.n=2"], r"^--set motif\.n=2: \[motif\] n must be an integer >= 3"),
        (["tile.sise=3"], r"^--set tile\.sise=3: unknown key 'sise' in \[tile\]"),
    ],
)
def test_a_bad_set_value_names_the_set_option(overrides, match):
    with pytest.raises(DesignError, match=match):
        small(overrides=overrides, source="small.toml")


def test_a_bad_file_is_still_named_with_overrides():
    with pytest.raises(DesignError, match=r"^small\.toml: \[tile\] stroke must be"):
        design_from_text(SMALL.replace("stroke = 1.0", "stroke = 50"), source="small.toml", overrides=["tile.frame=2"])


def test_a_disk_error_is_a_fabtiles_error_and_leaves_nothing(tmp_path, monkeypatch):
    import fabtiles.core.files
    from fabtiles import FabtilesError

    def full(path, data):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(fabtiles.core.files, "atomic_write", full)
    with pytest.raises(FabtilesError, match=r"cannot write into '.*out': No space left on device"):
        pipeline.build_design(small(), tmp_path / "out", ["svg"])
    assert list(tmp_path.iterdir()) == []


def test_output_folder_that_is_a_file(tmp_path):
    from fabtiles import FabtilesError

    (tmp_path / "f").write_text("keep")
    with pytest.raises(FabtilesError, match=r"output folder '.*f' exists and is not a folder"):
        pipeline.build_design(small(), tmp_path / "f", ["svg"])
    with pytest.raises(FabtilesError, match=r"cannot create output folder '.*sub'"):
        pipeline.build_design(small(), tmp_path / "f" / "sub", ["svg"])
    assert (tmp_path / "f").read_text() == "keep"


def test_preview_is_staged_with_the_files(tmp_path):
    result = pipeline.build_design(small(), tmp_path, ["svg"], preview=True)
    assert Path(result.preview) == tmp_path / "small.preview.svg"
    assert result.preview not in result.paths and Path(result.preview).read_text().startswith("<?xml")


def test_inlay_key_gives_the_deboss_3mf_its_inlay_part(tmp_path):
    """[output] inlay = true: the 3MF holds the plate and the inlay; the STL of the same build is one body."""
    from fabtiles.export.threemf import read_3mf

    design = small(overrides=["output.print_style=deboss", "output.inlay=true"])
    assert design.output.inlay is True
    pipeline.build_design(design, tmp_path, formats=["3mf", "stl"])
    assert list(read_3mf(tmp_path / "small.3mf")) == ["plate", "inlay"]
    assert (tmp_path / "small.stl").stat().st_size > 0


def test_inlay_needs_the_deboss_style(tmp_path):
    design = small(overrides=["output.inlay=true"])
    with pytest.raises(ParameterError, match="inlay=True needs style='deboss'"):
        pipeline.build_design(design, tmp_path, formats=["3mf"])
    assert list(tmp_path.iterdir()) == []


def test_inlay_must_be_a_flag():
    with pytest.raises(DesignError, match=r"inlay must be true or false"):
        small(overrides=["output.inlay=1"])


# --------------------------------------------------------------------------- each format on its own


def _refusing(fmt, message, monkeypatch):
    """Make format ``fmt``'s writer refuse with ``message``, as a writer's own check does."""
    from dataclasses import replace

    from fabtiles import FabricationError
    from fabtiles.export.formats import FORMATS

    def write(model, options):
        raise FabricationError(message)

    monkeypatch.setitem(FORMATS, fmt, replace(FORMATS[fmt], write=write))


def test_a_format_its_writer_refuses_is_named_and_the_others_are_written(tmp_path, monkeypatch):
    _refusing("step", "the STEP solid is bad", monkeypatch)
    result = pipeline.build_design(small(), tmp_path, ["svg", "step", "stl"])
    assert [Path(p).name for p in result.paths] == ["small.svg", "small.stl"]
    assert [r.format for r in result.reports] == ["svg", "stl"]
    (refused,) = result.refused
    assert (refused.format, refused.path, refused.reason) == (
        "step",
        str(tmp_path / "small.step"),
        "the STEP solid is bad",
    )
    assert refused.line() == f"refused {tmp_path / 'small.step'} (step): the STEP solid is bad"
    # the refused file is absent, and nothing else (no staging folder) is left
    assert sorted(p.name for p in tmp_path.iterdir()) == ["small.stl", "small.svg"]
    # the printer's model was made, its findings reported once, though one of its formats was refused
    assert [label.split()[0] for label, _ in result.models] == ["laser", "printer"]


@pytest.mark.parametrize("machine,written", [("laser", ["small.stl"]), ("printer", ["small.dxf", "small.svg"])])
def test_a_strict_machine_refuses_its_own_formats_only(tmp_path, machine, written):
    """A strict profile's findings (and a bed too small) refuse that machine's formats; the other
    machine's are written, its findings reported."""
    profile = tmp_path / "strict.toml"
    profile.write_text(f'kind = "{machine}"\n[{machine}]\nstrict = true\nbed_mm = [10, 10]\n')
    design = small(overrides=[f'output.{machine}_profile="{profile}"'])
    out = tmp_path / "out"
    result = pipeline.build_design(design, out, ["svg", "dxf", "stl"])
    assert sorted(p.name for p in out.iterdir()) == written
    refused = {r.format for r in result.refused}
    assert refused == {"svg", "dxf", "stl"} - {Path(p).suffix[1:] for p in written}
    assert len({r.reason for r in result.refused}) == 1  # one model, one reason
    assert "10 x 10 mm bed" in result.refused[0].reason
    assert [label.split()[0] for label, _ in result.models] == ["printer" if machine == "laser" else "laser"]


def test_a_build_whose_every_format_is_refused_raises_and_writes_nothing(tmp_path, monkeypatch):
    from fabtiles import FabricationError, ProfileError

    # one reason (one model's, or one format): that error itself, its type kept
    profile = tmp_path / "strict.toml"
    profile.write_text('kind = "printer"\n[printer]\nstrict = true\nbed_mm = [10, 10]\n')
    # not made as pieces: the tile larger than the bed is the strict profile's finding
    design = small(overrides=[f'output.printer_profile="{profile}"', "output.pieces=false"])
    with pytest.raises(FabricationError, match="profile is strict"):
        pipeline.build_design(design, tmp_path / "a", ["stl", "3mf"])
    assert not (tmp_path / "a").exists()

    def coarse(model, options):
        raise ProfileError("tolerance_mm is too coarse", param="tolerance_mm")

    from dataclasses import replace

    from fabtiles.export.formats import FORMATS

    monkeypatch.setitem(FORMATS, "step", replace(FORMATS["step"], write=coarse))
    with pytest.raises(ProfileError, match="too coarse") as err:
        pipeline.build_design(small(), tmp_path / "b", ["step"])
    assert err.value.param == "tolerance_mm"
    # several reasons: each format named with its own
    _refusing("svg", "the SVG is bad", monkeypatch)
    with pytest.raises(
        FabricationError, match=r"^formats refused: svg: the SVG is bad; step: tolerance_mm is too coarse$"
    ):
        pipeline.build_design(small(), tmp_path / "c", ["svg", "step"])
    assert not (tmp_path / "b").exists() and not (tmp_path / "c").exists()


def test_a_refused_format_leaves_the_file_of_an_earlier_build_as_it_was(tmp_path, monkeypatch):
    (tmp_path / "small.stl").write_text("old")
    _refusing("stl", "the mesh is bad", monkeypatch)
    result = pipeline.build_design(small(), tmp_path, ["svg", "stl"])
    assert (tmp_path / "small.stl").read_text() == "old"
    assert result.earlier == [str(tmp_path / "small.stl")] and result.refused[0].path == result.earlier[0]


def test_an_outcome_names_the_formats_refused(tmp_path, monkeypatch):
    _refusing("stl", "the mesh is bad", monkeypatch)
    out = pipeline.run_job("t", small, str(tmp_path), ("svg", "stl"))
    assert (
        out.ok
        and out.message == "wrote 1 file; laser: nothing found; printer: nothing found; refused stl"
        and out.refused == ["stl: the mesh is bad"]
    )


def test_the_deep_check_fails_on_a_refused_print_file(tmp_path, monkeypatch):
    from fabtiles import FabricationError
    from fabtiles.making.deep import read_back

    _refusing("stl", "the mesh is bad", monkeypatch)
    design = small(overrides=['output.formats=["stl", "3mf"]'])
    with pytest.raises(FabricationError, match=r"^the mesh is bad$"):
        read_back(design)
