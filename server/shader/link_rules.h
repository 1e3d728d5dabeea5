#pragma once
// What links a vertex shader to a fragment shader, judged by ShadeLab as the browser judges it,
// before any driver: a GPU driver may link what the browser refuses, or refuse with a log that
// names nothing ("Link info ---------"). The rules and their words are Chromium's (ANGLE's link),
// probed case by case in Debian's Chromium (tests/webgl_rules/cases.json keeps them):
//  - a fragment input the code uses needs a vertex output of its name, type, array size and
//    interpolation (`flat` or not; `centroid` and precision may differ); in GLSL ES 1.00 its
//    invariance too. An input the code never names binds nothing (GLSL ES 3.00 section 4.3.4);
//  - a uniform both stages declare has one type (a struct's fields included), used or not, and
//    one precision where both stages use it (samplers aside);
//  - a uniform block both declare has the same members, types and precisions, the same matrix
//    packing (the block's, and each matrix member's), array size, and an instance name in both
//    or in neither; a block without one puts its members among the global names, which no
//    uniform or other such block of the other stage may share;
//  - GLSL ES 1.00: gl_FragCoord / gl_PointCoord read as invariant only where gl_Position /
//    gl_PointSize are;
//  - the vertex inputs fit the browser's 16 locations.
// docs/webgl-rules.md lists them with their sources.
#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "shader/glsl_facts.h"
#include "shader/shader_source.h"

namespace shadelab::shader {

// GLSL ES 1.00 section 4.6.4: a fragment shader's built-in, and the vertex shader's whose
// invariance it needs to be invariant.
inline constexpr std::array<std::pair<std::string_view, std::string_view>, 2> kInvariantBuiltinPairs{
    {{"gl_FragCoord", "gl_Position"}, {"gl_PointCoord", "gl_PointSize"}}};

struct LinkRuleBreak {
  Stage stage;  // where the student reads it: the stage whose declaration is named
  GlslPoint at;
  std::string message;
};

// Every rule the pair breaks, in the order the fragment shader declares what breaks it.
std::vector<LinkRuleBreak> link_rule_breaks(const GlslFacts& vertex, const GlslFacts& fragment, GlslVersion version);

}  // namespace shadelab::shader
