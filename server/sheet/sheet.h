#pragma once
// The homework's submission sheet, as data, in the notebook's order: each deliverable's grid
// (with the code handed in with it), the notebook's questions with the student's answers, the
// images of the Blender half, then any scene ShadeLab rendered. Laid out by sheet_pdf.h (cairo)
// and sheet_html.h. No GL, no workers: sheet/assemble.h fills it from graded renders.
//
// | section            | holds                                                                 |
// |--------------------|-----------------------------------------------------------------------|
// | CheckpointSection  | the 3x3 grid the student's shaders render (or, for a deliverable      |
// |                    | handed in as images, the frames they saved), its grade and diagnosis, |
// |                    | and the shader code (line numbers; lines the grader points at marked) |
// | questions, answers | the notebook's questions, each with the cells under it in the         |
// |                    | student's HW2.ipynb (the purple bunny rendered in their colours)     |
// | ImageSection       | an image the student hands in (camera_25.png, eevee0001.png)          |
// | SceneSection       | a Blender-half render (the two objects, a dolly-zoom lens): the image |
// |                    | with each object's framing box, the framing verdicts, the materials   |
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "grade/image_check.h"
#include "road/deliverable_score.h"
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
  std::string checkpoint;       // the course's name for it: normals
  std::string title;            // and its words: "Normals: the normal colour computed in the vertex shader"
  bool graded = false;          // its code was graded; false: no code (saved frames, or nothing)
  std::string grid_png;         // the student's code's render, or their saved frames; empty: neither
  std::string grid_caption;     // which of the two it is
  grade::Report report;         // when not graded, messages[0] says what was handed in
  std::vector<CodeListing> code;  // vertex, then fragment
  // The frames the student saved (images/hw2_{prefix}_*.png), shown beside the grid their code
  // renders, and how they were graded (grade/judge_saved_frames.h).
  std::string saved_grid_png;                  // set when there is code to show them beside
  std::optional<grade::Report> frames_report;  // against the reference, at their lags
  std::optional<grade::Report> match_report;   // against what the code renders
  road::DeliverableScore score;               // the three above as Gradescope scores them
};

// An image the course asks for beside the frames, as the student handed it in.
struct ImageSection {
  std::string title;    // "Dolly zoom: 25 mm"
  std::string file;     // where it was looked for: images/camera_25.png
  std::string png;      // empty when missing or unreadable
  std::string problem;  // why, then
  std::optional<grade::ImageCheck> check;  // the course checks it (the dolly zoom's cameras)
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

// One of the notebook's questions with the student's answer read from their HW2.ipynb, and, for a
// question that asks for colours, the bunny rendered in the colours they gave.
struct AnswerSection {
  std::string question;
  std::string answer;          // what the student wrote (notebook_reading.h); empty: `missing` says why
  std::string missing;         // "(unanswered: the placeholder is as handed out)"; empty when answered
  std::string render_png;      // empty: no colours to render (render_caption says why, when it matters)
  std::string render_caption;  // "ambient (0.30, 0.10, 0.40), ..., as the page renders them"
};

struct Sheet {
  std::string title;          // the course's hand-in title ("HW2 submission") unless the caller gave one
  std::string notebook_name;  // the course's notebook ("HW2.ipynb"), as its problems are named
  std::vector<CheckpointSection> checkpoints;  // in the course's (the notebook's) order
  std::vector<std::string> questions;          // the notebook's
  std::vector<AnswerSection> answered;         // from the student's notebook; empty when none was handed in
  std::string notebook_problem;                // why the notebook gave no answers ("not a Jupyter notebook")
  std::string notebook_note;                   // how the answers were read, when not against the handed-out notebook
  std::string answers;                         // an answers file as the student wrote it; may be empty
  std::vector<ImageSection> images;            // the course's hand-in images, in its order
  std::vector<SceneSection> scenes;
};

// The grader's verdict in one line: "1 / 1: matches the reference exactly".
std::string verdict(const grade::Report& report);
// A section's line: its score as Gradescope gives it, and why (road/deliverable_score.h).
std::string section_verdict(const CheckpointSection& section);
// The line's colour: "pass" (every point), "fail" (something graded fell short) or "note".
std::string_view section_class(const CheckpointSection& section);
// The saved frames' verdicts in words: "saved frames: 1 / 1: matches the reference ... (drawn 0.05
// to 0.30 degrees behind their nominal angles)", then "saved frames against the code: ...".
std::vector<std::string> frames_lines(const CheckpointSection& section);
// The lines a report's diagnostics point at in `file_name` (its errors and warnings).
std::set<int> lines_pointed_at(const grade::Report& report, const std::string& file_name);
// "both objects fully in the image", or which are not: the checklist's framing requirement.
std::string framing_verdict(const SceneSection& scene);
// A checked image's line: "0 / 0 (for the TA): matches the handout's camera (...)".
std::string image_verdict(const grade::ImageCheck& check);
// One object's framing in words: "fully in the image, covers 12.3% of it".
std::string framing_line(const scene_render::ObjectFraming& f);
// A Principled material in the words Blender's panel uses.
std::string material_line(const scene::Material& m);
// Tabs as 4 spaces, invalid UTF-8 bytes and control characters as '?': text a PDF font can show.
std::string printable(const std::string& text);

}  // namespace shadelab::sheet
