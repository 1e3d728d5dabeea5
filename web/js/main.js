// The page: the homework's spinning view in WebGL2, editors, and the server beside it. Every fact
// of the homework (canvas, meshes, camera, uniform values, frames and their names) is the
// course's, from GET /api/course (?course=ID picks one of the server's courses).
import { compareImages, imageDataOf } from "./compare.js";
import { Editor } from "./editor.js";
import { courseUniforms, GlView } from "./gl_view.js";
import { api, offerKey } from "./api.js";
import { parseObj } from "./obj.js";
import { groupByDeliverable, saveLikeTheCoursePage } from "./saved_frames.js";
import { glslFromFile } from "./shader_module.js";

const $ = (id) => document.getElementById(id);
const editors = { vertex: new Editor($("vertex-editor"), "phong_vert.js"), fragment: new Editor($("fragment-editor"), "phong_frag.js") };
const state = { course: null, view: null, mesh: null, uploadedId: null, last: null, changed: new Set() };
const COLOUR_ROLES = ["ambient", "diffuse", "specular"];
// The settings are read, never submitted (the page's Content-Security-Policy has no inline handler).
$("settings").addEventListener("submit", (e) => e.preventDefault());

function status(id, text, isError = false) {
  $(id).textContent = text;
  $(id).classList.toggle("error", isError);
}

// A frame's file name as the course's page downloads it: hw2_{prefix}_{k}.png.
const frameFile = (prefix, k, extension = "png") =>
  `${state.course.frames.fileName.replaceAll("{prefix}", prefix).replaceAll("{k}", String(k))}.${extension}`;

// ---- uniforms: the course's values unless the student changed a control ---------------------
const hexToVec4 = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255).concat([1]);
const vecToHex = (v) => "#" + v.slice(0, 3).map((c) => Math.round(Math.min(1, Math.max(0, c)) * 255).toString(16).padStart(2, "0")).join("");
function uniforms() {
  const u = courseUniforms(state.course);
  for (const role of COLOUR_ROLES)
    if (state.changed.has(role) && u[role]) u[role] = { ...u[role], value: hexToVec4($(`color-${role}`).value) };
  if (state.changed.has("lightPosition") && u.lightPosition)
    u.lightPosition = { ...u.lightPosition, value: ["light-x", "light-y", "light-z"].map((id) => Number($(id).value)) };
  return u;
}
// What the server gets: only values the student changed, only for names the program uses.
function serverUniforms() {
  const out = {};
  for (const [role, { names, value }] of Object.entries(uniforms())) {
    if (!state.changed.has(role)) continue;
    for (const name of names) if (state.view.active.includes(name)) out[name] = value;
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
  const view = state.view;
  const errors = view.setProgram(loaded.vertex, loaded.fragment);
  view.uniforms = uniforms();
  state.dirty = true;
  editors.vertex.show(errors.filter((e) => e.stage === "vertex"));
  editors.fragment.show(errors.filter((e) => e.stage !== "vertex"));
  status("local-status", errors.length ? "Your shaders do not compile in this browser: see the messages under the editors." : "Compiled in your browser (WebGL2).", errors.length > 0);
  return errors.length === 0;
}

async function loadMesh(name) {
  const mesh = state.course.meshes.find((m) => m.name === name);
  const response = await api(mesh.url);
  if (!response.ok) throw new Error(`cannot load ${name}`);
  state.view.setMesh(parseObj(await response.text()));
  state.dirty = true;
  state.mesh = name;
  state.uploadedId = null;
}

// The course's page turns the mesh a frame's step per second (20 degrees). A still view is drawn
// only when something changed: software WebGL at 60 frames a second would take a core from the
// server next to it.
function spin(time) {
  const view = state.view;
  if ($("spin").checked) view.draw((state.course.frames.degreesPerFrame * time) / 1000);
  else if (state.dirty) view.draw(0);
  state.dirty = false;
  requestAnimationFrame(spin);
}

// ---- server -------------------------------------------------------------------------------
function job(output) {
  return {
    course: state.course.id,
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
  link.download = frameFile($("prefix").value, "grid");
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

// The editors' code graded against a deliverable's reference, as the hand-in will be: the verdict,
// what is wrong, and the line a render confirmed marked in its editor.
async function checkCode() {
  const checkpoint = state.course.checkpoints.find((c) => c.name === $("check-deliverable").value);
  status("server-status", `Grading the code as ${checkpoint.title}…`);
  const body = { reference: checkpoint.name, vertex: editors.vertex.text, fragment: editors.fragment.text,
                 vertexName: editors.vertex.name, fragmentName: editors.fragment.name };
  if (state.course.id) body.course = state.course.id;
  const response = await api("/api/grade", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
  const report = await response.json();
  if (!response.ok) {
    status("server-status", `Server: ${report.detail} [${report.code}]`, true);
    throw Object.assign(new Error(report.detail), { problem: report });
  }
  showCodeResult(checkpoint, report);
  status("server-status", `Graded the code as ${checkpoint.title}: ${report.pass ? "pass" : "fail"}.`);
  return report;
}

// Compile errors at their lines, and the line of a confirmed repair (what is wrong there).
function showCodeResult(checkpoint, report) {
  const found = report.repairSearch?.found;
  for (const stage of ["vertex", "fragment"]) {
    const marks = (report.diagnostics ?? []).filter((d) => d.stage === stage || (stage === "fragment" && d.stage === "link"));
    if (found?.line && found.file === editors[stage].name) marks.push({ line: found.line, message: found.text, severity: "mistake" });
    editors[stage].show(marks);
  }
  const result = $("code-result");
  result.replaceChildren(element("h3", { textContent: `The editors' code, graded as ${checkpoint.title}` }),
                         verdictOf(report, "Your code"), element("ul", {}, report.messages.map((m) => element("li", { textContent: m }))));
  result.hidden = false;
}

// The deliverables whose code the editors can hold; the one the current preset is the reference of first.
function fillCheckDeliverable(course, preset) {
  const select = $("check-deliverable");
  select.innerHTML = "";
  for (const c of course.checkpoints.filter((c) => c.code)) select.append(new Option(c.title, c.name, false, c.reference === preset));
}

async function downloadFrames() {
  const response = await post("frames");
  const notice = response.headers.get("X-ShadeLab-Notice");
  if (notice) status("server-status", `Downloaded the server's frames: ${notice}.`);
  const url = URL.createObjectURL(await response.blob());
  const a = Object.assign(document.createElement("a"), { href: url, download: frameFile($("prefix").value, "frames", "zip") });
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
  const blob = await state.view.captureFrame(k * Number($("degrees").value));
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

// ---- saved frames: the check a student runs before handing them in ---------------------------
const element = (tag, props = {}, children = []) => {
  const e = Object.assign(document.createElement(tag), props);
  e.append(...children);
  return e;
};

// One deliverable's frames graded by the server; with `withCode`, against the editors' shaders too.
async function gradeSavedFrames(checkpoint, files, withCode) {
  const form = new FormData();
  form.append("reference", checkpoint.name);
  if (state.course.id) form.append("course", state.course.id);
  form.append("mesh", state.mesh);
  if (withCode) {
    form.append("vertex", new Blob([editors.vertex.text]), editors.vertex.name);
    form.append("fragment", new Blob([editors.fragment.text]), editors.fragment.name);
  }
  for (const f of files) form.append("frames", f, f.name);
  const response = await api("/api/grade", { method: "POST", body: form });
  const body = await response.json();
  if (!response.ok) throw new Error(`${checkpoint.name}: ${body.detail} [${body.code}]`);
  return body;
}

// The mistake in a few words beside a failing verdict: the confirmed repair's, else the formula's
// where it explains the frames; never a report's internal id (`unguarded_specular`). What is
// wrong, at which line, follows in the messages.
function mistakeWords(report) {
  if (report.pass) return "";
  const words = report.repairSearch?.found?.label || (report.explanation?.explained ? report.explanation.label : "");
  return words ? ` (${words})` : "";
}

function verdictOf(report, what) {
  return element("p", { className: `verdict ${report.pass ? "pass" : "fail"}`,
                        textContent: `${what}: ${report.pass ? "pass" : "fail"}${mistakeWords(report)}` });
}

function showSavedResult(checkpoint, result) {
  const lags = result.frames.frames.map((f) => (f.lagDegrees ?? 0).toFixed(2));
  const parts = [element("h3", { textContent: checkpoint.title }),
                 verdictOf(result.frames, "Your saved frames"),
                 element("ul", {}, result.frames.messages.map((m) => element("li", { textContent: m })))];
  if (lags.length) parts.push(element("p", { className: "lags", textContent: `Drawn behind each frame's angle by ${lags.join(", ")} degrees` }));
  if (result.code) parts.push(verdictOf(result.code, "Made by the editors' code"),
                              element("ul", {}, result.code.messages.map((m) => element("li", { textContent: m }))));
  for (const w of result.frames.warnings ?? []) parts.push(element("p", { className: "lags", textContent: w }));
  if (result.heatmap) parts.push(element("img", { src: `data:image/png;base64,${result.heatmap}`, alt: `${checkpoint.name}: where the frames differ from the reference` }));
  // What the grader flags for the TA (frames ShadeLab made, frames with no lag), first and plain.
  const flags = (result.frames.flags ?? []).map((f) => element("p", { className: "flag", textContent: `Flagged for the TA: ${f.message}` }));
  parts.splice(1, 0, ...flags);
  const article = element("article", { className: "saved-result" }, parts);
  article.dataset.checkpoint = checkpoint.name;
  $("saved-results").append(article);
}

// Files dropped or chosen: each deliverable's frames graded; what is no deliverable's frame is said.
async function checkSavedFrames(files) {
  const course = state.course;
  const { groups, strays } = groupByDeliverable([...files], course);
  $("saved-results").innerHTML = "";
  const names = Object.keys(groups);
  if (!names.length) {
    status("saved-status", `None of these is a saved frame (${course.frames.fileName.replace("{prefix}", "normals").replace("{k}", "0")}.png and the like).`, true);
    return [];
  }
  status("saved-status", `Grading ${names.join(", ")}…`);
  const results = [];
  for (const name of names) {
    const checkpoint = course.checkpoints.find((c) => c.name === name);
    const result = await gradeSavedFrames(checkpoint, groups[name], $("saved-code").value === name);
    showSavedResult(checkpoint, result);
    results.push(result);
  }
  const stray = strays.length ? ` Not frames of any deliverable, not graded: ${strays.map((f) => f.name).join(", ")}.` : "";
  status("saved-status", `Graded ${names.join(", ")}.${stray}`);
  return results;
}

// The deliverables whose code the editors can hold; the one the current preset is the reference of first.
function fillSavedCode(course, preset) {
  const select = $("saved-code");
  select.innerHTML = "";
  select.append(new Option("none (the frames alone)", ""));
  for (const c of course.checkpoints.filter((c) => c.code)) select.append(new Option(c.name, c.name, false, c.reference === preset));
}

function wireSavedFrames() {
  const drop = $("saved-drop");
  drop.addEventListener("dragover", (e) => { e.preventDefault(); drop.classList.add("over"); });
  drop.addEventListener("dragleave", () => drop.classList.remove("over"));
  drop.addEventListener("drop", (e) => {
    e.preventDefault();
    drop.classList.remove("over");
    reportTo("saved-status", checkSavedFrames(e.dataTransfer.files));
  });
  $("saved-files").addEventListener("change", (e) => reportTo("saved-status", checkSavedFrames(e.target.files)));
}

// ---- wiring -------------------------------------------------------------------------------
async function choosePreset(name, presets) {
  const p = presets.find((x) => x.name === name);
  $("preset").value = name;  // the list says what the editors hold, however it was chosen
  editors.vertex.name = p.vertex.name;
  editors.fragment.name = p.fragment.name;
  $("vertex-name").textContent = p.vertex.name;
  $("fragment-name").textContent = p.fragment.name;
  editors.vertex.text = p.vertex.source;
  editors.fragment.text = p.fragment.source;
  // A deliverable's reference saves its frames under the deliverable's prefix (hw2_normals_*).
  $("prefix").value = state.course.checkpoints.find((c) => c.reference === name)?.prefix ?? name;
  fillSavedCode(state.course, name);
  fillCheckDeliverable(state.course, name);
  $("code-result").hidden = true;
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
  if (file.name.toLowerCase().endsWith(".obj")) state.view.setMesh(parseObj(await file.text()));
  status("local-status", `Uploaded ${file.name}: ${body.info.triangles} triangles.` +
         (file.name.toLowerCase().endsWith(".obj") ? "" : " (The local view previews OBJ only; the server renders it.)"));
}

const report = (p) => p.catch((e) => { if (!e.problem) status("server-status", e.message, true); });
const reportTo = (id, p) => p.catch((e) => status(id, e.message, true));

// The controls start at the course's values.
function fillControls(course) {
  $("course-title").textContent = course.title;
  document.title = `ShadeLab · ${course.title}`;
  [$("glcanvas").width, $("glcanvas").height] = [course.canvas.width, course.canvas.height];
  for (const m of course.meshes) $("mesh").append(new Option(m.name, m.name, false, m.name === course.defaultMesh));
  const u = courseUniforms(course);
  for (const role of COLOUR_ROLES) if (u[role]) $(`color-${role}`).value = vecToHex(u[role].value);
  if (u.lightPosition) ["light-x", "light-y", "light-z"].forEach((id, i) => ($(id).value = u.lightPosition.value[i]));
  $("frame-count").value = course.frames.count;
  $("degrees").value = course.frames.degreesPerFrame;
  $("width").value = course.canvas.width;
  $("height").value = course.canvas.height;
  for (const p of course.presets) $("preset").append(new Option(p.name, p.name, false, p.name === course.pagePreset));
  const notice = course.viewer?.framesDownloadNotice;
  if (notice) Object.assign($("frames-notice"), { hidden: false, textContent: `The server's frames and grid are ${notice}.` });
  const last = course.checkpoints.at(-1);
  if (last) $("saved-example").textContent = frameFile(last.prefix, 0);
}

async function init() {
  const which = new URLSearchParams(location.search).get("course");
  const response = await api(`/api/course${which ? `?course=${encodeURIComponent(which)}` : ""}`);
  if (!response.ok) throw new Error(`the server has no course ${which ?? ""}`);
  const course = (state.course = await response.json());
  const presets = course.presets;
  state.view = new GlView($("glcanvas"), course);
  fillControls(course);
  await loadMesh(course.defaultMesh);
  // The page opens as the course's index.html does: with the starter the students received.
  await choosePreset(course.pagePreset ?? course.defaultPreset, presets);
  requestAnimationFrame(spin);

  $("preset").addEventListener("change", () => choosePreset($("preset").value, presets));
  $("mesh").addEventListener("change", () => loadMesh($("mesh").value).then(() => (state.last = null)));
  $("mesh-file").addEventListener("change", (e) => e.target.files[0] && uploadMesh(e.target.files[0]));
  for (const role of COLOUR_ROLES)
    $(`color-${role}`).addEventListener("input", () => { state.changed.add(role); state.view.uniforms = uniforms(); state.dirty = true; });
  for (const id of ["light-x", "light-y", "light-z"])
    $(id).addEventListener("input", () => { state.changed.add("lightPosition"); state.view.uniforms = uniforms(); state.dirty = true; });
  $("apply").addEventListener("click", applyLocally);
  $("spin").addEventListener("change", () => (state.dirty = true));
  $("render-server").addEventListener("click", () => report(renderOnServer()));
  $("download-frames").addEventListener("click", () => report(downloadFrames()));
  $("check-code").addEventListener("click", () => report(checkCode()));
  $("compare").addEventListener("click", () => report(compareFrame(0)));
  wireSavedFrames();
  document.addEventListener("keydown", (e) => {
    if (e.key === "Enter" && (e.ctrlKey || e.metaKey)) report(renderOnServer());
  });

  // Hooks for the browser tests (tests/browser), which drive the page as a student would.
  window.shadelab = {
    course, view: state.view, editors, state, renderOnServer, compareFrame, applyLocally, frameFile, checkSavedFrames, checkCode,
    // What the course's page would save for the shaders now applied, on a clock of `hz` (see saved_frames.js).
    saveLikeTheCoursePage: (prefix, clock) => saveLikeTheCoursePage(state.view, course, prefix, clock),
    choosePreset: (name) => choosePreset(name, presets),
    chooseMesh: async (name) => { $("mesh").value = name; await loadMesh(name); state.last = null; },
  };
}

offerKey($("api-key"));
window.shadelabReady = init().catch((e) => status("local-status", e.message, true));
