#include "image/png_stream.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace shadelab::image {

struct PngStream::State {
  std::vector<std::uint8_t> bytes;
  OIIO::Filesystem::IOVecOutput sink{bytes};
  std::unique_ptr<OIIO::ImageOutput> out;
  std::string error;
  std::vector<std::uint8_t> rgb;  // staging for RGB rows
};

PngStream::PngStream(int width, int height, int channels, const PngSettings& settings)
    : state_(std::make_unique<State>()), width_(width), height_(height), channels_(channels) {
  state_->out = OIIO::ImageOutput::create("grid.png");
  if (!state_->out) {
    state_->error = "OpenImageIO has no PNG writer: " + OIIO::geterror();
    return;
  }
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("png:compressionLevel", settings.compression_level);
  if (settings.filter != 0) spec.attribute("png:filter", settings.filter);
  // Our alpha is already straight (toBlob's rule ran): tell OIIO not to convert it.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  state_->out->set_ioproxy(&state_->sink);
  if (!state_->out->open("grid.png", spec)) state_->error = "PNG encoding failed: " + state_->out->geterror();
}

PngStream::~PngStream() = default;

Status PngStream::write_rows(const Image& rows, int y_begin, int y_end) {
  if (!state_->error.empty()) return make_error(ErrorCode::io_error, state_->error);
  const std::uint8_t* data = rows.row(y_begin);
  if (channels_ == 3) {
    const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(y_end - y_begin);
    state_->rgb.resize(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) {
      state_->rgb[i * 3 + 0] = data[i * 4 + 0];
      state_->rgb[i * 3 + 1] = data[i * 4 + 1];
      state_->rgb[i * 3 + 2] = data[i * 4 + 2];
    }
    data = state_->rgb.data();
  }
  if (!state_->out->write_scanlines(y_begin, y_end, 0, OIIO::TypeDesc::UINT8, data)) {
    state_->error = "PNG encoding failed: " + state_->out->geterror();
    return make_error(ErrorCode::io_error, state_->error);
  }
  return Ok{};
}

Expected<std::vector<std::uint8_t>> PngStream::finish() {
  if (!state_->error.empty()) return make_error(ErrorCode::io_error, state_->error);
  if (!state_->out->close()) return make_error(ErrorCode::io_error, "PNG encoding failed: " + state_->out->geterror());
  return std::move(state_->bytes);
}

}  // namespace shadelab::image
