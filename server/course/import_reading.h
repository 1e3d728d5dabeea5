#pragma once
// Reading a homework folder for `course import` (course/course_import.h): its files found by name,
// shallowest first, and what a page's script holds (a list of numbers after a name, a {...}
// block, the homework quantity a uniform's name means), read as text: the import never runs the
// page.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "course/course.h"

namespace shadelab::course {

std::string read_text(const std::filesystem::path& p);

// A number as a course profile and a shader write it: 6.0, 0.25, 1e-05.
std::string literal_number(double v);

// The homework folder's files, relative to it, shallowest first.
struct Folder {
  std::filesystem::path root;
  std::vector<std::filesystem::path> files;

  explicit Folder(std::filesystem::path r);
  std::optional<std::filesystem::path> named(const std::string& name) const;
  std::string text(const std::filesystem::path& relative) const { return read_text(root / relative); }
};

// The numbers of the first bracketed list ([...] or (...)) at or after `at`, up to its close.
std::vector<double> numbers_after(const std::string& s, size_t at);

// The text of the {...} block that opens at or after `at`.
std::string block_after(const std::string& s, size_t at);

// Which homework quantity a uniform's (or a value's) name is, by the words in it.
std::optional<UniformRole> role_of(const std::string& name);

// uAmbientColor -> ambientColor: the other spelling the handout allows.
std::string plain_spelling(const std::string& name);

// The name hw2.js would use for `role` when it does not look it up yet (the students' TODO for
// diffuse and specular): as it names ambient, with the role's word in place ("uDiffuseColor").
std::string name_like_ambient(const std::map<UniformRole, std::string>& names, UniformRole role);

// `file` as a path relative to the folder `output` is written in.
std::string path_from(const std::filesystem::path& file, const std::filesystem::path& output);

}  // namespace shadelab::course
