#pragma once
// A student's HW2 folder as the course lays it out (src/shaders/ and images/), written for the
// platform graders' tests (Gradescope's, PrairieLearn's) with the real shadelab binary: every
// deliverable right unless the arguments say otherwise.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/files.h"
#include "support/run_command.h"
#include "support/test_support.h"

namespace shadelab::testkit {

inline void write_file_at(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// A preset's stage as the course's JS module (shaders/<preset>_<stage>.js).
inline std::string preset_module(const std::string& preset, const std::string& stage) {
  return read_text(std::filesystem::path(SHADELAB_SOURCE_DIR) / "shaders" / (preset + "_" + stage + ".js"));
}

// A deliverable's frames as the page saves them, rendered by `shadelab render` from `preset` at
// the angles a 60 Hz page draws them (each frame after the first a little behind its nominal
// angle: ShadeLab's frames at the exact angles are no hand-in) and named for `prefix`.
inline void save_page_frames(const std::filesystem::path& folder, const std::string& preset, const std::string& prefix,
                             const std::string& more = "", const std::string& angles = kPageAngles) {
  std::filesystem::create_directories(folder);
  const auto r = run_shadelab("render --preset " + preset + " --prefix " + prefix + " --frames-dir '" + folder.string() + "' --angles " + angles + " " + more);
  ASSERT_EQ(r.status, 0) << r.output;
}

// The whole hand-in under `root` (root/HW2/...): both pairs of shaders, the notebook, each
// deliverable's saved frames, the dolly zoom's cameras and the Eevee render.
inline void write_hand_in(const std::filesystem::path& root, const std::string& specular_frames = "specular",
                          const std::string& specular_code = "specular") {
  const std::filesystem::path source = SHADELAB_SOURCE_DIR;
  write_file_at(root / "HW2/src/shaders/starter_vert.js", preset_module("normals", "vert"));
  write_file_at(root / "HW2/src/shaders/starter_frag.js", preset_module("normals", "frag"));
  write_file_at(root / "HW2/src/shaders/phong_vert.js", preset_module(specular_code, "vert"));
  write_file_at(root / "HW2/src/shaders/phong_frag.js", preset_module(specular_code, "frag"));
  write_file_at(root / "HW2/HW2.ipynb", "{}");
  save_page_frames(root / "HW2/images", "normals", "normals");
  save_page_frames(root / "HW2/images", "diffuse", "diffuse");
  if (!specular_frames.empty()) save_page_frames(root / "HW2/images", specular_frames, "specular");
  // The Blender half: the dolly zoom as Blender renders the handout's cameras, and two objects on a plane in Eevee.
  for (const char* lens : {"25", "50", "100"})
    write_file_at(root / (std::string("HW2/images/camera_") + lens + ".png"),
                  read_text(source / "tests/blender_half" / (std::string("blender_camera_") + lens + ".png")));
  write_file_at(root / "HW2/images/eevee0001.png", read_text(source / "tests/blender_half/blender_two_objects_eevee.png"));
}

}  // namespace shadelab::testkit
