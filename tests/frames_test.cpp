// Grading the frames a student saved from their browser (grade/judge_saved_frames.h), in process on
// the real renderer: frames drawn with the page's lag pass and the lag is found; each kind of wrong
// hand-in (another deliverable's frames, a repeated frame, the wrong size, frames that are not what
// the code renders) fails with a diagnosis a student can act on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "grade/judge_saved_frames.h"
#include "grade/lag_fit.h"
#include "image/encode.h"
#include "image/png_decode.h"
#include "support/test_support.h"

using namespace shadelab;

namespace {

// A page at 60 Hz lags each frame by up to 1/60 s of rotation; these are within that.
const std::vector<double> kLags = {0, 0.12, 0.21, 0.05, 0.3, 0.17, 0.26, 0.09, 0.23};

const scene::Mesh& bunny() { return testkit::builtin(testkit::course().default_mesh); }

std::vector<grade::SavedFrame> saved_frames(const std::string& preset, const std::string& prefix, const std::vector<double>& lags = kLags) {
  return testkit::saved_frames(preset, prefix, lags);
}

class FramesTest : public ::testing::Test {
 protected:
  // One set of renders for the suite, as one worker grading a class: the reference grid renders once.
  static grade::GradeRenders& renders() {
    static grade::GradeRenders r(testkit::shared_renderer());
    return r;
  }
  // `from_page`: the course wants frames saved from its page (the built-in course does).
  static grade::FramesGradeOutput grade(const std::string& checkpoint, const std::vector<grade::SavedFrame>& saved,
                                        const std::string& code_preset = "", bool from_page = true) {
    const course::Course& c = testkit::course();
    const auto found = c.checkpoint(checkpoint);
    EXPECT_TRUE(found.ok());
    grade::GradeSpec spec = c.frames_grade_spec(*found->checkpoint, grade::GradeOptions{.max_score = 1});
    EXPECT_TRUE(spec.frames_from_page);
    spec.frames_from_page = from_page;
    render::RenderRequest code = c.render_request({}, {});
    if (!code_preset.empty()) {
      const auto* p = c.preset(code_preset);
      code = c.render_request(p->vertex, p->fragment);
    }
    auto out = grade::judge_saved_frames(renders(), spec, code, saved, [] { return Expected<const scene::Mesh*>(&bunny()); }, "bunny",
                                      [](JobPhase) -> Status { return Ok{}; });
    EXPECT_TRUE(out.ok()) << (out ? "" : out.error().message);
    return out ? std::move(*out) : grade::FramesGradeOutput{};
  }
};

TEST_F(FramesTest, FramesDrawnWithThePagesLagPassAndTheLagIsFound) {
  const auto out = grade("specular", saved_frames("specular", "specular"));
  EXPECT_TRUE(out.frames.pass) << out.frames.diagnosis << ": " << (out.frames.messages.empty() ? "" : out.frames.messages[0]);
  EXPECT_EQ(out.frames.score, 1);
  ASSERT_EQ(out.frames.frames.size(), 9u);
  for (size_t k = 0; k < kLags.size(); ++k) {
    ASSERT_TRUE(out.frames.frames[k].lag_degrees.has_value()) << k;
    EXPECT_NEAR(*out.frames.frames[k].lag_degrees, kLags[k], 0.05) << "frame " << k;
  }
  EXPECT_FALSE(out.code.has_value());  // no code handed in: the frames alone
  EXPECT_FALSE(out.heatmap_png.empty());
}

// A slow machine's page at 30 Hz lags a frame by up to 0.67 degrees: inside the window, found, and
// nothing said about a lag beyond it.
TEST_F(FramesTest, FramesFromA30HzPagePassAndTheirLagIsFound) {
  const std::vector<double> lags = {0, 0.65, 0.42, 0.61, 0.55, 0.5, 0.66, 0.35, 0.58};
  const auto out = grade("specular", saved_frames("specular", "specular", lags));
  EXPECT_TRUE(out.frames.pass) << out.frames.diagnosis << ": " << (out.frames.messages.empty() ? "" : out.frames.messages[0]);
  ASSERT_EQ(out.frames.frames.size(), 9u);
  for (size_t k = 0; k < lags.size(); ++k) EXPECT_NEAR(out.frames.frames[k].lag_degrees.value_or(-1), lags[k], 0.05) << "frame " << k;
  for (const auto& m : out.frames.messages) EXPECT_EQ(m.find("or more behind"), std::string::npos) << m;
}

// A frame drawn further behind than any clock the window allows (a page that stalled) is a finding.
TEST_F(FramesTest, AFrameBeyondTheWindowIsSaidToBe) {
  std::vector<double> lags = kLags;
  lags[4] = 1.3;
  const auto out = grade("specular", saved_frames("specular", "specular", lags));
  bool said = false;
  for (const auto& m : out.frames.messages) said |= m.find("hw2_specular_4.png was drawn 0.70 degrees or more behind 80.00") != std::string::npos;
  EXPECT_TRUE(said) << ::testing::PrintToString(out.frames.messages);
  EXPECT_NEAR(out.frames.frames[3].lag_degrees.value_or(-1), kLags[3], 0.05);  // the others fitted as before
}

TEST_F(FramesTest, TheReferenceGridIsTheGradersWorkOncePerSession) {
  const auto saved = saved_frames("diffuse", "diffuse");
  grade("diffuse", saved);
  const auto again = grade("diffuse", saved);
  EXPECT_TRUE(again.frames.pass);
  // The grid (65 frames) from memory; only the reference at the fitted angles is rendered.
  EXPECT_EQ(again.frames.grader_work.rendered, 1);
  EXPECT_EQ(again.frames.grader_work.from_memory, 1);
}

bool has_flag(const grade::Report& r, grade::FlagKind kind) {
  for (const auto& f : r.flags)
    if (f.kind == kind) return true;
  return false;
}

// Frames at the exact angles that are not ShadeLab's to the pixel: another rasteriser's (a page
// with a fixed clock). Every 97th pixel of the object in each frame 12/255 brighter in red.
std::vector<grade::SavedFrame> from_another_rasteriser(std::vector<grade::SavedFrame> frames) {
  for (auto& f : frames) {
    auto image = image::decode_png(f.bytes);
    EXPECT_TRUE(image.ok());
    size_t object = 0;
    for (size_t i = 0; i < image->bytes.size(); i += 4) {
      const bool clear = image->bytes[i] == 0 && image->bytes[i + 1] == 0 && image->bytes[i + 2] == 0;
      if (!clear && ++object % 97 == 0) image->bytes[i] = static_cast<std::uint8_t>(std::min(255, image->bytes[i] + 12));
    }
    auto png = image::encode_png(*image);
    f.bytes.assign(png->begin(), png->end());
  }
  return frames;
}

// The reference's frames as ShadeLab draws them at exactly 20k degrees (GET /api/render's frames):
// no browser draws them, so where the course wants frames saved from its page they score 0, named.
TEST_F(FramesTest, ShadeLabsOwnFramesOfTheReferenceScoreZeroWhereTheCourseWantsPageFrames) {
  const auto out = grade("normals", saved_frames("normals", "normals", std::vector<double>(9, 0.0)));
  EXPECT_FALSE(out.frames.pass);
  EXPECT_EQ(out.frames.score, 0);
  EXPECT_EQ(out.frames.diagnosis, "made_by_shadelab");
  ASSERT_FALSE(out.frames.messages.empty());
  EXPECT_NE(out.frames.messages[0].find("saved from its page"), std::string::npos) << out.frames.messages[0];
  ASSERT_EQ(out.frames.flags.size(), 1u);
  EXPECT_EQ(out.frames.flags[0].kind, grade::FlagKind::made_by_shadelab);
  EXPECT_NE(out.frames.flags[0].message.find("made by ShadeLab, not saved from the page"), std::string::npos);
  for (const auto& f : out.frames.frames) EXPECT_TRUE(f.grade.pass) << "each frame matches; the hand-in is what fails";
}

TEST_F(FramesTest, ShadeLabsOwnFramesAreOnlyFlaggedWhereTheCourseAllowsThem) {
  const auto out = grade("normals", saved_frames("normals", "normals", std::vector<double>(9, 0.0)), "", false);
  EXPECT_TRUE(out.frames.pass) << out.frames.diagnosis;
  EXPECT_EQ(out.frames.score, 1);
  EXPECT_TRUE(has_flag(out.frames, grade::FlagKind::made_by_shadelab));
}

// A page with a fixed clock: every frame at its exact angle, but drawn by another rasteriser. It
// passes; the TA is told there was no lag.
TEST_F(FramesTest, FramesWithNoLagThatAreNotShadeLabsPassFlaggedForTheTA) {
  const auto out = grade("normals", from_another_rasteriser(saved_frames("normals", "normals", std::vector<double>(9, 0.0))));
  EXPECT_TRUE(out.frames.pass) << out.frames.diagnosis;
  EXPECT_EQ(out.frames.score, 1);
  for (const auto& f : out.frames.frames) EXPECT_NEAR(*f.lag_degrees, 0, 0.05);
  ASSERT_EQ(out.frames.flags.size(), 1u);
  EXPECT_EQ(out.frames.flags[0].kind, grade::FlagKind::no_lag);
}

// Frames drawn as a page on a running clock draws them (60 and 30 Hz): no flag at all.
TEST_F(FramesTest, FramesAtThePagesLagAreNotFlagged) {
  EXPECT_TRUE(grade("specular", saved_frames("specular", "specular")).frames.flags.empty());
  const std::vector<double> at_30hz = {0, 0.65, 0.42, 0.61, 0.55, 0.5, 0.66, 0.35, 0.58};
  EXPECT_TRUE(grade("specular", saved_frames("specular", "specular", at_30hz)).frames.flags.empty());
}

TEST_F(FramesTest, DiffuseFramesHandedInAsSpecularAreNamedForWhatTheyAre) {
  const auto out = grade("specular", saved_frames("diffuse", "specular"));
  EXPECT_FALSE(out.frames.pass);
  EXPECT_EQ(out.frames.score, 0);
  EXPECT_EQ(out.frames.diagnosis, "missing_specular");
}

TEST_F(FramesTest, NormalsFramesHandedInAsSpecularAreNamedForWhatTheyAre) {
  const auto out = grade("specular", saved_frames("normals", "specular"));
  EXPECT_FALSE(out.frames.pass);
  EXPECT_EQ(out.frames.diagnosis, "frames_of_normals");
  ASSERT_FALSE(out.frames.messages.empty());
  EXPECT_NE(out.frames.messages[0].find("hw2_normals_0.png"), std::string::npos) << out.frames.messages[0];
}

TEST_F(FramesTest, TheStartersFlatFramesAreFlatShading) {
  const auto out = grade("normals", saved_frames("starter", "normals"));
  EXPECT_FALSE(out.frames.pass);
  EXPECT_EQ(out.frames.diagnosis, "flat_shading");
}

TEST_F(FramesTest, AFrameSavedTwiceIsOutOfOrder) {
  auto saved = saved_frames("specular", "specular");
  saved[5].bytes = saved[4].bytes;
  const auto out = grade("specular", saved);
  EXPECT_FALSE(out.frames.pass);
  EXPECT_EQ(out.frames.diagnosis, "frames_out_of_order");
  EXPECT_FALSE(out.frames.frames[5].grade.pass);
  ASSERT_FALSE(out.frames.messages.empty());
  EXPECT_NE(out.frames.messages[0].find("hw2_specular_5.png shows frame 4"), std::string::npos) << out.frames.messages[0];
}

TEST_F(FramesTest, FramesOfTheWrongSizeAreInvalidAndSaySo) {
  render::RenderRequest request = testkit::preset_request("specular");
  request.width = 640;
  request.height = 480;
  request.frames = 1;
  auto rendered = testkit::render_frames(request, bunny());
  ASSERT_TRUE(rendered.ok());
  auto png = image::encode_png(rendered->frames[0]);
  auto saved = saved_frames("specular", "specular");
  saved[2].bytes.assign(png->begin(), png->end());
  const auto out = grade("specular", saved);
  EXPECT_FALSE(out.frames.pass);
  EXPECT_EQ(out.frames.diagnosis, "frames_invalid");
  ASSERT_FALSE(out.frames.messages.empty());
  EXPECT_NE(out.frames.messages[0].find("hw2_specular_2.png is 640 x 480"), std::string::npos) << out.frames.messages[0];
}

TEST_F(FramesTest, BytesThatAreNotAPngAreInvalid) {
  auto saved = saved_frames("normals", "normals");
  saved[0].bytes = "GIF89a not a png";
  const auto out = grade("normals", saved);
  EXPECT_EQ(out.frames.diagnosis, "frames_invalid");
  EXPECT_NE(out.frames.messages[0].find("hw2_normals_0.png"), std::string::npos) << out.frames.messages[0];
}

TEST_F(FramesTest, TooFewFramesAreInvalid) {
  auto saved = saved_frames("normals", "normals");
  saved.pop_back();
  const auto out = grade("normals", saved);
  EXPECT_EQ(out.frames.diagnosis, "frames_invalid");
}

TEST_F(FramesTest, FramesThatAreWhatTheCodeRendersMatchIt) {
  const auto out = grade("specular", saved_frames("specular", "specular"), "specular");
  EXPECT_TRUE(out.frames.pass);
  ASSERT_TRUE(out.code.has_value());
  EXPECT_TRUE(out.code->pass) << out.code->diagnosis;
}

TEST_F(FramesTest, StaleFramesFromAnEarlierVersionOfCorrectCodeAreStale) {
  // The code is right; the frames were saved before the specular term was written.
  const auto out = grade("specular", saved_frames("diffuse", "specular"), "specular");
  EXPECT_FALSE(out.frames.pass);
  ASSERT_TRUE(out.code.has_value());
  EXPECT_FALSE(out.code->pass);
  EXPECT_EQ(out.code->diagnosis, "stale_frames");
}

TEST_F(FramesTest, OneEditedFrameIsFoundAmongFramesFromTheCode) {
  auto saved = saved_frames("specular", "specular");
  saved[3] = saved_frames("diffuse", "specular")[3];
  const auto out = grade("specular", saved, "specular");
  ASSERT_TRUE(out.code.has_value());
  EXPECT_EQ(out.code->diagnosis, "edited_frames");
  EXPECT_NE(out.code->messages[0].find("frame 3 differs"), std::string::npos) << out.code->messages[0];
}

TEST_F(FramesTest, CorrectFramesFromOtherCodeAreNotFromTheCode) {
  const auto out = grade("specular", saved_frames("specular", "specular"), "diffuse");
  EXPECT_TRUE(out.frames.pass);
  ASSERT_TRUE(out.code.has_value());
  EXPECT_EQ(out.code->diagnosis, "frames_not_from_code");
}

TEST_F(FramesTest, CodeThatDoesNotCompileIsTheCodesReportNotTheFrames) {
  const course::Course& c = testkit::course();
  const auto found = c.checkpoint("specular");
  const grade::GradeSpec spec = c.frames_grade_spec(*found->checkpoint, grade::GradeOptions{.max_score = 1});
  const auto* p = c.preset("specular");
  shader::ShaderFile broken = p->fragment;
  broken.text.replace(broken.text.find("void main"), 9, "float broken() { return undeclared_name; }\nvoid main");
  auto out = grade::judge_saved_frames(renders(), spec, c.render_request(p->vertex, broken), saved_frames("specular", "specular"),
                                    [] { return Expected<const scene::Mesh*>(&bunny()); }, "bunny", [](JobPhase) -> Status { return Ok{}; });
  ASSERT_TRUE(out.ok());
  EXPECT_TRUE(out->frames.pass);
  ASSERT_TRUE(out->code.has_value());
  EXPECT_FALSE(out->code->pass);
  EXPECT_EQ(out->code->diagnosis, "compile_failed");
}

// The lag fit on its own: a frame drawn further behind than the window is fitted at the window's
// edge and said to be; the fit's parabola lands between grid steps.
TEST(LagFit, TheGridAndItsIndexAgree) {
  const grade::LagGrid grid;
  const auto angles = grid.angles();
  EXPECT_EQ(angles.size(), 1u + 8u * static_cast<size_t>(grid.steps()));
  EXPECT_EQ(grid.steps(), 8);  // a 30 Hz clock's interval (0.67 degrees) inside the window
  EXPECT_DOUBLE_EQ(angles[grid.index(0, 0)], 0);
  EXPECT_DOUBLE_EQ(angles[grid.index(3, 0)], 60);
  EXPECT_NEAR(angles[grid.index(3, 7)], 60 - 0.7, 1e-9);
}

TEST(PngDecode, RejectsWhatIsNotAPngAndTooLargeASide) {
  EXPECT_FALSE(image::decode_png("").ok());
  EXPECT_FALSE(image::decode_png(std::string(100, '\x89')).ok());
  image::Image big{1, 5000, image::PixelType::u8, std::vector<std::uint8_t>(5000 * 4, 255)};
  auto png = image::encode_png(big);
  ASSERT_TRUE(png.ok());
  auto decoded = image::decode_png(std::string(png->begin(), png->end()));
  ASSERT_FALSE(decoded.ok());
  EXPECT_NE(decoded.error().message.find("5000"), std::string::npos) << decoded.error().message;
}

}  // namespace
