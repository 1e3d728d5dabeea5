#include "worker/worker_main.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <list>
#include <map>
#include <optional>

#include <OpenImageIO/strutil.h>

#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "image/metrics.h"
#include "grade/report.h"
#include "render/renderer.h"
#include "worker/job.h"
#include "worker/protocol.h"
#include "worker/scene_job.h"
#include "scene/scene_mesh.h"
#include "scene_render/scene_renderer.h"
#include "worker/zip_archive.h"

namespace shadelab::worker {

namespace {

using nlohmann::json;

json describe(const std::vector<render::VariableInfo>& vars) {
  json out = json::array();
  for (const auto& v : vars) out.push_back({{"name", v.name}, {"type", v.type}, {"arraySize", v.array_size}});
  return out;
}

json timings(const render::PhaseTimes& t) {
  return {{"compile", t.compile_ms}, {"upload", t.upload_ms}, {"firstFrame", t.first_frame_ms},
          {"render", t.render_ms},   {"readback", t.readback_ms}, {"encode", t.sink_ms}};
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  return OIIO::Strutil::base64_encode({reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

// A frame that is one colour throughout: the most common "my render is blank" complaint.
std::optional<std::array<int, 4>> constant_colour(const image::Image& f) {
  if (f.type != image::PixelType::u8 || f.bytes.size() < 4) return std::nullopt;
  for (size_t i = 4; i < f.bytes.size(); i += 4)
    if (std::memcmp(&f.bytes[i], &f.bytes[0], 4) != 0) return std::nullopt;
  return std::array<int, 4>{f.bytes[0], f.bytes[1], f.bytes[2], f.bytes[3]};
}

class Worker {
 public:
  Worker(int fd, render::Renderer renderer) : fd_(fd), renderer_(std::move(renderer)) {}

  void serve() {
    while (true) {
      Message in;
      const auto status = read_message(fd_, in, std::chrono::steady_clock::now() + std::chrono::hours(24 * 365));
      if (status == ReadStatus::closed) return;
      if (status != ReadStatus::ok) continue;
      Message out = handle(in);
      out.header["event"] = "result";
      if (!write_message(fd_, out)) return;
    }
  }

 private:
  Message failure(const Error& e) { return {{{"ok", false}, {"error", to_json(e)}}, {}}; }

  Expected<const scene::Mesh*> mesh(const Job& job, const std::string& payload) {
    if (auto it = meshes_.find(job.mesh); it != meshes_.end()) return &it->second;
    Expected<scene::Mesh> loaded = payload.empty()
                                       ? scene::builtin_mesh(job.mesh)
                                       : scene::load_mesh({reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size()},
                                                          job.mesh_format, job.mesh);
    if (!loaded) return loaded.take_error();
    if (meshes_.size() >= 16) meshes_.erase(meshes_.begin());
    return &meshes_.emplace(job.mesh, std::move(*loaded)).first->second;
  }

  // The job's mesh, fitted to the homework framing when it asks for that.
  Expected<const scene::Mesh*> job_mesh(const Job& job, const std::string& payload) {
    auto m = mesh(job, payload);
    if (!m || !job.fit) return m;
    fitted_ = **m;
    scene::fit_to_homework(fitted_);
    return &fitted_;
  }

  // Tells the server the compile is over: from here a hang or a crash is the render's.
  bool enter_render_phase() { return write_message(fd_, {{{"event", "phase"}, {"phase", "render"}}, {}}); }

  // Scenes run our own shaders, not a student's: straight to the render phase and its deadline.
  Message scene(const Message& in) {
    if (!enter_render_phase()) return failure(make_error(ErrorCode::io_error, "lost the server"));
    auto job = scene_job_from_message(in);
    if (!job) return failure(job.error());
    auto description = scene::parse_scene(job->scene);
    if (!description) return failure(description.error());
    if (!scene_renderer_) {
      auto created = scene_render::SceneRenderer::create();
      if (!created) return failure(created.error());
      scene_renderer_.emplace(std::move(*created));
    }
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
    auto rendered = scene_renderer_->render(*description, resolve);
    if (!rendered) return failure(rendered.error());
    const auto encode_start = std::chrono::steady_clock::now();
    auto png = image::encode_png(rendered->image);
    if (!png) return failure(png.error());
    const double encode_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - encode_start).count();
    return {{{"ok", true},
             {"report", rendered->report.to_json(*description)},
             {"contentType", "image/png"},
             {"timings", {{"render", rendered->report.total_ms}, {"encode", encode_ms}}}},
            std::string(png->begin(), png->end())};
  }

  Message handle(const Message& in) {
    if (is_scene_message(in)) return scene(in);
    auto parsed = job_from_json(in.header);
    if (!parsed) return failure(parsed.error());
    Job& job = *parsed;

    if (job.kind == JobKind::mesh_check) {
      auto m = mesh(job, in.payload);
      if (!m) return failure(m.error());
      const auto b = scene::bounds(**m);
      return {{{"ok", true},
               {"triangles", (*m)->triangle_count()},
               {"normalsFromFile", (*m)->normals_from_file},
               {"bounds", {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}}}},
              {}};
    }

    if (job.kind == JobKind::grade) return grade(job, in.payload);

    auto compiled = renderer_.compile(job.request.vertex, job.request.fragment);
    if (!compiled) return failure(compiled.error());
    json diagnostics = json::array();
    for (const auto& d : compiled->diagnostics) diagnostics.push_back(to_json(d));
    if (job.kind == JobKind::compile)
      return {{{"ok", true},
               {"warnings", compiled->warnings},
               {"diagnostics", diagnostics},
               {"attributes", describe(compiled->attributes)},
               {"uniforms", describe(compiled->uniforms)},
               {"timings", {{"compile", compiled->compile_ms}}}},
              {}};

    if (!enter_render_phase()) return failure(make_error(ErrorCode::io_error, "lost the server"));
    return render(job, in.payload, diagnostics, compiled->compile_ms);
  }

  Message render(Job& job, const std::string& payload, const json& diagnostics, double compile_ms) {
    auto m = job_mesh(job, payload);
    if (!m) return failure(m.error());
    const scene::Mesh& mesh_ref = **m;
    const auto& r = job.request;
    const auto layout = image::GridLayout::for_frames(r.frames, r.width, r.height);
    const bool png = job.format == Format::png;
    const bool overlapped_grid = job.output == Output::grid && png;

    std::optional<image::GridPngEncoder> grid_png;
    if (overlapped_grid) grid_png.emplace(layout, r.frames);
    std::vector<image::Image> frames;
    json constant = json::array();
    auto report = renderer_.render(r, mesh_ref, [&](int k, const image::Image& f, bool opaque) {
      if (grid_png) grid_png->add_frame(k, f, opaque);
      else frames.push_back(f);
      if (auto c = constant_colour(f)) constant.push_back({{"frame", k}, {"rgba", *c}});
    });
    if (!report) return failure(report.error());

    json header = {{"ok", true},
                   {"warnings", report->warnings},
                   {"diagnostics", diagnostics},
                   {"samples", report->samples},
                   {"constantFrames", constant},
                   {"attributes", describe(report->attributes)},
                   {"uniforms", describe(report->uniforms)}};
    const auto encode_start = std::chrono::steady_clock::now();
    const auto encode = [&](const image::Image& img) { return png ? image::encode_png(img) : image::encode_exr(img); };
    const auto name = [&](int k) { return "hw2_" + job.prefix + "_" + std::to_string(k) + (png ? ".png" : ".exr"); };
    Message out;
    if (job.output == Output::grid) {
      auto bytes = grid_png ? grid_png->finish() : encode(image::compose_grid(layout, frames));
      if (!bytes) return failure(bytes.error());
      out.payload.assign(bytes->begin(), bytes->end());
      header["contentType"] = png ? "image/png" : "image/x-exr";
    } else if (job.output == Output::frames) {
      std::vector<std::pair<std::string, std::vector<std::uint8_t>>> files;
      for (size_t k = 0; k < frames.size(); ++k) {
        auto bytes = encode(frames[k]);
        if (!bytes) return failure(bytes.error());
        files.emplace_back(name(static_cast<int>(k)), std::move(*bytes));
      }
      auto zip = zip_stored(files);
      if (!zip) return failure(zip.error());
      out.payload = std::move(*zip);
      header["contentType"] = "application/zip";
    } else {
      auto grid = encode(image::compose_grid(layout, frames));
      if (!grid) return failure(grid.error());
      json images = {{"grid", base64(*grid)}, {"frames", json::array()}};
      for (size_t k = 0; k < frames.size(); ++k) {
        auto bytes = encode(frames[k]);
        if (!bytes) return failure(bytes.error());
        images["frames"].push_back({{"name", name(static_cast<int>(k))}, {"data", base64(*bytes)}});
      }
      header["images"] = std::move(images);
      header["contentType"] = "application/json";
    }
    auto t = timings(report->times);
    t["compile"] = compile_ms;  // compiled just before; the render found the program cached
    t["encode"] = report->times.sink_ms +
                  std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - encode_start).count();
    header["timings"] = t;
    out.header = std::move(header);
    return out;
  }

  using Frames = std::vector<image::Image>;

  Expected<Frames> frames_of(const render::RenderRequest& r, const scene::Mesh& m) {
    Frames out;
    auto report = renderer_.render(r, m, [&](int, const image::Image& f, bool) { out.push_back(f); });
    if (!report) return report.take_error();
    return out;
  }

  // Reference and mistake renders depend only on their shaders and the job's parameters: a batch
  // grading a class renders them once per worker.
  Expected<Frames> cached_frames(const render::RenderRequest& r, const scene::Mesh& m, const Job& job) {
    // The key is the request actually rendered (shaders, size, uniforms, ...) and the mesh.
    Job keyed;
    keyed.request = r;
    keyed.request.vertex.name = keyed.request.fragment.name = "";
    keyed.mesh = job.mesh;
    keyed.fit = job.fit;
    const std::string key = to_json(keyed).dump() + (r.pixel_type == image::PixelType::f32 ? "f32" : "u8");
    if (auto it = references_.find(key); it != references_.end()) return it->second;
    auto frames = frames_of(r, m);
    if (!frames) return frames;
    if (references_.size() > 64) references_.clear();
    return references_.emplace(key, std::move(*frames)).first->second;
  }

  Message grade(Job& job, const std::string& payload) {
    const auto& spec = job.grade;
    const auto graded = [](json result) { return Message{{{"ok", true}, {"result", std::move(result)}}, {}}; };
    auto compiled = renderer_.compile(job.request.vertex, job.request.fragment);
    if (!compiled) return graded(grade::failed_submission(compiled.error(), spec.reference_name, spec.options.max_score));
    if (!enter_render_phase()) return failure(make_error(ErrorCode::io_error, "lost the server"));

    auto m = job_mesh(job, payload);
    if (!m) return failure(m.error());
    const scene::Mesh& mesh_ref = **m;
    render::RenderRequest r = job.request;
    r.pixel_type = image::PixelType::u8;
    // Every set of frames is rendered under the homework's light, then under each probe light.
    const auto render_set = [&](const render::RenderRequest& base, bool cache) -> Expected<Frames> {
      Frames all;
      for (int p = -1; p < static_cast<int>(spec.probes.size()); ++p) {
        render::RenderRequest lit = base;
        if (p >= 0) {
          auto with = with_light(base, spec.probes[static_cast<size_t>(p)].light_position);
          if (!with) return with.take_error();
          lit = std::move(*with);
        }
        auto frames = cache ? cached_frames(lit, mesh_ref, job) : frames_of(lit, mesh_ref);
        if (!frames) return frames.take_error();
        all.insert(all.end(), std::make_move_iterator(frames->begin()), std::make_move_iterator(frames->end()));
      }
      return all;
    };
    auto student = render_set(r, false);
    if (!student) return graded(grade::failed_submission(student.error(), spec.reference_name, spec.options.max_score));
    // The canvas stores NaN as 0: render to floats as well to find it. No multisampling needed.
    render::RenderRequest as_float = r;
    as_float.pixel_type = image::PixelType::f32;
    as_float.msaa = 0;
    auto student_float = render_set(as_float, false);
    if (!student_float) return graded(grade::failed_submission(student_float.error(), spec.reference_name, spec.options.max_score));

    // The reference gets the same uniform values as the submission: a grader that changes the
    // colours grades against the reference with those colours.
    render::RenderRequest ref = r;
    ref.vertex = spec.reference_vertex;
    ref.fragment = spec.reference_fragment;
    auto reference = render_set(ref, true);
    if (!reference) return failure(make_error(ErrorCode::invalid_argument, "the reference does not render: " + reference.error().message));
    std::vector<grade::RenderedMistake> mistakes;
    for (const auto& mk : spec.mistakes) {
      render::RenderRequest mr = ref;
      mr.vertex = mk.vertex;
      mr.fragment = mk.fragment;
      auto frames = render_set(mr, true);
      if (frames) mistakes.push_back({mk.id, mk.message, std::move(*frames)});
    }
    const auto result = grade::grade(*student, *student_float, *reference, mistakes, spec.options);
    json out = grade::to_json(result, spec.reference_name);
    out["warnings"] = compiled->warnings;
    for (size_t k = 0; k < out["frames"].size(); ++k) {
      const size_t set = k / static_cast<size_t>(r.frames);
      out["frames"][k]["light"] = set == 0 ? std::string("homework") : spec.probes[set - 1].name;
    }
    Frames heat;  // the homework light's frames
    for (size_t k = 0; k < static_cast<size_t>(r.frames); ++k) heat.push_back(image::heatmap((*student)[k], (*reference)[k]));
    auto heat_png = image::encode_png(image::compose_grid(image::GridLayout::for_frames(r.frames, r.width, r.height), heat));
    if (heat_png) out["heatmap"] = base64(*heat_png);
    return graded(std::move(out));
  }

  // `base` with the light moved, for the names the program declares as the page does (vec3);
  // a name declared otherwise stays as the homework sets it, as in the browser.
  Expected<render::RenderRequest> with_light(const render::RenderRequest& base, const std::array<float, 3>& position) {
    auto program = renderer_.compile(base.vertex, base.fragment);
    if (!program) return program.take_error();
    render::RenderRequest lit = base;
    for (const char* name : {"uLightPosition", "lightPosition"}) {
      const bool declared = std::any_of(program->uniforms.begin(), program->uniforms.end(),
                                        [&](const auto& u) { return u.name == name && u.type == "vec3" && u.array_size == 1; });
      const bool set = std::any_of(lit.uniforms.begin(), lit.uniforms.end(), [&](const auto& u) { return u.name == name; });
      if (declared && !set) lit.uniforms.push_back({name, {position[0], position[1], position[2]}});
    }
    return lit;
  }

  int fd_;
  render::Renderer renderer_;
  std::map<std::string, Frames> references_;
  std::map<std::string, scene::Mesh> meshes_;
  scene::Mesh fitted_;
  std::optional<scene_render::SceneRenderer> scene_renderer_;  // made on the first scene job
};

}  // namespace

int run_worker(int fd, const egl::ContextOptions& options) {
  auto renderer = render::Renderer::create(options);
  if (!renderer) {
    write_message(fd, {{{"event", "ready"}, {"ok", false}, {"error", to_json(renderer.error())}}, {}});
    return 1;
  }
  const auto& info = renderer->context_info();
  if (!write_message(fd, {{{"event", "ready"}, {"ok", true}, {"renderer", info.gl_renderer}, {"version", info.gl_version},
                           {"software", info.software}}, {}}))
    return 1;
  Worker(fd, std::move(*renderer)).serve();
  return 0;
}

}  // namespace shadelab::worker
