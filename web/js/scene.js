// The Blender half of the homework on a page: objects on a ground plane, their Principled
// materials, the camera (with the dolly-zoom helper), the sun and the render settings, as a scene
// description (docs/scenes.md) rendered by POST /api/scene. The result shows each object's framing
// box and the checklist's verdict ("both objects fully in the image").
import { api, problemText } from "./api.js";

const $ = (id) => document.getElementById(id);
const form = $("scene-form");
form.addEventListener("submit", (e) => e.preventDefault());  // read, never submitted (no inline handler under the CSP)
const BUILTINS = ["suzanne", "uv_sphere", "cube", "plane", "teapot", "bunny"];
const state = { base: null, uploads: [], last: null };

// Blender's colour fields show sRGB hex; a Principled base colour is linear.
const toLinear = (c) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
const toSrgb = (c) => (c <= 0.0031308 ? c * 12.92 : 1.055 * c ** (1 / 2.4) - 0.055);
const hexOf = (rgb) => "#" + rgb.map((c) => Math.round(Math.min(1, Math.max(0, toSrgb(c))) * 255).toString(16).padStart(2, "0")).join("");
const linearOf = (hex) => [1, 3, 5].map((i) => Number(toLinear(parseInt(hex.slice(i, i + 2), 16) / 255).toFixed(6)));

function status(text, error = false) {
  $("scene-status").textContent = text;
  $("scene-status").classList.toggle("error", error);
}

function input(name, value, attrs = {}) {
  const el = document.createElement("input");
  Object.assign(el, { name, value: String(value) }, attrs);
  return el;
}

function labelled(text, ...controls) {
  const label = document.createElement("label");
  label.append(text + " ", ...controls);
  return label;
}

function meshSelect(current) {
  const select = document.createElement("select");
  select.name = "mesh";
  for (const [value, text] of [...BUILTINS.map((m) => [m, m]), ...state.uploads]) select.add(new Option(text, value, false, value === current));
  if (![...select.options].some((o) => o.value === current)) select.add(new Option(current, current, false, true));
  return select;
}

// One object's fieldset: where it is, how it is shaded, its material.
function objectFieldset(o) {
  const m = o.material ?? {};
  const num = (name, value, step, extra = {}) => input(name, value, { type: "number", step, ...extra });
  const fs = document.createElement("fieldset");
  fs.className = "object";
  const legend = document.createElement("legend");
  legend.textContent = o.name;
  const scale = Array.isArray(o.scale) ? o.scale[0] : (o.scale ?? 1);
  const shading = document.createElement("select");
  shading.name = "shading";
  for (const s of ["smooth", "flat"]) shading.add(new Option(s, s, false, (o.shading ?? "smooth") === s));
  const remove = document.createElement("button");
  Object.assign(remove, { type: "button", textContent: "Remove" });
  remove.addEventListener("click", () => { fs.remove(); changed(); });
  const [lx, ly, lz] = o.location ?? [0, 0, 0], [rx, ry, rz] = o.rotation ?? [0, 0, 0];
  fs.append(legend,
    labelled("Name", input("name", o.name, { type: "text", required: true })),
    labelled("Mesh", meshSelect(o.mesh)),
    labelled("Location", num("lx", lx, 0.1), num("ly", ly, 0.1), num("lz", lz, 0.1)),
    labelled("Rotation", num("rx", rx, 5), num("ry", ry, 5), num("rz", rz, 5)),
    labelled("Scale", num("scale", scale, 0.1, { min: 0 })),
    labelled("Shading", shading),
    labelled("Base colour", input("color", hexOf(m.baseColor ?? [0.8, 0.8, 0.8]), { type: "color" })),
    ...["metallic", "roughness", "specular", "subsurface"].map((k) =>
      labelled(k[0].toUpperCase() + k.slice(1), num(k, m[k] ?? { roughness: 0.5, specular: 0.5 }[k] ?? 0, 0.05, { min: 0, max: 1 }))),
    remove);
  fs.dataset.extra = JSON.stringify({ subsurfaceColor: m.subsurfaceColor, subsurfaceRadius: m.subsurfaceRadius });
  return fs;
}

function fill(scene) {
  state.base = scene;
  $("objects").replaceChildren(...scene.objects.map(objectFieldset));
  const f = form.elements, cam = scene.camera, sun = scene.lights?.find((l) => l.type === "sun") ?? { strength: 3, rotation: [50, 0, 45] };
  [f.cx.value, f.cy.value, f.cz.value] = cam.location;
  [f.tx.value, f.ty.value, f.tz.value] = cam.target ?? [0, 0, 0];
  f["use-rotation"].checked = Array.isArray(cam.rotation);
  [f.crx.value, f.cry.value, f.crz.value] = cam.rotation ?? [70, 0, 0];
  f.lens.value = cam.lens ?? 50;
  f.sun.value = sun.strength;
  [f.srx.value, f.sry.value, f.srz.value] = sun.rotation ?? [0, 0, 0];
  f.engine.value = scene.render?.engine ?? "eevee";
  f.view.value = scene.render?.viewTransform ?? "filmic";
  // Blender's defaults when the scene sets none: 1920 x 1080 at 100%, the size students hand in.
  f.width.value = scene.render?.width ?? 1920;
  f.height.value = scene.render?.height ?? 1080;
  f.percentage.value = String(scene.render?.resolutionPercentage ?? 100);
  f.ground.checked = Boolean(scene.ground);
  changed();
}

function readObject(fs) {
  const v = (name) => fs.querySelector(`[name=${name}]`).value;
  const n = (name) => Number(v(name));
  const extra = JSON.parse(fs.dataset.extra || "{}");
  const material = { baseColor: linearOf(v("color")), metallic: n("metallic"), roughness: n("roughness"), specular: n("specular"), subsurface: n("subsurface") };
  if (material.subsurface > 0 && extra.subsurfaceColor) Object.assign(material, extra);
  return { name: v("name"), mesh: v("mesh"), location: [n("lx"), n("ly"), n("lz")], rotation: [n("rx"), n("ry"), n("rz")],
           scale: n("scale"), shading: v("shading"), material };
}

// Aimed at a target (as the dolly-zoom helper needs), or turned by Blender's Euler rotation.
function camera(base) {
  const f = form.elements, num = (name) => Number(f[name].value);
  const { rotation, target, ...rest } = base;
  const aim = f["use-rotation"].checked ? { rotation: [num("crx"), num("cry"), num("crz")] } : { target: [num("tx"), num("ty"), num("tz")] };
  return { ...rest, location: [num("cx"), num("cy"), num("cz")], lens: num("lens"), ...aim };
}

// The scene the form describes; what the form does not show is kept from the loaded scene.
function readScene() {
  const f = form.elements, base = state.base;
  const num = (name) => Number(f[name].value);
  const sun = { ...(base.lights?.find((l) => l.type === "sun") ?? { type: "sun", angle: 5 }), strength: num("sun"), rotation: [num("srx"), num("sry"), num("srz")] };
  const scene = {
    objects: [...document.querySelectorAll("#objects fieldset.object")].map(readObject),
    camera: camera(base.camera),
    lights: [sun, ...(base.lights ?? []).filter((l) => l.type !== "sun")],
    render: { ...base.render, width: num("width"), height: num("height"), resolutionPercentage: num("percentage"),
              engine: f.engine.value, viewTransform: f.view.value },
  };
  if (f.ground.checked) scene.ground = base.ground ?? { size: 10 };
  if (base.world) scene.world = base.world;
  return scene;
}

function changed() {
  const link = $("download-scene");
  if (link.href.startsWith("blob:")) URL.revokeObjectURL(link.href);
  link.href = URL.createObjectURL(new Blob([JSON.stringify(readScene(), null, 2) + "\n"], { type: "application/json" }));
}

async function renderScene(scene) {
  const response = await api("/api/scene?format=json", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(scene) });
  if (!response.ok) throw new Error(await problemText(response));
  return response.json();
}

function verdictOf(framing) {
  const out = framing.filter((f) => f.drawn && !f.fullyVisible).map((f) => f.name);
  if (out.length) return { text: `not fully in the image: ${out.join(", ")}`, ok: false };
  return { text: framing.length === 2 ? "both objects fully in the image" : "every object fully in the image", ok: framing.length > 0 };
}

// The image with each object's framing box over it, in percentages of the image.
function renderFigure(result, caption) {
  const wrap = document.createElement("div");
  wrap.className = "render";
  const img = new Image();
  img.src = `data:image/png;base64,${result.image}`;
  img.alt = caption;
  wrap.append(img);
  for (const f of result.framing) {
    if (!f.boundingBox) continue;
    const b = f.boundingBox, box = document.createElement("div");
    box.className = `box ${f.fullyVisible ? "in" : "out"}`;
    box.textContent = f.name;
    Object.assign(box.style, { left: `${(100 * b.x0) / result.width}%`, top: `${(100 * b.y0) / result.height}%`,
                               width: `${(100 * (b.x1 - b.x0)) / result.width}%`, height: `${(100 * (b.y1 - b.y0)) / result.height}%` });
    wrap.append(box);
  }
  return wrap;
}

function show(result) {
  state.last = result;
  const v = verdictOf(result.framing);
  $("verdict").textContent = v.text;
  $("verdict").className = v.ok ? "pass" : "fail";
  const figure = renderFigure(result, "The scene rendered on the server");
  figure.id = "render";
  $("render").replaceWith(figure);
  $("framing").replaceChildren(...result.framing.map((f) => {
    const li = document.createElement("li");
    li.textContent = `${f.name}: ${f.fullyVisible ? "fully in the image" : "cut by the frame"}, ${(100 * f.fractionInFrame).toFixed(0)}% in frame, covers ${(100 * f.imageCoverage).toFixed(1)}% of the image`;
    return li;
  }));
  $("passes").replaceChildren(...result.passes.flatMap((p) => {
    const dt = document.createElement("dt"), dd = document.createElement("dd");
    dt.textContent = p.name;
    dd.textContent = `${p.ms.toFixed(1)} ms`;
    return [dt, dd];
  }));
  const link = $("download-render");
  link.href = `data:image/png;base64,${result.image}`;
  link.hidden = false;
}

async function renderOnServer() {
  status("Rendering on the server…");
  try {
    const result = await renderScene(readScene());
    show(result);
    status(`Rendered with ${result.engine} in ${result.totalMs.toFixed(0)} ms (${result.renderer ?? "server"}).`);
    return result;
  } catch (e) {
    status(`Server: ${e.message}`, true);
    return null;
  }
}

// Where the camera goes for each lens so the subject (what it looks at) keeps its size.
async function dollyStops(lenses) {
  const f = form.elements;
  const q = new URLSearchParams({ subject: [f.tx.value, f.ty.value, f.tz.value].join(","), from: [f.cx.value, f.cy.value, f.cz.value].join(","),
                                  lens: f.lens.value, lenses: lenses.join(",") });
  const response = await api(`/api/dolly?${q}`);
  if (!response.ok) throw new Error(await problemText(response));
  return (await response.json()).stops;
}

async function dollyTo() {
  try {
    const [stop] = await dollyStops([Number($("dolly-lens").value)]);
    const f = form.elements;
    [f.cx.value, f.cy.value, f.cz.value] = stop.location.map((c) => Number(c.toFixed(4)));
    f.lens.value = stop.lens;
    changed();
    status(`Camera moved to ${stop.distance.toFixed(2)} m from the subject for a ${stop.lens} mm lens.`);
  } catch (e) {
    status(`Dolly: ${e.message}`, true);
  }
}

async function dollyTrio() {
  status("Rendering the dolly zoom: 25, 50 and 100 mm…");
  try {
    const stops = await dollyStops([25, 50, 100]);
    const figures = [];
    for (const stop of stops) {
      const scene = readScene();
      scene.camera = { ...scene.camera, location: stop.location, lens: stop.lens };
      const result = await renderScene(scene);
      const figure = document.createElement("figure"), caption = document.createElement("figcaption");
      caption.textContent = `${stop.lens} mm at ${stop.distance.toFixed(2)} m: ` +
        result.framing.map((f) => `${f.name} covers ${(100 * f.imageCoverage).toFixed(1)}%`).join(", ");
      figure.append(renderFigure(result, `${stop.lens} mm`), caption);
      figures.push(figure);
    }
    $("dolly").replaceChildren(...figures);
    $("dolly").hidden = false;
    status("Dolly zoom rendered: the subject keeps its size, the background changes.");
  } catch (e) {
    status(`Dolly zoom: ${e.message}`, true);
  }
}

async function uploadMesh(file) {
  const body = new FormData();
  body.append("mesh", file, file.name);
  const response = await api("/api/meshes", { method: "POST", body });
  if (!response.ok) return status(`Mesh upload: ${await problemText(response)}`, true);
  const { id } = await response.json();
  state.uploads.push([id, file.name]);
  for (const select of document.querySelectorAll("select[name=mesh]")) select.add(new Option(file.name, id));
  status(`Uploaded ${file.name}: pick it as an object's mesh.`);
}

$("add-object").addEventListener("click", () => {
  const n = document.querySelectorAll("#objects fieldset.object").length + 1;
  $("objects").append(objectFieldset({ name: `Object ${n}`, mesh: "cube", location: [0, 1.5, 0.5] }));
  changed();
});
$("scene-mesh-file").addEventListener("change", (e) => e.target.files[0] && uploadMesh(e.target.files[0]));
$("render-scene").addEventListener("click", renderOnServer);
$("dolly-apply").addEventListener("click", dollyTo);
$("dolly-trio").addEventListener("click", dollyTrio);
form.addEventListener("input", changed);
document.addEventListener("keydown", (e) => { if (e.ctrlKey && e.key === "Enter") renderOnServer(); });

// The example scene, at the size students hand in: Blender's default output, 1920 x 1080 (the
// example file keeps the 640 x 480 its Cycles references were rendered at).
async function start() {
  const response = await api("/api/scenes/two_objects");
  if (!response.ok) return status(`Cannot load the example scene: ${await problemText(response)}`, true);
  const scene = await response.json();
  fill({ ...scene, render: { ...scene.render, width: 1920, height: 1080, resolutionPercentage: 100 } });
  status("The homework's two-objects scene at Blender's default 1920 x 1080: change it, then render on the server " +
         "(Resolution % 25 previews it in a sixteenth of the time).");
}

window.shadelabScene = { ready: start(), renderOnServer, dollyTrio, readScene };
