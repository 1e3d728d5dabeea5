#include "support/test_support.h"

#include <gtest/gtest.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "course/course_reader.h"
#include "image/encode.h"

namespace shadelab::testkit {

render::Renderer& shared_renderer() {
  static render::Renderer renderer = [] {
    auto r = render::Renderer::create({});
    if (!r) {
      // A test machine without EGL is a broken setup, not a reason to skip: fail loudly.
      std::fprintf(stderr, "cannot create the EGL renderer: %s\n", r.error().format().c_str());
      std::abort();
    }
    return std::move(*r);
  }();
  return renderer;
}

Expected<Rendered> render_frames(const render::RenderRequest& request, const scene::Mesh& mesh) {
  Rendered out;
  auto report = shared_renderer().render(request, mesh, [&](int, const image::Image& f, bool opaque) {
    out.frames.push_back(f);
    out.opaque.push_back(opaque);
  });
  if (!report) return report.take_error();
  out.report = std::move(*report);
  return out;
}

const course::Course& course() { return course::builtin_course(); }

render::RenderRequest preset_request(const std::string& name) {
  const course::Preset* p = course().preset(name);
  EXPECT_NE(p, nullptr) << name;
  if (!p) return course().render_request({}, {});
  return course().render_request(p->vertex, p->fragment);
}

std::vector<grade::SavedFrame> saved_frames(const std::string& preset, const std::string& prefix, const std::vector<double>& lags) {
  render::RenderRequest request = preset_request(preset);
  request.angles.clear();
  for (size_t k = 0; k < lags.size(); ++k) request.angles.push_back(static_cast<double>(k) * request.degrees_per_frame - lags[k]);
  auto rendered = render_frames(request, builtin(course().default_mesh));
  std::vector<grade::SavedFrame> out;
  if (!rendered) return out;
  for (size_t k = 0; k < rendered->frames.size(); ++k) {
    auto png = image::encode_png(rendered->frames[k]);
    EXPECT_TRUE(png.ok());
    out.push_back({course().frame_file(prefix, static_cast<int>(k), "png"), std::string(png->begin(), png->end())});
  }
  return out;
}

const scene::Mesh& builtin(const std::string& name) {
  static std::map<std::string, scene::Mesh> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    const course::CourseMesh* m = course().mesh(name);
    if (!m) std::abort();
    auto loaded = course::load_course_mesh(*m);
    if (!loaded) std::abort();
    it = cache.emplace(name, std::move(*loaded)).first;
  }
  return it->second;
}

render::RenderRequest fullscreen_request(const std::string& body, const std::string& declarations) {
  render::RenderRequest r;
  r.vertex = {"fullscreen_vert.glsl",
              "#version 300 es\nin vec4 aVertexPosition;\nvoid main() {\n  int i = gl_VertexID % 3;\n"
              "  gl_Position = vec4(i == 1 ? 3.0 : -1.0, i == 2 ? 3.0 : -1.0, 0.0, 1.0);\n}\n"};
  r.fragment = {"fullscreen_frag.glsl", "#version 300 es\nprecision highp float;\n" + declarations +
                                            "\nout vec4 c;\nvoid main() {\n" + body + "\n}\n"};
  r.width = 8;
  r.height = 8;
  r.frames = 1;
  r.msaa = 0;
  r.page = course().page();
  return r;
}

image::Image decode(const std::vector<std::uint8_t>& bytes) {
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  const bool exr = bytes.size() > 4 && bytes[0] == 0x76 && bytes[1] == 0x2f;
  auto in = OIIO::ImageInput::create(exr ? "exr" : "png");
  OIIO::ImageSpec spec;
  const bool opened = in && in->set_ioproxy(&reader) && in->open(exr ? "in.exr" : "in.png", spec, config);
  EXPECT_TRUE(opened) << (in ? in->geterror() : OIIO::geterror());
  if (!opened) return {};
  const auto type = exr ? image::PixelType::f32 : image::PixelType::u8;
  image::Image img = image::Image::blank(spec.width, spec.height, type);
  if (!exr) std::fill(img.bytes.begin(), img.bytes.end(), 255);  // RGB files read as opaque RGBA
  const auto format = exr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  const OIIO::stride_t pixel = static_cast<OIIO::stride_t>(img.pixel_bytes());
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, format, img.bytes.data(), pixel)) << in->geterror();
  return img;
}

std::array<int, 4> pixel(const image::Image& img, int x, int y) {
  const std::uint8_t* p = img.row(y) + static_cast<size_t>(x) * 4;
  return {p[0], p[1], p[2], p[3]};
}

}  // namespace shadelab::testkit
