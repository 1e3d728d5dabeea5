#pragma once
// Whether a student's line reads as a line of the reference's stage: the same tokens, where a
// local the student named otherwise counts as the reference's name (`vec3 toEye = ...` as `vec3 V
// = ...`). The names are aligned once, from the student's declarations that read as the
// reference's but for the name they declare, in the order the student wrote them: the smallest
// form of aligning a program with a correct one by its variables (Clara, PLDI 2018). A uniform, an
// input, a function, a name both programs declare or a name never declared alike is read as
// written: it aligns only with itself (`vec3 V = normalize(uLightPosition - vPosition);` is a
// wrong V, never the reference's L).
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab::grade {

class AlignedLines {
 public:
  AlignedLines(std::string_view student_glsl, std::string_view reference_glsl);

  // Whether `line` (one the student wrote, or one an edit rewrites) reads as a reference line.
  // A declaration may align a name not yet aligned: an edit that mends the line declaring it
  // makes it read as the reference's.
  bool reads_as_reference(std::string_view line) const;

 private:
  using Tokens = std::vector<std::string>;
  struct Names {
    std::map<std::string, std::string, std::less<>> to_reference, from_reference;
    // The locals each program declares: a name both declare is one variable, aligned with itself.
    std::set<std::string, std::less<>> student_declares, reference_declares;
  };
  // Whether `student` reads as `reference` under `names`; the declared name's new alignment, if
  // one is needed, goes into `declared` ("" where none is).
  static bool aligned(const Tokens& student, const Tokens& reference, const Names& names, std::pair<std::string, std::string>& declared);
  bool reads_as_reference(const Tokens& line, std::pair<std::string, std::string>& declared) const;

  std::vector<Tokens> reference_lines_;
  Names names_;
};

}  // namespace shadelab::grade
