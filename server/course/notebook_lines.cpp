#include "course/notebook_lines.h"

#include <algorithm>
#include <cctype>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/client_json.h"
#include "core/text.h"

namespace shadelab::course {

namespace {

using nlohmann::json;

// nbformat keeps a cell's source as one string or as its lines.
std::string source_of(const json& cell) {
  const json& s = cell.value("source", json());
  if (s.is_string()) return s.get<std::string>();
  std::string out;
  if (s.is_array())
    for (const auto& line : s)
      if (line.is_string()) out += line.get<std::string>();
  return out;
}

std::set<std::string> words_of(const std::string& text) {
  std::set<std::string> out;
  const std::string t = lower_case(text);
  static const std::regex word("[a-z0-9]{4,}");
  for (auto it = std::sregex_iterator(t.begin(), t.end(), word); it != std::sregex_iterator(); ++it) out.insert(it->str());
  return out;
}

bool is_fence(const NotebookLine& l) { return l.text.starts_with("```") || l.text.starts_with("~~~"); }

// The placeholder's lines around line `at`: the fence before and after it, when it has one.
std::pair<size_t, size_t> placeholder_span(const std::vector<NotebookLine>& lines, size_t at) {
  size_t begin = at, end = at + 1;
  if (begin > 0 && lines[begin - 1].cell == lines[at].cell && is_fence(lines[begin - 1])) --begin;
  if (end < lines.size() && lines[end].cell == lines[at].cell && is_fence(lines[end])) ++end;
  return {begin, end};
}

size_t cell_end(const std::vector<NotebookLine>& lines, size_t at) {
  const size_t cell = lines[at].cell;
  while (at < lines.size() && lines[at].cell == cell) ++at;
  return at;
}

}  // namespace

bool NotebookLine::code() const { return text == kCodeCell; }

Expected<std::vector<NotebookCell>> notebook_cells(const std::string& ipynb) {
  // A student's notebook: client bytes, read within the budget a request's JSON has.
  if (auto within = check_json_budget(ipynb, "the notebook"); !within) return within.take_error();
  const json nb = json::parse(ipynb, nullptr, false);
  if (nb.is_discarded() || !nb.is_object() || !nb.contains("cells") || !nb["cells"].is_array())
    return make_error(ErrorCode::invalid_argument, "the notebook is not a Jupyter notebook (JSON with \"cells\")");
  std::vector<NotebookCell> cells;
  for (const auto& c : nb["cells"])
    if (c.is_object()) cells.push_back({c.value("cell_type", std::string()), source_of(c)});
  return cells;
}

std::vector<NotebookLine> notebook_lines(const std::vector<NotebookCell>& cells) {
  std::vector<NotebookLine> out;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (cells[i].type == "code") {
      out.push_back({kCodeCell, i});
      continue;
    }
    std::istringstream text(cells[i].text);
    for (std::string line; std::getline(text, line);)
      if (std::string t = trimmed(line); !t.empty()) out.push_back({std::move(t), i});
  }
  return out;
}

Expected<std::vector<PlacedQuestion>> placed_questions(const std::vector<NotebookLine>& lines, const std::string& placeholder) {
  std::vector<PlacedQuestion> out;
  const std::string wanted = lower_case(placeholder);
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].code() || lower_case(lines[i].text).find(wanted) == std::string::npos) continue;
    const auto [begin, end] = placeholder_span(lines, i);
    size_t first = begin;
    const bool after_another = !out.empty() && lines[out.back().placeholder_end - 1].cell == lines[i].cell;
    const size_t floor = after_another ? out.back().placeholder_end : 0;
    while (first > floor && lines[first - 1].cell == lines[i].cell) --first;
    while (first < begin && lines[first].heading()) ++first;
    if (first == begin)
      return make_error(ErrorCode::invalid_argument, "the placeholder on line " + std::to_string(i + 1) + " of the notebook's text has no question before it");
    PlacedQuestion q{"", first, begin, end, cell_end(lines, i)};
    for (size_t k = first; k < begin; ++k) q.text += (q.text.empty() ? "" : " ") + lines[k].text;
    if (after_another) out.back().end = first;
    out.push_back(std::move(q));
    i = end - 1;
  }
  return out;
}

size_t words_shared(const std::string& a, const std::string& b) {
  const auto wa = words_of(a), wb = words_of(b);
  return static_cast<size_t>(std::count_if(wa.begin(), wa.end(), [&](const std::string& w) { return wb.count(w) > 0; }));
}

// Each pair of a question and a placed question whose text holds its `cell` words, the pair
// sharing most words first ("blue" is also in "blue-ish highlights"), each placed question once.
std::vector<int> match_questions(const std::vector<Question>& questions, const std::vector<PlacedQuestion>& placed) {
  struct Pair {
    size_t shared, question, placed;
  };
  std::vector<Pair> pairs;
  for (size_t q = 0; q < questions.size(); ++q)
    for (size_t p = 0; p < placed.size(); ++p)
      if (!questions[q].cell.empty() && lower_case(placed[p].text).find(lower_case(questions[q].cell)) != std::string::npos)
        pairs.push_back({words_shared(placed[p].text, questions[q].text), q, p});
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.shared > b.shared; });
  std::vector<int> out(questions.size(), -1);
  std::vector<bool> taken(placed.size(), false);
  for (const auto& pair : pairs)
    if (out[pair.question] < 0 && !taken[pair.placed]) out[pair.question] = static_cast<int>(pair.placed), taken[pair.placed] = true;
  return out;
}

}  // namespace shadelab::course
