#pragma once
// The benchmarks' one renderer per process, on the default device; a benchmark cannot go on
// without it, so a failure to create it ends the process with the reason.
#include <cstdlib>
#include <iostream>

#include "render/renderer.h"

namespace shadelab::bench {

inline render::Renderer& renderer() {
  static render::Renderer r = [] {
    auto created = render::Renderer::create({});
    if (!created) {
      std::cerr << created.error().format() << "\n";
      std::exit(1);
    }
    std::cerr << "renderer: " << created->context_info().gl_renderer << "\n";
    return std::move(*created);
  }();
  return r;
}

}  // namespace shadelab::bench
