#pragma once
// A student's files to a Sheet: each checkpoint the files hold (grade/submission_files.h) graded
// and rendered through render workers, so a hostile shader only ever runs in a killable worker.
// What `shadelab sheet` and POST /api/sheet share; the layouts (sheet_pdf.h, sheet_html.h) take
// the result.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
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
  std::string title = "HW2 submission";
  std::string answers;
  std::vector<SubmittedFile> files;
  std::vector<SceneInput> scenes;
};

// Errors: only what the service could not do (the pool full, no worker): whatever the shaders
// cause is their section's grade, and a scene that does not render has its error in its section.
Expected<Sheet> assemble(worker::WorkerPool& pool, SheetInput input);

}  // namespace shadelab::sheet
