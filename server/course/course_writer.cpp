#include "course/course_reader.h"

#include <array>
#include <charconv>
#include <cstdlib>
#include <string>

// The profile as its format writes it (course_reader.h's to_json): the reader's inverse.
namespace shadelab::course {

using nlohmann::json;

namespace {

// The thresholds that differ from GradeOptions' defaults (a course that keeps them writes none).
// A probe's numbers as the profile wrote them: a float's shortest decimal (0.6, not 0.6000000238).
std::array<double, 3> as_written(const std::array<float, 3>& v) {
  std::array<double, 3> out{};
  for (size_t i = 0; i < 3; ++i) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v[i]).ptr;
    out[i] = std::strtod(std::string(text, end).c_str(), nullptr);
  }
  return out;
}

json tolerance_json(const grade::GradeOptions& o) {
  const grade::GradeOptions d;
  json out = json::object();
  if (o.compare.threshold != d.compare.threshold) out["threshold"] = o.compare.threshold;
  if (o.max_failing_fraction != d.max_failing_fraction) out["maxFailingFraction"] = o.max_failing_fraction;
  if (o.same_outline != d.same_outline) out["sameOutline"] = o.same_outline;
  if (o.saved_frames_closer_than_reference != d.saved_frames_closer_than_reference)
    out["savedFramesCloserThanReference"] = o.saved_frames_closer_than_reference;
  return out;
}

// One checkpoint as the profile writes it: what is not its default, and its catalogue and probes.
json checkpoint_json(const Checkpoint& k) {
  json mistakes = json::array();
  for (const auto& m : k.mistakes) {
    json entry = {{"id", m.id}, {"message", m.message}};
    if (!m.preset.empty()) {
      entry["preset"] = m.preset;
    } else {
      json edits = json::array();
      for (const auto& e : m.edits)
        edits.push_back({{"stage", e.stage == Stage::vertex ? "vertex" : "fragment"}, {"find", e.find}, {"replace", e.replace}});
      entry["edits"] = std::move(edits);
    }
    if (const auto& r = m.shaders.reading) {
      entry["reading"] = json::object();
      if (r->variant != model::Variant::formula) entry["reading"]["variant"] = std::string(model::info(r->variant).id);
      for (const auto& v : r->values) entry["reading"]["values"][std::string(to_string(v.parameter))] = v.value;
    }
    mistakes.push_back(std::move(entry));
  }
  json probes = json::array();
  for (const auto& p : k.probes) {
    probes.push_back({{"name", p.name}});
    if (p.light_position) probes.back()["lightPosition"] = as_written(*p.light_position);
    if (p.light_color) probes.back()["lightColor"] = as_written(*p.light_color);
    if (!p.checks.empty()) probes.back()["checks"] = p.checks;
  }
  json entry = {{"name", k.name}, {"title", k.title}, {"prefix", k.prefix}, {"reference", k.reference}, {"points", k.points}};
  // The weights of the tests that apply, when one is not the default.
  const auto& w = k.weights;
  const TestWeights defaults;
  if (w.frames != defaults.frames || w.code != defaults.code || w.probe != defaults.probe || w.match != defaults.match) {
    json weights = {{"frames", w.frames}};
    if (k.applies(DeliverableTest::code)) weights["code"] = w.code;
    if (k.applies(DeliverableTest::probe)) weights["probe"] = w.probe;
    if (k.applies(DeliverableTest::match)) weights["match"] = w.match;
    entry["weights"] = std::move(weights);
  }
  if (!k.code.empty()) entry["code"] = k.code;
  if (!mistakes.empty()) entry["mistakes"] = std::move(mistakes);
  if (!probes.empty()) entry["probes"] = std::move(probes);
  if (const auto& f = k.formula) {
    entry["formula"] = {{"terms", model::to_string(f->terms)}, {"position", f->position}, {"normal", f->normal}};
    if (!f->colour.empty()) entry["formula"]["colour"] = f->colour;
    if (!f->geometry.empty()) entry["formula"]["geometry"] = f->geometry;
    for (const auto& [vector, local] : f->vectors) entry["formula"]["vectors"][std::string(name_in(grade::kFormulaVectorNames, vector))] = local;
  }
  return entry;
}

}  // namespace

json to_json(const Course& c, bool portable) {
  json uniforms = json::array();
  for (const auto& u : c.uniforms) {
    json entry = {{"names", u.names}, {"type", u.type}, {"value", u.value}};
    if (u.role) entry["role"] = to_string(*u.role);
    uniforms.push_back(std::move(entry));
  }
  json meshes = json::array();
  for (const auto& m : c.meshes) meshes.push_back({{"name", m.name}, {"file", portable ? m.source : m.file}});
  json presets = json::array();
  for (const auto& p : c.presets) {
    presets.push_back({{"name", p.name}, {"description", p.description}, {"vertex", portable ? p.vertex_source : p.vertex_file},
                       {"fragment", portable ? p.fragment_source : p.fragment_file}});
    if (p.is_public) presets.back()["public"] = true;
  }
  json checkpoints = json::array();
  for (const auto& k : c.checkpoints) checkpoints.push_back(checkpoint_json(k));
  json aliases = json::array();
  for (const auto& a : c.aliases) aliases.push_back({{"name", a.name}, {"checkpoint", a.checkpoint}, {"note", a.note}});
  const auto& cam = c.camera;
  json out = {{"format", kCourseFormat},
              {"id", c.id},
              {"title", c.title},
              {"canvas", {{"width", c.width}, {"height", c.height}}},
              {"frames", {{"count", c.frames}, {"degreesPerFrame", c.degrees_per_frame}, {"fileName", c.frame_name},
                          {"savedFromPage", c.frames_from_page}}},
              {"msaa", c.msaa},
              {"camera", {{"fovYDegrees", cam.fov_y_degrees}, {"near", cam.near}, {"far", cam.far},
                          {"meshTranslation", {cam.mesh_translation.x, cam.mesh_translation.y, cam.mesh_translation.z}}}},
              {"uniforms", uniforms},
              {"meshes", meshes},
              {"defaultMesh", c.default_mesh},
              {"presets", presets},
              {"defaultPreset", c.default_preset},
              {"checkpoints", checkpoints},
              {"defaultCheckpoint", c.default_checkpoint},
              {"aliases", aliases}};
  if (!c.source.empty()) out["source"] = c.source;
  if (!c.hand_in_title.empty()) out["handIn"] = c.hand_in_title;
  if (c.repair_shown != repair::RepairShown::where) out["repairShown"] = name_in(repair::kRepairShownNames, c.repair_shown);
  if (c.difference_picture != grade::DifferencePicture::blocks)
    out["differencePicture"] = name_in(grade::kDifferencePictureNames, c.difference_picture);
  if (json tolerance = tolerance_json(c.tolerance); !tolerance.empty()) out["tolerance"] = std::move(tolerance);
  if (!c.questions.empty() || !c.images.empty() || !c.notebook_file.empty()) {
    json questions = json::array(), images = json::array();
    for (const auto& q : c.questions) {
      json one = {{"id", q.id}, {"text", q.text}};
      if (!q.cell.empty()) one["cell"] = q.cell;
      if (!q.render_colours.empty()) one["renderColours"] = q.render_colours;
      questions.push_back(one);
    }
    for (const auto& i : c.images) {
      json image = {{"file", i.file}, {"title", i.title}};
      if (!i.scene_file.empty()) image["scene"] = portable ? i.scene_source : i.scene_file;
      if (i.objects != 0) image["objects"] = i.objects;
      if (i.points != 0) image["points"] = i.points;
      images.push_back(std::move(image));
    }
    out["notebook"] = {{"questions", questions}, {"images", images}};
    if (!c.notebook_file.empty()) out["notebook"]["file"] = c.notebook_file;
    if (c.handed_out) {
      out["notebook"]["handedOut"] = portable ? c.handed_out->source : c.handed_out->file;
      if (c.handed_out->placeholder != HandedOutNotebook{}.placeholder) out["notebook"]["placeholder"] = c.handed_out->placeholder;
    }
  }
  for (const auto& k : c.starter_constants)
    if (k.meaning == "exponent") out["specularExponent"] = {{"value", k.value}, {"variable", k.variable}};
  return out;
}

}  // namespace shadelab::course
