#include "grade/grader.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>

#include "core/words.h"
#include "core/check.h"
#include "grade/diagnosis.h"

namespace shadelab::grade {

namespace {

// Small shares keep their digits: 0.004%, not 0.0%.
std::string fine_percent(double f) { return shadelab::percent(f, f < 0.001 ? 3 : 1); }

// Failing pixels over the pixels the object covers in either image (see FrameGrade).
double failing_of_object(const image::Image& a, const image::Image& b, double failing_fraction) {
  std::size_t covered = 0;
  for (std::size_t i = 0; i < a.bytes.size(); i += 4) covered += !is_clear(&a.bytes[i]) || !is_clear(&b.bytes[i]);
  const double pixels = static_cast<double>(a.width) * a.height;
  return covered == 0 ? 0.0 : failing_fraction * pixels / static_cast<double>(covered);
}

// How the student's frames fare with `candidate` standing in for the reference: each frame's
// failing share of the object, counted once (compare()'s other metrics are not needed here).
struct AgainstCandidate {
  double matching = 0;  // share of frames that pass
  double mean_failing = 0;
};

// One frame's failing share of the object with `candidate` standing in for the reference.
double failing_share(const image::Image& frame, const image::Image& candidate, const GradeOptions& options) {
  const double pixels = static_cast<double>(frame.width) * frame.height;
  return failing_of_object(frame, candidate, static_cast<double>(image::failing_pixels(frame, candidate, options.compare)) / pixels);
}

AgainstCandidate against(const SharedFrames& student, const SharedFrames& candidate, const GradeOptions& options) {
  AgainstCandidate out;
  for (size_t k = 0; k < student.size(); ++k) {
    const double failing = failing_share(*student[k], *candidate[k], options);
    out.matching += failing <= options.max_failing_fraction;
    out.mean_failing += failing;
  }
  const auto n = static_cast<double>(student.size());
  out.matching /= n;
  out.mean_failing /= n;
  return out;
}

image::Image with_channels(const image::Image& frame, const std::array<int, 3>& order) {
  image::Image out = frame;
  for (size_t i = 0; i < out.bytes.size(); i += 4)
    for (int c = 0; c < 3; ++c) out.bytes[i + static_cast<size_t>(c)] = frame.bytes[i + static_cast<size_t>(order[static_cast<size_t>(c)])];
  return out;
}

// The student's frames with RGB permuted: does some order other than R, G, B match the reference
// in every frame? An order is given up at its first frame that does not match.
std::string swapped_channels(const SharedFrames& student, const SharedFrames& reference,
                             const GradeOptions& options) {
  constexpr std::array<std::array<int, 3>, 5> orders = {{{0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  const char* names = "RGB";
  for (const auto& order : orders) {
    bool every = true;
    for (size_t k = 0; k < student.size() && every; ++k)
      every = failing_share(with_channels(*student[k], order), *reference[k], options) <= options.max_failing_fraction;
    if (every)
      return std::string("colour channels swapped: your (") + names[order[0]] + ", " + names[order[1]] + ", " +
             names[order[2]] + ") would match the reference's (R, G, B)";
  }
  return "";
}

// The frame with the largest failing share of the object (the first of equals).
size_t worst_frame(const GradeResult& r) {
  size_t worst = 0;
  for (size_t k = 1; k < r.frames.size(); ++k)
    if (r.frames[k].failing_fraction_of_object > r.frames[worst].failing_fraction_of_object) worst = k;
  return worst;
}

}  // namespace

GradeResult assess(const SharedFrames& student, const std::vector<image::NonFinite>& student_non_finite, const SharedFrames& reference,
                   const GradeOptions& options) {
  SHADELAB_CHECK(!student.empty() && student.size() == reference.size(), "grade needs matching frame lists");
  GradeResult r;
  r.max_score = options.max_score;
  std::size_t nan = 0, inf = 0, pixels = 0;
  int passing = 0;
  for (size_t k = 0; k < student.size(); ++k) {
    FrameGrade f;
    f.metrics = image::compare(*student[k], *reference[k], options.compare);
    f.failing_fraction_of_object = failing_of_object(*student[k], *reference[k], f.metrics.failing_fraction);
    if (k < student_non_finite.size()) f.non_finite = student_non_finite[k];
    f.pass = f.failing_fraction_of_object <= options.max_failing_fraction && f.non_finite.nan == 0 && f.non_finite.inf == 0;
    passing += f.pass;
    nan += f.non_finite.nan;
    inf += f.non_finite.inf;
    pixels += static_cast<std::size_t>(student[k]->width) * student[k]->height;
    r.frames.push_back(f);
  }
  const size_t worst = worst_frame(r);
  r.pass = passing == static_cast<int>(student.size());
  r.score = options.max_score * passing / static_cast<double>(student.size());
  const auto& w = r.frames[worst].metrics;
  const double worst_object = r.frames[worst].failing_fraction_of_object;
  if (nan > 0) {
    r.diagnosis = to_string(Diagnosis::nan);
    r.messages.push_back("NaN in " + fine_percent(static_cast<double>(nan) / pixels) +
                         " of pixels: the browser shows them black or transparent (a division by zero, or normalize() "
                         "of a zero vector?)");
  }
  if (inf > 0) r.messages.push_back("infinity in " + fine_percent(static_cast<double>(inf) / pixels) + " of pixels");
  if (r.pass) {
    r.messages.push_back(w.identical ? "matches the reference exactly"
                                     : "matches the reference: at worst " + fine_percent(worst_object) +
                                           " of the object's pixels differ by more than the tolerance (frame " +
                                           std::to_string(worst) + ")");
  }
  return r;
}

void explain(GradeResult& r, const SharedFrames& student, const SharedFrames& reference, const std::vector<RenderedMistake>& mistakes,
             const GradeOptions& options, const RenderedMistake* recognised) {
  if (r.pass) return;
  const size_t worst = worst_frame(r);
  const auto passing = std::count_if(r.frames.begin(), r.frames.end(), [](const FrameGrade& f) { return f.pass; });
  const double worst_object = r.frames[worst].failing_fraction_of_object;
  // Which known mistake explains the frames best, if one explains them at all?
  const RenderedMistake* best = recognised;
  double failing_sum = 0;
  for (const auto& f : r.frames) failing_sum += f.failing_fraction_of_object;
  double best_failing = failing_sum / static_cast<double>(r.frames.size());
  const double reference_failing = best_failing;
  if (!recognised)  // the formula's reading found it: nothing to compare
    for (const auto& m : mistakes) {
      const AgainstCandidate fit = against(student, m.frames, options);
      const bool explains = fit.matching == 1.0 || fit.mean_failing < options.closer_than_reference * reference_failing;
      if (explains && fit.mean_failing < best_failing) best = &m, best_failing = fit.mean_failing;
    }
  if (best) {
    if (r.diagnosis.empty()) r.diagnosis = best->id;
    r.messages.push_back(best->message);
  } else if (const std::string swap = swapped_channels(student, reference, options); !swap.empty()) {
    if (r.diagnosis.empty()) r.diagnosis = to_string(Diagnosis::swapped_channels);
    r.messages.push_back(swap);
  }
  r.messages.push_back(std::to_string(student.size() - static_cast<size_t>(passing)) + " of " + std::to_string(student.size()) +
                       " frames differ from the reference; worst frame " + std::to_string(worst) + ": " +
                       fine_percent(worst_object) + " of the object's pixels off by more than " +
                       std::to_string(static_cast<int>(options.compare.threshold * 255 + 1e-9)) + "/255");
}

GradeResult grade(const SharedFrames& student, const std::vector<image::NonFinite>& student_non_finite,
                  const SharedFrames& reference, const std::vector<RenderedMistake>& mistakes, const GradeOptions& options) {
  GradeResult r = assess(student, student_non_finite, reference, options);
  explain(r, student, reference, mistakes, options);
  return r;
}

}  // namespace shadelab::grade
