#include "course/code_question.h"

#include "core/words.h"

namespace shadelab::course {

namespace {

// The student's program, or the preset's when the question names one the viewer may see.
Expected<Program> program_of(const Course& c, CodeQuestion& q, const Viewer& viewer, std::vector<std::string>& notes) {
  if (q.preset.empty()) return std::move(*q.code);
  auto found = find_visible_preset(c, q.preset, viewer);
  if (!found) return found.take_error();
  if (found->alias) notes.push_back(found->alias->note);
  return Program{found->preset->vertex, found->preset->fragment};
}

}  // namespace

Expected<CodeAnswer> answer(const Course& c, CodeQuestion q, const Viewer& viewer) {
  if (q.checkpoint.empty() == !q.own_reference)
    return make_error(ErrorCode::invalid_argument, "give either 'reference' (a checkpoint: " + comma_list(c.checkpoint_names()) +
                                                       ") or 'referenceVertex' and 'referenceFragment'");
  CodeAnswer out;
  auto program = program_of(c, q, viewer, out.notes);
  if (!program) return program.take_error();
  out.request = c.render_request(std::move(program->vertex), std::move(program->fragment));
  if (q.own_reference) {
    out.spec = c.own_reference_spec(std::move(q.own_reference->vertex), std::move(q.own_reference->fragment));
  } else {
    auto found = c.checkpoint(q.checkpoint);
    if (!found) return found.take_error();
    if (found->alias) out.notes.push_back(found->alias->note);
    out.vectors = vector_words(*found->checkpoint);
    out.spec = c.grade_spec(*found->checkpoint, c.grade_options(*found->checkpoint));
  }
  if (!q.mesh) return out;
  auto mesh = c.find_mesh(*q.mesh);
  if (!mesh) return mesh.take_error();
  out.mesh = *mesh;
  return out;
}

}  // namespace shadelab::course
