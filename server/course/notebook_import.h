#pragma once
// `course import`'s notebook: the folder's notebook (the built-in course's name for it first) kept beside the profile as the handed-out
// notebook, and the questions read from it (each placeholder's question). A question the built-in
// profile also asks keeps its id and what it renders; the others are q1, q2, ... in the
// notebook's order.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadelab::course {

struct FolderNotebook {
  std::string path;  // in the folder: HW2.ipynb
  std::string text;
};

// The folder's notebook: the one named `preferred` (the built-in course's notebook.file), else the
// first .ipynb of `files` (relative to `root`, the shallowest first), Jupyter's checkpoint copies
// aside; none when it has no notebook.
std::optional<FolderNotebook> folder_notebook(const std::filesystem::path& root, const std::vector<std::filesystem::path>& files,
                                             const std::string& preferred);

struct ImportedNotebook {
  nlohmann::json section;                                  // the profile's "notebook"
  std::optional<std::pair<std::string, std::string>> kept;  // the file to write beside the profile (name, text)
  std::vector<std::string> found, assumed;
};

// `builtin` is the built-in profile's notebook section (portable form); `kept_name` the file name
// the notebook is kept under, beside the profile.
ImportedNotebook import_notebook(const std::optional<FolderNotebook>& notebook, const nlohmann::json& builtin, const std::string& kept_name);

}  // namespace shadelab::course
