#include "sheet/assemble.h"

#include <algorithm>
#include <future>
#include <optional>

#include "grade/checkpoints.h"
#include "grade/submission_files.h"
#include "render/render_request.h"
#include "scene/scene_description.h"
#include "worker/client.h"

namespace shadelab::sheet {

namespace {

namespace fs = std::filesystem;

const std::string& text_of(const SheetInput& input, const fs::path& path) {
  static const std::string none;
  for (const auto& f : input.files)
    if (f.path == path) return f.text;
  return none;
}

render::RenderRequest request_for(const SheetInput& input, const fs::path& vert, const fs::path& frag) {
  render::RenderRequest r;
  r.vertex = {vert.filename().string(), text_of(input, vert)};
  r.fragment = {frag.filename().string(), text_of(input, frag)};
  return r;
}

// The grid the student's shaders render, as the page would save it; empty when they do not.
Expected<std::string> grid(worker::WorkerPool& pool, const render::RenderRequest& request) {
  if (!render::check_sources(request, render::RenderLimits{})) return std::string();
  worker::Job job;
  job.kind = worker::JobKind::render;
  job.request = request;
  auto rendered = worker::run<worker::RenderResult>(pool, worker::to_message(job));
  if (rendered) return std::move(rendered->result.body);
  if (info(rendered.error().code).submission_caused) return std::string();
  return rendered.take_error();
}

Expected<grade::Report> graded(worker::WorkerPool& pool, const std::string& checkpoint, const render::RenderRequest& request) {
  auto spec = grade::checkpoint_spec(checkpoint, grade::GradeOptions{});
  if (!spec) return spec.take_error();
  if (auto sources = render::check_sources(request, render::RenderLimits{}); !sources)
    return grade::failed_submission(sources.error(), checkpoint, spec->options.max_score);
  worker::Job job;
  job.kind = worker::JobKind::grade;
  job.request = request;
  job.grade = std::move(*spec);
  auto answered = worker::grade(pool, job, "");
  if (!answered) return answered.take_error();
  return std::move(answered->result.report);
}

Expected<CheckpointSection> section(worker::WorkerPool& pool, const SheetInput& input, const grade::CheckpointFiles& c) {
  CheckpointSection s;
  s.checkpoint = c.checkpoint;
  if (!c.pair) {
    s.report.checkpoint = c.checkpoint;
    s.report.messages = {"not in the submission: no " + *c.homework_stem + "_vert.js and " + *c.homework_stem + "_frag.js in one folder"};
    return s;
  }
  const auto request = request_for(input, c.pair->first, c.pair->second);
  auto report = graded(pool, c.checkpoint, request);
  if (!report) return report.take_error();
  s.report = std::move(*report);
  auto png = grid(pool, request);
  if (!png) return png.take_error();
  s.grid_png = std::move(*png);
  for (const auto& path : {c.pair->first, c.pair->second})
    s.code.push_back({path.string(), text_of(input, path), lines_pointed_at(s.report, path.string())});
  return s;
}

// A scene rendered by a worker; what the scene itself gets wrong is its section's error.
Expected<SceneSection> scene_section(worker::WorkerPool& pool, SceneInput input) {
  SceneSection s;
  s.name = input.name;
  auto description = scene::parse_scene(input.scene);
  if (!description) {
    s.error = description.error().message;
    return s;
  }
  s.width = description->render.width;
  s.height = description->render.height;
  s.lens_mm = description->camera.lens_mm;
  for (const auto& o : description->objects) s.materials.emplace_back(o.name, o.material);
  auto rendered = worker::run<worker::SceneResult>(pool, worker::to_message(worker::SceneJob{*description, std::move(input.meshes)}));
  if (!rendered) {
    const auto& e = rendered.error();
    if (info(e.code).status >= 500) return e;  // the service's failure, not the scene's
    s.error = e.message;
    return s;
  }
  s.png = std::move(rendered->result.png);
  s.framing = std::move(rendered->result.report.framing);
  return s;
}

}  // namespace

// Every section's jobs are in the pool at once (its workers take them in parallel); the sections
// are collected in the sheet's order, so the result does not depend on which finishes first.
Expected<Sheet> assemble(worker::WorkerPool& pool, SheetInput input) {
  Sheet sheet;
  sheet.title = input.title;
  sheet.answers = input.answers;
  std::vector<fs::path> paths;
  for (const auto& f : input.files) paths.push_back(f.path);
  grade::sort_submission(paths);
  std::vector<std::future<Expected<CheckpointSection>>> checkpoints;
  for (const auto& c : grade::plan_checkpoints(paths))
    checkpoints.push_back(std::async(std::launch::async, [&pool, &input, c] { return section(pool, input, c); }));
  std::vector<std::future<Expected<SceneSection>>> scenes;
  for (auto& scene : input.scenes)
    scenes.push_back(std::async(std::launch::async, [&pool, s = std::move(scene)]() mutable { return scene_section(pool, std::move(s)); }));
  std::optional<Error> failed;
  for (auto& f : checkpoints) {
    auto s = f.get();
    if (s) sheet.checkpoints.push_back(std::move(*s));
    else if (!failed) failed = s.error();
  }
  for (auto& f : scenes) {
    auto s = f.get();
    if (s) sheet.scenes.push_back(std::move(*s));
    else if (!failed) failed = s.error();
  }
  if (failed) return *failed;
  return sheet;
}

}  // namespace shadelab::sheet
