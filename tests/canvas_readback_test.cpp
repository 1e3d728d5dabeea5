#include <gtest/gtest.h>

#include <cmath>

#include "image/canvas_readback.h"

using namespace shadelab::image;

namespace {
std::array<int, 4> blob(int r, int g, int b, int a) {
  std::uint8_t px[4] = {static_cast<std::uint8_t>(r), static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(b),
                        static_cast<std::uint8_t>(a)};
  canvas_blob_pixel(px);
  return {px[0], px[1], px[2], px[3]};
}
}  // namespace

// The bytes Chromium wrote for these buffer values (docs/homework-contract.md).
TEST(CanvasReadbackTest, MatchesChromiumsMeasuredBytes) {
  EXPECT_EQ(blob(102, 51, 26, 128), (std::array<int, 4>{203, 102, 52, 128}));
  EXPECT_EQ(blob(204, 153, 102, 128), (std::array<int, 4>{255, 255, 203, 128}));  // clamped per channel
  EXPECT_EQ(blob(12, 34, 56, 0), (std::array<int, 4>{0, 0, 0, 0}));
  EXPECT_EQ(blob(12, 34, 56, 255), (std::array<int, 4>{12, 34, 56, 255}));
}

TEST(CanvasReadbackTest, FollowsTheFloat32RuleForEveryPair) {
  for (int a = 1; a < 255; ++a)
    for (int c = 0; c < 256; ++c) {
      const float expected = std::nearbyint(std::fmin(1.0f, (c / 255.0f) * (1.0f / (a / 255.0f))) * 255.0f);
      ASSERT_EQ(blob(c, c, c, a)[0], static_cast<int>(expected)) << "c=" << c << " a=" << a;
    }
}

TEST(CanvasReadbackTest, FlipsRowsAndReportsOpacity) {
  Image out = Image::blank(1, 2, PixelType::u8);
  const std::uint8_t bottom_up[] = {1, 2, 3, 255, 4, 5, 6, 255};
  EXPECT_TRUE(canvas_blob_from_readback(bottom_up, out));
  EXPECT_EQ(out.bytes[0], 4);  // GL's last row is the image's first
  EXPECT_EQ(out.bytes[4], 1);
  const std::uint8_t translucent[] = {1, 2, 3, 255, 4, 5, 6, 254};
  EXPECT_FALSE(canvas_blob_from_readback(translucent, out));
}
