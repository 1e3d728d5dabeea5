#pragma once
// Reference renders kept on disk across processes: a course's references and its catalogue of
// mistakes are rendered once per course and checkpoint (by `shadelab course warm`, or by the first
// grade that needs them) and read back by every later grade: a fresh `shadelab autograde`, a
// Gradescope container built with them, every worker of a server. Diagnosing a wrong submission
// then costs comparisons, not renders.
//
// An entry is named by SHA-256 of everything its pixels depend on: the request's pixel identity
// (render/render_request.h), the mesh's content address, the renderer (GL_RENDERER and
// GL_VERSION), and this build (the executable's own SHA-256), so a new build or another driver
// never reads another's frames. Entries are written to a temporary file and renamed into place,
// so a reader sees a whole entry or none; one that does not read back whole is a miss.
//
// | bytes            | what                                                     |
// |------------------|----------------------------------------------------------|
// | "SLREF1\n"       | the format                                               |
// | 4 x uint32, LE   | width, height, frames, pixel type (0: RGBA8, 1: RGBA32F) |
// | the rest         | the frames' pixels, rows top-down, zlib (level 1)        |
#include <filesystem>
#include <optional>
#include <string>

#include "grade/grader.h"
#include "render/render_request.h"

namespace shadelab::grade {

class ReferenceStore {
 public:
  // `folder` is created when missing; `renderer` names the driver ("llvmpipe (LLVM 15...) 3.2 Mesa ...").
  ReferenceStore(std::filesystem::path folder, std::string renderer);

  // The key of `request` rendered on the mesh with content address `mesh`.
  std::string key(const render::RenderRequest& request, const std::string& mesh) const;
  std::optional<SharedFrames> load(const std::string& key) const;
  // Best effort: a store that cannot be written (read-only, full) only costs a later render.
  void save(const std::string& key, const SharedFrames& frames) const;

 private:
  std::filesystem::path folder_;
  std::string renderer_;
};

// What names this build (once per process): the linker's GNU build ID, else the executable's
// SHA-256. Part of every key.
const std::string& build_fingerprint();

// The default folder: $SHADELAB_CACHE_DIR, else $XDG_CACHE_HOME/shadelab/references, else
// ~/.cache/shadelab/references; empty when none can be named.
std::string default_reference_folder();

}  // namespace shadelab::grade
