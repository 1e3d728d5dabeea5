#pragma once
// The homework's submission sheet, as data: what the checklist asks a student to hand in, laid
// out by sheet_pdf.h (cairo) and sheet_html.h. No GL, no workers: the CLI (and later the HTTP
// route) fills it from graded renders.
//
// | section            | holds                                                                 |
// |--------------------|-----------------------------------------------------------------------|
// | CheckpointSection  | the 3x3 grid the student's shaders render, its grade and diagnosis,   |
// |                    | and the shader code (line numbers; lines the grader points at marked) |
// | SceneSection       | a Blender-half render (the two objects, a dolly-zoom lens): the image |
// |                    | with each object's framing box, the framing verdicts, the materials   |
// | answers            | the short answers, as the student wrote them                          |
#include <set>
#include <string>
#include <vector>

#include "grade/report.h"
#include "scene/scene_description.h"
#include "scene_render/framing.h"

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

struct SceneSection {
  std::string name;                 // the scene file's name: "two_objects.json"
  std::string png;                  // empty when the scene did not render
  std::string error;                // why, then
  int width = 0, height = 0;        // of the render
  double lens_mm = 0;
  std::vector<scene_render::ObjectFraming> framing;
  std::vector<std::pair<std::string, scene::Material>> materials;  // per object, in the scene's order
};

struct Sheet {
  std::string title = "HW2 submission";
  std::vector<CheckpointSection> checkpoints;  // in the homework's order
  std::vector<SceneSection> scenes;
  std::string answers;                          // may be empty
};

// The checklist's words for a checkpoint's section.
std::string section_title(const std::string& checkpoint);
// The grader's verdict in one line: "1 / 1: matches the reference exactly".
std::string verdict(const grade::Report& report);
// The lines a report's diagnostics point at in `file_name` (its errors and warnings).
std::set<int> lines_pointed_at(const grade::Report& report, const std::string& file_name);
// "both objects fully in the image", or which are not: the checklist's framing requirement.
std::string framing_verdict(const SceneSection& scene);
// One object's framing in words: "fully in the image, covers 12.3% of it".
std::string framing_line(const scene_render::ObjectFraming& f);
// A Principled material in the words Blender's panel uses.
std::string material_line(const scene::Material& m);
// Tabs as 4 spaces, invalid UTF-8 bytes and control characters as '?': text a PDF font can show.
std::string printable(const std::string& text);

}  // namespace shadelab::sheet
