#pragma once
// A headless OpenGL ES 3.x context on an EGL device: a GPU when there is one, otherwise Mesa's
// software device (llvmpipe), otherwise Mesa's surfaceless platform. Rendering goes to FBOs, so the
// context is made current with no surface at all.
#include <memory>
#include <string>
#include <vector>

#include "core/expected.h"

namespace shadelab::egl {

struct ContextOptions {
  bool force_software = false;  // --software / SHADELAB_SOFTWARE=1
};

// What an EGL device says about itself, before any context exists.
struct DeviceDescription {
  int index = 0;
  std::string name;        // DRM node, or "software"
  bool software = false;   // EGL_MESA_device_software
  std::string extensions;
};

struct ContextInfo {
  std::string platform;    // "device" or "surfaceless"
  std::string device;      // DRM node or "software"
  bool software = false;
  bool robust_access = false;
  std::string egl_vendor, egl_version;
  std::string gl_vendor, gl_renderer, gl_version, glsl_version;
  int max_samples = 0;
};

std::vector<DeviceDescription> enumerate_devices();

// Move-only owner of display + context; current on the creating thread.
class HeadlessContext {
 public:
  static Expected<HeadlessContext> create(const ContextOptions& options);

  HeadlessContext(HeadlessContext&&) noexcept;
  HeadlessContext& operator=(HeadlessContext&&) noexcept;
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;
  ~HeadlessContext();

  const ContextInfo& info() const { return info_; }
  // Makes the context current on the calling thread (it is current on the creating one already).
  Status make_current() const;

 private:
  struct Handles;
  HeadlessContext(std::unique_ptr<Handles> handles, ContextInfo info);

  std::unique_ptr<Handles> handles_;
  ContextInfo info_;
};

}  // namespace shadelab::egl
