#include "grade/submission_files.h"

#include <algorithm>

namespace shadelab::grade {

namespace fs = std::filesystem;

namespace {

struct Known {
  const char* name;
  std::optional<std::string> homework_stem;
  bool required;
};
const Known kCheckpoints[] = {
    {"smooth", std::nullopt, false}, {"gouraud", "starter", true}, {"diffuse", std::nullopt, false}, {"specular", "phong", true}};

// The shallowest folder holding STEM_vert.js and STEM_frag.js.
std::optional<std::pair<fs::path, fs::path>> pair_named(const std::vector<fs::path>& files, const std::string& stem) {
  for (const auto& vert : files) {
    if (vert.filename() != stem + "_vert.js") continue;
    const fs::path frag = vert.parent_path() / (stem + "_frag.js");
    if (std::find(files.begin(), files.end(), frag) != files.end()) return std::pair{vert, frag};
  }
  return std::nullopt;
}

}  // namespace

std::vector<CheckpointFiles> plan_checkpoints(const std::vector<fs::path>& files) {
  std::vector<CheckpointFiles> plan;
  for (const auto& c : kCheckpoints) {
    auto pair = pair_named(files, c.name);
    if (!pair && c.homework_stem) pair = pair_named(files, *c.homework_stem);
    if (pair || c.required) plan.push_back({c.name, c.homework_stem, c.required, pair});
  }
  return plan;
}

std::string listing(const std::vector<fs::path>& files) {
  if (files.empty()) return "nothing";
  std::string out;
  for (size_t i = 0; i < files.size() && i < 20; ++i) out += (i ? ", " : "") + files[i].string();
  return files.size() > 20 ? out + " and " + std::to_string(files.size() - 20) + " more" : out;
}

void sort_submission(std::vector<fs::path>& files) {
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const auto depth = [](const fs::path& p) { return std::distance(p.begin(), p.end()); };
    return std::pair(depth(a), a.string()) < std::pair(depth(b), b.string());
  });
}

}  // namespace shadelab::grade
