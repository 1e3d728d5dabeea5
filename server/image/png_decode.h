#pragma once
// A PNG a student saved from their browser, decoded to straight (not premultiplied) RGBA8 rows,
// top-down: what `canvas.toBlob` wrote, byte for byte. Any PNG encoding is read (palette, grey,
// 16-bit, with or without alpha): another browser or tool may have re-encoded it. Only a worker
// decodes a stranger's PNG; its header is checked first, so no decoder ever allocates for a size
// larger than `max_side` a side.
#include <string_view>

#include "core/expected.h"
#include "image/image.h"

namespace shadelab::image {

// invalid_argument with the reason (not a PNG, too large, truncated or corrupt) otherwise.
Expected<Image> decode_png(std::string_view bytes, unsigned max_side = 4096);

}  // namespace shadelab::image
