#include <gtest/gtest.h>

#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "support/test_support.h"

using namespace shadelab;
using namespace shadelab::image;

namespace {
Image solid(int w, int h, std::uint8_t r, std::uint8_t a = 255) {
  Image img = Image::blank(w, h, PixelType::u8);
  for (size_t i = 0; i < img.bytes.size(); i += 4) {
    img.bytes[i] = r;
    img.bytes[i + 3] = a;
  }
  return img;
}
}  // namespace

TEST(GridTest, LayoutHasCeilSqrtColumns) {
  EXPECT_EQ(GridLayout::for_frames(9, 640, 480).columns, 3);
  EXPECT_EQ(GridLayout::for_frames(9, 640, 480).rows, 3);
  EXPECT_EQ(GridLayout::for_frames(10, 1, 1).columns, 4);
  EXPECT_EQ(GridLayout::for_frames(10, 1, 1).rows, 3);
  EXPECT_EQ(GridLayout::for_frames(1, 1, 1).columns, 1);
  EXPECT_EQ(GridLayout::for_frames(2, 1, 1).columns, 2);
  EXPECT_EQ(GridLayout::for_frames(2, 1, 1).rows, 1);
  EXPECT_EQ(GridLayout::for_frames(9, 640, 480).width(), 1920);
}

TEST(GridTest, FramesGoRowByRow) {
  const auto layout = GridLayout::for_frames(4, 2, 2);
  std::vector<Image> frames;
  for (int k = 0; k < 4; ++k) frames.push_back(solid(2, 2, static_cast<std::uint8_t>(10 * (k + 1))));
  const Image grid = compose_grid(layout, frames);
  EXPECT_EQ(testkit::pixel(grid, 0, 0)[0], 10);
  EXPECT_EQ(testkit::pixel(grid, 2, 0)[0], 20);
  EXPECT_EQ(testkit::pixel(grid, 0, 2)[0], 30);
  EXPECT_EQ(testkit::pixel(grid, 3, 3)[0], 40);
}

TEST(GridTest, OpaquePngIsRgbAndRoundTrips) {
  const Image img = solid(3, 2, 77);
  auto png = encode_png(img);
  ASSERT_TRUE(png);
  EXPECT_EQ((*png)[25], 2);  // IHDR colour type 2: RGB
  EXPECT_EQ(testkit::decode(*png).bytes, img.bytes);
}

TEST(GridTest, TranslucentPngKeepsStraightAlpha) {
  const Image img = solid(3, 2, 203, 128);
  auto png = encode_png(img);
  ASSERT_TRUE(png);
  EXPECT_EQ((*png)[25], 6);  // RGBA
  EXPECT_EQ(testkit::decode(*png).bytes, img.bytes);  // not premultiplied on the way out
}

TEST(GridTest, OverlappedEncoderMatchesTheSerialEncode) {
  const auto layout = GridLayout::for_frames(9, 16, 8);
  std::vector<Image> frames;
  for (int k = 0; k < 9; ++k) frames.push_back(solid(16, 8, static_cast<std::uint8_t>(20 * k)));
  GridPngEncoder encoder(layout, 9);
  for (int k = 8; k >= 0; --k) encoder.add_frame(k, frames[static_cast<size_t>(k)], true);  // any order
  auto overlapped = encoder.finish();
  ASSERT_TRUE(overlapped);
  EXPECT_EQ(*overlapped, *encode_png(compose_grid(layout, frames)));
}

TEST(GridTest, LateTransparencyReencodesAsRgba) {
  const auto layout = GridLayout::for_frames(9, 64, 64);
  std::vector<Image> frames;
  for (int k = 0; k < 9; ++k) frames.push_back(solid(64, 64, static_cast<std::uint8_t>(k * 25), k == 7 ? 128 : 255));
  GridPngEncoder encoder(layout, 9);
  for (int k = 0; k < 9; ++k) encoder.add_frame(k, frames[static_cast<size_t>(k)], k != 7);
  auto png = encoder.finish();
  ASSERT_TRUE(png);
  EXPECT_TRUE(encoder.reencoded());
  EXPECT_EQ(testkit::decode(*png).bytes, compose_grid(layout, frames).bytes);
}

TEST(GridTest, MissingFramesAreAnErrorNotAHang) {
  GridPngEncoder encoder(GridLayout::for_frames(4, 2, 2), 4);
  encoder.add_frame(0, solid(2, 2, 1), true);
  EXPECT_FALSE(encoder.finish());
}

TEST(GridTest, EmptyCellsAreTransparent) {
  const auto layout = GridLayout::for_frames(2, 2, 2);  // 2 x 1: no empty cell
  EXPECT_EQ(layout.cells(), 2);
  const auto three = GridLayout::for_frames(3, 2, 2);   // 2 x 2 with one empty cell
  GridPngEncoder encoder(three, 3);
  for (int k = 0; k < 3; ++k) encoder.add_frame(k, solid(2, 2, 50), true);
  auto png = encoder.finish();
  ASSERT_TRUE(png);
  const Image img = testkit::decode(*png);
  EXPECT_EQ(testkit::pixel(img, 3, 3), (std::array<int, 4>{0, 0, 0, 0}));
  EXPECT_EQ(testkit::pixel(img, 0, 0), (std::array<int, 4>{50, 0, 0, 255}));
}
