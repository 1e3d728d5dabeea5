#include "sheet/assemble.h"

#include <algorithm>
#include <cstdio>
#include <future>
#include <optional>

#include "course/submission_files.h"
#include "road/deliverable_score.h"
#include "road/code_grid.h"
#include "road/hand_in_checks.h"
#include "image/png_info.h"
#include "render/render_request.h"
#include "sheet/notebook.h"
#include "sheet/notebook_reading.h"
#include "sheet/saved_grid.h"
#include "scene/scene_description.h"
#include "road/code_request.h"
#include "road/submission.h"
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

// The course's render job with the student's pair: the grid their code draws.
road::GridJob render_job_for(const course::Course& course, const SheetInput& input, const fs::path& vert, const fs::path& frag) {
  return road::course_grid_job(course, {vert.filename().string(), text_of(input, vert)}, {frag.filename().string(), text_of(input, frag)});
}

// The code's grade by the grading road, as Gradescope's: the checkpoint's points, the course's mesh.
Expected<grade::Report> graded(worker::WorkerPool& pool, const course::Course& course, const course::Checkpoint& checkpoint, const SheetInput& input,
                               const std::pair<fs::path, fs::path>& pair, const grade::ReferenceStorePlaces& reference_store) {
  road::CodeRequest request;
  request.code = road::ShaderPair{{pair.first.filename().string(), text_of(input, pair.first)},
                                  {pair.second.filename().string(), text_of(input, pair.second)}};
  request.reference = checkpoint.name;
  auto built = road::code_submission(course, std::move(request), course::Viewer{}, {});
  if (!built) return built.take_error();
  built->submission.spec.reference_store = reference_store;
  auto answered = road::grade_code(pool, std::move(built->submission));
  if (!answered) return answered.take_error();
  return std::move(answered->result.report);
}

// The file `input` holds at `name` (a file name, or a path ending in it), the shallowest first.
const SubmittedFile* image_named(const SheetInput& input, const std::string& name) {
  std::vector<fs::path> paths;
  for (const auto& f : input.images) paths.push_back(f.path);
  const fs::path* found = course::file_at(paths, name);
  return found ? &input.images[static_cast<size_t>(found - paths.data())] : nullptr;
}

// A checkpoint without code: the frames the student saved under its prefix, when they did.
CheckpointSection from_saved_frames(const course::Course& course, const course::Checkpoint& checkpoint, const SheetInput& input) {
  CheckpointSection s{checkpoint.name, checkpoint.title};
  s.report.checkpoint = checkpoint.name;
  s.report.max_score = checkpoint.points;
  std::vector<std::pair<std::string, std::string>> frames;
  for (int k = 0; k < course.frames; ++k)
    if (const SubmittedFile* f = image_named(input, course.frame_file(checkpoint.prefix, k, "png"))) frames.emplace_back(f->path.string(), f->text);
  const std::string first = course.frame_file(checkpoint.prefix, 0, "png");
  if (frames.empty()) {
    s.report.messages = {"not in the submission: no " + course::wanted_files(course, checkpoint) + " in one folder, and no saved frames (" +
                         first + ", ...)"};
    return s;
  }
  auto grid_png = saved_frames_grid(frames);
  if (!grid_png) {
    s.report.messages = {"the saved frames cannot be shown: " + grid_png.error().message};
    return s;
  }
  s.grid_png = std::move(*grid_png);
  s.grid_caption = "the frames the student saved";
  s.report.messages = {"handed in as images: " + std::to_string(frames.size()) + " of " + std::to_string(course.frames) +
                       " saved frames (" + first + ", ...); no code to grade"};
  return s;
}

// The deliverable's saved frames graded at their lags by the grading road, with the code when the
// section has some (`pair`), and shown beside the code's grid; nothing when none were saved.
Status add_saved_frames(worker::WorkerPool& pool, const course::Course& course, const SheetInput& input, const course::Checkpoint& checkpoint,
                        const std::optional<std::pair<fs::path, fs::path>>& pair, const grade::ReferenceStorePlaces& reference_store, CheckpointSection& s) {
  road::FramesSubmission submission;
  std::vector<std::pair<std::string, std::string>> shown;
  for (int k = 0; k < course.frames; ++k) {
    const std::string name = course.frame_file(checkpoint.prefix, k, "png");
    if (const SubmittedFile* f = image_named(input, name)) {
      submission.saved.push_back({name, f->text});
      shown.emplace_back(f->path.string(), f->text);
    } else {
      submission.missing.push_back(name);
    }
  }
  if (submission.saved.empty()) return Ok{};
  if (pair) {
    if (auto grid_png = saved_frames_grid(shown)) s.saved_grid_png = std::move(*grid_png);
    submission.code = std::pair{shader::ShaderFile{pair->first.filename().string(), text_of(input, pair->first)},
                                shader::ShaderFile{pair->second.filename().string(), text_of(input, pair->second)}};
  }
  // The sheet shows no heat map.
  auto graded = road::grade_saved_frames(pool, course, checkpoint, std::move(submission), {course.default_mesh, checkpoint.points, reference_store, grade::HeatMap::never});
  if (!graded) return graded.take_error();
  s.frames_report = std::move(graded->result.frames);
  s.match_report = std::move(graded->result.code);
  return Ok{};
}

// A deliverable with code: its grade, the grid it renders and its listings.
Expected<CheckpointSection> code_section(worker::WorkerPool& pool, const course::Course& course, const SheetInput& input,
                                         const course::Checkpoint& checkpoint, const std::pair<fs::path, fs::path>& pair,
                                         const grade::ReferenceStorePlaces& reference_store) {
  CheckpointSection s{checkpoint.name, checkpoint.title};
  s.graded = true;
  auto report = graded(pool, course, checkpoint, input, pair, reference_store);
  if (!report) return report.take_error();
  s.report = std::move(*report);
  auto png = road::render_grid(pool, render_job_for(course, input, pair.first, pair.second));
  if (!png) return png.take_error();
  s.grid_png = std::move(*png);
  s.grid_caption = "rendered from the student's code";
  for (const auto& path : {pair.first, pair.second})
    s.code.push_back({path.string(), text_of(input, path), lines_pointed_at(s.report, path.string())});
  return s;
}

Expected<CheckpointSection> section(worker::WorkerPool& pool, const course::Course& course, const SheetInput& input,
                                    const course::Checkpoint& checkpoint, const std::optional<course::CheckpointFiles>& c,
                                    const grade::ReferenceStorePlaces& reference_store) {
  const std::optional<std::pair<fs::path, fs::path>> pair = c ? c->pair : std::nullopt;
  Expected<CheckpointSection> s = pair ? code_section(pool, course, input, checkpoint, *pair, reference_store)
                                       : Expected<CheckpointSection>(from_saved_frames(course, checkpoint, input));
  if (!s) return s;
  if (auto added = add_saved_frames(pool, course, input, checkpoint, pair, reference_store, *s); !added) return added.take_error();
  s->score = road::score_deliverable(checkpoint, checkpoint.points,
                                      {s->graded ? &s->report : nullptr, s->frames_report ? &*s->frames_report : nullptr,
                                       s->match_report ? &*s->match_report : nullptr});
  return s;
}

// The course's hand-in images, each found in the submission or said to be missing.
std::vector<ImageSection> images(const course::Course& course, const SheetInput& input) {
  std::vector<ImageSection> out;
  for (const auto& wanted : course.images) {
    ImageSection s{wanted.title, wanted.file, {}, {}};
    const SubmittedFile* f = image_named(input, wanted.file);
    const auto info = f ? image::png_info(f->text) : std::nullopt;
    if (!f) s.problem = "not in the submission";
    else if (!info) s.problem = f->path.string() + " is not a PNG file";
    else if (info->width > course::kMaxHandInSide || info->height > course::kMaxHandInSide) s.problem = f->path.string() + " is larger than 8192 pixels a side";
    else s.png = f->text;
    out.push_back(std::move(s));
  }
  return out;
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

std::string rgb_words(const std::array<double, 3>& c) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f)", c[0], c[1], c[2]);
  return buf;
}

// The shaders that draw an answer's colours: `preset`'s, where the sheet's reader may see it;
// else the student's own code for the deliverable `preset` is the reference of, when handed in.
std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>> colour_shaders(const course::Course& course, const SheetInput& input,
                                                                                  const std::string& preset) {
  const course::Preset* p = course.preset(preset);
  if (!p) return std::nullopt;
  if (course::may_see(input.viewer, *p)) return std::pair{p->vertex, p->fragment};
  std::vector<fs::path> paths;
  for (const auto& f : input.files) paths.push_back(f.path);
  course::sort_submission(paths);
  for (const auto& planned : course::plan_checkpoints(course, paths)) {
    auto found = course.checkpoint(planned.checkpoint);
    if (found && found->checkpoint->reference == preset && planned.pair)
      return std::pair{shader::ShaderFile{planned.pair->first.filename().string(), text_of(input, planned.pair->first)},
                       shader::ShaderFile{planned.pair->second.filename().string(), text_of(input, planned.pair->second)}};
  }
  return std::nullopt;
}

// The course's page drawing its default mesh with `shaders` in the colours an answer gives.
Expected<std::string> colours_render(worker::WorkerPool& pool, const course::Course& course,
                                     const std::pair<shader::ShaderFile, shader::ShaderFile>& shaders, const AnswerColours& colours) {
  road::GridJob job = road::course_grid_job(course, shaders.first, shaders.second);
  job.job.request.frames = 1;
  for (const auto& [role, rgb] : {std::pair{course::UniformRole::ambient, colours.ambient},
                                  {course::UniformRole::diffuse, colours.diffuse},
                                  {course::UniformRole::specular, colours.specular}})
    if (const course::PageUniform* u = course.uniform_with_role(role))
      for (const auto& name : u->names) job.job.request.uniforms.push_back({name, {rgb[0], rgb[1], rgb[2], 1.0}});
  return road::render_grid(pool, std::move(job));
}

// Each question with the cells under it in the student's notebook; the colours a question asks
// for rendered beside the answer.
Status add_answers(worker::WorkerPool& pool, const course::Course& course, const SheetInput& input, Sheet& sheet) {
  if (input.notebook.empty()) return Ok{};
  auto reading = read_notebook(input.notebook, course);
  if (!reading) {
    sheet.notebook_problem = reading.error().message;
    return Ok{};
  }
  sheet.notebook_note = reading->note;
  for (size_t i = 0; i < course.questions.size(); ++i) {
    const course::Question& q = course.questions[i];
    const NotebookAnswer& read = reading->answers[i];
    AnswerSection a{read.question, read.text, words_for(read.found, course.notebook_name()), {}, {}};
    if (!q.render_colours.empty() && !a.answer.empty()) {
      const auto shaders = colour_shaders(course, input, q.render_colours);
      if (const auto colours = colours_in(a.answer); colours && shaders) {
        auto png = colours_render(pool, course, *shaders, *colours);
        if (!png) return png.take_error();
        a.render_png = std::move(*png);
        a.render_caption = std::string(course::may_see(input.viewer, *course.preset(q.render_colours)) ? "the bunny" : "your shaders' bunny") +
                           " in your colours: ambient " + rgb_words(colours->ambient) + ", diffuse " + rgb_words(colours->diffuse) +
                           ", specular " + rgb_words(colours->specular);
      } else if (colours) {
        a.render_caption = "not rendered: the course's " + q.render_colours + " reference is for its staff, and the submission has no " +
                           q.render_colours + " shaders of its own to draw your colours with";
      } else {
        a.render_caption = "no ambient, diffuse and specular RGB values found in the answer to render";
      }
    }
    sheet.answered.push_back(std::move(a));
  }
  return Ok{};
}

// Every section's jobs are in the pool at once (its workers take them in parallel); the sections
// are collected in the sheet's order, so the result does not depend on which finishes first.
Expected<Sheet> assemble(worker::WorkerPool& pool, const course::Course& course, SheetInput input, const grade::ReferenceStorePlaces& reference_store) {
  Sheet sheet;
  sheet.title = input.title.empty() ? course.hand_in_name() : input.title;
  sheet.notebook_name = course.notebook_name();
  sheet.answers = input.answers;
  sheet.questions = quoted_questions(course);
  sheet.images = images(course, input);
  auto checks = std::async(std::launch::async, [&pool, &course, &input] {
    return road::check_hand_in_images(pool, course, [&input](const std::string& file) -> const std::string* {
      const SubmittedFile* f = image_named(input, file);
      return f ? &f->text : nullptr;
    });
  });
  std::vector<fs::path> paths;
  for (const auto& f : input.files) paths.push_back(f.path);
  course::sort_submission(paths);
  const auto plan = course::plan_checkpoints(course, paths);
  std::vector<std::future<Expected<CheckpointSection>>> checkpoints;
  for (const auto& checkpoint : course.checkpoints) {
    std::optional<course::CheckpointFiles> files;
    for (const auto& p : plan)
      if (p.checkpoint == checkpoint.name) files = p;
    checkpoints.push_back(std::async(std::launch::async, [&pool, &course, &input, &checkpoint, files, &reference_store] {
      return section(pool, course, input, checkpoint, files, reference_store);
    }));
  }
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
  auto checked = checks.get();
  if (!checked && !failed) failed = checked.error();
  if (failed) return *failed;
  for (auto& check : *checked)
    for (auto& image : sheet.images)
      if (image.file == check.file) image.check = std::move(check);
  if (auto s = add_answers(pool, course, input, sheet); !s) return s.take_error();
  return sheet;
}

}  // namespace shadelab::sheet
