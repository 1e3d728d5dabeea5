#include "sheet/notebook.h"

#include <algorithm>
#include <cctype>
#include <regex>
#include <set>

#include "core/text.h"
#include "course/notebook_lines.h"

namespace shadelab::sheet {

namespace {

using Cell = course::NotebookCell;

bool is_heading(const Cell& c) { return c.type == "markdown" && trimmed(c.text).starts_with("#"); }

// Which cell asks each question: a markdown cell holding the question's `cell` words, each cell
// for one question. Where words fit more than one cell or question ("blue" is also in "blue-ish
// highlights", and in an answer that says "z is blue"), the pair sharing the most words wins, a
// cell that asks something (a '?') counting as kAsks words more, then the earlier cell.
constexpr size_t kAsks = 3;
std::vector<std::optional<size_t>> question_cells(const std::vector<Cell>& cells, const std::vector<course::Question>& questions) {
  struct Pair {
    size_t shared, question, cell;
  };
  std::vector<Pair> pairs;
  for (size_t q = 0; q < questions.size(); ++q) {
    if (questions[q].cell.empty()) continue;
    for (size_t i = 0; i < cells.size(); ++i) {
      if (cells[i].type != "markdown" || lower_case(cells[i].text).find(lower_case(questions[q].cell)) == std::string::npos) continue;
      const size_t asks = cells[i].text.find('?') != std::string::npos ? kAsks : 0;
      pairs.push_back({asks + course::words_shared(cells[i].text, questions[q].text), q, i});
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.shared > b.shared; });
  std::vector<std::optional<size_t>> at(questions.size());
  std::set<size_t> taken;
  for (const auto& p : pairs)
    if (!at[p.question] && !taken.count(p.cell)) at[p.question] = p.cell, taken.insert(p.cell);
  return at;
}

}  // namespace

Expected<std::vector<std::string>> notebook_answers(const std::string& ipynb, const std::vector<course::Question>& questions) {
  auto read = course::notebook_cells(ipynb);
  if (!read) return read.take_error();
  const std::vector<Cell>& cells = *read;
  const std::vector<std::optional<size_t>> at = question_cells(cells, questions);
  std::vector<std::string> out;
  for (size_t qi = 0; qi < questions.size(); ++qi) {
    std::string answer;
    if (at[qi]) {
      for (size_t i = *at[qi] + 1; i < cells.size(); ++i) {
        const bool another_question = std::find(at.begin(), at.end(), std::optional<size_t>(i)) != at.end();
        if (another_question || is_heading(cells[i])) break;
        if (cells[i].type == "code" || trimmed(cells[i].text).empty()) continue;
        answer += (answer.empty() ? "" : "\n\n") + trimmed(cells[i].text);
      }
      if (answer.empty()) {  // written into the question's own cell, after the question
        const std::string& own = cells[*at[qi]].text;
        const size_t line_end = own.find('\n', lower_case(own).find(lower_case(questions[qi].cell)));
        if (line_end != std::string::npos) answer = trimmed(own.substr(line_end));
      }
    }
    out.push_back(answer);
  }
  return out;
}

std::optional<AnswerColours> colours_in(const std::string& answer) {
  const std::string text = lower_case(answer);
  const std::regex role_name("ambient|diffuse|specular");
  const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+))");
  struct Found {
    std::string role;
    size_t begin, end;
  };
  std::vector<Found> roles;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), role_name); it != std::sregex_iterator(); ++it)
    roles.push_back({it->str(), static_cast<size_t>(it->position()), static_cast<size_t>(it->position() + it->length())});
  AnswerColours out;
  bool have[3] = {false, false, false};
  for (size_t i = 0; i < roles.size(); ++i) {
    const size_t stop = i + 1 < roles.size() ? roles[i + 1].begin : text.size();
    // Words out first: the 4 of "vec4" is not a colour.
    const std::string span = std::regex_replace(text.substr(roles[i].end, stop - roles[i].end), std::regex("[a-z_][a-z0-9_]*"), " ");
    std::vector<double> values;
    for (auto it = std::sregex_iterator(span.begin(), span.end(), number); it != std::sregex_iterator() && values.size() < 3; ++it)
      values.push_back(std::stod(it->str()));
    const int slot = roles[i].role == "ambient" ? 0 : roles[i].role == "diffuse" ? 1 : 2;
    if (values.size() < 3 || have[slot]) continue;
    const bool bytes = std::any_of(values.begin(), values.end(), [](double v) { return v > 1; });
    std::array<double, 3> rgb{};
    for (size_t c = 0; c < 3; ++c) rgb[c] = std::clamp(bytes ? values[c] / 255.0 : values[c], 0.0, 1.0);
    (slot == 0 ? out.ambient : slot == 1 ? out.diffuse : out.specular) = rgb;
    have[slot] = true;
  }
  if (!have[0] || !have[1] || !have[2]) return std::nullopt;
  return out;
}

}  // namespace shadelab::sheet
