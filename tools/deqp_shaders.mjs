// The dEQP GLES 3 shader cases (Khronos VK-GL-CTS, data/gles3/shaders/*.test), judged by Debian's
// Chromium and by ShadeLab's /api/compile, and where the two agree (issue 82's figure). The suite
// is not in this repository (it is read, not copied): give a checkout of KhronosGroup/VK-GL-CTS.
//
//   node tools/deqp_shaders.mjs CTS_CHECKOUT [--out report.json] [FILE.test ...]
//
// Each case is built as dEQP builds it (glsShaderLibraryCase.cpp, read): a `both` case becomes
// two pairs, `_vertex` (its source specialized as the vertex shader, a generated fragment shader
// beside it) and `_fragment`; a case with its own two stages has its ${VERTEX_...} and
// ${FRAGMENT_...} parameters filled. Cases that need an extension, an implementation limit or
// separable programs (ES 3.1) are counted and left out: WebGL 2 has none of them. Each pair is
// compiled and linked in Chromium's WebGL 2 context (its verdict beside dEQP's expectation), then
// sent to a real server (build/shadelab; SHADELAB_SERVER_PRELOAD preloads a library into it, as
// for tools/webgl_conformance.mjs). Needs the browser tests' npm install (tools/test.sh does it).
import { readdirSync, readFileSync, writeFileSync } from "node:fs";
import path from "node:path";
import { startBrowser, startServer } from "../tests/browser/harness.mjs";

const args = process.argv.slice(2);
const outAt = args.indexOf("--out");
const out = outAt >= 0 ? args.splice(outAt, 2)[1] : null;
const [checkout, ...wanted] = args;
if (!checkout) {
  console.error("usage: node tools/deqp_shaders.mjs CTS_CHECKOUT [--out report.json] [FILE.test ...]");
  process.exit(2);
}
const dir = path.resolve(checkout, "data/gles3/shaders");
const files = wanted.length ? wanted : readdirSync(dir).filter((f) => f.endsWith(".test")).sort();

// --- The .test format (gluShaderLibrary.cpp's parser, read) -------------------------------

function tokenize(text) {
  const tokens = [];
  for (let i = 0; i < text.length; ) {
    const c = text[i];
    if (/\s/.test(c)) { ++i; continue; }
    if (c === "#") { while (i < text.length && text[i] !== "\n") ++i; continue; }
    if (text.startsWith('""', i)) {
      let j = i + 2;
      while (j < text.length && !text.startsWith('""', j)) j += text[j] === "\\" ? 2 : 1;
      tokens.push({ kind: "source", text: text.slice(i + 2, j) });
      i = j + 2;
      continue;
    }
    if (c === '"') {
      let j = i + 1;
      while (j < text.length && text[j] !== '"') j += text[j] === "\\" ? 2 : 1;
      tokens.push({ kind: "string", text: text.slice(i + 1, j) });
      i = j + 1;
      continue;
    }
    const word = /^[A-Za-z0-9_.\-+]+/.exec(text.slice(i, i + 200));
    if (word) { tokens.push({ kind: "word", text: word[0] }); i += word[0].length; continue; }
    tokens.push({ kind: "punct", text: c });
    ++i;
  }
  return tokens;
}

// parseShaderSource: escapes read, the first empty line eaten, the first line's indentation
// taken off every line (a tab counts 4).
function shaderSource(raw) {
  let s = raw.replace(/\\(.)/g, (_, ch) => (ch === "n" ? "\n" : ch === "t" ? "\t" : ch));
  s = s.replace(/^ *\r?\n/, "");
  let indent = 0;
  for (const ch of s) { if (ch === " ") indent += 1; else if (ch === "\t") indent += 4; else break; }
  return s.split(/\r?\n/).map((line) => {
    let k = 0, taken = 0;
    while (k < line.length && taken < indent && (line[k] === " " || line[k] === "\t")) taken += line[k++] === "\t" ? 4 : 1;
    return line.slice(k);
  }).join("\n");
}

function parseCases(text, file) {
  const t = tokenize(text);
  let at = 0;
  const cases = [];
  const skipBlock = () => { // { ... } with nesting
    let depth = 0;
    do { if (t[at].text === "{") ++depth; if (t[at].text === "}") --depth; ++at; } while (depth > 0 && at < t.length);
  };
  const parseValues = () => {
    const values = { inputs: [], outputs: [], uniforms: [] };
    ++at; // {
    while (t[at].text !== "}") {
      const kind = t[at].text;
      if (["input", "output", "uniform"].includes(kind)) {
        values[kind + "s"].push({ type: t[at + 1].text, name: t[at + 2].text });
      }
      while (t[at].text !== ";") ++at;
      ++at;
    }
    ++at;
    return values;
  };
  const parseCase = (prefix) => {
    const name = prefix + t[at++].text;
    const c = { file, name, version: "100", expect: "pass", values: { inputs: [], outputs: [], uniforms: [] }, skipped: null };
    while (t[at].text !== "end") {
      const w = t[at++].text;
      if (w === "version") { c.version = t[at++].text; if (t[at].text === "es") ++at; }
      else if (w === "expect") c.expect = t[at++].text;
      else if (w === "desc") ++at;
      else if (w === "values") c.values = parseValues();
      else if (w === "both" || w === "vertex" || w === "fragment") c[w] = shaderSource(t[at++].text);
      else if (w === "require") {
        c.skipped = "requires an extension or a limit";
        while (t[at].text !== "end" && !["version", "expect", "desc", "values", "both", "vertex", "fragment", "require", "output_color", "pipeline_program"].includes(t[at].text)) {
          if (t[at].text === "{") skipBlock(); else ++at;
        }
      } else if (w === "pipeline_program") {
        c.skipped = "separable programs (ES 3.1)";
        while (t[at].kind === "source" || t[at].text !== "end") ++at;
        ++at;
      } else if (w === "output_color") ++at;
      else if (["tessellation_control", "tessellation_evaluation", "geometry"].includes(w)) { c.skipped = `a ${w} stage`; ++at; }
      else throw new Error(`${file}: ${name}: unexpected '${w}'`);
    }
    ++at;
    return c;
  };
  const parseGroup = (prefix) => {
    while (at < t.length && t[at].text !== "end") {
      const w = t[at++].text;
      if (w === "group") {
        const name = t[at++].text;
        if (t[at].kind === "string") ++at;
        parseGroup(`${prefix}${name}.`);
        ++at; // end
      } else if (w === "case") {
        cases.push(parseCase(prefix));
      } else if (w === "import") {
        ++at;
      } else throw new Error(`${file}: unexpected '${w}'`);
    }
  };
  parseGroup(path.basename(file, ".test") + ".");
  return cases;
}

// --- Specialization (glsShaderLibraryCase.cpp, read) -------------------------------------

const isFloat = (type) => /^(float|vec|mat)/.test(type);
const floatOf = (type) => type.replace(/^[ibu]vec/, "vec").replace(/^(int|uint|bool)$/, "float");
const declaration = (version) => (version === "300" ? "#version 300 es" : "#version 100");

function compareFunctions(values, useFloatTypes) {
  const seen = new Set(values.outputs.map((v) => v.type));
  const lines = [];
  const cmp = (type, text) => { if (seen.has(type)) lines.push(text); };
  if (useFloatTypes) {
    cmp("bool", "bool isOk (float a, bool b) { return ((a > 0.5) == b); }");
    for (const n of [2, 3, 4]) cmp(`bvec${n}`, `bool isOk (vec${n} a, bvec${n} b) { return (greaterThan(a, vec${n}(0.5)) == b); }`);
    cmp("int", "bool isOk (float a, int b)  { float atemp = a+0.5; return (float(b) <= atemp && atemp <= float(b+1)); }");
    for (const n of [2, 3, 4]) cmp(`ivec${n}`, `bool isOk (vec${n} a, ivec${n} b) { return (ivec${n}(floor(a + 0.5)) == b); }`);
    cmp("uint", "bool isOk (float a, uint b) { float atemp = a+0.5; return (float(b) <= atemp && atemp <= float(b+1u)); }");
    for (const n of [2, 3, 4]) cmp(`uvec${n}`, `bool isOk (vec${n} a, uvec${n} b) { return (uvec${n}(floor(a + 0.5)) == b); }`);
  } else {
    for (const type of ["bool", "bvec2", "bvec3", "bvec4", "int", "ivec2", "ivec3", "ivec4", "uint", "uvec2", "uvec3", "uvec4"])
      cmp(type, `bool isOk (${type} a, ${type} b) { return (a == b); }`);
  }
  cmp("float", "bool isOk (float a, float b, float eps) { return (abs(a-b) <= (eps*abs(b) + eps)); }");
  for (const n of [2, 3, 4])
    cmp(`vec${n}`, `bool isOk (vec${n} a, vec${n} b, float eps) { return all(lessThanEqual(abs(a-b), (eps*abs(b) + eps))); }`);
  for (const type of ["mat2", "mat2x3", "mat2x4", "mat3x2", "mat3", "mat3x4", "mat4x2", "mat4x3", "mat4"]) {
    const cols = Number(type[3]), rows = type.length > 4 ? Number(type[5]) : cols;
    const diffs = Array.from({ length: cols }, (_, k) => `abs(a[${k}]-b[${k}])`);
    const max = cols === 2 ? `max(${diffs[0]}, ${diffs[1]})` : cols === 3 ? `max(max(${diffs[0]}, ${diffs[1]}), ${diffs[2]})`
      : `max(max(${diffs[0]}, ${diffs[1]}), max(${diffs[2]}, ${diffs[3]}))`;
    cmp(type, `bool isOk (${type} a, ${type} b, float eps) { vec${rows} diff = ${max}; return all(lessThanEqual(diff, vec${rows}(eps))); }`);
  }
  return lines.map((l) => l + "\n").join("");
}

function compareOp(target, values, prefix) {
  if (!values.outputs.length) return `${target} = vec4(1.0);\n`;
  const checks = values.outputs.map((v, k) => (k ? "RES = RES && " : "bool RES = ") +
    (isFloat(v.type) ? `isOk(${v.name}, ref_${v.name}, 0.05);\n` : `isOk(${prefix}${v.name}, ref_${v.name});\n`));
  return checks.join("") + `${target} = vec4(RES, RES, RES, 1.0);\n`;
}

function genVertexShader(c) {
  const io = c.version === "300" ? ["in", "out"] : ["attribute", "varying"];
  let s = `${declaration(c.version)}\nprecision highp float;\nprecision highp int;\n\n${io[0]} highp vec4 dEQP_Position;\n`;
  for (const v of c.values.inputs) {
    s += `${io[0]} ${floatOf(v.type)} a_${v.name};\n`;
    s += isFloat(v.type) ? `${io[1]} ${floatOf(v.type)} ${v.name};\n` : `${io[1]} ${floatOf(v.type)} v_${v.name};\n`;
  }
  s += "\nvoid main()\n{\n    gl_Position = dEQP_Position;\n";
  for (const v of c.values.inputs) s += isFloat(v.type) ? `    ${v.name} = a_${v.name};\n` : `    v_${v.name} = a_${v.name};\n`;
  return s + "}\n";
}

function genFragmentShader(c) {
  const es3 = c.version === "300";
  const prec = es3 ? "highp" : "mediump";
  let s = `${declaration(c.version)}\nprecision ${prec} float;\nprecision ${prec} int;\n\n`;
  if (es3) s += "layout(location = 0) out mediump vec4 dEQP_FragColor;\n\n";
  s += compareFunctions(c.values, true) + "\n";
  for (const v of c.values.outputs) {
    s += `${es3 ? "in" : "varying"} ${floatOf(v.type)} ${isFloat(v.type) ? "" : "v_"}${v.name};\n`;
    s += `uniform ${v.type} ref_${v.name};\n`;
  }
  return s + "\nvoid main()\n{\n    " + compareOp(es3 ? "dEQP_FragColor" : "gl_FragColor", c.values, "v_") + "}\n";
}

const fill = (template, params) => template.replace(/\$\{(\w+)\}/g, (m, name) => params[name] ?? m);

function specializeVertex(c, src) {
  const io = c.version === "300" ? ["in", "out"] : ["attribute", "varying"];
  let decl = `${io[0]} highp vec4 dEQP_Position;\n`, setup = "", output = "gl_Position = dEQP_Position;\n";
  for (const v of c.values.inputs) {
    if (isFloat(v.type)) decl += `${io[0]} ${floatOf(v.type)} ${v.name};\n`;
    else { decl += `${io[0]} ${floatOf(v.type)} a_${v.name};\n`; setup += `${v.type} ${v.name} = ${v.type}(a_${v.name});\n`; }
  }
  for (const v of c.values.outputs) {
    if (isFloat(v.type)) decl += `${io[1]} ${floatOf(v.type)} ${v.name};\n`;
    else {
      decl += `${io[1]} ${floatOf(v.type)} v_${v.name};\n${v.type} ${v.name};\n`;
      output += `v_${v.name} = ${floatOf(v.type)}(${v.name});\n`;
    }
  }
  return fill(src, { DECLARATIONS: decl, SETUP: setup, OUTPUT: output, POSITION_FRAG_COLOR: "gl_Position" });
}

function specializeFragment(c, src) {
  const es3 = c.version === "300";
  const fragColor = es3 ? "dEQP_FragColor" : "gl_FragColor";
  let decl = compareFunctions(c.values, false), setup = "";
  const output = compareOp(fragColor, c.values, "");
  if (es3) decl += "layout(location = 0) out mediump vec4 dEQP_FragColor;\n";
  for (const v of c.values.inputs) {
    if (isFloat(v.type)) decl += `${es3 ? "in" : "varying"} ${floatOf(v.type)} ${v.name};\n`;
    else {
      decl += `${es3 ? "in" : "varying"} ${floatOf(v.type)} v_${v.name};\n`;
      const offset = /^(int|ivec)/.test(v.type) ? " * 1.0025" : "";
      setup += `${v.type} ${v.name} = ${v.type}(v_${v.name}${offset});\n`;
    }
  }
  for (const v of c.values.outputs) decl += `uniform ${v.type} ref_${v.name};\n${v.type} ${v.name};\n`;
  return fill(src, { DECLARATIONS: decl, SETUP: setup, OUTPUT: output, POSITION_FRAG_COLOR: fragColor });
}

function uniformDeclarations(values) {
  return values.uniforms.filter((v) => !v.name.includes(".")).map((v) => `uniform ${v.type} ${v.name};\n`).join("");
}

function specializeComplete(c) {
  const es3 = c.version === "300";
  const vin = es3 ? "in" : "attribute";
  let vdecl = `${vin} highp vec4 dEQP_Position;\n`, vsetup = "";
  for (const v of c.values.inputs) {
    if (isFloat(v.type)) vdecl += `${vin} ${v.type} ${v.name};\n`;
    else { vdecl += `${vin} ${floatOf(v.type)} a_${v.name};\n`; vsetup += `${v.type} ${v.name} = ${v.type}(a_${v.name});\n`; }
  }
  vdecl += uniformDeclarations(c.values);
  const fragColor = es3 ? "dEQP_FragColor" : "gl_FragColor";
  let fdecl = compareFunctions(c.values, false);
  if (es3) fdecl += "layout(location = 0) out mediump vec4 dEQP_FragColor;\n";
  for (const v of c.values.outputs) fdecl += `uniform ${v.type} ref_${v.name};\n${v.type} ${v.name};\n`;
  fdecl += uniformDeclarations(c.values);
  const params = {
    VERTEX_DECLARATIONS: vdecl, VERTEX_SETUP: vsetup, VERTEX_OUTPUT: "gl_Position = dEQP_Position;\n",
    FRAGMENT_DECLARATIONS: fdecl, FRAGMENT_OUTPUT: compareOp(fragColor, c.values, ""), FRAG_COLOR: fragColor,
  };
  return { vertex: fill(c.vertex, params), fragment: fill(c.fragment, params) };
}

function pairsOf(c) {
  if (c.both !== undefined)
    return [
      { name: `${c.name}_vertex`, vertex: specializeVertex(c, c.both), fragment: genFragmentShader(c) },
      { name: `${c.name}_fragment`, vertex: genVertexShader(c), fragment: specializeFragment(c, c.both) },
    ];
  if (c.vertex === undefined || c.fragment === undefined) return [];
  return [{ name: c.name, ...specializeComplete(c) }];
}

// --- Judging -----------------------------------------------------------------------------

const expected = { pass: ["accepted"], build_successful: ["accepted"], compile_fail: ["compile_failed"],
  link_fail: ["link_failed"], compile_or_link_fail: ["compile_failed", "link_failed"] };

async function chromiumVerdicts(page, pairs) {
  return page.evaluate((all) => {
    const gl = document.getElementById("c").getContext("webgl2");
    const compile = (type, text) => { const s = gl.createShader(type); gl.shaderSource(s, text); gl.compileShader(s); return s; };
    return all.map(({ vertex, fragment }) => {
      const vs = compile(gl.VERTEX_SHADER, vertex), fs = compile(gl.FRAGMENT_SHADER, fragment);
      let verdict = "compile_failed";
      if (gl.getShaderParameter(vs, gl.COMPILE_STATUS) && gl.getShaderParameter(fs, gl.COMPILE_STATUS)) {
        const p = gl.createProgram();
        gl.attachShader(p, vs); gl.attachShader(p, fs); gl.linkProgram(p);
        verdict = gl.getProgramParameter(p, gl.LINK_STATUS) ? "accepted" : "link_failed";
        gl.deleteProgram(p);
      }
      gl.deleteShader(vs); gl.deleteShader(fs);
      return verdict;
    });
  }, pairs);
}

async function shadelabVerdict(base, pair) {
  const r = await fetch(`${base}/api/compile`, {
    method: "POST", headers: { "content-type": "application/json" },
    body: JSON.stringify({ vertex: pair.vertex, fragment: pair.fragment }),
  });
  if (r.ok) return { verdict: "accepted", status: r.status };
  const problem = await r.json().catch(() => ({}));
  const code = ["missing_version", "shader_source_invalid"].includes(problem.code) ? "compile_failed" : problem.code;
  return { verdict: code ?? `http ${r.status}`, status: r.status, detail: problem.detail };
}

const cases = files.flatMap((f) => parseCases(readFileSync(path.join(dir, f), "utf8"), f));
const skipped = cases.filter((c) => c.skipped);
const pairs = cases.filter((c) => !c.skipped).flatMap((c) => pairsOf(c).map((p) => ({ ...p, expect: c.expect })));
const shadelab = await startServer();
const browser = await startBrowser();
try {
  const page = await browser.newPage();
  await page.setContent("<canvas id=c></canvas>");
  for (let k = 0; k < pairs.length; k += 200) {
    const slice = pairs.slice(k, k + 200);
    const verdicts = await chromiumVerdicts(page, slice);
    slice.forEach((p, i) => { p.chromium = verdicts[i]; });
  }
  for (const p of pairs) p.shadelab = await shadelabVerdict(shadelab.base, p);
} finally {
  await browser.close();
  await shadelab.stop();
}

const count = (pred) => pairs.filter(pred).length;
const summary = {
  files: files.length,
  cases: cases.length,
  skipped: skipped.length,
  pairs: pairs.length,
  es300Pairs: count((p) => p.vertex.startsWith("#version 300 es")),
  es300Agree: count((p) => p.vertex.startsWith("#version 300 es") && p.shadelab.verdict === p.chromium),
  chromiumAgreesWithDeqp: count((p) => expected[p.expect]?.includes(p.chromium)),
  shadelabAgreesWithChromium: count((p) => p.shadelab.verdict === p.chromium),
  serverErrors: count((p) => p.shadelab.status >= 500),
};
console.log(JSON.stringify(summary, null, 1));
for (const p of pairs.filter((x) => x.shadelab.verdict !== x.chromium))
  console.log(`differs: ${p.name} (dEQP ${p.expect}, Chromium ${p.chromium}, ShadeLab ${p.shadelab.verdict}: ${p.shadelab.detail ?? ""})`);
if (out) writeFileSync(out, JSON.stringify({ summary, skipped: skipped.map((c) => `${c.name}: ${c.skipped}`), pairs }, null, 1));
