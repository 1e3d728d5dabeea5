#include "repair/program_reading.h"

namespace shadelab::repair {

struct ProgramReading::Text {
  std::string student_vertex, student_fragment, their_vertex, their_fragment;
  StageTokens vertex{student_vertex, shader::Stage::vertex}, fragment{student_fragment, shader::Stage::fragment};

  Text(StagePair student, StagePair theirs)
      : student_vertex(student.vertex), student_fragment(student.fragment), their_vertex(theirs.vertex), their_fragment(theirs.fragment) {}
};

namespace {

StageLiveness liveness_of(const StageTokens& s, const std::set<std::string, std::less<>>* fragment_reads) {
  return fragment_reads ? vertex_liveness(s, *fragment_reads) : fragment_liveness(s);
}

}  // namespace

std::string with_edit(std::string_view glsl, const RepairEdit& edit) {
  std::string out(glsl.substr(0, edit.begin));
  out += edit.with;
  out += glsl.substr(edit.end);
  return out;
}

std::string edited_line(std::string_view glsl, const RepairEdit& edit) {
  const std::string edited = with_edit(glsl, edit);
  const size_t start = edited.rfind('\n', edit.begin == 0 ? 0 : edit.begin - 1);
  const size_t from = start == std::string::npos || edit.begin == 0 ? 0 : start + 1;
  const size_t to = edited.find('\n', edit.begin + edit.with.size());
  std::string line = edited.substr(from, to == std::string::npos ? std::string::npos : to - from);
  const size_t indent = line.find_first_not_of(" \t");
  return indent == std::string::npos ? std::string() : line.substr(indent);
}

StageReading::StageReading(const StageTokens& student_tokens, std::string_view their_glsl,
                           const std::set<std::string, std::less<>>* fragment_reads)
    : student(student_tokens),
      theirs(their_glsl, student_tokens.stage),
      lines(shader::lines_of(student_tokens.glsl)),
      aligned(student, theirs),
      liveness(liveness_of(student, fragment_reads)) {}

std::string_view StageReading::line_of(const RepairEdit& edit) const {
  return edit.line >= 1 && static_cast<size_t>(edit.line) <= lines.size() ? lines[static_cast<size_t>(edit.line) - 1] : std::string_view();
}

ProgramReading::ProgramReading(StagePair student, StagePair theirs) : ProgramReading(std::make_unique<const Text>(student, theirs)) {}

ProgramReading::ProgramReading(std::unique_ptr<const Text> text)
    : text_(std::move(text)),
      fragment(text_->fragment, text_->their_fragment, nullptr),
      vertex(text_->vertex, text_->their_vertex, &fragment.liveness.live_names) {}

ProgramReading::ProgramReading(ProgramReading&&) noexcept = default;
ProgramReading::~ProgramReading() = default;

Expected<ProgramReading> ProgramReading::within(StagePair student, StagePair theirs, size_t max_tokens) {
  auto text = std::make_unique<const Text>(student, theirs);
  for (const StageTokens* stage : {&text->vertex, &text->fragment})
    if (stage->size() > max_tokens)
      return Error{ErrorCode::payload_too_large, "the " + std::string(to_string(stage->stage)) + " stage holds " + std::to_string(stage->size()) +
                                                     " tokens, and the repair search reads at most " + std::to_string(max_tokens) + " a stage"};
  return ProgramReading(std::move(text));
}

}  // namespace shadelab::repair
