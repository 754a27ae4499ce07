"""Benchmark: nesting (issue 34), 30 tiles of three designs on 600 x 400 mm sheets.

Ten each of table3-1 in a 100 mm square, table3-2 in a 100 mm hexagon and table3-3 in a
100 mm circle (frame 4 mm), each part its outer cut path (kerf 0.15 mm included), a gap of
1.15 mm (the kerf + 1 mm, ``fabtiles nest``'s default). Sheets used and material use
(the parts' area over the sheets') of:

- ``fabtiles nest`` (:func:`fabtiles.geometry.nest.nest`: Sparrow through spyrrow), quarter
  turns, at time budgets up to the default;
- a bounding-box packing: ``rectpack``'s max-rects (best short side fit), rotation allowed, the
  boxes grown by the gap;
- the grid of ``fabtiles build --sheet``, one design per sheet
  (:func:`fabtiles.geometry.sheet.layout_sheet`, as many as fit, the same gap).

Run by hand, never in CI::

    python benchmarks/bench_nest.py
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from fabtiles.designs.design_file import design_from_text  # noqa: E402 - after sys.path holds this checkout
from fabtiles.geometry.nest import DEFAULT_TIME_S, nest  # noqa: E402 - after sys.path holds this checkout
from fabtiles.geometry.sheet import layout_sheet  # noqa: E402 - after sys.path holds this checkout
from fabtiles.making import BuildOptions, Models, prepare_tile  # noqa: E402 - after sys.path holds this checkout
from fabtiles.making.nesting import part_outline  # noqa: E402 - after sys.path holds this checkout

SHEET = (600.0, 400.0)
COPIES = 10
DESIGNS = (("table3-1", "square"), ("table3-2", "hexagon"), ("table3-3", "circle"))


def parts():
    """The three designs' parts (outer cut paths), their tile outlines and the profile."""
    out = []
    for preset, outline in DESIGNS:
        d = design_from_text(
            f'[motif]\npreset = "{preset}"\n[packing]\nradius = 12.5\n[tile]\noutline = '
            f'"{outline}"\nsize = 100\nframe = 4.0\nstroke = 1.0\n',
            name=preset,
        )
        options = BuildOptions.of_design(d)
        tile = prepare_tile(d)
        plan = Models(tile, options).cut
        out.append((f"{preset} {outline}", part_outline(plan), tile.outline_shape(), options.cutter, plan.kerf_mm))
    return out


def use(areas_by_sheet):
    return " / ".join(f"{a / (SHEET[0] * SHEET[1]):.2f}" for a in areas_by_sheet)


def rectpack_sheets(shapes, gap):
    import rectpack

    packer = rectpack.newPacker(mode=rectpack.PackingMode.Offline, pack_algo=rectpack.MaxRectsBssf, rotation=True)
    for k, s in enumerate(shapes):
        x0, y0, x1, y1 = s.bounds
        packer.add_rect(x1 - x0 + gap, y1 - y0 + gap, rid=k)
    packer.add_bin(SHEET[0] + gap, SHEET[1] + gap, count=len(shapes))
    packer.pack()
    sheets: dict = {}
    for b, *_, rid in packer.rect_list():
        sheets.setdefault(b, 0.0)
        sheets[b] += shapes[rid].area
    assert sum(len(b) for b in packer) == len(shapes)
    return list(sheets.values())


def main():
    designs = parts()
    kerf = max(k for *_, k in designs)
    gap = kerf + 1.0
    shapes = [p for _, p, *_ in designs for _ in range(COPIES)]
    total = sum(s.area for s in shapes)
    print(f"30 parts, {total / 1e6:.3f} m^2 (a sheet is {SHEET[0] * SHEET[1] / 1e6:.2f} m^2), gap {gap:g} mm\n")
    print("| packing | time budget | wall s | sheets | material use per sheet |")
    print("|---|---:|---:|---:|---|")
    for budget in (2.0, DEFAULT_TIME_S):
        t0 = time.perf_counter()
        n = nest([(k, s) for k, s in enumerate(shapes)], sheet_mm=SHEET, gap_mm=gap, time_s=budget)
        wall = time.perf_counter() - t0
        print(
            f"| fabtiles nest (spyrrow), quarter turns | {budget:g} s | {wall:.1f} | {n.sheets} | "
            f"{' / '.join(f'{u:.2f}' for u in n.material_use())} |"
        )
    t0 = time.perf_counter()
    sheets = rectpack_sheets(shapes, gap)
    print(
        f"| bounding boxes, rectpack max-rects, turned | - | {time.perf_counter() - t0:.2f} | {len(sheets)} | "
        f"{use(sheets)} |"
    )
    grid = []
    for name, part, outline, profile, _ in designs:
        fit = len(layout_sheet([(outline, outline)], profile, gap_mm=gap, fill=True).offsets)
        full, rest = divmod(COPIES, fit)
        grid += [fit * part.area] * full + ([rest * part.area] if rest else [])
        print(f"<!-- {name}: {fit} per sheet in the grid -->", file=sys.stderr)
    print(f"| grid of --sheet, one design per sheet | - | - | {len(grid)} | {use(grid)} |")
    print(f"\nleast sheets by area alone: {math.ceil(total / (SHEET[0] * SHEET[1]))}")


if __name__ == "__main__":
    main()
