// Read LightBurn projects with lbrnts (npm) and print what it found in each as a line of JSON:
// node lbrnts_read.mjs FILE.lbrn2 ...   (run from a folder whose node_modules holds lbrnts)
import fs from "node:fs"
import { createRequire } from "node:module"
import path from "node:path"

const require = createRequire(path.join(process.cwd(), "index.js"))
const { LightBurnProject, CutSetting, ShapePath, ShapeGroup } = await import(require.resolve("lbrnts"))

for (const file of process.argv.slice(2)) {
  const project = LightBurnProject.parse(fs.readFileSync(file, "utf8"))
  const cuts = project.children.filter((c) => c instanceof CutSetting).map((c) => ({
    index: c.index, name: c.name, type: c.type, speed: c.speed, maxPower: c.maxPower,
    numPasses: c.numPasses, priority: c.priority, interval: c.interval,
  }))
  const shapes = []
  const walk = (list) => {
    for (const s of list) {
      if (s instanceof ShapePath) shapes.push({
        cutIndex: s.cutIndex, closed: s.isClosed, vertices: s.verts.length,
        // the vertices with their handles and the primitives' kinds (0 line, 1 Bezier), as lbrnts read them
        verts: s.verts.map((v) => [v.x, v.y, v.c0x ?? null, v.c0y ?? null, v.c1x ?? null, v.c1y ?? null]),
        prims: s.prims.map((p) => p.type),
      })
      if (s instanceof ShapeGroup) walk(s.children)
    }
  }
  walk(project.children)
  console.log(JSON.stringify({ formatVersion: project.formatVersion, cuts, shapes }))
}
