#include "course/notebook_import.h"

#include <fstream>
#include <iterator>

#include "course/notebook_lines.h"

namespace shadelab::course {

namespace {

using nlohmann::json;

std::vector<Question> questions_of(const json& section) {
  std::vector<Question> out;
  for (const auto& q : section.value("questions", json::array()))
    out.push_back({q.value("id", ""), q.value("text", ""), q.value("cell", ""), q.value("renderColours", "")});
  return out;
}

// Each placed question as the profile writes it: the built-in question it is, else a new one whose
// `cell` words are its first line.
json questions_from(const std::vector<NotebookLine>& lines, const std::vector<PlacedQuestion>& placed, const json& builtin) {
  const std::vector<Question> known = questions_of(builtin);
  const std::vector<int> at = match_questions(known, placed);
  json out = json::array();
  for (size_t p = 0; p < placed.size(); ++p) {
    json q = {{"id", "q" + std::to_string(p + 1)}, {"text", placed[p].text}, {"cell", lines[placed[p].first].text}};
    for (size_t k = 0; k < known.size(); ++k)
      if (at[k] == static_cast<int>(p)) {
        q["id"] = known[k].id, q["cell"] = known[k].cell;
        if (!known[k].render_colours.empty()) q["renderColours"] = known[k].render_colours;
      }
    out.push_back(std::move(q));
  }
  return out;
}

}  // namespace

std::optional<FolderNotebook> folder_notebook(const std::filesystem::path& root, const std::vector<std::filesystem::path>& files,
                                             const std::string& preferred) {
  const std::filesystem::path* found = nullptr;
  for (const auto& f : files)
    if (!preferred.empty() && f.filename() == preferred && !found) found = &f;
  for (const auto& f : files)
    if (!found && f.extension() == ".ipynb" && f.generic_string().find(".ipynb_checkpoints") == std::string::npos) found = &f;
  if (!found) return std::nullopt;
  std::ifstream in(root / *found, std::ios::binary);
  return FolderNotebook{found->generic_string(), {std::istreambuf_iterator<char>(in), {}}};
}

ImportedNotebook import_notebook(const std::optional<FolderNotebook>& notebook, const json& builtin, const std::string& kept_name) {
  ImportedNotebook out{builtin, std::nullopt, {}, {}};
  const std::string placeholder = builtin.value("placeholder", HandedOutNotebook{}.placeholder);
  if (!notebook) {
    out.assumed.push_back("the notebook's questions and the built-in course's handed-out notebook (no .ipynb in the folder)");
    return out;
  }
  auto cells = notebook_cells(notebook->text);
  const std::vector<NotebookLine> lines = cells ? notebook_lines(*cells) : std::vector<NotebookLine>{};
  auto placed = cells ? placed_questions(lines, placeholder) : Expected<std::vector<PlacedQuestion>>(cells.take_error());
  if (!placed || placed->empty()) {
    out.assumed.push_back("the built-in course's notebook questions: " + notebook->path + " " +
                          (placed ? "marks no answer's place with '" + placeholder + "'" : placed.error().message));
    return out;
  }
  out.section["handedOut"] = kept_name;
  out.section["file"] = std::filesystem::path(notebook->path).filename().string();  // as students hand it in
  out.section["questions"] = questions_from(lines, *placed, builtin);
  out.kept = {kept_name, notebook->text};
  out.found.push_back(std::to_string(placed->size()) + " questions, each before a '" + placeholder + "' (" + notebook->path +
                      ", kept as " + kept_name + ")");
  return out;
}

}  // namespace shadelab::course
