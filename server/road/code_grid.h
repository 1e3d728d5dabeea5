#pragma once
// What a student's code draws, as a grid the student can look at: the course's page on its default
// mesh with their pair, every frame in the notebook's layout. Shown beside a grade (the sheet, a
// PrairieLearn result); never graded itself (the grade renders what it compares).
#include <string>

#include "core/expected.h"
#include "course/course.h"
#include "shader/shader_source.h"
#include "worker/job.h"
#include "worker/pool.h"

namespace shadelab::road {

struct GridJob {
  worker::Job job;
  std::string payload;  // the mesh's bytes, when they travel
};

// The course's render job of its default mesh with the pair (vertex, fragment); `frame_side` > 0
// draws each frame that many pixels wide (the canvas's shape kept) instead of the canvas's size.
GridJob course_grid_job(const course::Course& course, shader::ShaderFile vertex, shader::ShaderFile fragment, int frame_side = 0);

// The grid's PNG; empty when the shaders do not render (too long, do not compile, crash): the
// grade beside it says why. An error only for the grader's own failure.
Expected<std::string> render_grid(worker::WorkerPool& pool, GridJob job);

}  // namespace shadelab::road
