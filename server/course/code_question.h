#pragma once
// What a code grade asks of its course, asked once (road/code_request.h builds every code
// submission from the answer): the program drawn as the course draws it (the student's own, or a
// preset the viewer may see), what it is graded against (a checkpoint's spec with its tolerance
// and its formula's vectors' words, or the page's own reference at the course's tolerance), and
// the course's mesh it is drawn on.
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "course/access.h"
#include "course/course.h"
#include "grade/formula_vectors.h"
#include "grade/grade_spec.h"
#include "render/render_request.h"
#include "shader/shader_source.h"

namespace shadelab::course {

struct Program {
  shader::ShaderFile vertex, fragment;
};

struct CodeQuestion {
  std::optional<Program> code;           // the student's program...
  std::string preset;                    // ...or a preset of the course, by name
  std::string checkpoint;                // a checkpoint (or an alias of one)...
  std::optional<Program> own_reference;  // ...or the page's own reference ("custom")
  std::optional<std::string> mesh;       // one of the course's meshes (empty: its default); none: the caller's own
};

struct CodeAnswer {
  render::RenderRequest request;  // the program on the course's canvas, frames and page setup
  grade::GradeSpec spec;
  grade::VectorWords vectors;     // the checkpoint's formula's vectors ("V": "the direction to the eye")
  const CourseMesh* mesh = nullptr;
  std::vector<std::string> notes;  // an alias's, where the question used one
};

// The answer, or the Error a name the course does not have (or a preset `viewer` may not see)
// gets; neither or both of a checkpoint and an own reference is invalid_argument.
Expected<CodeAnswer> answer(const Course& course, CodeQuestion question, const Viewer& viewer);

}  // namespace shadelab::course
