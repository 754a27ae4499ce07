"""Latency of the web app's preview of a 150 mm tile (issue 7: under 150 ms; with the
findings overlay, issue 14: under 300 ms), its 3D view's data (issue 25: under 500 ms for the
150 mm default tile, a few MB at most) and its checks with the job and material figures.

Run by hand: ``python benchmarks/bench_web.py``. It starts the app in-process with
Starlette's test client (no network), warms it up, then times repeated preview requests
for the default design (table3-3, R = 15 mm, 150 mm square) and a few variations.
"""

from __future__ import annotations

import json
import statistics
import time
import warnings

warnings.simplefilter("ignore", DeprecationWarning)

QUERIES = {
    "default 150 mm square": "",
    "rosette, one motif": "preset=table2-left&packing=none&outline=circle&width=150",
    "R = 10 mm, round joins": "radius=10&join=round",
    "outline circles": "outline_circles=true",
    "default, findings overlay (filled: clean)": "findings=true",
    "default, findings overlay (not filled: 692 marks)": "findings=true&fill_small_holes=false",
    "R = 10 mm, round joins, findings overlay": "radius=10&join=round&findings=true",
}

VIEWS = {
    "default 150 mm square, relief": "",
    "default, interlaced relief (dips)": "interlace=true",
    "default, deboss with inlay": "print_style=deboss&inlay=true",
    "300 mm square (its centre)": "width=300",
    "600 x 400 mm (a lighter preview: its centre)": "outline=rectangle&width=600&height=400",
}


def main(repeat: int = 15) -> None:
    from fastapi.testclient import TestClient

    from fabtiles.web.app import create_app

    client = TestClient(create_app())
    client.get("/api/preview.svg")  # warm-up: imports and first build
    print("| preview | median ms | best ms | SVG kB |\n|---|---:|---:|---:|")
    for label, query in QUERIES.items():
        times = []
        for _ in range(repeat):
            t = time.perf_counter()
            r = client.get(f"/api/preview.svg?{query}")
            times.append((time.perf_counter() - t) * 1000)
            assert r.status_code == 200, r.text
        print(f"| {label} | {statistics.median(times):.0f} | {min(times):.0f} | {len(r.content) / 1000:.0f} |")
    print()
    print(
        "| 3D view (GET /api/view.glb) | median ms | best ms | GLB kB | triangles | shown |\n"
        "|---|---:|---:|---:|---:|---|"
    )
    for label, query in VIEWS.items():
        times = []
        for _ in range(max(3, repeat // 3)):
            t = time.perf_counter()
            r = client.get(f"/api/view.glb?{query}")
            times.append((time.perf_counter() - t) * 1000)
            assert r.status_code == 200, r.text
        triangles = sum(p["triangles"] for p in json.loads(r.headers["X-Fabtiles-Parts"]).values())
        print(
            f"| {label} | {statistics.median(times):.0f} | {min(times):.0f} | {len(r.content) / 1000:.0f} | "
            f"{triangles:,} | {r.headers['X-Fabtiles-View']} |"
        )
    print()
    print("| checks (GET /api/checks, job and material) | median ms | best ms |\n|---|---:|---:|")
    for label, query in {"default 150 mm square": ""}.items():
        times = []
        for _ in range(max(3, repeat // 3)):
            t = time.perf_counter()
            assert client.get(f"/api/checks?{query}").status_code == 200
            times.append((time.perf_counter() - t) * 1000)
        print(f"| {label} | {statistics.median(times):.0f} | {min(times):.0f} |")


if __name__ == "__main__":
    main()
