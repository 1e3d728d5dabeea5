#include <gtest/gtest.h>

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
