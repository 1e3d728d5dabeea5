// The scene format and Blender's conventions, without GL: parsing, axes, lenses, dolly zoom,
// and which passes a scene calls for.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "scene/blender_convention.h"
#include "scene/camera_model.h"
#include "scene/dolly_zoom.h"
#include "scene/pass_plan.h"
#include "scene/scene_description.h"
#include "scene/scene_mesh.h"

using namespace shadelab;
using nlohmann::json;

namespace {
json minimal() { return {{"objects", {{{"mesh", "cube"}}}}}; }

scene::SceneDescription parsed(const json& j) {
  auto s = scene::parse_scene(j);
  EXPECT_TRUE(s) << (s ? "" : s.error().message);
  return s ? *s : scene::SceneDescription{};
}

std::string error_of(const json& j) {
  auto s = scene::parse_scene(j);
  EXPECT_FALSE(s);
  return s ? "" : s.error().message;
}
}  // namespace

TEST(SceneDescriptionTest, DefaultsAreBlendersPrincipledAndEevee) {
  const auto s = parsed(minimal());
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].material.base_color, glm::dvec3(0.8));
  EXPECT_EQ(s.objects[0].material.roughness, 0.5);
  EXPECT_EQ(s.objects[0].material.specular, 0.5);
  EXPECT_EQ(s.render.engine, scene::Engine::eevee);
  EXPECT_EQ(s.render.view_transform, scene::ViewTransform::filmic);
  EXPECT_EQ(s.camera.lens_mm, 50);
  EXPECT_FALSE(s.ground);
  // Blender's default output, what students hand in.
  EXPECT_EQ(s.render.width, 1920);
  EXPECT_EQ(s.render.height, 1080);
}

// Resolution % scales the output as Blender does (rounded down), the framing unchanged.
TEST(SceneDescriptionTest, ResolutionPercentageScalesTheOutputAsBlenderDoes) {
  auto j = minimal();
  j["render"] = {{"width", 1920}, {"height", 1080}, {"resolutionPercentage", 25}};
  auto s = parsed(j);
  EXPECT_EQ(s.render.width, 480);
  EXPECT_EQ(s.render.height, 270);
  EXPECT_EQ(s.render.percentage, 25);
  j["render"] = {{"width", 641}, {"height", 3}, {"resolutionPercentage", 33}};
  s = parsed(j);
  EXPECT_EQ(s.render.width, 211);
  EXPECT_EQ(s.render.height, 1) << "never below one pixel";
  j["render"] = {{"resolutionPercentage", 0}};
  EXPECT_FALSE(scene::parse_scene(j));
}

TEST(SceneDescriptionTest, ErrorsNameTheField) {
  EXPECT_EQ(error_of({{"objects", json::array()}}), "objects: expected a non-empty array of objects");
  json j = minimal();
  j["objects"][0]["material"] = {{"roughness", 1.5}};
  EXPECT_EQ(error_of(j), "objects[0].material.roughness: expected a number in [0, 1]");
  j = minimal();
  j["objects"][0]["location"] = {1, 2};
  EXPECT_EQ(error_of(j), "objects[0].location: expected [x, y, z]");
  j = minimal();
  j["objects"][0]["mesh"] = "";
  EXPECT_EQ(error_of(j), "objects[0].mesh: empty (name a built-in mesh, an uploaded mesh id or a file field)");
  j = minimal();
  j["camera"] = {{"lens", 0.5}};
  EXPECT_EQ(error_of(j), "camera.lens: expected a number in [1, 5000]");
  j = minimal();
  j["camera"] = {{"clipStart", 10}, {"clipEnd", 1}};
  EXPECT_EQ(error_of(j), "camera.clipEnd: must be greater than clipStart");
  j = minimal();
  j["lights"] = {{{"type", "laser"}}};
  EXPECT_EQ(error_of(j), "lights[0].type: expected one of area, point, spot, sun");
  j = minimal();
  j["render"] = {{"shadowMapSize", 1000}};
  EXPECT_EQ(error_of(j), "render.shadowMapSize: expected a power of two");
  j = minimal();
  j["objects"][0]["colour"] = "red";
  EXPECT_EQ(error_of(j), "objects[0].colour: unknown field");
  EXPECT_EQ(error_of(json::array()), "the scene must be a JSON object");
  j = minimal();
  j["objects"].push_back({{"mesh", "cube"}});
  j["objects"][0]["name"] = "A";
  j["objects"][1]["name"] = "A";
  EXPECT_EQ(error_of(j), "objects: two objects are named 'A'");
}

TEST(BlenderConventionTest, CameraRotation90LooksAlongPlusY) {
  const glm::dmat3 r = scene::euler_xyz_degrees({90, 0, 0});
  const glm::dvec3 forward = r * glm::dvec3(0, 0, -1), up = r * glm::dvec3(0, 1, 0);
  EXPECT_NEAR(forward.y, 1, 1e-12);
  EXPECT_NEAR(up.z, 1, 1e-12);
  // Z then Y then X applied last-to-first: Rz * Ry * Rx.
  const glm::dvec3 v = scene::euler_xyz_degrees({0, 0, 90}) * glm::dvec3(1, 0, 0);
  EXPECT_NEAR(v.y, 1, 1e-12);
}

TEST(BlenderConventionTest, LookAtKeepsUpTowardsWorldZ) {
  const glm::dmat3 r = scene::look_at_rotation({0, -7, 3}, {0, 0, 0.8});
  const glm::dvec3 forward = r * glm::dvec3(0, 0, -1), up = r * glm::dvec3(0, 1, 0);
  EXPECT_NEAR(glm::dot(forward, glm::normalize(glm::dvec3(0, 7, -2.2))), 1, 1e-12);
  EXPECT_GT(up.z, 0.9);
  EXPECT_NEAR(std::abs((r * glm::dvec3(1, 0, 0)).z), 0, 1e-12);  // no roll
  // Straight down still gives a valid frame.
  const glm::dmat3 down = scene::look_at_rotation({0, 0, 5}, {0, 0, 0});
  EXPECT_NEAR(glm::determinant(down), 1, 1e-12);
}

TEST(BlenderConventionTest, LensToFieldOfViewMatchesBlender) {
  // Blender's figures for the reference scene: 50 mm on a 36 mm sensor, 640 x 480, fit auto.
  scene::Camera c;
  c.lens_mm = 50;
  const auto m = scene::make_camera(c, 640, 480);
  EXPECT_NEAR(m.horizontal_fov_degrees(), 39.5978, 1e-4);
  EXPECT_NEAR(m.vertical_fov_degrees(), 30.2192, 1e-4);
  // Portrait: the sensor spans the height.
  const auto p = scene::make_camera(c, 480, 640);
  EXPECT_NEAR(p.vertical_fov_degrees(), 39.5978, 1e-4);
  c.sensor_fit = scene::SensorFit::vertical;
  EXPECT_NEAR(scene::make_camera(c, 640, 480).vertical_fov_degrees(), 39.5978, 1e-4);
}

TEST(BlenderConventionTest, YUpFilesStandUpInTheZUpWorld) {
  EXPECT_EQ(scene::y_up_to_z_up({1, 2, 3}), glm::dvec3(1, -3, 2));
  EXPECT_TRUE(scene::format_is_y_up("obj"));
  EXPECT_TRUE(scene::format_is_y_up("GLB"));
  EXPECT_FALSE(scene::format_is_y_up("stl"));
  // Suzanne's face looks at -Y in Blender; its OBJ export has it looking at +Z.
  auto suzanne = scene::builtin_scene_mesh("suzanne");
  ASSERT_TRUE(suzanne);
  double front = 0;
  for (const auto& p : suzanne->positions) front = std::min(front, static_cast<double>(p.y));
  EXPECT_LT(front, -0.8);
  const auto b = scene::bounds(*suzanne);
  EXPECT_NEAR(b.max.x - b.min.x, 2.734, 0.01);  // Blender's monkey at size 2
}

TEST(BlenderConventionTest, ProjectPutsTheTargetAtTheImageCentre) {
  scene::Camera c;
  c.location = {3, -5, 2};
  c.target = {0.5, 0.25, 1};
  const auto m = scene::make_camera(c, 640, 480);
  const auto p = m.project({0.5, 0.25, 1});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->x, 320, 1e-9);
  EXPECT_NEAR(p->y, 240, 1e-9);
  EXPECT_FALSE(m.project({6, -10, 3}));  // behind the camera
}

TEST(DollyZoomTest, DistanceScalesWithTheLens) {
  const auto stops = scene::dolly_zoom({0, 0, 0}, {0, -4, 0}, 25, {25, 50, 100});
  ASSERT_EQ(stops.size(), 3u);
  EXPECT_EQ(stops[1].location, glm::dvec3(0, -8, 0));   // the handout's placements
  EXPECT_EQ(stops[2].location, glm::dvec3(0, -16, 0));
  const auto off_axis = scene::dolly_zoom({1, 1, 1}, {1, -2, 5}, 35, {70});
  EXPECT_NEAR(off_axis[0].distance, 10, 1e-12);
  EXPECT_NEAR(glm::length(off_axis[0].location - glm::dvec3(1, 1, 1)), 10, 1e-12);
}

TEST(PassPlanTest, OnlyWhatTheSceneCallsFor) {
  json j = minimal();
  auto plan = scene::plan_passes(parsed(j));
  EXPECT_FALSE(plan.shadows);
  EXPECT_FALSE(plan.reflection);
  EXPECT_FALSE(plan.subsurface);
  EXPECT_TRUE(plan.features().empty());

  j["lights"] = {{{"type", "sun"}, {"castShadow", false}}};
  EXPECT_FALSE(scene::plan_passes(parsed(j)).shadows) << "a light that casts no shadow";
  j["lights"] = {{{"type", "point"}, {"power", 0}}};
  EXPECT_FALSE(scene::plan_passes(parsed(j)).shadows) << "a light that gives no light";
  j["lights"] = {{{"type", "sun"}}};
  EXPECT_TRUE(scene::plan_passes(parsed(j)).shadows);
  j["objects"][0]["scale"] = 0;
  EXPECT_FALSE(scene::plan_passes(parsed(j)).shadows) << "nothing drawn casts a shadow";
  j["objects"][0]["scale"] = 1;

  j["objects"][0]["material"] = {{"metallic", 1}};
  EXPECT_FALSE(scene::plan_passes(parsed(j)).reflection) << "no ground to reflect";
  j["ground"] = {{"size", 10}};
  EXPECT_TRUE(scene::plan_passes(parsed(j)).reflection);
  j["objects"][0]["material"] = {{"roughness", 0.8}};
  EXPECT_FALSE(scene::plan_passes(parsed(j)).reflection) << "a rough dielectric is not glossy";

  j["objects"][0]["material"] = {{"subsurface", 0.3}};
  EXPECT_TRUE(scene::plan_passes(parsed(j)).subsurface);
  j["render"] = {{"engine", "workbench"}};
  plan = scene::plan_passes(parsed(j));
  EXPECT_FALSE(plan.subsurface) << "Workbench has no subsurface";
  EXPECT_FALSE(plan.shadows) << "Workbench shadows are opt-in";
}
