#pragma once
// The homework page's contract (docs/homework-contract.md, shaders/README.md): the names hw2.js
// feeds a student's program by, and the shape of what it feeds. The values (the camera, the
// colours, the light) are an offering's facts: the course profile (course/course.h) sets them in
// each request's PageSetup. Everything here is CPU data.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace shadelab::render {

inline constexpr const char* kPositionAttribute = "aVertexPosition";
inline constexpr const char* kNormalAttribute = "aVertexNormal";
inline constexpr unsigned kPositionLocation = 0;
inline constexpr unsigned kNormalLocation = 1;

inline constexpr const char* kWorldToClip = "uWorldToClipSpaceMatrix";
inline constexpr const char* kMeshToWorld = "uMeshToWorldMatrix";
inline constexpr const char* kMeshToWorldRot = "uMeshToWorldRotMatrix";

// The page's camera: world-to-camera is the identity (the eye at the origin looking down -Z), a
// perspective projection with the canvas's aspect, and the mesh rotated about +Y, then moved.
// Zero-initialised: a request without a course's camera is refused by validate().
struct PageCamera {
  double fov_y_degrees = 0;
  double near = 0, far = 0;
  glm::dvec3 mesh_translation{0.0};
};

struct FrameTransforms {
  glm::mat4 world_to_clip;
  glm::mat4 mesh_to_world;
  glm::mat4 mesh_to_world_rot;
};
FrameTransforms homework_transforms(const PageCamera& camera, int width, int height, double degrees);

// A constant uniform the page sets. Colours are uploaded with uniform4fv, the light position with
// uniform3fv: a program that declares another type keeps the value at zero, as in the browser.
struct ConstantUniform {
  std::string name;
  std::string glsl_type;  // what the page's upload call requires: "vec4"
  std::array<float, 4> value{};
  int components = 0;
};

// What the page sets up before it draws: the camera and the constant uniforms (every spelling
// the course feeds, uDiffuseColor and diffuseColor alike).
struct PageSetup {
  PageCamera camera;
  std::vector<ConstantUniform> uniforms;
};

// A frame's file name from the course's pattern ("hw2_{prefix}_{k}"), as the page's download names
// it; `index` in place of {k} names the set ("frames": hw2_specular_frames.zip).
std::string frame_file_name(std::string_view pattern, std::string_view prefix, std::string_view index, std::string_view extension);
std::string frame_file_name(std::string_view pattern, std::string_view prefix, int k, std::string_view extension);

}  // namespace shadelab::render
