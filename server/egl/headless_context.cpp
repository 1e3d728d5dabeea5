#include "egl/headless_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl32.h>

#include <cstdlib>
#include <cstring>

namespace shadelab::egl {

namespace {

struct DeviceApi {
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;

  static DeviceApi load() {
    DeviceApi api;
    api.query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    api.query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    api.get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    return api;
  }
  bool has_devices() const { return query_devices && query_device_string && get_platform_display; }
};

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

std::string str(const char* s) { return s ? s : ""; }
std::string gl_string(GLenum name) { return str(reinterpret_cast<const char*>(glGetString(name))); }

std::vector<EGLDeviceEXT> query_device_handles(const DeviceApi& api) {
  EGLint count = 0;
  if (!api.has_devices() || !api.query_devices(0, nullptr, &count) || count <= 0) return {};
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  if (!api.query_devices(count, devices.data(), &count)) return {};
  devices.resize(static_cast<size_t>(count));
  return devices;
}

DeviceDescription describe(const DeviceApi& api, EGLDeviceEXT device, int index) {
  DeviceDescription d;
  d.index = index;
  d.extensions = str(api.query_device_string(device, EGL_EXTENSIONS));
  d.software = has_extension(d.extensions.c_str(), "EGL_MESA_device_software");
  if (has_extension(d.extensions.c_str(), "EGL_EXT_device_drm"))
    d.name = str(api.query_device_string(device, EGL_DRM_DEVICE_FILE_EXT));
  if (d.name.empty()) d.name = d.software ? "software" : "device " + std::to_string(index);
  return d;
}

// A display that initialised, with what we know of where it came from.
struct OpenDisplay {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string platform, device;
  bool software = false;
};

bool initialize(EGLDisplay display) {
  EGLint major = 0, minor = 0;
  return display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor);
}

// Hardware devices first (unless software is forced), then the software device, then the
// surfaceless platform for EGL stacks without device enumeration.
OpenDisplay open_display(const ContextOptions& options) {
  const DeviceApi api = DeviceApi::load();
  const auto handles = query_device_handles(api);
  std::vector<DeviceDescription> devices;
  for (size_t i = 0; i < handles.size(); ++i) devices.push_back(describe(api, handles[i], static_cast<int>(i)));

  for (bool want_software : {false, true}) {
    if (!want_software && options.force_software) continue;
    for (const auto& d : devices) {
      if (d.software != want_software) continue;
      EGLDisplay display = api.get_platform_display(EGL_PLATFORM_DEVICE_EXT, handles[static_cast<size_t>(d.index)], nullptr);
      if (initialize(display)) return {display, "device", d.name, d.software};
    }
  }
  if (api.get_platform_display) {
    // Mesa honours this for the surfaceless platform; the device path above needs no such hint.
    if (options.force_software) setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    EGLDisplay display = api.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (initialize(display)) return {display, "surfaceless", "surfaceless", options.force_software};
  }
  return {};
}

EGLContext create_es3_context(EGLDisplay display, EGLConfig config, bool robust) {
  std::vector<EGLint> attribs = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0};
  if (robust) attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_ROBUST_ACCESS, EGL_TRUE});
  attribs.push_back(EGL_NONE);
  return eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
}

}  // namespace

struct HeadlessContext::Handles {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  ~Handles() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

std::vector<DeviceDescription> enumerate_devices() {
  const DeviceApi api = DeviceApi::load();
  std::vector<DeviceDescription> out;
  const auto handles = query_device_handles(api);
  for (size_t i = 0; i < handles.size(); ++i) out.push_back(describe(api, handles[i], static_cast<int>(i)));
  return out;
}

Expected<HeadlessContext> HeadlessContext::create(const ContextOptions& options) {
  OpenDisplay opened = open_display(options);
  if (opened.display == EGL_NO_DISPLAY)
    return make_error(ErrorCode::egl_unavailable,
                      "no EGL display could be initialised (is Mesa's libegl-mesa0 installed?)");
  auto handles = std::make_unique<Handles>();
  handles->display = opened.display;

  if (!eglBindAPI(EGL_OPENGL_ES_API)) return make_error(ErrorCode::egl_unavailable, "EGL cannot bind OpenGL ES");

  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint num_configs = 0;
  if (!eglChooseConfig(opened.display, config_attribs, &config, 1, &num_configs) || num_configs < 1)
    config = nullptr;  // EGL_KHR_no_config_context: rendering goes to FBOs anyway

  ContextInfo info;
  const char* display_extensions = eglQueryString(opened.display, EGL_EXTENSIONS);
  const bool robust_offered = has_extension(display_extensions, "EGL_EXT_create_context_robustness") ||
                              std::strncmp(str(eglQueryString(opened.display, EGL_VERSION)).c_str(), "1.5", 3) == 0;
  if (robust_offered) {
    handles->context = create_es3_context(opened.display, config, true);
    info.robust_access = handles->context != EGL_NO_CONTEXT;
  }
  if (handles->context == EGL_NO_CONTEXT) handles->context = create_es3_context(opened.display, config, false);
  if (handles->context == EGL_NO_CONTEXT)
    return make_error(ErrorCode::egl_unavailable, "EGL could not create an OpenGL ES 3 context");
  if (!eglMakeCurrent(opened.display, EGL_NO_SURFACE, EGL_NO_SURFACE, handles->context))
    return make_error(ErrorCode::egl_unavailable, "EGL could not make the context current without a surface");

  info.platform = opened.platform;
  info.device = opened.device;
  info.egl_vendor = str(eglQueryString(opened.display, EGL_VENDOR));
  info.egl_version = str(eglQueryString(opened.display, EGL_VERSION));
  info.gl_vendor = gl_string(GL_VENDOR);
  info.gl_renderer = gl_string(GL_RENDERER);
  info.gl_version = gl_string(GL_VERSION);
  info.glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
  // The surfaceless platform does not say which driver it picked; the renderer string does.
  info.software = opened.software || info.gl_renderer.find("llvmpipe") != std::string::npos ||
                  info.gl_renderer.find("softpipe") != std::string::npos;
  glGetIntegerv(GL_MAX_SAMPLES, &info.max_samples);
  return HeadlessContext(std::move(handles), std::move(info));
}

HeadlessContext::HeadlessContext(std::unique_ptr<Handles> handles, ContextInfo info)
    : handles_(std::move(handles)), info_(std::move(info)) {}
HeadlessContext::HeadlessContext(HeadlessContext&&) noexcept = default;
HeadlessContext& HeadlessContext::operator=(HeadlessContext&&) noexcept = default;
HeadlessContext::~HeadlessContext() = default;

Status HeadlessContext::make_current() const {
  if (!eglMakeCurrent(handles_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, handles_->context))
    return make_error(ErrorCode::egl_unavailable, "EGL could not make the context current");
  return Ok{};
}

}  // namespace shadelab::egl
