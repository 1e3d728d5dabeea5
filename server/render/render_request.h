#pragma once
// A render job as plain data, validated completely before any GL call. The homework's facts (size,
// frames, rotation, samples, camera, uniform values) are not defaults here: a course profile fills
// them (course::Course::render_request), so one offering's numbers live in one place.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "image/image.h"
#include "render/homework_contract.h"
#include "render/uniform_plan.h"
#include "shader/shader_source.h"

namespace shadelab::render {

// What the driver may do to the shaders' float arithmetic. as_compiled: what the student's program
// gets everywhere (Mesa's optimiser rewrites algebra as GPU compilers do: x - x -> 0). ieee: the
// outputs are declared invariant (shader/invariant_outputs.h), so no rewrite changes a value and a
// NaN or Inf that IEEE arithmetic gives appears: what the grader draws (docs/grading.md).
enum class FloatSemantics { as_compiled, ieee };

struct RenderRequest {
  shader::ShaderFile vertex;
  shader::ShaderFile fragment;
  int width = 0;
  int height = 0;
  int frames = 1;
  double degrees_per_frame = 0;  // frame k is rotated exactly k * degrees_per_frame about +Y...
  std::vector<double> angles;    // ...unless this lists each frame's rotation in degrees (its size is `frames`)
  int msaa = 0;                  // the browser canvas's antialias: true is 4; 0 turns it off
  // Where in each pixel a render without MSAA samples, in GL's window coordinates within the pixel
  // ((0, 0) its lower-left corner); its centre unless set. The grader draws its geometry at each of
  // an MSAA frame's sample positions in turn (grade/formula_geometry.h), so that a pixel's samples
  // are seen one by one.
  std::optional<std::array<double, 2>> sample_position;
  PageSetup page;                // the camera and the constant uniforms the page sets
  std::vector<UniformSetting> uniforms;  // the caller's values, over the page's
  image::PixelType pixel_type = image::PixelType::u8;  // f32: float target, for EXR
  FloatSemantics semantics = FloatSemantics::as_compiled;
};

struct RenderLimits {
  int max_width = 2048;
  int max_height = 2048;
  int max_frames = 36;
  size_t max_source_bytes = 64 * 1024;
};

Status validate(const RenderRequest& request, const RenderLimits& limits);
// Everything in a request that changes its pixels, exactly, and nothing else (file names do not):
// two requests with the same identity render the same frames on the same mesh and driver.
std::string pixel_identity(const RenderRequest& request);
// Frame k's rotation about +Y, in degrees.
double frame_angle(const RenderRequest& request, int k);
// The source checks that need no GL (size, UTF-8, NUL bytes, the JS module's syntax, #version) on
// both stages. Callers answer these before a job leaves for a worker: the JSON that carries a job
// cannot hold invalid UTF-8, and a student should not wait for a worker to hear about a typo.
Status check_sources(const RenderRequest& request, const RenderLimits& limits);

// What the renderer itself insists on, whatever limits the caller's policy sets (the CLI and the
// HTTP edge validate against their own, smaller, configurable limits first).
inline constexpr RenderLimits kRendererHardLimits{16384, 16384, 3600, 1u << 20};

// Milliseconds spent in each phase of one job.
struct PhaseTimes {
  double compile_ms = 0;       // unwrap + compile + link + reflect (0 when the program was cached)
  double upload_ms = 0;        // mesh to GPU (0 when cached)
  double first_frame_ms = 0;   // submitting frame 0 (llvmpipe JIT-compiles the shaders here)
  double render_ms = 0;        // the frame loop less readback and sink: submission and waiting for the driver
  double readback_ms = 0;      // glReadPixels + the browser's alpha rule (overlaps the next frame's raster)
  double sink_ms = 0;          // time the frame consumer held the render thread
  double total_ms = 0;
};

struct VariableInfo {
  std::string name;
  std::string type;  // "vec4"
  int array_size = 1;
};

struct RenderReport {
  std::vector<std::string> warnings;
  std::vector<VariableInfo> attributes, uniforms;
  int samples = 0;            // what the driver allocated
  bool program_cached = false;
  int passes = 1;             // over the geometry, a frame (Renderer::render_together may need several)
  PhaseTimes times;
};

// Receives each finished frame in order, rows top-down, as the browser would save it.
using FrameSink = std::function<void(int index, const image::Image& frame, bool opaque)>;

}  // namespace shadelab::render
