#pragma once
// Uploaded meshes, content-addressed: kept in this replica's memory (bounded; the oldest goes
// first) and, with a shared store, in Redis too, so a replica that did not take the upload can
// still render it. The bytes are checked by a worker (assimp runs there, not in the HTTP process)
// before they are kept; what comes back from Redis is checked against its id before it is used.
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "store/shared_store.h"

namespace shadelab::http {

struct StoredMesh {
  std::string id, filename, format, bytes;
  nlohmann::json info;  // triangles, bounds, normalsFromFile
};

class MeshStore {
 public:
  MeshStore(size_t capacity, store::SharedStore* shared) : capacity_(capacity), shared_(shared) {}
  void put(StoredMesh mesh);
  // nullopt: no such mesh anywhere. store_unavailable: not here, and the shared store that may
  // hold it cannot be asked (a 503, never a wrong 404).
  Expected<std::optional<StoredMesh>> get(const std::string& id);

 private:
  std::optional<StoredMesh> get_local(const std::string& id) const;
  void put_local(StoredMesh mesh);

  size_t capacity_;
  store::SharedStore* shared_;
  mutable std::mutex mutex_;
  std::deque<StoredMesh> meshes_;
};

}  // namespace shadelab::http
