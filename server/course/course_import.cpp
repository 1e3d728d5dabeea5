#include "course/course_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>

#include "core/text.h"
#include "course/course_reader.h"
#include "course/import_reading.h"
#include "course/notebook_import.h"
#include "course/script_facts.h"

namespace shadelab::course {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class Importer {
 public:
  explicit Importer(const ImportOptions& o) : o_(o), folder_(o.folder), p_(to_json(builtin_course(), true)) {}

  Expected<ImportedCourse> run() {
    identity();
    canvas();
    if (auto s = script(); !s) return s.take_error();
    exponent();
    if (auto s = meshes(); !s) return s.take_error();
    presets();
    notebook();
    out_.profile = std::move(p_);
    return std::move(out_);
  }

 private:
  void found(std::string what) { out_.found.push_back(std::move(what)); }
  void assumed(std::string what) { out_.assumed.push_back(std::move(what)); }

  // The folder's notebook (the built-in course's notebook.file, else the shallowest .ipynb) kept as the handed-out one.
  void notebook() {
    const std::string kept = fs::path(o_.output).stem().string() + ".handed_out.ipynb";
    auto imported = import_notebook(folder_notebook(folder_.root, folder_.files, p_["notebook"].value("file", "")), p_["notebook"], kept);
    p_["notebook"] = std::move(imported.section);
    if (imported.kept) out_.derived_files.push_back(std::move(*imported.kept));
    for (auto& f : imported.found) found(std::move(f));
    for (auto& a : imported.assumed) assumed(std::move(a));
  }

  void identity() {
    std::string id = o_.id;
    if (id.empty()) {
      for (const char c : lower_case(fs::absolute(o_.folder).lexically_normal().filename().string()))
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') id += c;
      if (id.empty() || !std::isalnum(static_cast<unsigned char>(id[0]))) id = "course-" + id;
      id = id.substr(0, 32);
    }
    p_["id"] = id;
    p_["title"] = "HW2 (" + fs::absolute(o_.folder).lexically_normal().filename().string() + ")";
    p_["source"] = "imported by shadelab course import from " + fs::absolute(o_.folder).lexically_normal().string();
  }

  void canvas() {
    const auto index = folder_.named("index.html");
    static const std::regex canvas_tag("<canvas[^>]*>", std::regex::icase);
    static const std::regex width("\\bwidth\\s*=\\s*[\"']?([0-9]+)", std::regex::icase), height("\\bheight\\s*=\\s*[\"']?([0-9]+)", std::regex::icase);
    std::smatch tag, w, h;
    const std::string html = index ? folder_.text(*index) : std::string();
    if (index && std::regex_search(html, tag, canvas_tag)) {
      const std::string t = tag.str();
      if (std::regex_search(t, w, width) && std::regex_search(t, h, height)) {
        p_["canvas"] = {{"width", std::stoi(w[1])}, {"height", std::stoi(h[1])}};
        found("canvas " + w[1].str() + " x " + h[1].str() + " (" + index->generic_string() + ")");
        return;
      }
    }
    assumed("canvas " + std::to_string(p_["canvas"]["width"].get<int>()) + " x " + std::to_string(p_["canvas"]["height"].get<int>()) +
            " (no <canvas width height> in an index.html)");
  }

  // The page's script: the module index.html loads, else the file holding `uniformValues`.
  std::optional<fs::path> page_script() const {
    if (auto script = folder_.named("hw2.js")) return script;
    for (const auto& f : folder_.files)
      if (f.extension() == ".js" && folder_.text(f).find("uniformValues") != std::string::npos) return f;
    return std::nullopt;
  }

  Status script() {
    const auto path = page_script();
    if (!path) {
      assumed("everything hw2.js would say (no hw2.js in the folder): the built-in course's uniforms, camera and frames");
      return Ok{};
    }
    const std::string js = folder_.text(*path), where = " (" + path->generic_string() + ")";
    uniforms(js, where);
    const ScriptFacts facts(js);
    camera(facts, where);
    frames(facts, where);
    if (js.find("antialias") != std::string::npos && std::regex_search(js, std::regex("antialias\\s*:\\s*false"))) {
      p_["msaa"] = 0;
      found("no multisampling: antialias: false" + where);
    } else {
      assumed("4x multisampling (WebGL's default antialias: true, as Chromium gives it)");
    }
    static const std::regex obj_file("OBJ_FILE\\s*=\\s*[\"']([^\"']+)[\"']");
    std::smatch m;
    if (o_.default_mesh.empty() && std::regex_search(js, m, obj_file)) {
      default_mesh_ = mesh_name(fs::path(m[1].str()).stem().string());
      found("default mesh " + default_mesh_ + ": OBJ_FILE" + where + "; the deliverables may use another (--default-mesh)");
    }
    return Ok{};
  }

  // uniformValues' numbers, and the names hw2.js looks the uniforms up by.
  void uniforms(const std::string& js, const std::string& where) {
    std::map<UniformRole, std::string> names;  // role -> the name hw2.js uses
    static const std::regex lookup("getUniformLocation\\s*\\([^,]*,\\s*[\"']([A-Za-z_][A-Za-z0-9_]*)[\"']");
    for (std::sregex_iterator it(js.begin(), js.end(), lookup), end; it != end; ++it)
      if (const auto role = role_of((*it)[1]); role && !names.count(*role)) names[*role] = (*it)[1];
    std::map<UniformRole, std::vector<double>> values;
    const size_t at = js.find("uniformValues");
    const std::string block = at == std::string::npos ? std::string() : block_after(js, at);
    static const std::regex key("([A-Za-z_][A-Za-z0-9_]*)\\s*:");
    for (std::sregex_iterator it(block.begin(), block.end(), key), end; it != end; ++it)
      if (const auto role = role_of((*it)[1]); role && !values.count(*role))
        values[*role] = numbers_after(block, static_cast<size_t>(it->position() + it->length()));
    for (auto& u : p_["uniforms"]) {
      const auto known = uniform_role_named(u.value("role", ""));
      if (!known) continue;  // the built-in course gives every uniform a role
      const UniformRole role = *known;
      const std::string role_name(to_string(role));
      const std::string builtin_name = u["names"][0];
      std::string name = names.count(role) ? names[role] : name_like_ambient(names, role);
      if (!names.count(role) && !name.empty()) assumed(role_name + " is named " + name + " (hw2.js does not look it up: the students' TODO)");
      if (name.empty()) name = builtin_name;
      if (name != builtin_name) course_names_[builtin_name] = name;
      json spellings = json::array({name});
      if (const auto plain = plain_spelling(name); !plain.empty()) spellings.push_back(plain);
      u["names"] = spellings;
      const size_t components = u["value"].size();
      if (values.count(role) && values[role].size() >= components) {
        u["value"] = std::vector<double>(values[role].begin(), values[role].begin() + static_cast<long>(components));
        found(role_name + " = " + u["value"].dump() + " as " + name + where);
      } else {
        assumed(role_name + " = " + u["value"].dump() + " (the built-in course's; not in uniformValues" + where + ")");
      }
    }
  }

  void camera(const ScriptFacts& script, const std::string& where) {
    auto& cam = p_["camera"];
    if (const auto projection = projection_of(script)) {
      cam["fovYDegrees"] = projection->fov_y_degrees;
      cam["near"] = projection->near;
      cam["far"] = projection->far;
      found("camera: fovY " + literal_number(cam["fovYDegrees"]) + " degrees, near " + literal_number(cam["near"]) + ", far " +
            literal_number(cam["far"]) + where);
    } else {
      assumed("camera: fovY " + literal_number(cam["fovYDegrees"]) + " degrees, near " + literal_number(cam["near"]) + ", far " +
              literal_number(cam["far"]) + " (no perspective call with numbers for its field of view, near and far" + where + ")");
    }
    if (const auto at = mesh_translation_of(script)) {
      cam["meshTranslation"] = *at;
      found("the mesh stands at " + cam["meshTranslation"].dump() + where);
    } else {
      assumed("the mesh stands at " + cam["meshTranslation"].dump() + " (no translate call with [x, y, z]" + where + ")");
    }
  }

  void frames(const ScriptFacts& script, const std::string& where) {
    const std::string& js = script.text();
    auto& f = p_["frames"];
    std::smatch m;
    if (const auto degrees = degrees_per_second_of(script)) {
      f["degreesPerFrame"] = *degrees;
      found("the mesh turns " + literal_number(*degrees) + " degrees per second, a frame a second" + where);
    } else {
      assumed("the mesh turns " + literal_number(f["degreesPerFrame"]) + " degrees a frame (no N * TIME or TIME * N" + where + ")");
    }
    if (std::regex_search(js, m, std::regex("MAX_OUT_FRAMES\\s*=\\s*([0-9]+)")) && std::stoi(m[1]) > 0) {
      f["count"] = std::stoi(m[1]);
      found("frames: " + m[1].str() + " (MAX_OUT_FRAMES" + where + ")");
    } else {
      assumed("frames: " + std::to_string(f["count"].get<int>()) + " (MAX_OUT_FRAMES is 0 or absent; the notebook's 3 x 3 grid)");
    }
    static const std::regex templated("`([A-Za-z0-9_.-]*)\\$\\{\\s*IMAGE_PREFIX\\s*\\}([A-Za-z0-9_.-]*)\\$\\{[^}]*\\}\\.png`");
    static const std::regex joined("[\"']([A-Za-z0-9_.-]*)[\"']\\s*\\+\\s*IMAGE_PREFIX\\s*\\+\\s*[\"']([A-Za-z0-9_.-]*)[\"']\\s*\\+\\s*[^+]+\\+\\s*[\"']\\.png[\"']");
    if (std::regex_search(js, m, templated) || std::regex_search(js, m, joined)) {
      f["fileName"] = m[1].str() + "{prefix}" + m[2].str() + "{k}";
      found("frames are saved as " + f["fileName"].get<std::string>() + ".png" + where);
    } else {
      assumed("frames are saved as " + f["fileName"].get<std::string>() + ".png (no download name around IMAGE_PREFIX" + where + ")");
    }
  }

  void exponent() {
    const auto frag = folder_.named("phong_frag.js");
    std::smatch m;
    const std::string text = frag ? folder_.text(*frag) : std::string();
    static const std::regex alpha("float\\s+([A-Za-z_]*(?:[Aa]lpha|[Ss]hin[A-Za-z]*|[Ee]xponent)[A-Za-z0-9_]*)\\s*=\\s*([0-9]*\\.?[0-9]+)\\s*;");
    if (frag && std::regex_search(text, m, alpha)) {
      exponent_ = std::stod(m[2]);
      p_["specularExponent"] = {{"value", exponent_}, {"variable", m[1].str()}};
      found("the starter's exponent: " + m[1].str() + " = " + m[2].str() + " (" + frag->generic_string() + ")");
    } else {
      exponent_ = p_["specularExponent"]["value"];
      assumed("the starter's exponent: " + literal_number(exponent_) + " (no float ...Alpha = N; in a phong_frag.js)");
    }
  }

  static std::string mesh_name(const std::string& stem) {
    std::string out;
    for (const char c : lower_case(stem)) out += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
    return out.substr(0, 32);
  }

  Status meshes() {
    json list = json::array();
    for (const auto& f : folder_.files) {
      if (lower_case(f.extension().string()) != ".obj") continue;
      const std::string name = mesh_name(f.stem().string());
      if (std::any_of(list.begin(), list.end(), [&](const json& m) { return m["name"] == name; })) continue;
      list.push_back({{"name", name}, {"file", path_from(o_.folder / f, o_.output)}});
      found("mesh " + name + " (" + f.generic_string() + ")");
    }
    if (list.empty()) {
      assumed("the built-in course's meshes (no .obj file in the folder)");
      return Ok{};
    }
    p_["meshes"] = list;
    const std::string wanted = !o_.default_mesh.empty() ? o_.default_mesh : default_mesh_;
    const bool known = std::any_of(list.begin(), list.end(), [&](const json& m) { return m["name"] == wanted; });
    if (!o_.default_mesh.empty() && !known)
      return make_error(ErrorCode::invalid_argument, "--default-mesh " + o_.default_mesh + " is not one of the folder's meshes");
    p_["defaultMesh"] = known ? wanted : list[0]["name"].get<std::string>();
    if (!known) assumed("default mesh " + p_["defaultMesh"].get<std::string>() + " (the first .obj file)");
    return Ok{};
  }

  json& preset(const std::string& name) {
    for (auto& p : p_["presets"])
      if (p["name"] == name) return p;
    p_["presets"].push_back({{"name", name}, {"description", name}});
    return p_["presets"].back();
  }

  // A pair from `dir` as a preset's files, when both are there.
  bool pair_as_preset(const fs::path& dir, const std::string& stem, const std::string& preset_name, const std::string& what) {
    const Folder f(dir);
    const auto vert = f.named(stem + "_vert.js"), frag = f.named(stem + "_frag.js");
    if (!vert || !frag) return false;
    auto& p = preset(preset_name);
    p["vertex"] = path_from(dir / *vert, o_.output);
    p["fragment"] = path_from(dir / *frag, o_.output);
    found(what + ": " + (dir / *vert).generic_string() + ", " + frag->filename().string());
    return true;
  }

  void presets() {
    if (!pair_as_preset(o_.folder, "starter", "starter", "the starter as distributed"))
      assumed("the starter: the built-in course's starter_*.js (no starter_vert.js and starter_frag.js in the folder)");
    const std::string builtin_why = o_.solution ? " (not in the solution folder)" : " (no --solution)";
    if (!o_.solution || !pair_as_preset(*o_.solution, "starter", "normals", "the normals reference (the solution's starter)"))
      assumed("the normals reference: the built-in course's" + builtin_why);
    if (!o_.solution || !pair_as_preset(*o_.solution, "diffuse", "diffuse", "the diffuse reference"))
      assumed("the diffuse reference: the built-in course's" + builtin_why);
    if (!o_.solution || !pair_as_preset(*o_.solution, "phong", "specular", "the specular reference (the solution's phong)"))
      specular_from_builtin(builtin_why);
    builtin_shaders_in_course_names();
    keep_applicable_mistakes();
  }

  // `text` with the built-in course's uniform names replaced by this course's, word by word.
  std::string in_course_names(const std::string& text) const {
    if (course_names_.empty()) return text;
    static const std::regex word("[A-Za-z_][A-Za-z0-9_]*");
    std::string out;
    size_t last = 0;
    for (std::sregex_iterator it(text.begin(), text.end(), word), end; it != end; ++it) {
      out.append(text, last, static_cast<size_t>(it->position()) - last);
      const auto renamed = course_names_.find(it->str());
      out += renamed == course_names_.end() ? it->str() : renamed->second;
      last = static_cast<size_t>(it->position() + it->length());
    }
    return out.append(text, last);
  }

  // A built-in shader that reads a uniform under the built-in name would read 0 on this course's
  // page (a black reference every black submission matches): each one that names one is written
  // beside the profile with the course's names.
  void builtin_shaders_in_course_names() {
    for (auto& p : p_["presets"])
      for (const char* stage : {"vertex", "fragment"}) {
        const std::string file = p.value(stage, "");
        std::optional<std::string> text;
        if (file.starts_with("builtin:")) text = stage_text(p["name"], stage);
        for (const auto& [name, derived] : out_.derived_files)
          if (name == file) text = derived;
        if (!text) continue;
        std::string in_names = in_course_names(*text);
        if (in_names == *text) continue;
        const std::string renamed = fs::path(o_.output).stem().string() + "." + p["name"].get<std::string>() + "_" +
                                    (std::string(stage) == "vertex" ? "vert" : "frag") + ".js";
        std::erase_if(out_.derived_files, [&](const auto& d) { return d.first == renamed; });
        out_.derived_files.emplace_back(renamed, std::move(in_names));
        if (file != renamed)
          assumed("the " + p["name"].get<std::string>() + " preset's " + stage + " shader: the built-in course's with this course's uniform names, written to " + renamed);
        p[stage] = renamed;
      }
  }

  // The built-in specular reference with the folder's exponent: written beside the profile when
  // the exponent differs.
  void specular_from_builtin(const std::string& why) {
    const auto& builtin = builtin_course();
    const double value = builtin.specular_exponent();
    if (exponent_ == value) {
      assumed("the specular reference: the built-in course's" + why);
      return;
    }
    const Preset& s = *builtin.preset("specular");
    std::string text = s.fragment.text;
    const std::string from = "float " + builtin.starter_constants.front().variable + " = " + literal_number(value) + ";";
    const std::string variable = p_["specularExponent"]["variable"];
    text.replace(text.find(from), from.size(), "float " + variable + " = " + literal_number(exponent_) + ";");
    text = std::regex_replace(text, std::regex("\\b" + builtin.starter_constants.front().variable + "\\b"), variable);
    const std::string file = fs::path(o_.output).stem().string() + ".specular_frag.js";
    out_.derived_files.emplace_back(file, text);
    preset("specular")["fragment"] = file;
    assumed("the specular reference: the built-in course's with " + variable + " = " + literal_number(exponent_) + ", written to " + file + why);
  }

  // The reference text a checkpoint's mistakes are edits of, as the import chose it.
  std::optional<std::string> stage_text(const std::string& preset_name, const std::string& stage) {
    for (const auto& p : p_["presets"]) {
      if (p["name"] != preset_name) continue;
      const std::string file = p[stage];
      if (file.starts_with("builtin:")) {
        const auto& b = *builtin_course().preset(preset_name);
        return stage == "vertex" ? b.vertex.text : b.fragment.text;
      }
      // Lexically: the profile's folder need not exist yet.
      const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : (fs::absolute(o_.output).parent_path() / file).lexically_normal();
      for (const auto& [name, text] : out_.derived_files)
        if (name == file) return text;
      return read_text(path);
    }
    return std::nullopt;
  }

  void keep_applicable_mistakes() {
    const std::string builtin_exponent = literal_number(builtin_course().specular_exponent());
    for (auto& c : p_["checkpoints"]) {
      if (!c.contains("mistakes")) continue;
      json kept = json::array();
      for (auto m : c["mistakes"]) {
        bool applies = true;
        if (!m.contains("edits")) m["edits"] = json::array();  // a whole preset: it applies
        for (auto& e : m["edits"]) {
          // The handout's-exponent edit follows the course's exponent and its variable's name.
          const std::string builtin_variable = builtin_course().starter_constants.front().variable;
          const std::string variable = p_["specularExponent"]["variable"];
          for (const char* side : {"find", "replace"})
            e[side] = in_course_names(std::regex_replace(e[side].get<std::string>(), std::regex("\\b" + builtin_variable + "\\b"), variable));
          std::string find = e["find"];
          if (find.find("= " + builtin_exponent + ";") != std::string::npos) {
            e["find"] = std::regex_replace(find, std::regex("= " + builtin_exponent + ";"), "= " + literal_number(exponent_) + ";");
            m["message"] = std::regex_replace(m["message"].get<std::string>(), std::regex("uses " + builtin_exponent), "uses " + literal_number(exponent_));
          }
          const auto text = stage_text(c["reference"], e["stage"]);
          applies = applies && text && text->find(e["find"].get<std::string>()) != std::string::npos &&
                    e["find"].get<std::string>() != e["replace"].get<std::string>();
        }
        if (m["edits"].empty()) m.erase("edits");
        if (applies) kept.push_back(m);
        else assumed("mistake " + c["name"].get<std::string>() + "/" + m["id"].get<std::string>() + " left out: its edit does not apply to the chosen reference");
      }
      c["mistakes"] = kept;
    }
  }

  const ImportOptions& o_;
  Folder folder_;
  json p_;
  ImportedCourse out_;
  std::string default_mesh_;
  double exponent_ = 0;
  // The built-in course's uniform names this folder's page calls otherwise, by role
  // (uLightPosition -> uLightPos): the built-in shaders and the mistakes' edits take them.
  std::map<std::string, std::string> course_names_;
};

}  // namespace

Expected<ImportedCourse> import_course(const ImportOptions& options) {
  if (!fs::is_directory(options.folder)) return make_error(ErrorCode::invalid_argument, "'" + options.folder.string() + "' is not a folder");
  if (options.solution && !fs::is_directory(*options.solution))
    return make_error(ErrorCode::invalid_argument, "--solution '" + options.solution->string() + "' is not a folder");
  return Importer(options).run();
}

}  // namespace shadelab::course
