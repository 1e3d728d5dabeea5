#pragma once
// The shadelab subcommands. Each registers its flags on the CLI11 app and returns the function
// that runs it; main() only parses and dispatches.
#include <functional>

#include <CLI/CLI.hpp>

namespace shadelab::cli {

using Command = std::function<int()>;

Command add_render_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_serve_command(CLI::App& app);
Command add_worker_command(CLI::App& app);
Command add_grade_command(CLI::App& app);
Command add_scene_command(CLI::App& app);
Command add_dolly_command(CLI::App& app);

}  // namespace shadelab::cli
