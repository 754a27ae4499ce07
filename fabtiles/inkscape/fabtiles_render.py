#!/usr/bin/env python3
"""Extensions > Render > fabtiles: a fabtiles pattern inserted at true millimetres, one layer per laser layer.

Inkscape runs this script with its own python3 and the inkex it ships, not the Python
fabtiles is installed in: the script writes a design file of the dialog's values and asks
that Python (``FABTILES_PYTHON``, recorded by ``fabtiles install-inkscape-extension``) for
the laser SVG (``fabtiles build --format svg``), then moves each of its layer groups into
the document as an Inkscape layer of the same name, scaled so one millimetre is one
millimetre whatever the document's units. fabtiles' errors come back as Inkscape's error
message (one line, no traceback).
"""

import os
import subprocess
import sys
import tempfile

import inkex

FABTILES_PYTHON = sys.executable  # replaced at install time by the Python fabtiles is installed in

DESIGN = """[motif]
preset = "{preset}"

[packing]
kind = "{packing}"
radius = {radius!r}

[tile]
outline = "square"
size = [{size!r}, {size!r}]
frame = {frame!r}
stroke = {stroke!r}
"""


class FabtilesRender(inkex.EffectExtension):
    """The dialog's values (the README's sample by default) -> the pattern's laser layers."""

    def add_arguments(self, pars):
        pars.add_argument("--preset", default="table3-3")
        pars.add_argument("--packing", default="hex")
        pars.add_argument("--radius", type=float, default=12.5)
        pars.add_argument("--size", type=float, default=150.0)
        pars.add_argument("--stroke", type=float, default=1.0)
        pars.add_argument("--frame", type=float, default=5.0)

    def effect(self):
        o = self.options
        with tempfile.TemporaryDirectory() as tmp:
            design = os.path.join(tmp, "fabtiles.toml")
            with open(design, "w") as f:
                f.write(DESIGN.format(preset=o.preset.replace('"', ""), packing=o.packing, radius=o.radius,
                                      size=o.size, frame=o.frame, stroke=o.stroke))
            res = subprocess.run([FABTILES_PYTHON, "-m", "fabtiles", "build", design, "-o", tmp, "--format", "svg"],
                                 capture_output=True, text=True)
            if res.returncode != 0:
                lines = [x for x in res.stderr.splitlines() if x.strip()]
                raise inkex.AbortExtension(lines[-1] if lines else f"fabtiles failed (exit status {res.returncode})")
            laser = inkex.load_svg(os.path.join(tmp, "fabtiles.svg")).getroot()
        mm = self.svg.unittouu("1mm")
        # the laser SVG's viewBox starts at (xmin, -ymax) (its y flipped): moved to the page's corner
        vx, vy = (float(v) for v in laser.get("viewBox").split()[:2])
        for group in list(laser):
            if group.tag != inkex.addNS("g", "svg"):
                continue
            layer = self.svg.add(inkex.Layer.new(group.get("id")))
            layer.set("id", self.svg.get_unique_id("fabtiles-" + group.get("id")))
            layer.set("transform", f"scale({mm!r}) translate({-vx!r}, {-vy!r})")
            for attr in ("fill", "fill-rule", "stroke", "stroke-width"):
                if group.get(attr) is not None:
                    layer.set(attr, group.get(attr))
            for child in list(group):
                layer.append(child)


if __name__ == "__main__":
    FabtilesRender().run()
