#pragma once
// The homework page's contract (docs/homework-contract.md, shaders/README.md): what hw2.js feeds a
// student's program, by name, with its values. Everything here is CPU data.
#include <array>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

namespace shadelab::render {

inline constexpr const char* kPositionAttribute = "aVertexPosition";
inline constexpr const char* kNormalAttribute = "aVertexNormal";
inline constexpr unsigned kPositionLocation = 0;
inline constexpr unsigned kNormalLocation = 1;

// Camera: fovY 45 degrees, near 0.1, far 100, eye at the origin looking down -Z (world-to-camera
// is the identity). Mesh: rotated `degrees` about +Y, then translated to (0, -2, -7.5).
struct FrameTransforms {
  glm::mat4 world_to_clip;
  glm::mat4 mesh_to_world;
  glm::mat4 mesh_to_world_rot;
};
FrameTransforms homework_transforms(int width, int height, double degrees);

inline constexpr const char* kWorldToClip = "uWorldToClipSpaceMatrix";
inline constexpr const char* kMeshToWorld = "uMeshToWorldMatrix";
inline constexpr const char* kMeshToWorldRot = "uMeshToWorldRotMatrix";

// A constant uniform hw2.js sets. Colours are uploaded with uniform4fv, the light position with
// uniform3fv: a program that declares another type keeps the value at zero, as in the browser.
struct ConstantUniform {
  std::string_view name;
  std::string_view glsl_type;  // what the page's upload call requires
  std::array<float, 4> value;
  int components;
};

// Both spellings the handout allows (uDiffuseColor and diffuseColor) are fed.
const std::vector<ConstantUniform>& homework_constant_uniforms();

}  // namespace shadelab::render
