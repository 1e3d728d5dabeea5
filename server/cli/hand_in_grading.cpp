#include "cli/hand_in_grading.h"

#include <cmath>
#include <future>
#include <map>
#include <memory>

#include "cli/submission_files.h"
#include "core/enum_names.h"
#include "course/submission_files.h"
#include "road/code_grid.h"
#include "road/hand_in_checks.h"
#include "sheet/saved_grid.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using course::DeliverableTest;
using Deadline = std::optional<std::chrono::steady_clock::time_point>;
using CodePair = std::pair<fs::path, fs::path>;

constexpr EnumName<HandInPart> kHandInParts[] = {
    {HandInPart::whole, "whole"}, {HandInPart::deliverables, "deliverables"}, {HandInPart::images, "images"}};
static_assert(std::size(kHandInParts) == static_cast<size_t>(HandInPart::images) + 1);

bool grades_images(const HandInFlags& f) { return f.checkpoint.empty() && f.part != HandInPart::deliverables; }

// Each deliverable's files, its shader pair and its saved frames where the hand-in has them; for
// one checkpoint's code alone, that checkpoint with its pair and no frames; none for the images.
std::vector<DeliverableGrades> deliverables(const course::Course& course, const HandInFlags& f, const std::vector<fs::path>& files) {
  const std::vector<course::CheckpointFiles> plan = course::plan_checkpoints(course, files);
  std::vector<DeliverableGrades> out;
  if (f.checkpoint.empty() && f.part == HandInPart::images) return out;
  for (const auto& k : course.checkpoints) {
    if (!f.checkpoint.empty() && k.name != f.checkpoint) continue;
    DeliverableGrades d{&k, f.max_score.value_or(k.points), std::nullopt, {}, {}, {}};
    if (f.checkpoint.empty()) d.frames = course::saved_frame_files(course, k, files);
    for (const auto& p : plan)
      if (p.checkpoint == k.name) d.code = p.pair;
    out.push_back(std::move(d));
  }
  return out;
}

// The grade jobs `out` needs: one for each deliverable's code and one for its frames.
int jobs_for(const std::vector<DeliverableGrades>& out) {
  int jobs = 0;
  for (const auto& d : out) jobs += (d.code ? 1 : 0) + (d.frames.any() ? 1 : 0);
  return jobs;
}

// The jobs queued beside the grades, which take no worker of their own: the grids a student sees
// and the checked images.
size_t queued_beside_grades(const course::Course& course, const HandInFlags& f, const std::vector<DeliverableGrades>& ds) {
  size_t jobs = 0;
  for (const auto& d : ds) jobs += d.code && !d.frames.any() && f.grid_side > 0;
  if (grades_images(f))
    for (const auto& image : course.images) jobs += image.checked();
  return jobs;
}

// The work in flight. On the heap, so that a deadline can walk away from it: a future of
// std::async waits in its destructor, and the workers die with the process.
struct InFlight {
  std::unique_ptr<worker::WorkerPool> pool;
  std::vector<std::future<std::optional<Expected<Graded>>>> code;
  std::vector<std::future<std::optional<Expected<GradedFrames>>>> frames;
  std::vector<std::future<Expected<std::string>>> code_grids;  // one per deliverable; "" without code
  std::optional<std::future<Expected<std::vector<grade::ImageCheck>>>> images;
};

// The course's checked images (the dolly zoom's cameras), each found as the sheet finds it: at its
// path in the folder, or a path ending in it, the shallowest first.
Expected<std::vector<grade::ImageCheck>> check_images(worker::WorkerPool& pool, const course::Course& course, const fs::path& root,
                                                      const std::vector<fs::path>& files) {
  std::map<std::string, std::string> read;
  return road::check_hand_in_images(pool, course, [&](const std::string& name) -> const std::string* {
    const fs::path* found = course::file_at(files, name);
    return found ? &(read[name] = read_text(root / *found)) : nullptr;
  });
}

// Every job queued at once (the pool's workers take them in parallel): each deliverable's code
// against the reference, its frames (with the code) side by side, the grid its code draws when
// asked for and no frames were saved, and the checked images.
void start(InFlight& work, const course::Course& course, const HandInFlags& f, const fs::path& root, const std::vector<DeliverableGrades>& ds,
           const std::vector<fs::path>& files) {
  worker::WorkerPool& pool = *work.pool;
  for (const auto& d : ds) {
    GradeFlags flags = f.grade;
    flags.reference = d.checkpoint->name;
    const std::optional<CodePair> code = d.code;
    work.code.push_back(std::async(std::launch::async, [&pool, &course, flags, root, code]() -> std::optional<Expected<Graded>> {
      if (!code) return std::nullopt;
      return grade_one(pool, course, flags, root / code->first, root / code->second);
    }));
    const course::Checkpoint& k = *d.checkpoint;
    work.frames.push_back(std::async(std::launch::async, [&pool, &course, flags, root, &k, frames = d.frames, code]() -> std::optional<Expected<GradedFrames>> {
      if (!frames.any()) return std::nullopt;
      return grade_saved_frames(pool, course, flags, k, root, frames, code);
    }));
    // What the code draws, where no saved frames show the student their work.
    const int side = d.frames.any() ? 0 : f.grid_side;
    work.code_grids.push_back(std::async(std::launch::async, [&pool, &course, root, code, side]() -> Expected<std::string> {
      if (!code || side <= 0) return std::string();
      return road::render_grid(pool, road::course_grid_job(course, {code->first.filename().string(), read_text(root / code->first)},
                                                           {code->second.filename().string(), read_text(root / code->second)}, side));
    }));
  }
  if (grades_images(f))
    work.images = std::async(std::launch::async, [&pool, &course, root, files] { return check_images(pool, course, root, files); });
}

// The future's value, or nullopt when the deadline comes first.
template <class T>
std::optional<T> by_deadline(std::future<T>& f, const Deadline& deadline) {
  if (deadline && f.wait_until(*deadline) != std::future_status::ready) return std::nullopt;
  return f.get();
}

Error out_of_time() {
  return make_error(ErrorCode::grader_failed, "the grader ran out of the time the course allows a grade before it finished this test");
}

// The saved frames as the student handed them in, as a grid; empty when they cannot be shown (the
// frames' test says why).
std::string saved_grid(const DeliverableGrades& d, const fs::path& root, int side) {
  std::vector<std::pair<std::string, std::string>> named;
  for (const auto& frame : d.frames.frames) {
    std::error_code error;
    if (frame && fs::file_size(root / *frame, error) <= kMaxFrameBytes && !error) named.emplace_back(frame->string(), read_text(root / *frame));
  }
  auto grid = named.empty() ? Expected<std::string>(std::string()) : sheet::saved_frames_grid(named, 3, side);
  return grid ? *grid : std::string();
}

void add_grids(const HandInFlags& f, const fs::path& root, const std::vector<DeliverableGrades>& ds,
               std::vector<Expected<std::string>>& code_grids, HandInResults& out) {
  if (f.grid_side <= 0) return;
  for (size_t i = 0; i < ds.size(); ++i) {
    const std::string& title = ds[i].checkpoint->title;
    if (ds[i].frames.any())
      if (std::string png = saved_grid(ds[i], root, f.grid_side); !png.empty()) out.grids.push_back({title + ": the frames you saved", std::move(png)});
    if (code_grids[i] && !code_grids[i]->empty()) out.grids.push_back({title + ": what your code draws", std::move(*code_grids[i])});
  }
}

void add_tests(std::vector<HandInTest> tests, HandInResults& out) {
  for (auto& t : tests) {
    out.score += t.score;
    out.max_score += t.max_score;
    out.tests.push_back(std::move(t));
  }
}

std::string summary_of(const HandInResults& r, const std::vector<DeliverableGrades>& ds) {
  int passed = 0;
  for (const auto& t : r.tests) passed += t.pass;
  std::string summary = std::to_string(passed) + " of " + std::to_string(r.tests.size()) + " tests passed\n";
  if (!r.finished) summary += "The grader ran out of time before it finished every test: those it did not finish say so.\n";
  // The flags at the top, where the TA opening the submission reads first.
  for (const auto& d : ds)
    if (d.frames_grade && *d.frames_grade)
      for (const auto& flag : (**d.frames_grade).result.frames.flags)
        summary += "FLAGGED FOR THE TA (" + d.checkpoint->name + " saved frames): " + flag.message + "\n";
  return summary;
}

}  // namespace

std::string_view to_string(HandInPart part) { return name_in(kHandInParts, part); }
std::optional<HandInPart> hand_in_part_named(std::string_view name) { return value_in(kHandInParts, name); }

HandInResults grade_hand_in(const course::Course& course, const HandInFlags& f, const fs::path& root) {
  const std::vector<fs::path> files = submitted_files(root);
  std::vector<DeliverableGrades> ds = deliverables(course, f, files);
  // As many workers as there are jobs, up to one per core: a submission with one deliverable's
  // code gets one worker with every core's llvmpipe thread, not one of two with half of them.
  auto work = std::make_unique<InFlight>();
  worker::PoolConfig config = pool_config(f.grade, jobs_for(ds));
  config.max_queue += queued_beside_grades(course, f, ds);
  work->pool = std::make_unique<worker::WorkerPool>(config);
  start(*work, course, f, root, ds, files);

  HandInResults out;
  std::vector<Expected<std::string>> code_grids;
  for (size_t i = 0; i < ds.size(); ++i) {
    auto code = by_deadline(work->code[i], f.deadline);
    auto frames = by_deadline(work->frames[i], f.deadline);
    auto grid = by_deadline(work->code_grids[i], f.deadline);
    out.finished &= code && frames && grid;
    ds[i].code_grade = code ? std::move(*code) : std::optional<Expected<Graded>>(Expected<Graded>(out_of_time()));
    ds[i].frames_grade = frames ? std::move(*frames) : std::optional<Expected<GradedFrames>>(Expected<GradedFrames>(out_of_time()));
    code_grids.push_back(grid ? std::move(*grid) : Expected<std::string>(std::string()));
  }
  for (const auto& d : ds) {
    std::vector<HandInTest> tests = deliverable_tests(course, d, files);
    if (!f.checkpoint.empty())
      std::erase_if(tests, [](const HandInTest& t) { return t.test != DeliverableTest::code && t.test != DeliverableTest::probe; });
    add_tests(std::move(tests), out);
    if (d.code_grade && *d.code_grade) out.seconds += (**d.code_grade).seconds;
    if (d.frames_grade && *d.frames_grade) out.seconds += (**d.frames_grade).seconds;
  }
  if (work->images) {
    auto images = by_deadline(*work->images, f.deadline);
    out.finished &= images.has_value();
    add_tests(image_tests(course, images ? std::move(*images) : Expected<std::vector<grade::ImageCheck>>(out_of_time())), out);
  }
  add_grids(f, root, ds, code_grids, out);
  out.score = std::round(out.score * 1e6) / 1e6;  // shares of points: 0.4 + 0.2 + ... is not exact in binary
  out.summary = summary_of(out, ds);
  if (!out.finished) (void)work.release();  // abandoned: the caller writes its results and exits without waiting
  return out;
}

}  // namespace shadelab::cli
