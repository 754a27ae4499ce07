"""The manual as a reader meets it: its commands, the output it shows for them, its Python snippets.

A page (``README.md``, ``docs/*.md``) is read as a list of steps, in the page's order:

- a ```sh block: its lines are shell commands (a trailing ``\\`` joins two lines; ``# exits N``
  in a line's comment is the status it exits with, else 0). A plain ``` block right after it is
  what those commands print, in order (stdout and stderr, as a terminal shows them);
- a plain ``` block whose first line starts with ``$ ``: a transcript, each ``$ command`` line
  followed by what that command prints;
- a ```python block: run as a script (each ``print(...)  # ... "quoted"`` line must print its
  quoted text), or as a doctest when it holds ``>>>`` lines.

Any other plain ``` block is an error: text that is not output is fenced ```text. A shown output
matches what was printed line for line; a line ``...`` stands for any number of lines, and
``...`` inside a line for any text in that line (so an abridged output says where it is abridged).

`run_page` runs a page's steps in one fresh folder holding a copy of ``samples/``, as a reader
does after cloning: later commands use the files earlier ones wrote. ``fabtiles``, ``python``
and ``python3`` are this interpreter's (``sys.executable -m fabtiles``); the commands listed in
`NOT_RUN` are not run, for the reason given there. A plain ``fabtiles ...`` (no shell syntax, see
`in_process_args`) is run by the CLI in this process, as ``python -m fabtiles`` would run it, which
spares each its interpreter's start and imports; any other command is run by bash.
"""

from __future__ import annotations

import contextlib
import doctest
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import traceback
import warnings
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

BLOCK = re.compile(r"^```(\w*)\n(.*?)^```\n", re.MULTILINE | re.DOTALL)

NOT_RUN = {
    # the start of a command line -> why the docs test does not run it
    "python3 -m venv": "installs fabtiles into a new environment",
    "pip install": "installs packages",
    "fabtiles install-viewer": "installs three.js from npm",
    "fabtiles serve": "serves the web app until stopped (tests/web runs the app)",
    "fabtiles install-inkscape-extension": "installs into the user's Inkscape (tests/cli/test_inkscape_extension.py)",
    "dask scheduler": "serves a Dask scheduler until stopped",
    "dask worker": "serves a Dask worker until stopped",
    "fabtiles batch designs/*.toml -o /shared/out --scheduler": (
        "needs a Dask cluster (tests/making/test_jobs_dask.py runs one)"
    ),
    "HOME=$tmp meerk40t": "how tests/export/test_laser_programs.py runs MeerK40t on its own file",
}

PROSE_FROM_OUTPUT = ("first-cut.md", "first-print.md")
"""The pages whose prose quotes figures of their commands' outputs (each must be printed there)."""

FIGURE = re.compile(
    r"about \d+ min|[\d.,]+ m of cut|[\d,]+ pierces|[\d.]+ g of filament"
    r"|[\d,]+ (?:small )?holes|\d+ x \d+ mm"
)
"""A figure quoted from a command's output: a job time, a length of cut, pierces, filament, a count
of holes, a card's size."""

PROGRAMS = {"prusa-slicer": "apt-get install prusa-slicer"}
"""The programs (not fabtiles) the docs' commands run: a command of one that is missing is not run
and says how to install it, except where the programs are required (CI): there it fails."""

SNIPPETS_NOT_RUN = {
    # (page, the start of the snippet's first line) -> why it is not run
    ("architecture.md", "def model_glb_bytes(model) -> bytes:"): "signatures, not a program",
}


@dataclass
class Step:
    """One thing a reader does: commands (kind ``sh``) or a snippet (``python``, ``doctest``)."""

    kind: str
    where: str  # page:line
    commands: list[tuple[str, int]] = field(default_factory=list)  # (command, exit status)
    code: str = ""
    shown: list[str] | None = None  # the output the page shows, if it shows one


def steps(page: Path) -> list[Step]:
    """The page's steps in order (see the module's docstring)."""
    text = page.read_text(encoding="utf-8")
    blocks = [(m.group(1), m.group(2), m.start(), m.end()) for m in BLOCK.finditer(text)]
    out: list[Step] = []
    taken = set()
    for i, (lang, body, start, end) in enumerate(blocks):
        where = f"{page.name}:{text[:start].count(chr(10)) + 2}"
        if i in taken:
            continue
        if lang == "sh":
            step = Step("sh", where, commands=shell_lines(body))
            nxt = blocks[i + 1] if i + 1 < len(blocks) else None
            if nxt and nxt[0] == "" and not text[end : nxt[2]].strip():
                step.shown = output_lines(nxt[1])
                taken.add(i + 1)
            out.append(step)
        elif lang == "" and body.lstrip().startswith("$ "):
            command, shown = None, []
            for line in body.replace("\\\n", " ").splitlines():
                if line.startswith("$ "):
                    if command:
                        out.append(Step("sh", where, commands=shell_lines(command), shown=shown))
                    command, shown = line[2:], []
                else:
                    shown.append(line.rstrip())
            out.append(Step("sh", where, commands=shell_lines(command), shown=trim(shown)))
        elif lang == "":
            out.append(Step("stray", where, code=body))
        elif lang == "python":
            first = body.strip().splitlines()[0]
            if any(page.name == name and first.startswith(start) for name, start in SNIPPETS_NOT_RUN):
                continue
            out.append(Step("doctest" if re.search(r"^\s*>>> ", body, re.MULTILINE) else "python", where, code=body))
    return out


def prose_figures(page: Path) -> list[str]:
    """The figures quoted in backticks outside the code blocks."""
    text = BLOCK.sub("", page.read_text(encoding="utf-8"))
    return [span for span in re.findall(r"`([^`\n]+)`", text) if FIGURE.search(span)]


def shell_lines(body: str) -> list[tuple[str, int]]:
    cmds = []
    for line in body.replace("\\\n", " ").splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        exits = re.search(r"#.*\bexits (\d+)", line)
        cmds.append((line.strip(), int(exits.group(1)) if exits else 0))
    return cmds


def trim(lines: list[str]) -> list[str]:
    while lines and not lines[-1].strip():
        lines = lines[:-1]
    while lines and not lines[0].strip():
        lines = lines[1:]
    return lines


def output_lines(text: str) -> list[str]:
    return trim([line.rstrip() for line in text.splitlines()])


def skipped(command: str) -> str | None:
    """Why ``command`` is not run, or None."""
    from real_programs import REQUIRED

    program = command.split()[0]
    if program in PROGRAMS and not shutil.which(program) and not REQUIRED:
        return f"{program} is not installed: {PROGRAMS[program]}"
    return next((why for start, why in NOT_RUN.items() if command.startswith(start)), None)


def mismatch(shown: list[str], printed: list[str]) -> str | None:
    """None when ``printed`` matches ``shown`` (``...`` lines and in-line ``...`` as wildcards),
    else the first shown line that does not match."""
    patterns = [
        None if s.strip() == "..." else re.compile(".*".join(re.escape(part) for part in s.split("...")) + r"\Z")
        for s in shown
    ]
    best = [0]

    @_memo
    def match(i: int, j: int) -> bool:
        best[0] = max(best[0], i)
        if i == len(patterns):
            return j == len(printed)
        if patterns[i] is None:
            return any(match(i + 1, k) for k in range(j, len(printed) + 1))
        return j < len(printed) and bool(patterns[i].match(printed[j])) and match(i + 1, j + 1)

    if match(0, 0):
        return None
    return shown[best[0]] if best[0] < len(shown) else "(the output goes on past the last line shown)"


def _memo(f):
    seen = {}

    def g(*args):
        if args not in seen:
            seen[args] = f(*args)
        return seen[args]

    return g


def fresh_folder(tmp: Path) -> Path:
    """A folder as a reader's clone has it: the samples, and the shims that make ``fabtiles`` and
    ``python`` this interpreter."""
    shutil.copytree(ROOT / "samples", tmp / "samples")
    shims = tmp / ".shims"
    shims.mkdir()
    for name, target in (
        ("fabtiles", f'"{sys.executable}" -m fabtiles'),
        ("python", f'"{sys.executable}"'),
        ("python3", f'"{sys.executable}"'),
    ):
        (shims / name).write_text(f'#!/bin/sh\nexec {target} "$@"\n')
        (shims / name).chmod(0o755)
    return tmp


def command_env(folder: Path) -> dict[str, str]:
    """The variables a command runs with, over this process's: the shims first on ``PATH``, ``HOME``
    in the folder (the programs' settings, PrusaSlicer's, stay there) and a 100-column terminal."""
    (folder / ".home").mkdir(exist_ok=True)
    return {
        "PATH": os.pathsep.join([str(folder / ".shims"), str(Path(sys.executable).parent), os.environ.get("PATH", "")]),
        "PYTHONPATH": str(ROOT),
        "PYTHONUNBUFFERED": "1",
        "COLUMNS": "100",
        "HOME": str(folder / ".home"),
    }


PLAIN_WORD = r"""(?:[\w@%+=:,./-]|'[^']*'|"[^"$`\\!]*")+"""
"""A word the shell passes on as it is once its quotes are taken off: letters, digits and
``@%+=:,./-_``, single-quoted text, and double-quoted text with no ``$``, backquote, backslash or
``!``. So no variable, glob, tilde, brace, escape, redirection, pipe, list or sub-shell."""

PLAIN = re.compile(rf"{PLAIN_WORD}(?:\s+{PLAIN_WORD})*")

POOLED = {"batch", "sweep"}
"""The commands that build in a pool of processes: forked from the test process those would carry
its state, so these run by bash, as a reader's do."""


def in_process_args(command: str) -> list[str] | None:
    """The arguments of ``command`` when it is a plain ``fabtiles ...`` (its words all `PLAIN_WORD`\\ s,
    then maybe a ``# comment``; not one of `POOLED`), which the CLI runs in this process with the
    same effect as bash (`run_in_process`); else None, and bash runs it."""
    body = re.sub(r"\s#.*", "", command).strip()  # a '#' inside quotes leaves a quote open: not plain
    if not PLAIN.fullmatch(body):
        return None
    words = shlex.split(body)
    if words[0] != "fabtiles":
        return None
    subcommand = next((w for w in words[1:] if not w.startswith("-")), None)
    return None if subcommand in POOLED else words[1:]


def run_in_process(args: list[str], folder: Path) -> subprocess.CompletedProcess:
    """``fabtiles ARGS`` run by the CLI in this process as ``python -m fabtiles`` would run it in
    ``folder``: the same variables (`command_env`), help laid out for the 100 columns, warnings
    shown by a fresh interpreter's filters, stdout and stderr into one text in the order written,
    a traceback printed for an exception that escapes (status 1), the exit status of ``sys.exit``.
    """
    from click import formatting
    from click.testing import CliRunner

    from fabtiles.cli.main import cli

    here = os.getcwd()
    os.chdir(folder)
    with CliRunner().isolation(env=command_env(folder)) as (_, _, output), warnings.catch_warnings():
        formatting.FORCED_WIDTH = None  # not the runner's 80 columns: COLUMNS' (isolation restores it)
        for stream in (sys.stdout, sys.stderr):
            stream.reconfigure(write_through=True)  # as PYTHONUNBUFFERED: the two interleave as written
        warnings.resetwarnings()
        for action, category, module in FRESH_FILTERS:
            warnings.filterwarnings(action, category=category, module=module, append=True)
        warnings.showwarning = _show_warning
        try:
            cli.main(args=args, prog_name="fabtiles")
            status = 0
        except SystemExit as done:
            status = done.code if isinstance(done.code, int) else 0 if done.code is None else 1
            if done.code is not None and not isinstance(done.code, int):
                print(done.code, file=sys.stderr)
        except Exception:
            traceback.print_exc()  # the interpreter's last words, to stderr
            status = 1
        finally:
            os.chdir(here)
        text = output.getvalue().decode("utf-8", "backslashreplace")
    return subprocess.CompletedProcess(["fabtiles", *args], status, text)


FRESH_FILTERS = [
    ("default", DeprecationWarning, "__main__"),
    ("ignore", DeprecationWarning, ""),
    ("ignore", PendingDeprecationWarning, ""),
    ("ignore", ImportWarning, ""),
    ("ignore", ResourceWarning, ""),
]
"""The warnings filters of a fresh interpreter with no ``-W`` (the order of ``warnings.filters``)."""


def _show_warning(message, category, filename, lineno, file=None, line=None):
    sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))


def run_command(command: str, folder: Path) -> subprocess.CompletedProcess:
    """``command`` run in ``folder``, stdout and stderr together as a terminal shows them: a plain
    ``fabtiles ...`` (`in_process_args`) by the CLI in this process, anything else by bash."""
    args = in_process_args(command)
    if args is not None:
        return run_in_process(args, folder)
    return subprocess.run(
        ["bash", "-c", command],
        cwd=folder,
        env={**os.environ, **command_env(folder)},
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=600,
        check=False,
    )


def run_python(step: Step, namespace: dict) -> list[str]:
    """Run a snippet in ``namespace`` (the page's session so far); the problems found."""
    if step.kind == "doctest":
        test = doctest.DocTestParser().get_doctest(step.code, namespace, step.where, step.where, 0)
        report = io.StringIO()
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
        runner.run(test, out=report.write, clear_globs=False)
        return [report.getvalue()] if runner.failures else []
    quoted = [
        q
        for line in step.code.splitlines()
        if line.lstrip().startswith("print(") and "#" in line
        for q in re.findall(r'"([^"]+)"', line.split("#", 1)[1])
    ]
    printed = io.StringIO()
    try:
        with contextlib.redirect_stdout(printed):
            exec(compile(step.code, step.where, "exec"), namespace)
    except Exception as error:
        return [f"{step.where}: the snippet raised {type(error).__name__}: {error}"]
    return [f"{step.where}: printed no {q!r}:\n{printed.getvalue()}" for q in quoted if q not in printed.getvalue()]


@dataclass
class PageRun:
    problems: list[str]
    printed: list[str]  # what each command printed, in order
    not_run: list[str]  # the commands skipped by name


def run_page(page: Path, folder: Path) -> PageRun:
    """Run every step of ``page`` in ``folder`` (made by `fresh_folder`), in order."""
    problems, printed, not_run = [], [], []
    namespace: dict = {"__name__": "__docs__"}
    here = os.getcwd()
    os.chdir(folder)
    try:
        for step in steps(page):
            if step.kind == "stray":
                problems.append(
                    f"{step.where}: a plain ``` block that is not a command's output "
                    "(fence text as ```text, a transcript starts with '$ ')"
                )
            elif step.kind in ("python", "doctest"):
                problems += run_python(step, namespace)
            else:
                out = ""
                missing = False
                for command, status in step.commands:
                    why = skipped(command)
                    missing = missing or bool(why and why.endswith(PROGRAMS.get(command.split()[0], "\0")))
                    if why or missing:  # after a missing program, the block's other commands need its files
                        not_run.append(command)
                        continue
                    done = run_command(command, folder)
                    out += done.stdout
                    printed.append(done.stdout)
                    if done.returncode != status:
                        problems.append(
                            f"{step.where}: `{command}` exited {done.returncode}, not {status}:\n{done.stdout[-3000:]}"
                        )
                if step.shown is not None and not missing:
                    wrong = mismatch(step.shown, output_lines(out))
                    if wrong is not None:
                        problems.append(
                            f"{step.where}: the page shows a line that was not printed there: "
                            f"{wrong!r}\nprinted:\n{out}"
                        )
    finally:
        os.chdir(here)
    if page.name in PROSE_FROM_OUTPUT:
        everything = "\n".join(printed)
        problems += [
            f"{page.name}: the prose quotes {f!r}, which no command printed"
            for f in prose_figures(page)
            if f not in everything
        ]
    return PageRun(problems, printed, not_run)


TIME = re.compile(r"(?<![\w.])\d[\d,]*(?:\.\d+)?\s?(?:s|ms)\b")
"""A time in the prose: ``1.45 s``, ``104 ms``."""
SETTING = re.compile(
    r"(at most|within|under|over|budget|target|limit|--time|time_s|up to|less than|more than|"
    r"below|above|[<>])\b[^.;]{0,20}$|^\W*(budget|limit)",
    re.IGNORECASE,
)
"""Words that make a time a setting or a bound (``at most 10 s``, ``its 2 s budget``), not a measurement."""
DATED = re.compile(r"\b20\d\d-\d\d-\d\d\b|results\.json")


def undated_timings(page: Path) -> list[str]:
    """The paragraphs of ``page`` (a table with the paragraph before it) that give a measured time
    but neither the day it was measured nor `benchmarks/results.json` as its source."""
    text = BLOCK.sub("\n\n", page.read_text(encoding="utf-8"))
    # the tables benchmarks/run.py --readme writes from benchmarks/results.json
    text = re.sub(
        r"<!-- benchmarks/run.py --readme: start -->.*?<!-- benchmarks/run.py --readme: end -->",
        "",
        text,
        flags=re.DOTALL,
    )
    units: list[str] = []
    for para in re.split(r"\n\s*\n", text):
        if para.lstrip().startswith("|") and units:
            units[-1] += "\n" + para
        else:
            units.append(para)
    found = []
    for unit in units:
        flat = " ".join(unit.split())
        times = [
            m
            for m in TIME.finditer(flat)
            if not SETTING.search(flat[max(0, m.start() - 25) : m.start()])
            and not SETTING.search(flat[m.end() : m.end() + 10])
        ]
        if times and not DATED.search(flat):
            found.append(f"{page.name}: {[m.group(0) for m in times]} in: {flat[:100]}...")
    return found


def toml_blocks(page: Path) -> list[tuple[str, str]]:
    """The page's ```toml blocks: ``(page:line, text)``."""
    text = page.read_text(encoding="utf-8")
    return [
        (f"{page.name}:{text[: m.start()].count(chr(10)) + 2}", m.group(2))
        for m in BLOCK.finditer(text)
        if m.group(1) == "toml"
    ]


def toml_problem(where: str, body: str) -> str | None:
    """None when a page's TOML loads as what it shows: a profile (it has ``kind``), else a design,
    its sections put in place of those of ``samples/table3-3.toml`` (a page shows the sections it
    is about)."""
    import tempfile

    import tomli_w
    import tomllib

    from fabtiles.designs.design_file import design_from_text
    from fabtiles.machines import profiles as _profiles

    try:
        shown = tomllib.loads(body)
        if "kind" in shown:
            with tempfile.TemporaryDirectory() as folder:
                path = Path(folder) / "profile.toml"
                path.write_text(body, encoding="utf-8")
                _profiles.load_profile(str(path))
        else:
            design = tomllib.loads((ROOT / "samples" / "table3-3.toml").read_text(encoding="utf-8"))
            design_from_text(tomli_w.dumps(design | shown), name="shown")
    except Exception as error:
        return f"{where}: {type(error).__name__}: {error}"
    return None
