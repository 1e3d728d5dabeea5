#pragma once
// A worker job of a course: its canvas, frames, samples and page setup in the request, its frame
// names, and one of its meshes attached the way workers take meshes (an embedded file by its
// path, a profile's own mesh as bytes under its content address).
#include <string>

#include "core/expected.h"
#include "course/course.h"
#include "worker/job.h"

namespace shadelab::worker {

// A job of `kind` drawing `vertex` and `fragment` as the course draws them (its canvas, frames,
// samples and page setup), with its frame names; no mesh yet.
Job course_job(const course::Course& course, JobKind kind, shader::ShaderFile vertex = {}, shader::ShaderFile fragment = {});
// A job of `kind` drawing `request`, one the course made already (course::answer's), with its frame names.
Job course_job(const course::Course& course, JobKind kind, render::RenderRequest request);

// Sets the job's mesh to the course's mesh `name` and puts its bytes, if they travel, in
// `payload`; mesh_not_found naming the course's meshes for another name.
Status attach_course_mesh(const course::Course& course, const std::string& name, Job& job, std::string& payload);
void attach_mesh(const course::CourseMesh& mesh, Job& job, std::string& payload);

}  // namespace shadelab::worker
