// A hostile student (docs/reliability.md, "The attacker"): their files, their folder names and any
// request, with or without a key. The server runs as a child process, so an attack that crashes
// it fails a test instead of killing the run; its resident peak is read from /proc. Each test is
// an attack that worked before 2026-12-06 and must now fail.
import assert from "node:assert/strict";
import { mkdtempSync, readFileSync, writeFileSync } from "node:fs";
import os from "node:os";
import path from "node:path";
import { deflateSync, inflateSync } from "node:zlib";
import { after, before, describe, test } from "node:test";

import { openPage, repo, startBrowser, startServer } from "./harness.mjs";

const cases = JSON.parse(readFileSync(path.join(repo, "tests/shader_source/module_cases.json"), "utf8")).cases;
const shaderText = (file) => readFileSync(path.join(repo, "shaders", file), "utf8");
const STAFF = "staff-key-0123456789abcdef", STUDENT = "student-key-0123456789abc";
const ONE_GIB = 1 << 30;

let server, browser;
before(async () => {
  const keys = path.join(mkdtempSync(path.join(os.tmpdir(), "shadelab-hostile-")), "keys");
  writeFileSync(keys, `${STAFF} ta staff\n${STUDENT} alice\n`);
  server = await startServer(["--api-keys", keys, "--students-without-keys"]);
  browser = await startBrowser();
});
after(async () => {
  await browser?.close();
  await server?.stop();
});

// The most memory the server process has held (VmHWM), in bytes.
const residentPeak = (pid) => Number(/VmHWM:\s+(\d+) kB/.exec(readFileSync(`/proc/${pid}/status`, "utf8"))[1]) * 1024;

async function stillAnswers() {
  assert.ok(!server.exited(), "the server process died");
  assert.equal((await fetch(`${server.base}/livez`)).status, 200);
}

// Once more where the server closed a kept-alive socket as the request went out (a test that
// held the event loop saw its close late): every request here may be sent twice.
async function post(route, body, headers = {}) {
  const send = () => fetch(`${server.base}${route}`, { method: "POST", headers: { "Content-Type": "application/json", ...headers }, body });
  try {
    return await send();
  } catch (e) {
    if (e.cause?.code !== "UND_ERR_SOCKET") throw e;
    return send();
  }
}

describe("a student's shader file is read, never run", () => {
  test("Chromium's own import() does with each module case what the case says, and the page's reader reads what it says", async () => {
    // The browser's verdict, on a blank page of its own (no CSP): what the student's page would do.
    const blank = await browser.newPage();
    await blank.goto("about:blank");
    const { page, context } = await openPage(browser, server.base);
    try {
      for (const c of cases) {
        if (c.browser !== "raw") {
          const verdict = await blank.evaluate(async (file) => {
            try {
              const m = await import(URL.createObjectURL(new Blob([file], { type: "text/javascript" })));
              return typeof m.default === "string" ? { accepts: true, glsl: m.default.replace(/\r\n?/g, "\n") } : { accepts: false };
            } catch (e) {
              return { accepts: false, error: String(e) };
            }
          }, c.file);
          assert.equal(verdict.accepts, c.browser === "accepts", `${c.name}: Chromium ${verdict.accepts ? "accepts" : "refuses"} it (${verdict.error ?? ""})`);
          if (c.glsl !== undefined) assert.equal(verdict.glsl, c.glsl, `${c.name}: Chromium reads other GLSL`);
        }
        const read = await page.evaluate(async (file) => {
          const m = await import("/js/shader_module.js");
          try {
            return { glsl: m.glslFromFile(file).glsl, module: m.looksLikeModule(file) };
          } catch (e) {
            return { error: e.message, line: e.line };
          }
        }, c.file);
        if (c.glsl !== undefined) assert.equal(read.glsl, c.glsl, `${c.name}: the page reads ${JSON.stringify(read)}`);
        else assert.ok(read.error !== undefined || !read.module, `${c.name}: the page read it as ${JSON.stringify(read.glsl)}`);
        if (typeof c.refused === "string") assert.match(read.error ?? "", new RegExp(c.refused.replace(/[.*+?^${}()|[\]\\]/g, "\\$&")), c.name);
      }
    } finally {
      await blank.close();
      await context.close();
    }
  });

  test("a phong_frag.js with code after its string runs nothing in a TA's page: Apply locally, Render on server", async () => {
    const { page, context } = await openPage(browser, server.base);
    try {
      // A TA: their staff key entered, which the file's code would carry off were it anywhere a
      // script can read (it was in localStorage; it is an HttpOnly cookie now).
      assert.ok(await page.evaluate(async (key) => (await fetch("/api/session", { method: "POST", headers: { Authorization: `Bearer ${key}` } })).ok, STAFF));
      await page.reload();
      assert.equal((await page.evaluate(async () => (await fetch("/api/session")).json())).role, "staff");
      const readable = await page.evaluate(() => JSON.stringify(localStorage) + document.cookie);
      assert.equal(readable.includes(STAFF), false, "a script can read the staff key");
      await page.waitForFunction(() => window.shadelab !== undefined, null, { timeout: 30000 });
      await page.waitForFunction(() => document.querySelectorAll("#preset option").length > 0, null, { timeout: 30000 });
      const starter = shaderText("starter_frag.js");
      for (const tail of ["\ndocument.title = 'pwned';\n", " // note\u2028document.title = 'pwned';\n"]) {
        await page.fill("#fragment", starter.trimEnd() + tail);
        await page.locator("#apply").click();
        await page.waitForFunction(() => document.querySelector("#local-status").textContent !== "", null, { timeout: 30000 });
        assert.match(await page.textContent("#local-status"), /does not load/);
        await page.locator("#render-server").click();
        await page.waitForFunction(() => /shader|module|text after/i.test(document.querySelector("#server-status").textContent), null, { timeout: 60000 });
        assert.notEqual(await page.title(), "pwned", "the file's code ran in the page");
        await page.evaluate(() => { document.querySelector("#local-status").textContent = ""; document.querySelector("#server-status").textContent = ""; });
      }
      // And were a regression to import a blob, the page's policy would refuse to run it.
      const ran = await page.evaluate(async () => {
        try {
          await import(URL.createObjectURL(new Blob(["document.title = 'pwned';"], { type: "text/javascript" })));
          return document.title === "pwned";
        } catch {
          return false;
        }
      });
      assert.equal(ran, false, "a blob: module ran under the page's Content-Security-Policy");
    } finally {
      await context.close();
    }
  });

  test("the page is served with a policy that runs script only from the server itself", async () => {
    const policy = (await fetch(`${server.base}/`)).headers.get("content-security-policy") ?? "";
    assert.match(policy, /script-src 'self'(;|$)/);
    assert.doesNotMatch(policy, /unsafe-inline|unsafe-eval|blob:[^;]*script|script-src[^;]*blob:/);
  });

  test("a correct shader followed by `// note` U+2028 code scores nothing on /api/grade", async () => {
    const vertex = shaderText("specular_vert.js"), fragment = shaderText("specular_frag.js").trimEnd() + " // note\u2028document.title = 'pwned';\n";
    const r = await post("/api/grade", JSON.stringify({ reference: "specular", vertex, fragment, vertexName: "phong_vert.js", fragmentName: "phong_frag.js" }), { Authorization: `Bearer ${STAFF}` });
    const body = await r.json();
    assert.notEqual(body.score, body.maxScore ?? 1, JSON.stringify(body).slice(0, 400));
    assert.match(JSON.stringify(body), /unexpected text after the shader string/);
  });
});

// An 8-bit RGB or RGBA PNG (what ShadeLab writes) as {width, height, rgba(x, y)}.
function decodePng(png) {
  let width = 0, height = 0, channels = 0;
  const idat = [];
  for (let at = 8; at < png.length; ) {
    const length = png.readUInt32BE(at), type = png.toString("latin1", at + 4, at + 8), data = png.subarray(at + 8, at + 8 + length);
    if (type === "IHDR") [width, height, channels] = [data.readUInt32BE(0), data.readUInt32BE(4), { 2: 3, 6: 4 }[data[9]]];
    if (type === "IDAT") idat.push(data);
    at += 12 + length;
  }
  assert.equal(png.subarray(0, 8).toString("latin1"), "\x89PNG\r\n\x1a\n");
  const raw = inflateSync(Buffer.concat(idat)), stride = width * channels, rows = Buffer.alloc(stride * height);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)], line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? rows[y * stride + i - channels] : 0, b = y > 0 ? rows[(y - 1) * stride + i] : 0;
      const c = i >= channels && y > 0 ? rows[(y - 1) * stride + i - channels] : 0;
      const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
      const predicted = [0, a, b, (a + b) >> 1, pa <= pb && pa <= pc ? a : pb <= pc ? b : c][filter];
      rows[y * stride + i] = (line[i] + predicted) & 0xff;
    }
  }
  return { width, height, rgb: (x, y) => [...rows.subarray((y * width + x) * channels, (y * width + x) * channels + 3)].join(",") };
}

describe("the staff key", () => {
  test("rides only on the server's own pages: a cookie sent from another origin, or as a script's request from elsewhere, is no key", async () => {
    const start = await fetch(`${server.base}/api/session`, { method: "POST", headers: { Authorization: `Bearer ${STAFF}` } });
    const setCookie = start.headers.get("set-cookie") ?? "";
    assert.match(setCookie, /HttpOnly/);
    assert.match(setCookie, /SameSite=Strict/);
    assert.doesNotMatch(setCookie, new RegExp(STAFF), "the key in the cookie as written");
    const cookie = setCookie.split(";")[0];
    const role = async (headers) => (await (await fetch(`${server.base}/api/session`, { headers: { Cookie: cookie, ...headers } })).json()).role;
    assert.equal(await role({}), "staff");
    assert.equal(await role({ Origin: server.base }), "staff");
    assert.equal(await role({ Origin: "http://evil.example" }), "student");
    assert.equal(await role({ "Sec-Fetch-Site": "cross-site" }), "student");
    assert.equal(await role({ "Sec-Fetch-Site": "same-site" }), "student");
    const ended = await fetch(`${server.base}/api/session/end`, { method: "POST", headers: { Cookie: cookie } });
    assert.match(ended.headers.get("set-cookie") ?? "", /Max-Age=0/);
  });
});

describe("what a student sees is not the reference", () => {
  // A black submission: per pixel, the heat map's ramp inverted to the reference's brightest
  // channel below 0.5. The course shows its students blocks (differencePicture); staff every pixel.
  test("a black submission's difference picture is blocks of three shades for a student, every pixel for staff", async () => {
    const fragment = shaderText("starter_frag.js").replace("fragColor = vec4(normalize(abs(vNormal.xyz)), 1.0);", "fragColor = vec4(0.0, 0.0, 0.0, 1.0);");
    const body = JSON.stringify({ reference: "diffuse", vertex: shaderText("starter_vert.js"), fragment });
    const picture = async (headers) => {
      const graded = await (await post("/api/grade", body, headers)).json();
      assert.ok(graded.heatmap, JSON.stringify(graded).slice(0, 300));
      return decodePng(Buffer.from(graded.heatmap, "base64"));
    };
    const student = await picture({}), staff = await picture({ Authorization: `Bearer ${STAFF}` });
    const colours = (p) => { const seen = new Set(); for (let y = 0; y < p.height; ++y) for (let x = 0; x < p.width; ++x) seen.add(p.rgb(x, y)); return seen; };
    const shown = colours(student), staffShown = colours(staff);
    assert.deepEqual([...shown].filter((c) => !["0,0,0", "255,0,0", "255,255,0"].includes(c)), [], "a shade other than the three");
    assert.ok(shown.size >= 2, "the student's picture shows where the frames differ");
    assert.ok(staffShown.size > 16, `staff see every pixel's difference (${staffShown.size} colours)`);
    // Each block one shade: 32 pixels a side, 16 a side of each 512 x 512 frame (the grid lays the
    // course's frames 3 x 3).
    const side = 32;
    assert.equal(student.width, 3 * 512);
    for (let y = 0; y < student.height; y += side)
      for (let x = 0; x < student.width; x += side)
        for (const [dx, dy] of [[side - 1, 0], [0, side - 1], [side - 1, side - 1], [side >> 1, side >> 1]])
          assert.equal(student.rgb(x + dx, y + dy), student.rgb(x, y), `the block at ${x}, ${y} is not one shade`);
  });

  test("a uniform typed otherwise than the reference's says only that the reference could not be drawn with it", async () => {
    const fragment = shaderText("starter_frag.js")
      .replace("out vec4 fragColor;", "out vec4 fragColor;\nuniform float uSpecularColor;")
      .replace("fragColor = vec4(normalize(abs(vNormal.xyz)), 1.0);", "fragColor = vec4(normalize(abs(vNormal.xyz)) * uSpecularColor, 1.0);");
    const r = await post("/api/grade", JSON.stringify({ reference: "specular", vertex: shaderText("starter_vert.js"), fragment, uniforms: { uSpecularColor: 1 } }));
    const text = await r.text();
    assert.match(text, /the reference cannot be drawn with the uniform values sent/, text.slice(0, 400));
    assert.doesNotMatch(text, /vec4|vec3/, "the reference's uniform types reached a student");
  });
});

describe("every input has a budget before it is read", () => {
  const nested = (depth) => "[".repeat(depth) + "]".repeat(depth);

  test("keyless bodies nesting 200,000 arrays are refused with a short 400, and the server answers on", async () => {
    const attempts = [
      ["/api/grade", `{"reference": "specular", "savedFrames": ${nested(200000)}}`, {}],
      ["/api/render", `{"preset": "starter", "width": ${nested(200000)}}`, { Authorization: `Bearer ${STUDENT}` }],
      ["/api/grade", `{"reference": "specular", "savedFrames": ${nested(20000)}}`, {}],
    ];
    for (const [route, body, headers] of attempts) {
      const r = await post(route, body, headers);
      const text = await r.text();
      assert.equal(r.status, 400, `${route}: ${text.slice(0, 200)}`);
      assert.match(text, /levels deep/);
      assert.ok(text.length < 2000, `${route}: the 400 is ${text.length} bytes (it echoes the body)`);
      await stillAnswers();
    }
  });

  test("a 16 MiB body of empty arrays is refused before it becomes millions of values", async () => {
    const body = `{"reference": "specular", "savedFrames": [${"[],".repeat((15 << 20) / 3)}[]]}`;
    const r = await post("/api/grade", body);
    const text = await r.text();
    assert.equal(r.status, 413, text.slice(0, 200));
    assert.match(text, /JSON values/);
    await stillAnswers();
    assert.ok(residentPeak(server.pid) < ONE_GIB, `the server held ${residentPeak(server.pid)} bytes`);
  });

  // A grey PNG of `side` x `side` (8 bits, one channel): zeros deflate to a few kilobytes.
  function bigPng(side) {
    const crcTable = Array.from({ length: 256 }, (_, n) => { let c = n; for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; return c >>> 0; });
    const crc = (bytes) => { let c = 0xffffffff; for (const b of bytes) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8); return (c ^ 0xffffffff) >>> 0; };
    const chunk = (type, data) => {
      const out = Buffer.alloc(12 + data.length);
      out.writeUInt32BE(data.length, 0);
      out.write(type, 4, "latin1");
      data.copy(out, 8);
      out.writeUInt32BE(crc(out.subarray(4, 8 + data.length)), 8 + data.length);
      return out;
    };
    const header = Buffer.alloc(13);
    header.writeUInt32BE(side, 0);
    header.writeUInt32BE(side, 4);
    header[8] = 8;  // bit depth; colour type 0 (grey), the rest 0
    const signature = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
    return Buffer.concat([signature, chunk("IHDR", header), chunk("IDAT", deflateSync(Buffer.alloc((side + 1) * side), { level: 9 })), chunk("IEND", Buffer.alloc(0))]);
  }

  test("a keyless sheet of 27 PNGs that each decode to 4096 x 4096 is refused before a decode", async () => {
    const png = bigPng(4096).toString("base64");
    const images = {};
    for (const d of ["normals", "diffuse", "specular"]) for (let k = 0; k < 9; ++k) images[`images/hw2_${d}_${k}.png`] = png;
    const files = { "shaders/phong_vert.js": shaderText("starter_vert.js"), "shaders/phong_frag.js": shaderText("starter_frag.js") };
    const before = Date.now();
    const r = await post("/api/sheet", JSON.stringify({ files, images, format: "html" }));
    const text = await r.text();
    assert.equal(r.status, 413, text.slice(0, 300));
    assert.match(text, /pixels in all/);
    assert.ok(Date.now() - before < 20000, "the refusal took as long as decoding");
    await stillAnswers();
    assert.ok(residentPeak(server.pid) < ONE_GIB, `the server held ${residentPeak(server.pid)} bytes`);
  });
});

describe("/metrics", () => {
  test("labels come from the server's own routes: a made-up path is 'unknown', never a series of its own", async () => {
    for (let i = 0; i < 40; ++i) await fetch(`${server.base}/api/made-up-${i}`);
    await fetch(`${server.base}/api/x%22%7D%20shadelab_worker_crashes_total%2099999%0Ay`);
    await fetch(`${server.base}/api/meshes/m0123456789abcdef.obj`);
    const text = await (await fetch(`${server.base}/metrics`)).text();
    assert.doesNotMatch(text, /made-up|99999|m0123456789abcdef/);
    assert.match(text, /shadelab_requests_total\{route="unknown",status="(401|404)"\} \d+/);
    assert.match(text, /route="GET \/api\/meshes\/\{id\}\.obj"/);
    const series = text.split("\n").filter((l) => l.startsWith("shadelab_requests_total")).length;
    assert.ok(series < 40, `${series} request series`);
  });
});
