#pragma once
// The floor the service is measured against: the canonical job (canonical_job.h: the course's
// bunny, specular, 9 frames 512 x 512, 4x MSAA, grid PNG) done the plain way, in one process, serially, with raw EGL and
// GLES calls and libpng: compile and link, draw each frame into a multisampled framebuffer,
// resolve, glReadPixels, then compose the grid and write it as a PNG (zlib level 1, the UP filter,
// RGB: the fastest settings the encode table in docs/performance-log.md found). No ShadeLab code runs
// in the timed part; ShadeLab's readers only prepare the inputs (the GLSL out of the preset's JS
// modules, the bunny's triangles, the course's matrices and colours).
//
// Used by floor_bench (the floor alone) and load_bench (the floor and the service, job by job).
#include <memory>
#include <string>

namespace shadelab::bench {

struct FloorPhases {
  double compile = 0, render = 0, readback = 0, encode = 0, total = 0;
};

class FloorJob {
 public:
  // Opens its own surfaceless EGL context (current on the calling thread) and uploads the mesh.
  FloorJob();
  ~FloorJob();
  FloorJob(const FloorJob&) = delete;
  FloorJob& operator=(const FloorJob&) = delete;

  // One job with the course's default preset, its fragment shader given a never-taken branch on `serial`
  // (Mesa caches programs by their IR: a changed comment would be a cache hit).
  FloorPhases run(unsigned serial);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace shadelab::bench
