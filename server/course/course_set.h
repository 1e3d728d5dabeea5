#pragma once
// The courses a server holds (`shadelab serve --course A.json --course B.json`), the first the
// default: a request names one by its id in its `course` field, or means the default.
#include <memory>
#include <string_view>
#include <vector>

#include "core/expected.h"
#include "course/course.h"

namespace shadelab::course {

class CourseSet {
 public:
  // The built-in course alone.
  CourseSet();
  // `courses` must be non-empty with distinct ids (invalid_argument otherwise).
  static Expected<CourseSet> of(std::vector<std::shared_ptr<const Course>> courses);

  const Course& default_course() const { return *courses_.front(); }
  // The course `id` names; the default for an empty id; unknown_course naming the ids held.
  Expected<const Course*> named(std::string_view id) const;
  const std::vector<std::shared_ptr<const Course>>& all() const { return courses_; }

 private:
  explicit CourseSet(std::vector<std::shared_ptr<const Course>> courses) : courses_(std::move(courses)) {}
  std::vector<std::shared_ptr<const Course>> courses_;
};

}  // namespace shadelab::course
