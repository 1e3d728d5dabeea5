// Every preset on both built-in meshes against the approved images in tests/golden/.
#include <gtest/gtest.h>

#include "image/grid.h"
#include "support/golden.h"
#include "support/test_support.h"

using namespace shadelab;

class GoldenTest : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(GoldenTest, GridMatchesTheApprovedImage) {
  const auto& [preset, mesh] = GetParam();
  auto request = testkit::preset_request(preset);
  // Half the canonical size keeps the goldens small; the framing and the step are the homework's.
  request.width = 320;
  request.height = 240;
  auto r = testkit::render_frames(request, testkit::builtin(mesh));
  ASSERT_TRUE(r) << r.error().format();
  const auto grid = image::compose_grid(image::GridLayout::for_frames(9, 320, 240), r->frames);
  const auto result = testkit::compare_with_golden(preset + "_" + mesh, grid);
  EXPECT_TRUE(result.passed) << result.message;
}

INSTANTIATE_TEST_SUITE_P(Presets, GoldenTest,
                         ::testing::Combine(::testing::Values("starter", "smooth", "gouraud", "diffuse", "specular"),
                                            ::testing::Values("teapot", "bunny")),
                         [](const auto& p) { return std::get<0>(p.param) + "_" + std::get<1>(p.param); });
