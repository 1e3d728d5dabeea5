#pragma once
// A scene job as it travels to a worker: the scene JSON (validated by the HTTP layer, parsed again
// in the worker), and the bytes of every non-built-in mesh it names, packed into the message
// payload back to back.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "worker/protocol.h"

namespace shadelab::worker {

struct SceneMeshBytes {
  std::string reference;  // as the scene's objects name it
  std::string format;     // file extension: obj, glb, ply, ...
  std::string bytes;
};

struct SceneJob {
  nlohmann::json scene;
  std::vector<SceneMeshBytes> meshes;
};

inline constexpr const char* kSceneJobKind = "scene";

Message to_message(const SceneJob& job);
bool is_scene_message(const Message& m);
Expected<SceneJob> scene_job_from_message(const Message& m);

}  // namespace shadelab::worker
