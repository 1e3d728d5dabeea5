// shadelab sheet HW2_DIR -o sheet.pdf: the submission sheet the homework's checklist asks for,
// made from the student's folder. Each checkpoint found (cli/submission_files.h) is rendered
// (the 3x3 grid) and graded through render workers, then laid out with its code: a PDF (cairo)
// and, with --html, the same as one HTML page. The same folder gives the same bytes.
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include "cli/file_output.h"
#include "cli/grade_runner.h"
#include "cli/submission_files.h"
#include "sheet/sheet_html.h"
#include "sheet/sheet_pdf.h"
#include "worker/client.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;

struct SheetFlags {
  GradeFlags grade;
  std::string folder, pdf, html, answers, title = "HW2 submission";
};

// The grid the student's shaders render, as the page would save it; empty when they do not.
std::string grid_of(worker::WorkerPool& pool, const fs::path& vert, const fs::path& frag) {
  worker::Job job;
  job.kind = worker::JobKind::render;
  job.request.vertex = {vert.filename().string(), read_text(vert)};
  job.request.fragment = {frag.filename().string(), read_text(frag)};
  if (!render::check_sources(job.request, render::RenderLimits{})) return {};
  auto rendered = worker::run<worker::RenderResult>(pool, worker::to_message(job));
  return rendered ? rendered->result.body : std::string();
}

sheet::CheckpointSection section(worker::WorkerPool& pool, const SheetFlags& f, const CheckpointFiles& c) {
  sheet::CheckpointSection s;
  s.checkpoint = c.checkpoint;
  if (!c.pair) {
    s.report.checkpoint = c.checkpoint;
    s.report.messages = {"not in the submission: no " + *c.homework_stem + "_vert.js and " + *c.homework_stem + "_frag.js in one folder"};
    return s;
  }
  const fs::path vert = fs::path(f.folder) / c.pair->first, frag = fs::path(f.folder) / c.pair->second;
  GradeFlags flags = f.grade;
  flags.reference = c.checkpoint;
  s.report = grade_one(pool, flags, vert, frag).result.report;
  s.grid_png = grid_of(pool, vert, frag);
  for (const auto& [path, relative] : {std::pair{vert, c.pair->first}, std::pair{frag, c.pair->second}})
    s.code.push_back({relative.string(), read_text(path), sheet::lines_pointed_at(s.report, relative.string())});
  return s;
}

int run_sheet(const SheetFlags& f) {
  sheet::Sheet sheet;
  sheet.title = f.title;
  if (!f.answers.empty()) {
    if (!fs::is_regular_file(f.answers)) {
      std::cerr << "error: cannot read the answers file '" << f.answers << "'\n";
      return 2;
    }
    sheet.answers = read_text(f.answers);
  }
  const auto plan = plan_checkpoints(submitted_files(f.folder));
  worker::WorkerPool pool(pool_config(f.grade, static_cast<int>(2 * plan.size())));
  for (const auto& c : plan) sheet.checkpoints.push_back(section(pool, f, c));
  auto pdf = sheet::render_pdf(sheet);
  if (!pdf) return fail(pdf.error());
  if (auto s = write_file(f.pdf, *pdf); !s) return fail(s.error());
  if (!f.html.empty())
    if (auto s = write_file(f.html, sheet::render_html(sheet)); !s) return fail(s.error());
  for (const auto& s : sheet.checkpoints) std::cout << s.checkpoint << ": " << sheet::verdict(s.report) << "\n";
  return 0;
}

}  // namespace

Command add_sheet_command(CLI::App& app) {
  auto f = std::make_shared<SheetFlags>();
  auto* cmd = app.add_subcommand("sheet", "The submission sheet from a student's HW2 folder: grids, grades and code, as PDF (and HTML)");
  cmd->add_option("folder", f->folder, "The student's HW2 folder (shaders/*_vert.js, *_frag.js), or the shader modules alone")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--output", f->pdf, "Where the PDF goes")->required();
  cmd->add_option("--html", f->html, "Also write the sheet as one HTML page here");
  cmd->add_option("--answers", f->answers, "A text file with the short answers");
  cmd->add_option("--title", f->title, "The sheet's title (e.g. the student's name)")->capture_default_str();
  cmd->add_flag("--software", f->grade.software, "Force Mesa's software renderer");
  return [f] { return run_sheet(*f); };
}

}  // namespace shadelab::cli
