#pragma once
// The student's program read once beside another program that passes (the course's reference, or
// a classmate's): each stage's tokens and lines, the student's locals aligned with the other's
// (repair/aligned_lines.h), and which statements can reach what the program draws
// (repair/live_statements.h). Every finder, and the words of a confirmed repair, read what is
// kept here: a search reads each stage into tokens once, never its text again.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"
#include "repair/aligned_lines.h"
#include "repair/live_statements.h"
#include "repair/stage_tokens.h"

namespace shadelab::repair {

// `glsl` with `edit` made.
std::string with_edit(std::string_view glsl, const RepairEdit& edit);

// The line `edit` is on, as it reads after the edit.
std::string edited_line(std::string_view glsl, const RepairEdit& edit);

// One of the student's stages read beside the other program's.
struct StageReading {
  const StageTokens& student;           // the reading's own, read first
  StageTokens theirs;
  std::vector<std::string_view> lines;  // the student's, split once
  AlignedLines aligned;                 // the student's locals named as the other program names them
  StageLiveness liveness;

  StageReading(const StageTokens& student_tokens, std::string_view their_glsl, const std::set<std::string, std::less<>>* fragment_reads);

  // The student's line `edit` changes, as they wrote it; and as it reads after the edit.
  std::string_view line_of(const RepairEdit& edit) const;
  std::string edited_line(const RepairEdit& edit) const { return repair::edited_line(student.glsl, edit); }
  // Whether the student wrote the edit's line as the other program writes it (their names for its
  // locals aside); whether it reads so once the edit is made.
  bool written_as_theirs(const RepairEdit& edit) const { return aligned.reads_as_reference(line_of(edit)); }
  bool reads_as_theirs_after(const RepairEdit& edit) const { return aligned.reads_as_reference(edited_line(edit)); }
};

class ProgramReading {
  struct Text;  // both programs' text and the student's tokens, at a fixed address: the rest views them

 public:
  ProgramReading(StagePair student, StagePair theirs = {});
  ProgramReading(ProgramReading&&) noexcept;
  ~ProgramReading();

  // The same where each of the student's stages holds at most `max_tokens` tokens; otherwise
  // payload_too_large, saying which stage and by how much, and nothing more is read: aligning and
  // finding edits grow with the square of a stage's length.
  static Expected<ProgramReading> within(StagePair student, StagePair theirs, size_t max_tokens);

  const StageReading& operator[](shader::Stage s) const { return s == shader::Stage::vertex ? vertex : fragment; }
  StagePair student() const { return {vertex.student.glsl, fragment.student.glsl}; }
  bool beside_nothing() const { return fragment.theirs.glsl.empty(); }  // a grade without a reference

 private:
  explicit ProgramReading(std::unique_ptr<const Text> text);
  std::unique_ptr<const Text> text_;

 public:
  StageReading fragment, vertex;  // in this order: the vertex stage's liveness is what reaches the outputs the fragment stage reads
};

}  // namespace shadelab::repair
