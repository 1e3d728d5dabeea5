#include "sheet/notebook_reading.h"

#include <dtl/dtl.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/words.h"
#include "course/notebook_lines.h"
#include "sheet/notebook.h"

namespace shadelab::sheet {

namespace {

using course::NotebookLine;
using course::PlacedQuestion;

// A notebook follows the handed-out one when at least this share of the handed-out text is still
// in it, in its order. A student's notebook keeps nearly all of it (they add answers and change
// code, whose cells are markers here); a notebook of another offering or another course keeps
// little, and then its lines cannot say what the student added.
constexpr double kFollowsHandedOut = 0.5;

constexpr std::array<std::pair<AnswerFound, std::string_view>, 6> kAnswerWords{{
    {AnswerFound::written, ""},
    {AnswerFound::under_question, ""},
    {AnswerFound::placeholder_left, "(unanswered: the placeholder is as handed out)"},
    {AnswerFound::none_written, "(unanswered: nothing written in the question's place)"},
    {AnswerFound::question_removed, "(the question is not in {notebook}: its text was removed, and nothing was written in its place)"},
    {AnswerFound::not_found, "(no answer under this question in {notebook})"},
}};

// Where each line of the student's notebook came from: the handed-out line it is (the diff's
// common lines), or none (added by the student).
struct Alignment {
  std::vector<long> handed_out_of;  // per student line: its handed-out line, or -1
  std::vector<bool> kept;           // per handed-out line: still in the student's notebook
};

Alignment align(const std::vector<NotebookLine>& handed_out, const std::vector<NotebookLine>& student) {
  std::vector<std::string> a, b;
  for (const auto& l : handed_out) a.push_back(l.text);
  for (const auto& l : student) b.push_back(l.text);
  dtl::Diff<std::string, std::vector<std::string>> diff(a, b);
  diff.compose();
  Alignment out{std::vector<long>(b.size(), -1), std::vector<bool>(a.size(), false)};
  size_t i = 0, j = 0;  // walked in the edit script's order: its indices differ by edit type
  for (const auto& [line, info] : diff.getSes().getSequence()) {
    if (info.type == dtl::SES_COMMON) out.kept[i] = true, out.handed_out_of[j++] = static_cast<long>(i++);
    else if (info.type == dtl::SES_DELETE) ++i;
    else ++j;
  }
  return out;
}

// The share of the handed-out text still there, placeholders left out: a student removes those.
double share_kept(const std::vector<NotebookLine>& handed_out, const std::vector<PlacedQuestion>& placed, const Alignment& a) {
  std::vector<bool> counted(handed_out.size(), true);
  for (const auto& q : placed) std::fill(counted.begin() + static_cast<long>(q.placeholder_begin), counted.begin() + static_cast<long>(q.placeholder_end), false);
  size_t text = 0, kept = 0;
  for (size_t i = 0; i < handed_out.size(); ++i)
    if (counted[i] && !handed_out[i].code()) ++text, kept += a.kept[i];
  return text == 0 ? 0 : static_cast<double>(kept) / static_cast<double>(text);
}

// The placed question a handed-out line is the place of, or -1.
int place_of(const std::vector<PlacedQuestion>& placed, long line) {
  for (size_t p = 0; p < placed.size(); ++p)
    if (line >= static_cast<long>(placed[p].first) && line < static_cast<long>(placed[p].end)) return static_cast<int>(p);
  return -1;
}

// Each added line goes to the question whose place the handed-out line before it is in.
std::vector<std::string> added_per_place(const std::vector<NotebookLine>& student, const Alignment& a, const std::vector<PlacedQuestion>& placed) {
  std::vector<std::string> out(placed.size());
  long before = -1;
  for (size_t j = 0; j < student.size(); ++j) {
    if (a.handed_out_of[j] >= 0) {
      before = a.handed_out_of[j];
      continue;
    }
    const int p = before < 0 ? -1 : place_of(placed, before);
    if (p >= 0 && !student[j].code()) out[static_cast<size_t>(p)] += (out[static_cast<size_t>(p)].empty() ? "" : "\n") + student[j].text;
  }
  return out;
}

NotebookAnswer answer_at(const PlacedQuestion& q, const Alignment& a, std::string added) {
  NotebookAnswer out{q.text, std::move(added), AnswerFound::written};
  if (!out.text.empty()) return out;
  const auto kept = [&](size_t from, size_t to) { return std::any_of(a.kept.begin() + from, a.kept.begin() + to, [](bool k) { return k; }); };
  out.found = !kept(q.first, q.placeholder_begin) ? AnswerFound::question_removed
              : kept(q.placeholder_begin, q.placeholder_end) ? AnswerFound::placeholder_left
                                                             : AnswerFound::none_written;
  return out;
}

Expected<NotebookReading> under_questions(const std::string& ipynb, const course::Course& course, std::string note) {
  auto answers = notebook_answers(ipynb, course.questions);
  if (!answers) return answers.take_error();
  NotebookReading out{{}, std::move(note)};
  for (size_t q = 0; q < course.questions.size(); ++q)
    out.answers.push_back({course.questions[q].text, (*answers)[q], (*answers)[q].empty() ? AnswerFound::not_found : AnswerFound::under_question});
  return out;
}

}  // namespace

std::string words_for(AnswerFound found, std::string_view notebook) {
  for (const auto& [f, words] : kAnswerWords) {
    if (f != found) continue;
    std::string out(words);
    if (const auto at = out.find("{notebook}"); at != std::string::npos) out.replace(at, 10, notebook);
    return out;
  }
  return {};
}

std::vector<std::string> quoted_questions(const course::Course& course) {
  std::vector<std::string> out;
  for (const auto& q : course.questions) out.push_back(q.text);
  if (!course.handed_out) return out;
  auto cells = course::notebook_cells(course.handed_out->text);
  if (!cells) return out;
  const auto placed = course::placed_questions(course::notebook_lines(*cells), course.handed_out->placeholder);
  if (!placed) return out;
  const std::vector<int> at = course::match_questions(course.questions, *placed);
  for (size_t q = 0; q < out.size(); ++q)
    if (at[q] >= 0) out[q] = (*placed)[static_cast<size_t>(at[q])].text;
  return out;
}

Expected<NotebookReading> read_notebook(const std::string& ipynb, const course::Course& course) {
  auto cells = course::notebook_cells(ipynb);
  if (!cells) return cells.take_error();
  if (!course.handed_out) return under_questions(ipynb, course, "");
  const course::HandedOutNotebook& handed = *course.handed_out;
  auto handed_cells = course::notebook_cells(handed.text);
  if (!handed_cells) return handed_cells.take_error();
  const std::vector<NotebookLine> handed_out = course::notebook_lines(*handed_cells), student = course::notebook_lines(*cells);
  auto placed = course::placed_questions(handed_out, handed.placeholder);
  if (!placed) return placed.take_error();
  const Alignment a = align(handed_out, student);
  if (const double kept = share_kept(handed_out, *placed, a); kept < kFollowsHandedOut)
    return under_questions(ipynb, course,
                           course.notebook_name() + " keeps " + percent(kept) + " of the handed-out notebook's text, so what the student added cannot be told " +
                               "from it: each answer below is the cells under its question, and may include the question's own words");
  const std::vector<std::string> added = added_per_place(student, a, *placed);
  const std::vector<int> at = course::match_questions(course.questions, *placed);
  NotebookReading out;
  for (size_t q = 0; q < course.questions.size(); ++q)
    out.answers.push_back(at[q] < 0 ? NotebookAnswer{course.questions[q].text, "", AnswerFound::not_found}
                                    : answer_at((*placed)[static_cast<size_t>(at[q])], a, added[static_cast<size_t>(at[q])]));
  return out;
}

}  // namespace shadelab::sheet
