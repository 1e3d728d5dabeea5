#pragma once
// Which files of a student's submission (their HW2 folder, or the shader modules alone) are which
// checkpoint's shaders: what `shadelab autograde` grades, and `shadelab sheet` and POST /api/sheet
// lay out. Works on the submission's relative paths; reading them is the caller's.
//
// | files in the submission               | checkpoint | required                    |
// |---------------------------------------|------------|-----------------------------|
// | smooth_vert.js + smooth_frag.js       | smooth     | no: when present            |
// | gouraud_vert.js + gouraud_frag.js, else starter_vert.js + starter_frag.js | gouraud | yes                         |
// | diffuse_vert.js + diffuse_frag.js     | diffuse    | no: when present            |
// | specular_vert.js + specular_frag.js, else phong_vert.js + phong_frag.js   | specular | yes                         |
//
// The homework edits starter_* into Gouraud shading and phong_* into ambient + diffuse + specular,
// and its checklist hands in that code; a student who kept each stage's files names them.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shadelab::grade {

struct CheckpointFiles {
  std::string checkpoint;
  std::optional<std::string> homework_stem;  // the homework's file names for it ("starter"), if any
  bool required = false;
  std::optional<std::pair<std::filesystem::path, std::filesystem::path>> pair;  // vertex, fragment; relative
};

// Each checkpoint `files` hold (relative paths, shallowest first), in the homework's order, and
// each required one (pair empty). A pair is taken from one folder, the shallowest first.
std::vector<CheckpointFiles> plan_checkpoints(const std::vector<std::filesystem::path>& files);

// "a.js, b.js and 3 more", or "nothing": what a student is told their submission held.
std::string listing(const std::vector<std::filesystem::path>& files);

// Shallowest first, then by path: the order plan_checkpoints expects.
void sort_submission(std::vector<std::filesystem::path>& files);

}  // namespace shadelab::grade
