#include "worker/worker_main.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <optional>

#include "core/lru_cache.h"
#include "grade/judge_code.h"
#include "grade/judge_saved_frames.h"
#include "grade/hand_in_images.h"
#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "image/png_decode.h"
#include "course/course_reader.h"
#include "render/renderer.h"
#include "scene/scene_mesh.h"
#include "scene_render/scene_renderer.h"
#include "worker/fatal_signal.h"
#include "worker/fault_injection.h"
#include "worker/job.h"
#include "worker/protocol.h"
#include "worker/result.h"
#include "worker/zip_archive.h"

namespace shadelab::worker {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::optional<ConstantFrame> constant_colour(int k, const image::Image& f) {
  if (f.type != image::PixelType::u8 || f.bytes.size() < 4) return std::nullopt;
  for (size_t i = 4; i < f.bytes.size(); i += 4)
    if (std::memcmp(&f.bytes[i], &f.bytes[0], 4) != 0) return std::nullopt;
  return ConstantFrame{k, {f.bytes[0], f.bytes[1], f.bytes[2], f.bytes[3]}};
}

std::string as_string(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

// The frames of a render as the job's output asks for them, into `out`.
Status encode_output(const Job& job, const std::vector<image::Image>& frames, std::optional<image::GridPngEncoder>& grid_png,
                     RenderResult& out) {
  const auto& r = job.request;
  const bool png = job.format == Format::png;
  const auto layout = image::GridLayout::for_frames(r.frames, r.width, r.height);
  const auto encode = [&](const image::Image& img) { return png ? image::encode_png(img) : image::encode_exr(img); };
  const auto name = [&](size_t k) { return render::frame_file_name(job.frame_name, job.prefix, static_cast<int>(k), png ? "png" : "exr"); };
  if (job.output == Output::frames) {
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> files;
    for (size_t k = 0; k < frames.size(); ++k) {
      auto bytes = encode(frames[k]);
      if (!bytes) return bytes.take_error();
      files.emplace_back(name(k), std::move(*bytes));
    }
    if (!job.notice.empty()) files.emplace_back("FOR_CHECKING_NOT_FOR_HANDING_IN.txt", std::vector<std::uint8_t>(job.notice.begin(), job.notice.end()));
    auto zip = zip_stored(files);
    if (!zip) return zip.take_error();
    out.body = std::move(*zip);
    out.content_type = "application/zip";
    return Ok{};
  }
  auto grid = grid_png ? grid_png->finish() : encode(image::compose_grid(layout, frames));
  if (!grid) return grid.take_error();
  out.body = as_string(*grid);
  out.content_type = png ? "image/png" : "image/x-exr";
  if (job.output == Output::json)
    for (size_t k = 0; k < frames.size(); ++k) {
      auto bytes = encode(frames[k]);
      if (!bytes) return bytes.take_error();
      out.frames.push_back({name(k), as_string(*bytes)});
    }
  return Ok{};
}

class Worker {
 public:
  Worker(int fd, render::Renderer renderer) : fd_(fd), renderer_(std::move(renderer)), renders_(renderer_) {}

  // The first job in a fresh process pays for what every later job finds ready: llvmpipe's
  // draw and rasteriser setup, the course's default mesh parsed and uploaded, the multisampled
  // target, the JIT of the class's shared vertex shader (~50 ms more on the 2-core machine). A
  // worker pays it here, on the built-in course's default job, so no client does.
  Status warm_up() {
    const course::Course& c = course::builtin_course();
    const course::CourseMesh& m = *c.mesh(c.default_mesh);
    auto preset = c.find_preset(c.default_preset);
    if (!preset) return preset.take_error();
    Job job;
    job.mesh = m.id;
    job.mesh_embedded = m.id;
    job.mesh_format = m.format;
    auto warm_mesh = mesh(job, {});
    if (!warm_mesh) return warm_mesh.take_error();
    // Two frames: the first JIT-compiles, the second runs as every later one does.
    render::RenderRequest request = c.render_request(preset->preset->vertex, preset->preset->fragment);
    request.frames = 2;
    auto rendered = renderer_.render(request, **warm_mesh, [](int, const image::Image&, bool) {});
    if (!rendered) return rendered.take_error();
    return Ok{};
  }

  void serve() {
    while (true) {
      Message in;
      const auto status = read_message(fd_, in, Clock::now() + std::chrono::hours(24 * 365));
      if (status == ReadStatus::closed) return;
      if (status != ReadStatus::ok) continue;
      job_kind_ = in.header.is_object() ? in.header.value("kind", std::string("?")) : "?";
      note_doing("a " + job_kind_ + " job");
      Message out = handle(in);
      note_doing("idle");
      out.header["event"] = "result";
      out.header["caches"] = caches();
      if (!write_message(fd_, out)) return;
    }
  }

 private:
  // What this worker keeps between jobs, sent with every result for the server's /metrics.
  nlohmann::json caches() const {
    const auto sizes = renderer_.cache_sizes();
    const size_t mesh_bytes = sizes.mesh_bytes + meshes_.bytes() + scene::bytes_of(fitted_);
    return {{"programs", sizes.programs}, {"meshes", sizes.meshes}, {"meshBytes", mesh_bytes},
            {"referenceBytes", renders_.reference_cache_bytes()}};
  }

  template <class Result>
  static Message answer_or_error(Expected<Result> r) { return r ? answer(*r) : answer(r.error()); }

  Message handle(const Message& in) {
    auto kind = job_kind_of(in);
    if (!kind) return answer(kind.error());
    if (*kind == JobKind::scene) return answer_or_error(scene(in));
    if (*kind == JobKind::check_images) return answer_or_error(check_images(in));
    auto job = job_from_message(in);
    if (!job) return answer(job.error());
    switch (job->kind) {
      case JobKind::mesh_check: return answer_or_error(check_mesh(*job, in.payload));
      case JobKind::compile: return answer_or_error(compile(*job));
      case JobKind::grade: return answer_or_error(grade(*job, in.payload));
      case JobKind::grade_frames: return answer_or_error(grade_frames(*job, in));
      case JobKind::render: return answer_or_error(render(*job, in.payload));
      case JobKind::scene:
      case JobKind::check_images: break;
    }
    return answer(make_error(ErrorCode::worker_protocol, "a job of an unknown kind"));
  }

  // Tells the server which phase the job is in (worker/pool.h): "render" once the compile is
  // over, "grader" once a grade's own work begins.
  Status enter_phase(JobPhase phase) {
    note_doing("a " + job_kind_ + " job, " + std::string(doing(phase)));
    if (write_message(fd_, {{{"event", "phase"}, {"phase", to_string(phase)}}, {}})) return Ok{};
    return make_error(ErrorCode::io_error, "lost the server");
  }
  Status enter_render_phase() { return enter_phase(JobPhase::render); }

  Expected<const scene::Mesh*> mesh(const Job& job, const std::string& payload) {
    if (const scene::Mesh* hit = meshes_.find(job.mesh)) return hit;
    if (payload.empty() && job.mesh_embedded.empty())
      return make_error(ErrorCode::worker_protocol, "the job names the mesh '" + job.mesh + "' but carries none of its bytes");
    Expected<scene::Mesh> loaded =
        payload.empty() ? scene::embedded_mesh(job.mesh_embedded, job.mesh)
                        : scene::load_mesh({reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size()}, job.mesh_format, job.mesh);
    if (!loaded) return loaded.take_error();
    const size_t bytes = scene::bytes_of(*loaded);
    return &meshes_.insert(job.mesh, std::move(*loaded), bytes);
  }

  // The job's mesh, fitted to the course's framing when it asks for that. The last fitted mesh is
  // kept: a class rendering one uploaded mesh fits it once (a copy and a pass over a
  // million-triangle mesh cost ~40 ms). A mesh's id names its bytes (embedded or content-addressed).
  Expected<const scene::Mesh*> job_mesh(const Job& job, const std::string& payload) {
    auto m = mesh(job, payload);
    if (!m || !job.fit) return m;
    const std::string key = fitted_key(job);
    if (fitted_of_ != key) {
      fitted_of_.clear();
      fitted_ = **m;
      scene::fit_to(fitted_, *job.fit);
      fitted_of_ = key;
    }
    return &fitted_;
  }

  // The mesh's id and, when fitted, the box it was fitted into: what its frames depend on.
  static std::string fitted_key(const Job& job) {
    if (!job.fit) return job.mesh;
    const auto& b = *job.fit;
    char box[160];
    std::snprintf(box, sizeof box, "|fit:%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z);
    return job.mesh + box;
  }

  Expected<MeshCheckResult> check_mesh(const Job& job, const std::string& payload) {
    inject_fault(fault_plan(payload), FaultPhase::mesh, fd_);  // inactive outside fault-injection runs
    auto m = mesh(job, payload);
    if (!m) return m.take_error();
    const auto b = scene::bounds(**m);
    return MeshCheckResult{(*m)->triangle_count(), (*m)->normals_from_file, {b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}};
  }

  Expected<CompileResult> compile(const Job& job) {
    auto c = renderer_.compile(job.request.vertex, job.request.fragment);
    if (!c) return c.take_error();
    return CompileResult{c->warnings, c->diagnostics, c->attributes, c->uniforms, c->compile_ms};
  }

  Expected<RenderResult> render(const Job& job, const std::string& payload) {
    const FaultPlan fault = fault_plan(job.request.fragment.text);  // inactive outside fault-injection runs
    inject_fault(fault, FaultPhase::compile, fd_);
    auto compiled = compile(job);
    if (!compiled) return compiled.take_error();
    if (auto s = enter_render_phase(); !s) return s.take_error();
    inject_fault(fault, FaultPhase::render, fd_);
    auto m = job_mesh(job, payload);
    if (!m) return m.take_error();
    const auto& r = job.request;
    std::optional<image::GridPngEncoder> grid_png;  // encodes the grid while the next frames render
    if (job.output == Output::grid && job.format == Format::png) grid_png.emplace(image::GridLayout::for_frames(r.frames, r.width, r.height), r.frames);
    std::vector<image::Image> frames;
    RenderResult out;
    auto report = renderer_.render(r, **m, [&](int k, const image::Image& f, bool opaque) {
      if (k == 0) inject_fault(fault, FaultPhase::readback, fd_);
      if (grid_png) grid_png->add_frame(k, f, opaque);
      else frames.push_back(f);
      if (auto c = constant_colour(k, f)) out.constant_frames.push_back(*c);
    });
    if (!report) return report.take_error();
    inject_fault(fault, FaultPhase::encode, fd_);
    const auto encode_start = Clock::now();
    if (auto s = encode_output(job, frames, grid_png, out); !s) return s.take_error();
    out.warnings = report->warnings;
    out.diagnostics = compiled->diagnostics;
    out.attributes = report->attributes;
    out.uniforms = report->uniforms;
    out.samples = report->samples;
    const auto& t = report->times;
    // Compiled just before: the render found the program cached, so the compile time is that one.
    out.timings = {compiled->compile_ms, t.upload_ms, t.first_frame_ms, t.render_ms, t.readback_ms, t.sink_ms + ms_since(encode_start)};
    return out;
  }

  Expected<GradeResult> grade(const Job& job, const std::string& payload) {
    const FaultPlan fault = fault_plan(job.request.fragment.text);  // inactive outside fault-injection runs
    auto graded = grade::judge_code(renders_, job.grade, job.request, [&] { return job_mesh(job, payload); }, fitted_key(job), [&](JobPhase phase) {
      auto entered = enter_phase(phase);
      if (phase == JobPhase::grader) inject_fault(fault, FaultPhase::grader, fd_);
      return entered;
    });
    if (!graded) return graded.take_error();
    return GradeResult{std::move(graded->report), std::move(graded->heatmap_png), std::move(graded->values)};
  }

  Expected<FramesGradeResult> grade_frames(const Job& job, const Message& in) {
    auto payload = frames_payload_from(in);
    if (!payload) return payload.take_error();
    auto graded = grade::judge_saved_frames(renders_, job.grade, job.request, payload->saved, [&] { return job_mesh(job, payload->mesh); },
                                        fitted_key(job), [&](JobPhase phase) { return enter_phase(phase); });
    if (!graded) return graded.take_error();
    return FramesGradeResult{std::move(graded->frames), std::move(graded->code), std::move(graded->heatmap_png)};
  }

  Status make_scene_renderer() {
    if (scene_renderer_) return Ok{};
    auto created = scene_render::SceneRenderer::create();
    if (!created) return created.take_error();
    scene_renderer_.emplace(std::move(*created));
    return Ok{};
  }

  // Scenes run our own shaders, not a student's: straight to the render phase and its deadline.
  Expected<SceneResult> scene(const Message& in) {
    if (auto s = enter_render_phase(); !s) return s.take_error();
    auto job = scene_job_from_message(in);
    if (!job) return job.take_error();
    if (auto s = make_scene_renderer(); !s) return s.take_error();
    const auto& uploads = job->meshes;
    const auto resolve = [&uploads](const std::string& reference) -> Expected<scene::Mesh> {
      for (const auto& m : uploads)
        if (m.reference == reference) {
          auto mesh = scene::load_mesh({reinterpret_cast<const std::uint8_t*>(m.bytes.data()), m.bytes.size()}, m.format, reference);
          if (mesh) scene::to_scene_space(*mesh, m.format);
          return mesh;
        }
      return scene::builtin_scene_mesh(reference);
    };
    auto rendered = scene_renderer_->render(job->scene, resolve);
    if (!rendered) return rendered.take_error();
    const auto encode_start = Clock::now();
    auto png = image::encode_png(rendered->image);
    if (!png) return png.take_error();
    return SceneResult{std::move(rendered->report), ms_since(encode_start), as_string(*png)};
  }

  // The student's images judged as the course asks (grade/hand_in_images.h): the worker decodes
  // them (a stranger's PNG) and draws the views the judgement asks for.
  Expected<ImagesResult> check_images(const Message& in) {
    if (auto s = enter_render_phase(); !s) return s.take_error();
    auto job = images_job_from_message(in);
    if (!job) return job.take_error();
    const auto render = [&](const scene::SceneDescription& scene) -> Expected<image::Image> {
      if (auto s = make_scene_renderer(); !s) return s.take_error();
      auto rendered = scene_renderer_->render(scene, scene_render::resolve_builtin_mesh);
      if (!rendered) return rendered.take_error();
      return std::move(rendered->image);
    };
    auto verdicts = grade::judge_hand_in_images(std::move(job->images), course::kMaxHandInSide, render);
    if (!verdicts) return verdicts.take_error();
    return ImagesResult{std::move(*verdicts)};
  }

  int fd_;
  render::Renderer renderer_;
  grade::GradeRenders renders_;  // a grade's renders and the caches every grade shares
  // Parsed meshes by id (a built-in's name or an upload's content address). An upload of 16 MiB
  // parses to up to ~1M triangles, 72 MB: the budget keeps five of those, or the class's few.
  LruCache<scene::Mesh> meshes_{16, 384u << 20};
  scene::Mesh fitted_;
  std::string fitted_of_;  // fitted_key() of the job fitted_ was made for; empty: none
  std::string job_kind_;  // the job being served, for the fatal-signal report
  std::optional<scene_render::SceneRenderer> scene_renderer_;  // made on the first scene job
};

}  // namespace

int run_worker(int fd, const egl::ContextOptions& options, WarmUp warm_up) {
  report_fatal_signals();
  note_doing("starting");
  auto renderer = render::Renderer::create(options);
  if (!renderer) {
    Message failed = answer(renderer.error());
    failed.header["event"] = "ready";
    write_message(fd, failed);
    return 1;
  }
  const auto info = renderer->context_info();
  Worker worker(fd, std::move(*renderer));
  if (warm_up == WarmUp::before_ready) {
    if (auto warmed = worker.warm_up(); !warmed) {
      Message failed = answer(warmed.error());
      failed.header["event"] = "ready";
      write_message(fd, failed);
      return 1;
    }
  }
  inject_fault(start_fault_plan(), FaultPhase::start, fd);  // inactive outside fault-injection runs
  if (!write_message(fd, {{{"event", "ready"}, {"ok", true}, {"renderer", info.gl_renderer}, {"version", info.gl_version},
                           {"software", info.software}}, {}})) {
    std::cerr << "shadelab worker: its ready message could not be sent (" << std::strerror(errno) << ")\n";  // the operator's only clue
    return 1;
  }
  // A replacement's warm-up: a failure here is the first job's to report, as it would be cold.
  if (warm_up == WarmUp::after_ready) (void)worker.warm_up();
  worker.serve();
  return 0;
}

}  // namespace shadelab::worker
