#include <gtest/gtest.h>

#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "image/png_stream.h"
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

namespace {
Image noise(int w, int h, bool translucent) {
  Image img = Image::blank(w, h, PixelType::u8);
  std::uint32_t state = 12345;
  for (size_t i = 0; i < img.bytes.size(); ++i) {
    state = state * 1664525u + 1013904223u;
    img.bytes[i] = static_cast<std::uint8_t>(state >> 24);
    if (i % 4 == 3 && !translucent) img.bytes[i] = 255;
  }
  return img;
}
}  // namespace

// ShadeLab writes its PNGs itself (image/png_stream.h); OpenImageIO's reader (libpng) is the judge.
// Sizes that are not a multiple of the 32-row segments, every filter, RGB and RGBA.
TEST(PngWriterTest, EveryFilterRoundTripsThroughLibpng) {
  for (const bool translucent : {false, true})
    for (const auto filter : {PngFilter::none, PngFilter::sub, PngFilter::up})
      for (const auto& [w, h] : {std::pair{37, 101}, std::pair{1, 1}, std::pair{640, 33}}) {
        const Image img = noise(w, h, translucent);
        auto png = encode_png(img, {.compression_level = 1, .filter = filter});
        ASSERT_TRUE(png);
        EXPECT_EQ((*png)[25], translucent ? 6 : 2);
        EXPECT_EQ(testkit::decode(*png).bytes, img.bytes) << w << "x" << h << " filter " << static_cast<int>(filter);
      }
}

// The bytes depend on the image alone: not on the threads that deflate it, nor on how its rows
// were handed over (the grid encoder gives a band of cells at a time).
TEST(PngWriterTest, TheBytesDoNotDependOnThreadsOrHowRowsArrive) {
  const Image img = noise(97, 203, false);
  const auto one_thread = encode_png(img, {.threads = 1});
  const auto seven = encode_png(img, {.threads = 7});
  ASSERT_TRUE(one_thread && seven);
  EXPECT_EQ(*one_thread, *seven);
  PngStream stream(97, 203, 3, {.threads = 3});
  for (const auto& [from, to] : {std::pair{0, 1}, std::pair{1, 6}, std::pair{6, 64}, std::pair{64, 65}, std::pair{65, 203}})
    ASSERT_TRUE(stream.write_rows(img, from, to));
  auto pieces = stream.finish();
  ASSERT_TRUE(pieces);
  EXPECT_EQ(*pieces, *one_thread);
}

TEST(PngWriterTest, RowsOutOfOrderOrMissingAreAnError) {
  const Image img = noise(8, 40, false);
  PngStream stream(8, 40, 3, {});
  EXPECT_FALSE(stream.write_rows(img, 5, 10));
  ASSERT_TRUE(stream.write_rows(img, 0, 10));
  EXPECT_FALSE(stream.finish()) << "30 rows never came";
}
