"""Benchmark: STEP files with round walls as cylinders (issue 35) against an older checkout's planar ones.

For each design (by default the pierced circle of issue 30/35 at 100 and 150 mm: 3.3.3.4.4, round
joins, outline circles, small holes filled, and the 3.3.3.4.4 sample as a 100 mm pierced circle),
this checkout and an older one (``--old``, e.g. ``/work/main``) each write the STEP in a process of
its own, paired and alternated; then OCCT imports each file as CAD programs do (``STEPControl_Reader``
with shape healing, then ``BRepCheck_Analyzer`` on the solid), again one process per file. Reported:
the export's CPU seconds, the file's size, faces and cylinders, the import's CPU seconds (reading the
file and building the shape with its healing; the text's parse alone in brackets; OCP's own loading
left out) and whether OCCT finds the solid valid. CPU time, not wall time: the machine is shared.

Run by hand (never in CI)::

    python benchmarks/bench_step_cylinders.py --old <older checkout> [--repeat 2] [--sizes 100 150]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
NEW = HERE.parent

EXPORT = """
import json, sys, time
from fabtiles.making.models import BuildOptions, Models
from fabtiles.making.pipeline import prepare_tile
from fabtiles.designs.design_file import load_design
from fabtiles.export.step import step_bytes
d = load_design(sys.argv[1])
models = Models(prepare_tile(d), BuildOptions.of_design(d))
models.print.fused  # the checked mesh: made for every print format alike, not the STEP's own cost
t = time.process_time()
data = step_bytes(models.print, name="tile")
cpu = time.process_time() - t
open(sys.argv[2], "wb").write(data)
print(json.dumps({"export_cpu_s": cpu}))
"""

IMPORT = """
import json, sys, time
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.BRepCheck import BRepCheck_Analyzer
t = time.process_time()  # OCP's own loading (about a second) is no part of the file's cost
reader = STEPControl_Reader()
assert reader.ReadFile(sys.argv[1]) == IFSelect_RetDone
parsed = time.process_time()
reader.TransferRoots()
shape = reader.OneShape()
read = time.process_time()
valid = BRepCheck_Analyzer(shape).IsValid()
print(json.dumps({"import_cpu_s": read - t, "parse_cpu_s": parsed - t, "check_cpu_s": time.process_time() - read,
                  "valid": bool(valid)}))
"""


def issue_design(size: float) -> str:
    sys.path.insert(0, str(HERE))
    from bench_slicer import issue_design as design

    return design(True).replace("size = 150.8", f"size = {size}")


def sample_design(size: float) -> str:
    text = (NEW / "samples" / "tilings" / "3.3.3.4.4.toml").read_text()
    text = text.replace('outline = "square"', 'outline = "circle"').replace("size = 150", f"size = {size}")
    text = text.replace("edge = 16\n", "edge = 16\noutline_circles = true\n")
    text = text.replace("stroke = 1\n", 'stroke = 1\njoin = "round"\n')
    return text.replace('formats = ["dxf", "svg", "stl"]', 'formats = ["step"]\nprint_style = "pierced"')


def run(checkout: Path, code: str, *args) -> dict:
    env = dict(os.environ, PYTHONPATH=str(checkout))
    proc = subprocess.run(
        [sys.executable, "-c", code, *map(str, args)], capture_output=True, text=True, env=env, cwd=checkout
    )
    if proc.returncode:
        raise SystemExit(proc.stderr)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def cli_export(checkout: Path, toml: Path, out: Path) -> dict:
    """The STEP of a checkout older than the build models (issue 35 was filed on one): its CLI's build.

    Its export time is the whole build's CPU seconds (region, mesh, checks and file), marked so.
    """
    import resource
    import shutil

    text = toml.read_text()
    if "formats" not in text:
        text = text.replace("[output]\n", '[output]\nformats = ["step"]\n')
    design = out.with_suffix(".toml")
    design.write_text(text)
    folder = out.with_suffix(".out")
    shutil.rmtree(folder, ignore_errors=True)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(
        [sys.executable, "-m", "fabtiles", "build", str(design), "-o", str(folder)],
        capture_output=True,
        text=True,
        cwd=checkout,
        env=dict(os.environ, PYTHONPATH=str(checkout)),
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode:
        raise SystemExit(proc.stderr)
    (step,) = folder.glob("*.step")
    shutil.move(step, out)
    return {"export_cpu_s": after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, "cli": True}


def export(checkout: Path, toml: Path, out: Path) -> dict:
    if (checkout / "fabtiles" / "making" / "models.py").exists():
        return run(checkout, EXPORT, toml, out)
    if (checkout / "fabtiles" / "build" / "models.py").exists():  # before the layers were folders
        old_names = EXPORT.replace("fabtiles.making.", "fabtiles.build.").replace(
            "fabtiles.designs.design_file", "fabtiles.design"
        )
        return run(checkout, old_names, toml, out)
    return cli_export(checkout, toml, out)


def counts(path: Path) -> dict:
    text = path.read_text()
    return {
        "mb": path.stat().st_size / 1e6,
        "faces": text.count("ADVANCED_FACE("),
        "cylinders": text.count("CYLINDRICAL_SURFACE("),
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument(
        "--old",
        required=True,
        type=Path,
        help="the older checkout (its STEP has planar faces); one without fabtiles/making/models.py "
        "(fabtiles/build/models.py before the layers were folders) "
        "(as when issue 35 was filed, e.g. 3650417) writes it through its CLI",
    )
    ap.add_argument("--sizes", type=float, nargs="*", default=[100.0, 150.0])
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--no-sample", action="store_true", help="leave out the 3.3.3.4.4 sample")
    ap.add_argument("--design", type=Path, nargs="*", default=[], help="more design files (e.g. samples/*.toml)")
    ap.add_argument("--no-import", action="store_true", help="time the export only (OCCT imports a sheet slowly)")
    args = ap.parse_args(argv)
    designs = [(f"issue-35-{s:g}mm", issue_design(s)) for s in args.sizes]
    if not args.no_sample:
        designs.append(("3.3.3.4.4-circle-100mm", sample_design(100.0)))
    designs += [(d.stem, d.read_text()) for d in args.design]
    work = Path(tempfile.mkdtemp(prefix="bench-step-cyl-"))
    print("design | checkout | export CPU s | MB | faces | cylinders | OCCT import CPU s | check CPU s | valid")
    for name, text in designs:
        toml = work / f"{name}.toml"
        toml.write_text(text)
        for k in range(args.repeat):
            order = [("old", args.old), ("new", NEW)] if k % 2 == 0 else [("new", NEW), ("old", args.old)]
            rows = {}
            for label, checkout in order:
                out = work / f"{name}-{label}.step"
                rows[label] = export(checkout, toml, out) | counts(out)
            for label, _ in order:
                rows[label] |= (
                    {
                        "import_cpu_s": float("nan"),
                        "parse_cpu_s": float("nan"),
                        "check_cpu_s": float("nan"),
                        "valid": None,
                    }
                    if args.no_import
                    else run(NEW, IMPORT, work / f"{name}-{label}.step")
                )
            for label in ("old", "new"):
                r = rows[label]
                cpu = f"{r['export_cpu_s']:.2f}" + (" (whole build, CLI)" if r.get("cli") else "")
                print(
                    f"{name} | {label} | {cpu} | {r['mb']:.1f} | {r['faces']:,} | {r['cylinders']:,}"
                    f" | {r['import_cpu_s']:.2f} ({r['parse_cpu_s']:.2f}) | {r['check_cpu_s']:.2f} | {r['valid']}",
                    flush=True,
                )
            o, n = rows["old"], rows["new"]
            ratio = "(not paired: a whole build)" if o.get("cli") else f"{n['export_cpu_s'] / o['export_cpu_s']:.2f}x"
            print(
                f"{name} | new/old | {ratio} | {n['mb'] / o['mb']:.2f}x | "
                f"{n['faces'] / o['faces']:.2f}x | | {o['import_cpu_s'] / n['import_cpu_s']:.1f}x faster | |",
                flush=True,
            )


if __name__ == "__main__":
    main()
