// Rendering behaviour on a real EGL context (llvmpipe where there is no GPU).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>

#include "egl/device_survey.h"
#include "egl/headless_context.h"
#include "gl/mesh_buffer.h"
#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "support/test_support.h"

using namespace shadelab;
using testkit::fullscreen_request;
using testkit::pixel;
using testkit::render_frames;

namespace {
const scene::Mesh& bunny() { return testkit::builtin("bunny"); }

bool has_warning(const render::RenderReport& r, const std::string& needle) {
  for (const auto& w : r.warnings)
    if (w.find(needle) != std::string::npos) return true;
  return false;
}

std::vector<std::uint8_t> grid_png(const render::RenderRequest& request) {
  const auto layout = image::GridLayout::for_frames(request.frames, request.width, request.height);
  image::GridPngEncoder encoder(layout, request.frames);
  auto report = testkit::shared_renderer().render(request, bunny(),
                                                  [&](int k, const image::Image& f, bool o) { encoder.add_frame(k, f, o); });
  EXPECT_TRUE(report) << report.error().format();
  return *encoder.finish();
}
}  // namespace

TEST(RenderTest, ContextIsOpenGlEs3) {
  const auto& info = testkit::shared_renderer().context_info();
  EXPECT_NE(info.gl_version.find("OpenGL ES 3"), std::string::npos) << info.gl_version;
  EXPECT_FALSE(info.gl_renderer.empty());
  EXPECT_GE(info.max_samples, 4);
}

// The server sizes its pool by what a child process finds (serve's workers_for_this_machine): the
// child must answer, and say what this process finds when it lists the devices itself.
TEST(RenderTest, DeviceSurveyInAChildAgreesWithTheDevicesListedHere) {
  const auto start = std::chrono::steady_clock::now();
  const auto in_child = egl::survey_devices_in_child(std::chrono::seconds(30));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_NE(in_child, egl::DeviceSurvey::unanswered);
  const auto devices = egl::enumerate_devices();
  const bool hardware = std::any_of(devices.begin(), devices.end(), [](const auto& d) { return !d.software; });
  const auto expected = hardware ? egl::DeviceSurvey::hardware : egl::DeviceSurvey::software;
  EXPECT_EQ(in_child, expected);
  EXPECT_EQ(egl::survey_devices(std::chrono::seconds(30)), expected);  // /dev's nodes looked at first
  std::printf("survey: %s in %.1f ms\n", hardware ? "hardware" : "software", ms);
}

TEST(RenderTest, SameRequestTwiceGivesIdenticalBytes) {
  auto request = testkit::preset_request("specular");
  request.width = 320;
  request.height = 240;
  const auto first = grid_png(request);
  const auto second = grid_png(request);
  EXPECT_GT(first.size(), 1000u);
  EXPECT_EQ(first, second);
}

// A preset's ES 3.00 stage rewritten as the GLSL ES 1.00 a WebGL 1 tutorial would have it.
std::string as_es100(std::string text, bool vertex) {
  const auto replace_all = [&](const std::string& from, const std::string& to) {
    for (size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size()) text.replace(at, from.size(), to);
  };
  replace_all("#version 300 es", "#version 100");
  replace_all("\nin ", vertex ? "\nattribute " : "\nvarying ");
  replace_all("\nout vec4 fragColor;", "");
  replace_all("fragColor = ", "gl_FragColor = ");
  replace_all("\nout ", "\nvarying ");
  return text;
}

// WebGL 2 compiles GLSL ES 1.00 pairs (attribute, varying, gl_FragColor): the homework's
// attributes and uniforms reach them as they reach ES 3.00 ones, and the frames are the same.
TEST(RenderTest, AGlslEs100PairRendersAsItsEs300Twin) {
  for (const char* preset : {"normals", "specular"}) {
    auto es300 = testkit::preset_request(preset);
    es300.width = 160;
    es300.height = 120;
    es300.frames = 3;
    auto es100 = es300;
    es100.vertex.text = as_es100(es300.vertex.text, true);
    es100.fragment.text = as_es100(es300.fragment.text, false);
    ASSERT_EQ(es100.fragment.text.find("#version 300"), std::string::npos);
    ASSERT_NE(es100.fragment.text.find("gl_FragColor = "), std::string::npos);
    auto a = render_frames(es300, testkit::builtin("bunny"));
    auto b = render_frames(es100, testkit::builtin("bunny"));
    ASSERT_TRUE(a) << a.error().format();
    ASSERT_TRUE(b) << preset << ": " << b.error().format();
    for (size_t k = 0; k < a->frames.size(); ++k) EXPECT_EQ(a->frames[k].bytes, b->frames[k].bytes) << preset << " frame " << k;
  }
}

TEST(RenderTest, CompileErrorInJsModulePointsAtTheStudentsLine) {
  auto request = testkit::preset_request("specular");
  // Line 1 is a comment, the back-tick opens on line 2; the typo sits on file line 9.
  request.fragment = {"phong_frag.js",
                      "// my phong shader\nexport default `#version 300 es\nprecision highp float;\n"
                      "uniform vec4 uAmbientColor;\nin vec4 vPosition;\nin vec4 vNormal;\nout vec4 fragColor;\n"
                      "void main(void) {\n    fragColor = uAmbientColr;\n}\n`;\n"};
  auto r = render_frames(request, bunny());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::compile_failed);
  ASSERT_FALSE(r.error().diagnostics.empty()) << r.error().driver_log;
  const auto& d = r.error().diagnostics[0];
  EXPECT_EQ(d.file, "phong_frag.js");
  EXPECT_EQ(d.stage, "fragment");
  EXPECT_EQ(d.line, 9);
  EXPECT_GT(d.column, 0);
  EXPECT_NE(d.message.find("uAmbientColr"), std::string::npos);
  EXPECT_TRUE(r.error().driver_log.empty());  // the front end's verdict: no driver saw it
}

TEST(RenderTest, VertexSyntaxErrorAndMissingMainAreCompileErrors) {
  auto request = testkit::preset_request("smooth");
  request.vertex.text = "#version 300 es\nin vec4 aVertexPosition;\nvoid main() { gl_Position = aVertexPosition }\n";
  auto r = render_frames(request, bunny());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::compile_failed);
  EXPECT_EQ(r.error().diagnostics.at(0).stage, "vertex");
  EXPECT_EQ(r.error().diagnostics.at(0).line, 3);

  request = testkit::preset_request("smooth");
  request.fragment.text = "#version 300 es\nprecision highp float;\nout vec4 c;\n";
  r = render_frames(request, bunny());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::compile_failed);  // as the browser says it: "Missing main()"
  EXPECT_NE(r.error().diagnostics.at(0).message.find("Missing main()"), std::string::npos) << r.error().format();
}

TEST(RenderTest, VaryingMismatchIsALinkError) {
  auto request = testkit::preset_request("normals");
  request.fragment.text = "#version 300 es\nprecision highp float;\nin vec4 vColour;\nout vec4 c;\nvoid main() { c = vColour; }\n";
  auto r = render_frames(request, bunny());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::link_failed);
  EXPECT_TRUE(r.error().driver_log.empty());  // found by ShadeLab's link, before the driver
  EXPECT_NE(r.error().message.find("link"), std::string::npos);
  EXPECT_NE(r.error().message.find("FRAGMENT varying vColour does not match any VERTEX varying"), std::string::npos);
}

TEST(RenderTest, OneMegabyteSourceIsRejectedBeforeTheDriver) {
  auto request = testkit::preset_request("smooth");
  request.fragment.text = "#version 300 es\n" + std::string(1 << 20, '/');
  auto r = render_frames(request, bunny());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::shader_source_invalid);
}

TEST(RenderTest, BothUniformNamingStylesReceiveTheDefaults) {
  for (const std::string name : {"uDiffuseColor", "diffuseColor"}) {
    auto r = render_frames(fullscreen_request("c = " + name + ";", "uniform vec4 " + name + ";"), bunny());
    ASSERT_TRUE(r) << r.error().format();
    // (0.7, 0.5, 0.1, 1.0) as 8-bit, within llvmpipe's rounding.
    const auto p = pixel(r->frames[0], 4, 4);
    EXPECT_NEAR(p[0], 179, 1) << name;
    EXPECT_NEAR(p[1], 128, 1) << name;
    EXPECT_NEAR(p[2], 26, 1) << name;
    EXPECT_EQ(p[3], 255);
  }
}

TEST(RenderTest, RequestValuesOverrideDefaultsAndAreTypeChecked) {
  auto request = fullscreen_request("c = uDiffuseColor;", "uniform vec4 uDiffuseColor;");
  request.uniforms = {{"uDiffuseColor", {0.0, 1.0, 0.0, 1.0}}};
  auto r = render_frames(request, bunny());
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_EQ(pixel(r->frames[0], 1, 1), (std::array<int, 4>{0, 255, 0, 255}));

  request.uniforms = {{"uDiffuseColor", {0.0, 1.0, 0.0}}};
  r = render_frames(request, bunny());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::uniform_type_mismatch);
  EXPECT_NE(r.error().message.find("vec4"), std::string::npos);

  auto ints = fullscreen_request("c = vec4(vec3(float(uCount) / 4.0), 1.0);", "uniform int uCount;");
  ints.uniforms = {{"uCount", {1.5}}};
  r = render_frames(ints, bunny());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::uniform_type_mismatch);
  ints.uniforms = {{"uCount", {2}}};
  r = render_frames(ints, bunny());
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_NEAR(pixel(r->frames[0], 0, 0)[0], 128, 1);
}

TEST(RenderTest, UnusedUniformIsAWarningNotAnError) {
  auto request = fullscreen_request("c = vec4(1.0);");
  request.uniforms = {{"uShininess", {32.0}}};
  auto r = render_frames(request, bunny());
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_TRUE(has_warning(r->report, "uShininess"));
}

TEST(RenderTest, DefaultDeclaredWithAnotherTypeStaysZeroAsInTheBrowser) {
  auto r = render_frames(fullscreen_request("c = vec4(uAmbientColor + 0.5, 1.0);", "uniform vec3 uAmbientColor;"), bunny());
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_NEAR(pixel(r->frames[0], 0, 0)[0], 128, 1);
  EXPECT_TRUE(has_warning(r->report, "uAmbientColor"));
}

// The renderer keeps programs for later jobs: a value one job set must not reach the next job on
// the same shaders (the browser links a fresh program, every uniform at zero). A grade of the
// starter's shaders under another course's uniform names read the previous job's light this way.
TEST(RenderTest, AUniformOneJobSetIsZeroForTheNextJobOnTheSameProgram) {
  auto request = fullscreen_request("c = vec4(uExtra, 0.5, 0.0, 1.0);", "uniform float uExtra;");
  request.uniforms = {{"uExtra", {1.0}}};
  auto first = render_frames(request, bunny());
  ASSERT_TRUE(first) << first.error().format();
  EXPECT_EQ(pixel(first->frames[0], 1, 1)[0], 255);
  request.uniforms = {};
  auto next = render_frames(request, bunny());
  ASSERT_TRUE(next) << next.error().format();
  EXPECT_TRUE(next->report.program_cached) << "the same program, from the renderer's cache";
  EXPECT_EQ(pixel(next->frames[0], 1, 1)[0], 0) << "uExtra kept the earlier job's 1.0";
}

TEST(RenderTest, AlphaBelowOneIsSavedAsCanvasToBlobDoes) {
  auto r = render_frames(fullscreen_request("c = vec4(0.4, 0.2, 0.1, 0.5);"), bunny());
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_FALSE(r->opaque[0]);
  EXPECT_EQ(pixel(r->frames[0], 3, 3), (std::array<int, 4>{203, 102, 52, 128}));
  r = render_frames(fullscreen_request("c = vec4(0.8, 0.6, 0.4, 0.5);"), bunny());
  ASSERT_TRUE(r);
  EXPECT_EQ(pixel(r->frames[0], 3, 3), (std::array<int, 4>{255, 255, 203, 128}));
}

TEST(RenderTest, NanAndInfinityEndUpAsTheBrowserStoresThem) {
  const std::string decl = "uniform float uZero;";
  auto all_nan = render_frames(fullscreen_request("c = vec4(uZero / uZero);", decl), bunny());
  ASSERT_TRUE(all_nan) << all_nan.error().format();
  EXPECT_EQ(pixel(all_nan->frames[0], 2, 2), (std::array<int, 4>{0, 0, 0, 0}));
  auto mixed = render_frames(fullscreen_request("c = vec4(uZero / uZero, 1.0 / uZero, -1.0 / uZero, 1.0);", decl), bunny());
  ASSERT_TRUE(mixed);
  EXPECT_EQ(pixel(mixed->frames[0], 2, 2), (std::array<int, 4>{0, 255, 0, 255}));
}

TEST(RenderTest, FloatTargetKeepsValuesBeyondOneAndNan) {
  auto request = fullscreen_request("c = vec4(2.5, 0.25, uZero / uZero, 1.0);", "uniform float uZero;");
  request.pixel_type = image::PixelType::f32;
  auto r = render_frames(request, bunny());
  ASSERT_TRUE(r) << r.error().format();
  float px[4];
  std::memcpy(px, r->frames[0].row(1), sizeof px);
  EXPECT_EQ(px[0], 2.5f);
  EXPECT_EQ(px[1], 0.25f);
  EXPECT_TRUE(std::isnan(px[2]));
  auto exr = image::encode_exr(r->frames[0]);
  ASSERT_TRUE(exr) << exr.error().format();
  const auto decoded = testkit::decode(*exr);
  std::memcpy(px, decoded.row(1), sizeof px);
  EXPECT_EQ(px[0], 2.5f);
  EXPECT_TRUE(std::isnan(px[2]));
  // Every float of every pixel, bit for bit (the NaN's payload too), in the same row order.
  EXPECT_EQ(decoded.type, image::PixelType::f32);
  EXPECT_TRUE(decoded.bytes == r->frames[0].bytes);
}

TEST(RenderTest, ExrEncodingRefusesAnEightBitImage) {
  const auto exr = image::encode_exr(image::Image::blank(4, 3, image::PixelType::u8));
  ASSERT_FALSE(exr);
  EXPECT_EQ(exr.error().code, ErrorCode::io_error);
}

TEST(RenderTest, FlatVaryingsTakeTheLastCornerOfEachTriangle) {
  // One triangle whose three corners carry different normals; flat shading must show the third.
  scene::Mesh tri;
  tri.positions = {{-1, 0, 0}, {1, 0, 0}, {0, 2, 0}};
  tri.normals = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto request = testkit::preset_request("starter");
  request.frames = 1;
  request.msaa = 0;
  auto r = render_frames(request, tri);
  ASSERT_TRUE(r) << r.error().format();
  // Moved by the page's (0, -2, -7.5) and seen at fovY 45 degrees, the triangle spans the frame's
  // lower half from its middle row down to ~82% of its height; (1/2, 3/4) of the frame is inside.
  const auto p = pixel(r->frames[0], request.width / 2, request.height * 3 / 4);
  EXPECT_EQ(p, (std::array<int, 4>{0, 0, 255, 255}));
}

TEST(RenderTest, MultisamplingIsOnByDefaultAndCanBeTurnedOff) {
  auto request = testkit::preset_request("smooth");
  request.frames = 1;
  auto with = render_frames(request, bunny());
  ASSERT_TRUE(with) << with.error().format();
  EXPECT_EQ(with->report.samples, 4);
  request.msaa = 0;
  auto without = render_frames(request, bunny());
  ASSERT_TRUE(without);
  EXPECT_EQ(without->report.samples, 0);
  EXPECT_NE(with->frames[0].bytes, without->frames[0].bytes);  // edges differ

  request.msaa = 64;
  auto too_many = render_frames(request, bunny());
  ASSERT_FALSE(too_many);
  EXPECT_EQ(too_many.error().code, ErrorCode::msaa_unsupported);
}

TEST(RenderTest, FrameKIsRotatedByExactlyKTimesTheStep) {
  // A full turn later the mesh is where it started: frame 18 of 20-degree steps equals frame 0.
  auto request = testkit::preset_request("specular");
  request.width = 160;
  request.height = 120;
  request.frames = 19;
  auto r = render_frames(request, bunny());
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_EQ(r->frames[18].bytes, r->frames[0].bytes);
  EXPECT_NE(r->frames[9].bytes, r->frames[0].bytes);
}

TEST(RenderTest, BuiltinMeshesStayInViewAtEveryAngle) {
  for (const std::string name : {"bunny", "teapot"}) {
    auto request = testkit::preset_request("smooth");
    request.width = 160;
    request.height = 120;
    request.frames = 36;
    request.degrees_per_frame = 10;
    auto r = render_frames(request, testkit::builtin(name));
    ASSERT_TRUE(r) << r.error().format();
    for (size_t k = 0; k < r->frames.size(); ++k) {
      const auto& f = r->frames[k];
      bool lit = false;
      for (int x = 0; x < f.width; ++x)
        for (int y : {0, f.height - 1}) ASSERT_EQ(pixel(f, x, y)[0] + pixel(f, x, y)[1] + pixel(f, x, y)[2], 0) << name << " frame " << k;
      for (int y = 0; y < f.height; ++y) {
        for (int x : {0, f.width - 1}) ASSERT_EQ(pixel(f, x, y)[0] + pixel(f, x, y)[1] + pixel(f, x, y)[2], 0) << name << " frame " << k;
        for (int x = 0; x < f.width && !lit; ++x) lit = pixel(f, x, y)[0] > 0;
      }
      EXPECT_TRUE(lit) << name << " frame " << k << " is empty";
    }
  }
}

TEST(RenderTest, InvalidRequestsAreRejectedBeforeRendering) {
  auto request = testkit::preset_request("smooth");
  request.width = 5000;  // over the default policy (2048), which the CLI and the HTTP edge apply
  EXPECT_EQ(render::validate(request, render::RenderLimits{}).error().code, ErrorCode::invalid_argument);
  request.width = 20000;  // over what the renderer itself accepts, whatever the policy
  EXPECT_EQ(render_frames(request, bunny()).error().code, ErrorCode::invalid_argument);
  request = testkit::preset_request("smooth");
  request.frames = 0;
  EXPECT_EQ(render_frames(request, bunny()).error().code, ErrorCode::invalid_argument);
  request = testkit::preset_request("smooth");
  request.degrees_per_frame = std::nan("");
  EXPECT_EQ(render_frames(request, bunny()).error().code, ErrorCode::invalid_argument);
  // A sample position is for a render without MSAA, and lies within the pixel.
  request = testkit::preset_request("smooth");
  request.sample_position = std::array<double, 2>{0.375, 0.125};
  EXPECT_EQ(render_frames(request, bunny()).error().code, ErrorCode::invalid_argument);
  request.msaa = 0;
  request.sample_position = std::array<double, 2>{0.5, 1.5};
  EXPECT_EQ(render_frames(request, bunny()).error().code, ErrorCode::invalid_argument);
}

// A render at a sample position is the frame moved by a fraction of a pixel: another pixel
// identity and other pixels along the edges, while the pixel's centre draws the plain render.
TEST(RenderTest, ASamplePositionMovesTheFrameByLessThanAPixel) {
  auto request = testkit::preset_request("normals");
  request.frames = 1;
  request.msaa = 0;
  const auto centre = render_frames(request, bunny());
  auto moved = request;
  moved.sample_position = std::array<double, 2>{0.5, 0.5};
  EXPECT_NE(render::pixel_identity(moved), render::pixel_identity(request));
  const auto at_centre = render_frames(moved, bunny());
  moved.sample_position = std::array<double, 2>{0.125, 0.625};
  const auto off_centre = render_frames(moved, bunny());
  ASSERT_TRUE(centre.ok() && at_centre.ok() && off_centre.ok());
  EXPECT_EQ(at_centre->frames[0].bytes, centre->frames[0].bytes);
  EXPECT_NE(off_centre->frames[0].bytes, centre->frames[0].bytes);
}

TEST(RenderTest, CompileReportsActiveAttributesAndUniforms) {
  const auto p = testkit::preset_request("specular");
  auto report = testkit::shared_renderer().compile(p.vertex, p.fragment);
  ASSERT_TRUE(report) << report.error().format();
  std::vector<std::string> names;
  for (const auto& u : report->uniforms) names.push_back(u.name + ":" + u.type);
  EXPECT_NE(std::find(names.begin(), names.end(), "uSpecularColor:vec4"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "uLightPosition:vec3"), names.end());
  ASSERT_EQ(report->attributes.size(), 2u);
  EXPECT_EQ(report->attributes[0].name, "aVertexNormal");
}

TEST(RenderTest, AttributesThePageDoesNotFeedAreWarnedAbout) {
  auto request = testkit::preset_request("smooth");
  request.vertex.text = "#version 300 es\nin vec4 aVertexPosition;\nin vec2 aTexCoord;\nout vec4 vNormal;\n"
                        "uniform mat4 uWorldToClipSpaceMatrix;\nuniform mat4 uMeshToWorldMatrix;\n"
                        "void main() { vNormal = vec4(aTexCoord, 1.0, 0.0); gl_Position = uWorldToClipSpaceMatrix * "
                        "uMeshToWorldMatrix * aVertexPosition; }\n";
  request.frames = 1;
  auto r = render_frames(request, bunny());
  ASSERT_TRUE(r) << r.error().format();
  EXPECT_TRUE(has_warning(r->report, "aTexCoord"));
}

// gl/mesh_buffer.h: the index buffer draws exactly the page's corner list.
TEST(MeshBufferTest, IndexedCornersRebuildTheCornerListAndShareOnlyIdenticalVertices) {
  // Two triangles of a quad sharing an edge, then a corner that differs from the first only in
  // the sign of a zero normal component: a different input to a shader, so a different vertex.
  const std::vector<float> corners = {0, 0, 0, 0, 0, 1,  1, 0, 0, 0, 0, 1,  1, 1, 0, 0, 0, 1,
                                      0, 0, 0, 0, 0, 1,  1, 1, 0, 0, 0, 1,  0, 1, 0, 0, 0, 1,
                                      0, 0, 0, -0.0f, 0, 1,  1, 0, 0, 0, 0, 1,  0, 1, 0, 0, 0, 1};
  const auto indexed = gl::index_corners(corners);
  EXPECT_EQ(indexed.vertices.size() / 6, 5u);
  EXPECT_EQ(indexed.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 4, 1, 3}));
  std::vector<float> rebuilt;
  for (auto i : indexed.indices) rebuilt.insert(rebuilt.end(), indexed.vertices.begin() + i * 6, indexed.vertices.begin() + i * 6 + 6);
  ASSERT_EQ(rebuilt.size(), corners.size());
  EXPECT_EQ(std::memcmp(rebuilt.data(), corners.data(), corners.size() * sizeof(float)), 0);
}

TEST(MeshBufferTest, AClosedMeshStoresEachVertexOnce) {
  const auto bunny_corners = testkit::builtin("bunny").interleaved();
  const auto indexed = gl::index_corners(bunny_corners);
  EXPECT_EQ(indexed.indices.size(), bunny_corners.size() / 6);
  EXPECT_LT(indexed.vertices.size() * 3, bunny_corners.size()) << "the bunny shares most corners";
}

TEST(MeshBufferTest, TheCacheKnowsAMeshAgainAndTellsApartMeshesThatDifferInOneBit) {
  auto request = testkit::preset_request("specular");
  request.width = 64;
  request.height = 48;
  request.frames = 1;
  const auto upload_ms = [&](const scene::Mesh& mesh) {  // 0 exactly when the buffer came from the cache
    auto report = testkit::shared_renderer().render(request, mesh, [](int, const image::Image&, bool) {});
    EXPECT_TRUE(report) << report.error().format();
    return report ? report->times.upload_ms : -1.0;
  };
  const auto flip_lowest_bit = [](float& f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits ^= 1u;
    std::memcpy(&f, &bits, sizeof bits);
  };
  upload_ms(bunny());
  EXPECT_EQ(upload_ms(bunny()), 0.0) << "the same mesh again is a cache hit";
  scene::Mesh normal_differs = bunny();
  flip_lowest_bit(normal_differs.normals[1234].y);
  EXPECT_GT(upload_ms(normal_differs), 0.0) << "one bit of one normal makes another mesh";
  EXPECT_EQ(upload_ms(normal_differs), 0.0);
  scene::Mesh position_differs = bunny();
  flip_lowest_bit(position_differs.positions.back().x);
  EXPECT_GT(upload_ms(position_differs), 0.0) << "one bit of one position makes another mesh";
  EXPECT_EQ(upload_ms(bunny()), 0.0) << "the first mesh is still cached";
}

// A GPU reads frames back through pixel buffers and fences, llvmpipe directly. Either way the
// frames are the same bytes, in 8-bit and float targets, multisampled or not; the tests run the
// pixel-buffer path on llvmpipe so that it is checked where there is no GPU.
TEST(ReadbackTest, PixelBuffersGiveTheSameBytesAsDirectReads) {
  auto& renderer = testkit::shared_renderer();
  const gl::Readback original = renderer.readback();
  for (const auto pixel_type : {image::PixelType::u8, image::PixelType::f32})
    for (const int msaa : {4, 0}) {
      auto request = testkit::preset_request("specular");
      request.width = 96;
      request.height = 72;
      request.frames = 3;
      request.msaa = msaa;
      request.pixel_type = pixel_type;
      renderer.set_readback(gl::Readback::direct);
      auto direct = render_frames(request, bunny());
      renderer.set_readback(gl::Readback::pixel_buffer);
      auto buffered = render_frames(request, bunny());
      ASSERT_TRUE(direct && buffered);
      ASSERT_EQ(direct->frames.size(), 3u);
      ASSERT_EQ(buffered->frames.size(), 3u);
      for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(direct->frames[k].bytes, buffered->frames[k].bytes) << "frame " << k << ", msaa " << msaa;
        EXPECT_EQ(direct->opaque[k], buffered->opaque[k]);
      }
      EXPECT_NE(direct->frames[0].bytes, direct->frames[1].bytes) << "the frames differ, so a stale buffer would show";
    }
  renderer.set_readback(original);
  EXPECT_EQ(original, renderer.context_info().software ? gl::Readback::direct : gl::Readback::pixel_buffer);
}

// The grader's lights drawn together (Renderer::render_together, shader/uniform_variants.h).
namespace {

// `request` under the homework's light and under each of the specular checkpoint's probe lights.
std::vector<render::RenderRequest> under_grader_lights(const render::RenderRequest& request) {
  const auto spec = testkit::course().grade_spec(*testkit::course().checkpoint("specular")->checkpoint, {});
  std::vector<render::RenderRequest> lit = {request};
  for (const auto& probe : spec.probes) {
    lit.push_back(request);
    for (const auto& s : grade::probe_settings(spec, probe)) lit.back().uniforms.push_back({s.name, s.value});
  }
  return lit;
}

struct Together {
  std::vector<std::vector<image::Image>> frames;           // per request
  std::vector<std::vector<image::NonFinite>> non_finite;  // per request, with a census
  int passes = 0;
};

Together render_together(const std::vector<render::RenderRequest>& requests, bool census = false) {
  Together out;
  out.frames.resize(requests.size());
  out.non_finite.resize(requests.size());
  render::CensusSink counts;
  if (census) counts = [&](int i, int, const image::NonFinite& n) { out.non_finite[static_cast<size_t>(i)].push_back(n); };
  auto report = testkit::shared_renderer().render_together(
      requests, testkit::builtin(testkit::course().default_mesh),
      [&](int i, int, const image::Image& f, bool) { out.frames[static_cast<size_t>(i)].push_back(f); }, counts);
  EXPECT_TRUE(report) << report.error().format();
  if (report) out.passes = report->passes;
  return out;
}

std::vector<image::Image> render_alone(const render::RenderRequest& request, std::vector<image::NonFinite>* non_finite = nullptr,
                                       const scene::Mesh& mesh = testkit::builtin(testkit::course().default_mesh)) {
  std::vector<image::Image> frames;
  render::CensusSink counts;
  if (non_finite) counts = [&](int, int, const image::NonFinite& n) { non_finite->push_back(n); };
  auto report = testkit::shared_renderer().render(request, mesh, [&](int, const image::Image& f, bool) { frames.push_back(f); }, counts);
  EXPECT_TRUE(report) << report.error().format();
  return frames;
}

bool same_counts(const image::NonFinite& a, const image::NonFinite& b) { return a.nan == b.nan && a.inf == b.inf; }

bool same_bytes(const image::Image& a, const image::Image& b) {
  return a.width == b.width && a.height == b.height && a.type == b.type && a.bytes == b.bytes;
}

// Every shader the course grades the specular checkpoint with: its reference and each catalogued mistake.
std::vector<std::pair<std::string, render::RenderRequest>> graded_shaders(int frames) {
  const auto spec = testkit::course().grade_spec(*testkit::course().checkpoint("specular")->checkpoint, {});
  render::RenderRequest base = testkit::preset_request("specular");
  base.frames = frames;
  std::vector<std::pair<std::string, render::RenderRequest>> out = {{"reference", base}};
  for (const auto& m : spec.mistakes) {
    out.push_back({m.id, base});
    out.back().second.vertex = m.vertex;
    out.back().second.fragment = m.fragment;
  }
  return out;
}

}  // namespace

// The course's job (3 of its frames) as the grader draws it (8-bit with the canvas's 4x MSAA, IEEE
// arithmetic and the census), as the page's optimiser would (as compiled, no census), and in float:
// one pass, the bytes (and the counts) of a pass each.
TEST(RenderTogetherTest, OneDrawForEveryLightGivesTheBytesOfADrawEach) {
  struct Kind {
    const char* name;
    image::PixelType type;
    render::FloatSemantics semantics;
    bool census;
  };
  const Kind kinds[] = {{"graded", image::PixelType::u8, render::FloatSemantics::ieee, true},
                        {"as compiled", image::PixelType::u8, render::FloatSemantics::as_compiled, false},
                        {"float", image::PixelType::f32, render::FloatSemantics::ieee, false}};
  for (auto [name, request] : graded_shaders(3)) {
    for (const Kind& kind : kinds) {
      request.pixel_type = kind.type;
      request.msaa = kind.type == image::PixelType::u8 ? testkit::course().msaa : 0;
      request.semantics = kind.semantics;
      const auto lit = under_grader_lights(request);
      ASSERT_GE(lit.size(), 2u);
      const Together together = render_together(lit, kind.census);
      EXPECT_EQ(together.passes, 1) << name << ", " << kind.name;
      for (size_t i = 0; i < lit.size(); ++i) {
        std::vector<image::NonFinite> counts;
        const auto alone = render_alone(lit[i], kind.census ? &counts : nullptr);
        ASSERT_EQ(together.frames[i].size(), alone.size()) << name;
        ASSERT_EQ(together.non_finite[i].size(), counts.size()) << name;
        for (size_t k = 0; k < alone.size(); ++k) {
          EXPECT_TRUE(same_bytes(together.frames[i][k], alone[k])) << name << ", " << kind.name << ", light " << i << ", frame " << k;
          if (kind.census) {
            EXPECT_TRUE(same_counts(together.non_finite[i][k], counts[k])) << name << ", light " << i << ", frame " << k;
          }
        }
      }
    }
  }
}

// The census changes no byte of the frames it is drawn with: the grader's frames are the IEEE
// program's own.
TEST(RenderTogetherTest, TheCensusLeavesTheFramesAsTheyAre) {
  for (auto [name, request] : graded_shaders(2)) {
    request.semantics = render::FloatSemantics::ieee;
    std::vector<image::NonFinite> counts;
    const auto counted = render_alone(request, &counts);
    const auto plain = render_alone(request);
    ASSERT_EQ(counted.size(), plain.size());
    ASSERT_EQ(counts.size(), plain.size());
    for (size_t k = 0; k < plain.size(); ++k) {
      EXPECT_TRUE(same_bytes(counted[k], plain[k])) << name << ", frame " << k;
      EXPECT_EQ(counts[k].nan + counts[k].inf, 0u) << name << ": the course's shaders give finite colours";
    }
  }
}

// The census counts what a float render of the same program holds, pixel for pixel: compared at
// pixel centres (no MSAA, where both see one sample a pixel), for NaN and infinity under each light
// of one pass, on the course's mesh (the NaN where the light meets the surface head-on).
TEST(RenderTogetherTest, TheCensusCountsWhatAFloatRenderHolds) {
  auto request = testkit::preset_request("specular");
  request.frames = 2;
  request.msaa = 0;
  request.semantics = render::FloatSemantics::ieee;
  const std::string text = request.fragment.text;
  const auto at = text.find("fragColor = color;");
  ASSERT_NE(at, std::string::npos);
  // NaN on the side the light does not reach (so each light's own), infinity where the normal points down.
  request.fragment.text.replace(at, 18, "fragColor = color + vec4(sqrt(NdotL), 1.0 / max(0.0, N.y), 0.0, 0.0);");
  const auto lit = under_grader_lights(request);
  const Together together = render_together(lit, true);
  EXPECT_EQ(together.passes, 1);
  size_t nan = 0, inf = 0;
  for (size_t i = 0; i < lit.size(); ++i) {
    auto as_float = lit[i];
    as_float.pixel_type = image::PixelType::f32;
    const auto floats = render_alone(as_float);
    ASSERT_EQ(together.non_finite[i].size(), floats.size());
    for (size_t k = 0; k < floats.size(); ++k) {
      const auto expected = image::count_non_finite(floats[k]);
      EXPECT_TRUE(same_counts(together.non_finite[i][k], expected))
          << "light " << i << ", frame " << k << ": census " << together.non_finite[i][k].nan << " NaN, " << together.non_finite[i][k].inf
          << " inf; float " << expected.nan << ", " << expected.inf;
      nan += expected.nan;
      inf += expected.inf;
    }
  }
  EXPECT_GT(nan, 100u) << "the shader must give NaN somewhere for this to test anything";
  EXPECT_GT(inf, 100u) << "and infinity";
}

// With the canvas's 4x MSAA a pixel is counted when any of its samples held a NaN: the browser's
// canvas stores that sample as 0 and the pixel comes out darker. One fragment a pixel writes every
// sample it covers, so a NaN decided by the pixel's centre is counted pixel for pixel.
TEST(RenderTogetherTest, TheCensusCountsEveryPixelAnySampleOfWhichHeldANan) {
  auto request = fullscreen_request("c = vec4(gl_FragCoord.x < 3.0 ? uZero / uZero : 0.5, gl_FragCoord.y < 2.0 ? 1.0 / uZero : 0.5, 0.0, 1.0);",
                                    "uniform float uZero;");
  request.msaa = 4;
  request.semantics = render::FloatSemantics::ieee;
  std::vector<image::NonFinite> counts;
  const auto frames = render_alone(request, &counts);
  ASSERT_EQ(counts.size(), 1u);
  EXPECT_EQ(counts[0].nan, 3u * 8u) << "columns 0-2";
  EXPECT_EQ(counts[0].inf, 5u * 2u) << "rows 0-1 right of them";
  EXPECT_EQ(pixel(frames[0], 0, 7), (std::array<int, 4>{0, 255, 0, 255})) << "NaN stored as 0, infinity clamped";
}

// The lights must change what is drawn: each probe light's frames (one moved, one coloured: a vec3
// and a vec4 uniform varied in the one pass) are not the homework light's, nor each other's.
TEST(RenderTogetherTest, EachLightGetsItsOwnValue) {
  auto request = testkit::preset_request("specular");
  request.frames = 1;
  const auto lit = under_grader_lights(request);
  ASSERT_EQ(lit.size(), 3u);
  const Together together = render_together(lit);
  EXPECT_EQ(together.passes, 1);
  ASSERT_EQ(together.frames.size(), lit.size());
  for (size_t i = 0; i < lit.size(); ++i)
    for (size_t j = i + 1; j < lit.size(); ++j) EXPECT_FALSE(same_bytes(together.frames[i][0], together.frames[j][0])) << i << " " << j;
}

// What one pass cannot give the bytes of (a discard decides for every light at once) is drawn a
// light at a time, and requests that differ in nothing the program reads are drawn once.
TEST(RenderTogetherTest, ADiscardIsDrawnALightAtATimeAndTheSameRequestOnce) {
  auto request = testkit::preset_request("specular");
  request.frames = 1;
  const std::string text = request.fragment.text;
  request.fragment.text.replace(text.find("fragColor = color;"), 18, "if (color.r > 0.9) discard; fragColor = color;");
  const auto lit = under_grader_lights(request);
  const Together apart = render_together(lit);
  EXPECT_EQ(apart.passes, static_cast<int>(lit.size()));
  for (size_t i = 0; i < lit.size(); ++i) EXPECT_TRUE(same_bytes(apart.frames[i][0], render_alone(lit[i])[0]));

  auto normals = testkit::preset_request("normals");  // reads no light
  normals.frames = 1;
  const Together once = render_together(under_grader_lights(normals));
  EXPECT_EQ(once.passes, 1);
  ASSERT_EQ(once.frames.size(), lit.size());
  for (size_t i = 1; i < lit.size(); ++i) EXPECT_TRUE(same_bytes(once.frames[0][0], once.frames[i][0]));
}

// Every way of drawing hands over a census: a discard is drawn a light at a time, each pass with
// its own; a shader the census cannot be added to (GLSL ES 1.00: one output, no integer bits; a
// #define, which would apply to the census's code) is counted in a float render of its own.
TEST(RenderTogetherTest, EveryWayOfDrawingHandsOverACensus) {
  auto request = testkit::preset_request("specular");
  request.frames = 1;
  request.semantics = render::FloatSemantics::ieee;
  const std::string text = request.fragment.text;
  request.fragment.text.replace(text.find("fragColor = color;"), 18, "if (color.r > 0.9) discard; fragColor = (color - color) / (color.g - color.g);");
  const auto lit = under_grader_lights(request);
  const Together apart = render_together(lit, true);
  EXPECT_EQ(apart.passes, static_cast<int>(lit.size()));
  for (size_t i = 0; i < lit.size(); ++i) {
    std::vector<image::NonFinite> counts;
    EXPECT_TRUE(same_bytes(apart.frames[i][0], render_alone(lit[i], &counts)[0]));
    ASSERT_EQ(apart.non_finite[i].size(), 1u);
    EXPECT_TRUE(same_counts(apart.non_finite[i][0], counts[0]));
    EXPECT_GT(counts[0].nan, 1000u) << "0 / 0 where the colour is not discarded";
  }

  render::RenderRequest es100 = fullscreen_request("");
  es100.vertex.text = "attribute vec4 aVertexPosition;\nvoid main() { gl_Position = vec4(aVertexPosition.xy * 4.0, 0.0, 1.0); }\n";
  es100.fragment.text = "precision highp float;\nuniform float uZero;\nvoid main() { gl_FragColor = vec4(gl_FragCoord.x < 4.0 ? uZero / uZero : 0.5); }\n";
  es100.width = es100.height = 64;
  es100.semantics = render::FloatSemantics::ieee;
  std::vector<image::NonFinite> counts;
  auto frames = testkit::shared_renderer().render(es100, testkit::builtin("bunny"), [](int, const image::Image&, bool) {},
                                                  [&](int, int, const image::NonFinite& n) { counts.push_back(n); });
  ASSERT_TRUE(frames) << frames.error().format();
  EXPECT_EQ(frames->passes, 2) << "the frames, then the float render counted";
  ASSERT_EQ(counts.size(), 1u);
  auto as_float = es100;
  as_float.pixel_type = image::PixelType::f32;
  const auto expected = image::count_non_finite(render_alone(as_float, nullptr, testkit::builtin("bunny"))[0]);
  EXPECT_TRUE(same_counts(counts[0], expected)) << counts[0].nan << " against " << expected.nan;
  EXPECT_GT(expected.nan, 10u);
  // A macro that would blind the census to every NaN: the census declines, the float render counts.
  auto macro = fullscreen_request("c = vec4(uZero / uZero);", "#define floatBitsToUint(x) uvec4(0u)\nuniform float uZero;");
  macro.semantics = render::FloatSemantics::ieee;
  std::vector<image::NonFinite> macro_counts;
  render_alone(macro, &macro_counts);
  ASSERT_EQ(macro_counts.size(), 1u);
  EXPECT_EQ(macro_counts[0].nan, 64u) << "every pixel of the 8 x 8 frame";
}
