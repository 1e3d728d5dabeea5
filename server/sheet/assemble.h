#pragma once
// A student's files to a Sheet: each of the course's checkpoints graded and rendered from the code
// the files hold (course/submission_files.h) through render workers, so a hostile shader only ever
// runs in a killable worker; a checkpoint handed in as images shown from the frames the student
// saved; the course's questions and hand-in images after them, in the notebook's order.
// What `shadelab sheet` and POST /api/sheet share; the layouts (sheet_pdf.h, sheet_html.h) take
// the result.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "course/access.h"
#include "course/course.h"
#include "sheet/sheet.h"
#include "worker/job.h"
#include "worker/pool.h"

namespace shadelab::sheet {

struct SubmittedFile {
  std::filesystem::path path;  // relative to the submission: "shaders/phong_frag.js"
  std::string text;
};

// A Blender-half scene (docs/scenes.md) with the mesh files its objects name, if any.
struct SceneInput {
  std::string name;  // shown as the section's title: "two_objects.json"
  nlohmann::json scene;
  std::vector<worker::SceneMeshBytes> meshes;
};

struct SheetInput {
  std::string title;  // empty: the course's hand-in title (Course::hand_in_name)
  std::string answers;
  std::string notebook;               // HW2.ipynb's text; empty when not handed in
  std::vector<SubmittedFile> files;   // the shader modules (text)
  std::vector<SubmittedFile> images;  // the PNG files: saved frames, the Blender half's renders
  std::vector<SceneInput> scenes;
  // Who the sheet is for: a TA's (the command line, a staff key) shows the purple-bunny answer in
  // the reference's shading; a student's in their own code's, the reference being the staff's. A
  // student unless the caller says otherwise: forgetting to ask never shows a reference.
  course::Viewer viewer;
};

// Errors: only what the service could not do (the pool full, no worker): whatever the shaders
// cause is their section's grade, and a scene that does not render has its error in its section.
// `reference_store`: where reference renders are kept across processes (grade/reference_store.h).
Expected<Sheet> assemble(worker::WorkerPool& pool, const course::Course& course, SheetInput input,
                         const grade::ReferenceStorePlaces& reference_store = {});

}  // namespace shadelab::sheet
