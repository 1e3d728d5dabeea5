#pragma once
// What a submission is graded against, as plain data a worker receives whole: the reference
// shaders, the known mistakes (each already a pair of shaders), the probe lights and the
// tolerance. A course profile (course/course.h) builds it from its checkpoints; a request can
// also bring its own reference ("custom").
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.h"
#include "grade/grader.h"
#include "model/lighting.h"
#include "shader/shader_source.h"
#include "store/shared_store.h"

namespace shadelab::grade {

// What the checkpoint's formula reads a known mistake as (grade/formula_explanation.h): its
// variant and the values it changes, with the values the mistake gives them.
struct FormulaReading {
  model::Variant variant = model::Variant::formula;
  struct Value {
    model::Parameter parameter;
    std::vector<double> value;  // three for a colour or a position, one for the exponent
  };
  std::vector<Value> values;
};

// A known mistake: the reference with one deliberate change. A submission that matches a
// mistake's render better than the reference's is told, in these words, what it got wrong.
struct Mistake {
  std::string id;       // "missing_specular"
  std::string message;  // what the student reads
  shader::ShaderFile vertex, fragment;
  // A submission the formula reads so is this mistake, without a render of the mistake's own (one
  // a light); none for a mistake the formula cannot draw, which is rendered and compared.
  std::optional<FormulaReading> reading;
};

// Extra frames rendered under another light, for mistakes the homework's light cannot show: with
// the light at the page's position the unlit side barely faces the camera, so a specular term
// added where N.L <= 0 changes under 0.1% of the pixels. Behind the mesh, that side is in view.
// And the page's light is white, so a term that leaves the light's colour out draws the same
// under it: under a coloured light, it does not.
struct Probe {
  std::string name;
  std::optional<std::array<float, 3>> light_position;  // none: the page's
  std::optional<std::array<float, 3>> light_color;     // none: the page's
  std::string checks;  // the rule it checks, in a student's words ("the specular term only where N.L > 0")
};

// The uniform a probe sets, under each name the page feeds it by, as the page declares it.
struct ProbeUniform {
  std::vector<std::string> names;
  std::string type;  // vec3, vec4
};

// A number the starter shader sets that a student should keep ("float specularAlpha = 6.0;"): a
// failing submission that sets it to something else is told so, read from its source.
struct StarterConstant {
  std::string variable;  // specularAlpha
  std::string meaning;   // "exponent"
  double value = 0;
};

// Where reference renders are kept across processes (grade/reference_store.h): a folder on this
// machine and, in a cluster, the replicas' shared store, so a node renders a course's references
// only when no replica has. Both empty: only in the worker's memory.
struct ReferenceStorePlaces {
  std::string folder;
  store::SharedStoreConfig shared;  // Redis, with the operator's deadlines and expiry; empty url: none
  bool empty() const { return folder.empty() && shared.url.empty(); }
};

// Whether a grade draws the heat map of where the submission's frames differ from the reference
// (~25 ms of a grade's ~550 on the 2-core machine, most of it the PNG): the page shows it always;
// Gradescope only beside a failed test; a class batch nowhere.
enum class HeatMap { always, when_failing, never };

// What the picture of where a failing grade differs shows its reader. Per pixel (`full`), the
// difference's ramp inverts to the reference's own pixels: a black submission read back the
// reference's brightest channel below 0.5, at any angle or light a request asked for. A course
// chooses what its students see (the profile's `differencePicture`); staff see `full`.
// - none: no picture; the words and numbers only.
// - blocks: the frame in blocks of kDifferenceBlockSide pixels (16 a side at the course's 512
//   canvas), each one of three shades: no pixel off, some, or most. At most log2(3) bits a block
//   of 1,024 pixels that hold 24 bits each: 9 frames of 512 x 512 (56.6 Mbit) take at least
//   15,500 grades to read back whatever the student draws, and a frame of any other size a request
//   asks for as many (the block is a size in pixels, not a share of the frame).
// - full: each pixel's difference, as the page has always drawn it.
enum class DifferencePicture { none, blocks, full };
inline constexpr EnumName<DifferencePicture> kDifferencePictureNames[] = {
    {DifferencePicture::none, "none"},
    {DifferencePicture::blocks, "blocks"},
    {DifferencePicture::full, "full"},
};
inline constexpr int kDifferenceBlockSide = 32;

// A homework quantity the formula reads (a colour, the light's position), under every name the
// page feeds it by, with the course's value: a submission's own value under one of the names
// replaces it, as it does for the reference.
struct FormulaInput {
  std::vector<std::string> names;
  std::array<float, 3> value{};
  float alpha = 1;  // a colour's fourth component
};

// The checkpoint's formula (model/lighting.h), for saying why a failing submission's frames
// differ: its terms, the varyings the reference's vertex shader writes the eye-space position and
// the normal to (the model's geometry is rendered from them), and the values it reads. A
// normal-colour checkpoint's reference writes the colour (`colour_varying`, vColor) and no normal:
// its position and normal come from another of the course's vertex shaders with the same
// transforms (`geometry_vertex`, the diffuse deliverable's).
struct FormulaSpec {
  model::Terms terms = model::Terms::phong;
  std::string position_varying, normal_varying;  // vPosition, vNormal
  std::string colour_varying;                    // vColor: a normal-colour checkpoint's
  shader::ShaderFile geometry_vertex;            // empty: the reference's own vertex shader
  FormulaInput ambient, diffuse, specular, light_position, light_colour;
  StarterConstant exponent;  // specularAlpha, 6.0 (a phong checkpoint's)
};

struct GradeSpec;

// A uniform a probe sets, as the page declares it ("uLightColor", vec4, {1, 0.6, 0.3, 1}).
struct ProbeSetting {
  std::string name, type;
  std::vector<double> value;
};
// What `probe` sets, under every name of each uniform it changes.
std::vector<ProbeSetting> probe_settings(const GradeSpec& spec, const Probe& probe);

struct GradeSpec {
  std::string reference_name;  // a checkpoint, or "custom"
  shader::ShaderFile reference_vertex, reference_fragment;
  std::vector<Mistake> mistakes;
  std::vector<Probe> probes;
  // The uniforms a probe sets: the light's position and its colour.
  std::vector<std::string> light_position_uniforms;
  ProbeUniform light_color_uniform;
  std::vector<StarterConstant> starter_constants;
  std::optional<FormulaSpec> formula;  // none: a failing grade is explained by the catalogue alone
  GradeOptions options;
  ReferenceStorePlaces reference_store;
  HeatMap heatmap = HeatMap::always;
  DifferencePicture picture = DifferencePicture::full;  // the course's for a student, full for staff
  // Saved frames must come from the course's page: ShadeLab's own frames lose the saved-frames
  // test (false: they are flagged only). Course::frames_from_page.
  bool frames_from_page = true;
  // `shadelab course warm`'s grade: besides its own verdict, every render a failing grade of the
  // checkpoint may read is made and kept in the store (the formula's geometry, averaged and each
  // sample's, and every known mistake under every light), so that a store warmed once serves
  // every student, whichever reading their frames take.
  bool warm = false;
  // A failing grade a repair search follows: the student's fragment values are read against the
  // reference's (grade/value_reading.h), for the search alone.
  bool read_values = false;

  bool wants_heatmap(bool passed) const {
    return picture != DifferencePicture::none && (heatmap == HeatMap::always || (heatmap == HeatMap::when_failing && !passed));
  }
};

// A frame a student saved from their browser, as it arrived: its file name and its PNG bytes.
struct SavedFrame {
  std::string name;  // hw2_specular_3.png
  std::string bytes;
};

}  // namespace shadelab::grade
