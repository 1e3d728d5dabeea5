#pragma once
// Which files of a student's submission (their HW2 folder, or the shader modules alone) are which
// checkpoint's shaders: what `shadelab grade --submissions`, `shadelab autograde`, `shadelab
// sheet` and POST /api/sheet all use. Works on the submission's relative paths; reading them is
// the caller's.
//
// A checkpoint's shaders are STEM_vert.js + STEM_frag.js in one folder, the stems tried in order:
//
// | stem                          | example (built-in course)      |
// |-------------------------------|--------------------------------|
// | the checkpoint's name         | normals_vert.js, specular_*.js |
// | its aliases                   | gouraud_vert.js                |
// | the code it is handed in with | starter_*.js, phong_*.js       |
//
// A checkpoint handed in with code (the course's `code`) is required; one handed in as images
// alone (diffuse) is graded from code only when the student kept a pair under its own name.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "course/course.h"

namespace shadelab::course {

struct CheckpointFiles {
  std::string checkpoint;
  std::string code;  // the homework's file stem for it ("starter"); empty when handed in as images
  bool required = false;
  std::optional<std::pair<std::filesystem::path, std::filesystem::path>> pair;  // vertex, fragment; relative
};

// Each checkpoint of `course` that `files` hold (relative paths, shallowest first), in the
// course's order, and each required one (pair empty). A pair is taken from one folder, the
// shallowest first.
std::vector<CheckpointFiles> plan_checkpoints(const Course& course, const std::vector<std::filesystem::path>& files);

// The pair for one checkpoint: by its stems, else the only *_vert.js / *_frag.js pair there is.
std::optional<std::pair<std::filesystem::path, std::filesystem::path>> checkpoint_pair(
    const Course& course, const Checkpoint& checkpoint, const std::vector<std::filesystem::path>& files);

// A deliverable's saved frames in a submission: frame k's file by the course's name for it
// (hw2_specular_3.png), the shallowest first (images/ in the course's folder), and the files named
// as frames beyond the deliverable's count (hw2_specular_9.png), which are not graded.
struct SavedFrameFiles {
  std::vector<std::optional<std::filesystem::path>> frames;  // one per frame of the job
  std::vector<std::filesystem::path> extra;

  bool any() const;
  // "hw2_specular_4.png and hw2_specular_7.png": the frames not found; empty when none is missing.
  std::vector<std::string> missing(const Course& course, const Checkpoint& checkpoint) const;
};
SavedFrameFiles saved_frame_files(const Course& course, const Checkpoint& checkpoint, const std::vector<std::filesystem::path>& files);

// "starter_vert.js and starter_frag.js (or normals_vert.js and normals_frag.js)": what was looked for.
std::string wanted_files(const Course& course, const Checkpoint& checkpoint);

// The file at `path` (images/camera_25.png), or at a path ending in it, the shallowest first: a
// student's folder may sit inside another. Failing those, a file of its name at the top (an
// upload that keeps no folders, as PrairieLearn's: camera_25.png).
const std::filesystem::path* file_at(const std::vector<std::filesystem::path>& files, const std::string& path);

// "a.js, b.js and 3 more", or "nothing": what a student is told their submission held.
std::string listing(const std::vector<std::filesystem::path>& files);

// Shallowest first, then by path: the order plan_checkpoints expects.
void sort_submission(std::vector<std::filesystem::path>& files);

}  // namespace shadelab::course
