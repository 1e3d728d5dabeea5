// What a course grades by: a checkpoint's tests and their shares of its points, and the grade
// specs (what a worker receives whole: grade/grade_spec.h) its checkpoints make, for code and
// for saved frames.
#include "course/course.h"

#include "core/enum_names.h"

namespace shadelab::course {

namespace {
constexpr EnumName<DeliverableTest> kDeliverableTests[] = {{DeliverableTest::frames, "saved frames"},
                                                           {DeliverableTest::code, "code"},
                                                           {DeliverableTest::probe, "code under a hidden light"},
                                                           {DeliverableTest::match, "saved frames made by your code"}};
}  // namespace

std::string_view to_string(DeliverableTest test) { return name_in(kDeliverableTests, test); }

bool Checkpoint::applies(DeliverableTest test) const {
  switch (test) {
    case DeliverableTest::frames: return true;
    case DeliverableTest::code:
    case DeliverableTest::match: return !code.empty();
    case DeliverableTest::probe: return !code.empty() && !probes.empty();
  }
  return false;
}

double Checkpoint::max_score(DeliverableTest test, double of) const {
  const auto weight = [&](DeliverableTest t) {
    if (!applies(t)) return 0.0;
    switch (t) {
      case DeliverableTest::frames: return weights.frames;
      case DeliverableTest::code: return weights.code;
      case DeliverableTest::probe: return weights.probe;
      case DeliverableTest::match: return weights.match;
    }
    return 0.0;
  };
  double sum = 0;
  for (auto t : {DeliverableTest::frames, DeliverableTest::code, DeliverableTest::probe, DeliverableTest::match}) sum += weight(t);
  return sum > 0 ? of * weight(test) / sum : 0;
}

grade::GradeOptions Course::grade_options(const Checkpoint& c) const {
  grade::GradeOptions options = tolerance;
  options.max_score = c.points;
  return options;
}

grade::GradeSpec Course::own_reference_spec(shader::ShaderFile vertex, shader::ShaderFile fragment) const {
  grade::GradeSpec spec;
  spec.reference_name = "custom";
  spec.reference_vertex = std::move(vertex);
  spec.reference_fragment = std::move(fragment);
  spec.light_position_uniforms = light_position_names();
  spec.light_color_uniform = light_color_uniform();
  spec.options = tolerance;
  spec.options.max_score = 1;
  return spec;
}

grade::VectorWords vector_words(const Checkpoint& checkpoint) {
  grade::VectorWords out;
  if (checkpoint.formula)
    for (const auto& [vector, local] : checkpoint.formula->vectors) out.emplace(local, name_in(grade::kFormulaVectorWords, vector));
  return out;
}

grade::GradeSpec Course::grade_spec(const Checkpoint& c, const grade::GradeOptions& options) const {
  grade::GradeSpec spec;
  spec.reference_name = c.name;
  spec.picture = difference_picture;  // a student's; the road shows staff every pixel
  const Preset* reference = preset(c.reference);  // checked when the profile loaded
  spec.reference_vertex = reference->vertex;
  spec.reference_fragment = reference->fragment;
  for (const auto& m : c.mistakes) spec.mistakes.push_back(m.shaders);
  spec.probes = c.probes;
  spec.light_position_uniforms = light_position_names();
  spec.light_color_uniform = light_color_uniform();
  spec.starter_constants = starter_constants;
  spec.formula = formula_spec(c);
  spec.options = options;
  return spec;
}

std::optional<grade::FormulaSpec> Course::formula_spec(const Checkpoint& c) const {
  if (!c.formula) return std::nullopt;
  grade::FormulaSpec f{c.formula->terms, c.formula->position, c.formula->normal, c.formula->colour};
  if (const Preset* geometry = c.formula->geometry.empty() ? nullptr : preset(c.formula->geometry)) f.geometry_vertex = geometry->vertex;
  const auto input = [&](UniformRole role) {
    grade::FormulaInput in;
    if (const PageUniform* u = uniform_with_role(role)) {
      in.names = u->names;
      for (std::size_t i = 0; i < 3 && i < u->value.size(); ++i) in.value[i] = static_cast<float>(u->value[i]);
      if (u->value.size() == 4) in.alpha = static_cast<float>(u->value[3]);
    }
    return in;
  };
  f.ambient = input(UniformRole::ambient);
  f.diffuse = input(UniformRole::diffuse);
  f.specular = input(UniformRole::specular);
  f.light_position = input(UniformRole::light_position);
  f.light_colour = input(UniformRole::light_color);
  for (const auto& k : starter_constants)
    if (k.meaning == "exponent") f.exponent = k;
  return f;
}

grade::GradeSpec Course::frames_grade_spec(const Checkpoint& c, const grade::GradeOptions& options) const {
  grade::GradeSpec spec = grade_spec(c, options);
  spec.probes.clear();
  spec.frames_from_page = frames_from_page;
  const auto named = [&](const std::string& preset) {
    for (const auto& m : c.mistakes)
      if (m.preset == preset) return true;  // the catalogue says it better ("missing_specular")
    return preset == c.reference;
  };
  for (const Preset& p : presets) {
    if (named(p.name)) continue;
    const Checkpoint* owner = nullptr;
    for (const auto& other : checkpoints)
      if (other.reference == p.name) owner = &other;
    const std::string what = owner ? "the " + owner->name + " deliverable's frames (" + frame_file(owner->prefix, 0, "png") + ", ...)"
                                   : "the " + p.name + " shaders' frames (" + p.description + ")";
    spec.mistakes.push_back({"frames_of_" + p.name,
                             "these look like " + what + ", not the " + c.name + " deliverable's: saved under the wrong names, or before the shaders were changed?",
                             p.vertex, p.fragment});
  }
  return spec;
}

}  // namespace shadelab::course
