#pragma once
// Uploaded meshes, content-addressed and kept in memory (bounded; the oldest goes first). The
// bytes are checked by a worker (assimp runs there, not in the HTTP process) before they are kept.
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace shadelab::http {

struct StoredMesh {
  std::string id, filename, format, bytes;
  nlohmann::json info;  // triangles, bounds, normalsFromFile
};

class MeshStore {
 public:
  explicit MeshStore(size_t capacity) : capacity_(capacity) {}
  void put(StoredMesh mesh);
  std::optional<StoredMesh> get(const std::string& id) const;

 private:
  size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<StoredMesh> meshes_;
};

}  // namespace shadelab::http
