// shadelab: renders homework GLSL shaders headless. `shadelab --help` lists the subcommands.
#include <iostream>

#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"ShadeLab: renders student WebGL2 shaders headless, as the homework page would"};
  app.require_subcommand(1);
  const auto render = shadelab::cli::add_render_command(app);
  const auto info = shadelab::cli::add_info_command(app);
  const auto serve = shadelab::cli::add_serve_command(app);
  const auto worker = shadelab::cli::add_worker_command(app);
  const auto grade = shadelab::cli::add_grade_command(app);
  const auto autograde = shadelab::cli::add_autograde_command(app);
  const auto prairielearn = shadelab::cli::add_prairielearn_command(app);
  const auto sheet = shadelab::cli::add_sheet_command(app);
  const auto scene = shadelab::cli::add_scene_command(app);
  const auto dolly = shadelab::cli::add_dolly_command(app);
  const auto course = shadelab::cli::add_course_command(app);
  CLI11_PARSE(app, argc, argv);
  if (app.got_subcommand("render")) return render();
  if (app.got_subcommand("info")) return info();
  if (app.got_subcommand("serve")) return serve();
  if (app.got_subcommand("worker")) return worker();
  if (app.got_subcommand("grade")) return grade();
  if (app.got_subcommand("autograde")) return autograde();
  if (app.got_subcommand("prairielearn")) return prairielearn();
  if (app.got_subcommand("sheet")) return sheet();
  if (app.got_subcommand("scene")) return scene();
  if (app.got_subcommand("dolly")) return dolly();
  if (app.got_subcommand("course")) return course();
  return 2;
}
