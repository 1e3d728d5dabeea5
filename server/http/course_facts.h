#pragma once
// A course as the page and API clients see it (GET /api/course, GET /api/presets), for a viewer:
// what a student sees is the course's public material, never a reference's source. The CLI
// prints the same (`shadelab course show --as student`) for a page hosted elsewhere, such as a
// PrairieLearn question's live canvas.
#include <nlohmann/json.hpp>

#include "course/access.h"
#include "course/course.h"

namespace shadelab::http {

// The presets `viewer` may see, with their sources.
nlohmann::json presets_json(const course::Course& course, const course::Viewer& viewer);

// The profile's own JSON (docs/course-profile.md), with what only the server uses swapped out:
// meshes as the URLs the page loads them from, presets with their sources instead of file paths
// (those the viewer may see: course/access.h), no catalogue of mistakes (its edits quote the
// references), and what the page opens with.
nlohmann::json course_json(const course::Course& course, const course::Viewer& viewer);

}  // namespace shadelab::http
