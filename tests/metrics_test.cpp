#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "image/metrics.h"

using namespace shadelab::image;

namespace {
Image solid(int w, int h, std::uint8_t v) {
  Image img = Image::blank(w, h, PixelType::u8);
  for (size_t i = 0; i < img.bytes.size(); i += 4) img.bytes[i] = img.bytes[i + 1] = img.bytes[i + 2] = v, img.bytes[i + 3] = 255;
  return img;
}
}  // namespace

TEST(MetricsTest, IdenticalImagesSaySoWithNoInfinitePsnr) {
  const auto a = solid(16, 16, 100);
  const auto m = compare(a, a);
  EXPECT_TRUE(m.identical);
  EXPECT_FALSE(m.psnr.has_value());
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.ssim, 1.0);
  EXPECT_EQ(m.failing_fraction, 0.0);
}

TEST(MetricsTest, ConstantImagesGiveFiniteExactFigures) {
  const auto m = compare(solid(16, 16, 110), solid(16, 16, 100));
  EXPECT_FALSE(m.identical);
  EXPECT_NEAR(m.rmse, 10.0 / 255.0, 1e-12);
  ASSERT_TRUE(m.psnr.has_value());
  EXPECT_NEAR(*m.psnr, 20 * std::log10(25.5), 1e-9);
  EXPECT_NEAR(m.max_abs, 10.0 / 255.0, 1e-12);
  EXPECT_EQ(m.failing_fraction, 1.0);  // 10/255 > 0.016
  EXPECT_TRUE(std::isfinite(m.ssim));  // zero variance on both sides must not divide by zero
  EXPECT_GT(m.ssim, 0.9);
}

TEST(MetricsTest, ThresholdIsPerChannel) {
  auto a = solid(4, 4, 100), b = solid(4, 4, 100);
  b.bytes[0] = 104;  // 4/255 = 0.0157 <= 0.016: passes
  b.bytes[4] = 105;  // 5/255 > 0.016: fails
  const auto m = compare(a, b);
  EXPECT_DOUBLE_EQ(m.failing_fraction, 1.0 / 16);
}

TEST(MetricsTest, SpatialToleranceForgivesOnePixelShifts) {
  auto a = solid(8, 8, 0), b = solid(8, 8, 0);
  for (int y = 0; y < 8; ++y) a.bytes[(y * 8 + 3) * 4] = 255, b.bytes[(y * 8 + 4) * 4] = 255;  // an edge moved by one pixel
  EXPECT_GT(compare(a, b).failing_fraction, 0.2);
  EXPECT_EQ(compare(a, b, {.spatial_tolerance = true}).failing_fraction, 0.0);
}

TEST(MetricsTest, NonFinitePixelsAreCounted) {
  Image f = Image::blank(2, 2, PixelType::f32);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float px[4][4] = {{nan, 0, 0, 1}, {0, inf, 0, 1}, {0, 0, 0, 1}, {nan, inf, 0, 1}};
  std::memcpy(f.bytes.data(), px, sizeof px);
  const auto n = count_non_finite(f);
  EXPECT_EQ(n.nan, 2u);
  EXPECT_EQ(n.inf, 1u);
}

// What a student's course shows them of where their frames differ (grade::DifferencePicture::
// blocks): a shade a block, by the grader's own per-pixel test, so the picture of a black
// submission is the same against two references that differ only inside a block's shade.
TEST(MetricsTest, DifferenceBlocksShowWhereNotWhat) {
  const Image black = solid(64, 64, 0);
  EXPECT_EQ(difference_blocks(black, black, 16).bytes, solid(64, 64, 0).bytes) << "no pixel off: every block black";
  Image a = solid(64, 64, 0), b = solid(64, 64, 0);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      a.bytes[(y * 64 + x) * 4] = static_cast<std::uint8_t>(40 + 10 * x + y);  // a reference's shading in the first block
      b.bytes[(y * 64 + x) * 4] = static_cast<std::uint8_t>(250 - 7 * y);     // another's, as far off everywhere
    }
  a.bytes[(20 * 64 + 20) * 4] = b.bytes[(20 * 64 + 20) * 4] = 200;  // one pixel off in the block beside
  const Image from_a = difference_blocks(black, a, 16), from_b = difference_blocks(black, b, 16);
  EXPECT_EQ(from_a.bytes, from_b.bytes) << "the picture told the two references apart";
  const auto pixel = [&](int x, int y) {
    const std::uint8_t* p = from_a.bytes.data() + (y * 64 + x) * 4;
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  EXPECT_EQ(pixel(3, 7), (std::array<int, 3>{255, 255, 0})) << "most of the block off: yellow";
  EXPECT_EQ(pixel(31, 31), (std::array<int, 3>{255, 0, 0})) << "some of it off: red, over the whole block";
  EXPECT_EQ(pixel(16, 16), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(pixel(40, 40), (std::array<int, 3>{0, 0, 0}));
}
