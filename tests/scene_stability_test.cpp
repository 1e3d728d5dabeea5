// Hard cases for the scene renderer (ctest -L stability): every one renders finite radiance,
// and where a property is known, the render keeps it.
#include <gtest/gtest.h>

#include <cstring>

#include "support/scene_support.h"
#include "support/test_support.h"

using namespace shadelab;
using nlohmann::json;

namespace {
json base() {
  return {{"objects", {{{"name", "Ball"}, {"mesh", "uv_sphere"}, {"material", {{"metallic", 0.5}, {"roughness", 0.3}}}}}},
          {"ground", {{"size", 10}, {"height", -1}}},
          {"camera", {{"location", {0, -6, 2}}, {"target", {0, 0, 0}}}},
          {"lights", {{{"type", "sun"}, {"strength", 3}, {"rotation", {40, 0, 30}}},
                      {{"type", "point"}, {"power", 500}, {"location", {2, -2, 3}}}}},
          {"render", {{"width", 96}, {"height", 72}}}};
}

void expect_finite(const json& scene, const std::string& what) {
  auto r = testkit::render_scene(scene, true);
  ASSERT_TRUE(r) << what << ": " << r.error().format();
  EXPECT_EQ(testkit::non_finite_values(r->radiance), 0u) << what;
}

float radiance_at(const image::Image& img, int x, int y, int c) {
  float v;
  std::memcpy(&v, img.row(y) + static_cast<size_t>(x) * 16 + static_cast<size_t>(c) * 4, 4);
  return v;
}
}  // namespace

TEST(SceneStabilityTest, CameraInsideAnObject) {
  json s = base();
  s["camera"] = {{"location", {0, 0, 0}}, {"rotation", {90, 0, 0}}};
  expect_finite(s, "camera inside the sphere");
}

TEST(SceneStabilityTest, ExtremeLenses) {
  for (double lens : {1.0, 5000.0}) {
    json s = base();
    s["camera"]["lens"] = lens;
    expect_finite(s, "lens " + std::to_string(lens));
  }
  // 5000 mm from 6 m sees 4 cm across: the sphere fills the frame.
  json s = base();
  s["camera"]["lens"] = 5000.0;
  auto r = testkit::render_scene(s);
  ASSERT_TRUE(r);
  EXPECT_GT(testkit::framing_of(*r, "Ball")->image_coverage, 0.99);
}

TEST(SceneStabilityTest, LightOnTheSurface) {
  json s = base();
  s["lights"] = {{{"type", "point"}, {"power", 1000}, {"radius", 0}, {"location", {0, -1, 0}}},
                 {{"type", "spot"}, {"power", 1000}, {"radius", 0}, {"location", {0, 0, 1}}, {"rotation", {0, 0, 0}}},
                 {{"type", "area"}, {"power", 1000}, {"size", 0}, {"location", {0, 0, -1}}, {"rotation", {180, 0, 0}}}};
  expect_finite(s, "lights touching the sphere and the ground");
}

TEST(SceneStabilityTest, ZeroScaleObjectIsNotDrawn) {
  json s = base();
  s["objects"].push_back({{"name", "Flat"}, {"mesh", "cube"}, {"scale", {1, 0, 1}}});
  auto r = testkit::render_scene(s, true);
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_EQ(testkit::non_finite_values(r->radiance), 0u);
  const auto* f = testkit::framing_of(*r, "Flat");
  ASSERT_NE(f, nullptr);
  EXPECT_FALSE(f->drawn);
  EXPECT_EQ(f->image_coverage, 0.0);
}

TEST(SceneStabilityTest, RoughnessZeroAndOne) {
  // Roughness 0 is a mirror (a GGX lobe of width 0: a division by zero without the guard);
  // roughness 1 is the Phong exponent 0 of the homework's model. Both metal and dielectric.
  for (double roughness : {0.0, 1.0})
    for (double metallic : {0.0, 1.0}) {
      json s = base();
      s["objects"][0]["material"] = {{"roughness", roughness}, {"metallic", metallic}};
      expect_finite(s, "roughness " + std::to_string(roughness) + " metallic " + std::to_string(metallic));
    }
}

TEST(SceneStabilityTest, NearSingularNonUniformScaleKeepsNormals) {
  // A sphere squashed to 1e-6 of its height is a disc: its top must shade like a plane facing up
  // (the inverse-transpose normal matrix, computed in double), not black or NaN.
  json s = base();
  s["objects"][0]["scale"] = {1, 1, 1e-6};
  s["objects"][0]["material"] = {{"roughness", 1.0}, {"specular", 0.0}};
  s["camera"] = {{"location", {0, 0, 5}}, {"target", {0, 0, 0}}};
  s["lights"] = {{{"type", "sun"}, {"strength", 3}, {"castShadow", false}}};
  s["world"] = {{"color", {0, 0, 0}}};
  s.erase("ground");
  auto r = testkit::render_scene(s, true);
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_EQ(testkit::non_finite_values(r->radiance), 0u);
  // Straight-down sun on an upward plane: 0.8 / pi * 3 = 0.764.
  EXPECT_NEAR(radiance_at(r->radiance, 48, 36, 0), 0.8 / 3.14159265 * 3, 0.01);
}

TEST(SceneStabilityTest, FarFromTheOriginRendersLikeAtTheOrigin) {
  // Transforms are composed in double relative to the camera: moving the whole scene 1e5 m away
  // changes nothing a float32 vertex position could not hold.
  json near = base();
  json far = base();
  const double d = 1e5;
  far["objects"][0]["location"] = {d, d, 0};
  far["camera"] = {{"location", {d, d - 6, 2}}, {"target", {d, d, 0}}};
  far["lights"][1]["location"] = {d + 2, d - 2, 3};
  far.erase("ground");
  near.erase("ground");
  auto a = testkit::render_scene(near), b = testkit::render_scene(far);
  ASSERT_TRUE(a && b);
  size_t differing = 0;
  for (size_t i = 0; i < a->image.bytes.size(); ++i)
    if (std::abs(int(a->image.bytes[i]) - int(b->image.bytes[i])) > 2) ++differing;
  EXPECT_LT(static_cast<double>(differing) / a->image.bytes.size(), 0.002);
}

TEST(SceneStabilityTest, ExtremeNearFarKeepsDepthOrder) {
  // Clip range 1e-5 .. 1e7 (a ratio of 1e12): a red cube 2 km away in front of a blue one 1 m
  // behind it must still hide it. Reversed Z into a float depth buffer keeps them apart.
  json s = {{"objects", {{{"name", "Front"}, {"mesh", "cube"}, {"location", {0, 2000, 0}}, {"scale", 40},
                          {"material", {{"baseColor", {1, 0, 0}}, {"emission", {1, 0, 0}}, {"emissionStrength", 1}}}},
                         {{"name", "Back"}, {"mesh", "cube"}, {"location", {0, 2041, 0}}, {"scale", 60},
                          {"material", {{"baseColor", {0, 0, 1}}, {"emission", {0, 0, 1}}, {"emissionStrength", 1}}}}}},
            {"camera", {{"location", {0, 0, 0}}, {"rotation", {90, 0, 0}}, {"clipStart", 1e-5}, {"clipEnd", 1e7}}},
            {"world", {{"color", {0, 0, 0}}}},
            {"render", {{"width", 64}, {"height", 64}, {"viewTransform", "standard"}}}};
  auto r = testkit::render_scene(s);
  ASSERT_TRUE(r) << r.error().format();
  const auto px = testkit::pixel(r->image, 32, 32);
  EXPECT_GT(px[0], 200) << r->report.depth;
  EXPECT_LT(px[2], 50) << r->report.depth;
}

TEST(SceneStabilityTest, GrazingViewOfAPlane) {
  json s = base();
  s["ground"]["size"] = 1e4;
  s["camera"] = {{"location", {0, -50, -0.999}}, {"rotation", {90, 0, 0}}, {"clipEnd", 1e5}};
  expect_finite(s, "camera 1 mm above a 10 km plane, looking along it");
}
