#include "image/encode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <memory>

#include "image/png_stream.h"

namespace shadelab::image {

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
  std::vector<std::uint8_t> bytes;
  OIIO::Filesystem::IOVecOutput sink(bytes);
  auto out = OIIO::ImageOutput::create("frame.exr");
  if (!out) return make_error(ErrorCode::io_error, "OpenImageIO has no EXR writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  out->set_ioproxy(&sink);
  if (!out->open("frame.exr", spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.bytes.data()) || !out->close())
    return make_error(ErrorCode::io_error, "EXR encoding failed: " + out->geterror());
  return bytes;
}

}  // namespace shadelab::image
