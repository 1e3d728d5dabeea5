#pragma once
// Reading and writing course profiles (docs/course-profile.md, docs/course-profile.schema.json).
//
// A profile names its files (meshes, shaders) by paths relative to its own folder, or as
// "builtin:PATH" for a file compiled into the binary ("builtin:assets/bunny.obj"). The built-in
// profile sits in courses/ and names the repository's files relatively, so it reads the same
// from the binary and from a checkout.
//
// Every problem is an invalid_course error that names the field and the reason:
// "checkpoints[2].mistakes[1].edits[0].find: 'if (NdotL > 0.0) {' is not in specular_frag.js".
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "course/course.h"

namespace shadelab::course {

// Where a profile's relative paths are read: a folder on disk, or the binary's embedded files.
struct FileSource {
  // The bytes of `path` (relative to the profile, or "builtin:..."), and whether they are
  // embedded; an error in words ("no such file") when there are none.
  struct Read {
    std::string bytes;
    bool embedded = false;
    std::string resolved;  // the embedded path, or the file's path on disk
  };
  std::function<Expected<Read>(const std::string& path)> read;
};

// How a read file is named in a portable profile: "builtin:shaders/x.js", or its path.
std::string source_of(const FileSource::Read& read);

FileSource embedded_source(const std::string& folder);  // "courses": the built-in profile's folder
FileSource folder_source(const std::filesystem::path& folder);

Expected<Course> read_course(const std::string& json_text, const FileSource& files, const std::string& origin);
Expected<Course> load_course_file(const std::filesystem::path& path);

// The offering the handout describes, compiled in (courses/cs148-summer2022.json).
const Course& builtin_course();
inline constexpr const char* kBuiltinCoursePath = "courses/cs148-summer2022.json";
// The format a profile declares (`format`): the one this ShadeLab reads and writes.
inline constexpr const char* kCourseFormat = "shadelab-course-1";

// The profile as its format writes it: read_course(to_json(c)) gives c back, field for field.
// `portable`: each file named by where it was read ("builtin:assets/bunny.obj", or an absolute
// path) instead of as the profile wrote it, so the JSON loads from any folder.
nlohmann::json to_json(const Course& course, bool portable = false);

}  // namespace shadelab::course
