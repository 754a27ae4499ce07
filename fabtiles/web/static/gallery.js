// The gallery: each entry's thumbnail (drawn by the server's preview code) links to the editor.
"use strict";

async function gallery() {
  const box = document.getElementById("gallery");
  const items = await (await fetch("/api/gallery")).json();
  // the header counts what the page shows, from the same list
  const count = (g) => items.filter((e) => e.group === g).length;
  document.getElementById("gallery-intro").textContent =
    `The paper's ${count("preset")} presets, the ${count("tiling")} Archimedean tilings, ` +
    `${count("hankin")} of them by Hankin's method, ${count("two-uniform")} two-uniform tiling, ` +
    `${count("cylinder")} cylinders (` +
    `${items.filter((e) => e.group === "cylinder").map((e) => e.title.toLowerCase()).join(", ")}), ` +
    `${count("girih")} girih patterns and ${count("classical")} classical devices (` +
    `${items.filter((e) => e.group === "classical").map((e) => e.title.toLowerCase()).join(", ")}): ` +
    "choose one to open it in the editor.";
  for (const e of items) {
    const a = document.createElement("a");
    a.href = `/?${new URLSearchParams({ gallery: e.key, ...e.query })}`;  // the editor names the design after it
    a.dataset.key = e.key;
    const fig = document.createElement("figure");
    const img = document.createElement("img"), cap = document.createElement("figcaption");
    const title = document.createElement("strong");
    img.loading = "lazy";
    img.alt = e.title;
    img.src = `/api/gallery/${encodeURIComponent(e.key)}.svg`;
    title.textContent = e.title;
    cap.append(title, e.note);
    fig.append(img, cap);
    a.appendChild(fig);
    box.appendChild(a);
  }
}

gallery();
