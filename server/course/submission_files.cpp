#include "course/submission_files.h"

#include "core/words.h"

#include <algorithm>

namespace shadelab::course {

namespace fs = std::filesystem;

namespace {

// The shallowest folder holding STEM_vert.js and STEM_frag.js.
std::optional<std::pair<fs::path, fs::path>> pair_named(const std::vector<fs::path>& files, const std::string& stem) {
  for (const auto& vert : files) {
    if (vert.filename() != stem + "_vert.js") continue;
    const fs::path frag = vert.parent_path() / (stem + "_frag.js");
    if (std::find(files.begin(), files.end(), frag) != files.end()) return std::pair{vert, frag};
  }
  return std::nullopt;
}

std::vector<std::string> stems(const Course& course, const Checkpoint& c) {
  std::vector<std::string> out = {c.name};
  for (const auto& a : course.aliases)
    if (a.checkpoint == c.name) out.push_back(a.name);
  if (!c.code.empty()) out.push_back(c.code);
  return out;
}

std::optional<std::pair<fs::path, fs::path>> pair_by_stems(const Course& course, const Checkpoint& c, const std::vector<fs::path>& files) {
  for (const auto& stem : stems(course, c))
    if (auto pair = pair_named(files, stem)) return pair;
  return std::nullopt;
}

}  // namespace

std::vector<CheckpointFiles> plan_checkpoints(const Course& course, const std::vector<fs::path>& files) {
  std::vector<CheckpointFiles> plan;
  for (const auto& c : course.checkpoints) {
    auto pair = pair_by_stems(course, c, files);
    const bool required = !c.code.empty();
    if (pair || required) plan.push_back({c.name, c.code, required, pair});
  }
  return plan;
}

std::optional<std::pair<fs::path, fs::path>> checkpoint_pair(const Course& course, const Checkpoint& c, const std::vector<fs::path>& files) {
  if (auto pair = pair_by_stems(course, c, files)) return pair;
  std::vector<fs::path> verts, frags;
  for (const auto& f : files) {
    const std::string name = f.filename().string();
    if (name.ends_with("_vert.js")) verts.push_back(f);
    if (name.ends_with("_frag.js")) frags.push_back(f);
  }
  if (verts.size() == 1 && frags.size() == 1) return std::pair{verts[0], frags[0]};
  return std::nullopt;
}

bool SavedFrameFiles::any() const {
  return std::any_of(frames.begin(), frames.end(), [](const auto& f) { return f.has_value(); });
}

std::vector<std::string> SavedFrameFiles::missing(const Course& course, const Checkpoint& c) const {
  std::vector<std::string> out;
  for (size_t k = 0; k < frames.size(); ++k)
    if (!frames[k]) out.push_back(course.frame_file(c.prefix, static_cast<int>(k), "png"));
  return out;
}

SavedFrameFiles saved_frame_files(const Course& course, const Checkpoint& c, const std::vector<fs::path>& files) {
  SavedFrameFiles out;
  out.frames.resize(static_cast<size_t>(course.frames));
  for (const auto& f : files) {  // shallowest first: the first of a name wins
    for (int k = 0; k < course.frames; ++k)
      if (f.filename() == course.frame_file(c.prefix, k, "png") && !out.frames[static_cast<size_t>(k)]) out.frames[static_cast<size_t>(k)] = f;
    // Frames past the count: the page saved one more, or a set of another length.
    for (int k = course.frames; k < course.frames + 100; ++k)
      if (f.filename() == course.frame_file(c.prefix, k, "png")) out.extra.push_back(f);
  }
  return out;
}

std::string wanted_files(const Course& course, const Checkpoint& c) {
  std::string out;
  const auto all = stems(course, c);
  // The homework's own names first: what the student was told to hand in.
  std::vector<std::string> ordered;
  if (!c.code.empty()) ordered.push_back(c.code);
  for (const auto& s : all)
    if (s != c.code) ordered.push_back(s);
  for (size_t i = 0; i < ordered.size(); ++i) {
    const std::string pair = ordered[i] + "_vert.js and " + ordered[i] + "_frag.js";
    out += i == 0 ? pair : i == 1 ? " (or " + pair : ", or " + pair;
  }
  return ordered.size() > 1 ? out + ")" : out;
}

std::string listing(const std::vector<fs::path>& files) {
  if (files.empty()) return "nothing";
  std::vector<std::string> first;
  for (size_t i = 0; i < files.size() && i < 20; ++i) first.push_back(files[i].string());
  const std::string out = comma_list(first);
  return files.size() > 20 ? out + " and " + std::to_string(files.size() - 20) + " more" : out;
}

void sort_submission(std::vector<fs::path>& files) {
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const auto depth = [](const fs::path& p) { return std::distance(p.begin(), p.end()); };
    return std::pair(depth(a), a.string()) < std::pair(depth(b), b.string());
  });
}

const fs::path* file_at(const std::vector<fs::path>& files, const std::string& path) {
  const fs::path* found = nullptr;
  for (const auto& f : files) {
    const std::string p = f.generic_string();
    if ((p == path || p.ends_with("/" + path)) && (!found || std::distance(f.begin(), f.end()) < std::distance(found->begin(), found->end())))
      found = &f;
  }
  if (found) return found;
  const std::string name = fs::path(path).filename().generic_string();
  for (const auto& f : files)
    if (f.generic_string() == name) return &f;
  return nullptr;
}

}  // namespace shadelab::course
