// The gallery: each entry's thumbnail (drawn by the server's preview code) links to the editor.
"use strict";

async function gallery() {
  const box = document.getElementById("gallery");
  const items = await (await fetch("/api/gallery")).json();
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
