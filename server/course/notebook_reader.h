#pragma once
// A course profile's `notebook` (docs/course-profile.md): the notebook's file name, its questions
// (each found in the handed-out notebook, when there is one) and the images handed in with it,
// each checked against its scene or for its objects. Checked field by field into the profile's
// first problem (JsonReader), as the rest of the profile is.
#include "core/json_reader.h"
#include "course/course.h"
#include "course/course_reader.h"

namespace shadelab::course {

void read_notebook(const JsonReader& profile, const FileSource& files, Course& course);

}  // namespace shadelab::course
