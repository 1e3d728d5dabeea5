// shadelab course: the course profile (docs/course-profile.md) a TA gives every other command.
//
//   shadelab course import HW2_DIR [--solution DIR] -o course.json   a homework folder to a profile
//   shadelab course check course.json                                 load it and say what it holds
//   shadelab course show [--course FILE] [--as-student]               print a profile, files portable (or what a student sees)
//   shadelab course warm [--course FILE] [--cache-dir DIR]            render its references into the store
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include "http/course_facts.h"
#include "cli/course_option.h"
#include "cli/file_output.h"
#include "cli/grade_runner.h"
#include "course/access.h"
#include "course/course_import.h"
#include "course/course_reader.h"
#include "course/unseen_roles.h"
#include "image/encode.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;

struct CourseFlags {
  course::ImportOptions import;
  std::string solution, check, show;
  bool as_student = false;
  GradeFlags warm;
};

// What a loaded profile holds, in a few lines.
void summarise(const course::Course& c) {
  std::cout << c.id << ": " << c.title << "\n  canvas " << c.width << " x " << c.height << ", " << c.frames << " frames of "
            << c.degrees_per_frame << " degrees, " << c.msaa << "x MSAA, frames saved as " << c.frame_file("{prefix}", 0, "png")
            << "\n  meshes:";
  for (const auto& m : c.meshes) std::cout << " " << m.name << (m.name == c.default_mesh ? " (default)" : "");
  std::cout << "\n  checkpoints:";
  for (const auto& k : c.checkpoints) std::cout << " " << k.name << " (" << k.mistakes.size() << " known mistakes)";
  std::cout << "\n  students see:";
  const auto visible = course::visible_presets(c, course::Viewer{});
  for (const course::Preset* p : visible) std::cout << " " << p->name;
  std::cout << (visible.empty() ? " no preset (warning: mark the starter as handed out \"public\": true, or the page opens with nothing for them)" : "")
            << "; references, staff only:";
  for (const auto& p : c.presets)
    if (!p.is_public) std::cout << " " << p.name;
  std::cout << "\n  saved frames: " << (c.frames_from_page ? "from the page only (ShadeLab's own score 0)" : "ShadeLab's own accepted, flagged") << "\n";
  for (const auto& unseen : course::unseen_roles(c)) std::cout << "  warning: " << unseen.why << "\n";
}

int run_import(CourseFlags& f) {
  if (!f.solution.empty()) f.import.solution = f.solution;
  auto imported = course::import_course(f.import);
  if (!imported) return fail(imported.error());
  for (const auto& line : imported->found) std::cout << "found: " << line << "\n";
  for (const auto& line : imported->assumed) std::cout << "assumed: " << line << "\n";
  const fs::path folder = fs::absolute(f.import.output).parent_path();
  for (const auto& [name, text] : imported->derived_files)
    if (auto s = write_file(folder / name, text); !s) return fail(s.error());
  if (auto s = write_file(f.import.output, imported->profile.dump(2) + "\n"); !s) return fail(s.error());
  // The profile as every other command will read it: a problem here is the import's to report.
  auto loaded = course::load_course_file(f.import.output);
  if (!loaded) return fail(loaded.error());
  std::cout << "wrote " << f.import.output.string() << "\n";
  summarise(*loaded);
  return 0;
}

// A deliverable's frames, blank, at the course's canvas size and names.
std::vector<grade::SavedFrame> blank_frames(const course::Course& c, const course::Checkpoint& checkpoint) {
  const auto png = image::encode_png(image::Image::blank(c.width, c.height, image::PixelType::u8));
  std::vector<grade::SavedFrame> out;
  for (int k = 0; k < c.frames; ++k)
    out.push_back({c.frame_file(checkpoint.prefix, k, "png"), png ? std::string(png->begin(), png->end()) : std::string()});
  return out;
}

// Every checkpoint's references, its formula's geometry and its catalogue under every light,
// rendered once into the store: a grade that makes them all (grade::GradeSpec::warm) of its first
// known mistake, or of the reference itself when it has none.
int run_warm(const GradeFlags& flags) {
  if (flags.cache_dir.empty()) return fail(make_error(ErrorCode::invalid_argument, "course warm needs a --cache-dir to keep the renders in"));
  auto loaded = load_course(flags.course);
  if (!loaded) return fail(loaded.error());
  const course::Course& c = **loaded;
  worker::WorkerPool pool(pool_config(flags, static_cast<int>(c.checkpoints.size())));
  for (const auto& checkpoint : c.checkpoints) {
    GradeFlags f = flags;
    f.reference = checkpoint.name;
    f.warm_store = true;
    const course::Preset& reference = *c.preset(checkpoint.reference);
    const grade::Mistake* first = checkpoint.mistakes.empty() ? nullptr : &checkpoint.mistakes.front().shaders;
    auto graded = grade_pair(pool, c, f, first ? first->vertex : reference.vertex, first ? first->fragment : reference.fragment);
    if (!graded) return fail(graded.error());
    const auto& w = graded->result.report.grader_work;
    std::cout << checkpoint.name << ": " << w.rendered << " sets rendered, " << w.from_store << " already in " << flags.cache_dir << "\n";
    // The saved frames' lag grid (grade/lag_fit.h): a set of blank frames, graded, renders it.
    auto frames = grade_frame_set(pool, c, f, checkpoint, blank_frames(c, checkpoint), std::nullopt);
    if (!frames) return fail(frames.error());
    const auto& fw = frames->result.frames.grader_work;
    std::cout << checkpoint.name << " (saved frames): " << fw.rendered << " sets rendered, " << fw.from_store << " already in " << flags.cache_dir << "\n";
  }
  return 0;
}

}  // namespace

Command add_course_command(CLI::App& app) {
  auto f = std::make_shared<CourseFlags>();
  auto* cmd = app.add_subcommand("course", "Course profiles: import a homework folder, check a profile, show one");
  cmd->require_subcommand(1);
  auto* import = cmd->add_subcommand("import", "A TA's homework folder (and solution shaders) to a course profile");
  import->add_option("folder", f->import.folder, "The HW2 folder as handed out (index.html, src/hw2.js, src/shaders/, assets/)")
      ->required()
      ->check(CLI::ExistingDirectory);
  import->add_option("--solution", f->solution, "A folder with the solved shaders (starter_*.js, phong_*.js, diffuse_*.js)")
      ->check(CLI::ExistingDirectory);
  import->add_option("-o,--output", f->import.output, "Where the profile goes (its files are named relative to it)")->required();
  import->add_option("--id", f->import.id, "The profile's id (default: from the folder's name)");
  import->add_option("--default-mesh", f->import.default_mesh, "The mesh the deliverables use (default: OBJ_FILE in hw2.js)");
  auto* check = cmd->add_subcommand("check", "Load a profile and say what it holds, or what is wrong with it (field and reason)");
  check->add_option("file", f->check, "The profile")->required();
  auto* show = cmd->add_subcommand("show", "Print a profile as JSON, its files named where they were read (builtin:... or absolute)");
  add_course_option(show, f->show);
  show->add_flag("--as-student", f->as_student,
                 "Print what a student sees instead (GET /api/course without a staff key: the public presets, no mistakes catalogue), for a page hosted elsewhere");
  auto* warm = cmd->add_subcommand("warm", "Render a course's references and known mistakes once into the reference store");
  add_grader_options(warm, f->warm.course, f->warm.cache_dir, f->warm.software);
  return [f, import, check, show, warm] {
    if (*import) return run_import(*f);
    if (*warm) return run_warm(f->warm);
    if (*check || *show) {
      auto loaded = load_course(*check ? f->check : f->show);
      if (!loaded) return fail(loaded.error());
      if (*check) summarise(**loaded);
      else if (f->as_student) std::cout << http::course_json(**loaded, course::Viewer{}).dump(2) << "\n";
      else std::cout << course::to_json(**loaded, true).dump(2) << "\n";
      return 0;
    }
    return 2;
  };
}

}  // namespace shadelab::cli
