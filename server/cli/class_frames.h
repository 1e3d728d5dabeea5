#pragma once
// The saved frames of a class batch's deliverable, looked at across the class (grade/provenance.h):
// each student's frames fingerprinted by their pixels, so two students who hand in the same frames
// are flagged in the summary (class_batch.h), and compared with ShadeLab's own render of the
// reference at the exact angles, frames no page draws. Neither changes the batch's score (the
// code's): both are for the TA.
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cli/class_batch.h"
#include "course/course.h"
#include "image/image.h"
#include "worker/pool.h"

namespace shadelab::cli {

class ClassFrames {
 public:
  // The reference's frames at the exact angles (PNGs), drawn once, when the first student's frames
  // need them: a batch of code alone draws nothing more. An error skips that comparison, said once.
  using ReferenceFrames = std::function<Expected<std::vector<std::string>>()>;
  ClassFrames(const course::Course& course, const course::Checkpoint& checkpoint, ReferenceFrames reference);

  // The student's frames of the deliverable, when they hand in every one and each reads: their
  // fingerprint on `grade`, and the made_by_shadelab flag when they are ShadeLab's own.
  void check(const Student& student, StudentGrade& grade) const;

 private:
  const std::vector<image::Image>& reference() const;

  const course::Course& course_;
  const course::Checkpoint& checkpoint_;
  ReferenceFrames draw_reference_;
  mutable std::once_flag drawn_;
  mutable std::vector<image::Image> reference_;
};

// The reference's frames at the exact angles, drawn by this process's workers.
Expected<std::vector<std::string>> reference_frames(worker::WorkerPool& pool, const course::Course& course, const course::Checkpoint& checkpoint);

}  // namespace shadelab::cli
