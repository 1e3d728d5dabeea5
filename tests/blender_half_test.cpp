// The Blender half's cameras checked by the subject's outline (grade/outline.h, grade/camera_check.h)
// against ShadeLab's own renders of the handout's dolly zoom: Blender's own renders of the three
// cameras match them, and so do renders by the other engine with another light, background and
// size; one image saved twice, the handout's 50 mm typo followed, a camera left where it was and an
// image of something else are each named for what they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "grade/camera_check.h"
#include "grade/render_check.h"
#include "image/png_decode.h"
#include "support/files.h"
#include "support/scene_support.h"
#include "support/test_support.h"

using namespace shadelab;
using nlohmann::json;

namespace {

// The handout's three cameras, as the example scenes (assets/scenes/dolly_*.json) hold them.
const grade::CameraView k25{25, {0, -4, 0}}, k50{50, {0, -8, 0}}, k100{100, {0, -16, 0}};

json dolly(const grade::CameraView& v, int width, int height) {
  json scene = testkit::example_scene("dolly_25mm");
  scene["camera"]["lens"] = v.lens_mm;
  scene["camera"]["location"] = {v.location.x, v.location.y, v.location.z};
  scene["render"]["width"] = width;
  scene["render"]["height"] = height;
  return scene;
}

// What a student might render instead of Blender's Workbench: Eevee, lit by the default scene's
// light, in front of an orange world.
json eevee_dolly(const grade::CameraView& v, int width, int height) {
  json scene = dolly(v, width, height);
  scene["render"]["engine"] = "eevee";
  scene["lights"] = json::array({{{"type", "point"}, {"location", {4.0762, 1.0055, 5.9039}}, {"power", 1000}}});
  scene["world"] = {{"color", {0.6, 0.25, 0.05}}};
  return scene;
}

image::Image rendered(const json& scene) {
  auto r = testkit::render_scene(scene);
  EXPECT_TRUE(r) << r.error().format();
  return r ? r->image : image::Image{};
}

image::Image blender(int lens) {
  const auto png = testkit::read_text(std::filesystem::path(SHADELAB_SOURCE_DIR) / "tests/blender_half" /
                                      ("blender_camera_" + std::to_string(lens) + ".png"));
  auto decoded = image::decode_png(png);
  EXPECT_TRUE(decoded) << decoded.error().message;
  return decoded ? *decoded : image::Image{};
}

// ShadeLab's Workbench render of the subject from a view, as the worker makes it.
Expected<grade::Outline> view_outline(const grade::CameraView& v, int width, int height) {
  auto r = testkit::render_scene(dolly(v, width, height));
  if (!r) return r.take_error();
  return grade::outline_of(r->image, grade::CameraCheckOptions{}.background_tolerance);
}

std::vector<grade::CameraVerdict> judged(const image::Image& at25, const image::Image& at50, const image::Image& at100) {
  auto verdicts = grade::judge_cameras({{"images/camera_25.png", k25, at25, {}},
                                        {"images/camera_50.png", k50, at50, {}},
                                        {"images/camera_100.png", k100, at100, {}}},
                                       view_outline);
  EXPECT_TRUE(verdicts) << verdicts.error().message;
  return verdicts ? *verdicts : std::vector<grade::CameraVerdict>(3);
}

std::string said(const std::vector<grade::CameraVerdict>& verdicts) {
  std::string out;
  for (const auto& v : verdicts) out += v.message + "\n";
  return out;
}

}  // namespace

// The thresholds' footing, printed as docs/grading.md's table: renders made elsewhere overlap their
// own view by more than the 90% that matches, and the next view by more than the 1% that must
// stand out.
TEST(CameraCheckTest, TheMarginsTheThresholdsRestOn) {
  const grade::CameraCheckOptions options;
  std::vector<std::pair<grade::CameraView, grade::Outline>> views;
  for (const auto& v : {k25, k50, k100}) views.emplace_back(v, *view_outline(v, 320, 240));
  for (const auto& [view, outline] : views) {
    std::printf("ShadeLab %-19s", (std::to_string(static_cast<int>(view.lens_mm)) + " mm").c_str());
    for (const auto& other : views) std::printf(" %.3f", grade::overlap(outline, other.second));
    std::printf("\n");
  }
  const auto row = [&](const std::string& name, const image::Image& image, const grade::CameraView& own) {
    const grade::Outline outline = grade::resampled(grade::outline_of(image, options.background_tolerance), 320, 240);
    double mine = 0, next = 0;
    std::printf("%-28s", name.c_str());
    for (const auto& [view, reference] : views) {
      const double o = grade::overlap(outline, reference);
      std::printf(" %.3f", o);
      (view == own ? mine : next) = view == own ? o : std::max(next, o);
    }
    std::printf("\n");
    EXPECT_GE(mine, options.matches) << name;
    EXPECT_GT(mine - next, options.stands_out) << name;
  };
  for (const auto& [lens, view] : {std::pair{25, k25}, {50, k50}, {100, k100}}) {
    row("Blender " + std::to_string(lens) + " mm", blender(lens), view);
    row("Eevee " + std::to_string(lens) + " mm", rendered(eevee_dolly(view, 640, 480)), view);
  }
}

TEST(CameraCheckTest, BlendersOwnRendersMatchTheHandoutsCameras) {
  const auto verdicts = judged(blender(25), blender(50), blender(100));
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(verdicts[i].pass) << said(verdicts);
    EXPECT_GT(verdicts[i].overlap, 0.98) << said(verdicts);
    EXPECT_NEAR(verdicts[i].size_ratio, 1.0, 0.02) << said(verdicts);
  }
  ASSERT_TRUE(verdicts[2].seen);
  EXPECT_EQ(*verdicts[2].seen, k100);
  EXPECT_NE(verdicts[0].message.find("matches the handout's camera (a 25 mm lens at (0, -4, 0)"), std::string::npos) << said(verdicts);
}

TEST(CameraCheckTest, AnotherEngineLightBackgroundAndSizeStillMatch) {
  const auto verdicts =
      judged(rendered(eevee_dolly(k25, 800, 600)), rendered(eevee_dolly(k50, 800, 600)), rendered(eevee_dolly(k100, 800, 600)));
  for (const auto& v : verdicts) EXPECT_TRUE(v.pass) << said(verdicts);
}

TEST(CameraCheckTest, OneImageSavedForTwoCamerasIsNamed) {
  const image::Image fifty = blender(50);
  const auto verdicts = judged(blender(25), fifty, fifty);
  EXPECT_TRUE(verdicts[0].pass) << said(verdicts);
  EXPECT_TRUE(verdicts[1].pass) << said(verdicts);
  EXPECT_FALSE(verdicts[2].pass);
  EXPECT_EQ(verdicts[2].message.rfind("the same image as images/camera_50.png: shows a 50 mm lens at (0, -8, 0)", 0), 0u) << said(verdicts);
}

TEST(CameraCheckTest, TheHandoutsFiftyMillimetreTypoFollowedIsTheLens) {
  // The handout's text says 50 mm at (0, -16, 0); the file's name and the effect need 100 mm.
  const auto verdicts = judged(blender(25), blender(50), rendered(dolly({50, {0, -16, 0}}, 640, 480)));
  EXPECT_TRUE(verdicts[0].pass && verdicts[1].pass) << said(verdicts);
  EXPECT_FALSE(verdicts[2].pass);
  ASSERT_TRUE(verdicts[2].seen) << said(verdicts);
  EXPECT_EQ(*verdicts[2].seen, (grade::CameraView{50, {0, -16, 0}}));
  EXPECT_NE(verdicts[2].message.find("the camera is in place, the lens is not"), std::string::npos) << said(verdicts);
  EXPECT_NEAR(verdicts[2].size_ratio, 0.5, 0.03) << "half the lens, half the size";
}

TEST(CameraCheckTest, ACameraLeftWhereItWasIsTheCamerasPlace) {
  const auto verdicts = judged(blender(25), rendered(dolly({50, {0, -4, 0}}, 640, 480)), blender(100));
  EXPECT_FALSE(verdicts[1].pass);
  ASSERT_TRUE(verdicts[1].seen) << said(verdicts);
  EXPECT_EQ(*verdicts[1].seen, (grade::CameraView{50, {0, -4, 0}}));
  EXPECT_NE(verdicts[1].message.find("the lens is right, the camera is not where the handout puts it"), std::string::npos) << said(verdicts);
}

TEST(CameraCheckTest, SomethingElseOrNothingIsNeverAConfidentGuess) {
  const image::Image other = rendered([] {
    json scene = testkit::example_scene("two_objects");
    scene["render"]["width"] = 320;
    scene["render"]["height"] = 240;
    return scene;
  }());
  image::Image grey = image::Image::blank(320, 240, image::PixelType::u8);
  std::fill(grey.bytes.begin(), grey.bytes.end(), std::uint8_t{90});
  auto verdicts = grade::judge_cameras({{"images/camera_25.png", k25, other, {}},
                                        {"images/camera_50.png", k50, grey, {}},
                                        {"images/camera_100.png", k100, std::nullopt, "not in the submission"}},
                                       view_outline);
  ASSERT_TRUE(verdicts) << verdicts.error().message;
  for (const auto& v : *verdicts) {
    EXPECT_FALSE(v.pass) << v.message;
    EXPECT_FALSE(v.seen) << v.message;
  }
  EXPECT_NE((*verdicts)[0].message.find("does not match the handout's camera, and no other of its cameras stands out"), std::string::npos)
      << (*verdicts)[0].message;
  EXPECT_NE((*verdicts)[1].message.find("not checked: the subject cannot be told from the background"), std::string::npos)
      << (*verdicts)[1].message;
  EXPECT_EQ((*verdicts)[2].message, "not in the submission");
}

// The Eevee render (grade/render_check.h): what the image alone shows, and the rest left to the TA.
TEST(RenderCheckTest, BlendersAndShadeLabsTwoObjectsAreAPngAndNotBlank) {
  const auto png = testkit::read_text(std::filesystem::path(SHADELAB_SOURCE_DIR) / "tests/blender_half/blender_two_objects_eevee.png");
  auto blender_render = image::decode_png(png);
  ASSERT_TRUE(blender_render);
  for (const auto& [who, image] :
       {std::pair<std::string, image::Image>{"Blender", *blender_render}, {"ShadeLab", rendered(testkit::example_scene("two_objects"))}}) {
    const auto r = grade::check_render(image);
    EXPECT_TRUE(r.pass) << who << ": " << r.facts_line();
    EXPECT_TRUE(r.facts_line().starts_with("a PNG: yes (640 x 480); not blank: yes (")) << who << ": " << r.facts_line();
  }
  EXPECT_NE(grade::render_check_leaves_out(2).find("That it shows 2 objects on a plane, each fully within the image, with different "
                                                   "materials, is the TA's to judge"),
            std::string::npos);
}

TEST(RenderCheckTest, ABlankImageIsNamed) {
  image::Image grey = image::Image::blank(320, 240, image::PixelType::u8);
  std::fill(grey.bytes.begin(), grey.bytes.end(), std::uint8_t{90});
  grey.bytes[0] = 200;  // one pixel off is still blank
  const auto blank = grade::check_render(grey);
  EXPECT_FALSE(blank.pass);
  EXPECT_EQ(blank.facts_line(), "a PNG: yes (320 x 240); not blank: no (0.0% of the pixels differ from the commonest colour)");
}
