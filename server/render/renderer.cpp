#include "render/renderer.h"

#include "core/hash.h"
#include "core/lru_cache.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <iostream>
#include <optional>

#include <glm/gtc/type_ptr.hpp>

#include "gl/mesh_buffer.h"
#include "gl/program.h"
#include "gl/render_target.h"
#include "image/canvas_readback.h"
#include "render/homework_contract.h"
#include "shader/driver_log.h"
#include "shader/invariant_outputs.h"
#include "shader/uniform_variants.h"
#include "shader/webgl_rules.h"

namespace shadelab::render {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

constexpr gl::AttributeBinding kBindings[] = {{kPositionAttribute, kPositionLocation}, {kNormalAttribute, kNormalLocation}};
constexpr size_t kProgramCacheSize = 32;
constexpr size_t kMeshCacheSize = 8;
// Vertex and index buffers kept between jobs (system memory on llvmpipe): a million-triangle
// closed mesh takes ~24 MB, the same triangles with no shared corners ~84 MB.
constexpr size_t kMeshCacheBytes = 256u << 20;

std::vector<VariableInfo> describe(const std::vector<gl::ActiveVariable>& vars) {
  std::vector<VariableInfo> out;
  for (const auto& v : vars) out.push_back({v.name, std::string(v.type.name), v.array_size});
  return out;
}

// What a set of requests for Renderer::render_together differ in.
struct Variants {
  enum class Kind {
    identical,  // nothing: one render stands for all
    uniforms,   // the values of some vec3 or vec4 uniforms: one pass can render all (shader/uniform_variants.h)
    apart,      // anything else: a render each
  } kind = Kind::apart;
  std::vector<std::string> names;          // the vec3 and vec4 uniforms
  std::vector<size_t> components;          // each name's: 3 or 4
  std::vector<std::vector<float>> values;  // per request: each name's floats, in order
};

using IndexedSink = Renderer::IndexedSink;

// A clip-space shift that moves the frame by (0.5, 0.5) - `at` pixels: the rasteriser's one sample,
// at each pixel's centre, then sees what a sample at `at` would.
glm::mat4 sampling_at(const std::array<double, 2>& at, int width, int height) {
  glm::mat4 shift(1.0f);
  shift[3][0] = static_cast<float>(2.0 * (0.5 - at[0]) / width);
  shift[3][1] = static_cast<float>(2.0 * (0.5 - at[1]) / height);
  return shift;
}

}  // namespace

struct Renderer::State {
  egl::HeadlessContext context;
  LruCache<gl::Program> programs{kProgramCacheSize, SIZE_MAX};  // by vertex GLSL + '\0' + fragment GLSL; count only
  LruCache<gl::MeshBuffer> meshes{kMeshCacheSize, kMeshCacheBytes};  // by scene::content_address()
  // Two targets, so frame k is read back while the driver renders frame k + 1.
  std::array<std::optional<gl::RenderTarget>, 2> targets;
  gl::Readback readback = context.info().software ? gl::Readback::direct : gl::Readback::pixel_buffer;
  std::vector<std::uint8_t> staging;

  // Unwraps both stages and builds (or finds) the program; errors carry located diagnostics.
  struct Built {
    gl::Program* program;
    shader::UnwrappedSource vertex, fragment;
    std::vector<Diagnostic> webgl_warnings;  // the browser's own, which the driver does not give
    std::vector<shader::StandIn> renamed;    // for the driver: its words get the student's names back
    bool cached;
    bool rewritten = false;  // by shader/uniform_variants.h: its runs' colours, then their census
    shader::VariantOutputs outputs{1, 0};
  };
  // With `variants`, one run for each of their requests; with `census`, the flags of every run.
  Expected<Built> build(const shader::ShaderFile& vf, const shader::ShaderFile& ff,
                        FloatSemantics semantics = FloatSemantics::as_compiled, const Variants* variants = nullptr, bool census = false) {
    const shader::SourceLimits limits{kRendererHardLimits.max_source_bytes};
    auto vertex = shader::unwrap(vf, shader::Stage::vertex, limits);
    if (!vertex) return vertex.take_error();
    auto fragment = shader::unwrap(ff, shader::Stage::fragment, limits);
    if (!fragment) return fragment.take_error();
    if (auto same = shader::check_same_version(*vertex, *fragment, ff); !same) return same.take_error();
    auto webgl = shader::apply_webgl_rules(*vertex, *fragment, vf, ff);
    if (!webgl) return webgl.take_error();
    const int runs = variants ? static_cast<int>(variants->values.size()) : 1;
    const bool rewritten = variants || census;
    if (rewritten) {  // same lines, and the new main after them
      auto glsl = shader::with_uniform_variants(*vertex, *fragment, variants ? variants->names : std::vector<std::string>{}, runs,
                                                gl::max_outputs(), census);
      if (!glsl) return glsl.take_error();
      fragment->glsl = std::move(*glsl);
    }
    const shader::VariantOutputs outputs = rewritten ? shader::variant_outputs(runs, census) : shader::VariantOutputs{1, 0};
    if (semantics == FloatSemantics::ieee) {  // same lines, so the line maps still hold
      vertex->glsl = shader::with_invariant_outputs(vertex->glsl, shader::Stage::vertex);
      fragment->glsl = shader::with_invariant_outputs(fragment->glsl, shader::Stage::fragment);
    }
    std::string key = vertex->glsl + '\0' + fragment->glsl;
    if (gl::Program* hit = programs.find(key))
      return Built{hit, std::move(*vertex), std::move(*fragment), std::move(webgl->warnings), std::move(webgl->renamed), true, rewritten,
                   outputs};

    std::optional<gl::BuildFailure> failure;
    gl::Program program = gl::Program::build(vertex->glsl, fragment->glsl, kBindings, failure);
    if (failure) return build_error(*failure, vf, ff, *vertex, *fragment, webgl->renamed);
    gl::Program& kept = programs.insert(std::move(key), std::move(program), 0);
    return Built{&kept, std::move(*vertex), std::move(*fragment), std::move(webgl->warnings), std::move(webgl->renamed), false, rewritten,
                 outputs};
  }

  // The front end accepted the pair, as the browser would: a driver that refuses it is this
  // server's limit, never the student's error. The driver's words stay for the staff and the
  // operator's log (stderr), which also counts it.
  static Error build_error(const gl::BuildFailure& f, const shader::ShaderFile& vf, const shader::ShaderFile& ff,
                           const shader::UnwrappedSource& vs, const shader::UnwrappedSource& fs,
                           const std::vector<shader::StandIn>& renamed) {
    Error e;
    e.code = ErrorCode::driver_refused;
    e.driver_log = f.log;
    std::string what;
    switch (f.stage) {
      case gl::BuildStage::vertex:
        e.diagnostics = shader::parse_driver_log(f.log, "vertex", vf.name, &vs);
        what = "compile the vertex shader";
        break;
      case gl::BuildStage::fragment:
        e.diagnostics = shader::parse_driver_log(f.log, "fragment", ff.name, &fs);
        what = "compile the fragment shader";
        break;
      case gl::BuildStage::link:
        e.diagnostics = shader::parse_driver_log(f.log, "link", "", nullptr);
        what = "link the shaders";
        break;
    }
    shader::restore_names(e.diagnostics, renamed);
    shader::restore_names(e.driver_log, renamed);
    e.message = "the shaders pass the browser's rules, but this server's graphics driver will not " + what +
                ": ShadeLab cannot run them here (not the student's error; staff can see the driver's log)";
    std::cerr << "shadelab: driver_refused: the driver would not " << what << " that ShadeLab's front end accepted: "
              << e.driver_log.substr(0, e.driver_log.find('\n')) << "\n";
    return e;
  }

  static std::vector<Diagnostic> warning_diagnostics(const Built& built, const shader::ShaderFile& vf,
                                                     const shader::ShaderFile& ff) {
    auto out = built.webgl_warnings;
    auto vertex = shader::parse_driver_log(built.program->vertex_log(), "vertex", vf.name, &built.vertex);
    out.insert(out.end(), vertex.begin(), vertex.end());
    auto fragment = shader::parse_driver_log(built.program->fragment_log(), "fragment", ff.name, &built.fragment);
    auto link = shader::parse_driver_log(built.program->link_log(), "link", "", nullptr);
    out.insert(out.end(), fragment.begin(), fragment.end());
    out.insert(out.end(), link.begin(), link.end());
    shader::restore_names(out, built.renamed);
    return out;
  }

  gl::MeshBuffer& mesh_buffer(const scene::Mesh& mesh, bool& cached) {
    std::string name = scene::content_address(mesh);
    if (gl::MeshBuffer* hit = meshes.find(name)) {
      cached = true;
      return *hit;
    }
    cached = false;
    gl::MeshBuffer buffer = gl::MeshBuffer::upload(mesh.interleaved());
    const size_t bytes = buffer.bytes();
    return meshes.insert(std::move(name), std::move(buffer), bytes);
  }

  // The pair of targets for this request's size, samples and format, reused between jobs.
  Expected<std::array<gl::RenderTarget*, 2>> render_targets(const RenderRequest& r, shader::VariantOutputs outputs) {
    const auto format = r.pixel_type == image::PixelType::u8 ? gl::PixelFormat::rgba8 : gl::PixelFormat::rgba32f;
    const bool reusable = targets[0] && targets[0]->width() == r.width && targets[0]->height() == r.height &&
                          targets[0]->format() == format && requested_samples == r.msaa && targets[0]->outputs() == outputs.total() &&
                          targets[0]->census_outputs() == outputs.census;
    if (!reusable) {
      targets = {};
      for (auto& t : targets) {
        auto created = gl::RenderTarget::create(r.width, r.height, r.msaa, format, outputs.total(), outputs.census);
        if (!created) return created.take_error();
        t = std::move(*created);
      }
      requested_samples = r.msaa;
    }
    return std::array<gl::RenderTarget*, 2>{&*targets[0], &*targets[1]};
  }
  int requested_samples = -1;

  // The frames of `request` (of every request in `variants`, one output each) with a program built
  // for it; a float frame's non-finite colours, or the census the program draws, to `census`.
  Expected<RenderReport> draw(const RenderRequest& request, const scene::Mesh& mesh, const Built& built, const Variants* variants,
                              Clock::time_point start, const IndexedSink& sink, const CensusSink& census) {
    RenderReport report;
    report.program_cached = built.cached;
    report.times.compile_ms = built.cached ? 0.0 : ms_since(start);
    const gl::Program& program = *built.program;
    for (auto* w : {&built.vertex.warnings, &built.fragment.warnings})
      report.warnings.insert(report.warnings.end(), w->begin(), w->end());
    report.attributes = describe(program.attributes());
    report.uniforms = describe(program.uniforms());
    auto plan = plan_uniforms(program.uniforms(), request.page.uniforms, request.uniforms);
    if (!plan) return plan.take_error();
    report.warnings.insert(report.warnings.end(), plan->warnings.begin(), plan->warnings.end());

    int position_location = -1, normal_location = -1;
    for (const auto& a : program.attributes()) {
      if (a.name == kPositionAttribute) {
        position_location = a.location;
      } else if (a.name == kNormalAttribute) {
        normal_location = a.location;
      } else {
        report.warnings.push_back("attribute '" + a.name + "' is not fed by the homework page (only " +
                                  kPositionAttribute + " and " + kNormalAttribute + " are); it reads (0, 0, 0, 1)");
      }
    }

    const shader::VariantOutputs outputs = built.outputs;
    auto pair = render_targets(request, outputs);
    if (!pair) return pair.take_error();
    report.samples = (*pair)[0]->samples();
    if (request.msaa > 0 && report.samples != request.msaa)
      report.warnings.push_back("the driver gave " + std::to_string(report.samples) + " samples per pixel for the " +
                                std::to_string(request.msaa) + " asked for");

    const auto upload_start = Clock::now();
    bool mesh_cached = false;
    const gl::MeshBuffer& buffer = mesh_buffer(mesh, mesh_cached);
    report.times.upload_ms = mesh_cached ? 0.0 : ms_since(upload_start);

    program.use();
    // The program may be a cached one another job set: what this job's plan leaves unset reads 0,
    // as in the browser's fresh program (and as the plan's warnings say).
    program.zero_uniforms();
    for (const auto& c : plan->constant) program.set_uniform(*c.uniform, c.values);
    if (built.rewritten) set_variants(program, variants, outputs.colours);

    staging.resize((*pair)[0]->bytes_per_read());
    const size_t frame_bytes = (*pair)[0]->bytes_per_frame();
    image::Image frame = image::Image::blank(request.width, request.height, request.pixel_type);
    const auto read_and_emit = [&](int k) {
      const auto read_start = Clock::now();
      if (auto read = (*pair)[static_cast<size_t>(k % 2)]->finish_read(staging.data()); !read) return read;
      for (int o = 0; o < outputs.colours; ++o) {
        const auto convert_start = Clock::now();
        const std::uint8_t* pixels = staging.data() + static_cast<size_t>(o) * frame_bytes;
        bool opaque = false;
        if (request.pixel_type == image::PixelType::u8)
          opaque = image::canvas_blob_from_readback(pixels, frame);
        else
          image::float_from_readback(reinterpret_cast<const float*>(pixels), frame);
        if (census && request.pixel_type == image::PixelType::f32) census(o, k, image::count_non_finite(frame));
        report.times.readback_ms += ms_since(o == 0 ? read_start : convert_start);
        const auto sink_start = Clock::now();
        sink(o, k, frame, opaque);
        report.times.sink_ms += ms_since(sink_start);
      }
      const size_t pixels = static_cast<size_t>(request.width) * static_cast<size_t>(request.height);
      for (int j = 0; j < outputs.census; ++j) {  // runs 2j and 2j + 1
        const std::uint8_t* flags = staging.data() + static_cast<size_t>(outputs.colours + j) * frame_bytes;
        for (int run = 2 * j; run < std::min(2 * j + 2, outputs.colours); ++run) census(run, k, image::count_census(flags, pixels, run % 2 == 1));
      }
      return Status{Ok{}};
    };

    // Frame k is submitted, then frame k - 1 is read: llvmpipe rasterises k on its threads while
    // this thread copies k - 1 out, and a GPU gets its next commands before the readback stalls.
    const auto loop_start = Clock::now();
    for (int k = 0; k < request.frames; ++k) {
      const auto submit_start = Clock::now();
      gl::RenderTarget& rt = *(*pair)[static_cast<size_t>(k % 2)];
      FrameTransforms t = homework_transforms(request.page.camera, request.width, request.height, frame_angle(request, k));
      if (request.sample_position) t.world_to_clip = sampling_at(*request.sample_position, request.width, request.height) * t.world_to_clip;
      if (plan->world_to_clip) program.set_uniform(*plan->world_to_clip, {glm::value_ptr(t.world_to_clip), 16});
      if (plan->mesh_to_world) program.set_uniform(*plan->mesh_to_world, {glm::value_ptr(t.mesh_to_world), 16});
      if (plan->mesh_to_world_rot) program.set_uniform(*plan->mesh_to_world_rot, {glm::value_ptr(t.mesh_to_world_rot), 16});
      rt.begin_frame();
      buffer.draw(position_location, normal_location);
      rt.resolve();
      rt.start_read(readback);
      // The draw call is where llvmpipe JIT-compiles the program's code for this state.
      if (k == 0) report.times.first_frame_ms = ms_since(submit_start);
      if (k > 0)
        if (auto read = read_and_emit(k - 1); !read) return read.take_error();
    }
    if (auto read = read_and_emit(request.frames - 1); !read) return read.take_error();
    report.times.render_ms = ms_since(loop_start) - report.times.readback_ms - report.times.sink_ms;
    report.times.total_ms = ms_since(start);
    return report;
  }

  // The rewritten program's run count, and each request's values for the uniforms they differ in
  // into its arrays (none for the census alone: one run).
  static void set_variants(const gl::Program& program, const Variants* v, int runs) {
    const auto active = [&](const std::string& name) -> const gl::ActiveVariable* {
      for (const auto& u : program.uniforms())
        if (u.name == name || u.name == name + "[0]") return &u;
      return nullptr;
    };
    for (size_t n = 0, at = 0; v && n < v->names.size(); at += v->components[n++]) {
      std::vector<float> all;
      for (const auto& values : v->values)
        all.insert(all.end(), values.begin() + static_cast<long>(at), values.begin() + static_cast<long>(at + v->components[n]));
      if (const auto* u = active(shader::variant_uniform(v->names[n]))) program.set_uniform(*u, all);
    }
    if (const auto* count = active(shader::kVariantCount)) program.set_uniform(*count, std::vector<float>{static_cast<float>(runs)});
  }

  // What `requests` differ in, judged on the uniform values each would upload to the program.
  Expected<Variants> variants_of(const std::vector<RenderRequest>& requests) {
    Variants v;
    const auto all_but_uniforms = [](RenderRequest r) {
      r.uniforms.clear();
      return pixel_identity(r);
    };
    const std::string shared = all_but_uniforms(requests.front());
    for (const auto& r : requests)
      if (all_but_uniforms(r) != shared) return v;
    if (auto valid = validate(requests.front(), kRendererHardLimits); !valid) return valid.take_error();
    auto built = build(requests.front().vertex, requests.front().fragment);
    if (!built) return built.take_error();
    std::vector<UniformPlan> plans;
    for (const auto& r : requests) {
      auto plan = plan_uniforms(built->program->uniforms(), r.page.uniforms, r.uniforms);
      if (!plan) return plan.take_error();
      plans.push_back(std::move(*plan));
    }
    for (const auto& plan : plans)  // the frame's matrices fed by the renderer in one and set by the request in another
      if (plan.world_to_clip != plans.front().world_to_clip || plan.mesh_to_world != plans.front().mesh_to_world ||
          plan.mesh_to_world_rot != plans.front().mesh_to_world_rot)
        return v;
    v.values.resize(requests.size());
    for (const auto& u : built->program->uniforms()) {
      std::vector<std::vector<float>> each;  // an unset uniform reads 0, as in a render of its own
      for (const auto& plan : plans) each.push_back(value_in(plan, u));
      if (std::all_of(each.begin(), each.end(), [&](const auto& e) { return e == each.front(); })) continue;
      const std::string_view type = u.type.name;
      if ((type != "vec3" && type != "vec4") || u.array_size != 1) return v;
      v.names.push_back(u.name);
      v.components.push_back(type == "vec3" ? 3 : 4);
      for (size_t i = 0; i < each.size(); ++i) v.values[i].insert(v.values[i].end(), each[i].begin(), each[i].end());
    }
    v.kind = v.names.empty() ? Variants::Kind::identical : Variants::Kind::uniforms;
    return v;
  }

  // What `plan` uploads to `u`, or zeros, as many as its type has, when it leaves it unset.
  static std::vector<float> value_in(const UniformPlan& plan, const gl::ActiveVariable& u) {
    for (const auto& c : plan.constant)
      if (c.uniform == &u) return c.values;
    return std::vector<float>(std::string_view(u.type.name) == "vec4" ? 4 : 3, 0.f);
  }
};

Renderer::Renderer(std::unique_ptr<State> state) : state_(std::move(state)) {}
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Expected<Renderer> Renderer::create(const egl::ContextOptions& options) {
  auto context = egl::HeadlessContext::create(options);
  if (!context) return context.take_error();
  return Renderer(std::make_unique<State>(State{std::move(*context)}));
}

const egl::ContextInfo& Renderer::context_info() const { return state_->context.info(); }

gl::Readback Renderer::readback() const { return state_->readback; }
void Renderer::set_readback(gl::Readback mode) { state_->readback = mode; }

Renderer::CacheSizes Renderer::cache_sizes() const {
  return {state_->programs.size(), state_->meshes.size(), state_->meshes.bytes()};
}

Expected<CompileReport> Renderer::compile(const shader::ShaderFile& vertex, const shader::ShaderFile& fragment) {
  const auto start = Clock::now();
  auto built = state_->build(vertex, fragment);
  if (!built) return built.take_error();
  CompileReport report;
  report.compile_ms = ms_since(start);
  report.cached = built->cached;
  report.warnings = built->vertex.warnings;
  report.warnings.insert(report.warnings.end(), built->fragment.warnings.begin(), built->fragment.warnings.end());
  report.diagnostics = State::warning_diagnostics(*built, vertex, fragment);
  report.attributes = describe(built->program->attributes());
  report.uniforms = describe(built->program->uniforms());
  return report;
}

Expected<RenderReport> Renderer::render(const RenderRequest& request, const scene::Mesh& mesh, const FrameSink& sink,
                                        const CensusSink& census) {
  const auto start = Clock::now();
  if (auto valid = validate(request, kRendererHardLimits); !valid) return valid.take_error();
  const auto frame_sink = [&](int, int k, const image::Image& f, bool opaque) { sink(k, f, opaque); };
  const bool drawn_census = census && request.pixel_type == image::PixelType::u8;
  auto built = state_->build(request.vertex, request.fragment, request.semantics, nullptr, drawn_census);
  if (built || !drawn_census) {
    if (!built) return built.take_error();
    return state_->draw(request, mesh, *built, nullptr, start, frame_sink, census);
  }
  // No census in this program (the rewrite declined it: GLSL ES 1.00, several outputs, a macro; or
  // the driver did not take it): the frames as drawn, then their colours counted in a float render
  // of their own, at pixel centres.
  auto report = render(request, mesh, sink);
  if (!report) return report;
  RenderRequest as_float = request;
  as_float.pixel_type = image::PixelType::f32;
  as_float.msaa = 0;
  auto counted = render(as_float, mesh, [](int, const image::Image&, bool) {}, census);
  if (!counted) return counted.take_error();
  report->passes = 2;
  return report;
}

Expected<RenderReport> Renderer::render_together(const std::vector<RenderRequest>& requests, const scene::Mesh& mesh,
                                                 const IndexedSink& sink, const CensusSink& census) {
  const auto start = Clock::now();
  if (requests.empty()) return RenderReport{};
  auto variants = state_->variants_of(requests);
  if (!variants) return variants.take_error();
  // Request i's render, its frames (and census) handed on as those of the requests it stands for.
  const auto render_for = [&](size_t i, size_t first, size_t last) {
    CensusSink counts;
    if (census)
      counts = [&](int, int k, const image::NonFinite& n) {
        for (size_t to = first; to <= last; ++to) census(static_cast<int>(to), k, n);
      };
    return render(requests[i], mesh, [&](int k, const image::Image& f, bool opaque) {
      for (size_t to = first; to <= last; ++to) sink(static_cast<int>(to), k, f, opaque);
    }, counts);
  };
  const auto a_pass_each = [&]() -> Expected<RenderReport> {
    RenderReport report;
    int passes = 0;
    for (size_t i = 0; i < requests.size(); ++i) {
      auto r = render_for(i, i, i);
      if (!r) return r;
      passes += r->passes;
      report = std::move(*r);
    }
    report.passes = passes;
    return report;
  };
  switch (variants->kind) {
    case Variants::Kind::identical: return render_for(0, 0, requests.size() - 1);
    case Variants::Kind::apart: return a_pass_each();
    case Variants::Kind::uniforms: break;
  }
  const RenderRequest& first = requests[0];
  auto built = state_->build(first.vertex, first.fragment, first.semantics, &*variants, census && first.pixel_type == image::PixelType::u8);
  if (!built) return a_pass_each();  // the rewrite declined, or the driver did not take it
  return state_->draw(first, mesh, *built, &*variants, start, sink, census);
}

}  // namespace shadelab::render
