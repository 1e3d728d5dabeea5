// The PrairieLearn checkpoint question's live canvas in Debian's chromium: the question installed by
// prairielearn/install_questions.py, its question.html as PrairieLearn renders it (the client files'
// URL filled in; each pl-file-editor as the Ace editor PrairieLearn puts there, holding the file it
// opens on), served over HTTP. The canvas must draw the starter on the course's mesh and say where a
// shader that does not compile is wrong, as the student types.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, writeFileSync } from "node:fs";
import http from "node:http";
import os from "node:os";
import path from "node:path";
import { after, before, test } from "node:test";

import { openPage, repo, startBrowser } from "./harness.mjs";

const plCourse = mkdtempSync(path.join(os.tmpdir(), "shadelab-pl-course-"));
const question = path.join(plCourse, "questions", "shadelab-hw2-specular");
let browser, server, base;

// Ace as PrairieLearn's pl-file-editor leaves it: an element of class ace_editor whose env.editor
// gives the text. The editor's text lives on the element so the test can type into it.
function asRendered(html) {
  return html
    .replaceAll("{{options.client_files_question_url}}", "/clientFilesQuestion")
    .replace(/<pl-file-editor[^>]*source-file-name="([^"]+)"[^>]*><\/pl-file-editor>/g, (_, file) => {
      const text = JSON.stringify(readFileSync(path.join(question, file), "utf8"));
      return `<div class="ace_editor" data-file="${file}"></div><script>(() => { const e = document.currentScript.previousElementSibling;` +
        ` e.text = ${text}; e.env = { editor: { getValue: () => e.text } }; })();</script>`;
    });
}

before(async () => {
  execFileSync("python3", [path.join(repo, "prairielearn/install_questions.py"), plCourse], { env: process.env });
  const page = asRendered(readFileSync(path.join(question, "question.html"), "utf8"));
  server = http.createServer((req, res) => {
    const url = new URL(req.url, "http://localhost");
    if (url.pathname === "/favicon.ico") return res.writeHead(204).end();  // PrairieLearn's own, not the question's
    if (url.pathname === "/") return res.writeHead(200, { "Content-Type": "text/html" }).end(`<!doctype html><html><body>${page}</body></html>`);
    const file = path.join(question, path.normalize(url.pathname));
    if (!file.startsWith(path.join(question, "clientFilesQuestion"))) return res.writeHead(404).end();
    const types = { ".js": "text/javascript", ".json": "application/json", ".obj": "text/plain" };
    try {
      res.writeHead(200, { "Content-Type": types[path.extname(file)] ?? "application/octet-stream" }).end(readFileSync(file));
    } catch {
      res.writeHead(404).end();
    }
  });
  await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
  base = `http://127.0.0.1:${server.address().port}`;
  browser = await startBrowser();
});
after(async () => {
  await browser?.close();
  server?.close();
});

// Lit pixels of the canvas's next frame, read in the same frame as live.js draws it.
const litPixels = (page) =>
  page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(() => {
    const canvas = document.getElementById("shadelab-live");
    const gl = canvas.getContext("webgl2");
    const pixels = new Uint8Array(canvas.width * canvas.height * 4);
    gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    let lit = 0;
    for (let i = 0; i < pixels.length; i += 4) lit += pixels[i] + pixels[i + 1] + pixels[i + 2] > 30;
    resolve(lit);
  }))));

test("the checkpoint question's canvas draws the student's shaders as they type", async () => {
  const { page, context, consoleErrors } = await openPage(browser, base, { ready: "document" });
  try {
    // The starter on the bunny: a lit object in the middle of a black canvas.
    await page.waitForFunction(() => document.getElementById("shadelab-live-status").textContent === "" &&
      document.querySelectorAll(".ace_editor").length === 2, null, { timeout: 30000 });
    let lit = 0;
    for (let i = 0; i < 50 && lit === 0; ++i) lit = await litPixels(page);
    assert.ok(lit > 5000, `the starter draws the bunny: ${lit} lit pixels`);
    // A fragment shader that does not compile: the status says where, and the canvas keeps the last good program.
    await page.evaluate(() => {
      const fragment = document.querySelectorAll(".ace_editor")[1];
      fragment.text = fragment.text.replace("void main", "vod main");
    });
    await page.waitForFunction(() => /fragment line \d+/.test(document.getElementById("shadelab-live-status").textContent), null, { timeout: 10000 });
    assert.ok((await litPixels(page)) > 5000, "the last program that compiled still draws");
    assert.deepEqual(consoleErrors, []);
  } finally {
    await context.close();
  }
});
