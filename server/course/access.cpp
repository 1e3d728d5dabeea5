#include "course/access.h"

#include "core/enum_names.h"
#include "core/words.h"

namespace shadelab::course {

namespace {

// The roles by the names the keys file and the API use, in the enum's order.
constexpr EnumName<Role> kRoles[] = {{Role::student, "student"}, {Role::staff, "staff"}};

std::vector<std::string> names_of(const std::vector<const Preset*>& presets) {
  std::vector<std::string> names;
  for (const Preset* p : presets) names.push_back(p->name);
  return names;
}

}  // namespace

std::string_view to_string(Role role) { return name_in(kRoles, role); }

std::optional<Role> role_named(std::string_view name) { return value_in(kRoles, name); }

bool may_see(const Viewer& viewer, const Preset& preset) { return preset.is_public || viewer.sees_references(); }

std::vector<const Preset*> visible_presets(const Course& course, const Viewer& viewer) {
  std::vector<const Preset*> out;
  for (const auto& p : course.presets)
    if (may_see(viewer, p)) out.push_back(&p);
  return out;
}

const Preset& page_preset(const Course& course) {
  for (const auto& p : course.presets)
    if (p.is_public) return p;
  return *course.preset(course.default_preset);
}

Expected<Course::FoundPreset> find_visible_preset(const Course& course, std::string_view name, const Viewer& viewer) {
  const std::vector<std::string> visible = names_of(visible_presets(course, viewer));
  auto found = course.find_preset(name);
  if (!found) {
    if (viewer.sees_references()) return found;
    return make_error(ErrorCode::unknown_preset, "no preset '" + std::string(name) + "' in " + course.id + " (presets: " + and_list(visible) + ")");
  }
  if (may_see(viewer, *found->preset)) return found;
  return make_error(ErrorCode::reference_private,
                    "'" + std::string(name) + "' is one of the course's references: its source and frames are for the course staff (a staff "
                    "API key). Students may render " + (visible.empty() ? std::string("their own shaders") : and_list(visible) + " and their own shaders") +
                    "; POST /api/grade compares yours with the reference without showing it");
}

}  // namespace shadelab::course
