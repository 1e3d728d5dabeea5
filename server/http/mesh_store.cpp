#include "http/mesh_store.h"

#include "http/api_request.h"
#include "worker/protocol.h"

namespace shadelab::http {

namespace {

std::string shared_key(const std::string& id) { return "shadelab:1:mesh:" + id; }

std::string encode(const StoredMesh& m) {
  return worker::encode_message({{{"id", m.id}, {"filename", m.filename}, {"format", m.format}, {"info", m.info}}, m.bytes});
}

// The stored mesh, if `value` is one and its bytes are the ones `id` names.
std::optional<StoredMesh> decode(const std::string& id, const std::string& value) {
  auto message = worker::decode_message(value);
  if (!message || mesh_id(message->payload) != id) return std::nullopt;
  const auto& h = message->header;
  const std::string filename = worker::header_text(h, "filename"), format = worker::header_text(h, "format");
  if (filename.empty() || format.empty()) return std::nullopt;
  return StoredMesh{id, filename, format, std::move(message->payload), h.contains("info") ? h["info"] : nlohmann::json::object()};
}

}  // namespace

void MeshStore::put(StoredMesh mesh) {
  // A failed store is not the uploader's problem: this replica keeps the mesh, and another asks
  // again when it needs it (and answers store_unavailable while Redis is down).
  if (shared_) (void)shared_->put(shared_key(mesh.id), encode(mesh));
  put_local(std::move(mesh));
}

Expected<std::optional<StoredMesh>> MeshStore::get(const std::string& id) {
  if (auto local = get_local(id)) return local;
  if (!shared_) return std::optional<StoredMesh>();
  auto value = shared_->get(shared_key(id));
  if (!value) return value.take_error();
  if (!*value) return std::optional<StoredMesh>();
  auto mesh = decode(id, **value);
  if (mesh) put_local(*mesh);
  return mesh;
}

std::optional<StoredMesh> MeshStore::get_local(const std::string& id) const {
  std::lock_guard lock(mutex_);
  for (const auto& m : meshes_)
    if (m.id == id) return m;
  return std::nullopt;
}

void MeshStore::put_local(StoredMesh mesh) {
  std::lock_guard lock(mutex_);
  for (const auto& m : meshes_)
    if (m.id == mesh.id) return;
  meshes_.push_back(std::move(mesh));
  if (meshes_.size() > capacity_) meshes_.pop_front();
}

}  // namespace shadelab::http
