// The page: the homework's spinning view in WebGL2, editors, and the server beside it.
import { compareImages, imageDataOf } from "./compare.js";
import { Editor } from "./editor.js";
import { DEFAULT_UNIFORMS, GlView } from "./gl_view.js";
import { api } from "./api.js";
import { parseObj } from "./obj.js";
import { glslFromFile } from "./shader_module.js";

const $ = (id) => document.getElementById(id);
const view = new GlView($("glcanvas"));
const editors = { vertex: new Editor($("vertex-editor"), "phong_vert.js"), fragment: new Editor($("fragment-editor"), "phong_frag.js") };
const state = { mesh: "bunny", uploadedId: null, last: null, changed: new Set() };

function status(id, text, isError = false) {
  $(id).textContent = text;
  $(id).classList.toggle("error", isError);
}

// ---- uniforms: the hw2.js defaults unless the student changed a control --------------------
const hexToVec4 = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255).concat([1]);
function uniforms() {
  const u = { ...DEFAULT_UNIFORMS };
  for (const name of ["uAmbientColor", "uDiffuseColor", "uSpecularColor"]) if (state.changed.has(name)) u[name] = hexToVec4($(name).value);
  if (state.changed.has("light")) u.uLightPosition = ["light-x", "light-y", "light-z"].map((id) => Number($(id).value));
  return u;
}
// What the server gets: only values that differ from its defaults, only for uniforms the program uses.
function serverUniforms() {
  const u = uniforms(), out = {};
  for (const [name, value] of Object.entries(u)) {
    const changed = name === "uLightPosition" ? state.changed.has("light") : state.changed.has(name);
    if (!changed) continue;
    const plain = name[1].toLowerCase() + name.slice(2);
    if (view.active.includes(name)) out[name] = value;
    if (view.active.includes(plain)) out[plain] = value;
  }
  return out;
}

// ---- local view ---------------------------------------------------------------------------
async function applyLocally() {
  const loaded = {};
  for (const stage of ["vertex", "fragment"]) {
    try {
      loaded[stage] = await glslFromFile(editors[stage].text);
      editors[stage].show([]);
    } catch (e) {
      editors[stage].show([{ line: e.line ?? 0, message: e.message }]);
      status("local-status", `The ${stage} shader does not load.`, true);
      return false;
    }
  }
  const errors = view.setProgram(loaded.vertex, loaded.fragment);
  view.uniforms = uniforms();
  state.dirty = true;
  editors.vertex.show(errors.filter((e) => e.stage === "vertex"));
  editors.fragment.show(errors.filter((e) => e.stage !== "vertex"));
  status("local-status", errors.length ? "Your shaders do not compile in this browser: see the messages under the editors." : "Compiled in your browser (WebGL2).", errors.length > 0);
  return errors.length === 0;
}

async function loadMesh(name) {
  const response = await api(`/api/meshes/${name}.obj`);
  if (!response.ok) throw new Error(`cannot load ${name}`);
  view.setMesh(parseObj(await response.text()));
  state.dirty = true;
  state.mesh = name;
  state.uploadedId = null;
}

// hw2.js turns the mesh 20 degrees per second. A still view is drawn only when something changed:
// software WebGL at 60 frames a second would take a core from the server next to it.
function spin(time) {
  if ($("spin").checked) view.draw((20 * time) / 1000);
  else if (state.dirty) view.draw(0);
  state.dirty = false;
  requestAnimationFrame(spin);
}

// ---- server -------------------------------------------------------------------------------
function job(output) {
  return {
    vertex: editors.vertex.text, fragment: editors.fragment.text,
    vertexName: editors.vertex.name, fragmentName: editors.fragment.name,
    mesh: state.uploadedId ?? state.mesh,
    width: Number($("width").value), height: Number($("height").value),
    frames: Number($("frame-count").value), degreesPerFrame: Number($("degrees").value),
    prefix: $("prefix").value, uniforms: serverUniforms(), output,
  };
}

async function post(output) {
  const response = await api("/api/render", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(job(output)) });
  if (response.ok) return response;
  const problem = await response.json().catch(() => ({ detail: response.statusText, diagnostics: [] }));
  for (const stage of ["vertex", "fragment"])
    editors[stage].show((problem.diagnostics ?? []).filter((d) => d.stage === stage || (stage === "fragment" && d.stage === "link")));
  status("server-status", `Server: ${problem.detail} [${problem.code}]`, true);
  throw Object.assign(new Error(problem.detail), { problem });
}

function showTimings(response) {
  const dl = $("timings");
  dl.innerHTML = "";
  const add = (k, v) => dl.append(Object.assign(document.createElement("dt"), { textContent: k }), Object.assign(document.createElement("dd"), { textContent: v }));
  add("renderer", response.headers.get("X-ShadeLab-Renderer") ?? "?");
  for (const part of (response.headers.get("Server-Timing") ?? "").split(",")) {
    const m = part.trim().match(/^(\w+);dur=([\d.]+)/);
    if (m) add(m[1], `${Number(m[2]).toFixed(1)} ms`);
  }
}

async function renderOnServer() {
  status("server-status", "Rendering on the server…");
  await applyLocally();
  const response = await post("json");
  const result = await response.json();
  state.last = result;
  showTimings(response);
  $("warnings").innerHTML = "";
  for (const w of result.warnings) $("warnings").append(Object.assign(document.createElement("li"), { textContent: w }));
  const grid = $("grid");
  grid.src = `data:image/png;base64,${result.images.grid}`;
  await grid.decode();
  grid.hidden = false;
  const link = $("download-grid");
  link.href = grid.src;
  link.download = `hw2_${$("prefix").value}_grid.png`;
  link.hidden = false;
  $("frames").innerHTML = "";
  for (const f of result.images.frames) {
    const fig = document.createElement("figure");
    fig.append(Object.assign(document.createElement("img"), { src: `data:image/png;base64,${f.data}`, alt: f.name }),
               Object.assign(document.createElement("figcaption"), { textContent: f.name }));
    $("frames").append(fig);
  }
  status("server-status", `Server rendered ${result.images.frames.length} frames (${result.samples}x MSAA).`);
  return result;
}

async function downloadFrames() {
  const response = await post("frames");
  const url = URL.createObjectURL(await response.blob());
  const a = Object.assign(document.createElement("a"), { href: url, download: `hw2_${$("prefix").value}_frames.zip` });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

// Frame k from this browser (what the student's page would save) against the server's.
async function compareFrame(k = 0) {
  if (!state.last) await renderOnServer();
  const canvas = $("glcanvas");
  const [w, h] = [Number($("width").value), Number($("height").value)];
  const previous = [canvas.width, canvas.height];
  [canvas.width, canvas.height] = [w, h];
  const blob = await view.captureFrame(k * Number($("degrees").value));
  [canvas.width, canvas.height] = previous;
  const browser = await imageDataOf(blob);
  const serverPng = await (await fetch(`data:image/png;base64,${state.last.images.frames[k].data}`)).blob();
  const server = await imageDataOf(serverPng);
  const result = compareImages(browser, server);
  $("comparison").hidden = false;
  $("compare-frame").textContent = k;
  $("compare-result").textContent = `${(result.fractionOver * 100).toFixed(3)}% of pixels differ by more than 8/255; ` +
    `mean absolute error ${result.meanAbsError.toExponential(2)}; ${result.interior} differing pixels away from an edge.`;
  for (const [id, img] of [["cmp-browser", browser], ["cmp-server", server], ["cmp-diff", result.diff]]) {
    const c = $(id);
    [c.width, c.height] = [img.width, img.height];
    c.getContext("2d").putImageData(img, 0, 0);
  }
  return { frame: k, fractionOver: result.fractionOver, meanAbsError: result.meanAbsError, interior: result.interior };
}

// ---- wiring -------------------------------------------------------------------------------
async function choosePreset(name, presets) {
  const p = presets.find((x) => x.name === name);
  editors.vertex.name = p.vertex.name;
  editors.fragment.name = p.fragment.name;
  $("vertex-name").textContent = p.vertex.name;
  $("fragment-name").textContent = p.fragment.name;
  editors.vertex.text = p.vertex.source;
  editors.fragment.text = p.fragment.source;
  $("prefix").value = name;
  state.last = null;
  await applyLocally();
}

async function uploadMesh(file) {
  const form = new FormData();
  form.append("mesh", file, file.name);
  const response = await api("/api/meshes", { method: "POST", body: form });
  const body = await response.json();
  if (!response.ok) return status("local-status", `Mesh upload: ${body.detail}`, true);
  state.uploadedId = body.id;
  if (file.name.toLowerCase().endsWith(".obj")) view.setMesh(parseObj(await file.text()));
  status("local-status", `Uploaded ${file.name}: ${body.info.triangles} triangles.` +
         (file.name.toLowerCase().endsWith(".obj") ? "" : " (The local view previews OBJ only; the server renders it.)"));
}

const report = (p) => p.catch((e) => { if (!e.problem) status("server-status", e.message, true); });

async function init() {
  const presets = await (await api("/api/presets")).json();
  for (const p of presets) $("preset").append(new Option(p.name, p.name, false, p.name === "specular"));
  $("preset").value = "specular";
  await loadMesh("bunny");
  await choosePreset("specular", presets);
  requestAnimationFrame(spin);

  $("preset").addEventListener("change", () => choosePreset($("preset").value, presets));
  $("mesh").addEventListener("change", () => loadMesh($("mesh").value).then(() => (state.last = null)));
  $("mesh-file").addEventListener("change", (e) => e.target.files[0] && uploadMesh(e.target.files[0]));
  for (const id of ["uAmbientColor", "uDiffuseColor", "uSpecularColor"])
    $(id).addEventListener("input", () => { state.changed.add(id); view.uniforms = uniforms(); state.dirty = true; });
  for (const id of ["light-x", "light-y", "light-z"])
    $(id).addEventListener("input", () => { state.changed.add("light"); view.uniforms = uniforms(); state.dirty = true; });
  $("apply").addEventListener("click", applyLocally);
  $("spin").addEventListener("change", () => (state.dirty = true));
  $("render-server").addEventListener("click", () => report(renderOnServer()));
  $("download-frames").addEventListener("click", () => report(downloadFrames()));
  $("compare").addEventListener("click", () => report(compareFrame(0)));
  document.addEventListener("keydown", (e) => {
    if (e.key === "Enter" && (e.ctrlKey || e.metaKey)) report(renderOnServer());
  });

  // Hooks for the browser tests (tests/browser), which drive the page as a student would.
  window.shadelab = {
    view, editors, state, renderOnServer, compareFrame, applyLocally,
    choosePreset: (name) => choosePreset(name, presets),
    chooseMesh: async (name) => { $("mesh").value = name; await loadMesh(name); state.last = null; },
  };
}

window.shadelabReady = init().catch((e) => status("local-status", e.message, true));
