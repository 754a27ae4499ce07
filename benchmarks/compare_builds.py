"""Compare the files two checkouts of fabtiles write for every sample in every format.

For a refactoring that must not change the output: each checkout builds every
``samples/*.toml`` in each format (one ``fabtiles build`` process per sample and
format, so a format the machine refuses, or a limit, is compared as its message),
then the files are compared by what they hold:

- DXF: entity by entity (type, layer, closed, vertices within 1e-9 mm), read by ezdxf;
- SVG and LightBurn: byte for byte;
- STL: vertex by vertex (the float32 triangles);
- 3MF: each object's vertices and triangles, and the parts' extruders;
- STEP: OCCT's volume and face count;
- findings: the set of ``code: message`` lines the build printed.

Usage::

    python benchmarks/compare_builds.py OLD_CHECKOUT NEW_CHECKOUT [--out DIR] [--sample NAME ...]

Both checkouts run with this interpreter (``PYTHONPATH`` set to each); the
output ends with one line per sample and format, and exits 1 on any difference.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np

FORMATS = ("dxf", "svg", "lbrn2", "stl", "3mf", "step")
FINDING = re.compile(r"^\s+- (?:[^:]+: )?([a-z_]+: .*)$")


def _last_line(text: str) -> str:
    """A command's last line of output (its one-line message), or nothing."""
    return text.strip().splitlines()[-1] if text.strip() else ""


def build(checkout: Path, sample: Path, fmt: str, out: Path) -> tuple[int, str]:
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, PYTHONPATH=str(checkout))
    proc = subprocess.run(
        [sys.executable, "-m", "fabtiles", "build", str(sample), "-o", str(out), "--format", fmt],
        capture_output=True,
        text=True,
        env=env,
        cwd=checkout,
    )
    return proc.returncode, proc.stdout + proc.stderr


def findings(output: str) -> set[str]:
    """The findings a build printed, without where they were printed (a file or a model)."""
    found = set()
    for line in output.splitlines():
        m = FINDING.match(line)
        if m:
            found.add(m.group(1))
    return found


def dxf_entities(path: Path):
    import ezdxf

    out = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "LWPOLYLINE":
            pts, closed = np.array([p[:2] for p in e.get_points("xy")]), e.closed
        elif e.dxftype() == "POLYLINE":
            pts, closed = np.array([v.dxf.location[:2] for v in e.vertices]), e.is_closed
        elif e.dxftype() == "LINE":
            pts, closed = np.array([e.dxf.start[:2], e.dxf.end[:2]]), False
        else:
            pts, closed = np.zeros((0, 2)), False
        out.append((e.dxftype(), e.dxf.layer, bool(closed), pts))
    return out


def same_dxf(a: Path, b: Path) -> str:
    ea, eb = dxf_entities(a), dxf_entities(b)
    if len(ea) != len(eb):
        return f"{len(ea)} entities, now {len(eb)}"
    for k, (x, y) in enumerate(zip(ea, eb, strict=True)):
        if x[:3] != y[:3] or x[3].shape != y[3].shape or (x[3].size and np.abs(x[3] - y[3]).max() > 1e-9):
            return f"entity {k} differs: {x[:3]} vs {y[:3]}"
    return ""


def stl_vertices(path: Path) -> np.ndarray:
    data = path.read_bytes()
    n = int.from_bytes(data[80:84], "little")
    rec = np.frombuffer(data[84 : 84 + 50 * n], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    return rec["v"]


def threemf_objects(path: Path):
    from xml.etree import ElementTree as ET

    with zipfile.ZipFile(path) as z:
        root = ET.fromstring(z.read("3D/3dmodel.model"))
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    out = []
    for obj in root.iterfind(".//m:object", ns):
        v = np.array([[float(x.get(c)) for c in "xyz"] for x in obj.iterfind(".//m:vertex", ns)])
        t = np.array([[int(x.get(c)) for c in ("v1", "v2", "v3")] for x in obj.iterfind(".//m:triangle", ns)])
        out.append((obj.get("name"), v, t))
    return out


def step_figures(path: Path) -> tuple[float, int]:
    """OCCT's volume and face count of a STEP file's solids, translated as written (no healing:
    build123d's import_step heals every face, minutes for the 600 x 400 mm sheet)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer

    from fabtiles.export.step import read_step_solids

    volume, faces = 0.0, 0
    for solid in read_step_solids(path):
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(solid, props)
        volume += props.Mass()
        explorer = TopExp_Explorer(solid, TopAbs_FACE)
        while explorer.More():
            faces += 1
            explorer.Next()
    return volume, faces


def compare(a: Path, b: Path, fmt: str) -> str:
    if fmt == "dxf":
        return same_dxf(a, b)
    if fmt in ("svg", "lbrn2"):
        return "" if a.read_bytes() == b.read_bytes() else "bytes differ"
    if fmt == "stl":
        va, vb = stl_vertices(a), stl_vertices(b)
        return "" if va.shape == vb.shape and np.array_equal(va, vb) else f"{va.shape} vs {vb.shape} or vertices differ"
    if fmt == "3mf":
        oa, ob = threemf_objects(a), threemf_objects(b)
        if len(oa) != len(ob):
            return f"{len(oa)} objects, now {len(ob)}"
        for (na, va, ta), (nb, vb, tb) in zip(oa, ob, strict=True):
            if va.shape != vb.shape or not np.allclose(va, vb, atol=1e-6) or not np.array_equal(ta, tb):
                return f"object {na!r}/{nb!r} differs"
        return ""
    if fmt == "step":
        (va, fa), (vb, fb) = step_figures(a), step_figures(b)
        return "" if abs(va - vb) <= 1e-6 * abs(va) and fa == fb else f"volume {va:.6g}/{vb:.6g}, faces {fa}/{fb}"
    raise ValueError(fmt)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old", type=Path)
    ap.add_argument("new", type=Path)
    ap.add_argument("--out", type=Path, default=Path("compare-out"))
    ap.add_argument("--sample", action="append", default=[])
    ap.add_argument("--format", action="append", default=[])
    args = ap.parse_args(argv)
    samples = sorted((args.new / "samples").glob("*.toml"))
    samples = [s for s in samples if not args.sample or s.stem in args.sample]
    bad = 0
    for sample in samples:
        for fmt in args.format or FORMATS:
            runs = {}
            for tag, checkout in (("old", args.old), ("new", args.new)):
                out = args.out / tag / sample.stem / fmt
                runs[tag] = (*build(checkout, checkout / "samples" / sample.name, fmt, out), out)
            (ca, oa, da), (cb, ob, db) = runs["old"], runs["new"]
            if ca != 0 or cb != 0:
                last = _last_line
                same = ca == cb and last(oa) == last(ob)
                verdict = "same refusal" if same else f"exit {ca}/{cb}: {last(oa)!r} / {last(ob)!r}"
            else:
                files_a = sorted(p.name for p in da.iterdir())
                files_b = sorted(p.name for p in db.iterdir())
                diffs = [] if files_a == files_b else [f"files {files_a} vs {files_b}"]
                diffs += [f"{n}: {d}" for n in files_a if n in files_b for d in [compare(da / n, db / n, fmt)] if d]
                if findings(oa) != findings(ob):
                    diffs.append(f"findings {sorted(findings(oa) ^ findings(ob))}")
                same = not diffs
                verdict = "identical" if same else "; ".join(diffs)
            bad += not same
            print(f"{sample.stem:22s} {fmt:6s} {verdict}", flush=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
