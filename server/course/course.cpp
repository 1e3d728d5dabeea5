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

Expected<const CourseMesh*> Course::find_mesh(std::string_view name) const {
  const std::string wanted(name.empty() ? std::string_view(default_mesh) : name);
  if (const CourseMesh* m = mesh(wanted)) return m;
  std::string names;
  for (const auto& n : mesh_names()) names += (names.empty() ? "" : ", ") + n;
  return make_error(ErrorCode::mesh_not_found, "no mesh '" + wanted + "' in " + id + " (its meshes: " + names + ")");
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

std::string Course::frame_file(std::string_view prefix, int k, std::string_view extension) const {
  return render::frame_file_name(frame_name, prefix, k, extension);
}

std::string Course::saved_frame_range(const Checkpoint& checkpoint) const {
  return frame_file(checkpoint.prefix, 0, "png") + " to " + frame_file(checkpoint.prefix, frames - 1, "png");
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
