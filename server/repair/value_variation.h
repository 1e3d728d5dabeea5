#pragma once
// Whether a value a stage computes can change from point to point (from vertex to vertex in the
// vertex stage), read from tokens for a restored value's words (grade/reference_edits.cpp): where
// the student's value is the same everywhere and the reference's is not, that is the change a
// student makes ("`V`, the direction to the eye, is the same at every point"). Read one way only:
// what is not known to be constant is never said to be, nor what is not known to vary.
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shader/glsl_lines.h"

namespace shadelab::repair {

class StageVariation {
 public:
  using Tokens = std::span<const shader::GlslToken>;

  // `stage`: every token of one stage's GLSL.
  explicit StageVariation(Tokens stage);

  // Whether `value` is the same at every point: every name it reads a uniform of the stage, a
  // type's constructor or a built-in function (a local or a function of the stage's own may hide
  // an input, so it is not known to be constant).
  bool constant(Tokens value) const;
  // Whether `value` reads something that varies: an input of the stage, a built-in that changes
  // from point to point (gl_FragCoord), or a name the stage writes from one of them.
  bool varies(Tokens value) const;
  // The stage's inputs that `value` reads by their own names, in the order it reads them.
  std::vector<std::string> inputs_read(Tokens value) const;

 private:
  std::set<std::string, std::less<>> uniforms_, inputs_, varying_;
};

}  // namespace shadelab::repair
