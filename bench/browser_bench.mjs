// The canonical job as a course runs it in the browser: headless Chromium (Debian's, through
// playwright-core, SwiftShader's WebGL2 with 4x MSAA, as tests/browser) on ShadeLab's copy of the
// homework page. Each job compiles a fragment shader the browser has not seen, draws the course's
// frames of its bunny on its canvas (9 frames, 512 x 512) and saves each with toBlob as the
// student's page does, then composes the 3x3 grid on a canvas and encodes it as a PNG.
//
//   node bench/browser_bench.mjs [JOBS=20]     (needs tests/browser's npm install and build/shadelab)
import { readFileSync } from "node:fs";
import path from "node:path";

import { openPage, repo, startBrowser, startServer } from "../tests/browser/harness.mjs";

const jobs = Number(process.argv[2] ?? 20);
// The GLSL of a homework JS module: its default-exported template literal.
const glslOf = (file) => readFileSync(path.join(repo, "shaders", file), "utf8").match(/export\s+default\s*`([\s\S]*?)`/)[1];
const vertex = glslOf("specular_vert.js");
const fragment = glslOf("specular_frag.js");
const entry = "void main(void) {";
if (!fragment.includes(entry)) throw new Error("the preset's fragment shader has no main");

const server = await startServer();
const browser = await startBrowser();
try {
  const { page } = await openPage(browser, server.base);
  await page.evaluate(async () => window.shadelab.chooseMesh(window.shadelab.course.defaultMesh));
  // The page's spinning preview draws a frame at every animation frame; left on, each toBlob
  // waits behind those draws (measured: 0.1-1.1 s a frame). The job alone is what is compared.
  await page.evaluate(() => {
    const spin = document.getElementById("spin");
    if (spin.checked) spin.click();
  });
  const base = Math.floor(Math.random() * 1e8);
  const times = [];
  for (let i = -2; i < jobs; ++i) {  // two warm-up jobs, as floor_bench and load_bench discard theirs
    const fresh = fragment.replace(entry, `${entry}\n    if (gl_FragCoord.x < -${base + i + 2}.0) discard;`);
    const t0 = performance.now();
    const bytes = await page.evaluate(async ([vs, fs]) => {
      const { view, course } = window.shadelab;
      const { width: w, height: h } = course.canvas;
      const n = course.frames.count;
      [view.canvas.width, view.canvas.height] = [w, h];
      const errors = view.setProgram({ glsl: vs, lineOffset: 0 }, { glsl: fs, lineOffset: 0 });
      if (errors.length) throw new Error(JSON.stringify(errors));
      const frames = [];
      for (let k = 0; k < n; ++k) frames.push(await view.captureFrame(course.frames.degreesPerFrame * k));
      const grid = new OffscreenCanvas(3 * w, Math.ceil(n / 3) * h);
      const ctx = grid.getContext("2d");
      for (let k = 0; k < n; ++k) ctx.drawImage(await createImageBitmap(frames[k]), (k % 3) * w, Math.floor(k / 3) * h);
      return (await grid.convertToBlob({ type: "image/png" })).size;
    }, [vertex, fresh]);
    if (bytes < 1000) throw new Error("the grid PNG is empty");
    if (i >= 0) times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  console.log(`headless Chromium (WebGL2 page, toBlob frames, grid PNG), ${jobs} jobs: p50 ${times[Math.floor(times.length / 2)].toFixed(1)} ms`);
} finally {
  await browser.close();
  await server.stop();
}
