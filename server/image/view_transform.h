#pragma once
// Blender's Filmic view transform, baked from Blender's own OCIO config (Debian's blender-data)
// through OpenColorIO (linked directly: OpenImageIO's binding cost every process its 267
// libraries at start, ~250 ms), into two tables the GPU applies per pixel:
//
// | Step | Table                 | Domain                                         | Size       |
// |------|-----------------------|------------------------------------------------|------------|
// | 1    | Linear -> Filmic Log  | log2(linear) in [-12.47, 12.53] per channel    | 65^3 RGB   |
// | 2    | Filmic Log -> display | Filmic Log value in [0, 1], per channel        | 4096       |
//
// Step 1 samples OCIO on the exact grid of Filmic's own 65^3 cube (same log2 allocation), so the
// GPU's trilinear lookup interpolates between the cube's own entries; step 2 is per channel and
// fine enough to be exact at 8 bits.
#include <string>
#include <vector>

#include "core/expected.h"

namespace shadelab::image {

struct FilmicTables {
  static constexpr int kCubeSize = 65;
  static constexpr int kCurveSize = 4096;
  static constexpr double kLog2Min = -12.473931188, kLog2Max = 12.526068812;
  std::vector<float> cube;   // kCubeSize^3 RGB, red fastest
  std::vector<float> curve;  // kCurveSize RGB
  std::string config_path;
};

// The OCIO config this build uses: SHADELAB_OCIO_CONFIG, else Blender's from blender-data.
std::string blender_ocio_config_path();

// Errors view_transform_unavailable when the config is missing or has no Filmic.
Expected<FilmicTables> bake_filmic(const std::string& config_path);

// Reference: OCIO itself on linear RGB pixels (in place), Linear -> Filmic sRGB. For tests and
// the accuracy bench; the renderer uses the baked tables.
Status apply_filmic_reference(const std::string& config_path, std::vector<float>& rgb);

}  // namespace shadelab::image
