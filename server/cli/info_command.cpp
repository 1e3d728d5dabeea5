#include <iostream>
#include <thread>

#include <GLES3/gl32.h>

#include "cli/commands.h"
#include "cli/course_option.h"
#include "cli/environment.h"
#include "core/cpu_budget.h"
#include "egl/headless_context.h"

namespace shadelab::cli {

Command add_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Print the EGL devices and the GL context ShadeLab would render with");
  auto software = std::make_shared<bool>(software_from_environment());
  add_software_option(cmd, *software);
  auto extensions = std::make_shared<bool>(false);
  cmd->add_flag("--extensions", *extensions, "Also list the GL extensions, one per line");
  return [software, extensions] {
    for (const auto& d : egl::enumerate_devices())
      std::cout << "EGL device " << d.index << ": " << d.name << (d.software ? " (software)" : "") << "\n";
    auto context = egl::HeadlessContext::create({.force_software = *software});
    if (!context) {
      std::cerr << "error: " << context.error().format() << "\n";
      return 1;
    }
    const auto& i = context->info();
    std::cout << "platform:      " << i.platform << " (" << i.device << ")\n"
              << "software:      " << (i.software ? "yes" : "no") << "\n"
              << "EGL:           " << i.egl_vendor << " " << i.egl_version << "\n"
              << "GL vendor:     " << i.gl_vendor << "\n"
              << "GL renderer:   " << i.gl_renderer << "\n"
              << "GL version:    " << i.gl_version << "\n"
              << "GLSL version:  " << i.glsl_version << "\n"
              << "robust access: " << (i.robust_access ? "yes" : "no") << "\n"
              << "max samples:   " << i.max_samples << "\n"
              << "cores:         " << core::usable_cores() << " usable, "
              << std::thread::hardware_concurrency() << " on the host\n";
    if (*extensions) {
      GLint count = 0;
      glGetIntegerv(GL_NUM_EXTENSIONS, &count);
      for (GLint e = 0; e < count; ++e)
        std::cout << "extension:     " << reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, e)) << "\n";
    }
    return 0;
  };
}

}  // namespace shadelab::cli
