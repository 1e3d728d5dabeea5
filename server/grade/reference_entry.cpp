#include "grade/reference_entry.h"

#include <zstd.h>

#include <cstdint>
#include <memory>

namespace shadelab::grade {

namespace {

constexpr size_t kMagicSize = kReferenceEntryFormat.size(), kHeaderSize = kMagicSize + 16;

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}
std::uint32_t get_u32(std::string_view in, size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(in[at + static_cast<size_t>(i)])} << (8 * i);
  return v;
}

}  // namespace

std::string encode_reference_entry(const SharedFrames& frames) {
  if (frames.empty()) return {};
  const image::Image& first = *frames.front();
  std::string pixels;
  for (const auto& f : frames) {
    if (f->width != first.width || f->height != first.height || f->type != first.type) return {};
    pixels.append(reinterpret_cast<const char*>(f->bytes.data()), f->bytes.size());
  }
  std::string out(kReferenceEntryFormat);
  put_u32(out, static_cast<std::uint32_t>(first.width));
  put_u32(out, static_cast<std::uint32_t>(first.height));
  put_u32(out, static_cast<std::uint32_t>(frames.size()));
  put_u32(out, first.type == image::PixelType::u8 ? 0 : 1);
  // With a checksum, as zlib's: a flipped bit in a stored frame is a miss, never a wrong grade.
  std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> context(ZSTD_createCCtx(), ZSTD_freeCCtx);
  if (!context || ZSTD_isError(ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, 1)) ||
      ZSTD_isError(ZSTD_CCtx_setParameter(context.get(), ZSTD_c_checksumFlag, 1)))
    return {};
  std::string compressed(ZSTD_compressBound(pixels.size()), '\0');
  const size_t size = ZSTD_compress2(context.get(), compressed.data(), compressed.size(), pixels.data(), pixels.size());
  if (ZSTD_isError(size)) return {};
  out.append(compressed.data(), size);
  return out;
}

// The frames of an entry holding `expected`'s shape, or nullopt when it is not a whole one
// (truncated, another format, another shape). The output is sized from the request, never from
// the entry, and zstd writes into it directly.
std::optional<SharedFrames> decode_reference_entry(std::string_view entry, const render::RenderRequest& expected) {
  if (entry.size() < kHeaderSize || entry.substr(0, kMagicSize) != kReferenceEntryFormat) return std::nullopt;
  if (expected.frames < 1 || expected.width < 1 || expected.height < 1) return std::nullopt;
  const bool is_u8 = expected.pixel_type == image::PixelType::u8;
  const std::uint32_t shape[] = {static_cast<std::uint32_t>(expected.width), static_cast<std::uint32_t>(expected.height),
                                 static_cast<std::uint32_t>(expected.frames), is_u8 ? 0u : 1u};
  for (size_t i = 0; i < 4; ++i)
    if (get_u32(entry, kMagicSize + 4 * i) != shape[i]) return std::nullopt;
  const void* payload = entry.data() + kHeaderSize;
  const size_t payload_size = entry.size() - kHeaderSize;
  const size_t frame_bytes = size_t(expected.width) * size_t(expected.height) * (is_u8 ? 4 : 16);
  if (ZSTD_getFrameContentSize(payload, payload_size) != frame_bytes * size_t(expected.frames)) return std::nullopt;
  std::vector<std::shared_ptr<image::Image>> frames;
  for (int k = 0; k < expected.frames; ++k)
    frames.push_back(std::make_shared<image::Image>(image::Image::blank(expected.width, expected.height, expected.pixel_type)));
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(), ZSTD_freeDCtx);
  if (!context) return std::nullopt;
  ZSTD_inBuffer in{payload, payload_size, 0};
  size_t left = 1;  // ZSTD_decompressStream's answer: 0 once the frame is read whole, checksum included
  const auto step = [&](ZSTD_outBuffer& to) {
    const size_t in_before = in.pos, out_before = to.pos;
    left = ZSTD_decompressStream(context.get(), &to, &in);
    return !ZSTD_isError(left) && (in.pos != in_before || to.pos != out_before || left == 0);
  };
  for (const auto& frame : frames) {
    ZSTD_outBuffer to{frame->bytes.data(), frame_bytes, 0};
    while (to.pos < to.size)
      if (!step(to)) return std::nullopt;  // damaged, or truncated: no progress
  }
  ZSTD_outBuffer none{nullptr, 0, 0};
  while (left != 0)
    if (!step(none)) return std::nullopt;
  if (in.pos != in.size) return std::nullopt;  // bytes after the frame: not an entry this build wrote
  return SharedFrames(frames.begin(), frames.end());
}

}  // namespace shadelab::grade
