#pragma once
// `shadelab course import HW2_DIR [--solution DIR] -o course.json`: a TA's homework folder, as they
// hand it out, to a course profile. What the folder says is read from it; the rest is the built-in
// profile's, and the report says which is which.
//
// | fact                          | read from                                                   |
// |-------------------------------|-------------------------------------------------------------|
// | canvas size                   | index.html's <canvas width height>                          |
// | uniform values                | hw2.js's `uniformValues`, matched to roles by their names   |
// | uniform names                 | hw2.js's getUniformLocation calls (the rest: u + Role + Color)|
// | camera                        | hw2.js's perspective and translate calls (script_facts.h)   |
// | degrees per frame, frames     | hw2.js's `N * TIME` or `TIME * N`; MAX_OUT_FRAMES (above 0) |
// | frame file names              | hw2.js's download name around IMAGE_PREFIX                  |
// | samples                       | hw2.js's getContext attributes (antialias: false gives 0)   |
// | meshes, the default one       | the .obj files in the folder; OBJ_FILE in hw2.js            |
// | the starter's exponent        | the starter phong_frag.js's `float ...Alpha = N;`           |
// | presets and references        | the folder's starter_*.js; the solution's starter_* (normals), |
// |                               | phong_* (specular), diffuse_* when present; else built-in   |
// | the notebook, its questions   | the folder's HW2.ipynb, kept beside the profile; each       |
// |                               | placeholder's question (notebook_import.h)                  |
// | checkpoints, mistakes, probes | the built-in profile's, each mistake kept only where its    |
// |                               | edits apply to the reference the import chose               |
//
// The import writes nothing itself: the caller writes the profile and any shader the import
// derived (a built-in reference with the folder's exponent), then loads the profile to check it.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"

namespace shadelab::course {

struct ImportOptions {
  std::filesystem::path folder;                   // the homework folder, as handed out
  std::optional<std::filesystem::path> solution;  // the TA's solved shaders
  std::filesystem::path output;                   // where the profile will be written (paths are relative to it)
  std::string id;                                 // the profile's id; empty: from the folder's name
  std::string default_mesh;                       // overrides OBJ_FILE
};

struct ImportedCourse {
  nlohmann::json profile;
  // Files to write beside the profile (path relative to its folder, text).
  std::vector<std::pair<std::string, std::string>> derived_files;
  std::vector<std::string> found;    // "canvas 400 x 300 (index.html)"
  std::vector<std::string> assumed;  // "frames: 9 (MAX_OUT_FRAMES is 0; the notebook's 3 x 3 grid)"
};

Expected<ImportedCourse> import_course(const ImportOptions& options);

}  // namespace shadelab::course
