#pragma once
// A student's notebook (the course's notebook.file: HW2.ipynb) read for what they wrote: compared line by line with the notebook the
// course handed out, each line they added is theirs, and belongs to the question whose place it
// was added in (after its text, where its placeholder was, or in a cell after it). So an answer
// written in the question's own cell is found, a question's own words are never an answer, and a
// placeholder left as handed out reads as unanswered. Without a handed-out notebook, or with a
// notebook that does not follow it, each answer is the cells under its question (notebook.h), and
// the reading says so.
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"
#include "course/course.h"

namespace shadelab::sheet {

// How an answer was found, or why there is none.
enum class AnswerFound {
  written,          // the student's lines
  under_question,   // the cells under the question (read without the handed-out notebook)
  placeholder_left, // the placeholder is as handed out
  none_written,     // nothing added, the placeholder gone
  question_removed, // the question's text is not in the student's notebook
  not_found,        // read without the handed-out notebook: no cell asks it, or nothing under it
};
// What the sheet says in place of an answer that is not there, naming the course's notebook
// (Course::notebook_name); empty for the two that are.
std::string words_for(AnswerFound found, std::string_view notebook);

struct NotebookAnswer {
  std::string question;  // quoted from the handed-out notebook; else the profile's words
  std::string text;      // what the student wrote, line by line
  AnswerFound found = AnswerFound::not_found;
};

struct NotebookReading {
  std::vector<NotebookAnswer> answers;  // one for each of the course's questions, in its order
  std::string note;                     // why the notebook was read without the handed-out one; empty when it was not
};

// The course's questions as the handed-out notebook asks them; the profile's words for a question
// it does not place, or without one.
std::vector<std::string> quoted_questions(const course::Course& course);

// invalid_argument when `ipynb` is not a notebook.
Expected<NotebookReading> read_notebook(const std::string& ipynb, const course::Course& course);

}  // namespace shadelab::sheet
