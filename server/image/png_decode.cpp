#include "image/png_decode.h"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <vector>

#include "image/png_info.h"

namespace shadelab::image {

namespace {

struct Reader {
  std::string_view bytes;
  size_t at = 0;
};

void read_bytes(png_structp png, png_bytep out, png_size_t length) {
  auto* r = static_cast<Reader*>(png_get_io_ptr(png));
  if (r->bytes.size() - r->at < length) png_error(png, "the file ends early");
  std::memcpy(out, r->bytes.data() + r->at, length);
  r->at += length;
}

// libpng reports an error by longjmp; the message is kept for the caller's Error.
void on_error(png_structp png, png_const_charp message) {
  auto* text = static_cast<std::string*>(png_get_error_ptr(png));
  *text = message;
  std::longjmp(png_jmpbuf(png), 1);
}
void on_warning(png_structp, png_const_charp) {}

Error unreadable(const std::string& why) { return make_error(ErrorCode::invalid_argument, "not a readable PNG file: " + why); }

// Reads the image into `rows`, to 8-bit RGBA whatever was stored: palettes and grey expanded, 16
// bits stripped, transparency chunks to alpha, opaque files given alpha 255. libpng reports errors
// by longjmp, so this frame holds only plain pointers; false on an error.
bool read_rgba(png_structp png, png_infop info, png_bytep* rows, size_t row_bytes, Reader* reader) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, reader, read_bytes);
  png_read_info(png, info);
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_filler(png, 0xff, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != row_bytes) png_error(png, "unexpected row size");
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

Expected<Image> decode_png(std::string_view bytes, unsigned max_side) {
  const auto info = png_info(bytes);
  if (!info) return unreadable("no PNG signature and header");
  if (info->width > max_side || info->height > max_side)
    return make_error(ErrorCode::invalid_argument, "the PNG is " + std::to_string(info->width) + " x " + std::to_string(info->height) +
                                                       " pixels: larger than " + std::to_string(max_side) + " a side");
  Image out = Image::blank(static_cast<int>(info->width), static_cast<int>(info->height), PixelType::u8);
  std::vector<png_bytep> rows(info->height);
  for (int y = 0; y < out.height; ++y) rows[static_cast<size_t>(y)] = out.row(y);
  std::string message;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &message, on_error, on_warning);
  if (!png) return unreadable("libpng would not start");
  png_infop png_info_struct = png_create_info_struct(png);
  Reader reader{bytes};
  const bool read = png_info_struct && read_rgba(png, png_info_struct, rows.data(), out.row_bytes(), &reader);
  png_destroy_read_struct(&png, &png_info_struct, nullptr);
  if (!read) return unreadable(message);
  return out;
}

}  // namespace shadelab::image
