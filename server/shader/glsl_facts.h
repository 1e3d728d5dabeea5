#pragma once
// What WebGL 2's shader rules need to know about one stage, read by glslang (Khronos' reference
// GLSL front end): its AST for the operators, blocks and interface, its preprocessor for the
// directives and layout qualifiers as they stand after #if, and its own errors for the GLSL ES
// 1.00 Appendix A limits and the texel-offset range, which it checks when told WebGL's values.
//
// glslang parses hostile input, so this runs only in a worker, as the driver's compiler does.
// Every position is in the GLSL the driver gets (1-based; 0 = unknown); UnwrappedSource::locate
// maps it into the student's file.
#include <string>
#include <string_view>
#include <vector>

#include "shader/shader_source.h"

namespace shadelab::shader {

struct GlslPoint {
  int line = 0, column = 0;
};

// The limits the browser holds every shader to, whatever its GPU: ANGLE caps MAX_DRAW_BUFFERS at
// 8 and MAX_VERTEX_ATTRIBS at 16, and Debian's Chromium reports both (WebGL 2's minimums are 4 and
// 16). A student's browser refuses a location past them, so ShadeLab does on any driver.
constexpr int kWebglMaxDrawBuffers = 8;
constexpr int kWebglMaxVertexAttribs = 16;

// An error glslang reported, as it printed it: "'limitations' : while loops not available".
struct GlslError {
  GlslPoint at;
  std::string token;    // what glslang quotes first ("limitations", "texel offset")
  std::string message;  // the rest
};

// A `?:` or `,` on operands WebGL forbids there: `?:` on an array, a struct or void; `,` on an
// array, a struct holding one, or void.
struct OperatorUse {
  enum class Kind { ternary, sequence } kind;
  enum class Operand { array, structure, void_value } operand;
  GlslPoint at;  // the `?` or the `,`
};

struct GlslVariable {
  std::string name;
  std::string type;       // glslang's words, precision left out: "4-component vector of float"
  std::string precision;  // "highp", "mediump", "lowp" or "" (none: bool, or no default)
  GlslPoint at;
  bool flat = false;       // `flat` (else smooth: `centroid` does not change how stages match)
  bool invariant = false;  // `invariant`
  bool used = false;       // statically used: named in a function, even one never called
  bool sampler = false;    // an opaque type, whose precision the stages need not share
  bool row_major = false;  // a block member's matrix packing, its own or its block's
  int location = -1;       // `layout(location = N)`; -1 without one
  int slots = 1;           // locations it takes: a matrix's columns, times an array's size
  std::string struct_name;           // a struct's type name ("Light"); "" for any other type
  std::vector<GlslVariable> fields;  // a struct's, in order, nested structs as "field.inner"
};

// A built-in the code reads or writes, and where it is declared so.
struct BuiltinUse {
  std::string name;  // "gl_FragCoord"
  GlslPoint at;
};

struct UniformBlock {
  std::string name;                  // the block's name, which the stages match by
  std::vector<GlslVariable> members; // in order; a struct member's fields as "member.field"
  GlslPoint at;
  bool row_major = false;      // the block's matrix packing: its layout, or the stage's default
  bool instance_name = false;  // `uniform B { ... } b;`: its members are not global names
  int array_size = 0;          // `} b[2];`; 0 for a block that is not an array
};

// `#extension NAME : BEHAVIOR`, read from the student's line as the browser's preprocessor reads
// it. `shape` says what is missing or out of place; `token` is the browser's quote for it.
struct ExtensionDirective {
  enum class Shape {
    well_formed,
    unfinished,           // the line ends before the name, the colon or the behavior
    name_not_identifier,  // `#extension 12 : enable`
    unexpected_token,     // where the colon should be, or after the behavior
    unknown_behavior,     // not require, enable, warn or disable
  };
  std::string name, behavior;  // "GL_EXT_frag_depth", "require"
  int line = 0;
  Shape shape = Shape::well_formed;
  bool after_code = false;  // a line of code (not a directive) where #if leaves it in comes before
  std::string token;  // what the browser quotes where the shape is not well formed
  int column = 0;     // where that token starts (1-based; 0 = the line)
};

// An active `#line` (one #if left in), with the numbers the preprocessor evaluated it to: the
// browser evaluates `#line 10 + 2` or `#line L` (a macro), the driver takes only plain numbers.
struct LineDirective {
  int line = 0;                // where it stands
  std::string evaluated;       // "#line 12" or "#line 12 3", as the preprocessor printed it
};

struct GlslFacts {
  bool parsed = false;                    // glslang compiled the stage: the AST facts are complete
  std::vector<GlslError> errors;          // glslang's, in order (when !parsed)
  std::vector<OperatorUse> operators;
  std::vector<GlslPoint> frag_data_nonzero;  // gl_FragData[n], n not the constant 0 (ES 1.00)
  std::vector<UniformBlock> uniform_blocks;
  std::vector<GlslVariable> inputs, outputs, uniforms;  // the stage's interface, blocks aside
  std::vector<ExtensionDirective> extensions;           // those #if left in
  std::vector<LineDirective> line_directives;            // those #if left in
  std::vector<GlslPoint> shared_or_packed;               // `shared` / `packed` inside layout(...)
  std::vector<int> invariant_all_pragmas;                // lines of `#pragma STDGL invariant(all)`, #if left in
  std::vector<BuiltinUse> invariant_builtins_used;       // gl_FragCoord, gl_Position, ...: used, and declared invariant
  std::string preprocessed;  // the preprocessor's output, each line in its place ("" when it failed)
};

// The values glslang checks against, set as WebGL 2 sets them: texel offsets in [-8, 7] and, for
// GLSL ES 1.00, Appendix A's loop and indexing limits.
GlslFacts read_glsl(std::string_view glsl, Stage stage, GlslVersion version);

}  // namespace shadelab::shader
