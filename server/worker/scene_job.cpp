#include "worker/scene_job.h"

namespace shadelab::worker {

Message to_message(const SceneJob& job) {
  Message m;
  nlohmann::json meshes = nlohmann::json::array();
  for (const auto& mesh : job.meshes) {
    meshes.push_back({{"reference", mesh.reference}, {"format", mesh.format}, {"offset", m.payload.size()}, {"size", mesh.bytes.size()}});
    m.payload += mesh.bytes;
  }
  m.header = {{"kind", kSceneJobKind}, {"scene", job.scene}, {"meshes", meshes}};
  return m;
}

bool is_scene_message(const Message& m) { return m.header.is_object() && m.header.value("kind", "") == kSceneJobKind; }

Expected<SceneJob> scene_job_from_message(const Message& m) {
  try {
    SceneJob job;
    job.scene = m.header.at("scene");
    for (const auto& mesh : m.header.at("meshes")) {
      const size_t offset = mesh.at("offset"), size = mesh.at("size");
      if (offset > m.payload.size() || size > m.payload.size() - offset)
        return make_error(ErrorCode::worker_protocol, "a scene mesh lies outside the message payload");
      job.meshes.push_back({mesh.at("reference"), mesh.at("format"), m.payload.substr(offset, size)});
    }
    return job;
  } catch (const nlohmann::json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed scene job: ") + e.what());
  }
}

}  // namespace shadelab::worker
