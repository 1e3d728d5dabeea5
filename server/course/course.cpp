#include "course/course.h"

#include <algorithm>

#include "core/embedded_files.h"
#include "core/enum_names.h"

namespace shadelab::course {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

const Preset* Course::preset(std::string_view name) const {
  for (const auto& p : presets)
    if (p.name == name) return &p;
  return nullptr;
}

const CourseMesh* Course::mesh(std::string_view name) const {
  for (const auto& m : meshes)
    if (m.name == name) return &m;
  return nullptr;
}

namespace {
constexpr EnumName<UniformRole> kUniformRoles[] = {{UniformRole::ambient, "ambient"},
                                                   {UniformRole::diffuse, "diffuse"},
                                                   {UniformRole::specular, "specular"},
                                                   {UniformRole::light_position, "lightPosition"},
                                                   {UniformRole::light_color, "lightColor"}};
}  // namespace

std::string_view to_string(UniformRole role) { return name_in(kUniformRoles, role); }
std::optional<UniformRole> uniform_role_named(std::string_view name) { return value_in(kUniformRoles, name); }
std::vector<std::string> uniform_role_names() {
  std::vector<std::string> out;
  for (const auto& row : kUniformRoles) out.emplace_back(row.name);
  return out;
}

const PageUniform* Course::uniform_with_role(UniformRole role) const {
  for (const auto& u : uniforms)
    if (u.role == role) return &u;
  return nullptr;
}

std::vector<std::string> Course::preset_names() const {
  std::vector<std::string> out;
  for (const auto& p : presets) out.push_back(p.name);
  return out;
}

std::vector<std::string> Course::checkpoint_names() const {
  std::vector<std::string> out;
  for (const auto& c : checkpoints) out.push_back(c.name);
  return out;
}

std::vector<std::string> Course::mesh_names() const {
  std::vector<std::string> out;
  for (const auto& m : meshes) out.push_back(m.name);
  return out;
}

Expected<Course::Found> Course::checkpoint(std::string_view name) const {
  for (const auto& c : checkpoints)
    if (c.name == name) return Found{&c, nullptr};
  for (const auto& a : aliases)
    if (a.name == name)
      for (const auto& c : checkpoints)
        if (c.name == a.checkpoint) return Found{&c, &a};
  std::string message = "no checkpoint '" + std::string(name) + "' in " + id + " (checkpoints: " + joined(checkpoint_names()) + ")";
  if (preset(name)) message += "; '" + std::string(name) + "' is a preset (a warm-up step), not a deliverable";
  return make_error(ErrorCode::unknown_preset, message);
}

Expected<Course::FoundPreset> Course::find_preset(std::string_view name) const {
  if (const Preset* p = preset(name)) return FoundPreset{p, nullptr};
  for (const auto& a : aliases)
    if (a.name == name)
      for (const auto& c : checkpoints)
        if (c.name == a.checkpoint) return FoundPreset{preset(c.reference), &a};
  return make_error(ErrorCode::unknown_preset, "no preset '" + std::string(name) + "' in " + id + " (presets: " + joined(preset_names()) + ")");
}

std::string Course::frames_download_notice() const {
  if (!frames_from_page) return "";
  return "for checking, not for handing in: the course wants the frames saved from its page (its Save button); frames ShadeLab "
         "drew are recognised and score 0 as saved frames";
}

render::PageSetup Course::page() const {
  render::PageSetup setup{camera, {}};
  for (const auto& u : uniforms)
    for (const auto& name : u.names) {
      render::ConstantUniform c{name, u.type, {}, static_cast<int>(u.value.size())};
      std::copy(u.value.begin(), u.value.end(), c.value.begin());
      setup.uniforms.push_back(std::move(c));
    }
  return setup;
}

std::string Course::hand_in_name() const { return hand_in_title.empty() ? title + " submission" : hand_in_title; }

std::string Course::notebook_name() const { return notebook_file.empty() ? "the notebook" : notebook_file; }

render::RenderRequest Course::render_request(shader::ShaderFile vertex, shader::ShaderFile fragment) const {
  render::RenderRequest r;
  r.vertex = std::move(vertex);
  r.fragment = std::move(fragment);
  r.width = width;
  r.height = height;
  r.frames = frames;
  r.degrees_per_frame = degrees_per_frame;
  r.msaa = msaa;
  r.page = page();
  return r;
}

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

grade::GradeSpec Course::grade_spec(const Checkpoint& c, const grade::GradeOptions& options) const {
  grade::GradeSpec spec;
  spec.reference_name = c.name;
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

std::string Course::frame_file(std::string_view prefix, int k, std::string_view extension) const {
  return render::frame_file_name(frame_name, prefix, k, extension);
}

std::vector<std::string> Course::light_position_names() const {
  const PageUniform* light = uniform_with_role(UniformRole::light_position);
  return light ? light->names : std::vector<std::string>{};
}

grade::ProbeUniform Course::light_color_uniform() const {
  const PageUniform* colour = uniform_with_role(UniformRole::light_color);
  return colour ? grade::ProbeUniform{colour->names, colour->type} : grade::ProbeUniform{};
}

double Course::specular_exponent() const {
  for (const auto& k : starter_constants)
    if (k.meaning == "exponent") return k.value;
  return 0;
}

Expected<scene::Mesh> load_course_mesh(const CourseMesh& m) {
  if (!m.embedded) {
    const auto* data = reinterpret_cast<const std::uint8_t*>(m.bytes.data());
    return scene::load_mesh({data, m.bytes.size()}, m.format, m.name);
  }
  const auto bytes = embedded_file(m.id);
  if (!bytes) return make_error(ErrorCode::mesh_not_found, "the mesh '" + m.name + "' (" + m.id + ") is not compiled into this binary");
  return scene::load_mesh({reinterpret_cast<const std::uint8_t*>(bytes->data()), bytes->size()}, m.format, m.name);
}

Expected<scene::Bounds> fit_bounds(const Course& course) {
  auto mesh = load_course_mesh(*course.mesh(course.default_mesh));
  if (!mesh) return mesh.take_error();
  return scene::bounds(*mesh);
}

}  // namespace shadelab::course
