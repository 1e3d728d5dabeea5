#include "http/mesh_store.h"

namespace shadelab::http {

void MeshStore::put(StoredMesh mesh) {
  std::lock_guard lock(mutex_);
  for (const auto& m : meshes_)
    if (m.id == mesh.id) return;
  meshes_.push_back(std::move(mesh));
  if (meshes_.size() > capacity_) meshes_.pop_front();
}

std::optional<StoredMesh> MeshStore::get(const std::string& id) const {
  std::lock_guard lock(mutex_);
  for (const auto& m : meshes_)
    if (m.id == id) return m;
  return std::nullopt;
}

}  // namespace shadelab::http
