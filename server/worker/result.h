#pragma once
// Every answer a render worker gives, typed: what the worker sends and what the HTTP process and
// the CLI read. An answer is one Message: {"ok": true, "result": {...}} with the result's files
// packed into the payload (never base64), or {"ok": false, "error": {...}}.
//
// | job kind   | result          | files in the payload                                   |
// |------------|-----------------|--------------------------------------------------------|
// | compile    | CompileResult   | none                                                   |
// | render     | RenderResult    | the body (grid image or zip); for output json, frames  |
// | mesh_check | MeshCheckResult | none                                                   |
// | scene      | SceneResult     | the PNG                                                |
// | grade      | GradeResult     | the heat map PNG, when the submission rendered         |
// | grade_frames | FramesGradeResult | the heat map PNG of the saved frames                 |
// | check_images | ImagesResult | none                                                  |
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "core/json_fields.h"
#include "grade/image_check.h"
#include "grade/report.h"
#include "render/render_request.h"
#include "repair/value_probes.h"
#include "scene_render/scene_report.h"
#include "worker/protocol.h"

namespace shadelab::worker {

struct CompileResult {
  std::vector<std::string> warnings;
  std::vector<Diagnostic> diagnostics;  // the driver's warnings, at the student's lines
  std::vector<render::VariableInfo> attributes, uniforms;
  double compile_ms = 0;
};

// A frame one colour throughout: the most common "my render is blank" complaint.
struct ConstantFrame {
  int frame = 0;
  std::array<int, 4> rgba{};
};

struct RenderTimings {
  double compile_ms = 0, upload_ms = 0, first_frame_ms = 0, render_ms = 0, readback_ms = 0, encode_ms = 0;
};

struct NamedFile {
  std::string name;
  std::string bytes;
};

struct RenderResult {
  std::vector<std::string> warnings;
  std::vector<Diagnostic> diagnostics;
  std::vector<render::VariableInfo> attributes, uniforms;
  int samples = 0;
  std::vector<ConstantFrame> constant_frames;
  RenderTimings timings;
  std::string content_type;       // of `body`: image/png, image/x-exr, application/zip
  std::string body;               // output grid: the grid; frames: the zip; json: the grid
  std::vector<NamedFile> frames;  // output json: hw2_{prefix}_{k}.{png,exr}
};

struct MeshCheckResult {
  size_t triangles = 0;
  bool normals_from_file = false;
  std::array<double, 3> min{}, max{};
};

struct SceneResult {
  scene_render::SceneReport report;
  double encode_ms = 0;
  std::string png;
};

struct GradeResult {
  grade::Report report;
  std::string heatmap_png;  // empty when the submission did not render
  std::optional<repair::ValueAgreement> values;  // for the repair search (GradeSpec::read_values); never sent to a client
};

// Saved frames graded (grade/judge_saved_frames.h): against the reference, and against
// the code handed in with them when there was some.
struct FramesGradeResult {
  grade::Report frames;
  std::optional<grade::Report> code;
  std::string heatmap_png;  // the saved frames against the reference; empty when they did not decode
};

// The handed-in images judged, in the job's order.
struct ImagesResult {
  std::vector<grade::ImageVerdict> verdicts;
};

// Worker side: the answer to send.
Message answer(const CompileResult& r);
Message answer(const RenderResult& r);
Message answer(const MeshCheckResult& r);
Message answer(const SceneResult& r);
Message answer(const GradeResult& r);
Message answer(const FramesGradeResult& r);
Message answer(const ImagesResult& r);
Message answer(const Error& e);

// Reader side: the result an answer holds, its Error, or worker_protocol when it is malformed.
template <class Result>
Expected<Result> result_from(const Message& answer);

// The JSON forms, one to_json / from_json pair per struct, shared by the wire and the HTTP
// responses that show them. A result's files travel beside its JSON (see the table above), so
// its pair reads and writes the rest. from_json throws nlohmann::json::exception when malformed.
SHADELAB_JSON_DECLARE(ConstantFrame);
SHADELAB_JSON_DECLARE(RenderTimings);
SHADELAB_JSON_DECLARE(CompileResult);
SHADELAB_JSON_DECLARE(RenderResult);
SHADELAB_JSON_DECLARE(MeshCheckResult);
SHADELAB_JSON_DECLARE(SceneResult);
SHADELAB_JSON_DECLARE(GradeResult);
SHADELAB_JSON_DECLARE(FramesGradeResult);
SHADELAB_JSON_DECLARE(ImagesResult);

}  // namespace shadelab::worker

namespace shadelab {
// An error as the worker sends it. Reading never throws: the worker runs student code, so what
// it sends is read, not trusted; an unknown or missing code reads as worker_protocol.
SHADELAB_JSON_DECLARE(Error);
}  // namespace shadelab

namespace shadelab::grade {
SHADELAB_JSON_DECLARE(ImageVerdict);
}  // namespace shadelab::grade

namespace shadelab::repair {
SHADELAB_JSON_DECLARE(ValueChangeTo);
SHADELAB_JSON_DECLARE(ValueAgreement);
}  // namespace shadelab::repair

namespace shadelab::render {
SHADELAB_JSON_DECLARE(VariableInfo);
}  // namespace shadelab::render

namespace shadelab::scene_render {
SHADELAB_JSON_DECLARE(PassTiming);
SHADELAB_JSON_DECLARE(ObjectFraming);
SHADELAB_JSON_DECLARE(CameraSummary);
SHADELAB_JSON_DECLARE(SceneReport);
}  // namespace shadelab::scene_render
