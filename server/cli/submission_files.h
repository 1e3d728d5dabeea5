#pragma once
// The files of a student's submission on disk, for the CLI: course/submission_files.h says which
// are which checkpoint's.
#include <filesystem>
#include <vector>

#include "course/submission_files.h"

namespace shadelab::cli {

// Every file under `root`, relative to it, in course::sort_submission's order; macOS archive litter
// (__MACOSX/, ._name), hidden files and symbolic links are not the student's (a link could make
// the grader read a file of the image).
std::vector<std::filesystem::path> submitted_files(const std::filesystem::path& root);

}  // namespace shadelab::cli
