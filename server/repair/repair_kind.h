#pragma once
// The kinds of repair edit as one table (repair_kind.cpp), in the manner of model/lighting.h: per
// kind its name, where the search finds it, what it reads and inserts, and its words. Adding a
// kind is one row there plus its finder.
#include <optional>
#include <string>
#include <string_view>

#include "shader/shader_source.h"

namespace shadelab::repair {

// What an edit does, in the order "smallest" breaks its ties (docs/grading.md, "Repairs"); the
// table's rows are in this order, checked at compile time.
enum class RepairKind {
  normalised,        // vec3 L = X;  ->  vec3 L = normalize(X);
  unnormalised,      // normalize(X)  ->  X
  clamped,           // dot(V, R)  ->  max(0.0, dot(V, R))
  // What a student left out, put back at their own line (repair/left_out_edits.h):
  factor_added,      // uDiffuseColor * max(...)  ->  uDiffuseColor * uLightColor * max(...): a factor the reference multiplies by
  term_added,        // color = D;  ->  color = uAmbientColor + D;  a uniform the reference adds and the student never reads
  exponent_added,    // max(dot(V, R), 0.0)  ->  pow(max(dot(V, R), 0.0), specularAlpha)
  guard_added,       // { ... }  ->  if (dot(N, L) > 0.0) { ... }: the reference's condition, in the student's names
  value_added,       // float spec = pow(...); never read  ->  ...; color += uSpecularColor * uLightColor * spec;  the reference's term
  swizzle_removed,   // color.bgra  ->  color
  direction_w,       // vec4(n, 1.0)  ->  vec4(n, 0.0), and the other way
  negation_removed,  // -X  ->  X
  negation_added,    // reflect(L, N)  ->  reflect(-L, N); vec3 V = X  ->  vec3 V = -X
  operator_swapped,  // A + B  ->  A - B, and the other way (+= and -= too)
  factor_removed,    // 0.5 * uLightPosition  ->  uLightPosition; M * P  ->  P for a matrix M
  term_removed,      // uLightPosition + vec3(0.0, 4.0, 0.0)  ->  uLightPosition
  matrix_added,      // aVertexNormal  ->  uMeshToWorldRotMatrix * aVertexNormal (a matrix uniform)
  literal_refit,     // max(0.5, X)  ->  max(0.0, X): a number the reference never writes, as one it does
  name_replaced,     // uDiffuseColor  ->  uSpecularColor (a uniform, an input or a local of the same type)
  arguments_swapped, // reflect(N, -L)  ->  reflect(-L, N), where the order matters
  flat_removed,      // flat out vec3 vNormal; and flat in vec3 vNormal;  ->  both interpolated (one edit of two stages)
  statement_restored,// an output the stage never writes: the reference's assignment to it, where it stands there
  write_restored,    // color += X; left out, where the stage writes color otherwise alike: the reference's write, where it stands there
  value_restored,    // vec3 R = normalize(L + V);  ->  the reference's value of R, where each writes R alike
  condition_restored,// if (true)  ->  the reference's condition, where the two have as many ifs
};

// Where the search finds a kind's edits, and so what they read.
enum class Found {
  in_student_text,   // the student's own tokens changed (repair/repair_edits.cpp): reads nothing of the reference
  reference_number,  // a number of the student's as one the reference writes (repair/reference_edits.cpp)
  formula,           // what the student left out, put back as the reference's formula has it (repair/left_out_edits.cpp)
  reference_text,    // the reference's own text written in (repair/reference_edits.cpp): named, never shown as a line
};

// What an edit's words are made of: its subject as written ("`L`"), that with what the course
// names it where it does ("`L`, the direction to the light,"), the course's name alone, the symbol
// a class is counted by ("L", else the subject as written), and what the edit says beside its
// subject (repair/repair_edit.h's fields of the same names).
struct Said {
  std::string name, named;
  std::string_view meaning;
  std::string symbol;
  shader::Stage stage;
  std::string subject, other, homework_matrix;
  bool constant_value;
  // value_restored: another of the formula's vectors whose value the student's holds at every
  // pixel drawn (repair/value_probes.h), its words and its symbol: "the direction to the light", "L".
  std::string_view holds, holds_symbol;
};

struct RepairKindInfo {
  RepairKind kind;
  std::string_view name;  // in a report: "normalised"
  Found found;
  // A statement of its own rather than a change to one of the student's: its line is aligned by
  // what it writes, never passed over as a line that already reads as the reference's.
  bool inserts_statement;
  // Puts back what reads another line (a term, a statement, a power): paired with each edit of a
  // line only it could make live, a mistake the missing part hid.
  bool makes_live;
  std::string (*words)(const Said&);  // for the student: "`L` is not normalised: ..."
  std::string (*label)(const Said&);  // for a class's count, alike for every student: "L not normalised"
};

const RepairKindInfo& info(RepairKind kind);
std::string_view to_string(RepairKind kind);
std::optional<RepairKind> repair_kind_named(std::string_view name);

// Such an edit writes the reference's own text: it is named, never shown as a repaired line.
inline bool writes_reference_text(RepairKind kind) { return info(kind).found == Found::reference_text; }
// Such an edit puts back what the student left out, read from the reference's formula: the
// student's line aligned with the reference's by what it lacks.
inline bool puts_back(RepairKind kind) { return info(kind).found == Found::formula; }
// Such an edit reads the reference: the search counts these apart from the student's own edits
// (road::RepairBudget).
inline bool reads_reference(RepairKind kind) { return info(kind).found != Found::in_student_text; }
inline bool inserts_statement(RepairKind kind) { return info(kind).inserts_statement; }
inline bool makes_live(RepairKind kind) { return info(kind).makes_live; }

}  // namespace shadelab::repair
