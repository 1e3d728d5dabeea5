#include "image/encode.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstring>
#include <exception>

#include "image/png_stream.h"

namespace shadelab::image {

namespace {

// OpenEXR writes through a stream it can seek (the scan-line offset table is filled in last).
class MemoryExrStream final : public Imf::OStream {
 public:
  explicit MemoryExrStream(std::vector<std::uint8_t>& bytes) : Imf::OStream("frame.exr"), bytes_(bytes) {}
  void write(const char c[], int n) override {
    const size_t end = static_cast<size_t>(position_) + static_cast<size_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, c, static_cast<size_t>(n));
    position_ = end;
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override { position_ = pos; }

 private:
  std::vector<std::uint8_t>& bytes_;
  uint64_t position_ = 0;
};

}  // namespace

bool is_opaque(const Image& image) {
  if (image.type != PixelType::u8) return false;
  for (size_t i = 3; i < image.bytes.size(); i += 4)
    if (image.bytes[i] != 255) return false;
  return true;
}

Expected<std::vector<std::uint8_t>> encode_png(const Image& image, const PngSettings& settings) {
  PngStream png(image.width, image.height, is_opaque(image) ? 3 : 4, settings);
  if (auto s = png.write_rows(image, 0, image.height); !s) return s.take_error();
  return png.finish();
}

Expected<std::vector<std::uint8_t>> encode_exr(const Image& image) {
  if (image.type != PixelType::f32) return make_error(ErrorCode::io_error, "EXR encoding needs a float image");
  std::vector<std::uint8_t> bytes;
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer pixels;
    // RGBA float, rows top to bottom, as the image holds them (4 floats a pixel).
    char* base = reinterpret_cast<char*>(const_cast<std::uint8_t*>(image.bytes.data()));
    const size_t pixel = 4 * sizeof(float), row = pixel * static_cast<size_t>(image.width);
    const char* names[] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      pixels.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), pixel, row));
    }
    MemoryExrStream stream(bytes);
    Imf::OutputFile file(stream, header, 1);  // one thread: the caller's job is one of many
    file.setFrameBuffer(pixels);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    return make_error(ErrorCode::io_error, std::string("EXR encoding failed: ") + e.what());
  }
  return bytes;
}

}  // namespace shadelab::image
