// Every preset of the built-in course on each of its meshes against the approved images in
// tests/golden/ (named PRESET_MESH.png).
#include <gtest/gtest.h>

#include <iostream>

#include "image/grid.h"
#include "support/golden.h"
#include "support/test_support.h"

using namespace shadelab;

class GoldenTest : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(GoldenTest, GridMatchesTheApprovedImage) {
  const auto& [preset, mesh] = GetParam();
  auto request = testkit::preset_request(preset);
  // Half the course's canvas keeps the goldens small; the framing and the step are the course's.
  request.width /= 2;
  request.height /= 2;
  auto r = testkit::render_frames(request, testkit::builtin(mesh));
  ASSERT_TRUE(r) << r.error().format();
  const auto grid = image::compose_grid(image::GridLayout::for_frames(request.frames, request.width, request.height), r->frames);
  const auto result = testkit::compare_with_golden(preset + "_" + mesh, grid);
  std::cout << preset << "_" << mesh << ": " << result.message << "\n";  // the fidelity figure, read by tools/gpu_check/run.sh
  EXPECT_TRUE(result.passed) << result.message;
}

INSTANTIATE_TEST_SUITE_P(Presets, GoldenTest,
                         ::testing::Combine(::testing::ValuesIn(testkit::course().preset_names()),
                                            ::testing::ValuesIn(testkit::course().mesh_names())),
                         [](const auto& p) { return std::get<0>(p.param) + "_" + std::get<1>(p.param); });
