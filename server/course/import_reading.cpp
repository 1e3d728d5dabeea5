#include "course/import_reading.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>

#include "core/text.h"

namespace shadelab::course {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string literal_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, v == std::floor(v) && std::abs(v) < 1e9 ? "%.1f" : "%g", v);
  return buf;
}

Folder::Folder(fs::path r) : root(std::move(r)) {
  for (const auto& e : fs::recursive_directory_iterator(root, fs::directory_options::skip_permission_denied))
    if (e.is_regular_file() && !e.is_symlink()) files.push_back(fs::relative(e.path(), root));
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const auto depth = [](const fs::path& p) { return std::distance(p.begin(), p.end()); };
    return std::pair(depth(a), a.string()) < std::pair(depth(b), b.string());
  });
}

std::optional<fs::path> Folder::named(const std::string& name) const {
  for (const auto& f : files)
    if (f.filename() == name) return f;
  return std::nullopt;
}

// The numbers of the first bracketed list ([...] or (...)) at or after `at`, up to its close.
std::vector<double> numbers_after(const std::string& s, size_t at) {
  const size_t open = s.find_first_of("[(", at);
  if (open == std::string::npos) return {};
  const size_t close = s.find_first_of("])", open + 1);
  std::vector<double> out;
  static const std::regex number("-?[0-9]*\\.?[0-9]+(?:[eE][-+]?[0-9]+)?");
  const std::string inside = s.substr(open + 1, close == std::string::npos ? std::string::npos : close - open - 1);
  for (std::sregex_iterator it(inside.begin(), inside.end(), number), end; it != end; ++it) out.push_back(std::stod(it->str()));
  return out;
}

// The text of the {...} block that opens at or after `at`.
std::string block_after(const std::string& s, size_t at) {
  const size_t open = s.find('{', at);
  if (open == std::string::npos) return {};
  int depth = 0;
  for (size_t i = open; i < s.size(); ++i) {
    depth += s[i] == '{' ? 1 : s[i] == '}' ? -1 : 0;
    if (depth == 0) return s.substr(open + 1, i - open - 1);
  }
  return {};
}

// Which homework quantity a uniform's (or a value's) name is, by the words in it.
std::optional<UniformRole> role_of(const std::string& name) {
  const std::string n = lower_case(name);
  const auto has = [&](const char* word) { return n.find(word) != std::string::npos; };
  if (has("ambient")) return UniformRole::ambient;
  if (has("diffuse")) return UniformRole::diffuse;
  if (has("specular")) return UniformRole::specular;
  if (has("light") && has("pos")) return UniformRole::light_position;
  if (has("light") && has("col")) return UniformRole::light_color;
  return std::nullopt;
}

// uAmbientColor -> ambientColor: the other spelling the handout allows.
std::string plain_spelling(const std::string& name) {
  if (name.size() > 1 && name[0] == 'u' && std::isupper(static_cast<unsigned char>(name[1])))
    return std::string(1, static_cast<char>(std::tolower(static_cast<unsigned char>(name[1])))) + name.substr(2);
  return {};
}

// The name hw2.js would use for `role` when it does not look it up yet (the students' TODO for
// diffuse and specular): as it names ambient, with the role's word in place ("uDiffuseColor").
std::string name_like_ambient(const std::map<UniformRole, std::string>& names, UniformRole role) {
  const auto ambient = names.find(UniformRole::ambient);
  if ((role != UniformRole::diffuse && role != UniformRole::specular) || ambient == names.end()) return {};
  const std::string& n = ambient->second;
  const size_t at = lower_case(n).find("ambient");
  std::string word(to_string(role));
  if (std::isupper(static_cast<unsigned char>(n[at]))) word[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(word[0])));
  return n.substr(0, at) + word + n.substr(at + 7);
}

std::string path_from(const fs::path& file, const fs::path& output) {
  const fs::path from = fs::absolute(output).parent_path().lexically_normal();
  return fs::absolute(file).lexically_normal().lexically_relative(from).generic_string();
}

}  // namespace shadelab::course
