#include "shader/invariant_outputs.h"

#include "core/words.h"
#include "shader/global_scan.h"

namespace shadelab::shader {

namespace {

bool declares_output(const GlobalStatement& s) { return s.has("out") && !s.has("invariant") && !s.has_parameters && !s.names.empty(); }

}  // namespace

std::string with_invariant_outputs(std::string_view glsl, Stage stage) {
  std::string out;
  size_t copied = 0;
  bool position_done = false;
  for (const GlobalStatement& s : scan_glsl(glsl).statements) {
    if (!declares_output(s)) continue;
    std::vector<std::string> names = s.names;
    if (stage == Stage::vertex && !position_done) names.push_back("gl_Position");
    position_done = true;
    out.append(glsl.substr(copied, s.semicolon + 1 - copied));
    copied = s.semicolon + 1;
    out += " invariant ";
    out += comma_list(names);
    out += ";";
  }
  out.append(glsl.substr(copied));
  return out;
}

}  // namespace shadelab::shader
