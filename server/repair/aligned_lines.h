#pragma once
// Whether a student's line reads as a line of the reference's stage: the same tokens, where a
// local the student named otherwise counts as the reference's name (`vec3 toEye = ...` as `vec3 V
// = ...`). The names are aligned once, from the student's declarations that read as the
// reference's but for the name they declare, in the order the student wrote them: the smallest
// form of aligning a program with a correct one by its variables (Clara, PLDI 2018). A uniform, an
// input, a function, a name both programs declare or a name never declared alike is read as
// written: it aligns only with itself (`vec3 V = normalize(uLightPosition - vPosition);` is a
// wrong V, never the reference's L).
#include <functional>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "repair/stage_tokens.h"

namespace shadelab::repair {

class AlignedLines {
 public:
  AlignedLines(const StageTokens& student, const StageTokens& reference);
  AlignedLines(std::string_view student_glsl, std::string_view reference_glsl);

  // Whether `line` (one the student wrote, or one an edit rewrites) reads as a reference line.
  // A declaration may align a name not yet aligned: an edit that mends the line declaring it
  // makes it read as the reference's.
  bool reads_as_reference(std::string_view line) const;

  // The reference's name for the student's local `name`: the one it aligns with, itself where both
  // programs declare it, the one `line` (an edit's line, which may mend its declaration) aligns
  // it with, or else the one it stands in for where the student uses it (`stands_for`); empty
  // where none does or the places disagree. `guessed`, where given, says whether the answer rests
  // on a use beside a local neither program had aligned (`dot(a, b)` as `dot(V, R)`: the order
  // alone says which is which) or on the one left beside such a guess: good enough to order a
  // search, whose renders confirm it, never to say what the student's local is.
  std::string reference_name(std::string_view name, std::string_view line, bool* guessed = nullptr) const;

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

  // The reference's local `name` stands in for where no declaration aligns it: at every place the
  // student writes it, the reference's local at the place of a line whose tokens around it (two
  // either side, names aligned) read alike, where those places agree on one: `dot(toEye,
  // mirrored)` against `dot(V, R)`, mirrored aligned with R.
  // With `unaligned_too`, a neighbour two locals neither program has aligned yet counts as alike
  // (`beside_unaligned`, a guess): `dot(viewDir, reflectDir)` against `dot(V, R)` where both lines
  // declaring them were changed (V from the eye, the half vector); the places must still agree.
  enum class Neighbours { aligned, unaligned_too };
  std::string stands_for(std::string_view name, bool* guessed, Neighbours neighbours) const;
  bool alike_around(const Tokens& student, size_t at, const Tokens& reference, size_t reference_at, Neighbours neighbours,
                    bool& beside_unaligned) const;
  bool same_token(const std::string& student, const std::string& reference) const;
  // A local one program declares that no declaration, use or lone pairing has aligned yet.
  bool student_unaligned(const std::string& student) const;
  bool reference_unaligned(const std::string& reference) const;
  bool align_lone_local(const StageTokens& student, const StageTokens& reference,
                        const std::function<bool(std::pair<std::string, std::string>)>& align);

  std::vector<Tokens> reference_lines_, student_lines_;
  Names names_;
  std::set<std::string, std::less<>> guessed_;  // the student's locals aligned by a guess (reference_name)
};

}  // namespace shadelab::repair
