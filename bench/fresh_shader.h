#pragma once
// A fragment shader no earlier job compiled, for benchmarks that time a student's fresh submission.
// Mesa caches compiled programs by their IR, in memory and on disk across processes, so a changed
// comment would be a cache hit. A branch that is never taken, on a constant unique to the job,
// makes a new program and changes no pixel. It returns rather than discards: a shader that may
// discard loses llvmpipe's early depth test and cannot share a pass between lights
// (shader/uniform_variants.h), and the homework's shaders do neither.
#include <string>

namespace shadelab::bench {

// `fragment` with that branch (and `extra`, more statements) at the top of `void main(void) {`.
inline std::string with_fresh_branch(std::string fragment, unsigned serial, const std::string& extra = "") {
  const std::string entry = "void main(void) {";
  fragment.insert(fragment.find(entry) + entry.size(), "\n    if (gl_FragCoord.x < -" + std::to_string(serial) + ".0) return;" + extra);
  return fragment;
}

}  // namespace shadelab::bench
