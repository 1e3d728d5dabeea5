#pragma once
// Names the browser runs and a compiler ShadeLab uses refuses. Checked word by word against
// Debian's Chromium (docs/webgl-rules.md): `dmat2` (a desktop GLSL type, reserved by glslang and
// Mesa in both languages) and `packed` (a layout word Mesa reserves as a name in ES 3.00) are
// names to the browser. So each is renamed, in both stages alike, to a stand-in of the same length
// that neither stage uses: columns stay where they were, and every diagnostic is given the
// student's own word back.
#include <string>
#include <vector>

#include "core/error.h"

namespace shadelab::shader {

struct StandIn {
  std::string word, stand_in;
};

// For glslang and the driver: `dmat2`. For the driver only (glslang takes it): `packed`, once
// the rules have refused it inside layout(...).
enum class NamesFor { front_end, driver };

// Renames each such word in both sources (whole words, comments included: harmless there).
std::vector<StandIn> rename_reserved_names(std::string& vertex, std::string& fragment, NamesFor use);

// Each stand-in in the messages becomes the student's word again.
void restore_names(std::vector<Diagnostic>& diagnostics, const std::vector<StandIn>& renamed);
void restore_names(std::string& text, const std::vector<StandIn>& renamed);

}  // namespace shadelab::shader
