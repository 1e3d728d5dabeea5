#include "course/formula_reader.h"

#include <regex>

#include "grade/formula_geometry.h"

namespace shadelab::course {

grade::FormulaReading formula_reading(const JsonReader& r) {
  r.only({"variant", "values"});
  grade::FormulaReading out;
  const std::string variant = r.text("variant", "formula");
  if (auto v = model::variant_named(variant)) out.variant = *v;
  else r.fail_at(r.at("variant"), "'" + variant + "' is not one of the formula's variants");
  if (!r.has("values")) return out;
  const JsonReader values = r.object("values");
  if (!r.get("values").is_object()) return out;
  for (const auto& [name, ignored] : r.get("values").items()) {
    const auto parameter = model::parameter_named(name);
    if (!parameter) {
      values.fail_at(values.at(name), "expected ambient, diffuse, specular, exponent or lightPosition");
      continue;
    }
    const std::size_t size = *parameter == model::Parameter::exponent ? 1 : 3;
    out.values.push_back({*parameter, values.numbers(name, {}, size, size, -1e7, 1e7)});
  }
  if (out.variant == model::Variant::formula && out.values.empty()) r.fail(r.path() + ": the formula unchanged is the reference: give a variant or values");
  return out;
}

namespace {

// The uniforms the lighting's formula reads, by role, and its exponent.
void check_lighting_inputs(const JsonReader& f, model::Terms terms, const Course& course) {
  for (const UniformRole role : {UniformRole::ambient, UniformRole::diffuse, UniformRole::light_position, UniformRole::light_color})
    if (!course.uniform_with_role(role)) f.fail(f.path() + ": the formula reads the " + std::string(to_string(role)) + ", but no uniform has that role");
  if (terms == model::Terms::phong && !course.uniform_with_role(UniformRole::specular))
    f.fail(f.path() + ": the formula reads the specular colour, but no uniform has that role");
  if (terms == model::Terms::phong && course.specular_exponent() <= 0)
    f.fail(f.path() + ": the formula's exponent is the course's specularExponent, and it has none");
}

// `vectors`: {"view": "V", ...}, each a vector of the formula and a local the reference's
// fragment shader declares as a vec3.
void read_vectors(const JsonReader& f, const Preset* reference, CheckpointFormula& out) {
  if (!f.has("vectors")) return;
  const JsonReader vectors = f.object("vectors");
  if (!f.get("vectors").is_object()) return;
  for (const auto& [name, ignored] : f.get("vectors").items()) {
    const auto vector = value_in(grade::kFormulaVectorNames, name);
    const std::string local = vectors.text(name, "");
    if (!vector) vectors.fail_at(vectors.at(name), "expected normal, light, view or reflected");
    else if (!std::regex_match(local, std::regex("[A-Za-z_][A-Za-z0-9_]*"))) vectors.fail_at(vectors.at(name), "expected a local's name");
    else if (reference && !std::regex_search(reference->fragment.text, std::regex("\\bvec3\\s+" + local + "\\s*[=;]")))
      vectors.fail_at(vectors.at(name), "the reference's fragment shader declares no `vec3 " + local + "`");
    else out.vectors.emplace_back(*vector, local);
  }
}

}  // namespace

CheckpointFormula checkpoint_formula(const JsonReader& f, const Preset* reference, const Course& course) {
  f.only({"terms", "position", "normal", "colour", "geometry", "vectors"});
  f.require("terms") && f.require("position") && f.require("normal");
  CheckpointFormula out;
  const std::string terms = f.text("terms", "phong");
  if (auto t = model::terms_named(terms)) out.terms = *t;
  else f.fail_at(f.at("terms"), "expected lambert, phong or normalColour");
  out.position = f.text("position", "");
  out.normal = f.text("normal", "");
  out.colour = f.text("colour", "");
  out.geometry = f.text("geometry", "");
  const Preset* geometry = reference;
  if (f.has("geometry") && !(geometry = course.preset(out.geometry))) f.fail_at(f.at("geometry"), "'" + out.geometry + "' is not one of presets");
  for (const char* field : {"position", "normal"}) {
    const std::string name = f.text(field, "");
    if (geometry && !name.empty() && !grade::writes_vec3_varying(geometry->vertex.text, name))
      f.fail_at(f.at(field), "the " + std::string(out.geometry.empty() ? "reference" : "geometry preset") + "'s vertex shader declares no `out vec3 " + name + ";`");
  }
  if (out.terms == model::Terms::normal_colour) {
    if (f.require("colour") && reference && !grade::varying_type(reference->vertex.text, out.colour))
      f.fail_at(f.at("colour"), "the reference's vertex shader declares no `out vec3 " + out.colour + ";` or `out vec4 " + out.colour + ";`");
  } else {
    if (f.has("colour")) f.fail_at(f.at("colour"), "only a normalColour formula reads a colour varying");
    check_lighting_inputs(f, out.terms, course);
  }
  read_vectors(f, reference, out);
  return out;
}

}  // namespace shadelab::course
