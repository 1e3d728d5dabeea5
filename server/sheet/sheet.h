#pragma once
// The homework's submission sheet, as data: what the checklist asks a student to hand in, laid
// out by sheet_pdf.h (cairo) and sheet_html.h. No GL, no workers: the CLI (and later the HTTP
// route) fills it from graded renders.
//
// | section            | holds                                                                 |
// |--------------------|-----------------------------------------------------------------------|
// | CheckpointSection  | the 3x3 grid the student's shaders render, its grade and diagnosis,   |
// |                    | and the shader code (line numbers; lines the grader points at marked) |
// | answers            | the short answers, as the student wrote them                          |
#include <set>
#include <string>
#include <vector>

#include "grade/report.h"

namespace shadelab::sheet {

struct CodeListing {
  std::string file_name;        // as the submission names it: "shaders/starter_vert.js"
  std::string text;
  std::set<int> marked_lines;   // 1-based: where the grader's diagnostics point
};

struct CheckpointSection {
  std::string checkpoint;       // smooth, gouraud, diffuse, specular
  std::string grid_png;         // empty when the shaders did not render
  grade::Report report;
  std::vector<CodeListing> code;  // vertex, then fragment
};

struct Sheet {
  std::string title = "HW2 submission";
  std::vector<CheckpointSection> checkpoints;  // in the homework's order
  std::string answers;                          // may be empty
};

// The checklist's words for a checkpoint's section.
std::string section_title(const std::string& checkpoint);
// The grader's verdict in one line: "1 / 1: matches the reference exactly".
std::string verdict(const grade::Report& report);
// The lines a report's diagnostics point at in `file_name` (its errors and warnings).
std::set<int> lines_pointed_at(const grade::Report& report, const std::string& file_name);
// Tabs as 4 spaces, invalid UTF-8 bytes and control characters as '?': text a PDF font can show.
std::string printable(const std::string& text);

}  // namespace shadelab::sheet
