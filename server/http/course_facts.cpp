#include "http/course_facts.h"

#include "course/course_reader.h"

namespace shadelab::http {

using nlohmann::json;

json presets_json(const course::Course& c, const course::Viewer& viewer) {
  json out = json::array();
  for (const course::Preset* p : course::visible_presets(c, viewer))
    out.push_back({{"name", p->name},
                   {"description", p->description},
                   {"public", p->is_public},
                   {"vertex", {{"name", p->vertex.name}, {"source", p->vertex.text}}},
                   {"fragment", {{"name", p->fragment.name}, {"source", p->fragment.text}}}});
  return out;
}

json course_json(const course::Course& c, const course::Viewer& viewer) {
  json out = course::to_json(c);
  json meshes = json::array();
  for (const auto& m : c.meshes) meshes.push_back({{"name", m.name}, {"url", "/api/meshes/" + m.name + ".obj?course=" + c.id}});
  out["meshes"] = std::move(meshes);
  out["presets"] = presets_json(c, viewer);
  out["pagePreset"] = course::page_preset(c).name;
  if (!course::may_see(viewer, *c.preset(c.default_preset))) out["defaultPreset"] = out["pagePreset"];
  out["viewer"] = {{"role", course::to_string(viewer.role)}, {"seesReferences", viewer.sees_references()},
                   {"framesDownloadNotice", c.frames_download_notice()}};
  for (auto& checkpoint : out["checkpoints"]) checkpoint.erase("mistakes");
  out.erase("format");
  return out;
}

}  // namespace shadelab::http
