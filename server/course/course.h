#pragma once
// A course profile: every fact of the homework an offering can change, in one place, for every
// layer (docs/course-profile.md). The canvas, the frames and their rotation, the samples, the
// page's camera and uniform values, the meshes, the reference shaders, the checkpoints with their
// file prefixes, points, known mistakes and probe lights. The built-in profile
// (courses/cs148-summer2022.json) is the offering the handout describes; `--course FILE` loads
// another. Lower layers take these facts as arguments and hard-code none of them.
//
// A Course is immutable once loaded and checked (course_reader.h): every file it names has been
// read, every mistake's edit applied to its reference and found to change it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"
#include "grade/formula_vectors.h"
#include "grade/grade_spec.h"
#include "repair/repair_edit.h"
#include "render/render_request.h"
#include "scene/mesh.h"
#include "scene/scene_description.h"
#include "shader/shader_source.h"

namespace shadelab::course {

enum class Stage { vertex, fragment };

// A reference pair: shaders/specular_vert.js and shaders/specular_frag.js.
struct Preset {
  std::string name;  // "specular"
  std::string description;
  std::string vertex_file, fragment_file;  // as the profile names them (relative to it)
  // Where they were read: "builtin:shaders/specular_vert.js", or the file's path on disk.
  std::string vertex_source, fragment_source;
  shader::ShaderFile vertex, fragment;     // named by their file names, as a student's are
  // Handed to the students ("public": true; the built-in course's starter as distributed). Any
  // other preset is a reference: its source and frames are the staff's (course/access.h).
  bool is_public = false;
};

// One deliberate change to a reference shader, found by its text.
struct Edit {
  Stage stage = Stage::fragment;
  std::string find, replace;
};

// A mistake students make on a checkpoint: the reference with edits, or another preset whole
// ("missing_specular" is the diffuse preset). `shaders` is made when the profile loads.
struct Mistake {
  std::string id, message;
  std::vector<Edit> edits;
  std::string preset;  // instead of edits
  grade::Mistake shaders;
};

// What a deliverable's points are shared by, Gradescope's tests for it: its saved frames against
// the reference, its code against the reference (under the page's light, and under the probe
// lights: a rule the page's light cannot show), and whether the saved frames are what the code
// renders. Shares of the checkpoint's points; a test that does not apply (no code, no probes)
// takes no share.
struct TestWeights {
  double frames = 1, code = 1, probe = 1, match = 1;
};
enum class DeliverableTest { frames, code, probe, match };
// What Gradescope calls each test after the deliverable's title: "saved frames", "code", "code
// under a hidden light", "saved frames made by your code".
std::string_view to_string(DeliverableTest test);

// The checkpoint's formula (model/lighting.h): its terms, and the varyings its reference's vertex
// shader writes the eye-space position and the normal to, from which the grader renders the
// geometry the formula is evaluated on. The normal's colour: the varying the reference writes it
// to, and the preset whose vertex shader writes the position and the normal instead (the
// reference's writes only the colour).
struct CheckpointFormula {
  model::Terms terms = model::Terms::phong;
  std::string position, normal;  // vPosition, vNormal
  std::string colour;            // vColor
  std::string geometry;          // a preset, or empty: the reference
  // The reference fragment shader's locals that are the formula's vectors ({view, "V"}), so a
  // repair at a student's name for one says what it is (grade/formula_vectors.h).
  std::vector<std::pair<grade::FormulaVector, std::string>> vectors;
};

// A deliverable: the frames `images/{frame name with prefix}` and, when `code` names a stem, the
// shaders `{code}_vert.js` / `{code}_frag.js` handed in with it.
struct Checkpoint {
  std::string name;    // normals
  std::string title;   // what the sheet and Gradescope call it
  std::string prefix;  // IMAGE_PREFIX: hw2_{prefix}_{k}.png
  std::string reference;  // a preset
  std::string code;       // "starter", "phong", or empty: the deliverable is images alone
  double points = 1;
  TestWeights weights;
  std::vector<Mistake> mistakes;
  std::vector<grade::Probe> probes;
  std::optional<CheckpointFormula> formula;  // none: a failure is explained by the catalogue alone

  bool applies(DeliverableTest test) const;
  // A test's share of `points` (0 for one that does not apply).
  double max_score(DeliverableTest test, double points) const;
};

// An old or other name for a checkpoint, and what it now means.
struct Alias {
  std::string name, checkpoint, note;
};

// The homework quantities a page uniform can be, named in a profile as ambient, diffuse,
// specular, lightPosition and lightColor (course.cpp's table).
enum class UniformRole { ambient, diffuse, specular, light_position, light_color };
std::string_view to_string(UniformRole role);
std::optional<UniformRole> uniform_role_named(std::string_view name);
std::vector<std::string> uniform_role_names();

// A constant uniform the page sets, under every name it feeds it by; `role` says which
// homework quantity it is, when it is one.
struct PageUniform {
  std::vector<std::string> names;
  std::string type;  // vec3, vec4, float
  std::vector<double> value;
  std::optional<UniformRole> role;
};

// A question of the notebook the sheet shows with the student's answer.
struct Question {
  std::string id;    // blue, purple, camera
  std::string text;  // in the course's words, or a paraphrase of them
  // Words the notebook's question cell holds (case ignored): the student's answer is the cells
  // under it. Empty: the question is not looked for in the notebook.
  std::string cell;
  // A preset whose shaders render the colours the answer gives (ambient, diffuse, specular RGB),
  // shown beside it; empty: none.
  std::string render_colours;
};

// The notebook as the course hands it out: a student's answers are what they changed in it
// (sheet/notebook_reading.h). Each answer's place is marked by `placeholder` (a fenced block in
// the course's notebook); the question is the text before it.
struct HandedOutNotebook {
  std::string file;    // as the profile names it: ../assets/notebooks/hw2_handed_out.ipynb
  std::string source;  // where it was read: "builtin:assets/notebooks/...", or its path
  std::string text;    // the .ipynb's bytes
  std::string placeholder = "YOUR ANSWER HERE";
};

// The largest side of a hand-in image that is read: a Blender render handed in is 1920 x 1080
// (Blender's default output), and nothing a homework asks for is larger than this.
inline constexpr unsigned kMaxHandInSide = 8192;

// An image the student hands in beside the page's frames (the Blender half's renders), by its
// path in their folder.
struct HandInImage {
  std::string file;   // images/camera_25.png
  std::string title;  // "Dolly zoom: 25 mm"
  // The scene the image must show, when it is checked (the dolly zoom's cameras): its camera is
  // the one the handout asks for, and ShadeLab renders its subject from that camera and from the
  // other checked images' to compare outlines (grade/camera_check.h). Empty: shown, not checked.
  std::string scene_file;    // as the profile names it: ../assets/scenes/dolly_25mm.json
  std::string scene_source;  // where it was read: "builtin:assets/scenes/dolly_25mm.json", or its path
  std::optional<scene::SceneDescription> scene;
  // Without a scene: how many objects the handout asks the render to show (the Eevee render's
  // two). The image is checked for what it shows alone (a PNG, not blank: grade/render_check.h);
  // the objects are the TA's to judge, and the check says so. 0: not checked.
  int objects = 0;
  double points = 0;  // Gradescope's points for the check; 0: reported for the TA

  bool checked() const { return scene.has_value() || objects > 0; }
};

// A mesh the page offers. Embedded meshes are compiled into the binary and travel to workers by
// their path; a profile's own meshes travel as bytes under a content address.
struct CourseMesh {
  std::string name;  // bunny
  std::string file;  // as the profile names it
  std::string format;  // obj, ply, ...
  std::string id;      // the worker's cache key: "assets/bunny.obj" when embedded, "course:<sha256>" else
  std::string source;  // where it was read: "builtin:assets/bunny.obj", or the file's path on disk
  bool embedded = false;
  std::string bytes;   // empty when embedded (embedded_file() has them)
};

struct Course {
  std::string id;     // cs148-summer2022
  std::string title;  // what pages and sheets are headed with
  std::string source; // where its facts come from, in words
  int width = 0, height = 0;
  int frames = 0;
  double degrees_per_frame = 0;
  int msaa = 0;
  std::string frame_name;  // "hw2_{prefix}_{k}": a frame's file name without its extension
  // The handout has students save the frames from the page: frames ShadeLab drew itself (the
  // reference at the exact angles, which no browser produces) lose the saved-frames test. False:
  // they are only flagged for the TA.
  bool frames_from_page = true;
  // The verdict's thresholds (the profile's `tolerance`; GradeOptions' defaults where it says
  // nothing). Its max_score is unused: a checkpoint's points are its score.
  grade::GradeOptions tolerance;
  // How much of a confirmed repair of a failing code grade its students are shown (the profile's
  // `repairShown`): what is wrong, where (the line: the default), or the repaired line too.
  repair::RepairShown repair_shown = repair::RepairShown::where;
  // What a failing grade's picture of where it differs shows its students (the profile's
  // `differencePicture`): blocks by default, which no number of grades a class could make inverts
  // to the reference's pixels; staff see every pixel.
  grade::DifferencePicture difference_picture = grade::DifferencePicture::blocks;
  render::PageCamera camera;
  std::vector<PageUniform> uniforms;
  std::vector<grade::StarterConstant> starter_constants;  // specularAlpha = 6.0
  std::vector<CourseMesh> meshes;
  std::string default_mesh;
  std::vector<Preset> presets;
  std::string default_preset;
  std::vector<Checkpoint> checkpoints;  // in the homework's (and the notebook's) order
  std::string default_checkpoint;
  std::vector<Alias> aliases;
  std::vector<Question> questions;    // the notebook's, in its order
  std::optional<HandedOutNotebook> handed_out;  // the notebook the answers are read against; none: read by the cells under each question
  std::vector<HandInImage> images;    // handed in after the questions, in the notebook's order
  // What the course calls a student's hand-in and their notebook, in the words they read (the
  // sheet's title, "HW2.ipynb: ..."): the profile's `handIn` and `notebook.file`.
  std::string hand_in_title;  // "HW2 submission"; empty: "<title> submission"
  std::string notebook_file;  // "HW2.ipynb"; empty: "the notebook"
  std::string origin;  // where it was read from: a path, or "built-in" (not part of the format)

  const Preset* preset(std::string_view name) const;
  const CourseMesh* mesh(std::string_view name) const;
  // The mesh `name` names (empty: the default); mesh_not_found naming the course's meshes.
  Expected<const CourseMesh*> find_mesh(std::string_view name) const;
  const PageUniform* uniform_with_role(UniformRole role) const;
  std::vector<std::string> preset_names() const;
  std::vector<std::string> checkpoint_names() const;
  std::vector<std::string> mesh_names() const;

  // A checkpoint by its name or an alias; unknown_preset (naming the checkpoints) for another.
  struct Found {
    const Checkpoint* checkpoint = nullptr;
    const Alias* alias = nullptr;  // set when `name` was an alias
  };
  Expected<Found> checkpoint(std::string_view name) const;
  // A preset by name, or by a checkpoint's alias (its reference); unknown_preset naming the presets.
  struct FoundPreset {
    const Preset* preset = nullptr;
    const Alias* alias = nullptr;
  };
  Expected<FoundPreset> find_preset(std::string_view name) const;

  // What the page sets up before it draws, for every request of this course.
  render::PageSetup page() const;
  // A request of the course's job for these shaders: its canvas, frames, rotation, samples, page.
  render::RenderRequest render_request(shader::ShaderFile vertex, shader::ShaderFile fragment) const;
  // What a submission of `checkpoint` is graded with: the course's tolerance, the checkpoint's points.
  grade::GradeOptions grade_options(const Checkpoint& checkpoint) const;
  // What a submission of `checkpoint` is graded against, with `options`' tolerance.
  grade::GradeSpec grade_spec(const Checkpoint& checkpoint, const grade::GradeOptions& options) const;
  // What a program is graded against where the page supplies its own reference ("custom"): the
  // course's tolerance, out of 1.
  grade::GradeSpec own_reference_spec(shader::ShaderFile vertex, shader::ShaderFile fragment) const;
  // What a checkpoint's saved frames are graded against: its grade spec without probe lights (the
  // page draws only under its own light), its mistakes, and the frames a student may have saved in
  // their place: each other preset's (another deliverable's frames under this one's names, the
  // starter's), named for what they are.
  grade::GradeSpec frames_grade_spec(const Checkpoint& checkpoint, const grade::GradeOptions& options) const;
  // Frame k's file name under `prefix`, with `extension` ("png"): hw2_specular_3.png.
  std::string frame_file(std::string_view prefix, int k, std::string_view extension) const;
  // A checkpoint's saved frames, first to last, as a student reads them: "hw2_specular_0.png to
  // hw2_specular_8.png".
  std::string saved_frame_range(const Checkpoint& checkpoint) const;
  // The names the page feeds the light's position by (what a probe light moves).
  std::vector<std::string> light_position_names() const;
  grade::ProbeUniform light_color_uniform() const;  // empty names: no uniform has the role
  // The checkpoint's formula with the course's values, for the grader (none when it has none).
  std::optional<grade::FormulaSpec> formula_spec(const Checkpoint& c) const;
  // What a download of ShadeLab's own frames says where the course wants frames saved from the
  // page: they are for checking, not for handing in. Empty where ShadeLab's frames may be handed in.
  std::string frames_download_notice() const;
  // The hand-in's title and the notebook's name as the course says them, or their plain words.
  std::string hand_in_name() const;
  std::string notebook_name() const;
  // The starter's specular exponent (the CPU reference's alpha); 0 when the profile sets none.
  double specular_exponent() const;
};

// The bounds an uploaded mesh is fitted to (`--fit`, "fit": true): the default mesh's.
Expected<scene::Bounds> fit_bounds(const Course& course);

// A course mesh, parsed (embedded ones from the binary).
Expected<scene::Mesh> load_course_mesh(const CourseMesh& mesh);

// The reference's locals that are `checkpoint`'s formula's vectors, with their words ("V": "the
// direction to the eye"); none where the checkpoint has no formula or names none.
grade::VectorWords vector_words(const Checkpoint& checkpoint);

}  // namespace shadelab::course
