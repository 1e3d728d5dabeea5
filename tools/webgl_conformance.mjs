// The Khronos WebGL conformance suite's GLSL compile-and-link cases, judged by Debian's Chromium
// and by ShadeLab's /api/compile, and where the two agree (issue 17's figure). The suite is not in
// this repository (it is read, not copied): give a checkout of KhronosGroup/WebGL.
//
//   node tools/webgl_conformance.mjs SUITE_CHECKOUT [--out report.json] [PAGE_DIR_OR_PAGE ...]
//
// Pages default to sdk/tests/conformance2/glsl3 (its 00_test_list.txt) and the promoted-extensions
// page. Each page loads with its own shaders and helpers, but its harness script
// (glsl-conformance-test.js) is replaced by a recorder with the same four functions: each case it
// is handed is compiled and linked in the page's WebGL 2 context (Chromium's verdict) beside the
// suite's expectation; then the same two sources go to a real server's /api/compile (ShadeLab's
// verdict). Needs the browser tests' npm install (tools/test.sh does it) and build/shadelab.
import { createServer } from "node:http";
import { existsSync, readFileSync, writeFileSync } from "node:fs";
import path from "node:path";
import { startBrowser, startServer } from "../tests/browser/harness.mjs";

const args = process.argv.slice(2);
const outAt = args.indexOf("--out");
const out = outAt >= 0 ? args.splice(outAt, 2)[1] : null;
const [checkout, ...wanted] = args;
if (!checkout) {
  console.error("usage: node tools/webgl_conformance.mjs SUITE_CHECKOUT [--out report.json] [PAGE_DIR_OR_PAGE ...]");
  process.exit(2);
}
const root = path.resolve(checkout, "sdk/tests");

// A directory's pages from its 00_test_list.txt (options such as --min-version dropped; nested
// lists followed).
function pagesIn(relative) {
  const full = path.join(root, relative);
  if (relative.endsWith(".html")) return existsSync(full) ? [relative] : [];
  const list = path.join(full, "00_test_list.txt");
  if (!existsSync(list)) return [];
  return readFileSync(list, "utf8").split("\n").flatMap((line) => {
    const name = line.replace(/--\S+ \S+\s*/g, "").trim();
    if (!name || name.startsWith("#") || name.startsWith("//")) return [];
    return name.endsWith(".txt") ? pagesIn(path.join(relative, path.dirname(name))) : [path.join(relative, name)];
  });
}

const pages = (wanted.length ? wanted : ["conformance2/glsl3", "conformance2/extensions/promoted-extensions-in-shaders.html"])
  .flatMap(pagesIn);

// The recorder: the harness's four entry points, recording instead of asserting. Defaults are a
// pass-through pair in the other shader's language, as the harness's are.
const recorder = `
(() => {
  const es3 = (s) => s.split("\\n")[0] === "#version 300 es";
  const defaults = {
    v100: "attribute vec4 vPosition;\\nvoid main() { gl_Position = vPosition; }",
    f100: "precision mediump float;\\nvoid main() { gl_FragColor = vec4(0.0, 1.0, 0.0, 1.0); }",
    v300: "#version 300 es\\nin vec4 vPosition;\\nvoid main() { gl_Position = vPosition; }",
    f300: "#version 300 es\\nprecision mediump float;\\nout vec4 color;\\nvoid main() { color = vec4(0.0, 1.0, 0.0, 1.0); }",
  };
  const cases = (window.__shadelabCases = window.__shadelabCases || []);
  const source = (info, stage) => {
    const given = info[stage + "ShaderSource"] ?? (info[stage + "ShaderId"] ? document.getElementById(info[stage + "ShaderId"]).text : undefined);
    return given;
  };
  function record(infos, contextVersion) {
    const canvas = document.createElement("canvas");
    const gl = canvas.getContext("webgl2");
    for (const info of infos) {
      if (info.ignoreResults) continue;
      let v = source(info, "v"), f = source(info, "f");
      let vSuccess = info.vShaderSuccess, fSuccess = info.fShaderSuccess;
      if (v === undefined) { v = f !== undefined && es3(f) ? defaults.v300 : defaults.v100; vSuccess = true; }
      if (f === undefined) { f = es3(v) ? defaults.f300 : defaults.f100; fSuccess = true; }
      if (info.vShaderPrep) v = info.vShaderPrep(v);
      if (info.fShaderPrep) f = info.fShaderPrep(f);
      const expected = vSuccess === false || fSuccess === false ? "compile_failed" : info.linkSuccess ? "accepted" : "link_failed";
      const compile = (type, text) => { const s = gl.createShader(type); gl.shaderSource(s, text); gl.compileShader(s); return s; };
      const vs = compile(gl.VERTEX_SHADER, v), fs = compile(gl.FRAGMENT_SHADER, f);
      let chromium = "compile_failed";
      if (gl.getShaderParameter(vs, gl.COMPILE_STATUS) && gl.getShaderParameter(fs, gl.COMPILE_STATUS)) {
        const p = gl.createProgram();
        gl.attachShader(p, vs); gl.attachShader(p, fs);
        if (v.includes("vPosition")) gl.bindAttribLocation(p, 0, "vPosition");
        gl.linkProgram(p);
        chromium = gl.getProgramParameter(p, gl.LINK_STATUS) ? "accepted" : "link_failed";
      }
      cases.push({ message: info.passMsg ?? "", vertex: v, fragment: f, expected, chromium, contextVersion: contextVersion ?? 2 });
    }
    window.__shadelabDone = true;
  }
  // runTest / runRenderTest: one pair from the page's #vertexShader / #fragmentShader, whose first
  // line ("// fails: ..." / "// succeeds: ...") says what to expect.
  function single() {
    const info = {};
    for (const [stage, id] of [["v", "vertexShader"], ["f", "fragmentShader"]]) {
      const el = document.getElementById(id);
      if (!el) continue;
      const text = el.text.trim();
      info[stage + "ShaderSource"] = text;
      info.passMsg = text.split("\\n")[0].substring(3);
      info[stage + "ShaderSuccess"] = !info.passMsg.includes("fail");
    }
    info.linkSuccess = info.vShaderSuccess !== false && info.fShaderSuccess !== false;
    record([info], 2);
  }
  window.GLSLConformanceTester = { runTests: record, runRenderTests: record, runTest: single, runRenderTest: single };
})();
`;

// Enough of js-test-pre.js for a page's own script to run to its runTests call.
const testPre = `
for (const name of ["description", "debug", "testPassed", "testFailed", "finishTest", "bufferedLogToConsole",
  "shouldBe", "shouldBeTrue", "shouldBeFalse", "shouldBeNull", "shouldBeUndefined", "shouldThrow", "notifyFinishedToHarness"])
  window[name] = () => {};
`;

function serveSuite() {
  const server = createServer((req, res) => {
    const rel = decodeURIComponent(new URL(req.url, "http://x").pathname);
    const file = path.join(root, rel);
    if (!file.startsWith(root + path.sep) || !existsSync(file)) { res.writeHead(404).end(); return; }
    const type = file.endsWith(".html") ? "text/html" : file.endsWith(".js") ? "text/javascript" : "text/plain";
    res.writeHead(200, { "content-type": type }).end(readFileSync(file));
  });
  return new Promise((resolve) => server.listen(0, "127.0.0.1", () => resolve(server)));
}

async function shadelabVerdict(base, c) {
  const start = performance.now();
  const r = await fetch(`${base}/api/compile`, {
    method: "POST", headers: { "content-type": "application/json" },
    body: JSON.stringify({ vertex: c.vertex, fragment: c.fragment }),
  });
  const ms = performance.now() - start;
  if (r.ok) return { verdict: "accepted", status: r.status, ms };
  const problem = await r.json().catch(() => ({}));
  const code = ["missing_version", "shader_source_invalid"].includes(problem.code) ? "compile_failed" : problem.code;
  return { verdict: code ?? `http ${r.status}`, status: r.status, ms };
}

const suite = await serveSuite();
const suiteBase = `http://127.0.0.1:${suite.address().port}`;
const shadelab = await startServer();
const browser = await startBrowser();
const all = [];
try {
  for (const page of pages) {
    const context = await browser.newContext();
    await context.route("**/glsl-conformance-test.js", (route) => route.fulfill({ contentType: "text/javascript", body: recorder }));
    await context.route("**/js-test-pre.js", (route) => route.fulfill({ contentType: "text/javascript", body: testPre }));
    const tab = await context.newPage();
    await tab.goto(`${suiteBase}/${page}?webglVersion=2`);
    await tab.waitForFunction(() => window.__shadelabDone === true, null, { timeout: 20000 }).catch(() => {});
    const cases = await tab.evaluate(() => window.__shadelabCases ?? []);
    for (const c of cases) all.push({ page, ...c, shadelab: await shadelabVerdict(shadelab.base, c) });
    console.error(`${page}: ${cases.length} cases`);
    await context.close();
  }
} finally {
  await browser.close();
  await shadelab.stop();
  suite.close();
}

const count = (pred) => all.filter(pred).length;
const times = all.map((c) => c.shadelab.ms).sort((a, b) => a - b);
const summary = {
  pages: pages.length,
  cases: all.length,
  es100: count((c) => !c.vertex.startsWith("#version 300 es") || !c.fragment.startsWith("#version 300 es")),
  chromiumAgreesWithSuite: count((c) => c.chromium === c.expected),
  shadelabAgreesWithChromium: count((c) => c.shadelab.verdict === c.chromium),
  serverErrors: count((c) => c.shadelab.status >= 500),
  compileMsP50: times[Math.floor(times.length / 2)] ?? null,
  compileMsMax: times.at(-1) ?? null,
};
console.log(JSON.stringify(summary, null, 1));
for (const c of all.filter((x) => x.shadelab.verdict !== x.chromium))
  console.log(`differs: ${c.page}: ${c.message} (Chromium ${c.chromium}, ShadeLab ${c.shadelab.verdict})`);
if (out) writeFileSync(out, JSON.stringify({ summary, cases: all }, null, 1));
