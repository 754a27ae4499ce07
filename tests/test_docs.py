"""The manual cannot drift from the code: every key, command and option documented, every link alive."""

from __future__ import annotations

import re
from dataclasses import fields

import click
import doc_pages
import numpy as np
import pytest

from fabtiles.cli.main import cli
from fabtiles.designs import design_file as design
from fabtiles.machines import profiles as _profiles

ROOT = doc_pages.ROOT
PAGES = doc_pages.PAGES


def text_of(*names) -> str:
    return "\n".join((ROOT / "docs" / n).read_text(encoding="utf-8") for n in names)


def documented(key: str, text: str) -> bool:
    """``key`` appears as code (`key`) or as a TOML key (``key =``) in ``text``."""
    k = re.escape(key)
    return bool(re.search(rf"`{k}`|^\s*{k}\s*=|[{{,]\s*{k}\s*=|^\[{k}\]", text, re.M))


@pytest.mark.parametrize(
    "section,keys",
    [
        ("motif", design.MOTIF_KEYS),
        ("packing", design.PACKING_KEYS),
        ("tile", design.TILE_KEYS),
        ("output", design.OUTPUT_KEYS),
        ("surface", design.SURFACE_KEYS),
    ],
)
def test_every_design_key_is_in_design_files_md(section, keys):
    text = text_of("design-files.md")
    assert f"[{section}]" in text
    assert [k for k in keys if not documented(k, text)] == []


def profile_keys() -> list[str]:
    keys = ["kind", "description", "laser", "printer", "layers", "name", "color"]
    for cls in (_profiles.CutterProfile, _profiles.PrinterProfile, _profiles.LaserLayers):
        keys += [f.name for f in fields(cls) if f.name not in ("name", "description", "layers")]
    return list(dict.fromkeys(keys))


def test_every_profile_key_is_in_profiles_md():
    text = text_of("profiles.md")
    assert [k for k in profile_keys() if not documented(k, text)] == []


def commands(group, prefix=()):
    for name, cmd in sorted(group.commands.items()):
        yield (*prefix, name), cmd
        if hasattr(cmd, "commands"):
            yield from commands(cmd, (*prefix, name))


def test_every_cli_command_and_option_is_in_cli_md():
    text = text_of("cli.md")
    sections = dict(re.findall(r"^## `fabtiles ([a-z -]+)`\n(.*?)(?=^## |\Z)", text, re.M | re.S))
    missing = []
    for path, cmd in commands(cli):
        name = " ".join(path)
        if name not in sections:
            missing.append(name)
            continue
        for param in cmd.params:
            for opt in param.opts if isinstance(param, click.Option) else ():
                if opt != "--help" and f"`{opt}`" not in sections[name]:
                    missing.append(f"{name} {opt}")
    assert missing == []


LINK = re.compile(r"\]\(([^)\s]+)\)")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_relative_link_points_to_a_file(page):
    broken = []
    for target in LINK.findall(page.read_text(encoding="utf-8")):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        if not (page.parent / target.split("#")[0]).exists():
            broken.append(target)
    assert broken == []


def test_the_readme_is_a_landing_page():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme.encode()) <= 15_000
    ci = (ROOT / ".ci" / "run").read_text()
    test_command = ci.split("# --- the README's test command (keep the two in step) ---\n", 1)[1].strip()
    assert test_command in readme  # the README's test command is CI's
    assert "fabtiles build samples/table3-3.toml -o out" in readme


def test_the_card_size_in_laser_cutting_md_is_the_cards():
    """The calibration card's size, as the docs state it, is the bundled laser profiles' cards' (to the mm)."""
    from fabtiles.geometry.calibration import calibration_card

    m = re.search(r"The card \(about (\d+) x (\d+) mm for the bundled profiles", text_of("laser-cutting.md"))
    assert m, "laser-cutting.md no longer states the card's size"
    stated = np.array([float(m.group(1)), float(m.group(2))])
    for name in _profiles.bundled_profiles("laser"):
        profile = _profiles.load_profile(name)
        if profile.cutter.card:
            card = calibration_card(profile)
            assert np.abs(np.array([card.width_mm, card.height_mm]) - stated).max() <= 1.0, name


def test_design_files_md_example_names_every_output_key():
    """The example design of design-files.md shows every [output] key of the schema (the inlay ones too)."""
    from fabtiles.core import schema as _schema

    text = text_of("design-files.md")
    example = text[text.index("[output]") : text.index("```", text.index("[output]"))]
    keys = [k.name for k in _schema.KEYS if k.section == "output"]
    assert keys and [k for k in keys if not re.search(rf"^{k} = ", example, re.M)] == []


def test_a_copy_of_a_profile_comes_with_the_command_that_makes_it():
    """Wherever the manual says to write values into a copy of a profile, it gives `fabtiles profile copy`."""
    missing = []
    for page in PAGES:
        text = " ".join(page.read_text(encoding="utf-8").split())
        for m in re.finditer(r"copy of (the|a|your) profile", text, re.I):
            if "fabtiles profile copy" not in text[m.start() : m.end() + 200]:
                missing.append(f"{page.name}: {text[m.start() : m.end() + 60]}")
    assert missing == []
    assert "fabtiles profile copy laser-3mm-plywood my-laser.toml" in text_of("profiles.md")


# --- the docs run: every page's commands, shown outputs and snippets (tests/doc_pages.py) ---


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_the_page_runs_as_shown(page, tmp_path):
    """The page's commands run, in its order, in one fresh folder holding the samples; each exits as
    the page says; each output the page shows is what was printed (``...`` where abridged); its
    Python snippets run (doctests where they show values)."""
    run = doc_pages.run_page(page, doc_pages.fresh_folder(tmp_path))
    assert run.problems == [], "\n\n".join(run.problems)


def test_every_command_not_run_is_named_and_still_in_the_docs():
    """The commands the docs test does not run (they install, serve or need a cluster) are the ones
    `doc_pages.NOT_RUN` lists by name, and each entry still names a command of the docs."""
    commands = [c for page in PAGES for step in doc_pages.steps(page) for c, _ in step.commands]
    assert [start for start in doc_pages.NOT_RUN if not any(c.startswith(start) for c in commands)] == []
    snippets = [
        (page.name, block.strip().splitlines()[0])
        for page in PAGES
        for lang, block in doc_pages.BLOCK.findall(page.read_text(encoding="utf-8"))
        if lang == "python"
    ]
    assert [
        (name, start)
        for name, start in doc_pages.SNIPPETS_NOT_RUN
        if not any(name == n and first.startswith(start) for n, first in snippets)
    ] == []


def test_the_readme_tour_quotes_figures_to_check():
    """The README's tour is a snippet whose print lines quote figures (the runner checks them)."""
    tour = [s for s in doc_pages.steps(ROOT / "README.md") if s.kind == "python"]
    assert len(tour) == 1
    assert re.search(r'^print\(.*#.*"[^"]*\d[^"]*"', tour[0].code, re.M)


PLANTED = """# a page with planted mistakes

```sh
fabtiles presets --no-such-option
```

```sh
fabtiles calibrate --profile laser-3mm-plywood -o card.svg
```

```
wrote card.svg: test card 99 x 99 mm for laser profile laser-3mm-plywood (kerf 0.15 mm), 24 labelled features
```

```
$ fabtiles calibrate --profile laser-3mm-plywood -o card.dxf
wrote card.dxf: test card ... 24 labelled features
...
```

```sh
fabtiles check samples/table3-3.toml --set packing.radius=40 --set tile.size=60
```

```
samples/table3-3.toml: laser profile laser-3mm-plywood ...
...
ok: nothing found
```

```python
import fabtiles as ft
ft.Star(n=2, radii=(1, 2))
```

```python
>>> 1 + 1
3
```

```
a stray block
```
"""


def test_the_runner_finds_planted_mistakes(tmp_path):
    """A command that does not exist, an output line that differs, an output that goes on past the
    block shown, a status other than the page's, a snippet that raises, a doctest that fails and a
    stray block each fail; the abridged output that matches passes."""
    page = tmp_path / "planted.md"
    page.write_text(PLANTED, encoding="utf-8")
    folder = tmp_path / "run"
    folder.mkdir()
    problems = doc_pages.run_page(page, doc_pages.fresh_folder(folder)).problems
    text = "\n".join(problems)
    assert "`fabtiles presets --no-such-option` exited 2, not 0" in text
    assert "test card 99 x 99 mm" in text
    assert "card.dxf" not in text  # the abridged transcript matches
    assert "--set tile.size=60` exited 1, not 0" in text
    assert "the page shows a line that was not printed there: 'ok: nothing found'" in text
    assert "the snippet raised" in text
    assert "Expected:\n    3\nGot:\n    2" in text
    assert "a plain ``` block that is not a command's output" in text
    assert len(problems) == 7, text


@pytest.mark.parametrize(
    "command,args",
    [
        ("fabtiles presets", ["presets"]),
        ("fabtiles build samples/t.toml -o out   # a comment", ["build", "samples/t.toml", "-o", "out"]),
        (
            "fabtiles build t.toml --set output.laser_mode='\"inlay\"'",
            ["build", "t.toml", "--set", 'output.laser_mode="inlay"'],
        ),
        (
            'fabtiles check t.toml --set output.laser_profile="my laser.toml"',
            ["check", "t.toml", "--set", "output.laser_profile=my laser.toml"],
        ),
        ("fabtiles batch samples/*.toml -o out", None),  # a glob
        ("fabtiles build t.toml --set tile.size=[200,200]", None),  # a glob too: a file 'tile.size=2' matches it
        ("fabtiles sweep t.toml --vary packing.radius=10:20:5 -o sweep", None),  # a pool of processes
        ("fabtiles build t.toml -o $OUT", None),
        ('fabtiles build "$HOME/t.toml"', None),
        ("fabtiles check t.toml > log", None),
        ("fabtiles check t.toml | grep laser", None),
        ("fabtiles check t.toml && ls", None),
        ("fabtiles build ~/t.toml", None),
        ("fabtiles check 'a #b'", None),  # a '#' that is no comment
        ("HOME=/tmp fabtiles presets", None),
        ("python samples/custom_sizes.py out", None),
        ("grep '^T[0-9]' mosaic.gcode", None),
    ],
)
def test_only_a_plain_fabtiles_command_runs_in_process(command, args):
    assert doc_pages.in_process_args(command) == args


@pytest.mark.parametrize(
    "command",
    [
        "fabtiles presets --no-such-option",  # a usage error
        "fabtiles nest --help",  # laid out for the terminal's columns
        "fabtiles calibrate --profile laser-3mm-plywood -o card.svg",
        "fabtiles build samples/table3-3.toml -o out --set output.laser_mode=inlay --format svg",  # a note first
    ],
)
def test_a_command_run_in_process_prints_exits_and_writes_as_by_bash(command, tmp_path, monkeypatch):
    """What the CLI prints in this process (stdout and stderr in order), its status and its files are
    what ``bash -c`` gives in a folder of their own."""
    runs = []
    for name, args in (("bash", None), ("here", doc_pages.in_process_args(command))):
        folder = doc_pages.fresh_folder(tmp_path / name)
        monkeypatch.setattr(doc_pages, "in_process_args", lambda c, args=args: args)
        done = doc_pages.run_command(command, folder)
        files = {
            p.relative_to(folder): p.read_bytes()
            for p in folder.rglob("*")
            if p.is_file() and not {".shims", ".home", "samples"} & set(p.relative_to(folder).parts)
        }
        runs.append((done.returncode, done.stdout.replace(str(folder), "FOLDER"), files))
    assert runs[1][0] == runs[0][0] and runs[1][1] == runs[0][1] and runs[1][2] == runs[0][2]
    assert runs[1][1]


@pytest.mark.parametrize(
    "shown,printed,ok",
    [
        (["a", "b"], ["a", "b"], True),
        (["a"], ["a", "b"], False),  # output past the block
        (["a", "...", "d"], ["a", "b", "c", "d"], True),
        (["a", "...", "d"], ["a", "d"], True),  # ... stands for no line too
        (["a ... c"], ["a b c"], True),
        (["a ... c"], ["a b d"], False),
        (["a", "c"], ["a", "b", "c"], False),  # abridged without saying so
    ],
)
def test_the_output_match(shown, printed, ok):
    assert (doc_pages.mismatch(shown, printed) is None) == ok


INLINE = re.compile(r"`(fabtiles [a-z-][^`\n]*)`")


def prose_command_problems(name: str, text: str) -> list[str]:
    """What is wrong with the ``fabtiles ...`` spans of ``text``'s prose: a command or an option
    the CLI does not have."""
    wrong = []
    for command in INLINE.findall(doc_pages.BLOCK.sub("", text)):
        words = command.split()[1:]
        group, path = cli, []
        while words and hasattr(group, "commands") and words[0] in group.commands:
            group = group.commands[words[0]]
            path.append(words.pop(0))
        if not path and words and not words[0].startswith("-"):
            wrong.append(f"{name}: `{command}`: no command {words[0]!r}")
            continue
        opts = {o for p in group.params for o in getattr(p, "opts", ()) + getattr(p, "secondary_opts", ())}
        opts |= {"--help"}
        wrong += [
            f"{name}: `{command}`: no option {w.split('=')[0]!r}"
            for w in words
            if w.startswith("-") and w.split("=")[0] not in opts and w != "..."
        ]
    return wrong


def test_every_command_in_the_prose_names_a_command_and_its_options():
    """A ``fabtiles ...`` written in the prose (not run: many are patterns, ``NAME``) names a command
    that exists and only options that command has."""
    assert [w for page in PAGES for w in prose_command_problems(page.name, page.read_text(encoding="utf-8"))] == []


def test_the_prose_check_finds_a_missing_option_and_command():
    text = "The preview (`fabtiles build --preview`), `fabtiles frob x`, `fabtiles build -o out`."
    assert prose_command_problems("p.md", text) == [
        "p.md: `fabtiles build --preview`: no option '--preview'",
        "p.md: `fabtiles frob x`: no command 'frob'",
    ]


def test_the_readmes_speed_figures_are_the_benchmarks_or_say_when_they_were_measured():
    """The README's speeds are `benchmarks/results.json`'s (the 600 x 400 mm sheet, whole command),
    and a figure not from there says the day it was measured."""
    import json

    readme = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    brief = readme[readme.index("Speed in brief") :]
    results = json.loads((ROOT / "benchmarks" / "results.json").read_text())
    sheet = next(s for s in results["scenarios"] if s["scenario"] == "sheet-600x400")
    ends = sheet["end_to_end"]
    assert (
        f"sheet of {sheet['segments']:,} segments writes its DXF in {ends['dxf end to end']:.2f} s, "
        f"its relief STL in {ends['stl end to end']:.2f} s (`benchmarks/results.json`)"
    ) in brief
    for m in re.finditer(r"[^;]*\d s\b[^;]*", brief.split(". ")[0]):
        assert "results.json" in m.group(0) or re.search(r"measured .*\d{4}-\d\d-\d\d", m.group(0)), m.group(0)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_time_in_the_prose_says_where_it_comes_from(page):
    """A measured time in the prose (``1.45 s``, ``104 ms``; not a setting or a bound such as
    ``at most 10 s``) sits in a paragraph that names `benchmarks/results.json` or the day it was
    measured (the tables `benchmarks/run.py --readme` writes come from results.json)."""
    assert doc_pages.undated_timings(page) == []


def test_the_timing_check_finds_an_undated_time(tmp_path):
    page = tmp_path / "p.md"
    page.write_text("It takes 1.45 s.\n\nAt most 10 s here.\n\nIt took 2.0 s (measured on 2026-12-04).\n")
    assert [x.split(":")[0] for x in doc_pages.undated_timings(page)] == ["p.md"]
    assert "1.45 s" in doc_pages.undated_timings(page)[0]


def test_a_missing_program_skips_its_block_unless_programs_are_required(tmp_path, monkeypatch):
    """Without PrusaSlicer (and not in CI) its command and the rest of its block are not run, nor
    their output checked; where programs are required, the command runs (and fails)."""
    import real_programs

    page = tmp_path / "p.md"
    page.write_text("```sh\nprusa-slicer --info x.3mf\ngrep T x.gcode\n```\n\n```\nT0\n```\n", encoding="utf-8")
    which = doc_pages.shutil.which
    monkeypatch.setattr(
        doc_pages.shutil, "which", lambda name, *a, **k: None if name == "prusa-slicer" else which(name)
    )
    monkeypatch.setattr(real_programs, "REQUIRED", False)
    (tmp_path / "a").mkdir()
    run = doc_pages.run_page(page, doc_pages.fresh_folder(tmp_path / "a"))
    assert run.problems == [] and run.not_run == ["prusa-slicer --info x.3mf", "grep T x.gcode"]
    monkeypatch.setattr(real_programs, "REQUIRED", True)
    (tmp_path / "b").mkdir()
    assert doc_pages.run_page(page, doc_pages.fresh_folder(tmp_path / "b")).problems != []


@pytest.mark.parametrize(
    "where,body", [b for page in PAGES for b in doc_pages.toml_blocks(page)], ids=lambda x: x if ":" in x else ""
)
def test_every_toml_the_docs_show_loads(where, body):
    """A design's sections (over the sample's) or a profile, as the page shows them, load."""
    assert doc_pages.toml_problem(where, body) is None


def test_the_toml_check_finds_a_wrong_key():
    assert "4.8.8" in doc_pages.toml_problem(
        "p.md:1", '[packing]\nkind = "archimedean"\ntiling = "4.8.8"\nedge = 14\n[packing.motifs]\n12 = "table3-1"\n'
    )
