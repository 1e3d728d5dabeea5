#pragma once
// A student's Jupyter notebook (HW2.ipynb, nbformat 4) read for their answers: the cells under
// each of the course's questions, and, for a question that asks for colours, the ambient, diffuse
// and specular RGB values they wrote. Never executed; a notebook that is not JSON, or not a
// notebook, answers nothing (the sheet says so), it does not fail the sheet.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "course/course.h"

namespace shadelab::sheet {

// Each of `questions`' answer in the notebook's text, in the questions' order: the markdown and raw
// cells after the markdown cell that asks it (it holds the question's `cell` words; of several, the
// one sharing most words with the question's text, each cell asking one question), up to the next
// question's cell or the next heading; the question cell's own text after the question's words
// when nothing follows. Empty for a question not found. invalid_argument when `ipynb` is not a notebook.
Expected<std::vector<std::string>> notebook_answers(const std::string& ipynb, const std::vector<course::Question>& questions);

// The colours an answer gives: "ambient (0.3, 0.1, 0.4)", "uDiffuseColor = vec4(0.6, 0.2, 0.8, 1.0)",
// "specular: 128, 160, 255" (0-255 when any value passes 1). Each role's first three numbers after
// its name, before the next role's name; nullopt unless all three roles have them.
struct AnswerColours {
  std::array<double, 3> ambient{}, diffuse{}, specular{};
};
std::optional<AnswerColours> colours_in(const std::string& answer);

}  // namespace shadelab::sheet
