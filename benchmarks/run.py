"""fabtiles benchmarks: wall time and peak memory of every pipeline stage.

Run by hand from a checkout (never in CI: these machines are shared and noisy)::

    python benchmarks/run.py                 # all scenarios, writes benchmarks/results.md
    python benchmarks/run.py --quick         # skip the 1,200 x 600 mm sheet, the panel and the scaling table
    python benchmarks/run.py --baselines     # also time the straightforward pipelines
    python benchmarks/run.py --baselines --readme   # and put the tables into docs/speed.md

Each scenario runs in a fresh Python process, so the figures include the
imports each stage pays for, and the memory of one scenario does not leak into
the next. Peak memory is the process's resident high-water mark at the end of
each stage (``ru_maxrss``), so it is cumulative: the peak of the scenario so far.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent

SCENARIOS = {
    "rosette-tile": dict(
        outline="circle",
        size=150,
        pattern="single",
        preset="table2-left",
        stages=["pattern", "region", "dxf", "svg", "stl", "3mf", "step"],
    ),
    "sheet-600x400": dict(
        outline="rectangle",
        size=(600, 400),
        pattern="hex",
        radius=15,
        stages=["pattern", "region", "dxf", "svg", "stl", "3mf"],
    ),
    "relief-200x200": dict(
        outline="square", size=200, pattern="hex", radius=15, stages=["pattern", "region", "stl", "3mf", "step"]
    ),
    "sheet-1200x600": dict(
        outline="rectangle",
        size=(1200, 600),
        pattern="hex",
        radius=15,
        stages=["pattern", "region", "dxf", "svg", "stl"],
    ),
    # a full router sheet (samples/panel-2440x1220.toml): the 6 mm bit's DXF, and for comparison the
    # same panel's pierced laser DXF on a laser profile with a bed that large
    "panel-2440x1220": dict(
        outline="rectangle",
        size=(2440, 1220),
        pattern="hex",
        radius=60,
        stroke=12.0,
        frame=40.0,
        profile="router-6mm-mdf",
        stages=["pattern", "region", "dxf"],
    ),
    "panel-2440x1220-laser": dict(
        outline="rectangle",
        size=(2440, 1220),
        pattern="hex",
        radius=60,
        stroke=12.0,
        frame=40.0,
        stages=["pattern", "region", "dxf"],
    ),
}

SCALING_SIZES = [(150, 100), (300, 200), (600, 400), (1200, 800)]

TARGETS = {  # (scenario, what) -> seconds; from the issues
    ("sheet-600x400", "dxf end to end"): 2.0,
    ("sheet-600x400", "svg end to end"): 2.0,
    ("sheet-600x400", "stl end to end"): 6.0,
    ("relief-200x200", "step end to end"): 30.0,
    ("panel-2440x1220", "dxf end to end"): 5.0,
}


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _profile(fmt: str, name: str | None = None):
    """The bundled profiles (``name``, if given), the beds made large enough for the 2,440 mm panel (the
    sheet's print is measured whole, not as the pieces a 256 mm bed would make of it)."""
    import dataclasses

    from fabtiles import load_profile

    if name is not None:
        return load_profile(name)
    if fmt in ("dxf", "svg"):
        return dataclasses.replace(load_profile("laser-3mm-plywood"), bed_mm=(2500.0, 1300.0))
    return dataclasses.replace(load_profile("fdm-0.4mm"), bed_mm=(2500.0, 1300.0))


def run_scenario(name: str) -> dict:
    """Run one scenario in this process and return its figures."""
    spec = SCENARIOS[name]
    t0 = time.perf_counter()
    import fabtiles as ft

    import_s = time.perf_counter() - t0
    rows = []
    out = Path(tempfile.mkdtemp(prefix="fabtiles-bench-"))

    def stage(label, func):
        t = time.perf_counter()
        value = func()
        rows.append({"stage": label, "seconds": time.perf_counter() - t, "peak_mb": _peak_mb()})
        return value

    motif = ft.Star.preset(spec.get("preset", "table3-3"))
    if spec["pattern"] == "single":
        pattern = motif
    else:
        pattern = ft.HexPacking(radius=spec["radius"], motif=motif)
    tile = ft.Tile(spec["outline"], spec["size"], pattern, frame=spec.get("frame", 5.0), stroke=spec.get("stroke", 1.0))
    segments = stage("pattern", tile.segments)
    stage("region", tile.region)
    sizes = {}
    for fmt in spec["stages"][2:]:
        path = out / f"{name}.{fmt}"
        stage(fmt, lambda path=path, fmt=fmt: tile.export(path, profile=_profile(fmt, spec.get("profile"))))
        sizes[fmt] = path.stat().st_size
    front = sum(r["seconds"] for r in rows if r["stage"] in ("pattern", "region"))
    end_to_end = {f"{r['stage']} end to end": front + r["seconds"] for r in rows if r["stage"] in sizes}
    for p in out.iterdir():
        p.unlink()
    out.rmdir()
    return {
        "scenario": name,
        "segments": len(segments),
        "import_s": import_s,
        "stages": rows,
        "end_to_end": end_to_end,
        "file_bytes": sizes,
        "peak_mb": _peak_mb(),
    }


def run_scaling(width: float, height: float) -> dict:
    """Pattern, region and DXF for one sheet size (for the growth table)."""
    import fabtiles as ft

    tile = ft.Tile(
        "rectangle", (width, height), ft.HexPacking(radius=15, motif=ft.Star.preset("table3-3")), frame=5.0, stroke=1.0
    )
    times = {}
    t = time.perf_counter()
    segments = tile.segments()
    times["pattern"] = time.perf_counter() - t
    t = time.perf_counter()
    tile.region()
    times["region"] = time.perf_counter() - t
    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        tile.export(Path(tmp) / "s.dxf", profile=_profile("dxf"))
        times["dxf"] = time.perf_counter() - t
    return {"size": [width, height], "segments": len(segments), "seconds": times, "peak_mb": _peak_mb()}


def run_baselines() -> dict:
    """The straightforward pipelines the issues name, for comparison (slow)."""
    import numpy as np
    import shapely

    import fabtiles as ft

    result = {}
    tile = ft.Tile(
        "rectangle", (600, 400), ft.HexPacking(radius=15, motif=ft.Star.preset("table3-3")), frame=5.0, stroke=1.0
    )
    seg = tile.segments()
    t = time.perf_counter()
    bands = shapely.buffer(shapely.linestrings(seg), 0.5, cap_style="flat", join_style="mitre")
    shapely.union_all(bands)
    result["one GEOS union of all bands (600x400)"] = time.perf_counter() - t

    import manifold3d

    region = tile.region()
    polys = []
    for part in getattr(region, "geoms", [region]):
        polys.append(np.asarray(part.exterior.coords)[:-1])
        polys.extend(np.asarray(h.coords)[:-1] for h in part.interiors)
    t = time.perf_counter()
    cs = manifold3d.CrossSection(polys, manifold3d.FillRule.EvenOdd)
    manifold3d.Manifold.extrude(cs, 1.2).to_mesh()
    result["one manifold cross-section for the whole sheet (extrude + mesh)"] = time.perf_counter() - t
    return result


OCCT_STEP_LIMIT_S = 600
"""How long the one-face OCCT baseline may spend writing its STEP before it is stopped."""


def run_occt_face_baseline(stage: str) -> dict:
    """The straightforward STEP pipeline: the 200 x 200 mm tile's material as ONE build123d
    face (all holes in it), extruded; ``stage`` is "extrude" or "step" (extrude, then write).

    Run in a child process with a time limit (see :func:`main`): the write may not end.
    """
    import numpy as np
    import shapely
    from build123d import Face, Wire, export_step, extrude

    import fabtiles as ft

    tile = ft.Tile("square", 200, ft.HexPacking(radius=15, motif=ft.Star.preset("table3-3")), frame=5.0, stroke=1.0)
    region = tile.region()
    polys = list(getattr(region, "geoms", [region]))
    t = time.perf_counter()
    solids = []
    for poly in polys:
        outer = Wire.make_polygon([tuple(p) + (0.0,) for p in np.asarray(poly.exterior.coords)[:-1]])
        inner = [Wire.make_polygon([tuple(p) + (0.0,) for p in np.asarray(r.coords)[:-1]]) for r in poly.interiors]
        solids.append(extrude(Face(outer, inner), amount=1.2))
    out = {
        "holes": int(sum(len(p.interiors) for p in polys)),
        "vertices": int(shapely.get_num_coordinates(region)),
        "extrude_s": time.perf_counter() - t,
    }
    if stage == "step":
        with tempfile.TemporaryDirectory() as tmp:
            t = time.perf_counter()
            export_step(solids[0], Path(tmp) / "naive.step")
            out["step_s"] = time.perf_counter() - t
            out["step_mb"] = (Path(tmp) / "naive.step").stat().st_size / 1e6
    return out


def _child(kind: str, arg: str, timeout: float | None = None) -> dict:
    code = f"import json, sys; sys.path.insert(0, {str(HERE)!r}); import run; print('@@' + json.dumps(run.{arg}))"
    try:
        proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"error": f"stopped after {timeout:g} s", "kind": kind, "timeout": timeout}
    if proc.returncode != 0:
        return {"error": proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "failed", "kind": kind}
    line = [ln for ln in proc.stdout.splitlines() if ln.startswith("@@")][-1]
    return json.loads(line[2:])


def startup_seconds(repeat: int = 5) -> float:
    """Best wall time of ``fabtiles --help`` in a new process."""
    best = math.inf
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "fabtiles", "--help"], capture_output=True, check=True)
        best = min(best, time.perf_counter() - t)
    return best


def _slope(xs, ys) -> float:
    lx = [math.log(x) for x in xs]
    ly = [math.log(max(y, 1e-6)) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly, strict=True)) / sum((a - mx) ** 2 for a in lx)


def report(results: dict) -> str:
    lines = [
        "# fabtiles benchmark results",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}; "
        f"command: `python benchmarks/run.py{' ' + ' '.join(sys.argv[1:]) if sys.argv[1:] else ''}`.",
        "",
        f"Start-up, `fabtiles --help`: **{results['startup_s']:.3f} s** (target < 0.3 s).",
        "",
    ]
    lines += ["| scenario | segments | stage | seconds | peak MB (so far) |", "|---|---:|---|---:|---:|"]
    for sc in results["scenarios"]:
        if "error" in sc:
            lines.append(f"| {sc.get('scenario', '?')} | | error: {sc['error']} | | |")
            continue
        for r in sc["stages"]:
            lines.append(
                f"| {sc['scenario']} | {sc['segments']:,} | {r['stage']} | {r['seconds']:.2f} | {r['peak_mb']:.0f} |"
            )
    lines += [
        "",
        "End to end (pattern + region + writer) against the targets:",
        "",
        "| scenario | output | seconds | target | file size |",
        "|---|---|---:|---:|---:|",
    ]
    for sc in results["scenarios"]:
        for what, sec in sc.get("end_to_end", {}).items():
            target = TARGETS.get((sc["scenario"], what))
            fmt = what.split()[0]
            verdict = "" if target is None else f"< {target:g} s {'ok' if sec < target else 'MISSED'}"
            size = sc["file_bytes"].get(fmt, 0) / 1e6
            lines.append(f"| {sc['scenario']} | {fmt} | {sec:.2f} | {verdict} | {size:.1f} MB |")
    if results.get("scaling"):
        lines += [
            "",
            "Growth with segment count (hexagonal packing R = 15 mm, table3-3):",
            "",
            "| sheet mm | segments | pattern s | region s | dxf s | peak MB |",
            "|---|---:|---:|---:|---:|---:|",
        ]
        ok = [s for s in results["scaling"] if "error" not in s]
        for s in ok:
            t = s["seconds"]
            lines.append(
                f"| {s['size'][0]:g} x {s['size'][1]:g} | {s['segments']:,} | {t['pattern']:.2f} | "
                f"{t['region']:.2f} | {t['dxf']:.2f} | {s['peak_mb']:.0f} |"
            )
        if len(ok) >= 3:
            xs = [s["segments"] for s in ok]
            for stage in ("region", "dxf"):
                k = _slope(xs[1:], [s["seconds"][stage] for s in ok[1:]])
                lines.append(
                    f"\nLog-log slope of {stage} time against segments (largest three sizes): "
                    f"**{k:.2f}** (1.0 is linear)."
                )
    if results.get("baselines"):
        lines += ["", "Straightforward pipelines, for comparison:", "", "| pipeline | seconds |", "|---|---:|"]
        for what, sec in results["baselines"].items():
            lines.append(f"| {what} | {sec} |" if isinstance(sec, str) else f"| {what} | {sec:.1f} |")
    return "\n".join(lines) + "\n"


README_START = "<!-- benchmarks/run.py --readme: start -->"
README_END = "<!-- benchmarks/run.py --readme: end -->"


def update_readme(readme: Path, text: str) -> None:
    """Replace what stands between the two markers in ``readme`` with the report (no title)."""
    body = text.split("\n", 2)[2].strip() if text.startswith("# ") else text.strip()
    doc = readme.read_text()
    if README_START not in doc or README_END not in doc:
        raise SystemExit(f"{readme} has no benchmark markers ({README_START} ... {README_END})")
    head, rest = doc.split(README_START, 1)
    _, tail = rest.split(README_END, 1)
    readme.write_text(f"{head}{README_START}\n{body}\n{README_END}{tail}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument(
        "--quick",
        action="store_true",
        help="skip the 1,200 x 600 mm sheet, the 2,440 x 1,220 mm panel and the scaling table",
    )
    ap.add_argument("--baselines", action="store_true", help="also time the straightforward pipelines (slow)")
    ap.add_argument("--only", nargs="*", choices=list(SCENARIOS), help="run only these scenarios")
    ap.add_argument("-o", "--output", default=str(HERE / "results.md"), help="markdown report to write")
    ap.add_argument(
        "--readme",
        action="store_true",
        help="also replace the section of docs/speed.md between the bench markers with the report",
    )
    args = ap.parse_args(argv)
    names = args.only or [n for n in SCENARIOS if not (args.quick and (n == "sheet-1200x600" or n.startswith("panel")))]
    results = {"startup_s": startup_seconds(), "scenarios": []}
    for name in names:
        print(f"running {name} ...", file=sys.stderr, flush=True)
        results["scenarios"].append(_child("scenario", f"run_scenario({name!r})"))
    if not args.quick and not args.only:
        results["scaling"] = []
        for w, h in SCALING_SIZES:
            print(f"scaling {w} x {h} ...", file=sys.stderr, flush=True)
            results["scaling"].append(_child("scaling", f"run_scaling({w}, {h})"))
    if args.baselines:
        print("baselines ...", file=sys.stderr, flush=True)
        results["baselines"] = _child("baselines", "run_baselines()")
        face = _child("occt", "run_occt_face_baseline('extrude')")
        what = "one OCCT face for the 200x200 tile"
        if "error" not in face:
            results["baselines"][f"{what} ({face['holes']:,} holes): face + extrude"] = face["extrude_s"]
        step = _child("occt", "run_occt_face_baseline('step')", timeout=OCCT_STEP_LIMIT_S)
        if "error" in step:
            results["baselines"][f"{what}: face + extrude + STEP write"] = f"> {OCCT_STEP_LIMIT_S} (stopped, no file)"
        else:
            results["baselines"][f"{what}: face + extrude + STEP write ({step['step_mb']:.0f} MB)"] = (
                step["extrude_s"] + step["step_s"]
            )
    text = report(results)
    Path(args.output).write_text(text)
    if args.readme:
        update_readme(HERE.parent / "docs" / "speed.md", text)
    (Path(args.output).with_suffix(".json")).write_text(json.dumps(results, indent=1))
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
