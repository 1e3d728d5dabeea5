#pragma once
// The shadelab subcommands. Each registers its flags on the CLI11 app and returns the function
// that runs it; main() only parses and dispatches.
#include <functional>

#include <CLI/CLI.hpp>

#include "core/error.h"

namespace shadelab::cli {

using Command = std::function<int()>;

// Prints an error as a compiler would (one located line per diagnostic, then the error and its
// code; the driver's log when it said more than the diagnostics) and returns the exit status 1.
int fail(const Error& error);

Command add_render_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_serve_command(CLI::App& app);
Command add_worker_command(CLI::App& app);
Command add_grade_command(CLI::App& app);
Command add_autograde_command(CLI::App& app);
Command add_prairielearn_command(CLI::App& app);
Command add_sheet_command(CLI::App& app);
Command add_scene_command(CLI::App& app);
Command add_dolly_command(CLI::App& app);
Command add_course_command(CLI::App& app);

}  // namespace shadelab::cli
