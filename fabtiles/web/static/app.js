// fabtiles web page: controls -> URL query -> /api/preview.svg, /api/checks, /api/export/*.
"use strict";

// The form's sliders, text boxes and check boxes, and the choices of its menus, come from the schema
// of the design keys (/api/schema, fabtiles/core/schema.py): filled in by applySchema() before the form is built.
let SLIDERS = {};
const state = {
  preset: "table3-3", n: 12, radii: [123, 85, 178], alpha: 23, spr: -7, special: 2, rotation: 0,
  packing: "hex", radius: 15, gap_n: 6, gap_inner: 0.5, outline_circles: false,
  gap_rotation: 0, gap_rosette: false, gap_alpha: 20, gap_spr: 0.2,  // the gap motif (radii inner, 1): a rosette
  // when gap_rosette (special circle 2), sent only then; its rotation only when not 0
  girih_pattern: "decagon-bowtie", girih_level: "",  // packing=girih: the pattern of girih tiles, its subdivision ("": 0)
  tiling: "4.8.8", edge: 20, motifs: {},  // packing=archimedean: motifs[sides] = preset ("" = the motif above)
  method: "motifs", contact_angle: 60, contact_gap: 0,  // method=hankin: Hankin's rays ("" motif: the rays)
  // a parquet deformation (the page's box "vary across the tile"): the angle at the far side, across which, how
  parquet: false, contact_angle_to: 75, parquet_direction: "x", parquet_curve: "linear",
  outline: "square", width: 150, height: 150, frame: 5, stroke: 1, corner_radius: 0, join: "miter",
  laser_profile: "laser-3mm-plywood", laser_mode: "pierced", printer_profile: "fdm-0.4mm", print_style: "relief",
  threemf_layout: "volumes",  // 3MF parts for PrusaSlicer, Bambu Studio, OrcaSlicer; "components" for Cura
  inlay_base: "pierced", inlay_fit_mm: "", inlay_pieces: "registration",  // laser_mode=inlay: the kit's lattice and fit ("": the profile's)
  tab_mm: "", tabs_per_part: "",  // holding tabs in each part's outer cut ("": none; 4 per part)
  miter_limit: 4, seamless: false, fill_small_holes: true, name: "",
  base_mm: "", relief_mm: "", pierced_mm: "", deboss_mm: "",  // "": the printer profile's
  interlace: false, interlace_gap_mm: "", interlace_cut: false,  // woven strands; "": a third of the stroke
  border_mm: 0, border_motif: "stars", border_angle: "",  // a frieze round the field (0: none; "": 67.5 or the contact angle)
  inlay: false,  // deboss: the 3MF gets a second part filling the grooves
  mosaic_inset_mm: "",  // mosaic: the faces below the bands ("": flush)
  colour_by: "none", palette: "zellige",  // the [colour] section: faces classed by shape, the palette
  band_colour: "", base_colour: "",  // "": the palette's
  faces: {},  // [colour.faces]: faces[letter] = colour (face_<letter>), the others the palette's
  shaded: "",  // [colour] shaded: the classes a laser engraves in shades ("": none)
  // [surface]: a flat tile, or a cylinder (the sample roller's size) whose tile is its unrolled strip;
  // mirror "": the print style's (a roller's), the text boxes "": the style's defaults
  shape: "flat", diameter: 60, length: 80, fit: "packing", mirror: "", bore_mm: "", rim_mm: "", lamp_fitting_mm: "",
  pointed_tops: false,  // a cylinder's openings pointed at the printer's overhang limit
  block_mm: "", grip_mm: "", groove_mm: "",  // a stamp's block and finger groove ("": the defaults)
};
// Options sent only when set: the schema's text and number boxes, and its check boxes (gap_rosette and
// parquet are the page's own: the gap motif as a rosette; the contact angle varying across the tile).
// MENUS: the schema's menus but the motif's (preset, special circle) and the tiling's, which have their own code.
let TEXT_KEYS = [], FLAG_KEYS = ["gap_rosette", "parquet"], MENUS = [];
// COLOUR_KEYS: the schema's colour pickers (the band's and the base's); sent only when chosen.
let COLOUR_KEYS = [];
// SURFACE_KEYS: the [surface] keys but the shape, each sent only where its condition holds (a cylinder's, a
// stamp's; the tile's outline, size and frame not for a cylinder: query()); UNMADE: per shape, the formats it is not made in and why (the schema's).
let SURFACE_KEYS = [], UNMADE = {};
const OWN_MENUS = new Set(["preset", "special", "tiling"]);
// WHEN: each control's condition (the schema's widget.when: [parameter, values] pairs, all to hold);
// RADII: the slider of each radius (the schema's widget of the radii list).
let WHEN = {}, RADII = { min: 0.05, max: 400, step: 0.05 };
let showFindings = true, chosen = null;  // the findings overlay; the finding chosen in the list
let presets = {}, tilings = {};
// The design as loaded or last chosen in the Preset menu, and its name (a preset, or a gallery entry's):
// the menu shows that name and the downloads are named after it while the design is as it was; any edit
// makes it "custom", and setting the values back brings the name back.
const EDITED = "custom";
let origin = { label: "table3-3", q: "", gallery: false };

function $(id) { return document.getElementById(id); }

function slider(container, key, label, min, max, step) {
  const row = document.createElement("label");
  row.className = "row";
  row.id = `${key}-row`;
  row.innerHTML = `<span>${label}</span><input type="range" min="${min}" max="${max}" step="${step}"
     id="${key}-range"><input type="number" step="${step}" id="${key}" name="${key}">`;
  container.appendChild(row);
  const err = document.createElement("div");
  err.className = "err";
  err.dataset.for = key === "gap_inner" ? "gap_radii" : key;
  container.appendChild(err);
  const range = row.querySelector("input[type=range]"), box = row.querySelector("input[type=number]");
  const set = (v) => { travel(range, v); range.value = v; box.value = v; };
  set(state[key]);
  const changed = (v) => {
    state[key] = Number(v);
    set(v);
    if (SLIDERS["motif-sliders"].some(([k]) => k === key)) state.preset = "";  // the motif's own now
    update();
  };
  range.addEventListener("input", () => changed(range.value));
  box.addEventListener("change", () => changed(box.value));
}

// A value outside a slider's travel (typed in its box, or from a link) widens the travel instead of
// pinning the slider at an end.
function travel(range, v) {
  const x = Number(v);
  if (!Number.isFinite(x)) return;
  if (x < Number(range.min)) range.min = x;
  if (x > Number(range.max)) range.max = x;
}

function radiiSliders() {
  const box = $("radii-sliders");
  box.innerHTML = "";
  state.radii.forEach((r, k) => {
    const row = document.createElement("label");
    row.className = "row";
    row.innerHTML = `<span>r${k + 1}</span><input type="range" min="${RADII.min}" max="${RADII.max}"
       step="${RADII.step}" id="r${k + 1}-range"><input type="number" step="any" min="0" id="r${k + 1}">`;
    box.appendChild(row);
    const range = row.querySelector("input[type=range]"), num = row.querySelector("input[type=number]");
    travel(range, r); range.value = r; num.value = r;
    const changed = (v) => {
      state.radii[k] = Number(v); travel(range, v); range.value = v; num.value = v; state.preset = ""; update();
    };
    range.addEventListener("input", () => changed(range.value));
    num.addEventListener("change", () => changed(num.value));
  });
  $("circles").value = state.radii.length;
  const sp = $("special"), keep = state.special;
  sp.innerHTML = '<option value="">none (a star)</option>';
  for (let w = 2; w <= state.radii.length; w++) sp.add(new Option(`circle ${w}`, String(w)));
  sp.value = keep && keep <= state.radii.length ? String(keep) : "";
}

function query() {
  const q = new URLSearchParams();
  if (state.preset) {
    q.set("preset", state.preset);
    if (state.rotation) q.set("rotation", state.rotation);
  } else {
    q.set("n", state.n);
    q.set("radii", state.radii.join(","));
    q.set("alpha", state.alpha);
    q.set("spr", state.spr);
    q.set("special", state.special || "none");
    q.set("rotation", state.rotation);
  }
  q.set("packing", state.packing);
  if (state.packing === "girih") {  // the tiles' strapwork: no circles, no gap motif
    q.set("girih_pattern", state.girih_pattern);
    q.set("edge", state.edge);
    if (state.seamless) q.set("seamless", "true");
  } else if (state.packing !== "none") {
    if (state.packing === "archimedean") {
      q.set("tiling", state.tiling);
      q.set("edge", state.edge);
      if (state.method === "hankin") {  // the paper's method is the default: its queries stay as they were
        q.set("method", state.method);
        q.set("contact_angle", state.contact_angle);
        if (Number(state.contact_gap)) q.set("contact_gap", state.contact_gap);
        if (state.parquet && applies("parquet")) {  // a parquet deformation, where the tile need not repeat
          q.set("contact_angle_to", state.contact_angle_to);
          q.set("parquet_direction", state.parquet_direction);
          q.set("parquet_curve", state.parquet_curve);
        }
      }
      for (const p of (tilings[state.tiling] || { kinds: [] }).kinds)
        if (state.motifs[p]) q.set(`motif_${p}`, state.motifs[p]);
    } else q.set("radius", state.radius);
    q.set("gap_n", state.gap_n);
    q.set("gap_radii", `${state.gap_inner},1`);
    if (state.gap_rotation) q.set("gap_rotation", state.gap_rotation);
    if (state.gap_rosette) {
      q.set("gap_special", 2);
      q.set("gap_alpha", state.gap_alpha);
      q.set("gap_spr", state.gap_spr);
    }
    q.set("outline_circles", state.outline_circles ? "true" : "false");
    if (state.seamless) q.set("seamless", "true");
  }
  const cylinder = state.shape === "cylinder";
  if (cylinder) {  // its tile is its unrolled strip: the diameter and length size it, no outline or frame
    q.set("shape", state.shape);
    q.set("diameter", state.diameter);
    q.set("length", state.length);
    if (state.fit !== "packing") q.set("fit", state.fit);
    if (state.mirror !== "") q.set("mirror", state.mirror);
    if (state.pointed_tops) q.set("pointed_tops", "true");
  } else {
    if (state.shape === "stamp") {  // a stamp keeps the tile's outline, size and frame
      q.set("shape", state.shape);
      if (state.mirror !== "") q.set("mirror", state.mirror);
    }
    q.set("outline", state.outline);
    q.set("width", state.width);
    if (state.outline === "rectangle") q.set("height", state.height);
    q.set("frame", state.frame);
    q.set("corner_radius", state.corner_radius);
    if (Number(state.border_mm)) {  // no border is the default: its queries stay as they were
      q.set("border_mm", state.border_mm);
      if (state.border_motif !== "stars") q.set("border_motif", state.border_motif);
    }
  }
  for (const k of ["stroke", "join", "laser_profile", "laser_mode",
                   "printer_profile", "print_style", "colour_by", "palette"]) q.set(k, state[k]);
  for (const k of COLOUR_KEYS) if (state[k]) q.set(k, state[k]);
  for (const [letter, colour] of Object.entries(state.faces)) if (colour) q.set(`face_${letter}`, colour);
  if (state.miter_limit !== 4) q.set("miter_limit", state.miter_limit);
  if (state.interlace) q.set("interlace", "true");
  if (state.interlace_cut) q.set("interlace_cut", "true");
  if (state.inlay) q.set("inlay", "true");
  if (state.threemf_layout !== "volumes") q.set("threemf_layout", state.threemf_layout);
  if (state.laser_mode === "inlay" && state.inlay_base !== "pierced") q.set("inlay_base", state.inlay_base);
  if (state.laser_mode === "inlay" && state.inlay_pieces !== "registration") q.set("inlay_pieces", state.inlay_pieces);
  q.set("fill_small_holes", state.fill_small_holes ? "true" : "false");
  for (const k of TEXT_KEYS) {  // a surface's or a packing's own box only where its condition holds
    const own = SURFACE_KEYS.includes(k) || (WHEN[k] || []).some(([param]) => param === "packing");
    if (String(state[k]).trim() !== "" && (!own || applies(k))) q.set(k, String(state[k]).trim());
  }
  return q;
}

function fromUrl() {
  const q = new URLSearchParams(location.search);
  if (![...q.keys()].length) return;
  for (const [k, v] of q) {
    if (k === "gallery") origin = { label: v, q: "", gallery: true };  // the page's own: opened from the gallery
    else if (k === "radii") state.radii = v.split(",").map(Number);
    else if (k === "gap_radii") state.gap_inner = Number(v.split(",")[0]);
    else if (k === "gap_special") state.gap_rosette = v !== "none" && v !== "";
    else if (k === "special") state.special = v === "none" || v === "" ? 0 : Number(v);
    else if (k.startsWith("motif_")) state.motifs[k.slice(6)] = v;
    else if (k.startsWith("face_")) state.faces[k.slice(5)] = v;
    else if (k === "outline_circles" || FLAG_KEYS.includes(k)) state[k] = v === "true";
    else if (TEXT_KEYS.includes(k)) state[k] = v;
    else if (k in state) state[k] = typeof state[k] === "number" ? Number(v) : v;
  }
  if (!q.has("preset")) state.preset = "";
  if (q.has("preset")) applyPreset(state.preset, false);
  state.parquet = q.has("contact_angle_to");  // the page's box: ticked by a link with a far-side angle
  if (!origin.gallery) origin.label = state.preset && !q.has("n") && !q.has("radii") ? state.preset : EDITED;
}

// The design's query without its file name (a name is no edit of the design).
function designKey() {
  const q = query();
  q.delete("name");
  return String(q);
}

// The design's name: the preset or gallery entry it was opened as, while it is as it was; else "custom".
function designLabel() { return designKey() === origin.q ? origin.label : EDITED; }

function remember(label, gallery = false) { origin = { label, q: designKey(), gallery }; }

// The Preset menu: the design's name while unedited (a gallery entry's too), "custom" once edited.
function showLabel() {
  const label = designLabel(), sel = $("preset");
  let own = sel.querySelector("option[data-gallery]");
  if (origin.gallery && !own) {
    own = new Option(`${origin.label} (gallery)`, `gallery:${origin.label}`);
    own.dataset.gallery = "1";
    own.disabled = true;  // shown, not chosen: the gallery page opens its entries
    sel.add(own, 1);
  }
  sel.value = label === EDITED ? "" : origin.gallery ? `gallery:${label}` : label;
  sel.dataset.label = label;
}

// Whether a control applies to the state: its conditions (the schema's widget.when) all hold.
function applies(key) {
  return (WHEN[key] || []).every(([param, values]) => values.includes(String(state[param])));
}

// Each control shown only where it applies (the schema's conditions): a rectangle's height, the kit's fit...
function applyWhen() {
  $("surface-note").hidden = state.shape !== "cylinder";
  for (const key of Object.keys(WHEN)) {
    const on = applies(key);
    const control = $(`${key}-row`) || ($(key) && $(key).closest(".row"));
    if (control) control.hidden = !on;
    for (const err of document.querySelectorAll(`.err[data-for="${key}"]`)) err.hidden = !on;
  }
}

function applyPreset(name, redraw = true) {
  const p = presets[name];
  if (!p) return;
  Object.assign(state, { preset: name, n: p.n, radii: [...p.radii], alpha: p.alpha, spr: p.spr,
                         special: p.special || 0 });
  if (redraw) syncControls();
}

function syncControls() {
  for (const group of Object.values(SLIDERS)) for (const [key] of group) {
    $(key).value = state[key]; $(`${key}-range`).value = state[key];
  }
  for (const key of MENUS) $(key).value = state[key];
  $("preset").value = state.preset;
  $("tiling").value = state.tiling;
  tilingControls();
  $("outline_circles").checked = state.outline_circles;
  for (const k of FLAG_KEYS) $(k).checked = state[k];
  for (const k of TEXT_KEYS) $(k).value = state[k];
  radiiSliders();
  showColours();
  applyWhen();
}

let timer = null, seq = 0;
function update() {
  applyWhen();
  showLabel();
  clearTimeout(timer);
  timer = setTimeout(refresh, 120);
}

function showError(field, message) {
  document.querySelectorAll(".err").forEach((e) => { e.textContent = ""; });
  document.querySelectorAll(".bad").forEach((e) => e.classList.remove("bad"));
  const status = $("status");
  status.className = message ? "error" : "";
  status.textContent = message ? `✗ ${message}` : "";
  downloads(!message);
  if (!message) return;
  let target = document.querySelector(`.err[data-for="${field}"]`);
  const row = $(field) && $(field).closest(".row");
  if (!target && row) {  // a control with no place for its error yet: one under its row
    target = document.createElement("div");
    target.className = "err";
    target.dataset.for = field;
    row.after(target);
  }
  if (target) { target.hidden = false; target.textContent = message; }
  const control = $(field) || $(`${field}-range`) || (field === "radii" ? $("radii-sliders") : null);
  if (control) control.classList.add("bad");
}

// The download links of the design: named after it (its File name, else its preset or gallery entry, else
// "custom"), and disabled (no link) while the design is invalid, so no button fetches an error.
function downloads(valid) {
  const q = query(), label = designLabel(), name = String(state.name).trim() || label;
  if (!String(state.name).trim()) q.set("name", label);
  const kit = state.laser_mode === "inlay", unmade = UNMADE[state.shape] || {};
  for (const a of document.querySelectorAll("#downloads a")) {
    const fmt = a.dataset.format;
    if (valid && unmade[fmt]) {  // not made in this shape: no link, and the reason beside the buttons
      a.removeAttribute("href");
      a.removeAttribute("download");
      a.setAttribute("aria-disabled", "true");
      a.classList.add("disabled");
      a.title = unmade[fmt];
      continue;
    }
    if (valid) {
      a.href = fmt ? `/api/export/${fmt}?${q}` : `/api/design.toml?${q}`;
      a.download = !fmt ? `${name}.toml` : kit && a.dataset.family === "cut" ? `${name}-kit-${fmt}.zip` : `${name}${a.dataset.suffix}`;
    } else {
      a.removeAttribute("href");
      a.removeAttribute("download");
    }
    a.setAttribute("aria-disabled", valid ? "false" : "true");
    a.classList.toggle("disabled", !valid);
    a.title = valid ? "" : "fix the design first (see the message above)";
  }
  const reasons = [...new Set(Object.values(unmade))], note = $("unmade");
  note.textContent = reasons.join("\n");
  note.hidden = !reasons.length;
}

async function refresh() {
  const q = query(), mine = ++seq, label = designLabel(), page = new URLSearchParams(q);
  if (label !== EDITED && origin.gallery) page.set("gallery", label);  // a shared link still names the entry
  history.replaceState(null, "", `?${page}`);
  $("nest-link").href = `/nest?${page}`;  // the nest page starts from this design
  downloads(false);  // until the server says the design is good
  // The face classes' list: awaited only when a class colour is chosen that the new design may lack
  // (it is dropped then, and the preview asked for without it).
  const faces = refreshFaces();
  if (Object.keys(state.faces).some((k) => k !== "A") && await faces && mine === seq) { refresh(); return; }
  const res = await fetch(`/api/preview.svg?${q}${showFindings ? "&findings=true" : ""}`);
  if (mine !== seq) return;
  if (!res.ok) {
    const body = await res.json().catch(() => ({ error: res.statusText, field: null }));
    showError(body.field, body.error);
    notShown(body.error);
    return;
  }
  const svg = await res.text();
  const nowColoured = res.headers.get("X-Fabtiles-Coloured") === "true";
  if (nowColoured !== coloured) { coloured = nowColoured; showColours(); }
  $("preview").src = "data:image/svg+xml;charset=utf-8," + encodeURIComponent(svg);
  $("preview").hidden = false;
  $("preview-error").hidden = true;
  showMarks(svg);
  $("preview").dataset.version = String(mine);
  showError(null, "");
  window.fabtilesDesign = String(q);  // the 3D view (view3d.js) follows every good design
  window.fabtilesInvalid = null;
  document.dispatchEvent(new CustomEvent("fabtiles:design", { detail: String(q) }));
  const kit = state.laser_mode === "inlay";
  $("kit-box").hidden = !kit;
  if (kit) $("kit").src = `/api/kit.svg?${q}`;
  const checks = await fetch(`/api/checks?${q}`);
  if (mine !== seq || !checks.ok) return;
  const data = await checks.json();
  const list = $("checks");
  list.innerHTML = "";
  const items = data.findings || [];
  if (!items.length) list.innerHTML = '<li class="ok">✓ no problems found</li>';
  for (const f of items) {
    const li = document.createElement("li");
    li.textContent = `${f.where ? f.where + ": " : ""}${f.code}: ${f.message}`;
    li.dataset.code = f.code;
    li.dataset.where = f.where;
    li.tabIndex = 0;
    li.title = "show where";
    li.addEventListener("click", () => choose(li));
    li.addEventListener("keydown", (e) => { if (e.key === "Enter" || e.key === " ") choose(li); });
    list.appendChild(li);
  }
  const again = chosen && list.querySelector(`li[data-code="${chosen.code}"][data-where="${chosen.where}"]`);
  if (again) choose(again, true); else chosen = null;
  $("status").textContent = [data.summary || "", ...(data.pieces || []), ...(data.fitted || []), data.cylinder || ""]
    .filter(Boolean).join("; ");
  const cutter = (data.cutter || "laser").replace(/^./, (c) => c.toUpperCase());
  $("job").textContent = data.job ? `${cutter} job (estimate from the profile): ${data.job.line}` : "";
  $("material").textContent = data.material
    ? `Print material: ${data.material.line} (the print time is the slicer's to tell)` : "";
  $("job").dataset.version = String(mine);
}

// An invalid design: what is wrong, said where the picture, the 3D view and the checks would be (the
// picture of the last good design stays, under the message; before any, there is none to show).
function notShown(message) {
  const note = $("preview-error");
  note.textContent = `${$("preview").getAttribute("src") ? "Not updated" : "No picture"}: ${message}`;
  note.hidden = false;
  if (!$("preview").getAttribute("src")) $("preview").hidden = true;
  const li = document.createElement("li");
  li.className = "error";
  li.textContent = `Not checked: ${message}`;
  $("checks").replaceChildren(li);
  $("job").textContent = "";
  $("material").textContent = "";
  window.fabtilesInvalid = message;  // for the 3D view, if its module loads after this
  document.dispatchEvent(new CustomEvent("fabtiles:invalid", { detail: message }));
}

// The marks of the preview's findings, copied into #marks (an SVG laid over the
// picture with the same viewBox), where choosing a finding can highlight them.
function showMarks(svgText) {
  const marks = $("marks");
  marks.innerHTML = "";
  if (!showFindings) return;
  const doc = new DOMParser().parseFromString(svgText, "image/svg+xml");
  const root = doc.documentElement, group = doc.querySelector("g.findings");
  marks.setAttribute("viewBox", root.getAttribute("viewBox"));
  if (group) marks.appendChild(document.importNode(group, true));
  highlight();
}

function highlight() {
  for (const m of $("marks").querySelectorAll(".finding")) {
    const on = chosen && m.classList.contains(chosen.code) && m.dataset.where === chosen.where;
    m.classList.toggle("hl", Boolean(on));
  }
  $("marks").classList.toggle("choosing", Boolean(chosen));
}

function choose(li, keep = false) {
  const same = chosen && chosen.code === li.dataset.code && chosen.where === li.dataset.where;
  chosen = same && !keep ? null : { code: li.dataset.code, where: li.dataset.where };
  for (const item of $("checks").querySelectorAll("li")) item.classList.toggle("chosen", item === li && Boolean(chosen));
  highlight();
}

// The colours: the face classes of the design (/api/faces) and the pickers of the band, the base and each
// class. The classes and the palette's colours do not depend on the colours chosen, so the list is asked
// for without them, and again only when something else changes.
let facesInfo = null, facesKey = null, facesSeq = 0;
// Whether the pictures are in the design's colours (the preview says so); else they show the plain ink
// and plate, and so do the pickers.
let coloured = false;

function classesQuery() {
  const q = query();
  for (const k of [...q.keys()]) if (k === "name" || COLOUR_KEYS.includes(k) || k.startsWith("face_")) q.delete(k);
  return q;
}

// Fetch the classes if the design changed; true when a chosen class colour was dropped (its class is gone).
async function refreshFaces() {
  const q = classesQuery(), key = String(q);
  if (key === facesKey) return false;
  const mine = ++facesSeq, res = await fetch(`/api/faces?${q}`);
  if (mine !== facesSeq || !res.ok) return false;  // a newer design's list is coming; a bad design is the preview's to show
  facesInfo = await res.json();
  facesKey = key;
  const letters = new Set(facesInfo.classes.map((c) => c.letter));
  const gone = Object.keys(state.faces).filter((k) => !letters.has(k));
  for (const k of gone) delete state.faces[k];
  showColours();
  return gone.length > 0;
}

// A colour as #rrggbb, what a colour picker takes (a link may give a name: a palette's, read in the design's
// palette first as the server reads it, else CSS's: "navy").
function hexOf(colour) {
  const named = facesInfo && facesInfo.names && facesInfo.names[String(colour).trim().toLowerCase()];
  if (named) return named;
  const ctx = document.createElement("canvas").getContext("2d");
  ctx.fillStyle = "#000000";
  ctx.fillStyle = colour;
  return ctx.fillStyle;
}

// The pickers show the colour chosen, else the palette's; each "palette's" button is enabled once a colour is chosen.
function showColours() {
  const palettes = facesInfo || { band: { colour: "#ffffff" }, base: { colour: "#000000" }, classes: [] };
  const plain = !coloured && palettes.plain;  // no colours given: what the pictures show
  for (const k of COLOUR_KEYS) {
    const own = plain ? plain[k.replace("_colour", "")] : palettes[k.replace("_colour", "")];
    $(k).value = state[k] ? hexOf(state[k]) : own ? own.colour : "#000000";
    document.querySelector(`.reset[data-reset="${k}"]`).disabled = !state[k];
  }
  const box = $("face-classes");
  box.innerHTML = "";
  for (const c of palettes.classes) {
    const chosen = state.faces[c.letter], colour = chosen ? hexOf(chosen) : plain ? plain.face.colour : c.colour;
    const row = document.createElement("div");
    row.className = "face-row";
    row.dataset.letter = c.letter;
    const swatch = document.createElement("span"), letter = document.createElement("span");
    const what = document.createElement("span");
    swatch.className = "swatch";
    swatch.style.background = colour;
    letter.className = "letter";
    letter.textContent = c.letter;
    what.className = "what";
    const count = c.count.toLocaleString("en");  // a shape with no plain name: its count alone
    what.textContent = c.description ? `${count} × ${c.description}` : `${count} faces`;
    what.title = `${Math.round(c.area_mm2).toLocaleString("en")} mm² in all; the palette's colour: ${c.name}`;
    row.append(swatch, letter, what);
    if (/^[A-Z]$/.test(c.letter)) {  // the page's parameters are face_A ... face_Z; a design file takes more
      const picker = document.createElement("input"), reset = document.createElement("button");
      picker.type = "color";
      picker.id = `face_${c.letter}`;
      picker.value = colour;
      picker.title = `the colour of class ${c.letter}`;
      picker.addEventListener("input", () => {
        state.faces[c.letter] = picker.value;
        swatch.style.background = picker.value;
        reset.disabled = false;
        update();
      });
      reset.type = "button";
      reset.className = "reset";
      reset.textContent = "palette's";
      reset.title = "back to the palette's colour";
      reset.disabled = !chosen;
      reset.addEventListener("click", () => { delete state.faces[c.letter]; showColours(); update(); });
      row.append(picker, reset);
    }
    box.appendChild(row);
  }
}

// packing=archimedean: the tiling menu, a motif menu per polygon kind, edge instead of radius.
function tilingControls() {
  const arch = state.packing === "archimedean", hankin = state.method === "hankin";
  $("tiling-controls").hidden = !arch;
  // Hankin's rays take no [motif] (the per-kind menus name presets); girih tiles draw their strapwork
  $("motif-box").hidden = (arch && hankin) || state.packing === "girih";
  $("kind-motifs-note").textContent = hankin
    ? "Each polygon takes Hankin's rays, or a preset per polygon kind in its incircle."
    : "Each polygon's incircle holds a motif: the one above, or a preset per polygon kind.";
  const box = $("kind-motifs");
  box.innerHTML = "";
  for (const p of arch && tilings[state.tiling] ? tilings[state.tiling].kinds : []) {
    const row = document.createElement("label");
    row.className = "row";
    row.innerHTML = `<span>${p}-gons</span><select id="motif_${p}" name="motif_${p}"></select>`;
    box.appendChild(row);
    const err = document.createElement("div");
    err.className = "err";
    err.dataset.for = `motif_${p}`;
    box.appendChild(err);
    const sel = row.querySelector("select");
    sel.add(new Option(hankin ? "Hankin's rays" : "the motif above", ""));
    for (const name of Object.keys(presets)) sel.add(new Option(name, name));
    sel.value = state.motifs[p] || "";
    sel.addEventListener("change", () => { state.motifs[p] = sel.value; update(); });
  }
}

// The download buttons: one per format the format table offers (a format plugin's too), before the design's.
function formatButtons(formats) {
  const design = $("download-design");
  for (const f of formats) {
    const a = document.createElement("a");
    a.className = "btn";
    Object.assign(a.dataset, { format: f.name, family: f.family, suffix: f.suffix });
    a.textContent = f.label;
    design.before(a);
  }
}

// The schema's widgets: sliders by group (the gap motif's inner radius after gap n), the text, number and
// check boxes, each number box's range and step, and each empty menu's choices; the download buttons.
function applySchema(schema) {
  formatButtons(schema.formats);
  UNMADE = schema.unmade || {};
  SLIDERS = {};
  for (const [q, f] of Object.entries(schema.fields)) {
    const w = f.widget;
    if (!w) continue;
    if (f.key.startsWith("surface.") && q !== "shape") SURFACE_KEYS.push(q);
    if (w.when && w.when.length) WHEN[q] = w.when;
    // the page's box "vary across the tile" applies where its controls would but for itself
    if ((w.when || []).some(([param]) => param === "parquet")) WHEN.parquet = w.when.filter(([param]) => param !== "parquet");
    if (w.kind === "slider" && f.type === "numbers") RADII = w;  // a slider per radius (radiiSliders)
    else if (w.kind === "slider") {
      (SLIDERS[w.group] = SLIDERS[w.group] || []).push([q, w.label, w.min, w.max, w.step]);
      if (q === "gap_n") {  // the gap motif's inner radius and its rosette box apply where its n does
        SLIDERS[w.group].push(["gap_inner", "gap inner r", 0.05, 1.5, 0.05]);
        WHEN.gap_inner = WHEN.gap_rosette = w.when;
      }
    } else if (w.kind === "checkbox") FLAG_KEYS.push(q);
    else if (w.kind === "colour") COLOUR_KEYS.push(q);
    else if (w.kind === "number" || w.kind === "text") {
      TEXT_KEYS.push(q);
      const box = $(q);
      if (box) for (const a of ["min", "max", "step", "placeholder"]) if (w[a] !== null && w[a] !== "") box.setAttribute(a, w[a]);
    } else if (w.kind === "select") {
      if (!OWN_MENUS.has(q)) MENUS.push(q);
      if (f.choices && $(q) && !$(q).options.length)
        for (const [value, label] of f.choices) $(q).add(new Option(label, value));
    }
  }
}

async function init() {
  presets = await (await fetch("/api/presets")).json();
  tilings = await (await fetch("/api/tilings")).json();
  for (const [t, info] of Object.entries(tilings)) $("tiling").add(new Option(`${t} (${info.name})`, t));
  const sel = $("preset");
  for (const name of Object.keys(presets)) sel.add(new Option(name, name));
  const profiles = await (await fetch("/api/profiles")).json();
  for (const n of profiles.laser) $("laser_profile").add(new Option(n, n));
  for (const n of profiles.printer) $("printer_profile").add(new Option(n, n));
  applySchema(await (await fetch("/api/schema")).json());
  fromUrl();
  for (const [box, list] of Object.entries(SLIDERS))
    for (const [key, label, min, max, step] of list) slider($(box), key, label, min, max, step);
  syncControls();
  sel.addEventListener("change", () => {
    if (sel.value) { applyPreset(sel.value); remember(sel.value); } else state.preset = "";
    update();
  });
  $("circles").addEventListener("change", () => {
    const s = Math.max(2, Math.min(8, Number($("circles").value) || 2));
    while (state.radii.length < s) state.radii.push(state.radii[state.radii.length - 1] + 20);
    state.radii.length = s;
    state.preset = "";
    radiiSliders();
    update();
  });
  $("special").addEventListener("change", () => { state.special = Number($("special").value) || 0; state.preset = ""; update(); });
  $("outline_circles").addEventListener("change", () => { state.outline_circles = $("outline_circles").checked; update(); });
  for (const k of FLAG_KEYS) $(k).addEventListener("change", () => { state[k] = $(k).checked; update(); });
  for (const k of TEXT_KEYS) $(k).addEventListener("change", () => { state[k] = $(k).value; update(); });
  for (const k of COLOUR_KEYS) {
    $(k).addEventListener("input", () => {
      state[k] = $(k).value;
      document.querySelector(`.reset[data-reset="${k}"]`).disabled = false;
      update();
    });
    document.querySelector(`.reset[data-reset="${k}"]`).addEventListener("click", () => {
      state[k] = "";
      showColours();
      update();
    });
  }
  $("show_findings").checked = showFindings;
  $("show_findings").addEventListener("change", () => { showFindings = $("show_findings").checked; update(); });
  for (const key of MENUS)
    $(key).addEventListener("change", () => { state[key] = $(key).value; update(); });
  for (const key of ["packing", "tiling"])
    $(key).addEventListener("change", () => { state[key] = $(key).value; tilingControls(); if (key === "tiling") update(); });
  // the method is a schema menu (its listener above sets it and redraws): the per-kind menus' captions follow it
  $("method").addEventListener("change", tilingControls);
  origin.q = designKey();
  showLabel();
  refresh();
}

// The pen plot (/api/plot.svg, fabtiles plot's SVG): drawn only while its box is open, for the
// design the page last drew well, with the box's pen, fill and cross-hatch.
let plotSeq = 0;
async function showPlot() {
  if (!$("plot-box").open || !window.fabtilesDesign) return;
  const q = new URLSearchParams(window.fabtilesDesign);
  q.set("pen_mm", $("plot-pen").value);
  if ($("plot-fill").checked) q.set("fill", "true");
  if ($("plot-cross").checked) q.set("cross", "true");
  const mine = ++plotSeq;
  $("plot-caption").textContent = "drawing…";
  const res = await fetch(`/api/plot.svg?${q}`);
  if (mine !== plotSeq) return;
  if (!res.ok) {
    const err = await res.json().catch(() => ({}));
    $("plot").hidden = true;
    $("plot-caption").textContent = "";
    $("plot-error").textContent = err.error || `the plot failed (${res.status})`;
    $("plot-error").hidden = false;
    return;
  }
  $("plot").src = "data:image/svg+xml;charset=utf-8," + encodeURIComponent(await res.text());
  $("plot").hidden = false;
  $("plot-error").hidden = true;
  $("plot-caption").textContent = `Pens (layer: strokes): ${res.headers.get("X-Fabtiles-Pens") || ""}`;
}
for (const id of ["plot-pen", "plot-fill", "plot-cross"]) $(id).addEventListener("change", showPlot);
$("plot-box").addEventListener("toggle", showPlot);
document.addEventListener("fabtiles:design", showPlot);

init();
