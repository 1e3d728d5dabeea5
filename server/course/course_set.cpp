#include "course/course_set.h"

#include "course/course_reader.h"

namespace shadelab::course {

CourseSet::CourseSet() : courses_{std::shared_ptr<const Course>(&builtin_course(), [](const Course*) {})} {}

Expected<CourseSet> CourseSet::of(std::vector<std::shared_ptr<const Course>> courses) {
  if (courses.empty()) return make_error(ErrorCode::invalid_argument, "a server needs at least one course");
  for (size_t i = 0; i < courses.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (courses[i]->id == courses[j]->id)
        return make_error(ErrorCode::invalid_argument, "two courses have the id '" + courses[i]->id + "' (" + courses[j]->origin + ", " +
                                                           courses[i]->origin + ")");
  return CourseSet(std::move(courses));
}

Expected<const Course*> CourseSet::named(std::string_view id) const {
  if (id.empty()) return courses_.front().get();
  std::string ids;
  for (const auto& c : courses_) {
    if (c->id == id) return c.get();
    ids += (ids.empty() ? "" : ", ") + c->id;
  }
  return make_error(ErrorCode::unknown_course, "this server holds no course '" + std::string(id) + "' (it holds: " + ids + ")");
}

}  // namespace shadelab::course
