#pragma once
// The grid of the frames a student saved from their browser (images/hw2_diffuse_0.png, ...),
// laid out as the notebook lays them out: files in order, row by row, three to a row. Decoded and
// drawn by cairo (its PNG reader), each file's header checked first (image/png_info.h).
#include <string>
#include <vector>

#include "core/expected.h"

namespace shadelab::sheet {

// The frames' largest side a sheet accepts: a browser's canvas, not a poster.
inline constexpr unsigned kMaxSavedFrameSide = 4096;

// PNG bytes of the grid, each cell the first frame's size, or `cell_width` pixels wide in its shape
// when set (a frame of another size is scaled into it). invalid_argument naming the frame when one
// is not a PNG or is too large.
Expected<std::string> saved_frames_grid(const std::vector<std::pair<std::string, std::string>>& named_pngs, int columns = 3,
                                        int cell_width = 0);

}  // namespace shadelab::sheet
