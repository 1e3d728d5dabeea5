#include "shader/glsl_facts.h"

#include "shader/extension_directives.h"
#include "shader/glsl_lines.h"

#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

namespace shadelab::shader {

namespace {

void initialize_glslang_once() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

TBuiltInResource webgl2_resources(GlslVersion version, Stage stage) {
  TBuiltInResource r = *GetDefaultResources();
  r.minProgramTexelOffset = -8;  // WebGL 2's MIN_PROGRAM_TEXEL_OFFSET / MAX_PROGRAM_TEXEL_OFFSET
  r.maxProgramTexelOffset = 7;
  r.maxDrawBuffers = kWebglMaxDrawBuffers;  // gl_MaxDrawBuffers and gl_MaxVertexAttribs as the browser has them
  r.maxVertexAttribs = kWebglMaxVertexAttribs;
  if (version == GlslVersion::es100) {  // GLSL ES 1.00 Appendix A, as WebGL enforces it
    r.limits.nonInductiveForLoops = false;
    r.limits.whileLoops = false;
    r.limits.doWhileLoops = false;
    r.limits.generalUniformIndexing = false;
    r.limits.generalAttributeMatrixVectorIndexing = false;
    r.limits.generalVaryingIndexing = false;
    // A vertex shader's uniforms, samplers among them, take any index in the browser (Chromium
    // accepts `t[int(attribute)]` there); Appendix A's sampler rule binds fragment shaders.
    r.limits.generalSamplerIndexing = stage == Stage::vertex;
    r.limits.generalVariableIndexing = false;
    r.limits.generalConstantMatrixVectorIndexing = false;
  }
  return r;
}

EShLanguage language(Stage stage) { return stage == Stage::vertex ? EShLangVertex : EShLangFragment; }
int default_version(GlslVersion version) { return version == GlslVersion::es100 ? 100 : 300; }

GlslPoint point(const glslang::TSourceLoc& loc) { return {loc.line, loc.column}; }

// "ERROR: 0:9: 'limitations' : while loops not available" -> {9, "limitations", "while loops ..."}.
std::vector<GlslError> read_info_log(const char* log) {
  std::vector<GlslError> out;
  std::istringstream in(log ? log : "");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("ERROR: ", 0) != 0) continue;
    const size_t colon1 = line.find(':', 7), colon2 = colon1 == std::string::npos ? colon1 : line.find(':', colon1 + 1);
    if (colon2 == std::string::npos) continue;
    GlslError e;
    e.at.line = std::atoi(line.c_str() + colon1 + 1);
    std::string rest = line.substr(colon2 + 1);
    const size_t open = rest.find('\''), close = open == std::string::npos ? open : rest.find('\'', open + 1);
    if (close != std::string::npos) {
      e.token = rest.substr(open + 1, close - open - 1);
      rest = rest.substr(close + 1);
    }
    const size_t text = rest.find_first_not_of(" :");
    e.message = text == std::string::npos ? "" : rest.substr(text);
    while (!e.message.empty() && e.message.back() == ' ') e.message.pop_back();
    if (e.message == "compilation terminated" || e.message.find("compilation errors") != std::string::npos) continue;
    out.push_back(std::move(e));
  }
  return out;
}

// "f(f1;" -> "f": glslang names a function by its mangled signature.
std::string function_name(std::string_view mangled) { return std::string(mangled.substr(0, mangled.find('('))); }

// Where a function is first named with its parenthesis (its declaration or definition).
GlslPoint function_at(std::string_view text, std::string_view name) {
  const std::vector<std::string_view> lines = lines_of(text);
  for (size_t k = 0; k < lines.size(); ++k) {
    const size_t at = whole_word(lines[k], name);
    if (at == std::string_view::npos) continue;
    const size_t after = lines[k].find_first_not_of(" \t", at + name.size());
    if (after != std::string_view::npos && lines[k][after] == '(') return {static_cast<int>(k) + 1, static_cast<int>(at) + 1};
  }
  return {};
}

// The errors glslang finds only when it links a stage alone, which the browser's compile finds:
// no main, recursion, a function called and never defined. glslang prints the function on the
// line after the error ("ERROR: Linking fragment stage: Recursion detected:" then
// "    f(f1; calling f(f1;"): the error takes the function's name and the line it is declared on.
std::vector<GlslError> read_link_log(const char* log, std::string_view text) {
  std::vector<GlslError> out;
  std::istringstream in(log ? log : "");
  bool naming = false;  // the last error waits for its function on the next line
  for (std::string line; std::getline(in, line);) {
    if (naming && line.rfind("    ", 0) == 0 && !out.empty()) {
      GlslError& e = out.back();
      e.token = function_name(std::string_view(line).substr(line.find_first_not_of(' ')));
      e.at = function_at(text, e.token);
      e.message = e.message.rfind("Recursive", 0) == 0
                      ? "Recursive function call in the following call chain: " + e.token +
                            " (GLSL ES 3.00 section 6.1: no function may call itself, directly or through others)"
                      : "Function " + e.token + "() is called but never defined (declared with no body)";
      naming = false;
      continue;
    }
    naming = false;
    if (line.rfind("ERROR: ", 0) != 0) continue;
    const size_t stage = line.find(" stage: ");
    const std::string message = stage == std::string::npos ? line.substr(7) : line.substr(stage + 8);
    GlslError e;
    if (message.rfind("Missing entry point", 0) == 0) {
      e.message = "Missing main(): the shader has no `void main()`, where it starts";
    } else if (message.rfind("Recursion detected", 0) == 0) {
      e.message = "Recursive function call";
      naming = true;
    } else if (message.rfind("No function definition (body) found", 0) == 0) {
      e.message = "Function called but never defined";
      naming = true;
    } else {
      e.message = message;
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::string precision_of(const glslang::TType& type) {
  switch (type.getQualifier().precision) {
    case glslang::EpqHigh: return "highp";
    case glslang::EpqMedium: return "mediump";
    case glslang::EpqLow: return "lowp";
    default: return "";
  }
}

std::string type_words(const glslang::TType& type) {
  std::string words = type.getCompleteString(false, false, false).c_str();
  words.erase(0, words.find_first_not_of(' '));
  return words;
}

// A block's members in order; a struct member's fields as "member.field", so a precision that
// differs inside a struct is found too.
// A block's members inherit its matrix packing where they name none (as the browser reads them:
// a vec4 member of a row_major block is row_major too), a struct's fields their member's.
void add_members(const glslang::TType& type, const std::string& prefix, bool row_major, std::vector<GlslVariable>& out);

bool packed_row_major(const glslang::TQualifier& q, bool inherited) {
  if (q.layoutMatrix == glslang::ElmRowMajor) return true;
  if (q.layoutMatrix == glslang::ElmColumnMajor) return false;
  return inherited;
}

// Locations a vertex input or fragment output takes: a matrix one per column, an array one per
// element.
int slots_of(const glslang::TType& type) {
  const int columns = type.isMatrix() ? type.getMatrixCols() : 1;
  return columns * (type.isArray() ? std::max(1, type.getCumulativeArraySize()) : 1);
}

GlslVariable variable(const std::string& name, const glslang::TType& type, const glslang::TSourceLoc& loc,
                      bool row_major = false) {
  const auto& q = type.getQualifier();
  GlslVariable v{name, type_words(type), precision_of(type), point(loc)};
  v.flat = q.flat;
  v.invariant = q.invariant;
  v.sampler = type.getBasicType() == glslang::EbtSampler;
  v.row_major = packed_row_major(q, row_major);
  v.location = q.hasLocation() ? static_cast<int>(q.layoutLocation) : -1;
  v.slots = slots_of(type);
  if (type.isStruct()) {
    v.struct_name = type.getTypeName().c_str();
    add_members(type, "", v.row_major, v.fields);
  }
  return v;
}

void add_members(const glslang::TType& type, const std::string& prefix, bool row_major, std::vector<GlslVariable>& out) {
  for (const auto& field : *type.getStruct()) {
    const std::string name = prefix + field.type->getFieldName().c_str();
    const bool packing = packed_row_major(field.type->getQualifier(), row_major);
    if (field.type->isStruct() && !field.type->isArray())
      add_members(*field.type, name + ".", packing, out);
    else
      out.push_back(variable(name, *field.type, field.loc, packing));
  }
}

class FactsTraverser : public glslang::TIntermTraverser {
 public:
  // `preprocessed`: the same text without comments, each line in its place ("" if unavailable).
  FactsTraverser(std::string_view glsl, std::string_view preprocessed, GlslFacts& facts)
      : facts_(facts), lines_(lines_of(glsl)), code_lines_(preprocessed.empty() ? lines_ : lines_of(preprocessed)) {}

  bool visitSelection(glslang::TVisit, glslang::TIntermSelection* node) override {
    if (const auto operand = forbidden_operand(node->getType(), OperatorUse::Kind::ternary)) {
      // An if statement is a void selection too; it starts with `if` where a `?:` has its `?`.
      if (*operand != OperatorUse::Operand::void_value || !starts_if(node->getLoc()))
        facts_.operators.push_back({OperatorUse::Kind::ternary, *operand, point(node->getLoc())});
    }
    return true;
  }

  bool visitAggregate(glslang::TVisit visit, glslang::TIntermAggregate* node) override {
    if (visit != glslang::EvPreVisit) return true;
    if (node->getOp() == glslang::EOpComma) {
      for (auto* operand : node->getSequence())
        if (auto* typed = operand->getAsTyped())
          if (const auto what = forbidden_operand(typed->getType(), OperatorUse::Kind::sequence)) {
            facts_.operators.push_back({OperatorUse::Kind::sequence, *what, point(node->getLoc())});
            break;
          }
    }
    if (node->getOp() == glslang::EOpLinkerObjects) {
      read_linker_objects(*node);
      return false;  // declarations, not uses
    }
    return true;
  }

  // A global named anywhere in the code is statically used (GLSL ES 3.00 section 4.3.4: the
  // link's rules bind the inputs a shader so uses, called or not).
  void visitSymbol(glslang::TIntermSymbol* node) override {
    const auto& q = node->getType().getQualifier();
    const std::string name = node->getName().c_str();
    if (q.storage == glslang::EvqUniform || q.storage == glslang::EvqVaryingIn) used_.insert(name);
    if (q.invariant && name.rfind("gl_", 0) == 0) invariant_builtins_.insert(name);
  }

  // Marks what the code used; called once the whole tree is read.
  void mark_used() {
    for (auto* list : {&facts_.inputs, &facts_.uniforms})
      for (auto& v : *list) v.used = used_.count(v.name) > 0;
    for (const auto& name : invariant_builtins_) facts_.invariant_builtins_used.push_back({name, invariant_declaration(name)});
  }

  bool visitBinary(glslang::TVisit visit, glslang::TIntermBinary* node) override {
    if (visit != glslang::EvPreVisit) return true;
    if (node->getOp() != glslang::EOpIndexDirect && node->getOp() != glslang::EOpIndexIndirect) return true;
    const auto* base = node->getLeft()->getAsSymbolNode();
    if (!base || base->getName() != "gl_FragData") return true;
    const auto* index = node->getRight()->getAsConstantUnion();
    if (!index || index->getConstArray()[0].getIConst() != 0) facts_.frag_data_nonzero.push_back(point(node->getLoc()));
    return true;
  }

 private:
  static std::optional<OperatorUse::Operand> forbidden_operand(const glslang::TType& type, OperatorUse::Kind kind) {
    if (type.isArray()) return OperatorUse::Operand::array;
    if (type.getBasicType() == glslang::EbtStruct && (kind == OperatorUse::Kind::ternary || type.containsArray()))
      return OperatorUse::Operand::structure;
    if (type.getBasicType() == glslang::EbtVoid) return OperatorUse::Operand::void_value;
    return std::nullopt;
  }

  bool starts_if(const glslang::TSourceLoc& loc) const {
    if (loc.line < 1 || static_cast<size_t>(loc.line) > lines_.size() || loc.column < 1) return false;
    const std::string_view line = lines_[static_cast<size_t>(loc.line - 1)];
    const size_t at = static_cast<size_t>(loc.column - 1);
    return line.compare(at, 2, "if") == 0 &&
           (at + 2 >= line.size() || !(std::isalnum(static_cast<unsigned char>(line[at + 2])) || line[at + 2] == '_'));
  }

  // glslang's linker objects carry no position; a global is declared before any use, so its
  // first appearance as a whole word outside comments is its declaration. The line comes from the
  // preprocessor's output, the column from the source line.
  GlslPoint first_word(std::string_view name) const {
    for (size_t k = 0; k < code_lines_.size(); ++k) {
      if (whole_word(code_lines_[k], name) == std::string_view::npos) continue;
      const size_t column = k < lines_.size() ? whole_word(lines_[k], name) : std::string_view::npos;
      return {static_cast<int>(k) + 1, column == std::string_view::npos ? 0 : static_cast<int>(column) + 1};
    }
    return {};
  }

  // `invariant gl_FragCoord;`: the first line of code naming both words.
  GlslPoint invariant_declaration(std::string_view name) const {
    for (size_t k = 0; k < code_lines_.size(); ++k) {
      const size_t at = whole_word(code_lines_[k], name);
      if (at == std::string_view::npos || whole_word(code_lines_[k], "invariant") == std::string_view::npos) continue;
      const size_t column = k < lines_.size() ? whole_word(lines_[k], name) : std::string_view::npos;
      return {static_cast<int>(k) + 1, column == std::string_view::npos ? 0 : static_cast<int>(column) + 1};
    }
    return {};
  }

  GlslVariable global(const std::string& name, const glslang::TType& type, const glslang::TSourceLoc& loc) const {
    GlslVariable v = variable(name, type, loc);
    if (v.at.line == 0) v.at = first_word(name);
    return v;
  }

  void read_linker_objects(glslang::TIntermAggregate& objects) {
    for (auto* node : objects.getSequence()) {
      const auto* symbol = node->getAsSymbolNode();
      if (!symbol) continue;
      const std::string name = symbol->getName().c_str();
      const auto& type = symbol->getType();
      const auto storage = type.getQualifier().storage;
      if (name.rfind("gl_", 0) == 0) continue;
      if (storage == glslang::EvqUniform && type.getBasicType() == glslang::EbtBlock) {
        UniformBlock block{type.getTypeName().c_str(), {}, point(symbol->getLoc())};
        if (block.at.line == 0) block.at = first_word(block.name);
        block.row_major = packed_row_major(type.getQualifier(), false);
        block.instance_name = name.rfind("anon@", 0) != 0;  // glslang's name for a block without one
        block.array_size = type.isArray() ? std::max(1, type.getOuterArraySize()) : 0;
        add_members(type, "", block.row_major, block.members);
        facts_.uniform_blocks.push_back(std::move(block));
      } else if (storage == glslang::EvqUniform) {
        facts_.uniforms.push_back(global(name, type, symbol->getLoc()));
      } else if (storage == glslang::EvqVaryingIn) {
        facts_.inputs.push_back(global(name, type, symbol->getLoc()));
      } else if (storage == glslang::EvqVaryingOut) {
        facts_.outputs.push_back(global(name, type, symbol->getLoc()));
      }
    }
  }

  GlslFacts& facts_;
  std::vector<std::string_view> lines_, code_lines_;
  std::set<std::string> used_, invariant_builtins_;
};

}  // namespace

namespace {

// `#pragma STDGL invariant(all)` as the preprocessor prints it, spaces anywhere between tokens.
bool is_invariant_all_pragma(std::string_view line) {
  std::string tokens;
  for (const char c : line)
    if (c != ' ' && c != '\t') tokens += c;
  return tokens == "#pragmaSTDGLinvariant(all)";
}

// GLSL ES 1.00 has no line continuation, and glslang follows it; the browser (and Mesa) join a
// line ending in a backslash to the next in either language, comments included. For glslang the
// joined line stands where it started and the lines it took stay, empty, so every later line
// keeps its number.
std::string joined_continuations(std::string_view glsl) {
  std::string out, taken;
  for (size_t i = 0; i < glsl.size(); ++i) {
    if (glsl[i] == '\\' && i + 1 < glsl.size() && glsl[i + 1] == '\n') {
      taken += '\n';
      ++i;
      continue;
    }
    out += glsl[i];
    if (glsl[i] == '\n') {
      out += taken;
      taken.clear();
    }
  }
  return out + taken;
}

// Directives and layout qualifiers as the preprocessor leaves them: glslang keeps every line in
// its place (a `#line` it evaluated too), so a line of its output is the same line of the input.
void read_preprocessed(const std::string& text, std::string_view source, GlslFacts& facts) {
  const std::vector<std::string_view> source_lines = lines_of(source);
  std::istringstream in(text);
  int number = 0;
  bool in_layout = false;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (is_extension_pragma(line)) {
      if (static_cast<size_t>(number) <= source_lines.size())
        facts.extensions.push_back(read_extension_directive(source_lines[static_cast<size_t>(number - 1)], number));
      continue;
    }
    if (line.rfind("#line", 0) == 0) {
      facts.line_directives.push_back({number, line});
      continue;
    }
    if (is_invariant_all_pragma(line)) {
      facts.invariant_all_pragmas.push_back(number);
      continue;
    }
    // The preprocessor's output separates punctuation from words only where the source did, so
    // words are read character by character.
    for (size_t i = 0; i < line.size();) {
      const auto c = static_cast<unsigned char>(line[i]);
      if (std::isalpha(c) || c == '_') {
        size_t end = i;
        while (end < line.size() && (std::isalnum(static_cast<unsigned char>(line[end])) || line[end] == '_')) ++end;
        const std::string_view word(line.data() + i, end - i);
        if (word == "layout") in_layout = true;
        else if (in_layout && (word == "shared" || word == "packed"))
          facts.shared_or_packed.push_back({number, static_cast<int>(i) + 1});
        i = end;
      } else {
        if (c == ')') in_layout = false;
        ++i;
      }
    }
  }
}

// glslang's preprocessor over `text`, each line in its place; nothing when it fails.
std::optional<std::string> preprocessed_by_glslang(const std::string& text, const TBuiltInResource& resources, EShLanguage stage,
                                                   int version) {
  const char* strings[] = {text.c_str()};
  glslang::TShader preprocessor(stage);
  preprocessor.setStrings(strings, 1);
  glslang::TShader::ForbidIncluder no_includes;
  std::string out;
  if (!preprocessor.preprocess(&resources, version, EEsProfile, false, false, EShMsgDefault, &out, no_includes)) return std::nullopt;
  return out;
}

// Marks each active `#extension` that a line of code stands before (extension_directives.h), with
// one more preprocess, only where the stage has an `#extension`.
void mark_extensions_after_code(const std::string& text, const TBuiltInResource& resources, EShLanguage stage, int version,
                                GlslFacts& facts) {
  if (facts.extensions.empty()) return;
  const auto kept = preprocessed_by_glslang(extensions_as_pragmas(directives_and_code_markers(text)), resources, stage, version);
  if (!kept) return;
  const int first_code = first_code_line(*kept);
  for (auto& d : facts.extensions) d.after_code = first_code != 0 && first_code < d.line;
}

}  // namespace

GlslFacts read_glsl(std::string_view glsl, Stage stage, GlslVersion version) {
  initialize_glslang_once();
  const TBuiltInResource resources = webgl2_resources(version, stage);
  const std::string text = version == GlslVersion::es100 ? joined_continuations(glsl) : std::string(glsl);
  const char* strings[] = {text.c_str()};
  GlslFacts facts;

  const std::string preprocessed =
      preprocessed_by_glslang(extensions_as_pragmas(text), resources, language(stage), default_version(version)).value_or("");
  if (!preprocessed.empty()) read_preprocessed(preprocessed, text, facts);
  facts.preprocessed = preprocessed;
  mark_extensions_after_code(text, resources, language(stage), default_version(version), facts);

  glslang::TShader shader(language(stage));
  shader.setStrings(strings, 1);
  facts.parsed = shader.parse(&resources, default_version(version), EEsProfile, false, false, EShMsgDefault);
  if (!facts.parsed) facts.errors = read_info_log(shader.getInfoLog());
  if (facts.parsed && shader.getIntermediate() && shader.getIntermediate()->getTreeRoot()) {
    FactsTraverser traverser(text, preprocessed, facts);
    shader.getIntermediate()->getTreeRoot()->traverse(&traverser);
    traverser.mark_used();
    glslang::TProgram program;  // declared after the shader: destroyed first
    program.addShader(&shader);
    if (!program.link(EShMsgDefault)) facts.errors = read_link_log(program.getInfoLog(), text);
  }
  return facts;
}

}  // namespace shadelab::shader
