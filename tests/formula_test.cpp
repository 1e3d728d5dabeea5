// The homework's formula as a model (model/fit.h, grade/formula_explanation.h). First on a sphere
// whose every pixel's geometry is known, drawn by the model itself: the fit finds each variant and
// each changed value. Then through the real server at the course's canvas, on shaders edited as a
// student edits them: each mistake of the model's kind explained with the right change and its
// numbers, correct formulations passing with no explanation, unrelated drawings not explained.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "course/course.h"
#include "grade/edge_placement.h"
#include "grade/formula_explanation.h"
#include "grade/formula_geometry.h"
#include "grade/grade_renders.h"
#include "image/encode.h"
#include "model/fit.h"
#include "render/sample_positions.h"
#include "support/http_fixture.h"
#include "support/test_support.h"

using nlohmann::json;
using namespace shadelab;

namespace {

// ---- The fit on a sphere -------------------------------------------------------------------

constexpr int kSize = 128;

// A sphere of radius 1.5 at (0, 0, -6) seen from the origin through a 45-degree frustum: each
// pixel's eye-space position and normal (shorter than 1 in a ripple, as interpolation between
// vertices leaves it), and a "flat" normal one per facet of a grid of directions, at each of the
// pixel's four samples (where a facet's edge crosses the pixel they differ) and averaged over them.
constexpr glm::vec3 kCentre(0, 0, -6);
constexpr float kRadius = 1.5f;

// The sphere's point seen at (x, y) in pixels, rows top-down, if the ray meets it `margin` inside.
std::optional<glm::vec3> sphere_at(float x, float y, float margin) {
  const float half = std::tan(glm::radians(22.5f));
  const glm::vec3 ray = glm::normalize(glm::vec3((2 * x / kSize - 1) * half, (1 - 2 * y / kSize) * half, -1));
  const float b = glm::dot(ray, kCentre), c = glm::dot(kCentre, kCentre) - kRadius * kRadius, disc = b * b - c;
  if (disc <= margin) return std::nullopt;
  return ray * (b - std::sqrt(disc));
}

glm::vec3 facet(const glm::vec3& n) { return glm::normalize(glm::round(n * 6.0f) / 6.0f); }

model::FrameSurface sphere() {
  // The 4x pattern (its rows here top-down: the sphere needs only samples apart in the pixel).
  const auto samples = render::standard_sample_positions(model::kMaxSamples);
  model::FrameSurface s;
  s.width = s.height = kSize;
  s.samples = model::kMaxSamples;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const auto p = sphere_at(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, 0.05f);
      if (!p) continue;  // the outline and the background
      const glm::vec3 n = (*p - kCentre) / kRadius;
      const float shorter = 0.9f + 0.1f * std::abs(std::sin(0.4f * static_cast<float>(x)) * std::sin(0.4f * static_cast<float>(y)));
      model::SurfacePoint point{*p, n * shorter, glm::vec3(0)};
      for (const auto& [sx, sy] : samples) {
        const auto at = sphere_at(static_cast<float>(x + sx), static_cast<float>(y + sy), 0);
        s.sample_flat_normals.push_back(facet(at ? (*at - kCentre) / kRadius : n));
        point.flat_normal += s.sample_flat_normals.back() / static_cast<float>(samples.size());
      }
      // The normal's colour, interpolated between unit colours at the vertices: shorter between them too.
      point.colour = glm::abs(n) * shorter;
      point.flat_colour = glm::abs(facet(n));
      s.pixels.push_back(static_cast<std::uint32_t>(y * kSize + x));
      s.points.push_back(point);
    }
  return s;
}

model::Parameters course_values() {
  return {{{0.2f, 0.1f, 0.1f}, {0.7f, 0.5f, 0.1f}, {0.1f, 0.4f, 0.8f}, glm::vec3(1)}, 6.0f};
}

// The page's light, an orange one and one behind the sphere (as the course's probes).
std::vector<model::Light> lights() {
  return {{{16, 8, 4}, glm::vec3(1)}, {{16, 8, 4}, {1, 0.6f, 0.3f}}, {{-6, 4, -20}, glm::vec3(1)}};
}

image::Image drawn_by(model::Variant v, const model::Parameters& p, const model::FrameSurface& s, const model::Light& light,
                     model::Terms terms = model::Terms::phong) {
  image::Image out = image::Image::blank(kSize, kSize, image::PixelType::u8);
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const glm::vec3 c = model::as_canvas_stores(model::shade(v, p, terms, s.points[i], light, s.samples_of(i)));
    std::uint8_t* px = out.bytes.data() + static_cast<std::size_t>(s.pixels[i]) * 4;
    for (int k = 0; k < 3; ++k) px[k] = static_cast<std::uint8_t>(std::lround(c[k] * 255));
    px[3] = 255;
  }
  return out;
}

struct Drawn {
  model::FrameSurface surface = sphere();
  std::vector<image::Image> images;
  std::vector<model::DrawnFrame> frames;
};

std::unique_ptr<Drawn> draw(model::Variant v, const model::Parameters& p, model::Terms terms = model::Terms::phong) {
  auto d = std::make_unique<Drawn>();
  for (const auto& l : lights()) d->images.push_back(drawn_by(v, p, d->surface, l, terms));
  for (std::size_t i = 0; i < d->images.size(); ++i) d->frames.push_back({&d->surface, &d->images[i], lights()[i], 0.01});
  return d;
}

model::FitOptions options() {
  model::FitOptions o;
  o.course = course_values();
  return o;
}

// V = normalize(position) and R = reflect(L, N) draw the same: V·reflect(L, N) = -V·reflect(-L, N).
bool same_drawing(model::Variant a, model::Variant b) {
  const auto pair = [](model::Variant v) { return v == model::Variant::view_away || v == model::Variant::reflect_sign; };
  return a == b || (pair(a) && pair(b));
}

TEST(FormulaModelTest, EveryVariantIsFoundOnTheFramesItDraws) {
  for (const auto& v : model::variants()) {
    if (v.variant == model::Variant::formula || !model::applies_to(v, model::Terms::phong)) continue;
    SCOPED_TRACE(std::string(v.id));
    const auto d = draw(v.variant, course_values());
    const auto fits = model::fit_variants(d->frames, options());
    ASSERT_FALSE(fits.empty());
    EXPECT_TRUE(fits.front().reproduces);
    EXPECT_TRUE(same_drawing(fits.front().variant, v.variant)) << model::info(fits.front().variant).id;
    EXPECT_NEAR(fits.front().parameters.exponent, 6.0f, 0.3f);
    // The formula with the course's values does not draw these frames: the variant is needed.
    const auto& course = course_values().colours;
    for (const auto& f : fits) {
      const auto& c = f.parameters.colours;
      const bool course_values_kept = glm::length(c.ambient - course.ambient) + glm::length(c.diffuse - course.diffuse) +
                                          glm::length(c.specular - course.specular) < 0.02f;
      EXPECT_FALSE(f.variant == model::Variant::formula && f.reproduces && course_values_kept);
    }
  }
}

// The normals deliverable's colour has no values: each variant is what it draws, and only it.
TEST(FormulaModelTest, EveryNormalColourVariantIsFoundOnTheFramesItDraws) {
  auto o = options();
  o.terms = model::Terms::normal_colour;
  int tried = 0;
  for (const auto& v : model::variants()) {
    if (!model::applies_to(v, model::Terms::normal_colour)) continue;
    SCOPED_TRACE(std::string(v.id));
    ++tried;
    const auto d = draw(v.variant, course_values(), model::Terms::normal_colour);
    const auto fits = model::fit_variants(d->frames, o);
    ASSERT_FALSE(fits.empty());
    EXPECT_TRUE(fits.front().reproduces);
    EXPECT_EQ(fits.front().variant, v.variant) << model::info(fits.front().variant).id;
    for (std::size_t i = 1; i < fits.size(); ++i) EXPECT_FALSE(fits[i].reproduces) << model::info(fits[i].variant).id;
  }
  EXPECT_EQ(tried, 10);  // the formula and its nine changes
}

// A flat-shaded pixel where a facet's edge crosses it is the mean of its samples' shades: with a
// sharp highlight, the shade of their averaged normal is another colour. The fit finds flat normals
// from the samples; the same frames read with the averaged normal alone are not reproduced.
// A flat colour's error grows with the distance its edges move: three reads of a V find its point
// wherever it lies within the reach, and say the nearer side where it lies beyond.
TEST(EdgePlacementTest, AVsPointIsFoundFromThreeReads) {
  constexpr double reach = 0.012;
  const auto v = [](double point, double slope, double floor) { return [=](double d) { return floor + slope * std::abs(d - point); }; };
  for (const double point : {-0.012, -0.007, -0.001, 0.0, 0.004, 0.0115}) {
    const auto e = v(point, 3e5, 40);
    EXPECT_NEAR(grade::v_point(e(-reach), e(0), e(reach), reach), point, 1e-9) << point;
  }
  const auto beyond = v(0.03, 3e5, 40);
  EXPECT_DOUBLE_EQ(grade::v_point(beyond(-reach), beyond(0), beyond(reach), reach), reach);
  // No V (the middle highest): the lower side; all alike: where the outlines put it.
  EXPECT_DOUBLE_EQ(grade::v_point(5, 9, 7, reach), -reach);
  EXPECT_DOUBLE_EQ(grade::v_point(4, 4, 4, reach), 0.0);
}

TEST(FormulaModelTest, AFlatHighlightIsTheMeanOfItsSamplesShades) {
  auto sharp = course_values();
  sharp.exponent = 24.0f;
  sharp.colours.specular = glm::vec3(0.6f, 0.6f, 0.6f);
  const auto d = draw(model::Variant::flat_normal, sharp);
  std::size_t crossed = 0;
  for (std::size_t i = 0; i < d->surface.points.size(); ++i) crossed += d->surface.samples_of(i)[0] != d->surface.samples_of(i)[3];
  EXPECT_GT(crossed, d->surface.points.size() / 10);  // edges cross a tenth of the pixels at least
  auto o = options();
  const auto fits = model::fit_variants(d->frames, o);
  ASSERT_TRUE(fits.front().reproduces);
  EXPECT_EQ(fits.front().variant, model::Variant::flat_normal);
  EXPECT_NEAR(fits.front().parameters.exponent, 24.0f, 0.05f * 24.0f);

  model::FrameSurface averaged = d->surface;
  averaged.samples = 0;
  averaged.sample_flat_normals.clear();
  std::vector<model::DrawnFrame> frames = d->frames;
  for (auto& f : frames) f.surface = &averaged;
  for (const auto& f : model::fit_variants(frames, o)) {
    if (f.variant == model::Variant::flat_normal) {
      EXPECT_FALSE(f.reproduces) << f.worst_failing;
    }
  }
}

TEST(FormulaModelTest, ChangedValuesAreFoundWithinFivePercent) {
  auto doubled_ambient = course_values();
  doubled_ambient.colours.ambient *= 2.0f;
  auto halved_specular = course_values();
  halved_specular.colours.specular *= 0.5f;
  auto sharper = course_values();
  sharper.exponent = 12.0f;
  for (const auto& [name, p] : {std::pair{"ambient", doubled_ambient}, std::pair{"specular", halved_specular}, std::pair{"exponent", sharper}}) {
    SCOPED_TRACE(name);
    const auto d = draw(model::Variant::formula, p);
    const auto fits = model::fit_variants(d->frames, options());
    ASSERT_TRUE(fits.front().reproduces);
    EXPECT_EQ(fits.front().variant, model::Variant::formula);
    const auto& f = fits.front().parameters;
    EXPECT_NEAR(f.exponent, p.exponent, 0.05f * p.exponent);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(f.colours.ambient[c], p.colours.ambient[c], 0.05f * p.colours.ambient[c] + 0.004f);
      EXPECT_NEAR(f.colours.specular[c], p.colours.specular[c], 0.05f * p.colours.specular[c] + 0.004f);
    }
  }
}

TEST(FormulaModelTest, ALightWrittenIntoTheShaderIsFoundWhereItIs) {
  auto moved = course_values();
  moved.light_position = glm::vec3(-10, 8, 4);
  const auto d = draw(model::Variant::formula, moved);
  for (const auto& f : model::fit_variants(d->frames, options())) EXPECT_FALSE(f.reproduces) << model::info(f.variant).id;
  const auto fit = model::fit_light_position(d->frames, options());
  EXPECT_TRUE(fit.reproduces) << fit.worst_failing;
  ASSERT_TRUE(fit.parameters.light_position);
  EXPECT_LT(glm::distance(*fit.parameters.light_position, glm::vec3(-10, 8, 4)), 0.05f * glm::length(glm::vec3(-10, 8, 4)))
      << fit.parameters.light_position->x << ", " << fit.parameters.light_position->y << ", " << fit.parameters.light_position->z;
}

TEST(FormulaModelTest, NoiseIsReproducedByNoVariant) {
  auto d = draw(model::Variant::formula, course_values());
  std::uint32_t state = 12345;
  for (auto& image : d->images)
    for (std::size_t i = 0; i < image.bytes.size(); i += 4) {
      state = state * 1664525u + 1013904223u;
      image.bytes[i] = static_cast<std::uint8_t>(state >> 24);
    }
  for (const auto& f : model::fit_variants(d->frames, options())) EXPECT_FALSE(f.reproduces) << model::info(f.variant).id;
}

// ---- The geometry the formula is evaluated on -------------------------------------------------

glm::vec4 texel(const image::Image& image, std::size_t i) {
  glm::vec4 t;
  std::memcpy(&t, image.bytes.data() + i * sizeof(t), sizeof(t));
  return t;
}

// A specular checkpoint's flat normal is rendered once per sample position, without MSAA: each
// render sees what that sample of the course's 4x MSAA frame sees, so that their mean is the MSAA
// frame's resolve wherever the mesh covers the pixel (with the sample positions the wrong way up,
// or off the driver's, a pixel that a triangle's edge crosses would differ).
TEST(FormulaGeometryTest, EachSampleRenderSeesThatSampleOfTheMsaaFrame) {
  const auto found = testkit::course().checkpoint("specular");
  ASSERT_TRUE(found);
  const auto spec = testkit::course().formula_spec(*found->checkpoint);
  ASSERT_TRUE(spec);
  render::RenderRequest reference = testkit::preset_request("specular");
  reference.frames = 1;
  reference.angles = {40};
  EXPECT_TRUE(grade::has_sample_geometry(*spec, reference));
  const auto requests = grade::geometry_requests(*spec, reference, grade::SampleGeometry::each_sample);
  ASSERT_TRUE(requests.ok()) << requests.error().message;
  std::optional<image::Image> resolved;
  std::vector<image::Image> samples;
  for (const auto& g : *requests) {
    if (g.quantity != model::Quantity::flat_normal && g.quantity != model::Quantity::sample_flat_normal) continue;
    auto r = testkit::render_frames(g.request, testkit::builtin(testkit::course().default_mesh));
    ASSERT_TRUE(r.ok());
    if (g.quantity == model::Quantity::flat_normal) {
      resolved = r->frames[0];
    } else {
      EXPECT_EQ(g.sample, static_cast<int>(samples.size()));
      samples.push_back(r->frames[0]);
    }
  }
  ASSERT_TRUE(resolved);
  ASSERT_EQ(samples.size(), 4u);
  std::size_t covered = 0, crossed = 0, differ = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(resolved->width * resolved->height); ++i) {
    const glm::vec4 r = texel(*resolved, i);
    if (r.a < 2) continue;  // an outline or the background
    ++covered;
    glm::vec3 mean(0);
    for (const auto& s : samples) mean += glm::vec3(texel(s, i)) / 4.0f;
    crossed += glm::vec3(texel(samples[0], i)) != glm::vec3(texel(samples[3], i));
    differ += glm::length(mean - glm::vec3(r)) > 1e-3f;
  }
  EXPECT_GT(covered, 10000u);
  EXPECT_GT(crossed, covered / 10) << "a triangle's edge crosses a tenth of the pixels at least";
  EXPECT_LE(differ, covered / 1000) << differ << " of " << covered << " pixels";
}

// ---- Through the real server, at the course's canvas ----------------------------------------

class FormulaGradeTest : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    auto config = testkit::test_config();
    // The references and the formula's geometry at 512 x 512, kept for the suite's other processes.
    config.reference_store = "/tmp/shadelab-formula-test-" + std::to_string(::getuid());
    // The formula's own reading of code, as a server with no repair search gives it
    // (--repair-candidates 0). With a search, a confirmed repair explains code and the formula
    // reads only what no repair was found for: grade_test (the flat starter, unnormalised
    // normals) and the mutation sample test that road.
    config.repair.candidates = 0;
    server_ = new testkit::RunningService(config);
  }
  static void TearDownTestSuite() { delete server_; }
  void SetUp() override { ASSERT_TRUE(server_->ok()) << server_->failure; }

  struct Edit {
    std::string find, replace;
    bool vertex = false;
  };
  // The checkpoint's reference with a student's edits.
  static course::Preset edited(const std::string& checkpoint, const std::vector<Edit>& edits) {
    auto p = *testkit::course().preset(checkpoint);
    for (const auto& e : edits) {
      auto& text = e.vertex ? p.vertex.text : p.fragment.text;
      const auto at = text.find(e.find);
      EXPECT_NE(at, std::string::npos) << e.find;
      if (at != std::string::npos) text.replace(at, e.find.size(), e.replace);
    }
    return p;
  }
  // ... graded against it at the course's canvas.
  static json grade(const std::string& checkpoint, const std::vector<Edit>& edits, const std::string& size = "") {
    const auto p = edited(checkpoint, edits);
    json job = {{"vertex", p.vertex.text}, {"fragment", p.fragment.text}, {"vertexName", "phong_vert.js"},
                {"fragmentName", "phong_frag.js"}, {"reference", checkpoint}};
    if (!size.empty()) job["width"] = 160, job["height"] = 120;
    auto r = server_->client().Post("/api/grade", job.dump(), "application/json");
    if (!r || r->status != 200) {
      ADD_FAILURE() << "no grade: " << (r ? r->body : "no response");
      return json::object();
    }
    return json::parse(r->body);
  }
  // The frames a student's page saves of the edited shaders (drawn `lags` degrees behind each
  // frame's angle, as a 60 Hz page draws them), handed in alone and graded: the frames' report.
  static constexpr std::array<double, 9> kPageLags = {0, 0.12, 0.21, 0.05, 0.3, 0.17, 0.26, 0.09, 0.23};
  static json grade_saved(const std::string& checkpoint, const std::vector<Edit>& edits,
                          const std::vector<double>& lags = {kPageLags.begin(), kPageLags.end()}) {
    const auto p = edited(checkpoint, edits);
    render::RenderRequest request = testkit::preset_request(checkpoint);
    request.vertex = p.vertex;
    request.fragment = p.fragment;
    request.angles.clear();
    for (std::size_t k = 0; k < lags.size(); ++k) request.angles.push_back(static_cast<double>(k) * request.degrees_per_frame - lags[k]);
    auto rendered = testkit::render_frames(request, testkit::builtin(testkit::course().default_mesh));
    if (!rendered) return json::object();
    const auto found = testkit::course().checkpoint(checkpoint);
    httplib::MultipartFormDataItems items = {{"reference", checkpoint, "", ""}};
    for (std::size_t k = 0; k < rendered->frames.size(); ++k) {
      auto png = image::encode_png(rendered->frames[k]);
      EXPECT_TRUE(png.ok());
      items.push_back({"frames", std::string(png->begin(), png->end()),
                       testkit::course().frame_file(found->checkpoint->prefix, static_cast<int>(k), "png"), "image/png"});
    }
    auto r = server_->client().Post("/api/grade", items);
    if (!r || r->status != 200) {
      ADD_FAILURE() << "no grade: " << (r ? r->body : "no response");
      return json::object();
    }
    return json::parse(r->body)["frames"];
  }
  // Each frame's lag as the grade describes it, within `within` degrees of the page's.
  static void expect_lags(const json& r, double within) {
    ASSERT_EQ(r["frames"].size(), kPageLags.size()) << r.dump().substr(0, 600);
    for (std::size_t k = 0; k < kPageLags.size(); ++k)
      EXPECT_NEAR(r["frames"][k]["lagDegrees"].get<double>(), kPageLags[k], within) << "frame " << k << ": " << r["explanation"].dump();
  }
  // Several grades at once: the server's two workers share them.
  static std::vector<json> grade_all(const std::string& checkpoint, const std::vector<std::vector<Edit>>& cases) {
    std::vector<std::future<json>> pending;
    for (const auto& edits : cases) pending.push_back(std::async(std::launch::async, [&, edits] { return grade(checkpoint, edits); }));
    std::vector<json> out;
    for (auto& p : pending) out.push_back(p.get());
    return out;
  }
  static testkit::RunningService* server_;
};
testkit::RunningService* FormulaGradeTest::server_ = nullptr;

struct Expected {
  std::string what;
  std::vector<FormulaGradeTest::Edit> edits;
  std::string variant;           // the explanation's
  std::string parameter;         // a changed value it names, or ""
  std::vector<double> value;     // that value, within 5%
};

void expect_explained(const json& r, const Expected& e) {
  SCOPED_TRACE(e.what);
  ASSERT_TRUE(r.contains("explanation")) << r.dump().substr(0, 800);
  const json& x = r["explanation"];
  EXPECT_FALSE(r["pass"]);
  EXPECT_TRUE(x["explained"]) << x.dump();
  EXPECT_EQ(x["variant"], e.variant) << x.dump();
  if (!e.parameter.empty()) {
    bool found = false;
    for (const auto& p : x["parameters"])
      if (p["name"] == e.parameter) {
        found = true;
        // Within 5% of the value's length (a colour's, a position's) of each component.
        double length = 0;
        for (const double v : e.value) length += v * v;
        for (std::size_t i = 0; i < e.value.size(); ++i) EXPECT_NEAR(p["fitted"][i].get<double>(), e.value[i], 0.05 * std::sqrt(length) + 0.01) << p.dump();
      }
    EXPECT_TRUE(found) << x.dump();
  } else {
    EXPECT_TRUE(x["parameters"].empty()) << x.dump();
  }
  EXPECT_LE(x["residual"].get<double>(), 0.02);
  // The student reads it: in the messages, with the homework's names.
  bool said = false;
  for (const auto& m : r["messages"]) said = said || m == x["text"];
  if (r["diagnosis"] == "") {
    EXPECT_TRUE(said) << r["messages"];
  }
}

TEST_F(FormulaGradeTest, SpecularMistakesOfTheModelsKindAreExplained) {
  const std::vector<Expected> cases = {
      {"the light's position used as a direction", {{"normalize(uLightPosition - vPosition)", "normalize(uLightPosition)"}}, "light_as_direction"},
      {"the view vector away from the eye", {{"normalize(-vPosition)", "normalize(vPosition)"}}, "view_away"},
      {"a fixed view vector", {{"normalize(-vPosition)", "vec3(0.0, 0.0, 1.0)"}}, "fixed_view"},
      {"the normal negated", {{"vec3 N = normalize(vNormal);", "vec3 N = -normalize(vNormal);"}}, "negated_normal"},
      {"Blinn's half vector", {{"vec3 R = reflect(-L, N);\n        color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);",
                                "vec3 H = normalize(L + V);\n        color += uSpecularColor * uLightColor * pow(max(0.0, dot(N, H)), specularAlpha);"}},
       "half_vector"},
      {"no max on N.L", {{"max(0.0, NdotL)", "NdotL"}}, "unclamped_diffuse"},
      {"the light's colour left out", {{"uDiffuseColor * uLightColor * max", "uDiffuseColor * max"}, {"uSpecularColor * uLightColor * pow", "uSpecularColor * pow"}}, "no_light_colour"},
      {"a light written into the shader elsewhere", {{"normalize(uLightPosition - vPosition)", "normalize(vec3(-10.0, 8.0, 4.0) - vPosition)"}},
       "formula", "lightPosition", {-10.0, 8.0, 4.0}},
      {"an ambient colour doubled", {{"vec4 color = uAmbientColor +", "vec4 color = 2.0 * uAmbientColor +"}}, "formula", "ambient", {0.4, 0.2, 0.2}},
      {"a specular term halved", {{"uSpecularColor * uLightColor * pow", "0.5 * uSpecularColor * uLightColor * pow"}}, "formula", "specular", {0.05, 0.2, 0.4}},
      {"an exponent of 12", {{"float specularAlpha = 6.0;", "float specularAlpha = 12.0;"}}, "formula", "exponent", {12.0}},
      {"flat normals", {{"out vec3 vNormal;", "flat out vec3 vNormal;", true}, {"in vec3 vNormal;", "flat in vec3 vNormal;"}}, "flat_normal"},
      {"the diffuse and specular colours swapped",
       {{"vec4 color = uAmbientColor + uDiffuseColor", "vec4 color = uAmbientColor + uSpecularColor"}, {"color += uSpecularColor * uLightColor", "color += uDiffuseColor * uLightColor"}},
       "formula", "diffuse", {0.1, 0.4, 0.8}},
  };
  std::vector<std::vector<Edit>> edits;
  for (const auto& c : cases) edits.push_back(c.edits);
  const auto grades = grade_all("specular", edits);
  for (std::size_t i = 0; i < cases.size(); ++i) expect_explained(grades[i], cases[i]);
  // The view vector away and reflect(L, N) draw the same frames: both are said.
  EXPECT_EQ(grades[1]["explanation"]["alsoFits"], json::array({"reflect_sign"}));
}

TEST_F(FormulaGradeTest, DiffuseMistakesOfTheModelsKindAreExplained) {
  const std::vector<Expected> cases = {
      {"the light's position used as a direction", {{"normalize(uLightPosition - vPosition)", "normalize(uLightPosition)"}}, "light_as_direction"},
      {"the normal negated", {{"vec3 N = normalize(vNormal);", "vec3 N = -normalize(vNormal);"}}, "negated_normal"},
      {"no max on N.L", {{"max(0.0, dot(N, L))", "dot(N, L)"}}, "unclamped_diffuse"},
      {"the light's colour left out", {{"uDiffuseColor * uLightColor * max", "uDiffuseColor * max"}}, "no_light_colour"},
      {"an ambient colour doubled", {{"fragColor = uAmbientColor + diffuse;", "fragColor = 2.0 * uAmbientColor + diffuse;"}}, "formula", "ambient", {0.4, 0.2, 0.2}},
      {"the diffuse term left out", {{"max(0.0, dot(N, L))", "0.0"}}, "formula", "diffuse", {0, 0, 0}},
  };
  std::vector<std::vector<Edit>> edits;
  for (const auto& c : cases) edits.push_back(c.edits);
  const auto grades = grade_all("diffuse", edits);
  for (std::size_t i = 0; i < cases.size(); ++i) expect_explained(grades[i], cases[i]);
}

// The normals deliverable: the colour normalize(abs(N)) per vertex, interpolated. Each change to it
// a student makes is said, with no value to fit.
TEST_F(FormulaGradeTest, NormalsMistakesOfTheModelsKindAreExplained) {
  const std::string colour = "vColor = vec4(normalize(abs(normal.xyz)), 1.0);";
  const auto channels = [&](const std::string& swizzle) { return Edit{"normalize(abs(normal.xyz))", "normalize(abs(normal." + swizzle + "))", true}; };
  const std::vector<Expected> cases = {
      {"abs() missing", {{"normalize(abs(normal.xyz))", "normalize(normal.xyz)", true}}, "missing_abs"},
      {"0.5 N + 0.5", {{"normalize(abs(normal.xyz))", "0.5 * normalize(normal.xyz) + 0.5", true}}, "offset_normal"},
      {"a flat colour", {{"out vec4 vColor;", "flat out vec4 vColor;", true}, {"in vec4 vColor;", "flat in vec4 vColor;"}}, "flat_colour"},
      {"the colour computed per fragment",
       {{"out vec4 vColor;", "out vec3 vN;", true}, {colour, "vN = normal.xyz;", true}, {"in vec4 vColor;", "in vec3 vN;"},
        {"fragColor = vColor;", "fragColor = vec4(normalize(abs(vN)), 1.0);"}},
       "fragment_colour"},
      {"red and blue swapped", {channels("zyx")}, "swapped_red_blue"},
      {"red and green swapped", {channels("yxz")}, "swapped_red_green"},
      {"green and blue swapped", {channels("xzy")}, "swapped_green_blue"},
      {"channels rotated", {channels("yzx")}, "rotated_channels"},
      {"channels rotated back", {channels("zxy")}, "rotated_channels_back"},
  };
  std::vector<std::vector<Edit>> edits;
  for (const auto& c : cases) edits.push_back(c.edits);
  const auto grades = grade_all("normals", edits);
  for (std::size_t i = 0; i < cases.size(); ++i) expect_explained(grades[i], cases[i]);
  // Said in the course's names: the reference's colour varying.
  EXPECT_NE(grades[0]["explanation"]["text"].get<std::string>().find("vColor must be normalize(abs(N))"), std::string::npos) << grades[0]["explanation"];

  const std::vector<std::vector<Edit>> correct = {
      {{colour, "vColor = vec4(abs(normalize(normal.xyz)), 1.0);", true}},
      {{colour, "vColor = vec4(normalize(sqrt(normal.xyz * normal.xyz)), 1.0);", true}},
      {{colour, "vec3 a = abs(normal.xyz);\n    vColor = vec4(a / length(a), 1.0);", true}},
  };
  for (const auto& r : grade_all("normals", correct)) {
    EXPECT_TRUE(r["pass"]) << r.dump().substr(0, 800);
    EXPECT_FALSE(r.contains("explanation"));
  }

  // Drawings the normal's colour is not: one colour, noise, the position's colour, and the normal
  // before the mesh's rotation (a mistake the model has no variant for): never a confident reading.
  const std::vector<std::vector<Edit>> unrelated = {
      {{"fragColor = vColor;", "fragColor = vec4(0.3, 0.8, 0.2, 1.0);"}},
      {{"fragColor = vColor;", "fragColor = vec4(fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453), 0.5, 0.5, 1.0);"}},
      {{colour, "vColor = vec4(abs(normalize(aVertexPosition.xyz)), 1.0);", true}},
      {{"vec4 normal = uMeshToWorldRotMatrix * aVertexNormal;", "vec4 normal = aVertexNormal;", true}},
  };
  const auto wrong = grade_all("normals", unrelated);
  for (const auto& r : wrong) {
    ASSERT_TRUE(r.contains("explanation")) << r.dump().substr(0, 600);
    EXPECT_FALSE(r["explanation"]["explained"]) << r["explanation"].dump();
    EXPECT_FALSE(r["pass"]);
  }
  EXPECT_EQ(wrong[0]["explanation"]["label"], "one colour") << wrong[0]["explanation"];
  // Not explained, it says where the frames differ, by the way the normal faces.
  const std::string noise = wrong[1]["explanation"]["text"];
  EXPECT_NE(noise.find("the parts facing the viewer or away (mostly blue): "), std::string::npos) << noise;
}

// The catalogue's mistakes are the model's test set: a mistake the profile says the formula reads
// is diagnosed by that reading, with no render of its own (the catalogue's words stay the
// student's); one without a reading is rendered and compared as before.
TEST_F(FormulaGradeTest, TheCatalogueIsDiagnosedByItsReadings) {
  for (const auto& checkpoint : {"specular", "diffuse", "normals"}) {
    const auto found = testkit::course().checkpoint(checkpoint);
    ASSERT_TRUE(found);
    const auto* c = found->checkpoint;
    ASSERT_TRUE(c->formula);
    const int lights = 1 + static_cast<int>(c->probes.size());
    // The geometry: the position and the normal as interpolated; a lit checkpoint's flat normal
    // (a specular's also at each of the 4 samples); the normal's colour, interpolated and flat.
    const int geometry = c->formula->terms == model::Terms::normal_colour ? 4 : c->formula->terms == model::Terms::phong ? 7 : 3;
    int unread = 0;
    for (const auto& m : c->mistakes) unread += !m.shaders.reading;
    std::vector<std::future<json>> pending;
    for (const auto& m : c->mistakes)
      pending.push_back(std::async(std::launch::async, [&, m] {
        json job = {{"vertex", m.shaders.vertex.text}, {"fragment", m.shaders.fragment.text}, {"reference", checkpoint}};
        auto r = server_->client().Post("/api/grade", job.dump(), "application/json");
        return r && r->status == 200 ? json::parse(r->body) : json::object();
      }));
    for (std::size_t i = 0; i < c->mistakes.size(); ++i) {
      const auto& m = c->mistakes[i].shaders;
      SCOPED_TRACE(std::string(checkpoint) + ": " + m.id);
      const json r = pending[i].get();
      if (r.value("pass", false)) {  // too slight to fail at this size (diffuse's unnormalized normals): nothing to explain
        EXPECT_FALSE(r.contains("explanation"));
        continue;
      }
      ASSERT_TRUE(r.contains("explanation")) << r.dump().substr(0, 600);
      EXPECT_EQ(r["diagnosis"], m.id) << r["explanation"].dump();
      if (!m.reading) continue;
      const json& x = r["explanation"];
      EXPECT_TRUE(x["explained"]) << x.dump();
      EXPECT_EQ(x["variant"], model::info(m.reading->variant).id) << x.dump();
      ASSERT_EQ(x["parameters"].size(), m.reading->values.size()) << x.dump();
      for (std::size_t k = 0; k < m.reading->values.size(); ++k) EXPECT_EQ(x["parameters"][k]["name"], to_string(m.reading->values[k].parameter));
      // The grader's sets: the reference's and the geometry's, and the mistakes with no reading,
      // each under every light; none of the read mistakes' own.
      const json& work = r["graderWork"];
      EXPECT_LE(work["rendered"].get<int>() + work["fromStore"].get<int>() + work["fromMemory"].get<int>(), lights + geometry + unread * lights) << work;
    }
  }
}

TEST_F(FormulaGradeTest, CorrectFormulationsPassWithNoExplanation) {
  const std::vector<std::vector<Edit>> correct = {
      {{"vec3 R = reflect(-L, N);", "vec3 R = 2.0 * dot(N, L) * N - L;"}},
      {{"if (NdotL > 0.0) {", "{"}, {"color += uSpecularColor * uLightColor * pow", "color += step(0.0, NdotL) * uSpecularColor * uLightColor * pow"}},
      {{"float specularAlpha = 6.0;", "const float specularAlpha = 3.0 + 3.0;"}, {"vec3 V = normalize(-vPosition);", "vec3 V = -vPosition / length(vPosition);"}},
  };
  for (const auto& r : grade_all("specular", correct)) {
    EXPECT_TRUE(r["pass"]) << r.dump().substr(0, 800);
    EXPECT_FALSE(r.contains("explanation"));
  }
}

TEST_F(FormulaGradeTest, UnrelatedDrawingsAreNotExplained) {
  const std::vector<std::vector<Edit>> unrelated = {
      {{"fragColor = color;", "fragColor = vec4(0.3, 0.8, 0.2, 1.0);"}},
      {{"fragColor = color;", "fragColor = vec4(fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453), 0.5, 0.5, 1.0);"}},
      {{"fragColor = color;", "fragColor = vec4(abs(N), 1.0);"}},
  };
  const auto grades = grade_all("specular", unrelated);
  for (const auto& r : grades) {
    ASSERT_TRUE(r.contains("explanation")) << r.dump().substr(0, 600);
    EXPECT_FALSE(r["explanation"]["explained"]) << r["explanation"].dump();
    EXPECT_FALSE(r["pass"]);
  }
  EXPECT_TRUE(grades[0]["explanation"]["text"].get<std::string>().starts_with("Your object is one colour, (0.30, 0.80, 0.20), everywhere"))
      << grades[0]["explanation"];
  // Not explained, it says where the frames differ, in the homework's parts.
  const std::string noise = grades[1]["explanation"]["text"];
  EXPECT_NE(noise.find("The grader cannot say why from the homework's formula"), std::string::npos) << noise;
  EXPECT_NE(noise.find("the lit side: "), std::string::npos) << noise;
}

// The page's only grade is the frames a student saves, drawn a little behind each frame's angle:
// they are read as code is, on the geometry at the angles their outlines fit. Each set is a grade
// of its own (a few seconds on llvmpipe), so the cases are three tests, not one long one.
void expect_saved_read_as_code(const std::vector<std::pair<std::string, Expected>>& cases) {
  for (const auto& [checkpoint, c] : cases) {
    const json r = FormulaGradeTest::grade_saved(checkpoint, c.edits);
    expect_explained(r, c);
    EXPECT_GT(r["graderWork"]["rendered"].get<int>(), 0);  // the geometry at the frames' own angles
    // Described at the angles their outlines fit, not where the reference's shading fits best.
    FormulaGradeTest::expect_lags(r, 0.02);
  }
}

TEST_F(FormulaGradeTest, SavedFramesAtThePagesLagAreExplainedAsCodeIs) {
  expect_saved_read_as_code({
      {"specular", {"the light's position used as a direction", {{"normalize(uLightPosition - vPosition)", "normalize(uLightPosition)"}}, "light_as_direction"}},
      {"specular", {"an exponent of 12", {{"float specularAlpha = 6.0;", "float specularAlpha = 12.0;"}}, "formula", "exponent", {12.0}}},
      {"specular", {"a specular term halved", {{"uSpecularColor * uLightColor * pow", "0.5 * uSpecularColor * uLightColor * pow"}}, "formula", "specular", {0.05, 0.2, 0.4}}},
      {"diffuse", {"the normal negated", {{"vec3 N = normalize(vNormal);", "vec3 N = -normalize(vNormal);"}}, "negated_normal"}},
      {"diffuse", {"an ambient colour doubled", {{"fragColor = uAmbientColor + diffuse;", "fragColor = 2.0 * uAmbientColor + diffuse;"}}, "formula", "ambient", {0.4, 0.2, 0.2}}},
  });
}

TEST_F(FormulaGradeTest, SavedFramesOfSharpOrFlatShadingAreReadAtTheirOwnAngles) {
  expect_saved_read_as_code({
      // Shading that changes sharply with the angle: read only on the geometry at the frames' own
      // angles, between the grid's steps.
      {"specular", {"an exponent under 1", {{"float specularAlpha = 6.0;", "float specularAlpha = 0.6;"}}, "formula", "exponent", {0.6}}},
      {"diffuse", {"flat normals", {{"out vec3 vNormal;", "flat out vec3 vNormal;", true}, {"in vec3 vNormal;", "flat in vec3 vNormal;"}}, "flat_normal"}},
      // Flat highlights: read on each sample's flat normal at the frames' own angles.
      {"specular", {"flat normals", {{"out vec3 vNormal;", "flat out vec3 vNormal;", true}, {"in vec3 vNormal;", "flat in vec3 vNormal;"}}, "flat_normal"}},
      {"normals", {"abs() missing", {{"normalize(abs(normal.xyz))", "normalize(normal.xyz)", true}}, "missing_abs"}},
      {"normals", {"red and blue swapped", {{"normalize(abs(normal.xyz))", "normalize(abs(normal.zyx))", true}}, "swapped_red_blue"}},
  });
}

TEST_F(FormulaGradeTest, SavedFramesOfNoiseOneColourOrAFlatColourAreSaidAsTheyAre) {
  // Noise is not explained, and frames that are right have nothing to explain.
  const json noise = grade_saved("specular", {{"fragColor = color;", "fragColor = vec4(fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453), 0.5, 0.5, 1.0);"}});
  ASSERT_TRUE(noise.contains("explanation")) << noise.dump().substr(0, 600);
  EXPECT_FALSE(noise["explanation"]["explained"]) << noise["explanation"].dump();
  // One colour is said to be, though another frame's outline falls a pixel away.
  const json one = grade_saved("specular", {{"fragColor = color;", "fragColor = vec4(0.3, 0.8, 0.2, 1.0);"}});
  ASSERT_TRUE(one.contains("explanation")) << one.dump().substr(0, 600);
  EXPECT_EQ(one["explanation"]["label"], "one colour") << one["explanation"].dump();
  // A flat colour changes at every triangle's edge: the outlines fit a frame's angle to about a
  // hundredth of a degree, which moves its edges by enough to leave more than the rule's share off.
  // The edges place each frame (grade/edge_placement.h): at the page's lags the formula reads it,
  // the catalogue's mistake is recognised by that reading (no render of its own), and the frames
  // are described at the angles read: the frames placed within a few thousandths of a degree of
  // the page's, the rest where their outlines fit (0.012 degrees off at worst here, unplaced).
  const std::vector<Edit> flat_colour = {{"out vec4 vColor;", "flat out vec4 vColor;", true}, {"in vec4 vColor;", "flat in vec4 vColor;"}};
  const json flat = grade_saved("normals", flat_colour);
  expect_explained(flat, {"a flat colour at the page's lags", flat_colour, "flat_colour"});
  EXPECT_EQ(flat["diagnosis"], "flat_shading") << flat.dump().substr(0, 800);
  expect_lags(flat, 0.01);
  expect_explained(grade_saved("normals", flat_colour, std::vector<double>(9, 0.0)), {"a flat colour, no lag", flat_colour, "flat_colour"});
  const json right = grade_saved("specular", {});
  EXPECT_TRUE(right["pass"]) << right["messages"];
  EXPECT_FALSE(right.contains("explanation"));
}

// Frames so small that a pixel holds many of the bunny's triangles: the formula cannot draw the
// reference itself within the rule, and says so rather than guess.
TEST_F(FormulaGradeTest, FramesTooSmallToReadAreSaidToBe) {
  const json r = grade("specular", {{"normalize(uLightPosition - vPosition)", "normalize(uLightPosition)"}}, "160x120");
  ASSERT_TRUE(r.contains("explanation")) << r.dump().substr(0, 600);
  EXPECT_FALSE(r["explanation"]["explained"]);
  EXPECT_TRUE(r["explanation"]["text"].get<std::string>().starts_with("The grader cannot read frames this small")) << r["explanation"];
}

}  // namespace

// A reading must not depend on the machine that drew the frames. Another GPU rounds a pixel's
// colour a step or two apart from llvmpipe (the H100's frames of the course's presets were within
// 3/255 of llvmpipe's on all but 0.003% of their pixels, README "On a GPU"), and a reading near
// one of its rules then reads one way here and another there: a fixed view vector with an exponent
// of 12 was explained on llvmpipe and not on the H100. Each case is read by the formula on its
// frames as drawn here, then on the student's and the reference's frames with every channel moved
// by up to `steps` eighth-bit steps either way (a fixed pattern): the same reading each time.
namespace formula_stability {

// Every channel the shader did not clamp moved by an amount in [-steps, steps] that a hash of the
// pixel, the channel and `seed` picks: the same frames on every run.
std::shared_ptr<const image::Image> rounded_apart(const image::Image& frame, int steps, std::uint32_t seed) {
  auto out = std::make_shared<image::Image>(frame);
  for (std::size_t i = 0; i < out->bytes.size(); ++i) {
    // Alpha, and a channel the shader's output clamped: the clamp comes before the rounding, so
    // every machine stores 0 and 255 alike.
    if (i % 4 == 3 || out->bytes[i] == 0 || out->bytes[i] == 255) continue;
    std::uint32_t h = static_cast<std::uint32_t>(i) * 2654435761u ^ seed * 40503u;
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    const int moved = static_cast<int>(out->bytes[i]) + static_cast<int>(h % static_cast<std::uint32_t>(2 * steps + 1)) - steps;
    out->bytes[i] = static_cast<std::uint8_t>(std::clamp(moved, 1, 254));
  }
  return out;
}

grade::SharedFrames rounded_apart(const grade::SharedFrames& frames, int steps, std::uint32_t seed) {
  if (steps == 0) return frames;
  grade::SharedFrames out;
  for (std::size_t k = 0; k < frames.size(); ++k) out.push_back(rounded_apart(*frames[k], steps, seed + static_cast<std::uint32_t>(k)));
  return out;
}

struct Read {
  std::string label;
  bool explained = false;
  double residual = 0;
};

// The checkpoint's reference with `edits` (find, replace) in its fragment stage, graded as code is
// and read by the formula on frames moved `steps` apart.
std::vector<Read> read_apart(const std::string& checkpoint, const std::vector<std::pair<std::string, std::string>>& edits,
                             const std::vector<int>& steps) {
  const course::Course& c = testkit::course();
  grade::GradeSpec spec = c.grade_spec(*c.checkpoint(checkpoint)->checkpoint, {});
  auto p = *c.preset(checkpoint);
  for (const auto& [find, replace] : edits) {
    const auto at = p.fragment.text.find(find);
    EXPECT_NE(at, std::string::npos) << find;
    if (at != std::string::npos) p.fragment.text.replace(at, find.size(), replace);
  }
  static grade::GradeRenders renders(testkit::shared_renderer());
  const scene::Mesh& mesh = testkit::builtin(c.default_mesh);
  renders.begin(spec);
  render::RenderRequest r = c.render_request(p.vertex, p.fragment);
  r.pixel_type = image::PixelType::u8;
  r.semantics = render::FloatSemantics::ieee;
  auto student = renders.submission_under_lights(spec, r, mesh);
  render::RenderRequest ref = r;
  ref.vertex = spec.reference_vertex;
  ref.fragment = spec.reference_fragment;
  auto reference = renders.cached_under_lights(spec, ref, mesh, c.default_mesh);
  const auto* geometry = renders.surfaces(*spec.formula, ref, mesh, c.default_mesh, grade::GeometryKept::in_memory);
  EXPECT_TRUE(student && reference && geometry);
  if (!student || !reference || !geometry) return {};
  std::vector<Read> out;
  for (const int s : steps) {
    const auto drawn = rounded_apart(student->frames, s, 1);
    const auto referenced = rounded_apart(*reference, s, 7919);
    const auto e = grade::explain_with_formula({&*spec.formula, ref.uniforms, spec.probes, geometry, &drawn, &referenced,
                                                renders.sampled_surfaces(*spec.formula, ref, mesh, c.default_mesh, grade::GeometryKept::in_memory)},
                                               spec.options)
                       .explanation;
    out.push_back({e.label, e.explained, e.residual});
  }
  return out;
}

}  // namespace formula_stability

TEST(FormulaStabilityTest, AReadingIsTheSameOnFramesAnotherMachineRoundsApart) {
  using formula_stability::read_apart;
  const std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> cases = {
      {"a fixed view vector and an exponent of 12", {{"normalize(-vPosition)", "vec3(0.0, 0.0, 1.0)"}, {"float specularAlpha = 6.0;", "float specularAlpha = 12.0;"}}},
      {"an exponent of 12", {{"float specularAlpha = 6.0;", "float specularAlpha = 12.0;"}}},
      {"an exponent of 0.6", {{"float specularAlpha = 6.0;", "float specularAlpha = 0.6;"}}},
      {"a fixed view vector", {{"normalize(-vPosition)", "vec3(0.0, 0.0, 1.0)"}}},
      {"an ambient colour doubled", {{"vec4 color = uAmbientColor +", "vec4 color = 2.0 * uAmbientColor +"}}},
      {"the normal negated", {{"vec3 N = normalize(vNormal);", "vec3 N = -normalize(vNormal);"}}},
      {"a light written into the shader elsewhere", {{"normalize(uLightPosition - vPosition)", "normalize(vec3(-10.0, 8.0, 4.0) - vPosition)"}}},
      {"a fixed view vector and the specular halved", {{"normalize(-vPosition)", "vec3(0.0, 0.0, 1.0)"}, {"uSpecularColor * uLightColor * pow", "0.5 * uSpecularColor * uLightColor * pow"}}},
      {"Blinn's half vector and an exponent of 24", {{"vec3 R = reflect(-L, N);\n        color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);",
                                "vec3 H = normalize(L + V);\n        color += uSpecularColor * uLightColor * pow(max(0.0, dot(N, H)), specularAlpha);"}, {"float specularAlpha = 6.0;", "float specularAlpha = 24.0;"}}},
  };
  const std::vector<int> steps = {0, 2, 3};
  for (const auto& [what, edits] : cases) {
    const auto reads = read_apart("specular", edits, steps);
    ASSERT_EQ(reads.size(), steps.size()) << what;
    EXPECT_TRUE(reads[0].explained) << what << ": " << reads[0].label;
    for (std::size_t i = 1; i < reads.size(); ++i) {
      EXPECT_EQ(reads[i].label, reads[0].label) << what << ", moved by up to " << steps[i] << "/255 (residual " << reads[i].residual << ", as drawn "
                                                << reads[0].residual << ")";
      EXPECT_EQ(reads[i].explained, reads[0].explained) << what << ", moved by up to " << steps[i] << "/255";
    }
  }
}
