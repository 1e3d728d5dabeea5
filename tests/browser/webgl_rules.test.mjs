// WebGL 2's shader rules, both directions, judged twice on tests/webgl_rules/cases.json: by
// Debian's Chromium (its WebGL 2 compiler is the one students' browsers run) and by the real
// server's /api/compile. Each case's written verdict must be both of theirs: the file is
// checked against a browser, and ShadeLab against the file.
import { after, before, test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import path from "node:path";
import { repo, startBrowser, startServer } from "./harness.mjs";

const { cases } = JSON.parse(readFileSync(path.join(repo, "tests/webgl_rules/cases.json"), "utf8"));
const source = (lines) => lines.join("\n") + "\n";
let server, browser, page;

before(async () => {
  server = await startServer();
  browser = await startBrowser();
  page = await browser.newPage();
  await page.setContent("<canvas id=c></canvas>");
});
after(async () => {
  await browser?.close();
  await server?.stop();
});

// compile_failed, link_failed or accepted, as a WebGL 2 page finds out.
function browserVerdicts(pairs) {
  return page.evaluate((all) => {
    const gl = document.getElementById("c").getContext("webgl2");
    if (!gl) throw new Error("no WebGL 2 context");
    const compile = (type, text) => {
      const s = gl.createShader(type);
      gl.shaderSource(s, text);
      gl.compileShader(s);
      return s;
    };
    return all.map(({ vertex, fragment }) => {
      const vs = compile(gl.VERTEX_SHADER, vertex), fs = compile(gl.FRAGMENT_SHADER, fragment);
      const compiled = gl.getShaderParameter(vs, gl.COMPILE_STATUS) && gl.getShaderParameter(fs, gl.COMPILE_STATUS);
      let verdict = "compile_failed";
      if (compiled) {
        const p = gl.createProgram();
        gl.attachShader(p, vs);
        gl.attachShader(p, fs);
        gl.linkProgram(p);
        verdict = gl.getProgramParameter(p, gl.LINK_STATUS) ? "accepted" : "link_failed";
        gl.deleteProgram(p);
      }
      gl.deleteShader(vs);
      gl.deleteShader(fs);
      return verdict;
    });
  }, pairs);
}

// What ShadeLab refuses before any compiler runs is a failed compile in the browser.
const sourceCodes = new Set(["missing_version", "shader_source_invalid"]);

async function serverVerdict(base, vertex, fragment) {
  const r = await fetch(`${base}/api/compile`, {
    method: "POST",
    headers: { "content-type": "application/json" },
    body: JSON.stringify({ vertex, fragment }),
  });
  if (r.ok) return "accepted";
  const problem = await r.json();
  return sourceCodes.has(problem.code) ? "compile_failed" : problem.code;
}

test("Chromium and ShadeLab give every case its written verdict", async () => {
  assert.ok(cases.length >= 30);
  const pairs = cases.map((c) => ({ vertex: source(c.vertex), fragment: source(c.fragment) }));
  const chromium = await browserVerdicts(pairs);
  const disagreements = [];
  for (let k = 0; k < cases.length; ++k) {
    const shadelab = await serverVerdict(server.base, pairs[k].vertex, pairs[k].fragment);
    // A case Mesa refuses though the browser runs it: on llvmpipe, this server's limit, said as such.
    const mesa = process.env.SHADELAB_SERVER_PRELOAD ? undefined : cases[k].mesa;
    if (chromium[k] !== cases[k].verdict || (shadelab !== cases[k].verdict && shadelab !== mesa))
      disagreements.push(`${cases[k].name}: written ${cases[k].verdict}, Chromium ${chromium[k]}, ShadeLab ${shadelab}`);
  }
  assert.deepEqual(disagreements, []);
});
