#pragma once
// Where a student's saved frames came from, as far as their pixels tell: from the course's page
// (each frame a little off ShadeLab's render, frames 1 to 8 lagging their angles), or not.
//
// - ShadeLab's own frames: identical, pixel for pixel, to ShadeLab's render of the reference at
//   the exact angles (what GET /api/render?preset=...&output=frames gives a staff key). No browser
//   produces them: even at frame 0 a student's browser differs in a few pixels (0.001-0.002% of
//   them, measured on a real student's page), and frames 1 to 8 lag by 0.16-0.26 degrees at 60 Hz.
//   Where the course wants frames saved from its page they lose the saved-frames test.
// - No lag on any frame, not identical: a page with a fixed clock; the TA looks, no points lost.
// - The same frames as another student's (a class batch): two runs of a page never share lags.
//
// A flag is for the TA: what to look at, in words, beside a score it does not change (but the
// first, where the course says so).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "grade/grader.h"

namespace shadelab::grade {

enum class FlagKind { made_by_shadelab, no_lag, same_frames };

std::string_view to_string(FlagKind kind);
std::optional<FlagKind> flag_named(std::string_view id);

struct Flag {
  FlagKind kind = FlagKind::no_lag;
  std::string message;  // what the TA (and the student) reads
};

// Whether every saved frame is, pixel for pixel, `reference`'s frame of the same index (the
// reference drawn by ShadeLab at each frame's exact angle).
bool drawn_by_shadelab(const std::vector<const image::Image*>& saved, const std::vector<const image::Image*>& reference);

// The frames' flag when they are ShadeLab's own.
Flag made_by_shadelab_flag(int frames);
// What a student reads where that costs the saved-frames test.
std::string save_from_the_page();
// The flag for frames drawn at their exact angles, not ShadeLab's: a page with a fixed clock.
Flag no_lag_flag(int frames);
// The flag for frames another student handed in too (by their names).
Flag same_frames_flag(std::string_view deliverable, const std::vector<std::string>& others);

// A content address of decoded frames: the same pixels give the same fingerprint, whatever the
// PNG encoder (a re-saved or renamed copy is the same hand-in).
std::string fingerprint(const std::vector<const image::Image*>& frames);

}  // namespace shadelab::grade
