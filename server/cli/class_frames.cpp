#include "cli/class_frames.h"

#include <iostream>

#include "cli/grade_runner.h"
#include "cli/submission_files.h"
#include "course/submission_files.h"
#include "grade/provenance.h"
#include "image/png_decode.h"
#include "worker/client.h"
#include "worker/course_job.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;

std::vector<const image::Image*> views(const std::vector<image::Image>& images) {
  std::vector<const image::Image*> out;
  for (const auto& i : images) out.push_back(&i);
  return out;
}

}  // namespace

ClassFrames::ClassFrames(const course::Course& course, const course::Checkpoint& checkpoint, ReferenceFrames reference)
    : course_(course), checkpoint_(checkpoint), draw_reference_(std::move(reference)) {}

const std::vector<image::Image>& ClassFrames::reference() const {
  std::call_once(drawn_, [this] {
    auto pngs = draw_reference_();
    if (!pngs) {
      std::cerr << "\nnote: saved frames are not compared with ShadeLab's own render of the reference: " << pngs.error().message << "\n";
      return;
    }
    for (const auto& png : *pngs)
      if (auto decoded = image::decode_png(png)) reference_.push_back(std::move(*decoded));
    if (reference_.size() != pngs->size()) reference_.clear();
  });
  return reference_;
}

void ClassFrames::check(const Student& student, StudentGrade& grade) const {
  const course::SavedFrameFiles files = course::saved_frame_files(course_, checkpoint_, submitted_files(student.dir));
  std::vector<image::Image> frames;
  for (const auto& f : files.frames) {
    std::error_code error;
    if (!f || fs::file_size(student.dir / *f, error) > kMaxFrameBytes || error) return;
    auto decoded = image::decode_png(read_text(student.dir / *f));
    if (!decoded) return;  // the frames' own grade says what is wrong with them; nothing to compare
    frames.push_back(std::move(*decoded));
  }
  if (frames.empty()) return;
  grade.frames_fingerprint = grade::fingerprint(views(frames));
  if (grade::drawn_by_shadelab(views(frames), views(reference()))) grade.report.flags.push_back(grade::made_by_shadelab_flag(course_.frames));
}

Expected<std::vector<std::string>> reference_frames(worker::WorkerPool& pool, const course::Course& course, const course::Checkpoint& checkpoint) {
  const course::Preset& reference = *course.preset(checkpoint.reference);
  worker::Job job = worker::course_job(course, worker::JobKind::render, reference.vertex, reference.fragment);
  std::string payload;
  if (auto attached = worker::attach_course_mesh(course, course.default_mesh, job, payload); !attached) return attached.take_error();
  job.output = worker::Output::json;
  auto rendered = worker::run<worker::RenderResult>(pool, worker::to_message(job, std::move(payload)));
  if (!rendered) return rendered.take_error();
  std::vector<std::string> out;
  for (auto& f : rendered->result.frames) out.push_back(std::move(f.bytes));
  return out;
}

}  // namespace shadelab::cli
