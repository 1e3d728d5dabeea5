#pragma once
// Reference renders kept on disk across processes: a course's references and its catalogue of
// mistakes are rendered once per course and checkpoint (by `shadelab course warm`, or by the first
// grade that needs them) and read back by every later grade: a fresh `shadelab autograde`, a
// Gradescope container built with them, every worker of a server. Diagnosing a wrong submission
// then costs comparisons, not renders.
//
// An entry is named by SHA-256 of everything its pixels depend on: the request's pixel identity
// (render/render_request.h), the mesh's content address, the renderer (GL_RENDERER and
// GL_VERSION), and this build (build_fingerprint()), so a new build or another driver never reads
// another's frames. Entries are written to a temporary file and renamed into place, so a reader
// sees a whole entry or none; one that does not read back whole is a miss.
//
// In a cluster the entries are also kept in the replicas' shared store (Redis, beside uploads):
// a node without one on disk takes it from there and keeps a copy, so a class spread over nodes
// renders a course's references once, not once per node. The disk is read first (no network for
// a warm node); the shared store is a cache like any other here, and its outage costs renders.
//
// The entry's bytes: grade/reference_entry.h.
#include <filesystem>
#include <optional>
#include <string>

#include "grade/grader.h"
#include "render/render_request.h"
#include "store/shared_store.h"

namespace shadelab::grade {

class ReferenceStore {
 public:
  // `folder` (none when empty) is created when missing; `shared`, when not null, is the cluster's
  // store; `renderer` names the driver ("llvmpipe (LLVM 15...) 3.2 Mesa ...").
  ReferenceStore(std::filesystem::path folder, store::SharedStore* shared, std::string renderer);

  // The key of `request` rendered on the mesh with content address `mesh`.
  std::string key(const render::RenderRequest& request, const std::string& mesh) const;
  // From the folder, else from the shared store (then copied into the folder). An entry is
  // `request`'s frames (its size, count and pixel type) or a miss: a damaged or forged one never
  // sizes an allocation beyond what rendering the request would.
  std::optional<SharedFrames> load(const std::string& key, const render::RenderRequest& request) const;
  // Best effort, to both: a store that cannot be written (read-only, full, down) only costs a
  // later render.
  void save(const std::string& key, const SharedFrames& frames) const;

 private:
  void write_to_folder(const std::string& key, const std::string& entry) const;

  std::filesystem::path folder_;
  store::SharedStore* shared_;
  std::string renderer_;
};

// What names this build (once per process): the linker's GNU build ID, else the executable's
// SHA-256. Part of every key.
const std::string& build_fingerprint();

// The default folder: $SHADELAB_CACHE_DIR, else $XDG_CACHE_HOME/shadelab/references, else
// ~/.cache/shadelab/references; empty when none can be named.
std::string default_reference_folder();

}  // namespace shadelab::grade
