#pragma once
// What a homework page's script (hw2.js) states, read in the forms a course writes it: numbers
// under names (`const fieldOfView = 45.0;`), small arithmetic (`20 * Math.PI / 180`, `TIME * 20`,
// `-0.0`), a helper's arguments in its own order (`mat4Perspective(P, fieldOfView, aspect, zNear,
// zFar)`). It is not a JavaScript interpreter: what it cannot read is not stated, never guessed,
// and the import then says "assumed".
#include <array>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab::course {

class ScriptFacts {
 public:
  explicit ScriptFacts(std::string_view script);  // comments are dropped; strings are kept

  // The value of an expression of numbers, names bound by const/let/var, Math.PI, + - * / and
  // parentheses, and the degree helpers toRadian(x) / degToRad(x) / glMatrix.toRadian(x).
  std::optional<double> number(std::string_view expression) const;
  // A list of numbers: [a, b, c], new Float32Array([...]), or a name bound to one.
  std::optional<std::vector<double>> numbers(std::string_view expression) const;
  // Each call of a function whose name (dots included: mat4.perspective) matches `callee`, as its
  // arguments split at the top-level commas; a function's own definition is not a call.
  std::vector<std::vector<std::string>> calls(const std::regex& callee) const;
  // k where the script (or `within`, a part of it) multiplies `name` by a constant factor
  // (`k * TIME` or `TIME * k`, k a number or a bound name).
  std::optional<double> factor_of(std::string_view name) const;
  std::optional<double> factor_of(std::string_view name, std::string_view within) const;

  const std::string& text() const { return text_; }

 private:
  std::optional<double> number(std::string_view expression, int depth) const;
  std::optional<std::vector<double>> numbers(std::string_view expression, int depth) const;

  std::string text_;  // without comments
  std::string code_;  // and without the strings' contents, at the same offsets
  std::map<std::string, std::string, std::less<>> bound_;  // name -> the expression it is bound to, first binding
};

// The page's camera and spin, as the homework's script sets them up.
struct PageProjection {
  double fov_y_degrees = 0, near = 0, far = 0;
};
// The first perspective call (perspective, mat4Perspective, mat4.perspective) whose field of view,
// near and far read as numbers: the field of view is its first numeric argument (in degrees, or
// in radians when under pi, as a field of view in degrees never is), near and far its last two.
std::optional<PageProjection> projection_of(const ScriptFacts& script);
// The first translate call (translate, mat4Translate, mat4.translate) with a list of three numbers.
std::optional<std::array<double, 3>> mesh_translation_of(const ScriptFacts& script);
// The factor of TIME in a rotation call (rotateY(20 * TIME), rotationMat(M, TIME * 20, 1)), else
// anywhere in the script: degrees per second of the page's clock.
std::optional<double> degrees_per_second_of(const ScriptFacts& script);

}  // namespace shadelab::course
