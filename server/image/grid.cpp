#include "image/grid.h"

#include <cmath>
#include <cstring>

#include "core/check.h"

namespace shadelab::image {

GridLayout GridLayout::for_frames(int frames, int cell_width, int cell_height) {
  SHADELAB_CHECK(frames > 0, "a grid needs at least one frame");
  int columns = 1;
  while (columns * columns < frames) ++columns;  // ceil(sqrt(N)) without floating point
  const int rows = (frames + columns - 1) / columns;
  return {columns, rows, cell_width, cell_height};
}

void place_frame(const GridLayout& layout, int index, const Image& frame, Image& grid) {
  SHADELAB_CHECK(frame.width == layout.cell_width && frame.height == layout.cell_height, "frame size != cell size");
  SHADELAB_CHECK(frame.type == grid.type, "frame and grid pixel types differ");
  const int x0 = (index % layout.columns) * layout.cell_width;
  const int y0 = (index / layout.columns) * layout.cell_height;
  const size_t offset = static_cast<size_t>(x0) * grid.pixel_bytes();
  for (int y = 0; y < frame.height; ++y) std::memcpy(grid.row(y0 + y) + offset, frame.row(y), frame.row_bytes());
}

Image compose_grid(const GridLayout& layout, const std::vector<Image>& frames) {
  SHADELAB_CHECK(!frames.empty(), "no frames");
  Image grid = Image::blank(layout.width(), layout.height(), frames.front().type);
  for (size_t i = 0; i < frames.size(); ++i) place_frame(layout, static_cast<int>(i), frames[i], grid);
  return grid;
}

}  // namespace shadelab::image
