// The nest page: designs (the editor's queries) with counts, the sheet, gap, turns, time and format;
// POST /api/nest draws each sheet with its material use and links the sheets' files as one zip.
"use strict";

const $ = (id) => document.getElementById(id);
let designs = [];  // [{ name, query, count }]

// A design's name as the server names it: its name, its preset while unedited, else "custom".
function nameOf(q) {
  if (q.get("name")) return q.get("name");
  return q.get("preset") && !q.has("n") && !q.has("radii") ? q.get("preset") : q.toString() ? "custom" : "table3-3";
}

// The editor's link passes its own URL: a gallery entry (gallery=4.8.8, the page's, never the API's) names it.
function designQuery(search) {
  const q = new URLSearchParams(search);
  const entry = q.get("gallery");
  q.delete("gallery");
  if (entry && !q.get("name")) q.set("name", entry);
  return q;
}

function addDesign(q, count = 1) {
  designs.push({ name: nameOf(q), query: q.toString(), count });
  drawDesigns();
}

function drawDesigns() {
  const list = $("designs");
  list.innerHTML = "";
  designs.forEach((d, k) => {
    const li = document.createElement("li");
    const row = document.createElement("div"), name = document.createElement("a");
    row.className = "design-row";
    name.className = "design-name";
    name.textContent = d.name;
    name.href = `/?${d.query}`;
    name.title = `open in the editor: ${d.query || "the default design"}`;
    const count = document.createElement("input");
    Object.assign(count, { type: "number", min: 1, step: 1, value: d.count, id: `count-${k}` });
    count.setAttribute("aria-label", `copies of ${d.name}`);
    count.addEventListener("input", () => { d.count = count.value === "" ? NaN : Number(count.value); });
    const remove = document.createElement("button");
    Object.assign(remove, { type: "button", textContent: "remove", title: `remove ${d.name}` });
    remove.addEventListener("click", () => { designs.splice(k, 1); drawDesigns(); });
    const err = document.createElement("div");
    err.className = "err";
    err.dataset.for = `designs[${k}]`;
    row.append(name, count, remove);
    li.append(row, err);
    list.appendChild(li);
  });
}

async function gallery() {
  const sel = $("add-design");
  for (const e of await (await fetch("/api/gallery")).json())
    sel.add(new Option(e.title, new URLSearchParams({ name: e.key, ...e.query }).toString()));
  sel.addEventListener("change", () => {
    if (sel.value) addDesign(new URLSearchParams(sel.value));
    sel.value = "";
  });
}

function number(id) {
  const v = $(id).value.trim();
  return v === "" ? null : Number(v);
}

function body() {
  const w = number("sheet-w"), h = number("sheet-h");
  return {
    designs: designs.map((d) => ({ query: d.query, count: d.count })),
    sheet: w === null && h === null ? null : [w, h],
    gap_mm: number("gap_mm"),
    rotate: $("rotate").value,
    time_s: number("time_s") ?? 3,
    format: $("format").value,
  };
}

function clearErrors() {
  for (const e of document.querySelectorAll(".err")) e.textContent = "";
  for (const e of document.querySelectorAll(".bad")) e.classList.remove("bad");
  $("status").classList.remove("error");
}

// A 422's field: a design's (designs[1].count, designs[0].stroke) under its row, the others under their control.
function showError(field, message) {
  const design = /^designs\[(\d+)\](?:\.(\w+))?/.exec(field || "");
  const box = design ? document.querySelector(`.err[data-for="designs[${design[1]}]"]`)
    : document.querySelector(`.err[data-for="${field}"]`);
  if (box) box.textContent = message;
  const control = design && design[2] === "count" ? $(`count-${design[1]}`)
    : field === "sheet" ? $("sheet-w") : field ? $(field) : null;
  if (control) control.classList.add("bad");
  $("status").textContent = message;
  $("status").classList.add("error");
}

function setDownload(href) {
  const a = $("download");
  if (href) { a.href = href; a.download = "nest.zip"; } else { a.removeAttribute("href"); a.removeAttribute("download"); }
  a.classList.toggle("disabled", !href);
  a.setAttribute("aria-disabled", href ? "false" : "true");
}

function drawSheets(answer) {
  const box = $("sheets");
  box.innerHTML = "";
  for (const s of answer.sheets) {
    const fig = document.createElement("figure"), cap = document.createElement("figcaption");
    fig.className = "sheet";
    fig.dataset.sheet = s.sheet;
    // the server's picture, inline so it scales to the box (its cut paths stay a pixel wide)
    const svg = new DOMParser().parseFromString(s.svg, "image/svg+xml").documentElement;
    fig.appendChild(document.importNode(svg, true));
    const parts = Object.entries(s.parts).map(([n, c]) => `${n} ×${c}`).join(", ");
    cap.className = "material-use";
    cap.textContent = `Sheet ${s.sheet}: ${s.count} part${s.count === 1 ? "" : "s"} (${parts}), ` +
      `material use ${Math.round(100 * s.material_use)}%${s.job ? `; ${s.job}` : ""}`;
    fig.appendChild(cap);
    box.appendChild(fig);
  }
  const [w, h] = answer.sheet_mm;
  $("summary").textContent = `${answer.parts} part${answer.parts === 1 ? "" : "s"} on ${answer.sheets.length} sheet${answer.sheets.length === 1 ? "" : "s"} ` +
    `of ${w} × ${h} mm (${answer.profile}), gap ${answer.gap_mm} mm, rotate ${answer.rotate}`;
  $("sheet-w").placeholder = w;
  $("sheet-h").placeholder = h;
  $("gap_mm").placeholder = answer.gap_mm;
}

async function runNest() {
  clearErrors();
  setDownload(null);
  $("nest-button").disabled = true;
  $("status").textContent = "nesting…";
  try {
    await formatsLoaded;  // the format menu is filled before its value is sent
    const res = await fetch("/api/nest", { method: "POST", headers: { "Content-Type": "application/json" },
                                           body: JSON.stringify(body()) });
    const answer = await res.json().catch(() => ({ error: res.statusText, field: null }));
    if (!res.ok) { showError(answer.field, answer.error || res.statusText); return; }
    drawSheets(answer);
    setDownload(answer.download);
    $("status").textContent = `done: ${answer.files.join(", ")}`;
  } finally {
    $("nest-button").disabled = false;
  }
}

// The formats nested sheets are written in, from the format table (/api/schema): its name, and its suffix
// when the name is not the suffix's ("LightBurn (.lbrn2)").
let formatsLoaded = Promise.resolve();

async function formats() {
  const sel = $("format");
  for (const f of (await (await fetch("/api/schema")).json()).formats)
    if (f.nests) sel.add(new Option(f.label.toLowerCase() === f.name ? f.label : `${f.label} (${f.suffix})`, f.name));
}

function start() {
  const q = designQuery(location.search);
  $("back").href = `/?${new URLSearchParams(location.search)}`;
  addDesign(q);
  $("nest-button").addEventListener("click", runNest);
  formatsLoaded = formats();
  gallery();
}

start();
