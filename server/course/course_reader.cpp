#include "course/course_reader.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>

#include "core/check.h"
#include "core/embedded_files.h"
#include "core/hash.h"
#include "core/json_reader.h"
#include "grade/starter_constants.h"
#include "course/formula_reader.h"
#include "course/notebook_reader.h"
#include "course/notebook_lines.h"
#include "scene/scene_description.h"

namespace shadelab::course {

namespace {

using nlohmann::json;

constexpr const char* kBuiltinPrefix = "builtin:";

// "courses/../assets/bunny.obj" -> "assets/bunny.obj": how an embedded path is looked up.
std::string normalized(const std::filesystem::path& p) { return p.lexically_normal().generic_string(); }

Expected<FileSource::Read> read_embedded(const std::string& path) {
  const auto bytes = embedded_file(path);
  if (!bytes) return make_error(ErrorCode::course_invalid, "no file '" + path + "' is compiled into this binary");
  return FileSource::Read{std::string(*bytes), true, path};
}


bool is_identifier(const std::string& s) { return std::regex_match(s, std::regex("[A-Za-z_][A-Za-z0-9_]{0,63}")); }
bool is_name(const std::string& s) { return std::regex_match(s, std::regex("[a-z0-9][a-z0-9_-]{0,31}")); }
bool is_prefix(const std::string& s) { return std::regex_match(s, std::regex("[A-Za-z0-9_-]{1,64}")); }

int components_of(const std::string& type) { return type == "float" ? 1 : type == "vec2" ? 2 : type == "vec3" ? 3 : type == "vec4" ? 4 : 0; }

// Reads the profile's fields in order, recording the first problem (JsonReader) and, past the
// syntax, the checks that need the files (a mistake's edit applies, a mesh parses).
class Parser {
 public:
  Parser(const FileSource& files, std::string origin) : files_(files) { course_.origin = std::move(origin); }

  Expected<Course> parse(const json& j) {
    JsonReader root(j, "", &error_, "a course profile");
    root.only({"format", "id", "title", "source", "canvas", "frames", "msaa", "camera", "uniforms", "specularExponent", "meshes",
               "defaultMesh", "presets", "defaultPreset", "checkpoints", "defaultCheckpoint", "aliases", "notebook", "tolerance", "handIn",
               "repairShown", "differencePicture"});
    if (root.require("format") && root.text("format", "") != kCourseFormat)
      root.fail_at("format", std::string("expected \"") + kCourseFormat + "\" (this ShadeLab reads that version of the format)");
    header(root);
    page(root);
    meshes(root);
    presets(root);
    checkpoints(root);
    aliases(root);
    read_notebook(root, files_, course_);
    if (!error_.empty()) return make_error(ErrorCode::course_invalid, course_.origin + ": " + error_);
    return std::move(course_);
  }

 private:
  void header(const JsonReader& r) {
    r.require("id");
    r.require("title");
    course_.id = r.text("id", "");
    if (r.has("id") && !is_name(course_.id)) r.fail_at("id", "expected lower-case letters, digits, '_' or '-' (at most 32)");
    course_.title = r.text("title", "");
    course_.source = r.text("source", "");
    course_.hand_in_title = r.text("handIn", "");
    repair_shown(r);
    difference_picture(r);
  }

  void difference_picture(const JsonReader& r) {
    std::set<std::string> names;
    for (const auto& row : grade::kDifferencePictureNames) names.emplace(row.name);
    const auto blocks = grade::DifferencePicture::blocks;
    course_.difference_picture =
        value_in(grade::kDifferencePictureNames, r.text("differencePicture", std::string(name_in(grade::kDifferencePictureNames, blocks)), names))
            .value_or(blocks);
  }

  void repair_shown(const JsonReader& r) {
    std::set<std::string> names;
    for (const auto& row : repair::kRepairShownNames) names.emplace(row.name);
    const std::string where = std::string(name_in(repair::kRepairShownNames, repair::RepairShown::where));
    course_.repair_shown = value_in(repair::kRepairShownNames, r.text("repairShown", where, names)).value_or(repair::RepairShown::where);
  }

  void page(const JsonReader& r) {
    const JsonReader canvas = r.object("canvas");
    if (r.require("canvas")) {
      canvas.only({"width", "height"});
      canvas.require("width") && canvas.require("height");
    }
    course_.width = canvas.integer("width", 0, 1, 16384);
    course_.height = canvas.integer("height", 0, 1, 16384);

    const JsonReader frames = r.object("frames");
    if (r.require("frames")) {
      frames.only({"count", "degreesPerFrame", "fileName", "savedFromPage"});
      frames.require("count") && frames.require("degreesPerFrame") && frames.require("fileName");
    }
    course_.frames = frames.integer("count", 0, 1, 3600);
    course_.degrees_per_frame = frames.number("degreesPerFrame", 0, -3600, 3600);
    course_.frame_name = frames.text("fileName", "");
    course_.frames_from_page = frames.boolean("savedFromPage", true);
    if (frames.has("fileName") && (!std::regex_match(course_.frame_name, std::regex("[A-Za-z0-9_{}.-]{1,128}")) ||
                                   course_.frame_name.find("{prefix}") == std::string::npos ||
                                   course_.frame_name.find("{k}") == std::string::npos))
      frames.fail_at(frames.at("fileName"), "expected a name holding {prefix} and {k}, in letters, digits, '_', '-' and '.'");

    r.require("msaa");
    course_.msaa = r.integer("msaa", 0, 0, 64);
    tolerance(r);

    const JsonReader camera = r.object("camera");
    if (r.require("camera")) {
      camera.only({"fovYDegrees", "near", "far", "meshTranslation"});
      camera.require("fovYDegrees") && camera.require("near") && camera.require("far") && camera.require("meshTranslation");
    }
    auto& c = course_.camera;
    c.fov_y_degrees = camera.number("fovYDegrees", 0, 1e-3, 179.9);
    c.near = camera.number("near", 0, 1e-9, 1e9);
    c.far = camera.number("far", 0, 1e-9, 1e12);
    c.mesh_translation = camera.vec3("meshTranslation", glm::dvec3(0.0), -1e7, 1e7);
    if (camera.has("near") && camera.has("far") && !(c.far > c.near)) camera.fail_at(camera.at("far"), "must be greater than near");

    uniforms(r);
    if (r.has("specularExponent")) {
      const JsonReader e = r.object("specularExponent");
      e.only({"value", "variable"});
      e.require("value") && e.require("variable");
      grade::StarterConstant k{e.text("variable", ""), "exponent", e.number("value", 0, 0, 1e6)};
      if (e.has("variable") && !is_identifier(k.variable)) e.fail_at(e.at("variable"), "expected a GLSL identifier");
      course_.starter_constants.push_back(std::move(k));
    }
  }

  void uniforms(const JsonReader& r) {
    const std::vector<std::string> role_names = uniform_role_names();
    const std::set<std::string> roles(role_names.begin(), role_names.end());
    std::set<std::string> names, seen_roles;
    for (const JsonReader& u : r.objects("uniforms")) {
      u.only({"names", "type", "value", "role"});
      u.require("names") && u.require("type") && u.require("value");
      PageUniform out;
      out.names = u.texts("names", {});
      if (u.has("names") && out.names.empty()) u.fail_at(u.at("names"), "expected at least one name");
      for (size_t i = 0; i < out.names.size(); ++i) {
        if (!is_identifier(out.names[i])) u.fail_at(JsonReader::element(u.at("names"), i), "expected a GLSL identifier");
        if (!names.insert(out.names[i]).second) u.fail_at(JsonReader::element(u.at("names"), i), "'" + out.names[i] + "' is named twice");
      }
      out.type = u.text("type", "", {"float", "vec2", "vec3", "vec4"});
      const int n = components_of(out.type);
      out.value = u.numbers("value", {}, 1, 4, -1e9, 1e9);
      if (n > 0 && u.has("value") && static_cast<int>(out.value.size()) != n)
        u.fail_at(u.at("value"), "a " + out.type + " takes " + std::to_string(n) + " numbers");
      const std::string role = u.text("role", "", roles);
      out.role = uniform_role_named(role);
      if (out.role && !seen_roles.insert(role).second) u.fail_at(u.at("role"), "the role '" + role + "' is given twice");
      course_.uniforms.push_back(std::move(out));
    }
  }

  // The verdict's thresholds, each optional.
  void tolerance(const JsonReader& r) {
    if (!r.has("tolerance")) return;
    const JsonReader t = r.object("tolerance");
    t.only({"threshold", "maxFailingFraction", "sameOutline", "savedFramesCloserThanReference"});
    grade::GradeOptions& o = course_.tolerance;
    o.compare.threshold = t.number("threshold", o.compare.threshold, 0, 1);
    o.max_failing_fraction = t.number("maxFailingFraction", o.max_failing_fraction, 0, 1);
    o.same_outline = t.number("sameOutline", o.same_outline, 0, 1);
    o.saved_frames_closer_than_reference = t.number("savedFramesCloserThanReference", o.saved_frames_closer_than_reference, 0, 1);
  }

  void meshes(const JsonReader& r) {
    if (r.require("meshes") && r.get("meshes").is_array() && r.get("meshes").empty()) r.fail_at("meshes", "expected at least one mesh");
    for (const JsonReader& m : r.objects("meshes")) {
      m.only({"name", "file"});
      m.require("name") && m.require("file");
      CourseMesh out;
      out.name = m.text("name", "");
      if (m.has("name") && !is_name(out.name)) m.fail_at(m.at("name"), "expected lower-case letters, digits, '_' or '-' (at most 32)");
      if (course_.mesh(out.name)) m.fail_at(m.at("name"), "'" + out.name + "' is named twice");
      out.file = m.text("file", "");
      out.format = scene::mesh_format_of(out.file);
      // The page reads its meshes with obj_parser.js: a course's meshes are OBJ files.
      if (!out.file.empty() && out.format != "obj") m.fail_at(m.at("file"), "expected an OBJ file (the page reads OBJ), not ." + out.format);
      if (!out.file.empty() && error_.empty()) {
        auto read = files_.read(out.file);
        if (!read) {
          m.fail_at(m.at("file"), read.error().message);
        } else {
          out.embedded = read->embedded;
          out.source = source_of(*read);
          out.id = read->embedded ? read->resolved : "course:" + sha256_hex(read->bytes).substr(0, 32);
          if (!read->embedded) out.bytes = std::move(read->bytes);
          // A profile's own mesh is parsed once here, so a bad file stops the load, not a job.
          if (!out.embedded) {
            auto parsed = load_course_mesh(out);
            if (!parsed) m.fail_at(m.at("file"), parsed.error().message);
          }
        }
      }
      course_.meshes.push_back(std::move(out));
    }
    course_.default_mesh = r.text("defaultMesh", course_.meshes.empty() ? "" : course_.meshes.front().name);
    if (error_.empty() && !course_.mesh(course_.default_mesh)) r.fail_at("defaultMesh", "'" + course_.default_mesh + "' is not one of meshes");
  }

  // A shader file of a preset: its text, named by its file name as a student's file is; `source`
  // gets where it was read.
  shader::ShaderFile shader_file(const JsonReader& r, const std::string& key, shader::Stage stage, std::string& source) {
    const std::string path = r.text(key, "");
    if (path.empty() || !error_.empty()) return {};
    auto read = files_.read(path);
    if (!read) {
      r.fail_at(r.at(key), read.error().message);
      return {};
    }
    source = source_of(*read);
    shader::ShaderFile file{std::filesystem::path(path).filename().string(), std::move(read->bytes)};
    if (auto unwrapped = shader::unwrap(file, stage, {}); !unwrapped) r.fail_at(r.at(key), unwrapped.error().message);
    return file;
  }

  void presets(const JsonReader& r) {
    if (r.require("presets") && r.get("presets").is_array() && r.get("presets").empty()) r.fail_at("presets", "expected at least one preset");
    for (const JsonReader& p : r.objects("presets")) {
      p.only({"name", "description", "vertex", "fragment", "public"});
      p.require("name") && p.require("vertex") && p.require("fragment");
      Preset out;
      out.name = p.text("name", "");
      if (p.has("name") && !is_name(out.name)) p.fail_at(p.at("name"), "expected lower-case letters, digits, '_' or '-' (at most 32)");
      if (course_.preset(out.name)) p.fail_at(p.at("name"), "'" + out.name + "' is named twice");
      out.description = p.text("description", "");
      out.is_public = p.boolean("public", false);
      out.vertex_file = p.text("vertex", "");
      out.fragment_file = p.text("fragment", "");
      out.vertex = shader_file(p, "vertex", shader::Stage::vertex, out.vertex_source);
      out.fragment = shader_file(p, "fragment", shader::Stage::fragment, out.fragment_source);
      // The starter's constants hold in every preset that sets them: the references agree with it.
      for (const auto& found : grade::changed_starter_constants(course_.starter_constants, out.fragment.text))
        p.fail_at(p.at("fragment"), out.fragment.name + " sets " + found.variable + " otherwise than specularExponent.value (" +
                                        found.message + ")");
      course_.presets.push_back(std::move(out));
    }
    course_.default_preset = r.text("defaultPreset", course_.presets.empty() ? "" : course_.presets.front().name);
    if (error_.empty() && !course_.preset(course_.default_preset))
      r.fail_at("defaultPreset", "'" + course_.default_preset + "' is not one of presets");
  }

  // The mistake's shaders: the reference with its edits applied, each edit found in the text.
  void apply_edits(const JsonReader& m, const Preset& reference, Mistake& out) {
    out.shaders.vertex = reference.vertex;
    out.shaders.fragment = reference.fragment;
    const auto edits = m.objects("edits");
    if (m.has("edits") && edits.empty()) m.fail_at(m.at("edits"), "expected at least one edit");
    for (const JsonReader& e : edits) {
      e.only({"stage", "find", "replace"});
      e.require("stage") && e.require("find") && e.require("replace");
      Edit edit{e.text("stage", "fragment", {"vertex", "fragment"}) == "vertex" ? Stage::vertex : Stage::fragment, e.text("find", ""),
                e.text("replace", "")};
      shader::ShaderFile& file = edit.stage == Stage::vertex ? out.shaders.vertex : out.shaders.fragment;
      const size_t at = edit.find.empty() ? std::string::npos : file.text.find(edit.find);
      if (!edit.find.empty() && at == std::string::npos)
        e.fail_at(e.at("find"), "'" + edit.find + "' is not in " + file.name + " (the reference '" + reference.name + "')");
      else if (at != std::string::npos)
        file.text.replace(at, edit.find.size(), edit.replace);
      out.edits.push_back(std::move(edit));
    }
  }

  Mistake mistake(const JsonReader& m, const Preset& reference, const std::set<std::string>& ids) {
    m.only({"id", "message", "edits", "preset", "reading"});
    m.require("id") && m.require("message");
    Mistake out;
    out.id = m.text("id", "");
    out.message = m.text("message", "");
    if (m.has("id") && !std::regex_match(out.id, std::regex("[a-z][a-z0-9_]{0,63}")))
      m.fail_at(m.at("id"), "expected lower-case letters, digits and '_'");
    if (ids.count(out.id)) m.fail_at(m.at("id"), "'" + out.id + "' is named twice in this checkpoint");
    if (m.has("message") && out.message.empty()) m.fail_at(m.at("message"), "expected what the student reads");
    if (m.has("edits") == m.has("preset")) m.fail(m.path() + ": give either 'edits' (on the reference) or 'preset' (another preset whole)");
    out.preset = m.text("preset", "");
    if (!out.preset.empty()) {
      const Preset* whole = course_.preset(out.preset);
      if (!whole) m.fail_at(m.at("preset"), "'" + out.preset + "' is not one of presets");
      else out.shaders.vertex = whole->vertex, out.shaders.fragment = whole->fragment;
    } else if (m.has("edits")) {
      apply_edits(m, reference, out);
    }
    out.shaders.id = out.id;
    out.shaders.message = out.message;
    if (m.has("reading")) out.shaders.reading = formula_reading(m.object("reading"));
    if (error_.empty() && out.shaders.vertex.text == reference.vertex.text && out.shaders.fragment.text == reference.fragment.text)
      m.fail(m.path() + ": the mistake's shaders are the reference's own: it would match every correct submission");
    return out;
  }

  void checkpoints(const JsonReader& r) {
    if (r.require("checkpoints") && r.get("checkpoints").is_array() && r.get("checkpoints").empty())
      r.fail_at("checkpoints", "expected at least one checkpoint");
    std::set<std::string> prefixes;
    for (const JsonReader& c : r.objects("checkpoints")) {
      c.only({"name", "title", "prefix", "reference", "code", "points", "weights", "mistakes", "probes", "formula"});
      c.require("name") && c.require("title") && c.require("prefix") && c.require("reference");
      Checkpoint out;
      out.name = c.text("name", "");
      if (c.has("name") && !is_name(out.name)) c.fail_at(c.at("name"), "expected lower-case letters, digits, '_' or '-' (at most 32)");
      for (const auto& other : course_.checkpoints)
        if (other.name == out.name) c.fail_at(c.at("name"), "'" + out.name + "' is named twice");
      out.title = c.text("title", "");
      out.prefix = c.text("prefix", "");
      if (c.has("prefix") && !is_prefix(out.prefix)) c.fail_at(c.at("prefix"), "expected letters, digits, '_' or '-' (at most 64)");
      if (!out.prefix.empty() && !prefixes.insert(out.prefix).second) c.fail_at(c.at("prefix"), "'" + out.prefix + "' is another checkpoint's prefix");
      out.reference = c.text("reference", "");
      out.code = c.text("code", "");
      if (c.has("code") && !is_identifier(out.code)) c.fail_at(c.at("code"), "expected a file stem: starter for starter_vert.js and starter_frag.js");
      out.points = c.number("points", 1, 0, 1e6);
      if (c.has("weights")) {
        const JsonReader w = c.object("weights");
        w.only({"frames", "code", "probe", "match"});
        out.weights = {w.number("frames", 1, 0, 1e6), w.number("code", 1, 0, 1e6), w.number("probe", 1, 0, 1e6), w.number("match", 1, 0, 1e6)};
      }
      const Preset* reference = course_.preset(out.reference);
      if (c.has("reference") && !reference && error_.empty()) c.fail_at(c.at("reference"), "'" + out.reference + "' is not one of presets");
      std::set<std::string> ids;
      if (reference)
        for (const JsonReader& m : c.objects("mistakes")) {
          out.mistakes.push_back(mistake(m, *reference, ids));
          ids.insert(out.mistakes.back().id);
        }
      for (const JsonReader& p : c.objects("probes")) {
        p.only({"name", "lightPosition", "lightColor", "checks"});
        p.require("name");
        if (!p.has("lightPosition") && !p.has("lightColor")) p.fail(p.path() + ": a probe changes the light: its lightPosition, its lightColor or both");
        const auto vec = [&](const char* field, double low, double high) -> std::optional<std::array<float, 3>> {
          if (!p.has(field)) return std::nullopt;
          const glm::dvec3 v = p.vec3(field, glm::dvec3(0.0), low, high);
          return std::array<float, 3>{float(v.x), float(v.y), float(v.z)};
        };
        out.probes.push_back({p.text("name", ""), vec("lightPosition", -1e7, 1e7), vec("lightColor", 0, 1), p.text("checks", "")});
        if (p.has("lightPosition") && !course_.uniform_with_role(UniformRole::light_position))
          p.fail(p.path() + ": a probe moves the light, but no uniform has the role lightPosition");
        if (p.has("lightColor") && !course_.uniform_with_role(UniformRole::light_color))
          p.fail(p.path() + ": a probe colours the light, but no uniform has the role lightColor");
      }
      if (c.has("formula")) out.formula = checkpoint_formula(c.object("formula"), reference, course_);
      for (std::size_t i = 0; i < out.mistakes.size(); ++i)
        if (const auto& reading = out.mistakes[i].shaders.reading) {
          if (!out.formula)
            c.fail_at(JsonReader::element(c.at("mistakes"), i) + ".reading", "a reading is the formula's: the checkpoint has no formula");
          else if (!model::applies_to(model::info(reading->variant), out.formula->terms))
            c.fail_at(JsonReader::element(c.at("mistakes"), i) + ".reading.variant",
                      "'" + std::string(model::info(reading->variant).id) + "' is not a variant of a " + std::string(model::to_string(out.formula->terms)) + " formula");
          else if (out.formula->terms == model::Terms::normal_colour && !reading->values.empty())
            c.fail_at(JsonReader::element(c.at("mistakes"), i) + ".reading.values", "the normal's colour has no values to change");
        }
      course_.checkpoints.push_back(std::move(out));
    }
    course_.default_checkpoint = r.text("defaultCheckpoint", course_.checkpoints.empty() ? "" : course_.checkpoints.back().name);
    if (error_.empty() && std::none_of(course_.checkpoints.begin(), course_.checkpoints.end(),
                                       [&](const Checkpoint& c) { return c.name == course_.default_checkpoint; }))
      r.fail_at("defaultCheckpoint", "'" + course_.default_checkpoint + "' is not one of checkpoints");
  }

  void aliases(const JsonReader& r) {
    for (const JsonReader& a : r.objects("aliases")) {
      a.only({"name", "checkpoint", "note"});
      a.require("name") && a.require("checkpoint") && a.require("note");
      Alias out{a.text("name", ""), a.text("checkpoint", ""), a.text("note", "")};
      if (a.has("name") && !is_name(out.name)) a.fail_at(a.at("name"), "expected lower-case letters, digits, '_' or '-' (at most 32)");
      const auto is_checkpoint = [&](const std::string& n) {
        return std::any_of(course_.checkpoints.begin(), course_.checkpoints.end(), [&](const Checkpoint& c) { return c.name == n; });
      };
      if (is_checkpoint(out.name)) a.fail_at(a.at("name"), "'" + out.name + "' is a checkpoint's own name");
      if (error_.empty() && !is_checkpoint(out.checkpoint)) a.fail_at(a.at("checkpoint"), "'" + out.checkpoint + "' is not one of checkpoints");
      course_.aliases.push_back(std::move(out));
    }
  }

  const FileSource& files_;
  Course course_;
  std::string error_;
};

}  // namespace

std::string source_of(const FileSource::Read& read) { return read.embedded ? kBuiltinPrefix + read.resolved : read.resolved; }

FileSource embedded_source(const std::string& folder) {
  return {[folder](const std::string& path) -> Expected<FileSource::Read> {
    if (path.starts_with(kBuiltinPrefix)) return read_embedded(path.substr(std::string(kBuiltinPrefix).size()));
    return read_embedded(normalized(std::filesystem::path(folder) / path));
  }};
}

FileSource folder_source(const std::filesystem::path& folder) {
  return {[folder](const std::string& path) -> Expected<FileSource::Read> {
    if (path.starts_with(kBuiltinPrefix)) return read_embedded(path.substr(std::string(kBuiltinPrefix).size()));
    const std::filesystem::path full = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : folder / path;
    std::ifstream in(full, std::ios::binary);
    if (!in) return make_error(ErrorCode::course_invalid, "cannot read '" + full.string() + "'");
    return FileSource::Read{std::string{std::istreambuf_iterator<char>(in), {}}, false, std::filesystem::absolute(full).lexically_normal().string()};
  }};
}

Expected<Course> read_course(const std::string& json_text, const FileSource& files, const std::string& origin) {
  const json j = json::parse(json_text, nullptr, false);
  if (j.is_discarded()) return make_error(ErrorCode::course_invalid, origin + ": not valid JSON");
  return Parser(files, origin).parse(j);
}

Expected<Course> load_course_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::course_invalid, "cannot read the course profile '" + path.string() + "'");
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  return read_course(text, folder_source(path.parent_path()), path.string());
}

const Course& builtin_course() {
  static const Course course = [] {
    const auto text = embedded_file(kBuiltinCoursePath);
    SHADELAB_CHECK(text.has_value(), "the built-in course profile is not embedded");
    auto read = read_course(std::string(*text), embedded_source("courses"), "built-in");
    SHADELAB_CHECK(static_cast<bool>(read), read ? "" : read.error().message.c_str());
    return std::move(*read);
  }();
  return course;
}

}  // namespace shadelab::course
