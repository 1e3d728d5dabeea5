#pragma once
// Who may see what of a course, decided here and nowhere else (docs/deploy.md, "Before students
// see it"). A student (the page, and any API caller without a staff key) sees the course's public
// material: the presets it hands out (the starter as distributed), its facts (canvas, meshes,
// uniform values, frame names) and their own results. The references' source and frames are the
// staff's. A server started for one learner (`serve --open-references`) shows them to everyone.
//
// | role    | how a request gets it                          | references          |
// |---------|------------------------------------------------|---------------------|
// | student | no key, or a key of the keys file without role | no (open: yes)      |
// | staff   | a key marked `staff` in the keys file          | yes                 |
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "course/course.h"

namespace shadelab::course {

enum class Role { student, staff };

std::string_view to_string(Role role);
std::optional<Role> role_named(std::string_view name);

// What one request may see: its role, and whether the server opened its references to everyone.
struct Viewer {
  Role role = Role::student;
  bool open_references = false;

  bool sees_references() const { return role == Role::staff || open_references; }
};

// A preset's source and frames: public ones to everyone, references to who sees references.
bool may_see(const Viewer& viewer, const Preset& preset);
// The presets `viewer` may see, in the course's order.
std::vector<const Preset*> visible_presets(const Course& course, const Viewer& viewer);
// What the page opens with: the course's first public preset (the starter the students received,
// as the course's own index.html opens with it); the default preset where it has none.
const Preset& page_preset(const Course& course);
// The preset `name` names (or a checkpoint's alias), when `viewer` may see it; reference_private
// naming the public presets when it is a reference, unknown_preset when there is none.
Expected<Course::FoundPreset> find_visible_preset(const Course& course, std::string_view name, const Viewer& viewer);

}  // namespace shadelab::course
