// image::decode_png on a frame a student saved from their browser (any PNG encoding, or not a PNG
// at all). Input: the file's bytes. Invariants: nothing thrown; a decoded frame is straight RGBA8
// of the size its header says, no side larger than the limit, and its bytes exactly fill it.
#include <string_view>

#include "fuzz_check.h"
#include "image/png_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  constexpr unsigned kMaxSide = 512;  // small, so a fuzzer's header does not spend its time allocating
  auto decoded = shadelab::image::decode_png(std::string_view(reinterpret_cast<const char*>(data), size), kMaxSide);
  if (!decoded) {
    FUZZ_CHECK(!decoded.error().message.empty());
    return 0;
  }
  const auto& img = *decoded;
  FUZZ_CHECK(img.type == shadelab::image::PixelType::u8);
  FUZZ_CHECK(img.width > 0 && img.height > 0);
  FUZZ_CHECK(static_cast<unsigned>(img.width) <= kMaxSide && static_cast<unsigned>(img.height) <= kMaxSide);
  FUZZ_CHECK(img.bytes.size() == static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4);
  return 0;
}
