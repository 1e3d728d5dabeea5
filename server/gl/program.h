#pragma once
// Compiling, linking and reflecting a vertex + fragment program. Logs come back verbatim; mapping
// them onto the student's file is the shader layer's job.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gl/gl_name.h"
#include "gl/glsl_type.h"

namespace shadelab::gl {

struct ActiveVariable {
  std::string name;    // as GL reports it ("lights[0]" for arrays)
  GlslType type;
  int array_size = 1;
  int location = -1;
};

enum class BuildStage { vertex, fragment, link };

struct BuildFailure {
  BuildStage stage;
  std::string log;
};

// The attribute locations we ask for before linking; explicit layout qualifiers still win, so the
// renderer reads the real ones back from the reflection.
struct AttributeBinding {
  const char* name;
  unsigned location;
};

class Program {
 public:
  // Either a linked program or the first stage that failed, with its log.
  static Program build(const std::string& vertex, const std::string& fragment,
                       std::span<const AttributeBinding> bindings, std::optional<BuildFailure>& failure);

  Program() = default;
  bool valid() const { return static_cast<bool>(name_); }
  GLuint id() const { return name_.get(); }
  const std::vector<ActiveVariable>& attributes() const { return attributes_; }
  const std::vector<ActiveVariable>& uniforms() const { return uniforms_; }
  // The logs of a good build (warnings, if the driver gave any), verbatim per stage.
  const std::string& vertex_log() const { return vertex_log_; }
  const std::string& fragment_log() const { return fragment_log_; }
  const std::string& link_log() const { return link_log_; }

  void use() const;
  // Uploads `values` (count = components x elements) to a reflected uniform.
  void set_uniform(const ActiveVariable& uniform, std::span<const float> values) const;
  // Every uniform back to zero, as a newly linked program holds them (the program in use). A
  // program kept for a later job must not carry this job's values into it.
  void zero_uniforms() const;

 private:
  ProgramName name_;
  std::vector<ActiveVariable> attributes_;
  std::vector<ActiveVariable> uniforms_;
  std::string vertex_log_, fragment_log_, link_log_;
};

}  // namespace shadelab::gl
