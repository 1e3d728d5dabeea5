// shadelab sheet HW2_DIR -o sheet.pdf: the submission sheet the homework's checklist asks for,
// made from the student's folder. Each checkpoint found (course/submission_files.h) is rendered
// (the 3x3 grid) and graded through render workers (sheet/assemble.h), then laid out with its
// code: a PDF (cairo) and, with --html, the same as one HTML page. The same folder gives the
// same bytes.
#include <filesystem>
#include <iostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/course_option.h"
#include "course/course_reader.h"
#include "cli/file_output.h"
#include "cli/grade_runner.h"
#include "cli/submission_files.h"
#include "scene/mesh.h"
#include "scene/scene_mesh.h"
#include "sheet/assemble.h"
#include "sheet/sheet_html.h"
#include "sheet/sheet_pdf.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;

struct SheetFlags {
  GradeFlags grade;
  std::string folder, pdf, html, answers, title;  // empty title: the course's hand-in title
  std::vector<std::string> scenes;
};

// A scene file with the mesh files its objects name (relative to it), as a worker reads them.
Expected<sheet::SceneInput> scene_input(const fs::path& file) {
  auto json = nlohmann::json::parse(read_text(file), nullptr, false);
  if (json.is_discarded()) return make_error(ErrorCode::invalid_argument, "'" + file.string() + "' is not JSON");
  sheet::SceneInput input{file.filename().string(), json, {}};
  if (!json.contains("objects") || !json["objects"].is_array()) return input;  // parse_scene says what is wrong
  for (const auto& o : json["objects"]) {
    const std::string mesh = o.is_object() ? o.value("mesh", "") : "";
    if (mesh.empty() || scene::is_builtin_scene_mesh(mesh)) continue;
    const fs::path path = file.parent_path() / mesh;
    if (fs::is_regular_file(path)) input.meshes.push_back({mesh, scene::mesh_format_of(mesh), read_text(path)});
  }
  return input;
}

int run_sheet(const SheetFlags& f) {
  auto loaded = load_course(f.grade.course);
  if (!loaded) return fail(loaded.error());
  sheet::SheetInput input{f.title, "", "", {}};
  input.viewer.role = course::Role::staff;  // the command line is a TA's machine: the answer in the reference's shading
  if (!f.answers.empty()) {
    if (!fs::is_regular_file(f.answers)) {
      std::cerr << "error: cannot read the answers file '" << f.answers << "'\n";
      return 2;
    }
    input.answers = read_text(f.answers);
  }
  for (const auto& path : submitted_files(f.folder)) {
    if (path.extension() == ".js") input.files.push_back({path, read_text(fs::path(f.folder) / path)});
    if (path.extension() == ".png") input.images.push_back({path, read_text(fs::path(f.folder) / path)});
    if (path.extension() == ".ipynb" && input.notebook.empty()) input.notebook = read_text(fs::path(f.folder) / path);  // the shallowest
  }
  for (const auto& file : f.scenes) {
    auto scene = scene_input(file);
    if (!scene) return fail(scene.error());
    input.scenes.push_back(std::move(*scene));
  }
  worker::WorkerPool pool(pool_config(f.grade, 16));  // every section's jobs queued at once (sheet/assemble.h)
  auto assembled = sheet::assemble(pool, **loaded, std::move(input), {.folder = f.grade.cache_dir});
  if (!assembled) return fail(assembled.error());
  const sheet::Sheet& sheet = *assembled;
  auto pdf = sheet::render_pdf(sheet);
  if (!pdf) return fail(pdf.error());
  if (auto s = write_file(f.pdf, *pdf); !s) return fail(s.error());
  if (!f.html.empty())
    if (auto s = write_file(f.html, sheet::render_html(sheet)); !s) return fail(s.error());
  for (const auto& s : sheet.checkpoints) std::cout << s.checkpoint << ": " << sheet::section_verdict(s) << "\n";
  for (const auto& s : sheet.images)
    if (s.check) std::cout << s.title << ": " << sheet::image_verdict(*s.check) << "\n";
  return 0;
}

}  // namespace

Command add_sheet_command(CLI::App& app) {
  auto f = std::make_shared<SheetFlags>();
  auto* cmd = app.add_subcommand("sheet", "The submission sheet from a student's HW2 folder: grids, grades and code, as PDF (and HTML)");
  cmd->add_option("folder", f->folder, "The student's HW2 folder (src/shaders/*.js, images/*.png), or the shader modules alone")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--output", f->pdf, "Where the PDF goes")->required();
  cmd->add_option("--html", f->html, "Also write the sheet as one HTML page here");
  cmd->add_option("--answers", f->answers, "A text file with the short answers");
  cmd->add_option("--scene", f->scenes, "A Blender-half scene (JSON, docs/scenes.md) to render with its framing report; repeat for more")
      ->check(CLI::ExistingFile);
  cmd->add_option("--title", f->title, "The sheet's title (e.g. the student's name; default: the course's hand-in title, \"HW2 submission\" in the built-in course)");
  add_grader_options(cmd, f->grade.course, f->grade.cache_dir, f->grade.software);
  return [f] { return run_sheet(*f); };
}

}  // namespace shadelab::cli
