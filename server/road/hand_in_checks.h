#pragma once
// The course's checked hand-in images judged for one student on the road: a worker decodes the
// student's PNGs, renders the handout's cameras for the dolly zoom's (grade/camera_check.h) and
// counts the objects in a render the handout describes in words (grade/render_check.h). One verdict, which the sheet, `shadelab sheet`'s
// summary and Gradescope each show as it is.
#include <functional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "course/course.h"
#include "grade/image_check.h"
#include "worker/pool.h"

namespace shadelab::road {

// The student's file at a path of their folder (images/camera_25.png), or null.
using FindFile = std::function<const std::string*(const std::string& path)>;

// One check per checked image of the course, in its order; none when it checks none. An Error is
// the service's (the pool full, no worker): what the student handed in is its verdict.
Expected<std::vector<grade::ImageCheck>> check_hand_in_images(worker::WorkerPool& pool, const course::Course& course, const FindFile& find);

}  // namespace shadelab::road
