// The 3D view: the print's parts from /api/view.glb (the 3MF's parts, each in its colour),
// turned with the mouse. three.js comes from the package (`fabtiles install-viewer`), never a CDN.
// app.js sends "fabtiles:design" (the query) whenever the 2D preview of a good design is drawn;
// a bad parameter sends nothing, so the last good model stays.
const box = document.getElementById("view3d");
const canvas = document.getElementById("view3d-canvas");
const caption = document.getElementById("view3d-caption");

async function start() {
  let THREE, GLTFLoader, OrbitControls;
  try {
    THREE = await import("three");
    ({ GLTFLoader } = await import("/static/vendor/three/examples/jsm/loaders/GLTFLoader.js"));
    ({ OrbitControls } = await import("/static/vendor/three/examples/jsm/controls/OrbitControls.js"));
  } catch (err) {
    box.classList.add("missing");
    caption.textContent = "The 3D view needs three.js in the package: run  fabtiles install-viewer  once, then reload.";
    return;
  }
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xeef1f5);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  scene.add(sun);
  const camera = new THREE.PerspectiveCamera(35, 1, 0.1, 20000);
  camera.up.set(0, 0, 1);  // the print's Z is up (mm), as in the slicer
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;
  // The camera stays above the plate: at most 80 degrees from straight down (the horizon is 90, under it
  // the plate's grey underside), and a right-drag moves it over the plate's plane, never down through it.
  controls.maxPolarAngle = THREE.MathUtils.degToRad(80);
  controls.screenSpacePanning = false;
  let model = null, fitted = null, seq = 0, turned = false;
  controls.addEventListener("start", () => { turned = true; });

  const render = () => {
    sun.position.copy(camera.position).add(new THREE.Vector3(0, 0, camera.position.length()));
    renderer.render(scene, camera);
    canvas.dataset.polar = THREE.MathUtils.radToDeg(controls.getPolarAngle()).toFixed(2);  // for the tests
  };
  const resize = () => {
    const w = canvas.clientWidth || 480, h = canvas.clientHeight || 360;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    if (model && !turned) fit();  // a new shape of the canvas: the whole tile again, unless turned by hand
    render();
  };
  new ResizeObserver(resize).observe(canvas);
  controls.addEventListener("change", render);

  // The camera of a new tile size: from the front and above, the whole tile in view. The distance is the
  // least that keeps every corner of the model's box inside MARGIN of the view's half-width and
  // half-height: a corner at lateral offset x and depth d - p.dir needs x <= (d - p.dir) tan(half angle).
  // A model standing taller than half its width (a cylinder on its end) is seen more from the side, its height
  // and its pattern both in view; a plate from above.
  const MARGIN = 0.9, VIEW_PLATE = new THREE.Vector3(0, -1.25, 1.1).normalize();
  const VIEW_STANDING = new THREE.Vector3(0, -1.6, 0.75).normalize();
  const fit = () => {
    const bounds = new THREE.Box3().setFromObject(model), size = bounds.getSize(new THREE.Vector3());
    const centre = bounds.getCenter(new THREE.Vector3()), span = Math.max(size.x, size.y, size.z);
    const VIEW = standing(size) ? VIEW_STANDING : VIEW_PLATE;
    const right = new THREE.Vector3().crossVectors(VIEW.clone().negate(), camera.up).normalize();
    const up = new THREE.Vector3().crossVectors(right, VIEW.clone().negate()).normalize();
    const tanY = Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) * MARGIN, tanX = tanY * camera.aspect;
    let distance = 0;
    for (const x of [bounds.min.x, bounds.max.x]) for (const y of [bounds.min.y, bounds.max.y])
      for (const z of [bounds.min.z, bounds.max.z]) {
        const p = new THREE.Vector3(x, y, z).sub(centre), depth = p.dot(VIEW);
        distance = Math.max(distance, depth + Math.abs(p.dot(right)) / tanX, depth + Math.abs(p.dot(up)) / tanY);
      }
    controls.target.copy(centre);
    camera.position.copy(centre).addScaledVector(VIEW, distance);
    camera.near = distance / 100; camera.far = distance + 20 * span;
    camera.updateProjectionMatrix();
    controls.update();
    fitted = key(size);
    turned = false;
  };
  // the model's size as the fit knows it: a new size (a tile's width and height, a standing model's length too)
  // is framed again; a plate's new print height is not
  const standing = (size) => size.z > 0.5 * Math.max(size.x, size.y);
  const key = (size) => `${size.x.toFixed(1)}x${size.y.toFixed(1)}${standing(size) ? `x${size.z.toFixed(1)}` : ""}`;
  document.getElementById("view3d-reset").addEventListener("click", () => { if (model) { fit(); render(); } });

  // The request of the model on its way: a newer design aborts it, so the browser closes its connection (it
  // holds one of the six the page has, the 2D preview's wait behind them) and the server stops building it.
  let asked = null;
  const drop = () => { if (asked) asked.abort(); asked = null; };
  const show = async (q) => {
    const mine = ++seq;
    drop();
    const request = asked = new AbortController();
    box.classList.add("loading");
    let res, data;
    try {
      res = await fetch(`/api/view.glb?${q}`, { signal: request.signal });
      if (res.ok) data = await res.arrayBuffer();
    } catch (err) {
      if (request.signal.aborted) return;  // a newer design's model replaced it: not an error
      if (mine !== seq) return;
      box.classList.remove("loading");
      caption.textContent = `3D view not updated: ${err.message || err}`;  // the server did not answer
      return;
    }
    if (mine !== seq) return;
    if (asked === request) asked = null;
    box.classList.remove("loading");
    if (!res.ok) {  // the design's error is the 2D preview's to show; the last good model stays
      const body = await res.json().catch(() => ({ error: res.statusText }));
      caption.textContent = `3D view not updated: ${body.error}`;
      return;
    }
    const view = res.headers.get("X-Fabtiles-View") || "";
    const parts = JSON.parse(res.headers.get("X-Fabtiles-Parts") || "{}");
    new GLTFLoader().parse(data, "", (gltf) => {
      if (mine !== seq) return;
      if (model) {
        scene.remove(model);
        model.traverse((o) => { if (o.isMesh) { o.geometry.dispose(); o.material.dispose(); } });
      }
      model = gltf.scene;
      model.traverse((o) => { if (o.isMesh) shadeByHeight(o); });
      scene.add(model);
      const size = new THREE.Box3().setFromObject(model).getSize(new THREE.Vector3());
      if (fitted !== key(size)) fit();  // keep the user's turn otherwise
      render();
      const names = Object.entries(parts).map(([n, p]) => `${n} (${p.triangles.toLocaleString("en")} triangles)`);
      caption.textContent = `Showing ${view}: ${names.join(", ")}. Drag to turn, wheel to zoom, right-drag to move.`;
      box.dataset.parts = Object.keys(parts).join(",");
      const colours = [];  // each part's colour as drawn (sRGB), in the parts' order: a mosaic's N colours
      model.traverse((o) => { if (o.isMesh) colours.push(`#${o.material.color.getHexString()}`); });
      box.dataset.colours = colours.join(",");
      canvas.dataset.version = String(mine);
    }, (err) => { caption.textContent = `3D view: the model could not be read (${err.message || err})`; });
  };
  // Flat faces, darkened by how low they lie in their part: every horizontal face has the same
  // normal, so without this an interlaced relief's dipped strands (0.6 mm under the top of its
  // 1.2 mm pattern, in the default profile) would have the shade of the strands passing over them.
  const shadeByHeight = (mesh) => {
    const z = mesh.geometry.getAttribute("position"), colours = new Float32Array(z.count * 3);
    let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < z.count; i++) { lo = Math.min(lo, z.getZ(i)); hi = Math.max(hi, z.getZ(i)); }
    for (let i = 0; i < z.count; i++) {
      // linear light: a face at half its part's height shows at 0.63 of a top face's sRGB value
      const t = hi > lo ? (z.getZ(i) - lo) / (hi - lo) : 1, k = 0.15 + 0.85 * t * t;
      colours.fill(k, 3 * i, 3 * i + 3);
    }
    mesh.geometry.setAttribute("color", new THREE.BufferAttribute(colours, 3));
    mesh.material.vertexColors = true;
    mesh.material.flatShading = true;
    mesh.material.needsUpdate = true;
  };
  document.addEventListener("fabtiles:design", (e) => show(e.detail));
  // an invalid design: no model is asked for; the last good one stays, the caption says why
  const invalid = (message) => {
    ++seq;
    drop();  // the model still coming is not drawn: its request is closed
    box.classList.remove("loading");
    caption.textContent = model ? `3D view not updated: ${message}` : `The print in 3D: not shown, ${message}`;
  };
  document.addEventListener("fabtiles:invalid", (e) => invalid(e.detail));
  if (window.fabtilesInvalid) invalid(window.fabtilesInvalid);  // refused before this module loaded
  else if (window.fabtilesDesign) show(window.fabtilesDesign);  // drawn before this module loaded
  resize();
}

start();
