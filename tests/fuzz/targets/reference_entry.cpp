// grade::decode_reference_entry on bytes from a reference store's disk or Redis (cut, flipped or
// forged). Input: one byte choosing the shape the grade expects (even: 4 x 3 RGBA8, odd: RGBA32F;
// 2 frames), then the entry. Invariants: nothing thrown; frames come back only in that shape,
// and they encode to an entry that decodes to the same bytes.
#include <string_view>

#include "fuzz_check.h"
#include "grade/reference_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  if (size < 1) return 0;
  shadelab::render::RenderRequest expected;
  expected.width = 4;
  expected.height = 3;
  expected.frames = 2;
  expected.pixel_type = data[0] % 2 == 0 ? shadelab::image::PixelType::u8 : shadelab::image::PixelType::f32;
  const std::string_view entry(reinterpret_cast<const char*>(data) + 1, size - 1);
  const auto frames = shadelab::grade::decode_reference_entry(entry, expected);
  if (!frames) return 0;
  FUZZ_CHECK(frames->size() == 2);
  for (const auto& f : *frames) {
    FUZZ_CHECK(f->width == 4 && f->height == 3 && f->type == expected.pixel_type);
    FUZZ_CHECK(f->bytes.size() == size_t{4} * 3 * (expected.pixel_type == shadelab::image::PixelType::u8 ? 4 : 16));
  }
  const auto again = shadelab::grade::decode_reference_entry(shadelab::grade::encode_reference_entry(*frames), expected);
  FUZZ_CHECK(again && again->size() == 2);
  for (size_t k = 0; k < 2; ++k) FUZZ_CHECK((*again)[k]->bytes == (*frames)[k]->bytes);
  return 0;
}
