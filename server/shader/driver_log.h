#pragma once
// Turns a driver's info log into Diagnostics located in the student's file. Understands the log
// formats of Mesa (`0:12(5): error: ...`), NVIDIA (`0(12) : error C0000: ...`) and ANGLE
// (`ERROR: 0:12: ...`); lines it cannot place are kept as unlocated diagnostics.
#include <string>
#include <vector>

#include "core/error.h"
#include "shader/shader_source.h"

namespace shadelab::shader {

// `source` is null for link logs, whose messages have no line to map.
std::vector<Diagnostic> parse_driver_log(const std::string& log, std::string_view stage, const std::string& file_name,
                                         const UnwrappedSource* source);

}  // namespace shadelab::shader
