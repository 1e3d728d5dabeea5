#pragma once
// The notebook's grid: frames row by row, ceil(sqrt(N)) columns (3 x 3 for 9 frames). Cells
// without a frame stay transparent black.
#include <vector>

#include "image/image.h"

namespace shadelab::image {

struct GridLayout {
  int columns = 1, rows = 1;
  int cell_width = 0, cell_height = 0;

  static GridLayout for_frames(int frames, int cell_width, int cell_height);
  int width() const { return columns * cell_width; }
  int height() const { return rows * cell_height; }
  int cells() const { return columns * rows; }
};

// Copies frame `index` into its cell of `grid` (grid.type must match frame.type).
void place_frame(const GridLayout& layout, int index, const Image& frame, Image& grid);
Image compose_grid(const GridLayout& layout, const std::vector<Image>& frames);

}  // namespace shadelab::image
