"""Latency of the web app's preview of a 150 mm tile (issue 7: under 150 ms; with the
findings overlay, issue 14: under 300 ms).

Run by hand: ``python benchmarks/bench_web.py``. It starts the app in-process with
Starlette's test client (no network), warms it up, then times repeated preview requests
for the default design (table3-3, R = 15 mm, 150 mm square) and a few variations.
"""

from __future__ import annotations

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


def main(repeat: int = 15) -> None:
    from fastapi.testclient import TestClient

    from fabtiles.web.app import create_app

    client = TestClient(create_app())
    client.get("/api/preview.svg")  # warm-up: imports and first build
    print(f"| preview | median ms | best ms | SVG kB |\n|---|---:|---:|---:|")
    for label, query in QUERIES.items():
        times = []
        for _ in range(repeat):
            t = time.perf_counter()
            r = client.get(f"/api/preview.svg?{query}")
            times.append((time.perf_counter() - t) * 1000)
            assert r.status_code == 200, r.text
        print(f"| {label} | {statistics.median(times):.0f} | {min(times):.0f} | {len(r.content) / 1000:.0f} |")


if __name__ == "__main__":
    main()
