// Saved frames made the way the course's page makes them (hw2.js's clock: each animation frame
// draws with the previous frame's time; frame k is saved at the first frame past k seconds), in
// Debian's chromium at 60 and 30 Hz, handed to the page's own "check your saved frames" and graded
// by the real server: a correct shader's frames pass with the lag found; each catalogued mistake's
// frames fail, named for what they are.
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import path from "node:path";
import { after, before, describe, test } from "node:test";

import { artifacts, openPage, repo, startBrowser, startServer } from "./harness.mjs";

const course = JSON.parse(readFileSync(path.join(repo, "courses/cs148-summer2022.json"), "utf8"));
// The first animation frame's timestamp sets each clock's lag (one per run on a steady clock):
// 0.25 degrees at 60 Hz, what the one student's saved frames show; 0.63 at 30 Hz, near a slow
// page's most (0.67).
const CLOCKS = [{ hz: 60, phaseMs: 4.2 }, { hz: 30, phaseMs: 1.8 }];
const LAG_TOLERANCE = 0.05;  // degrees, the issue's bound

let server, browser, page, context;
before(async () => {
  server = await startServer(["--open-references"]);  // the references in the editors: a self-study server
  browser = await startBrowser();
  ({ page, context } = await openPage(browser, server.base));
  await page.uncheck("#spin");
});
after(async () => {
  await context?.close();
  await browser?.close();
  await server?.stop();
});

// The shaders of `preset`, with a mistake's edits applied, in the page's editors and compiled there.
async function useShaders(preset, edits = []) {
  await page.evaluate(async ([p, e]) => {
    const s = window.shadelab;
    await s.choosePreset(p);
    for (const { stage, find, replace } of e) {
      const editor = s.editors[stage];
      if (!editor.text.includes(find)) throw new Error(`${stage} shader of ${p} has no '${find}'`);
      editor.text = editor.text.replace(find, replace);
    }
    if (!(await s.applyLocally())) throw new Error("the shaders do not compile in the browser");
  }, [preset, edits]);
}

// Saves the deliverable's frames as the course's page would on `clock`, then drops them (and any
// `extra` saved before) on the page's check; the check's results and the lags drawn with.
async function saveAndCheck(checkpoint, clock, { codeFor = "", extra = [] } = {}) {
  return page.evaluate(async ([prefix, c, code, earlier]) => {
    const s = window.shadelab;
    const saved = await s.saveLikeTheCoursePage(prefix, c);
    window.savedSoFar = [...(window.savedSoFar ?? []).filter((f) => earlier.includes(f.name)),
                         ...saved.map((f) => new File([f.blob], f.name, { type: "image/png" }))];
    document.getElementById("saved-code").value = code;
    const results = await s.checkSavedFrames(window.savedSoFar);
    return { results, lags: saved.map((f) => f.lag), names: window.savedSoFar.map((f) => f.name) };
  }, [checkpoint.prefix, clock, codeFor, extra]);
}

describe("saved frames, made as the course's page makes them", () => {
  for (const clock of CLOCKS)
    test(`a correct student's frames pass at ${clock.hz} Hz, the lag found`, async () => {
      let names = [];
      for (const checkpoint of course.checkpoints) {
        await useShaders(checkpoint.reference);
        // The editors now hold this deliverable's code: where it has code, check the frames came from it.
        const { results, lags, names: dropped } = await saveAndCheck(checkpoint, clock, { codeFor: checkpoint.code ? checkpoint.name : "", extra: names });
        names = dropped;
        const result = results.find((r) => r.deliverable === checkpoint.name);
        assert.ok(result, `${checkpoint.name} was graded`);
        assert.equal(results.length, course.checkpoints.indexOf(checkpoint) + 1, "every deliverable dropped so far is graded");
        assert.ok(result.frames.pass, `${checkpoint.name} at ${clock.hz} Hz: ${result.frames.diagnosis}: ${result.frames.messages.join(" | ")}`);
        assert.deepEqual(result.frames.flags, [], `${checkpoint.name} at ${clock.hz} Hz: a page's own frames are not flagged`);
        if (checkpoint.code) assert.ok(result.code?.pass, `${checkpoint.name}: the frames are what the editors' code renders: ${result.code?.messages.join(" | ")}`);
        const found = result.frames.frames.map((f) => f.lagDegrees);
        console.log(`${checkpoint.name} at ${clock.hz} Hz: lags drawn ${lags.map((l) => l.toFixed(3)).join(" ")}; found ${found.map((l) => l.toFixed(3)).join(" ")}`);
        for (const [k, lag] of lags.entries())
          assert.ok(Math.abs(found[k] - lag) <= LAG_TOLERANCE, `${checkpoint.name} frame ${k}: lag ${found[k]} found, ${lag} drawn`);
      }
      // What the student sees: a verdict per deliverable, each a pass.
      const shown = await page.$$eval("#saved-results article", (all) => all.map((a) => [a.dataset.checkpoint, a.querySelector(".verdict").className]));
      assert.deepEqual(shown, course.checkpoints.map((c) => [c.name, "verdict pass"]));
      await page.screenshot({ path: path.join(artifacts, `saved_frames_${clock.hz}hz.png`), fullPage: true });
    });

  test("the server's own frames of the reference, dropped on the check, are named for what they are", async () => {
    const normals = course.checkpoints.find((c) => c.name === "normals");
    const result = await page.evaluate(async ([preset]) => {
      const r = await (await fetch(`/api/render?preset=${preset}&output=json`)).json();
      const files = await Promise.all(r.images.frames.map(async (f) => new File([await (await fetch(`data:image/png;base64,${f.data}`)).blob()], f.name, { type: "image/png" })));
      document.getElementById("saved-code").value = "";
      return (await window.shadelab.checkSavedFrames(files))[0];
    }, [normals.reference]);
    assert.equal(result.frames.pass, false);
    assert.equal(result.frames.diagnosis, "made_by_shadelab");
    assert.deepEqual(result.frames.flags.map((f) => f.id), ["made_by_shadelab"]);
    assert.match(await page.textContent("#saved-results .flag"), /Flagged for the TA: made by ShadeLab, not saved from the page/);
    await page.screenshot({ path: path.join(artifacts, "saved_frames_made_by_shadelab.png"), fullPage: true });
  });

  test("frames chosen with the file input are checked, and a stray file is named", async () => {
    const specular = course.checkpoints.find((c) => c.name === "specular");
    await useShaders(specular.reference);
    const files = await page.evaluate(async ([prefix]) => {
      const saved = await window.shadelab.saveLikeTheCoursePage(prefix, { hz: 60, phaseMs: 9 });
      const out = [];
      for (const f of saved) out.push({ name: f.name, mimeType: "image/png", buffer: Array.from(new Uint8Array(await f.blob.arrayBuffer())) });
      return out;
    }, [specular.prefix]);
    await page.setInputFiles("#saved-files", [...files.map((f) => ({ ...f, buffer: Buffer.from(f.buffer) })),
                                              { name: "notes.txt", mimeType: "text/plain", buffer: Buffer.from("not a frame") }]);
    await page.waitForFunction(() => document.querySelector("#saved-status").textContent.startsWith("Graded"), null, { timeout: 60000 });
    assert.match(await page.textContent("#saved-status"), /Graded specular\. Not frames of any deliverable, not graded: notes\.txt\./);
    assert.equal(await page.getAttribute("#saved-results article .verdict", "class"), "verdict pass");
    const example = course.frames.fileName.replaceAll("{prefix}", course.checkpoints.at(-1).prefix).replaceAll("{k}", "0");
    assert.equal(await page.textContent("#saved-example"), `${example}.png`, "the hint names the course's own files");
  });

  // A mistake no one catalogued, saved from chromium's own rasteriser: the formula reads it, and
  // the student reads why on the page, in the homework's terms.
  test("a mistake outside the catalogue is explained on the page by the homework's formula", async () => {
    const specular = course.checkpoints.find((c) => c.name === "specular");
    await useShaders(specular.reference, [{ stage: "fragment", find: "normalize(uLightPosition - vPosition)", replace: "normalize(uLightPosition)" }]);
    const { results } = await saveAndCheck(specular, CLOCKS[0]);
    const { frames } = results.find((r) => r.deliverable === "specular");
    assert.equal(frames.pass, false);
    assert.equal(frames.explanation?.explained, true, JSON.stringify(frames.explanation));
    assert.equal(frames.explanation.variant, "light_as_direction");
    const shown = await page.textContent("#saved-results article[data-checkpoint=specular]");
    assert.match(shown, /Your frames are the homework's formula with one change: the light comes from the direction uLightPosition/);
    await page.screenshot({ path: path.join(artifacts, "saved_frames_explained.png"), fullPage: true });
  });

  // Each mistake of the catalogue, as a student's page would have saved it at 60 Hz. Two change
  // too little for any frame the page saves to show them, and pass; what finds them is said.
  const INVISIBLE_IN_FRAMES = {
    // The page's light never reaches where N.L <= 0 (at most ~60 pixels differ): the code's hidden-light test.
    "specular/unguarded_specular": "the code's hidden-light test",
    // The course's bunny has pixel-sized triangles, so interpolated normals barely shorten (0.1% of
    // the object's pixels, as much as two rasterisers differ by); the specular frames, whose
    // highlight magnifies it, and the specular code grade find it.
    "diffuse/unnormalized_normals": "the specular deliverable's frames and code",
  };
  for (const checkpoint of course.checkpoints)
    for (const mistake of checkpoint.mistakes ?? []) {
      const invisible = INVISIBLE_IN_FRAMES[`${checkpoint.name}/${mistake.id}`];
      test(`${checkpoint.name}: ${mistake.id} frames ${invisible ? `pass (invisible in frames: found by ${invisible})` : "fail, named"}`, async () => {
        await useShaders(mistake.preset ?? checkpoint.reference, mistake.edits ?? []);
        const { results } = await saveAndCheck(checkpoint, CLOCKS[0]);
        const { frames } = results.find((r) => r.deliverable === checkpoint.name);
        console.log(`${checkpoint.name}/${mistake.id}: ${frames.pass ? "pass" : "fail"} (${frames.diagnosis}) ${frames.messages[0] ?? ""}`);
        if (invisible) return assert.ok(frames.pass, frames.messages.join(" | "));
        assert.equal(frames.pass, false, `${mistake.id}'s frames passed`);
        assert.equal(frames.diagnosis, mistake.id, frames.messages.join(" | "));
        const verdict = await page.textContent(`#saved-results article[data-checkpoint=${checkpoint.name}] .verdict`);
        assert.ok(!verdict.includes(mistake.id), `the page shows the internal id: ${verdict}`);
      });
    }
});
