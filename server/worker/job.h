#pragma once
// Every job a render worker takes, typed: what the HTTP process and the CLI send. Each job is
// resolved and validated before it is sent (presets expanded, the scene parsed once, uploaded
// meshes attached as the message payload); the worker trusts its shape, not its content.
//
// | kind       | struct   | payload                        | answered with (worker/result.h) |
// |------------|----------|--------------------------------|---------------------------------|
// | render     | Job      | the uploaded mesh, if any      | RenderResult                    |
// | compile    | Job      | none                           | CompileResult                   |
// | mesh_check | Job      | the mesh file                  | MeshCheckResult                 |
// | grade      | Job      | the uploaded mesh, if any      | GradeResult                     |
// | grade_frames | Job    | the uploaded mesh, saved frames | FramesGradeResult              |
// | scene      | SceneJob | each non-built-in mesh's bytes | SceneResult                     |
// | check_images | ImagesJob | the handed-in PNGs         | ImagesResult                    |
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "core/json_fields.h"
#include "grade/grade_spec.h"
#include "grade/hand_in_images.h"
#include "render/render_request.h"
#include "scene/mesh.h"
#include "scene/scene_description.h"
#include "worker/protocol.h"

namespace shadelab::worker {

enum class JobKind { render, compile, mesh_check, grade, grade_frames, scene, check_images };
enum class Output { grid, frames, json };
enum class Format { png, exr };

struct Job {
  JobKind kind = JobKind::render;
  render::RenderRequest request;  // shaders, size, frames, msaa, page setup, uniforms, pixel type
  // The mesh by its id, the worker's cache key: a course mesh compiled into the binary is named by
  // its file there ("assets/bunny.obj", `mesh_embedded` set); any other (a course's own, an
  // upload) by its content address, its bytes in the payload.
  std::string mesh;
  std::string mesh_embedded;
  std::string mesh_format;               // file extension: obj, glb, ...
  std::optional<scene::Bounds> fit;      // fitted into these bounds (the course's default mesh's) when set
  std::string frame_name = "frame_{k}";  // the course's file name pattern: hw2_{prefix}_{k}
  std::string prefix = "render";
  Output output = Output::grid;
  Format format = Format::png;
  // Written beside the frames of a zip as FOR_CHECKING_NOT_FOR_HANDING_IN.txt, when not empty (a
  // course that wants frames saved from its page: Course::frames_download_notice).
  std::string notice;
  grade::GradeSpec grade;  // for JobKind::grade and grade_frames
  // The share of the pool's compile and render deadlines (CPU time) the job's shaders get, in
  // (0, 1]: a repair candidate's screen is small, and one that hangs is dropped at its share.
  // None: the whole deadlines. The grader's own renders keep theirs.
  std::optional<double> deadline_share;
};

// A grade_frames job's payload: the uploaded mesh's bytes (empty for a built-in one) and the
// frames the student saved, in order.
struct FramesPayload {
  std::string mesh;
  std::vector<grade::SavedFrame> saved;
};

struct SceneMeshBytes {
  std::string reference;  // as the scene's objects name it
  std::string format;     // file extension: obj, glb, ply, ...
  std::string bytes;
};

struct SceneJob {
  scene::SceneDescription scene;     // parsed and validated by the sender
  std::vector<SceneMeshBytes> meshes;
};

// The Blender half's images a student handed in, to be judged (grade/hand_in_images.h).
using CheckedImage = grade::HandInImage;

struct ImagesJob {
  std::vector<CheckedImage> images;
};

Message to_message(const Job& job, std::string mesh_bytes = {});
Message to_message(const Job& job, const FramesPayload& payload);  // a grade_frames job
Message to_message(const SceneJob& job);
Message to_message(const ImagesJob& job);

// The kind a message carries, for the worker's dispatch; worker_protocol when there is none.
Expected<JobKind> job_kind_of(const Message& message);
Expected<Job> job_from_message(const Message& message);
Expected<SceneJob> scene_job_from_message(const Message& message);
Expected<ImagesJob> images_job_from_message(const Message& message);
Expected<FramesPayload> frames_payload_from(const Message& message);

std::string_view to_string(JobKind k);
std::string_view to_string(Output o);
std::string_view to_string(Format f);

// A job's header on the wire; from_json throws nlohmann::json::exception when malformed.
SHADELAB_JSON_DECLARE(Job);

}  // namespace shadelab::worker

namespace shadelab::scene {
// The scene description on the wire: every field of the struct (worker/scene_json.h), nothing
// re-validated; from_json throws nlohmann::json::exception.
SHADELAB_JSON_DECLARE(SceneDescription);
}  // namespace shadelab::scene
