#include "cli/submission_files.h"

namespace shadelab::cli {

namespace fs = std::filesystem;

std::vector<fs::path> submitted_files(const fs::path& root) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name == "__MACOSX" || name == "node_modules" || name.starts_with(".")) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    // A symbolic link is not the student's file: starter_vert.js -> /autograder/... would have
    // the grader read, and quote in its diagnostics, a file of the image.
    if (it->is_regular_file() && !it->is_symlink()) files.push_back(fs::relative(it->path(), root));
  }
  course::sort_submission(files);
  return files;
}

}  // namespace shadelab::cli
