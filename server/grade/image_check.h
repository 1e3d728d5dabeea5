#pragma once
// A hand-in image's check (the Blender half's renders: grade/camera_check.h, render_check.h) as
// every place shows it: the sheet, `shadelab sheet`'s summary and Gradescope.
#include <string>

namespace shadelab::grade {

struct ImageVerdict {
  bool pass = false;
  std::string message;     // what the check found
  std::string leaves_out;  // what it cannot see, the TA's to look at; empty when nothing was checked
};

struct ImageCheck {
  std::string file;   // images/camera_25.png
  std::string title;  // "Dolly zoom: 25 mm"
  double points = 0;  // 0: reported for the TA
  ImageVerdict verdict;

  double score() const { return verdict.pass ? points : 0; }
  std::string text() const { return verdict.message + "." + (verdict.leaves_out.empty() ? "" : " " + verdict.leaves_out); }
};

}  // namespace shadelab::grade
