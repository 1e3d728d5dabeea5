// Starts the real shadelab server (port 0, real workers) and Debian's chromium, headless, through
// playwright-core: no browser download, nothing from outside this machine.
import { spawn } from "node:child_process";
import { mkdirSync } from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const here = path.dirname(fileURLToPath(import.meta.url));
export const repo = path.resolve(here, "../..");
export const artifacts = process.env.SHADELAB_ARTIFACTS ?? path.join(repo, "build", "browser-artifacts");
mkdirSync(artifacts, { recursive: true });

// SHADELAB_SERVER_PRELOAD names a library preloaded into the server and its workers alone (the
// browser keeps its own GL): tests/driver/accepts_all.cpp, a driver that accepts every shader.
export async function startServer(extraArgs = []) {
  const bin = process.env.SHADELAB_BIN ?? path.join(repo, "build", "shadelab");
  const preload = process.env.SHADELAB_SERVER_PRELOAD;
  const child = spawn(bin, ["serve", "--port", "0", "--workers", "2", "--web-root", path.join(repo, "web"), ...extraArgs], {
    stdio: ["ignore", "ignore", "pipe"],
    env: preload ? { ...process.env, LD_PRELOAD: preload } : process.env,
  });
  const port = await new Promise((resolve, reject) => {
    let err = "";
    child.stderr.on("data", (d) => {
      err += d;
      const m = err.match(/serving on http:\/\/[^:]+:(\d+) with/);  // the whole port, not a prefix of it
      if (m) resolve(Number(m[1]));
    });
    child.on("exit", (code) => reject(new Error(`server exited (${code}): ${err}`)));
  });
  const base = `http://127.0.0.1:${port}`;
  for (let i = 0; i < 200; ++i) {
    const r = await fetch(`${base}/readyz`).catch(() => null);
    if (r?.ok) break;
    await new Promise((r2) => setTimeout(r2, 50));
  }
  const exited = () => child.exitCode !== null || child.signalCode !== null;
  // pid and exited(): a test that attacks the server reads its resident peak and whether it lived.
  return { base, pid: child.pid, exited, stop: () => new Promise((resolve) => {
    if (exited()) return resolve();
    child.once("exit", resolve);
    child.kill("SIGTERM");
  }) };
}

export async function startBrowser() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    // WebGL2 on SwiftShader (the software renderer the fidelity figures were measured with);
    // the rest keeps Chromium from reaching for a network this machine does not have.
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
           "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run",
           "--disable-quic", "--disable-features=Translate,MediaRouter"],
  });
}

// A page with console errors collected; waits for the page's own start-up (the global it sets).
// `responses`: every response the page receives, as {url, text} promises (a download's body too).
export async function openPage(browser, base, { onDialog, path: pagePath = "/", ready = "shadelab" } = {}) {
  const context = await browser.newContext({ viewport: { width: 1400, height: 1000 }, acceptDownloads: true });
  const page = await context.newPage();
  const responses = [];
  page.on("response", (r) => responses.push(r.body().then((b) => ({ url: r.url(), text: b.toString("latin1") }), () => ({ url: r.url(), text: "" }))));
  if (onDialog) page.on("dialog", onDialog);
  const consoleErrors = [];
  page.on("console", (m) => m.type() === "error" && consoleErrors.push(m.text()));
  page.on("pageerror", (e) => consoleErrors.push(String(e)));
  await page.goto(base + pagePath);
  await page.waitForFunction((name) => window[name] !== undefined, ready, { timeout: 30000 });
  return { page, context, consoleErrors, responses };
}
