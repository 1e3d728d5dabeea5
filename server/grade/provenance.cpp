#include "grade/provenance.h"

#include "core/enum_names.h"
#include "core/hash.h"
#include "core/words.h"

namespace shadelab::grade {

namespace {

// The flags by their ids on the wire and in the class summary, in the enum's order.
constexpr EnumName<FlagKind> kFlags[] = {
    {FlagKind::made_by_shadelab, "made_by_shadelab"},
    {FlagKind::no_lag, "no_lag"},
    {FlagKind::same_frames, "same_frames"},
};

bool same_pixels(const image::Image& a, const image::Image& b) {
  return a.width == b.width && a.height == b.height && a.type == b.type && a.bytes == b.bytes;
}

}  // namespace

std::string_view to_string(FlagKind kind) { return name_in(kFlags, kind); }

std::optional<FlagKind> flag_named(std::string_view id) { return value_in(kFlags, id); }

bool drawn_by_shadelab(const std::vector<const image::Image*>& saved, const std::vector<const image::Image*>& reference) {
  if (saved.empty() || saved.size() != reference.size()) return false;
  for (size_t k = 0; k < saved.size(); ++k)
    if (!same_pixels(*saved[k], *reference[k])) return false;
  return true;
}

Flag made_by_shadelab_flag(int frames) {
  return {FlagKind::made_by_shadelab, "made by ShadeLab, not saved from the page: all " + std::to_string(frames) +
                                          " frames are identical, pixel for pixel, to ShadeLab's own render of the reference at the exact "
                                          "angles, which no browser produces (even at frame 0 a browser differs in a few pixels, and later "
                                          "frames lag their angles)"};
}

std::string save_from_the_page() {
  return "the course wants the frames saved from its page (its Save button), not made by ShadeLab: these score 0 as saved frames; "
         "save your own from the page and hand those in";
}

Flag no_lag_flag(int frames) {
  return {FlagKind::no_lag, "frames 1 to " + std::to_string(frames - 1) +
                                " were drawn at exactly their nominal angles: no lag on any frame, which a page on a running clock does not "
                                "give (a page with a fixed clock, or frames not saved from the page?); for the TA to look at, no points lost"};
}

Flag same_frames_flag(std::string_view deliverable, const std::vector<std::string>& others) {
  return {FlagKind::same_frames, "the same " + std::string(deliverable) + " frames, pixel for pixel, as " + and_list(others) +
                                     " handed in: two runs of a page never draw the same lags"};
}

std::string fingerprint(const std::vector<const image::Image*>& frames) {
  std::string all;
  for (const image::Image* f : frames) {
    all += std::to_string(f->width) + "x" + std::to_string(f->height) + ":";
    all.append(reinterpret_cast<const char*>(f->bytes.data()), f->bytes.size());
  }
  return sha256_hex(all);
}

}  // namespace shadelab::grade
