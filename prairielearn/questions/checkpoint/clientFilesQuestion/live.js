// The checkpoint question's live canvas: the student's two shaders, as they type them in the
// question's editors (PrairieLearn's pl-file-editor, vertex first), drawn on the course's mesh by
// the homework page's own view (ShadeLab's web/js, copied beside this file by
// prairielearn/install_questions.py with the mesh and what a student sees of the course).
// It only shows; the grade is the grader's, on submit. A student's module is read by shader_module.js
// (ECMAScript's grammar), never imported: staff open this page on submitted files.
import { GlView } from "./gl_view.js";
import { parseObj } from "./obj.js";
import { glslFromFile } from "./shader_module.js";

const here = (name) => new URL(name, import.meta.url);
const status = (text) => (document.getElementById("shadelab-live-status").textContent = text);

// The question's editors, in the page's order: PrairieLearn keeps each Ace instance on its element.
function editorTexts() {
  return [...document.querySelectorAll(".ace_editor")].map((element) => element.env?.editor?.getValue() ?? "");
}

async function start() {
  const canvas = document.getElementById("shadelab-live");
  const course = await (await fetch(here("course.json"))).json();
  const view = new GlView(canvas, course);
  view.setMesh(parseObj(await (await fetch(here(course.defaultMesh + ".obj"))).text()));
  let shown = "";
  const rebuild = async () => {
    const [vertex, fragment] = editorTexts();
    if (vertex === undefined || fragment === undefined || vertex + "\u0000" + fragment === shown) return;
    shown = vertex + "\u0000" + fragment;
    try {
      const errors = view.setProgram(await glslFromFile(vertex), await glslFromFile(fragment));
      status(errors.length ? errors.map((e) => `${e.stage} line ${e.line}: ${e.message}`).join("\n") : "");
    } catch (e) {
      status(e.message);
    }
  };
  setInterval(rebuild, 500);
  const spin = (time) => {
    view.draw((course.frames.degreesPerFrame * time) / 1000);  // the page turns a frame's step a second
    requestAnimationFrame(spin);
  };
  requestAnimationFrame(spin);
}

start().catch((e) => status(`the live view cannot start: ${e.message}`));
