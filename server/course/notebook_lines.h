#pragma once
// A Jupyter notebook (nbformat 4) as the lines a person wrote in it, and the handed-out notebook's
// questions found by its placeholders. Never executed: code cells are kept as one marker each, so
// that two notebooks line up cell for cell whatever their code says (students change the staff's
// `images_soln/` paths), and their outputs are never read.
#include <string>
#include <vector>

#include "core/expected.h"
#include "course/course.h"

namespace shadelab::course {

struct NotebookCell {
  std::string type;  // markdown, raw, code
  std::string text;
};

// The cells of `ipynb`; invalid_argument when it is not a notebook (JSON with a "cells" array).
Expected<std::vector<NotebookCell>> notebook_cells(const std::string& ipynb);

struct NotebookLine {
  std::string text;  // trimmed; a code cell's is kCodeCell
  size_t cell = 0;
  bool heading() const { return text.starts_with("#"); }
  bool code() const;
};
inline constexpr const char* kCodeCell = "\x01(code cell)";

// The non-blank lines of the markdown and raw cells, a code cell as one kCodeCell line.
std::vector<NotebookLine> notebook_lines(const std::vector<NotebookCell>& cells);

// A question of the handed-out notebook: the text before a placeholder, back to the previous
// placeholder or its cell's start (headings left out), and the lines that are the question's to
// answer in: from its first line to the next question's, or to the end of its cell.
struct PlacedQuestion {
  std::string text;              // its lines, joined by spaces
  size_t first = 0;              // its first line (into notebook_lines)
  size_t placeholder_begin = 0;  // the placeholder's lines: its fence and the placeholder itself
  size_t placeholder_end = 0;
  size_t end = 0;                // one past the last line an answer to it may be written among
};

// The questions of a handed-out notebook, in its order; invalid_argument when a placeholder has
// no text before it.
Expected<std::vector<PlacedQuestion>> placed_questions(const std::vector<NotebookLine>& lines, const std::string& placeholder);

// How many words (4 letters or more, case ignored) `a` and `b` share.
size_t words_shared(const std::string& a, const std::string& b);

// Which placed question each of `questions` is: the one whose text holds its `cell` words, of
// several the one sharing most words with its text. -1 where none holds them (or `cell` is empty).
std::vector<int> match_questions(const std::vector<Question>& questions, const std::vector<PlacedQuestion>& placed);

}  // namespace shadelab::course
