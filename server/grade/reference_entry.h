#pragma once
// One entry of the reference store (grade/reference_store.h): a set of frames as bytes, for a
// file or a Redis value. Its reader takes bytes from a disk or a network: a damaged, cut or
// forged entry is a miss, never frames that are not the request's and never an allocation the
// request would not make (tests/fuzz/targets/reference_entry.cpp).
//
// | bytes            | what                                                     |
// |------------------|----------------------------------------------------------|
// | "SLREF2\n"       | the format                                               |
// | 4 x uint32, LE   | width, height, frames, pixel type (0: RGBA8, 1: RGBA32F) |
// | the rest         | the frames' pixels, rows top-down: one zstd frame, level |
// |                  | 1, with its content size and checksum                    |
//
// zstd, not zlib: the same size at level 1, and ~6x faster to read back (a course's set of 9
// frames: 2.7 against 18 ms), which a grade pays for every set it reads (docs/performance-log.md).
#include <optional>
#include <string>
#include <string_view>

#include "grade/grader.h"
#include "render/render_request.h"

namespace shadelab::grade {

// The format's name, first in every entry and part of every key: a new format is a new key.
inline constexpr std::string_view kReferenceEntryFormat = "SLREF2\n";

// Empty when the frames do not share one size and pixel type (or cannot be compressed).
std::string encode_reference_entry(const SharedFrames& frames);

// `expected`'s frames (its width, height, frame count and pixel type), or nullopt.
std::optional<SharedFrames> decode_reference_entry(std::string_view entry, const render::RenderRequest& expected);

}  // namespace shadelab::grade
